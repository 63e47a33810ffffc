// The absolute tolerance's round-off floor (src/contact/contact_run_tolerance.cpp): an atol
// below what the cam's motion is computed to must not stall the engine. Case A7's Ẋ_C
// scatters by ~4e-14 around its exact value near θ = 0 (the contact point of the spline cam
// is found by an iteration); with atol 1e-14 at rtol 1e-10, Lee and the event method on
// cvode-bdf took steps of ~1e-18 s and never left t ≈ 1e-11 s (500 000 steps in 6 s), the
// arc cam example (millimetres) likewise at t = 0.0142 s with atol ≤ 1e-12. With the floor
// both finish, and against a second engine (Lee's located step on arkode-erk at rtol
// 1e-12, whose own error test the scatter does not reach) they hold the accuracy rtol asks:
// measured, A7 over 0.3 s (two flights, 8716 / 9535 steps): separation and impact times
// within 1.2e-10 s (Lee) and 4.4e-11 s (event); the arc cam (held throughout) over one
// revolution: displacement within 2.1e-14 mm and contact force within 8.5e-13 N.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

Scene a7(ContactModel model, Integrator integ, double rtol, double atol) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/case_A7.toml");
  s.contact.model = model;
  s.solver.integrator = integ;
  s.solver.rtol = rtol;
  s.solver.atol = atol;
  s.run.t_end = 0.3;
  return s;
}

bool mentions_floor(const Summary& s) {
  return std::any_of(s.warnings.begin(), s.warnings.end(),
                     [](const std::string& w) { return w.find("round-off floor") != std::string::npos; });
}

TEST(ToleranceFloor, CaseA7OnCvodeAtAtolBelowRoundOffFinishesAndMatchesTheOneStepEngine) {
  const RunResult ref = simulate(a7(ContactModel::Lee, Integrator::ArkodeErk, 1e-12, 1e-13));
  ASSERT_TRUE(ref.summary.finished) << ref.summary.message;
  ASSERT_EQ(ref.summary.events.size(), 4u);  // two flights: separation, impact, twice
  for (ContactModel m : {ContactModel::Lee, ContactModel::Event}) {
    SCOPED_TRACE(to_string(m));
    const RunResult r = simulate(a7(m, Integrator::CvodeBdf, 1e-10, 1e-14));
    ASSERT_TRUE(r.summary.finished) << r.summary.message;
    EXPECT_TRUE(mentions_floor(r.summary));
    EXPECT_LT(r.summary.steps, 100000);  // the stall took 500 000 steps to reach t = 2.6e-12 s
    ASSERT_EQ(r.summary.events.size(), ref.summary.events.size());
    double dt = 0;
    for (std::size_t i = 0; i < r.summary.events.size(); ++i) {
      EXPECT_EQ(r.summary.events[i].type, ref.summary.events[i].type);
      dt = std::max(dt, std::abs(r.summary.events[i].t - ref.summary.events[i].t));
    }
    std::printf("  A7 %s: events within %.3g s, %ld steps\n", to_string(m), dt, long(r.summary.steps));
    EXPECT_LT(dt, 1e-9);
  }
}

TEST(ToleranceFloor, ArcCamInMillimetresOnCvodeFinishesAndMatchesTheOneStepEngine) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/arc_cam_dwell.toml");
  s.run.t_end = 0.05;  // one revolution
  s.run.output_dt = 1e-4;
  Scene ref_scene = s;
  ref_scene.contact.model = ContactModel::Lee;
  ref_scene.solver.integrator = Integrator::ArkodeErk;
  ref_scene.solver.rtol = 1e-12;
  ref_scene.solver.atol = 1e-10;
  const RunResult ref = simulate(ref_scene);
  ASSERT_TRUE(ref.summary.finished) << ref.summary.message;
  s.contact.model = ContactModel::Event;
  s.solver.integrator = Integrator::CvodeBdf;
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-14;
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_TRUE(mentions_floor(r.summary));
  ASSERT_EQ(r.rows.size(), ref.rows.size());
  double du = 0, dF = 0;
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    ASSERT_NEAR(r.rows[i].t, ref.rows[i].t, 1e-15);
    du = std::max(du, std::abs(r.rows[i].u_c - ref.rows[i].u_c));
    dF = std::max(dF, std::abs(r.rows[i].contact_force - ref.rows[i].contact_force));
  }
  std::printf("  arc cam: |du| %.3g mm, |dF| %.3g N\n", du, dF);
  EXPECT_LT(du, 1e-7);
  EXPECT_LT(dF, 1e-3);
}

TEST(ToleranceFloor, NoFloorAndNoWarningWhenAtolIsAboveIt) {
  const RunResult r = simulate(a7(ContactModel::Lee, Integrator::CvodeBdf, 1e-8, 1e-10));
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_FALSE(mentions_floor(r.summary));
}

}  // namespace
}  // namespace camdyn
