// The network event-driven method at a motion law's joints (issue 23): a step that lands on
// a cam breakpoint sees the segment before it, the step that starts there the segment after
// it (one-sided cam evaluation, src/cam/joints.hpp one_sided_motion; methods/event.cpp
// enter_segment). Truths by hand, for a rigid follower (m = 0.1 kg, spring k = 35 kN/m,
// preload F0 = k δ0 = 250 N) on a point face, so X_C = base + L(θ):
//   * harmonic segment of rise H over β: L″ = H π²/(2β²) cos πx, x the segment's fraction;
//     the fall's end (x = 1, H < 0) has L″ = |H| π²/(2β²) > 0, the dwell after it L″ = 0;
//   * held on the cam the follower's force is F = m Ẍ_C + F0 + k L (u = X_C);
//   * on a dwell after the joint: F = F0 exactly;
//   * a joint where the new segment's F is negative: the follower leaves there, at zero
//     relative speed, and flies on its spring: u − u(0) = (L_j + F0/k) cos Ω(t − t_j) − F0/k,
//     Ω = √(k/m).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "cam/joints.hpp"
#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kM = 0.1, kK = 35000.0, kDelta0 = 0.00714285714285714, kH = 0.008;

Scene rigid_law(const std::string& law, double speed_rev_s, Integrator integ, double t_end) {
  Scene s = parse_scene("[cam]\nprofile = \"law\"\nfollower_face = \"point\"\nlaw = \"" + law + "\"\n",
                        "breaks.toml");
  s.follower.kind = FollowerKind::Rigid;
  s.follower.mass = kM;
  s.spring.stiffness = kK;
  s.spring.precompression = kDelta0;
  s.contact.model = ContactModel::Event;
  s.solver.rtol = 1e-7;
  s.solver.atol = 1e-10;
  s.run.output_dt = 0.0;
  s.cam.speed_rev_s = speed_rev_s;
  s.solver.integrator = integ;
  s.run.t_end = t_end;
  return s;
}

const char* kLobe = "dwell 100; harmonic 80 0.008; harmonic 80 -0.008; dwell 100";

TEST(CamOneSided, JointsGiveEachSegmentsOwnAcceleration) {
  // The fall→dwell joint at 260° (C1: the acceleration jumps) and the rise→fall joint at
  // 180° (C2: both harmonic ends have L″ = −Hπ²/(2β²)).
  Scene s = rigid_law(kLobe, 40.0, Integrator::ArkodeErk, 0.02);
  resolve_defaults(s);
  const Cam cam(s.cam);
  const CamDrive drive(s.cam);
  const double w = 2 * kPi * 40.0, beta = 80 * kDeg, a = kH * kPi * kPi / (2 * beta * beta) * w * w;
  // the landing time of the steps: as the method's stops compute it
  const double tb = drive.next_time_at_angles(0.7 / 40.0, cam.breakpoints(), 1.0);
  ASSERT_NEAR(tb, (260.0 / 360.0) / 40.0, 1e-12);
  for (double t : {tb, std::nextafter(tb, 0.0), tb * (1 + 4e-16), tb * (1 - 4e-16)}) {
    CamMotion l, r;
    ASSERT_TRUE(detail::one_sided_motion(cam, drive, cam.breakpoints(), t, -1, &l));
    ASSERT_TRUE(detail::one_sided_motion(cam, drive, cam.breakpoints(), t, +1, &r));
    EXPECT_NEAR(l.Xddot, a, 1e-9 * a) << t;  // the fall's end
    EXPECT_NEAR(r.Xddot, 0.0, 1e-9 * a) << t;  // the dwell
    EXPECT_NEAR(l.Xdot, 0.0, 1e-9 * kH * w);
    EXPECT_NEAR(r.Xdot, 0.0, 1e-9 * kH * w);
    EXPECT_EQ(l.X, r.X);
  }
  const double tn = drive.next_time_at_angles(0.4 / 40.0, cam.breakpoints(), 1.0);  // 180°
  ASSERT_NEAR(tn, 0.5 / 40.0, 1e-12);
  CamMotion l, r;
  ASSERT_TRUE(detail::one_sided_motion(cam, drive, cam.breakpoints(), tn, -1, &l));
  ASSERT_TRUE(detail::one_sided_motion(cam, drive, cam.breakpoints(), tn, +1, &r));
  EXPECT_NEAR(l.Xddot, -a, 1e-9 * a);
  EXPECT_NEAR(r.Xddot, -a, 1e-9 * a);
  // away from a breakpoint: no one-sided value
  EXPECT_FALSE(detail::one_sided_motion(cam, drive, cam.breakpoints(), 0.6 / 40.0, 1, &l));
}

// 40.7 rev/s, just below the lobe's jump speed: the fall ends with a large deceleration
// (m L″ω² = 255 N) and the dwell after it takes F0. The steps land on the joint; before
// the one-sided evaluation the step after it still saw the fall's acceleration in its first
// stage (ERK: the last stage's right-hand side; CVODE: its history) and the error test
// failed there on arkode-erk and cvode-bdf (t = 0.01774 s).
TEST(NetworkEventBreaks, HeldForceOnTheDwellAfterTheJointIsThePreload) {
  const double speed = 40.71135497350809, w = 2 * kPi * speed, beta = 80 * kDeg;
  const double F0 = kK * kDelta0;
  for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    const RunResult r = simulate(rigid_law(kLobe, speed, integ, 0.02));
    const char* name = to_string(integ);
    ASSERT_TRUE(r.summary.finished) << name << ": " << r.summary.message;
    EXPECT_EQ(r.summary.separations, 0) << name;
    const double u0 = r.rows.front().u_c;
    double err_dwell = 0, err_fall = 0, F_joint = NAN;
    int n_dwell = 0;
    for (const HistoryRow& row : r.rows) {
      const double th = std::fmod(row.theta / kDeg, 360.0);
      if (th > 260.0 + 1e-9 && th < 360.0 - 1e-9) {
        err_dwell = std::max(err_dwell, std::abs(row.contact_force - F0));
        ++n_dwell;
      } else if (th > 180.0 && th <= 260.0 + 1e-9) {  // the fall, up to the joint's row
        const double x = std::min((th - 180.0) / 80.0, 1.0);
        const double L = kH * (1 + std::cos(kPi * x)) / 2;
        const double Xdd = kH * kPi * kPi / (2 * beta * beta) * std::cos(kPi * x) * w * w;
        const double F = kM * -Xdd + F0 + kK * L;  // the fall L = H(1 + cos πx)/2: L″ = −Hπ²/(2β²) cos πx
        err_fall = std::max(err_fall, std::abs(row.contact_force - F));
        EXPECT_NEAR(row.u_c - u0, L, 1e-12) << name << " theta " << th;
        if (std::abs(th - 260.0) < 1e-9) F_joint = row.contact_force;
      }
    }
    std::printf("%s: dwell after the joint |F - F0| <= %.3g N (%d rows), fall %.3g N, joint row %.10g N\n",
                name, err_dwell, n_dwell, err_fall, F_joint);
    EXPECT_GE(n_dwell, 2) << name;  // rows at step ends: a held rigid follower takes long steps
    EXPECT_LT(err_dwell, 1e-9 * F0) << name;
    EXPECT_LT(err_fall, 1e-9 * F0) << name;
    // the step that lands on the joint ends with the fall's left limit: F0 + m |H|π²ω²/(2β²)
    EXPECT_NEAR(F_joint, F0 + kM * kH * kPi * kPi / (2 * beta * beta) * w * w, 1e-9 * F0) << name;
  }
}

// A fall that starts abruptly after the top dwell: at 112.5 rev/s the held force jumps from
// F0 + kH = 530 N to 530 − m (Hπ²/(2β²)) ω² = −270 N at the joint (270°). The follower
// leaves there, and not a moment later: the separation is at the joint's time, and the
// free flight after it is the spring's closed form from rest at u = H.
TEST(NetworkEventBreaks, FollowerLeavesAtAJointWhereTheForceJumpsNegative) {
  const char* law = "dwell 60; harmonic 150 0.008; dwell 60; harmonic 90 -0.008";
  const double speed = 112.5, w = 2 * kPi * speed, beta = 90 * kDeg, F0 = kK * kDelta0;
  ASSERT_LT(F0 + kK * kH - kM * kH * kPi * kPi / (2 * beta * beta) * w * w, -200.0);  // the jump's sign
  const double tj = 0.75 / speed, t_end = (300.0 / 360.0) / speed, Om = std::sqrt(kK / kM);
  for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    const Scene sc = rigid_law(law, speed, integ, t_end);
    const double s_rtol = sc.solver.rtol;  // the flight's integration error scale
    const RunResult r = simulate(sc);
    const char* name = to_string(integ);
    ASSERT_TRUE(r.summary.finished) << name << ": " << r.summary.message;
    ASSERT_GE(r.summary.events.size(), 1u) << name;
    const ContactEvent& e = r.summary.events.front();
    EXPECT_EQ(e.type, EventKind::Separation) << name;
    EXPECT_NEAR(e.t, tj, 1e-12) << name;
    const HistoryRow& last = r.rows.back();
    const double u = (kH + F0 / kK) * std::cos(Om * (last.t - tj)) - F0 / kK;
    std::printf("%s: separation %.3g s from the joint, flight u %.3g m from the closed form\n", name, e.t - tj,
                last.u_c - r.rows.front().u_c - u);
    EXPECT_NEAR(last.t, t_end, 1e-15);
    EXPECT_NEAR(last.u_c - r.rows.front().u_c, u, 10 * s_rtol * (kH + F0 / kK)) << name;
    EXPECT_EQ(last.in_contact, 0) << name;
  }
}

}  // namespace
}  // namespace camdyn
