// What a run says about its follower comes from the mechanism that runs, not from the
// scene's follower.kind (docs/guide/architecture.md, "A follower kind"): a user
// FollowerSystem replaces the scene's follower, so that key must change nothing, and the
// displacement tolerance's floor follows the gap the mechanism holds (docs/tolerances.md,
// "Refused at the start").
#include <gtest/gtest.h>

#include <memory>

#include "camdyn/follower_system.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

// One mass on a linear spring, its contact on the cam (the gap: q − lift above the base).
struct MassOnSpring : FollowerSystem {
  double m = 0.1, k = 2e4, P = 150.0;  // kg, N/m, N
  int size() const override { return 1; }
  std::vector<FollowerContact> contacts() const override {
    FollowerContact c;
    c.name = "cam";
    c.row = {1.0};
    return {c};
  }
  void force(double, const double* q, const double*, double* r) const override { r[0] = -(P + k * q[0]); }
  void solve_mass(const double* b, double* x) const override { x[0] = b[0] / m; }
  double kinetic_energy(const double* v) const override { return 0.5 * m * v[0] * v[0]; }
  double potential_energy(const double* q) const override { return P * q[0] + 0.5 * k * q[0] * q[0]; }
  std::string name() const override { return "mass on a spring"; }
};

// A circle cam (radius 0.02 m, eccentricity 4 mm) starting on its base circle.
Scene circle_cam_scene(FollowerKind kind) {
  Scene s = default_scene();
  s.cam.profile = CamProfileKind::Circle;
  s.cam.radius = 0.02;
  s.cam.eccentricity = 0.004;
  s.cam.theta0_deg = 180.0;
  s.cam.speed_rev_s = 20.0;
  s.follower.kind = kind;
  s.contact.tol_u = 1e-11;
  s.solver.integrator = Integrator::CvodeBdf;
  s.solver.rtol = 1e-8;
  s.solver.atol = 1e-12;
  s.run.t_end = 2e-3;
  s.run.output_dt = 0.0;
  return s;
}

// The floor is 1000 ulps of the largest cam radius (at least 1): 2.2e-13 here. A rigid
// follower's gap q₀ − X_C is a difference of two numbers of the cam's size, so tol_u = 1e-14
// is refused; a user follower's gap sees the lift above the base circle, so it is not.
TEST(MechanismProperties, TolUFloorFollowsTheGapTheMechanismHolds) {
  Scene s = circle_cam_scene(FollowerKind::Rigid);
  s.contact.tol_u = 1e-14;
  try {
    Simulator sim(s);
    ADD_FAILURE() << "tol_u 1e-14 accepted on a rigid follower";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "contact.tol_u");
  }
  EXPECT_NO_THROW(Simulator sim(s, std::make_shared<MassOnSpring>()));
}

// A user follower's summary does not depend on the scene's follower.kind, which it replaces:
// the same one-mass follower run under a rigid and an elastic_bar scene says the same about
// its tolerances (one unknown on Lee in CVODE: BDF orders 1-4, no warning).
TEST(MechanismProperties, UserFollowerSummaryIgnoresTheSceneFollowerKind) {
  const auto follower = std::make_shared<MassOnSpring>();
  const Summary a = Simulator(circle_cam_scene(FollowerKind::Rigid), follower).run();
  const Summary b = Simulator(circle_cam_scene(FollowerKind::ElasticBar), follower).run();
  ASSERT_TRUE(a.finished) << a.message;
  ASSERT_TRUE(b.finished) << b.message;
  EXPECT_EQ(a.tolerance_meaning, b.tolerance_meaning);
  EXPECT_EQ(a.tolerance_warning, b.tolerance_warning);
  EXPECT_NE(a.tolerance_meaning.find("BDF orders 1-4"), std::string::npos) << a.tolerance_meaning;
  EXPECT_TRUE(a.tolerance_warning.empty()) << a.tolerance_warning;
  EXPECT_EQ(a.steps, b.steps);
}

}  // namespace
}  // namespace camdyn
