// Networks with two or more contacts, the methods against each other (second formulations):
//   * a two-contact train: Lee, event-driven and penalty agree on 1 ms contact impulses,
//     and the energy balance closes;
//   * holonomic on IDA against Lee's holonomic contacts on arkode-erk;
//   * Lee on cvode-bdf reaches t_end with the event-driven method's events.
// Networks against closed forms: tests/mechanism/test_network_closed_forms.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

using camdyn_test::NetRun;
NetRun run(const Scene& s) { return camdyn_test::run_keeping_rows(s); }

// ---- two contacts: Lee, event-driven and penalty agree; the energy balance closes ------
// The OHC bucket-tappet example (cam with 0.2 mm lash, valve seat) over one lift event:
// the impulse of each contact in 1 ms windows, ∫F dt over the window (trapezoid on the
// output rows, 1 µs apart) plus the impact impulses at instants inside it.
std::map<std::string, std::vector<double>> window_impulses(const Scene& s, const NetRun& r) {
  std::map<std::string, std::vector<double>> w;
  const int nw = int(std::round(s.run.t_end / 1e-3));
  for (const ContactPointSpec& c : s.network.contacts) {
    std::vector<double> v(nw, 0.0);
    const std::string col = "F_" + c.name;
    for (size_t i = 1; i < r.rows.size(); ++i) {
      const double ta = r.rows[i - 1].t, tb = r.rows[i].t;
      const int k = std::min(nw - 1, int(0.5 * (ta + tb) / 1e-3));
      v[k] += 0.5 * (tb - ta) * (r.col(r.rows[i - 1], col) + r.col(r.rows[i], col));
    }
    for (const ContactEvent& e : r.sum.events)
      if (e.contact == c.name && e.impulse != 0.0) v[std::min(nw - 1, int(e.t / 1e-3))] += e.impulse;
    w[c.name] = v;
  }
  return w;
}

TEST(TwoContacts, LeeEventAndPenaltyAgreeOnImpulsesAndEnergyCloses) {
  Scene base = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  base.run.t_end = 0.036;  // one lift event (the cam turns at 25 rev/s)
  base.run.output_dt = 1e-6;
  base.solver.rtol = 1e-9;
  base.solver.atol = 1e-13;
  base.contact.tol_u = 1e-10;
  Scene lee = base, ev = base, pen = base;
  ev.contact.model = ContactModel::Event;
  pen.contact.model = ContactModel::Penalty;
  // k_p ≫ the stem's 5e7 N/m; c_p over-damps the contact on the tappet (ζ ≈ 2): at
  // critical damping the penalty contacts rebound for 5 µs after each impact and ring the
  // stem (1e-3 window differences). Penalty lands its steps on output times: rows at every
  // step (output_dt = 0) resolve its 2 µs force pulses for the window quadrature.
  pen.contact.penalty_stiffness = 1e11;
  pen.contact.penalty_damping = 4e5;
  pen.solver.rtol = 1e-8;
  pen.run.output_dt = 0.0;
  const NetRun a = run(lee), b = run(ev), c = run(pen);
  ASSERT_TRUE(a.sum.finished) << a.sum.message;
  ASSERT_TRUE(b.sum.finished) << b.sum.message;
  ASSERT_TRUE(c.sum.finished) << c.sum.message;
  const auto wa = window_impulses(lee, a), wb = window_impulses(ev, b), wc = window_impulses(pen, c);
  for (const auto& kv : wa) {
    const std::vector<double>& x = kv.second;
    double scale = 0, d_ev = 0, d_pen = 0;
    for (size_t k = 0; k < x.size(); ++k) {
      scale = std::max(scale, std::abs(x[k]));
      d_ev = std::max(d_ev, std::abs(x[k] - wb.at(kv.first)[k]));
      d_pen = std::max(d_pen, std::abs(x[k] - wc.at(kv.first)[k]));
    }
    std::printf("contact %s: max window impulse %.6g N·s; |Lee − event| %.3g, |Lee − penalty| %.3g (relative)\n",
                kv.first.c_str(), scale, d_ev / scale, d_pen / scale);
    EXPECT_LT(d_ev, 1e-3 * scale) << kv.first;
    EXPECT_LT(d_pen, 1e-3 * scale) << kv.first;
  }
  // the energy balance W = ΔT + ΔV + D against the energy that flows (the cam's work)
  double W = 0;
  for (const HistoryRow& row : a.rows) W = std::max(W, std::abs(row.work_cam));
  std::printf("energy residual: Lee %.3g, event %.3g, penalty %.3g of the cam's work %.4g J\n",
              a.sum.energy_residual / W, b.sum.energy_residual / W, c.sum.energy_residual / W, W);
  EXPECT_LT(a.sum.energy_residual, 1e-5 * W);
  EXPECT_LT(b.sum.energy_residual, 1e-5 * W);
  EXPECT_LT(c.sum.energy_residual, 1e-3 * W);
}

// A network on IDA (holonomic): the held contacts as an index-2 GGL DAE, the cam contact's
// closing by the Newton impact law and an IDA restart on the larger held set
// (methods/holonomic_ida.cpp) — against the second formulation, Lee's located step with contacts
// that never release (holonomic on arkode-erk): displacements, forces, the impact and the
// first tensile time.
TEST(HolonomicIda, HolonomicAgreesWithLeeHolonomicOnErk) {
  for (const char* ex : {"ohc_bucket_tappet", "ohv_pushrod_train"}) {
    Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/" + ex + ".toml");
    s.contact.model = ContactModel::Holonomic;
    s.run.t_end = 0.015;
    s.solver.integrator = Integrator::Ida;
    const RunResult a = simulate(s);
    s.solver.integrator = Integrator::ArkodeErk;
    const RunResult b = simulate(s);
    ASSERT_TRUE(a.summary.finished) << a.summary.message;
    ASSERT_TRUE(b.summary.finished) << b.summary.message;
    EXPECT_EQ(a.summary.integrator, "ida");
    ASSERT_EQ(a.rows.size(), b.rows.size());
    double du = 0, dF = 0, Fmax = 0;
    for (size_t i = 0; i < a.rows.size(); ++i) {
      ASSERT_EQ(a.rows[i].t, b.rows[i].t);
      du = std::max(du, std::abs(a.rows[i].u_c - b.rows[i].u_c));
      dF = std::max(dF, std::abs(a.rows[i].contact_force - b.rows[i].contact_force));
      Fmax = std::max(Fmax, std::abs(b.rows[i].contact_force));
    }
    ASSERT_EQ(a.summary.events.size(), b.summary.events.size()) << ex;
    ASSERT_GE(a.summary.events.size(), 2u) << ex;  // the lash closes, the seat turns tensile
    double dt = 0;
    for (size_t i = 0; i < a.summary.events.size(); ++i) {
      EXPECT_EQ(a.summary.events[i].type, b.summary.events[i].type) << ex;
      dt = std::max(dt, std::abs(a.summary.events[i].t - b.summary.events[i].t));
    }
    std::printf("%s: ida vs erk |du| %.2e m, |dF|/Fmax %.2e, events %zu, |dt| %.2e s\n", ex, du, dF / Fmax,
                a.summary.events.size(), dt);
    EXPECT_LT(du, 1e-10) << ex;          // measured 1.7e-14, 1.5e-14
    EXPECT_LT(dF, 1e-6 * Fmax) << ex;    // measured 2.2e-12, 2.1e-9
    EXPECT_LT(dt, 1e-9) << ex;           // measured 5e-16 … 1e-12
  }
}

// ---- Lee on cvode-bdf on a network: the OHC train's cam impact and seat separation -----
// A trial step whose force CVODE could not follow once made CVODE step with t + h = t
// forever (t_end 0.01 and 0.02 hung; 0.015 ran): now a trial step's work is bounded, the
// iteration's matrix comes from DIRK responses, a gap at zero that is not closing at a
// step's start is no switch, and a separation that keeps relocating is released. At
// 12 rev/s every step size then failed just before the seat let go (the start residual
// read by the acceleration-level test); at 40 rev/s iterating tighter diverged. On the OHV
// train's rocker chatter a seat that re-closed 0.27 µs after letting go was missed (the
// gap started a round-off below zero). The run must reach t_end with the event-driven
// method's events (a second formulation, on ERK): the same kinds on the same contacts,
// times to dt, impulses to a relative dP (the chatter's small impulses: 1e-3). Since the
// levels are solved inside CVODE's own step (methods/lee_cvode.cpp) the times agree to
// 2.1e-10 s (40 rev/s) and better, the impulses to 3.4e-5 (OHC) and 5.3e-5 (OHV chatter;
// before: dt 1e-8 and 5e-8 s, dP 0.1).
struct CvodeCase {
  const char* name;
  const char* scene;
  double t_end, speed;  // s, rev/s
  double dt, dP;
};
class NetworkLeeOnCvode : public ::testing::TestWithParam<CvodeCase> {};

TEST_P(NetworkLeeOnCvode, TrainReachesTEndWithTheEventMethodsEvents) {
  Scene lee = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/" + GetParam().scene + ".toml");
  lee.run.t_end = GetParam().t_end;
  lee.cam.speed_rev_s = GetParam().speed;
  lee.run.output_dt = 1e-4;
  lee.solver.integrator = Integrator::CvodeBdf;
  Scene ev = lee;
  ev.contact.model = ContactModel::Event;
  ev.solver.integrator = Integrator::ArkodeErk;
  const NetRun a = run(lee), b = run(ev);
  ASSERT_TRUE(a.sum.finished) << a.sum.message;
  ASSERT_TRUE(b.sum.finished) << b.sum.message;
  ASSERT_EQ(a.sum.events.size(), b.sum.events.size());
  ASSERT_GE(a.sum.events.size(), 2u);  // the cam's impact and the seat's separation
  for (size_t i = 0; i < a.sum.events.size(); ++i) {
    const ContactEvent &x = a.sum.events[i], &y = b.sum.events[i];
    EXPECT_EQ(to_string(x.type), std::string(to_string(y.type))) << i;
    EXPECT_EQ(x.contact, y.contact) << i;
    EXPECT_NEAR(x.t, y.t, GetParam().dt) << i << ' ' << to_string(x.type) << ' ' << x.contact;
    EXPECT_NEAR(x.impulse, y.impulse, GetParam().dP * std::abs(y.impulse)) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Runs, NetworkLeeOnCvode,
                         ::testing::Values(CvodeCase{"ohc_t_end_10ms", "ohc_bucket_tappet", 0.01, 25.0, 1e-9, 1e-4},
                                           CvodeCase{"ohc_t_end_20ms", "ohc_bucket_tappet", 0.02, 25.0, 1e-9, 1e-4},
                                           CvodeCase{"ohc_12_rev_s", "ohc_bucket_tappet", 0.025, 12.0, 1e-9, 1e-4},
                                           CvodeCase{"ohc_40_rev_s", "ohc_bucket_tappet", 0.012, 40.0, 1e-9, 1e-4},
                                           CvodeCase{"ohv_chatter", "ohv_pushrod_train", 0.012, 25.0, 1e-9, 1e-3}),
                         [](const ::testing::TestParamInfo<CvodeCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace camdyn
