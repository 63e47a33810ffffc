// camdyn — the penalty method on cvode-bdf takes the steps its error test needs on a stiff
// elastic bar (issue 36). The bar's undamped fast modes sit on the imaginary axis, where
// BDF orders 3–5 are not A-stable; at CVODE's default order 5 the steps were held at those
// modes' stability limit (examples/stiff_bar.toml with penalty k_p 1e7, c_p 632 over 5 ms:
// 50 008 steps at rtol 1e-3 and 72 610 at 1e-6, error-test failures 76 and 34, no Newton
// failure — more steps at the looser tolerance). With the elastic bar's order policy
// (BDF ≤ 2, cvode_bdf_order) the step follows the error test of BDF2: h ∝ rtol^(1/3),
// so 1000× tighter means ≈ 10× more steps (measured 2 839 → 28 262; over 0.05 s 29 998 at
// rtol 1e-6, the first work–precision table's 30 061).
#include <gtest/gtest.h>

#include <cmath>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace {

camdyn::Summary stiff_penalty(double rtol) {
  camdyn::Scene s = camdyn::load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/stiff_bar.toml");
  s.contact.model = camdyn::ContactModel::Penalty;
  s.contact.penalty_stiffness = 1e7;
  s.contact.penalty_damping = 632;
  s.solver.integrator = camdyn::Integrator::CvodeBdf;
  s.solver.rtol = rtol;
  s.run.t_end = 2e-3;
  return camdyn::simulate(s).summary;
}

}  // namespace

TEST(PenaltyBdfOrder, StiffBarStepsFollowTheBdf2ErrorTest) {
  const camdyn::Summary loose = stiff_penalty(1e-3), tight = stiff_penalty(1e-6);
  ASSERT_TRUE(loose.finished) << loose.message;
  ASSERT_TRUE(tight.finished) << tight.message;
  const double ratio = double(tight.steps) / double(loose.steps);
  std::printf("stiff bar penalty, 2 ms: %ld steps at rtol 1e-3, %ld at 1e-6 (ratio %.2f)\n", loose.steps,
              tight.steps, ratio);
  // BDF2's step law: (1e3)^(1/3) = 10, within a factor 2 (order changes 1 ↔ 2, the start).
  EXPECT_GT(ratio, 5.0);
  EXPECT_LT(ratio, 20.0);
  // Steps per simulated second at rtol 1e-3 (the old table's rate is 6e5/s at rtol 1e-6; at
  // order 5 this was 1e7/s).
  EXPECT_LT(double(loose.steps) / 2e-3, 2e6);
}
