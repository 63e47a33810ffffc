// Lee's method on cvode-bdf (src/contact/methods/lee_cvode.cpp): the held contact's
// three levels inside CVODE's step, no restart per step. Checked against a second
// formulation — the event-driven method, whose contact phase eliminates node 0 (the held
// bar, a different model and right-hand side) — and against the located step on
// arkode-erk; CVODE's restarts counted; the contact levels at every step end; the energy
// balance; the tolerance controlling the force error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

double peak_force(const RunResult& r) {
  double p = 0;
  for (const HistoryRow& row : r.rows) p = std::max(p, row.contact_force);
  return p;
}
// max |F_a − F_b| over rows at equal times (both runs land on the same output grid).
double max_force_diff(const RunResult& a, const RunResult& b) {
  EXPECT_EQ(a.rows.size(), b.rows.size());
  double d = 0;
  for (size_t i = 0; i < std::min(a.rows.size(), b.rows.size()); ++i) {
    EXPECT_DOUBLE_EQ(a.rows[i].t, b.rows[i].t);
    d = std::max(d, std::abs(a.rows[i].contact_force - b.rows[i].contact_force));
  }
  return d;
}

// The same scene run by Lee (on its engine: the multistep method on cvode-bdf) and by the
// event-driven method.
struct LeeAndEvent {
  RunResult lee, ev;
};
LeeAndEvent lee_and_event(Scene s) {
  s.contact.model = ContactModel::Lee;
  RunResult lee = simulate(s);
  s.contact.model = ContactModel::Event;
  return {std::move(lee), simulate(s)};
}

struct Variant {
  const char* name;
  MassMatrixKind mass;
  double rayleigh_beta;
};
class LeeMultistepHeld : public ::testing::TestWithParam<Variant> {};

// Case B1 held over 0.02 s (no separation): the force agrees with the event-driven held
// bar on the same engine to the tolerance's scale, node 0 sits on the cam at every step
// end (the projection), CVODE starts once and never restarts, and the energy balances.
TEST_P(LeeMultistepHeld, B1MatchesHeldBarWithoutRestarts) {
  const Variant v = GetParam();
  Scene s = paper_case("B1");
  s.follower.mass_matrix = v.mass;
  s.follower.rayleigh_beta = v.rayleigh_beta;
  s.solver.integrator = Integrator::CvodeBdf;
  s.solver.rtol = 1e-9;
  s.solver.atol = 1e-12;
  s.run.t_end = 0.02;
  s.run.output_dt = 1e-4;
  const auto [lee, ev] = lee_and_event(s);
  ASSERT_TRUE(lee.summary.finished) << lee.summary.message;
  ASSERT_TRUE(ev.summary.finished) << ev.summary.message;
  EXPECT_EQ(lee.summary.separations, 0);
  EXPECT_EQ(lee.summary.engine_restarts, 1);
  const double peak = peak_force(ev), d = max_force_diff(lee, ev);
  double max_gap = 0;
  for (const HistoryRow& r : lee.rows) max_gap = std::max(max_gap, std::abs(r.gap));
  const double W = lee.rows.back().work_cam;
  std::printf("%s: %ld steps (event %ld), %ld restarts; |F − F_event| %.3g of peak %.6g; "
              "max |gap| %.3g; energy residual %.3g of W %.6g\n",
              v.name, lee.summary.steps, ev.summary.steps, lee.summary.engine_restarts, d / peak,
              peak, max_gap, lee.summary.energy_residual, W);
  EXPECT_LT(d, 1e-6 * peak);
  EXPECT_LT(max_gap, 1e-12);
  EXPECT_LT(lee.summary.energy_residual, 1e-6 * std::abs(W));
}

INSTANTIATE_TEST_SUITE_P(
    Variants, LeeMultistepHeld,
    ::testing::Values(Variant{"consistent", MassMatrixKind::Consistent, 0.0},
                      Variant{"lumped", MassMatrixKind::Lumped, 0.0},
                      Variant{"consistent_damped", MassMatrixKind::Consistent, 1e-5}),
    [](const ::testing::TestParamInfo<Variant>& i) { return std::string(i.param.name); });

// The force error against a tight reference (the located step on arkode-erk at rtol
// 1e-11) falls with the tolerance.
TEST(LeeMultistep, ToleranceControlsForceError) {
  Scene s = paper_case("B1");
  s.run.t_end = 0.02;
  s.run.output_dt = 1e-4;
  s.solver.integrator = Integrator::ArkodeErk;
  s.solver.rtol = 1e-11;
  s.solver.atol = 1e-14;
  s.contact.tol_u = 1e-12;
  const RunResult ref = simulate(s);
  ASSERT_TRUE(ref.summary.finished) << ref.summary.message;
  const double peak = peak_force(ref);
  s.solver.integrator = Integrator::CvodeBdf;
  double err[3];
  const double rtols[3] = {1e-5, 1e-7, 1e-9};
  for (int k = 0; k < 3; ++k) {
    s.solver.rtol = rtols[k];
    s.solver.atol = 1e-3 * rtols[k];
    const RunResult r = simulate(s);
    ASSERT_TRUE(r.summary.finished) << r.summary.message;
    err[k] = max_force_diff(r, ref) / peak;
    std::printf("rtol %.0e: %ld steps, force error %.3g of the peak\n", rtols[k], r.summary.steps, err[k]);
  }
  EXPECT_LT(err[1], 0.1 * err[0]);
  EXPECT_LT(err[2], 0.1 * err[1]);
  EXPECT_LT(err[2], 1e-6);
}

// Case B2 through its first separations and impacts: the same events as the event-driven
// method on the same engine, at the same times; CVODE restarts at events only.
TEST(LeeMultistep, B2EventsAsEventDriven) {
  Scene s = paper_case("B2");
  s.solver.integrator = Integrator::CvodeBdf;
  s.solver.rtol = 1e-10;
  s.run.t_end = 0.08;
  const auto [lee, ev] = lee_and_event(s);
  ASSERT_TRUE(lee.summary.finished) << lee.summary.message;
  ASSERT_TRUE(ev.summary.finished) << ev.summary.message;
  ASSERT_GE(ev.summary.impacts, 3);
  EXPECT_EQ(lee.summary.impacts, ev.summary.impacts);
  EXPECT_EQ(lee.summary.separations, ev.summary.separations);
  ASSERT_EQ(lee.summary.events.size(), ev.summary.events.size());
  double dt = 0;
  for (size_t i = 0; i < ev.summary.events.size(); ++i) {
    EXPECT_EQ(lee.summary.events[i].type, ev.summary.events[i].type) << i;
    dt = std::max(dt, std::abs(lee.summary.events[i].t - ev.summary.events[i].t));
  }
  const long events = lee.summary.impacts + lee.summary.separations;
  std::printf("B2 0.08 s: lee %ld steps, event %ld steps; %ld events, max |Δt_event| %.3g s; "
              "%ld restarts\n",
              lee.summary.steps, ev.summary.steps, events, dt, lee.summary.engine_restarts);
  EXPECT_LT(dt, 1e-7);
  // one start, one restart per event, one more per free phase that arms its gap root
  EXPECT_LE(lee.summary.engine_restarts, 1 + 2 * events);
  EXPECT_LT(double(lee.summary.steps), 1.5 * double(ev.summary.steps));
}

}  // namespace
}  // namespace camdyn

namespace camdyn {
namespace {
// The stiff bar (examples/stiff_bar.toml: E = 5e8, 200 elements, k_e = 1.25e10) at loose
// tolerances, where an integrator may put up to rtol·|X_C| ≈ 1e-3 of drift into node 0:
// the held phase must stay held (no spurious separation) and its force stay within a few
// per cent of the event-driven held bar at rtol 1e-6 — a projection that moved node 0
// alone (or along M⁻¹e₀) turned that drift into first-element strain, force spikes of
// 1e4–1e9 and separations here; the projection puts the corrections on the static shape
// (methods/event.hpp: metric_scale_). The energy balances to 2e-3 of the work: measured
// 1.1e-3 / 3.4e-4 / 3.5e-5 of W at rtol 1e-2 / 1e-3 / 1e-4 (the single-follower stack,
// removed in round 3, had 1.9e-5 … 6e-6 with a rigid translation of the bar, bound 1e-4).
TEST(LeeMultistep, StiffBarLooseToleranceStaysHeld) {
  Scene s = paper_case("B2");
  s.follower.youngs_modulus = 5e8;
  s.follower.elements = 200;
  s.solver.integrator = Integrator::CvodeBdf;
  s.run.t_end = 0.05;
  s.run.output_dt = 1e-4;
  s.contact.model = ContactModel::Event;
  s.solver.rtol = 1e-6;
  const RunResult ref = simulate(s);
  ASSERT_TRUE(ref.summary.finished) << ref.summary.message;
  ASSERT_EQ(ref.summary.separations, 0);
  const double peak = peak_force(ref);
  s.contact.model = ContactModel::Lee;
  for (double rtol : {1e-2, 1e-3, 1e-4}) {
    s.solver.rtol = rtol;
    const RunResult r = simulate(s);
    ASSERT_TRUE(r.summary.finished) << r.summary.message;
    const double d = max_force_diff(r, ref);
    const double W = std::abs(r.rows.back().work_cam);
    std::printf("mechanism, rtol %.0e: %ld steps, %ld separations, max force %.6g (event: %.6g), "
                "max |F − F_event| %.3g of the peak, energy residual %.3g of W\n",
                rtol, r.summary.steps, r.summary.separations, r.summary.max_contact_force, peak, d / peak,
                r.summary.energy_residual / W);
    EXPECT_EQ(r.summary.separations, 0) << rtol;
    EXPECT_LT(std::abs(r.summary.max_contact_force - peak), 0.02 * peak) << rtol;
    EXPECT_LT(d, 0.05 * peak) << rtol;
    EXPECT_LT(r.summary.energy_residual, 2e-3 * W) << rtol;
  }
}
}  // namespace
}  // namespace camdyn
