// camdyn — a motion law with constant-velocity ramps (C0 joints: the cam's velocity jumps)
// under a follower held on the cam (issue 24). The cam strikes the follower at the joint:
// a plastic impact at the instant, after which the follower moves with the cam's new
// velocity. Checked against the law itself (the ramp's velocity H/β·ω, the impulse m·Δv)
// on Lee's located step (arkode-erk, arkode-dirk, cvode-bdf) and the event-driven method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <camdyn/scene.hpp>
#include <camdyn/simulator.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;

Scene ramp_scene() {
  return parse_scene(R"(
[cam]
profile = "law"
law = "ramp 10 0.1; cycloidal 70 7.9; dwell 20; modsine 70 -7.9; ramp 10 -0.1; dwell 180"
base_radius = 18.0
follower_face = "roller"
roller_radius = 8.0
follower_offset = 2.0
speed_rev_s = 25.0
theta0_deg = 270.0
[follower]
kind = "rigid"
mass = 1.2e-4
[spring]
stiffness = 40.0
precompression = 6.0
[run]
t_end = 0.08
output_dt = 1e-5
)",
                     "<test>");
}
}  // namespace

TEST(CamJointImpact, HeldFollowerTakesTheRampVelocityOnEveryEngine) {
  const double m = 1.2e-4, w = 2 * kPi * 25.0;
  const double v_ramp = 0.1 / (10.0 * kPi / 180.0) * w;  // L′ ω on the opening ramp
  struct Case {
    ContactModel model;
    Integrator integ;
  };
  const Case cases[] = {{ContactModel::Lee, Integrator::ArkodeErk},
                        {ContactModel::Lee, Integrator::ArkodeDirk},
                        {ContactModel::Lee, Integrator::CvodeBdf},
                        {ContactModel::Event, Integrator::ArkodeErk}};
  for (const Case& c : cases) {
    Scene sc = ramp_scene();
    sc.contact.model = c.model;
    sc.solver.integrator = c.integ;
    SCOPED_TRACE(std::string(to_string(c.model)) + " " + to_string(c.integ));
    const RunResult r = simulate(sc);
    ASSERT_TRUE(r.summary.finished) << r.summary.message;
    // The first event: the cam strikes the held follower where the ramp starts (θ = 360°).
    ASSERT_FALSE(r.summary.events.empty());
    const ContactEvent& e = r.summary.events.front();
    EXPECT_EQ(e.type, EventKind::Impact);
    EXPECT_NEAR(std::remainder(e.theta, 2 * kPi), 0.0, 1e-9);
    EXPECT_NEAR(e.impact_velocity, v_ramp, 1e-9 * v_ramp);
    EXPECT_NEAR(e.impulse, m * v_ramp, 1e-9 * m * v_ramp);
    // On the ramp the follower stays on the cam with the cam's velocity (plastic, held).
    int on_ramp = 0;
    for (const HistoryRow& row : r.rows) {
      const double deg = row.theta * 180 / kPi - 360.0;
      if (deg > 0.05 && deg < 9.95) {
        EXPECT_EQ(row.in_contact, 1) << row.t;
        EXPECT_NEAR(row.v_c, v_ramp, 1e-7 * v_ramp) << row.t;
        ++on_ramp;
      }
    }
    EXPECT_GT(on_ramp, 50);
    EXPECT_GE(r.summary.impacts, 2);  // both revolutions' opening ramps at least
    // The impacts' losses are booked: the energy ledger closes.
    double Vmax = 0;
    for (const HistoryRow& row : r.rows) Vmax = std::max(Vmax, std::fabs(row.potential));
    EXPECT_LT(r.summary.energy_residual, 1e-7 * Vmax);
  }
}
