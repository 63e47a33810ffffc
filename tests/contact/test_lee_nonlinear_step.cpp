// Lee's located step on a mechanism with nonlinear elements (methods/lee_located_step.cpp):
// the held step's force-shape correction goes through the responses of the mechanism's
// linear part (its M, C, K and the elements' tangent frozen at a step start), kept when the
// estimated linearisation error is within a tenth of the tolerances.
//   * A progressive valve spring whose table is linear is the linear spring written as an
//     element: the two-mass OHC train with it follows the same train with the linear spring
//     (the affine step map, a different formulation of the same force law) to the run's
//     tolerances, with the same events, at the linear train's right-hand-side count on
//     arkode-erk (the count is deterministic, unlike CPU time).
//   * A time-dependent gas load (with and without the guide friction of the finger example)
//     on arkode-dirk, where the step used to shrink to nothing: every engine runs it, and the
//     valve's motion agrees with the event method at tight tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

Scene progressive_twin(Scene s) {
  for (ElementSpec& e : s.network.elements)
    if (e.name == "valve_spring") {
      const double k = e.stiffness, P = e.preload, c = e.damping;
      e = ElementSpec();
      e.name = "valve_spring";
      e.kind = ElementKind::ProgressiveSpring;
      e.nodes = {"valve", "ground"};
      e.deflections = {0.0, 0.005, 0.010, 0.015, 0.020, 0.025};
      for (double d : e.deflections) e.forces.push_back(k * d);
      e.installed_deflection = P / k;
      e.damping = c;
    }
  return s;
}

double max_diff(const camdyn_test::NetRun& a, const camdyn_test::NetRun& b, const std::string& col) {
  EXPECT_EQ(a.rows.size(), b.rows.size());
  double d = 0.0;
  for (std::size_t i = 0; i < std::min(a.rows.size(), b.rows.size()); ++i)
    d = std::max(d, std::abs(a.col(a.rows[i], col) - b.col(b.rows[i], col)));
  return d;
}

// A run with its rows, and the time the valve lifts off its seat (NaN: it does not).
struct Lifted {
  camdyn_test::NetRun run;
  double lift_off = NAN;
};
Lifted run_lifting(const Scene& s) {
  struct Keep : Observer {
    Lifted* out;
    void on_row(const HistoryRow& r) override { out->run.rows.push_back(r); }
    void on_event(const ContactEvent& e) override {
      if (e.contact == "seat" && e.type == EventKind::Separation && std::isnan(out->lift_off)) out->lift_off = e.t;
    }
  } keep;
  Lifted l;
  keep.out = &l;
  Simulator sim(s);
  l.run.cols = sim.extra_columns();
  l.run.sum = sim.run(&keep);
  return l;
}

TEST(LeeNonlinearStep, LinearTableProgressiveSpringFollowsTheLinearTrain) {
  // measured (rtol 1e-8, tol_u 1e-9, one revolution, 8 mm lift): max |Δu_valve| 1e-17 m
  // (erk) and 2e-14 m (dirk), |Δu_tappet| ≤ 2e-18 m; rhs evaluations 119 896 against
  // 119 304 (erk, 1.005×) and 731 622 against 511 291 (dirk, 1.43×: the DIRK stages of the
  // nonlinear system take a second Newton iteration). Before the linear-part correction:
  // 225 667 (1.89×) and 1 418 696 (2.77×).
  const std::pair<Integrator, double> cases[] = {{Integrator::ArkodeErk, 1.05}, {Integrator::ArkodeDirk, 1.6}};
  for (const auto& [integ, max_ratio] : cases) {
    SCOPED_TRACE(to_string(integ));
    Scene lin = camdyn_test::two_mass_train();
    lin.contact.model = ContactModel::Lee;
    lin.solver.integrator = integ;
    lin.run.output_dt = 2e-5;
    const Scene prog = progressive_twin(lin);
    const camdyn_test::NetRun a = camdyn_test::run_keeping_rows(lin);
    const camdyn_test::NetRun b = camdyn_test::run_keeping_rows(prog);
    ASSERT_EQ(a.sum.termination, Termination::Finished) << a.sum.message;
    ASSERT_EQ(b.sum.termination, Termination::Finished) << b.sum.message;
    EXPECT_EQ(a.sum.impacts, b.sum.impacts);
    EXPECT_EQ(a.sum.separations, b.sum.separations);
    EXPECT_LT(max_diff(a, b, "u_valve"), 1e-12);
    EXPECT_LT(max_diff(a, b, "u_tappet"), 1e-12);
    EXPECT_LE(double(b.sum.rhs_evals), max_ratio * double(a.sum.rhs_evals))
        << b.sum.rhs_evals << " against " << a.sum.rhs_evals;
  }
}

// The finger example's exhaust valve under its cylinder pressure table, from the start
// (without the guide friction: the step fell to ~1e-11 s within 4 µs on Lee/arkode-dirk)
// and past the lift's start at 100° of cam (with it: a step-size underflow at 100°).
TEST(LeeNonlinearStep, GasLoadRunsOnEveryEngineAndAgreesWithTheEventMethod) {
  const Scene example = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_finger_gas_friction.toml");
  Scene no_friction = example;
  no_friction.network.elements.erase(
      std::remove_if(no_friction.network.elements.begin(), no_friction.network.elements.end(),
                     [](const ElementSpec& e) { return e.kind == ElementKind::GuideFriction; }),
      no_friction.network.elements.end());
  no_friction.run.t_end = 2e-3;
  Scene with_friction = example;
  with_friction.run.t_end = 0.018;  // the lift starts at 0.0111 s
  for (Scene s : {no_friction, with_friction}) {
    SCOPED_TRACE(s.network.elements.size());
    s.run.output_dt = 1e-5;
    Scene ref = s;
    ref.contact.model = ContactModel::Event;
    ref.solver.integrator = Integrator::ArkodeErk;
    ref.solver.rtol = 1e-10;
    ref.solver.atol = 1e-14;
    const Lifted R = run_lifting(ref);
    const camdyn_test::NetRun& r = R.run;
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
      SCOPED_TRACE(to_string(integ));
      s.solver.integrator = integ;
      const Lifted L = run_lifting(s);
      const camdyn_test::NetRun& l = L.run;
      ASSERT_EQ(l.sum.termination, Termination::Finished) << l.sum.message;
      EXPECT_LT(max_diff(l, r, "u_valve"), 1e-9);
      EXPECT_LT(max_diff(l, r, "u_finger"), 1e-9);
      EXPECT_LT(max_diff(l, r, "F_seat"), 1e-3);
      if (std::isnan(R.lift_off)) {
        EXPECT_TRUE(std::isnan(L.lift_off));
      } else {
        EXPECT_NEAR(L.lift_off, R.lift_off, 1e-6);
      }
    }
  }
}

}  // namespace
}  // namespace camdyn
