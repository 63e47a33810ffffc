// The verdict in words (issue 28; docs/contacts.md "The verdict") on constructed valves
// whose physics is known in closed form. One node "valve" (m = 0.1 kg) on a valve spring
// (k = 35 kN/m, preload F0 = 250 N), a cam contact (clearance c) above it and a seat (stop)
// below it; the cam a harmonic lobe: dwell 100°, harmonic rise 80° by H = 8 mm, harmonic
// fall 80°, dwell 100°. With x the fraction of a segment, β = 80° in radians:
//   rise X = H (1 − cos πx)/2,  X″ = H π²/(2β²) cos πx  (X″ < 0 for x > ½: the nose is
//   [140°, 220°] — the cam's geometry alone).
// Truths, each from the equations of motion written by hand:
//   * nose float (c = 0): the valve rides the cam, u = X; the cam's force m X″ω² + F0 + kX
//     reaches zero where cos πx* = −(F0 + kH/2)/(mω²Hπ²/(2β²) − kH/2);
//   * lift-off on the opening flank (c = 0.5 mm, cam restitution 0.6): the ramp meets the
//     resting valve where X = c, cos πx = 1 − 2c/H, with X″ > 0: it throws the valve off;
//   * seat bounce (c = 0.3 mm, seat restitution 0.5): the valve lands on its seat where the
//     fall gives X = c, at −Ẋ; it leaves at v0 = 0.5|Ẋ| and flies on the spring,
//     u = (F0/k)(cos Ωt − 1) + (v0/Ω) sin Ωt, back on the seat at
//     t = (2/Ω) atan(v0 k/(Ω F0)), Ω = √(k/m): the re-impact's cam angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/simulator.hpp"
#include "../network_run_support.hpp"
#include "results/verdict.hpp"

namespace camdyn {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double H = 0.008, m = 0.1, k = 35000.0, F0 = 250.0;
const double beta = 80.0 * kPi / 180.0;

Scene harmonic_valve(double clearance, double speed, double e_cam, double e_seat) {
  Scene s = parse_scene(R"(
[cam]
profile = "law"
law = "dwell 100; harmonic 80 0.008; harmonic 80 -0.008; dwell 100"
follower_face = "point"
[contact]
model = "event"
tol_u = 1e-10
[solver]
integrator = "arkode-erk"
rtol = 1e-10
atol = 1e-14
[run]
output_dt = 1e-5
)",
                        "verdict.toml");
  s.follower.kind = FollowerKind::Network;
  s.cam.speed_rev_s = speed;
  s.run.t_end = 1.0 / speed;
  s.network = camdyn_test::one_node_valve_network(m, k, F0, clearance);
  s.network.contacts[0].restitution = e_cam;
  s.network.contacts[1].restitution = e_seat;
  return s;
}

// The same lobe on a rigid follower: m 0.1 kg, k 35 kN/m, preload k·δ₀ = 250 N, 20 rev/s.
Scene rigid_harmonic() {
  return parse_scene(R"(
[cam]
profile = "law"
law = "dwell 100; harmonic 80 0.008; harmonic 80 -0.008; dwell 100"
follower_face = "point"
speed_rev_s = 20
[follower]
kind = "rigid"
mass = 0.1
[spring]
stiffness = 35000.0
precompression = 0.00714285714285714
)",
                     "jump.toml");
}

const VerdictItem* find(const Summary& s, const std::string& kind) {
  for (const VerdictItem& v : s.verdict)
    if (v.kind == kind) return &v;
  return nullptr;
}

TEST(Verdict, CamRegionsOfTheHarmonicLobe) {
  // The lobe 100°..260°, the nose (X″ < 0) from the rise's midpoint to the fall's: 140°..220°.
  Scene s = harmonic_valve(0.0, 20.0, 0.0, 0.0);
  resolve_defaults(s);
  const Cam cam(s.cam);
  const detail::CamRegions r(cam, s.cam);
  EXPECT_NEAR(r.open_deg(), 100.0, 0.06);
  EXPECT_NEAR(r.nose_start_deg(), 140.0, 0.06);
  EXPECT_NEAR(r.nose_end_deg(), 220.0, 0.06);
  EXPECT_NEAR(r.close_deg(), 260.0, 0.06);
  auto at = [&](double deg) { return r.at(deg * kPi / 180.0); };
  EXPECT_EQ(at(120), detail::CamRegions::Opening);
  EXPECT_EQ(at(139), detail::CamRegions::Opening);
  EXPECT_EQ(at(141), detail::CamRegions::Nose);
  EXPECT_EQ(at(219), detail::CamRegions::Nose);
  EXPECT_EQ(at(221), detail::CamRegions::Closing);
  EXPECT_EQ(at(300), detail::CamRegions::Closing);  // base circle after the lobe
  EXPECT_EQ(at(50), detail::CamRegions::Opening);   // base circle before it
  // Reversed rotation: the flanks swap.
  s.cam.speed_rev_s = -20.0;
  const detail::CamRegions rr(cam, s.cam);
  EXPECT_EQ(rr.at(120 * kPi / 180), detail::CamRegions::Closing);
  EXPECT_EQ(rr.at(240 * kPi / 180), detail::CamRegions::Opening);
}

TEST(Verdict, NoseFloatAtTheClosedFormAngle) {
  const double rev = 100.0, w = 2 * kPi * rev;
  const Summary s = Simulator(harmonic_valve(0.0, rev, 0.0, 0.0)).run();
  ASSERT_TRUE(s.finished) << s.message;
  const double A = m * w * w * H * kPi * kPi / (2 * beta * beta) - k * H / 2;
  const double x = std::acos(-(F0 + k * H / 2) / A) / kPi;
  const double theta = 100.0 + 80.0 * x;  // 156.1°
  ASSERT_FALSE(s.verdict.empty());
  EXPECT_EQ(s.verdict.front().kind, "nose_float") << s.verdict_text;
  EXPECT_EQ(s.verdict.front().contact, "cam");
  EXPECT_NEAR(s.verdict.front().theta_deg, theta, 0.02) << s.verdict_text;
  EXPECT_NEAR(s.verdict.front().speed_rev_s, rev, 1e-12);
  EXPECT_EQ(find(s, "opening_liftoff"), nullptr) << s.verdict_text;
  EXPECT_NE(s.verdict_text.find("float on the nose: contact 'cam' at"), std::string::npos) << s.verdict_text;
}

TEST(Verdict, LiftOffOnTheOpeningFlankByARampImpact) {
  const double c = 0.0005, rev = 20.0;
  const Summary s = Simulator(harmonic_valve(c, rev, 0.6, 0.0)).run();
  ASSERT_TRUE(s.finished) << s.message;
  const double theta = 100.0 + 80.0 * std::acos(1.0 - 2.0 * c / H) / kPi;  // 112.9°
  ASSERT_FALSE(s.verdict.empty());
  EXPECT_EQ(s.verdict.front().kind, "opening_liftoff") << s.verdict_text;
  EXPECT_EQ(s.verdict.front().contact, "cam");
  EXPECT_NEAR(s.verdict.front().theta_deg, theta, 0.01) << s.verdict_text;
  EXPECT_EQ(find(s, "nose_float"), nullptr) << s.verdict_text;  // far below the float speed
  EXPECT_EQ(find(s, "seat_bounce"), nullptr) << s.verdict_text;  // seat restitution 0
}

TEST(Verdict, SeatBounceAtTheClosedFormReImpact) {
  const double c = 0.0003, rev = 20.0, w = 2 * kPi * rev, e = 0.5;
  const Summary s = Simulator(harmonic_valve(c, rev, 0.0, e)).run();
  ASSERT_TRUE(s.finished) << s.message;
  // landing: fall segment 180°..260°, X = H (1 + cos πx)/2 = c
  const double x = std::acos(2.0 * c / H - 1.0) / kPi;
  const double th0 = 180.0 + 80.0 * x;
  const double Xdot = H * kPi / (2 * beta) * std::sin(kPi * x) * w;  // |Ẋ| there
  const double Om = std::sqrt(k / m), v0 = e * Xdot;
  const double t_fly = 2.0 / Om * std::atan(v0 * k / (Om * F0));
  const double theta = th0 + t_fly * w * 180.0 / kPi;
  const VerdictItem* b = find(s, "seat_bounce");
  ASSERT_NE(b, nullptr) << s.verdict_text;
  EXPECT_EQ(b->contact, "seat");
  EXPECT_NEAR(b->theta_deg, theta, 0.02) << s.verdict_text;
  EXPECT_EQ(find(s, "nose_float"), nullptr) << s.verdict_text;
  EXPECT_EQ(find(s, "opening_liftoff"), nullptr) << s.verdict_text;
  EXPECT_EQ(find(s, "closing_bounce"), nullptr) << s.verdict_text;  // the cam leaves in its lash
}

TEST(Verdict, NoSeparationBelowTheFloatSpeed) {
  const Summary s = Simulator(harmonic_valve(0.0, 20.0, 0.0, 0.0)).run();
  ASSERT_TRUE(s.finished) << s.message;
  ASSERT_EQ(s.verdict.size(), 1u) << s.verdict_text;
  EXPECT_EQ(s.verdict[0].kind, "no_separation");
  EXPECT_EQ(s.verdict_text, "no separation");
  EXPECT_TRUE(std::isnan(s.verdict[0].theta_deg));
}

TEST(Verdict, SingleFollowerNoseFloatOnTheEccentric) {
  // examples/circle_cam.toml: flat face on an eccentric circle, X = R + e cos θ (R 2, e 0.5),
  // m 1, k 500, precompression 7; started at θ₀ = 180° (spring origin x₀ = X(180°) = 1.5).
  // The cam's force F = −m e ω² cos θ + k (7 + X − 1.5) reaches zero where
  // cos θ = 3750/(e ω² − 250); at 16 rev/s first at θ = 360° − 38.7°. The nose of an
  // eccentric is where X″ = −e cos θ ≤ 0: |θ| ≤ 90°.
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/circle_cam.toml");
  s.cam.speed_rev_s = 16.0;
  s.cam.theta0_deg = 180.0;
  s.contact.model = ContactModel::Event;
  s.solver.rtol = 1e-10;
  s.run.t_end = 1.0 / 16.0;
  const Summary r = Simulator(s).run();
  ASSERT_TRUE(r.finished) << r.message;
  const double w = 2 * kPi * 16.0;
  const double theta = 360.0 - std::acos(3750.0 / (0.5 * w * w - 250.0)) * 180.0 / kPi;
  ASSERT_FALSE(r.verdict.empty());
  EXPECT_EQ(r.verdict.front().kind, "nose_float") << r.verdict_text;
  EXPECT_EQ(r.verdict.front().contact, "cam");
  EXPECT_NEAR(r.verdict.front().theta_deg, theta, 0.02) << r.verdict_text;
}

TEST(Verdict, SweepHasAVerdictColumnPerSpeed) {
  // The harmonic valve (c = 0) below and above its float speed (81.4 rev/s by the closed
  // form of the nose float: mω²Hπ²/(2β²) − kH/2 = F0 + kH/2).
  SweepOptions o;
  o.axes = {{"cam.speed_rev_s", {20.0, 100.0}}};
  Scene base = harmonic_valve(0.0, 20.0, 0.0, 0.0);
  base.run.t_end = 0.01;
  const SweepPlan plan = plan_sweep(base, o);
  std::vector<std::string> head;
  {
    std::string h = plan.header, f;
    for (char ch : h) {
      if (ch == ',' || ch == '\n') head.push_back(f), f.clear();
      else f += ch;
    }
  }
  const size_t col = size_t(std::find(head.begin(), head.end(), "verdict") - head.begin());
  ASSERT_LT(col, head.size());
  auto verdict_of = [&](long i) {
    const std::string j = run_sweep_point(plan, i, false, 0.0, nullptr);
    const std::string row = j.substr(j.find('\t', 2) + 1);
    std::vector<std::string> f(1);
    for (char ch : row) {
      if (ch == ',') f.emplace_back();
      else f.back() += ch;
    }
    return f.at(col);
  };
  EXPECT_EQ(verdict_of(0), "no_separation");
  EXPECT_EQ(verdict_of(1).rfind("nose_float", 0), 0u) << verdict_of(1);
}

TEST(Verdict, JumpBySimulationNamesItsPhenomenon) {
  // The rigid follower on the harmonic lobe, bisected by simulation: its phenomenon is the
  // nose float, and the bracket contains the closed form.
  Scene s = rigid_harmonic();
  s.contact.model = ContactModel::Event;
  s.run.t_end = 0.02;
  const JumpResult cf = jump_speed(s);
  JumpOptions o;
  o.force_simulation = true;
  o.rel_tol = 1e-3;
  const JumpResult r = jump_speed(s, o);
  EXPECT_EQ(r.method, "simulation");
  EXPECT_LE(r.lo_rev_s, cf.jump_speed_rev_s * (1 + 1e-6));
  EXPECT_GE(r.hi_rev_s, cf.jump_speed_rev_s * (1 - 1e-6));
  EXPECT_EQ(r.phenomenon, "nose_float") << r.phenomenon_text;
  EXPECT_NE(jump_speed_text(r).find(", bracket ["), std::string::npos);
}

TEST(Verdict, JumpSpeedTextHasOnlyTheBracketsDigits) {
  JumpResult r;
  r.method = "simulation";
  r.lo_rev_s = 24.987123;
  r.hi_rev_s = 24.989623;  // width 0.0025: the midpoint to 1e-3, the ends outwards to 1e-4
  EXPECT_EQ(jump_speed_text(r), "24.988 rev/s, bracket [24.9871, 24.9897] rev/s, width 0.0025 rev/s");
  r.lo_rev_s = 61.2;
  r.hi_rev_s = 67.9;  // width 6.7: to units, ends to tenths
  EXPECT_EQ(jump_speed_text(r), "65 rev/s, bracket [61.2, 67.9] rev/s, width 6.7 rev/s");
}

TEST(Verdict, ClosedFormJumpIsANoseFloatOnTheHarmonicLobe) {
  // A rigid follower on the harmonic lobe: F_req = m X″ω² + F0 + kX is least at the peak
  // (180°) when mω²π²/β² > k, so the closed form's angle is 180° — on the nose.
  Scene s = rigid_harmonic();
  const JumpResult r = jump_speed(s);
  EXPECT_NEAR(r.theta_deg, 180.0, 0.01);
  EXPECT_EQ(r.phenomenon, "nose_float");
  EXPECT_NE(r.phenomenon_text.find("float on the nose at 180.0 deg"), std::string::npos) << r.phenomenon_text;
  EXPECT_NE(jump_speed_text(r).find("(closed form)"), std::string::npos);
}

}  // namespace
}  // namespace camdyn
