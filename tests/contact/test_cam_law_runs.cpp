// camdyn — runs with the issue-24 cams: a roller follower held on an eccentric circle cam
// against the closed-form contact force, steps landing on the joints of a motion law (no
// rejection storm there), and the scene keys through the TOML path.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <camdyn/scene.hpp>
#include <camdyn/simulator.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(CamLawRuns, RollerHeldOnCircleCamForceMatchesClosedForm) {
  // Rigid follower of mass m on a spring k (preload k δ₀), roller R_r, offset ε, on a circle
  // cam (R, e) at constant ω: F = m s″ ω² + k δ₀ + k (s − s(θ₀)),
  // s = e cos θ + √((R + R_r)² − (ε − e sin θ)²).
  Scene sc = parse_scene(R"(
[cam]
profile = "circle"
radius = 2.0
eccentricity = 0.5
follower_face = "roller"
roller_radius = 0.4
follower_offset = 0.3
speed_rev_s = 1.0
width = 1.0
[follower]
kind = "rigid"
mass = 1.0
[spring]
stiffness = 500.0
precompression = 7.0
[run]
t_end = 1.0
output_dt = 0.005
)",
                         "<test>");
  const RunResult r = simulate(sc);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_EQ(r.summary.separations, 0);
  const double R = 2.0, e = 0.5, rr = 0.4, eps = 0.3, w = 2 * kPi, m = 1.0, k = 500.0, d0 = 7.0;
  auto s = [&](double th) {
    const double q = eps - e * std::sin(th);
    return e * std::cos(th) + std::sqrt((R + rr) * (R + rr) - q * q);
  };
  const double h = 1e-4;
  double err = 0, Fmax = 0;
  for (const HistoryRow& row : r.rows) {
    const double th = row.theta;
    const double s2 = (s(th + h) - 2 * s(th) + s(th - h)) / (h * h);
    const double F = m * s2 * w * w + k * d0 + k * (s(th) - s(0.0));
    err = std::max(err, std::fabs(row.contact_force - F));
    Fmax = std::max(Fmax, F);
  }
  EXPECT_LT(err, 1e-5 * Fmax) << "max |F − F_closed| = " << err;
  // Designer results: the pressure angle's closed form max over θ of atan2(ε − e sin θ, …)
  double phimax = 0;
  for (int i = 0; i < 36000; ++i) {
    const double th = 2 * kPi * i / 36000, q = eps - e * std::sin(th);
    phimax = std::max(phimax, std::fabs(std::atan2(q, std::sqrt((R + rr) * (R + rr) - q * q))));
  }
  EXPECT_NEAR(r.summary.max_pressure_angle_deg, phimax * 180 / kPi, 0.02);
  EXPECT_NEAR(r.summary.min_radius_of_curvature, R, 1e-12);
  EXPECT_TRUE(std::isfinite(r.summary.max_hertz_stress));
  // Mean power over whole revolutions = mean of F ṡ = d/dt of the spring energy: 0 per cycle
  // (no damping), so the mean torque over one revolution vanishes against its peak.
  EXPECT_LT(std::fabs(r.summary.cam_torque_mean), 2e-3 * std::fabs(r.summary.cam_torque_peak));
}

TEST(CamLawRuns, StepsLandOnLawJointsWithoutRejectionStorm) {
  // Cycloidal and 3-4-5 rise and fall between dwells: the jerk jumps at the four joints
  // (C2). Landing on them (cam.land_on_breaks) the error estimate never sees the jump
  // inside a step; without it the steps that straddle a joint are rejected and retried.
  auto run = [](const char* kind, bool land) {
    const std::string law = std::string("dwell 100; ") + kind + " 70 0.5; dwell 20; " + kind + " 70 -0.5; dwell 100";
    Scene sc = parse_scene("[cam]\nprofile = \"law\"\nlaw = \"" + law + R"("
base_radius = 4.0
speed_rev_s = 1.75
[follower]
kind = "rigid"
[run]
t_end = 2.0
output_dt = 0.0
)",
                           "<test>");
    sc.cam.land_on_breaks = land;
    return simulate(sc);
  };
  for (const char* kind : {"cycloidal", "poly345"}) {
    SCOPED_TRACE(kind);
    const RunResult with = run(kind, true), without = run(kind, false);
    ASSERT_TRUE(with.summary.finished) << with.summary.message;
    ASSERT_TRUE(without.summary.finished) << without.summary.message;
    std::printf("%s joints, 3.5 revolutions (14 joints): landing %ld steps %ld rejected; "
                "not landing %ld steps %ld rejected\n",
                kind, with.summary.steps, with.summary.rejected_steps, without.summary.steps,
                without.summary.rejected_steps);
    EXPECT_LT(2 * with.summary.rejected_steps, without.summary.rejected_steps);
    EXPECT_LT(with.summary.steps, without.summary.steps);
    // A row (output_dt = 0: every step) lands on each joint: θ = 100°, 170°, 190°, 260°, 360°.
    const double joints[] = {100, 170, 190, 260, 0};
    int landed = 0;
    for (const HistoryRow& row : with.rows) {
      const double deg = std::fmod(row.theta * 180 / kPi, 360.0);
      for (double j : joints)
        if (std::fabs(deg - j) < 1e-9 || std::fabs(deg - j - 360) < 1e-9) ++landed;
    }
    EXPECT_GE(landed, 14);
    EXPECT_EQ(with.summary.cam_continuity.rfind("C3 at 0°, C2 at 100°", 0), 0u) << with.summary.cam_continuity;
  }
}

TEST(CamLawRuns, SceneKeysRoundTripAndBadInputNamesTheKey) {
  const Scene sc = parse_scene(R"(
[cam]
profile = "arc"
base_radius = 2.0
nose_radius = 0.6
nose_distance = 1.8
flank_radius = 5.0
follower_face = "knife_edge"
follower_offset = 0.1
)",
                               "<test>");
  EXPECT_EQ(sc.cam.profile, CamProfileKind::Arc);
  EXPECT_EQ(sc.cam.follower_face, FollowerFace::KnifeEdge);
  const Scene back = parse_scene(to_toml(sc), "<round-trip>");
  EXPECT_TRUE(back.cam == sc.cam);
  try {
    parse_scene("[cam]\nfollower_face = \"wheel\"\n", "<test>");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.follower_face");
  }
  Scene bad = sc;
  bad.cam.law = "dwell 100";
  bad.cam.profile = CamProfileKind::Law;
  const RunResult r = [&] {
    try {
      return simulate(bad);
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), "cam.law");
      EXPECT_NE(e.rule().find("360"), std::string::npos) << e.rule();
      return RunResult{};
    }
  }();
  (void)r;
}

TEST(CamLawRuns, HeldThroughTheJointAfterADwellOnEveryEngine) {
  // Started on the base circle's dwell (θ₀ = 270°), so the first joint comes after a long
  // dwell; Lee and the event method on each engine. Rigid follower held on a cycloidal rise
  // and fall: F = m X″ω² + k(δ₀ + X), X = L(x − sin 2πx / 2π), x = (θ − θ_s)/β.
  const double L = 0.5, beta = kPi / 2, m = 1.0, k = 500.0, d0 = 0.2, w = 2 * kPi;
  auto X2 = [&](double th) {  // X″(θ), θ in [0, 2π)
    th = std::fmod(th, 2 * kPi);
    if (th < 0) th += 2 * kPi;
    if (th < beta) return L / (beta * beta) * 2 * kPi * std::sin(2 * kPi * th / beta);
    if (th < 2 * beta) return -L / (beta * beta) * 2 * kPi * std::sin(2 * kPi * (th - beta) / beta);
    return 0.0;
  };
  auto X = [&](double th) {
    th = std::fmod(th, 2 * kPi);
    if (th < 0) th += 2 * kPi;
    if (th < beta) { const double x = th / beta; return L * (x - std::sin(2 * kPi * x) / (2 * kPi)); }
    if (th < 2 * beta) { const double x = (th - beta) / beta; return L - L * (x - std::sin(2 * kPi * x) / (2 * kPi)); }
    return 0.0;
  };
  for (const char* model : {"lee", "event"})
    for (const char* engine : {"arkode-erk", "arkode-dirk", "cvode-bdf"}) {
      SCOPED_TRACE(std::string(model) + " on " + engine);
      Scene sc = parse_scene(std::string(R"(
[cam]
profile = "law"
law = "cycloidal 90 0.5; cycloidal 90 -0.5; dwell 180"
base_radius = 4.0
speed_rev_s = 1.0
theta0_deg = 270.0
[follower]
kind = "rigid"
mass = 1.0
[spring]
stiffness = 500.0
precompression = 0.2
[contact]
model = ")") + model + R"("
[solver]
integrator = ")" + engine + R"("
[run]
t_end = 1.5
output_dt = 0.002
)",
                             "<test>");
      const RunResult r = simulate(sc);
      ASSERT_TRUE(r.summary.finished) << r.summary.message;
      EXPECT_EQ(r.summary.separations, 0);
      double err = 0, Fmax = 0;
      for (const HistoryRow& row : r.rows) {
        const double F = m * X2(row.theta) * w * w + k * (d0 + X(row.theta));
        err = std::max(err, std::fabs(row.contact_force - F));
        Fmax = std::max(Fmax, F);
      }
      EXPECT_LT(err, 1e-4 * Fmax) << "max |F − F_closed| = " << err;
    }
}

TEST(CamLawRuns, LawRollerExamplePassesItsFirstJointOnEveryEngine) {
  // examples/law_roller.toml starts at 270° on the base circle's dwell and reaches the
  // dwell → cycloidal joint at t = 0.01 s. Lee on cvode-bdf stopped there ("the error test
  // failed repeatedly": a CVODE trial restarted at order 1 after the dwell's long steps); a
  // trial CVODE cannot complete is now rejected and halved. Checked against a second
  // formulation: the event-driven method on arkode-erk at rtol 1e-10.
  const std::string file = std::string(CAMDYN_SOURCE_DIR) + "/examples/law_roller.toml";
  Scene ref = load_scene_file(file);
  ref.run.t_end = 0.02;
  ref.run.output_dt = 1e-4;
  ref.contact.model = ContactModel::Event;
  ref.solver.integrator = Integrator::ArkodeErk;
  ref.solver.rtol = 1e-10;
  const RunResult rr = simulate(ref);
  ASSERT_TRUE(rr.summary.finished) << rr.summary.message;
  for (Integrator eng : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    SCOPED_TRACE(to_string(eng));
    Scene s = load_scene_file(file);
    s.run.t_end = 0.02;
    s.run.output_dt = 1e-4;
    s.solver.integrator = eng;
    const RunResult r = simulate(s);
    ASSERT_TRUE(r.summary.finished) << r.summary.message;
    ASSERT_EQ(r.rows.size(), rr.rows.size());
    double err = 0, Fmax = 0;
    for (std::size_t i = 0; i < r.rows.size(); ++i) {
      err = std::max(err, std::fabs(r.rows[i].contact_force - rr.rows[i].contact_force));
      Fmax = std::max(Fmax, std::fabs(rr.rows[i].contact_force));
    }
    EXPECT_LT(err, 1e-4 * Fmax) << "max |F − F_ref| = " << err;
  }
}
