// camdyn — motion laws (issue 24): peak coefficients against the closed forms of the
// literature (Norton, Cam Design and Manufacturing Handbook, table 3-2), exact derivatives
// against finite differences, continuity at the joints, closure, and the polydyne against
// an independent integration of the valve's equation of motion.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>
#include <camdyn/motion_law.hpp>
#include <camdyn/scene.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;

struct Peaks {
  double f1 = 0, f2 = 0, f3 = 0;
};
Peaks sample_peaks(MotionSegmentKind k) {
  Peaks p;
  const int n = 200000;
  for (int i = 0; i <= n; ++i) {
    const auto f = MotionLaw::normalised(k, double(i) / n);
    p.f1 = std::max(p.f1, std::fabs(f[1]));
    p.f2 = std::max(p.f2, std::fabs(f[2]));
    p.f3 = std::max(p.f3, std::fabs(f[3]));
  }
  return p;
}
}  // namespace

TEST(MotionLaw, PeakCoefficientsMatchClosedForms) {
  struct Case {
    MotionSegmentKind k;
    double Cv, Ca, tol;
  };
  // Closed forms: cycloidal 2, 2π; 3-4-5: 15/8, 10/√3; SHM π/2, π²/2; 4-5-6-7: 35/16,
  // 84/(5√5)·… (7.5132, Norton); modified trapezoid 2.0, 4.888; modified sine 1.76, 5.528
  // (Norton's table, 4 digits).
  const Case cases[] = {
      {MotionSegmentKind::Cycloidal, 2.0, 2 * kPi, 1e-9},
      {MotionSegmentKind::Poly345, 1.875, 10.0 / std::sqrt(3.0), 1e-8},
      {MotionSegmentKind::Harmonic, kPi / 2, kPi * kPi / 2, 1e-9},
      {MotionSegmentKind::Poly4567, 35.0 / 16.0, 7.5132, 1e-4},
      {MotionSegmentKind::ModTrap, 2.0, 4.888, 1e-3},
      {MotionSegmentKind::ModSine, 1.76, 5.528, 1e-3},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(to_string(c.k));
    const Peaks p = sample_peaks(c.k);
    EXPECT_NEAR(p.f1, c.Cv, c.tol * c.Cv);
    EXPECT_NEAR(p.f2, c.Ca, c.tol * c.Ca);
    const auto f0 = MotionLaw::normalised(c.k, 0.0), f1 = MotionLaw::normalised(c.k, 1.0);
    EXPECT_NEAR(f0[0], 0.0, 1e-14);
    EXPECT_NEAR(f1[0], 1.0, 1e-12);
    EXPECT_NEAR(f0[1], 0.0, 1e-12);
    EXPECT_NEAR(f1[1], 0.0, 1e-11);
  }
}

TEST(MotionLaw, DerivativesMatchFiniteDifferences) {
  const MotionSegmentKind kinds[] = {MotionSegmentKind::Cycloidal, MotionSegmentKind::Poly345,
                                     MotionSegmentKind::Harmonic,  MotionSegmentKind::Poly4567,
                                     MotionSegmentKind::ModTrap,   MotionSegmentKind::ModSine};
  const double h = 1e-5;
  for (auto k : kinds)
    for (double x = 0.013; x < 0.99; x += 0.0371) {
      SCOPED_TRACE(std::string(to_string(k)) + " x=" + std::to_string(x));
      const auto m = MotionLaw::normalised(k, x - h), c = MotionLaw::normalised(k, x),
                 p = MotionLaw::normalised(k, x + h);
      for (int d = 0; d < 3; ++d) {
        const double fd = (p[d] - m[d]) / (2 * h);
        EXPECT_NEAR(c[d + 1], fd, 1e-5 * (1 + std::fabs(c[d + 1])));
      }
    }
}

TEST(MotionLaw, TrigonometricLawsAgainstLibm) {
  // The laws' own sin/cos kernel (motion_law.cpp) against std::sin/std::cos: cycloidal
  // f = x − sin 2πx / 2π (phases over [0, 2π]: all four quadrants), harmonic
  // f = (1 − cos πx)/2, to a few ulps.
  for (int i = 0; i <= 20000; ++i) {
    const double x = i / 20000.0, a = 2 * kPi * x;
    const auto c = MotionLaw::normalised(MotionSegmentKind::Cycloidal, x);
    EXPECT_NEAR(c[0], x - std::sin(a) / (2 * kPi), 4e-16);
    EXPECT_NEAR(c[1], 1 - std::cos(a), 8e-16);
    EXPECT_NEAR(c[2], 2 * kPi * std::sin(a), 8e-15);
    EXPECT_NEAR(c[3], 4 * kPi * kPi * std::cos(a), 4e-14);
    const auto h = MotionLaw::normalised(MotionSegmentKind::Harmonic, x);
    EXPECT_NEAR(h[0], 0.5 * (1 - std::cos(kPi * x)), 4e-16);
    EXPECT_NEAR(h[1], 0.5 * kPi * std::sin(kPi * x), 2e-15);
  }
}

TEST(MotionLaw, ContinuityOrderAtJoints) {
  // dwell → cycloidal: acceleration 0 at the ends, jerk 4π²: C2. Harmonic: acceleration
  // π²/2 at the ends: C1. Ramp: velocity jump: C0. 4-5-6-7: jerk 0 at the ends: C3.
  const MotionLaw law = MotionLaw::parse(
      "dwell 40; cycloidal 50 2; harmonic 50 -1; dwell 20; ramp 20 0.5; poly4567 60 1; dwell 20; "
      "poly4567 60 -2.5; dwell 40");
  const auto& b = law.breakpoints();
  ASSERT_EQ(b.size(), 9u);
  const int expect[] = {3, 2, 1, 1, 0, 0, 3, 3, 3};
  for (std::size_t i = 0; i < b.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(b[i].order, expect[i]);
  }
  EXPECT_NEAR(b[1].jump[3], 2.0 * 4 * kPi * kPi / std::pow(50 * kPi / 180, 3), 1e-6);
  EXPECT_NEAR(law.lift(), 2.5, 1e-12);
  EXPECT_EQ(law.continuity_report().rfind("C3 at 0°, C2 at 40°, C1 at 90°", 0), 0u) << law.continuity_report();
}

TEST(MotionLaw, LiftMustCloseAndErrorsNameTheSegment) {
  try {
    MotionLaw::parse("dwell 180; cycloidal 90 1; cycloidal 90 -0.9");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.law");
    EXPECT_NE(e.rule().find("does not close"), std::string::npos) << e.rule();
  }
  EXPECT_THROW(MotionLaw::parse("dwell 180; cycloidal 90 1; cycloidal 80 -1"), SceneError);
  try {
    MotionLaw::parse("dwell 180; cycloid 90 1; cycloidal 90 -1");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(e.rule().find("segment 2"), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find("unknown kind 'cycloid'"), std::string::npos) << e.rule();
  }
  EXPECT_THROW(MotionLaw::parse("dwell 180 1; cycloidal 90 1; cycloidal 90 -1"), SceneError);
  EXPECT_THROW(MotionLaw::parse("poly 180 1 0 0 0 10 -15 5; poly345 180 -1"), SceneError);  // Σc ≠ 1
  // General coefficients equal to 3-4-5.
  const MotionLaw a = MotionLaw::parse("poly 180 1 0 0 0 10 -15 6; poly345 180 -1");
  const MotionLaw b = MotionLaw::parse("poly345 180 1; poly345 180 -1");
  for (double th = 0; th < 6.3; th += 0.1) {
    EXPECT_NEAR(a.eval(th).L, b.eval(th).L, 1e-13);
    EXPECT_NEAR(a.eval(th).L3, b.eval(th).L3, 1e-10);
  }
}

TEST(MotionLaw, PolydyneValveFollowsTheIntendedMotion) {
  // Valve of mass m on a spring ks, driven through a train of stiffness k by the cam lift
  // y(θ): m ẍ = k (y − x) − ks x. At the design speed the polydyne cam makes x follow the
  // intended 5-6-7-8-9 law exactly; integrated here by classical RK4 (independent of the
  // library), starting at rest on the base circle.
  const double k = 2e6, m = 0.1, ks = 4e4, rev_s = 50.0, H = 0.01;
  char buf[256];
  std::snprintf(buf, sizeof buf, "dwell 100; polydyne 70 %g k=%g m=%g ks=%g speed_rev_s=%g; dwell 20; "
                "polydyne 70 %g k=%g m=%g ks=%g speed_rev_s=%g; dwell 100", H, k, m, ks, rev_s, -H, k, m, ks, rev_s);
  const MotionLaw law = MotionLaw::parse(buf);
  EXPECT_NEAR(law.lift(), (1 + ks / k) * H, 1e-12);
  const double w = 2 * kPi * rev_s;
  auto intended = [&](double th) {
    const double deg = th * 180 / kPi;
    auto p = [](double x) { return MotionLaw::normalised(MotionSegmentKind::Polydyne, x)[0]; };
    if (deg < 100) return 0.0;
    if (deg < 170) return H * p((deg - 100) / 70);
    if (deg < 190) return H;
    if (deg < 260) return H - H * p((deg - 190) / 70);
    return 0.0;
  };
  auto run = [&](auto cam_lift) {
    double x = 0, v = 0, t = 0, err = 0;
    const double T = 1.0 / rev_s, dt = T / 200000;
    auto acc = [&](double tt, double xx) { return (k * (cam_lift(w * tt) - xx) - ks * xx) / m; };
    while (t < T) {
      const double k1x = v, k1v = acc(t, x);
      const double k2x = v + 0.5 * dt * k1v, k2v = acc(t + 0.5 * dt, x + 0.5 * dt * k1x);
      const double k3x = v + 0.5 * dt * k2v, k3v = acc(t + 0.5 * dt, x + 0.5 * dt * k2x);
      const double k4x = v + dt * k3v, k4v = acc(t + dt, x + dt * k3x);
      x += dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      t += dt;
      err = std::max(err, std::fabs(x - intended(w * t)));
    }
    return err;
  };
  const double err_polydyne = run([&](double th) { return law.eval(th).L; });
  const double err_plain = run([&](double th) { return intended(th); });
  EXPECT_LT(err_polydyne, 1e-4 * H);
  EXPECT_GT(err_plain, 30 * err_polydyne);  // the uncorrected cam: the train's vibration
}

TEST(MotionLaw, CamKindLawPointFollowerNeedsNoBaseRadius) {
  // The case: a 3-4-5 rise of 9 over 50° with a flat face needs r_b ≈ 60 or the
  // convexity check refuses it; the point follower (lift imposed) takes it as is.
  CamSpec c;
  c.profile = CamProfileKind::Law;
  c.law = "poly345 50 9; dwell 20; poly345 50 -9; dwell 240";
  c.base_radius = 20;
  try {
    Cam cam(c);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(e.rule().find("not convex"), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find("cam angles"), std::string::npos) << e.rule();
  }
  c.follower_face = FollowerFace::Point;
  c.base_radius = -1;  // unused
  const Cam cam(c);
  EXPECT_NEAR(cam.lift(), 9.0, 1e-12);
  const CamPoint p = cam.evaluate(25 * kPi / 180);
  EXPECT_NEAR(p.X_C, 4.5, 1e-12);
  EXPECT_NEAR(p.dX_dtheta, 9 * 1.875 / (50 * kPi / 180), 1e-9);
  ASSERT_EQ(cam.breakpoints().size(), 4u);
  EXPECT_NEAR(cam.breakpoints()[1], 50 * kPi / 180, 1e-15);
}

TEST(CamDriveStops, NextTimeAtAnglesConstantAndTable) {
  CamSpec c;
  c.speed_rev_s = 2.0;  // ω = 4π
  c.theta0_deg = 10;
  const CamDrive d(c);
  const std::vector<double> a{0.0, kPi / 2};
  // From θ = 10°: next 90° at Δθ = 80°.
  EXPECT_NEAR(d.next_time_at_angles(0.0, a, 10.0), (80.0 / 360.0) / 2.0, 1e-15);
  const double t1 = d.next_time_at_angles(0.0, a, 10.0);
  EXPECT_NEAR(d.next_time_at_angles(t1, a, 10.0), (350.0 / 360.0) / 2.0, 1e-14);
  c.speed_table_t = {0.0, 1.0};
  c.speed_table_rev_s = {0.0, 2.0};  // θ = θ0 + 2π t² (rev/s ramp)
  const CamDrive r(c);
  const double t = r.next_time_at_angles(0.0, a, 10.0);
  EXPECT_NEAR(r.theta(t) - r.theta(0.0), 80 * kPi / 180, 1e-12);
  EXPECT_EQ(r.next_time_at_angles(0.0, a, 0.01), INFINITY);
}
