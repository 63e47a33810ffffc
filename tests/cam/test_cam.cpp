// Tests of camdyn::Cam and camdyn::CamDrive (docs/method.md §2, §5) against independent truth:
// closed forms (eccentric circle), brute-force scans of the profile, finite differences,
// the paper's own kinematic formulas, and exact integrals of the drive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>

using camdyn::Cam;
using camdyn::CamDrive;
using camdyn::CamMotion;
using camdyn::CamPoint;
using camdyn::CamProfileKind;
using camdyn::CamSpec;
using camdyn::SceneError;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

CamSpec circle_spec(double R, double e) {
  CamSpec s;
  s.profile = CamProfileKind::Circle;
  s.radius = R;
  s.eccentricity = e;
  return s;
}

CamSpec lift_spec() {
  CamSpec s;
  s.profile = CamProfileKind::Lift;
  s.base_radius = 2.0;
  s.lift_angles_deg = {0, 60, 120, 180, 240, 300};
  s.lift = {0.0, 0.1, 0.5, 0.8, 0.4, 0.05};
  return s;
}

/// 5-point central differences of h(θ) = X_C(θ).
struct FD {
  double d1, d2;
};
FD central5(const Cam& cam, double th, double d) {
  auto X = [&](double t) { return cam.evaluate(t).X_C; };
  const double fm2 = X(th - 2 * d), fm1 = X(th - d), f0 = X(th), fp1 = X(th + d),
               fp2 = X(th + 2 * d);
  return {(fm2 - 8 * fm1 + 8 * fp1 - fp2) / (12 * d),
          (-fm2 + 16 * fm1 - 30 * f0 + 16 * fp1 - fp2) / (12 * d * d)};
}

}  // namespace

// ---- eccentric circle: closed form -----------------------------------------------------
TEST(CamCircle, MatchesClosedForm) {
  const std::vector<std::pair<double, double>> cases = {
      {2.0, 0.5}, {1.0, 0.0}, {3.0, 2.9}, {10.0, 0.1}, {0.01, 0.004}};
  for (const auto& [R, e] : cases) {
    const Cam cam(circle_spec(R, e));
    EXPECT_DOUBLE_EQ(cam.min_radius_of_curvature(), R);
    EXPECT_NEAR(cam.lift(), 2 * e, 1e-15 * R);
    double max_rel = 0, max_mot = 0;
    for (int i = 0; i < 1200; ++i) {
      const double th = -20.0 + 40.0 * i / 1199.0;
      const CamPoint p = cam.evaluate(th);
      const double X = e * std::cos(th) + R, h1 = -e * std::sin(th), h2 = -e * std::cos(th);
      const double scale = R + e;
      max_rel = std::max({max_rel, std::fabs(p.X_C - X) / scale,
                          std::fabs(p.dX_dtheta - h1) / scale,
                          std::fabs(p.d2X_dtheta2 - h2) / scale, std::fabs(p.rho - R) / R});
      // contact point (e cos θ + R, e sin θ) in the fixed frame
      EXPECT_NEAR(p.r, std::hypot(X, e * std::sin(th)), 1e-12 * scale);
      EXPECT_NEAR(p.beta, std::atan2(e * std::sin(th), X), 1e-12);
      for (const auto& [w, wd] : {std::pair{7.0, 0.0}, std::pair{-3.0, 25.0}, std::pair{0.5, -4.0}}) {
        const double Xd = h1 * w, Xdd = h2 * w * w + h1 * wd;
        const double ms = scale * (w * w + std::fabs(wd) + std::fabs(w));
        for (const CamMotion& m : {cam.motion(th, w, wd), cam.motion_paper(th, w, wd)}) {
          max_mot = std::max({max_mot, std::fabs(m.X - X) / scale, std::fabs(m.Xdot - Xd) / ms,
                              std::fabs(m.Xddot - Xdd) / ms});
        }
      }
    }
    std::printf("circle R=%g e=%g: max rel error geometry %.3g, motion %.3g\n", R, e, max_rel,
                max_mot);
    EXPECT_LT(max_rel, 1e-12);
    EXPECT_LT(max_mot, 1e-12);
  }
}

// ---- the paper cam (docs/method.md §5) ------------------------------------------------------
TEST(CamPaper, ShapeNumbers) {
  const Cam cam{CamSpec{}};
  std::printf("paper cam: min rho = %.6f, lift = %.6f, X_C(0) = %.15f\n",
              cam.min_radius_of_curvature(), cam.lift(), cam.evaluate(0.0).X_C);
  EXPECT_GT(cam.min_radius_of_curvature(), 0.45);  // docs/method.md: ≈ 0.53 at the nose
  EXPECT_LT(cam.min_radius_of_curvature(), 0.60);
  EXPECT_GT(cam.lift(), 0.95);  // docs/method.md: about 1.03
  EXPECT_LT(cam.lift(), 1.10);
  EXPECT_NEAR(cam.evaluate(0.0).X_C, 2.0, 1e-3);  // base circle at θ = 0
  // Symmetric about the x axis → h(θ) = h(−θ).
  for (double th : {0.3, 1.1, 2.0, 2.9}) EXPECT_NEAR(cam.evaluate(th).X_C, cam.evaluate(-th).X_C, 1e-12);
  // The nose (polar angle π, radius 3) faces the follower at θ = π.
  EXPECT_NEAR(cam.evaluate(kPi).X_C, 3.0, 1e-12);
}

TEST(CamPaper, MotionFormsAgreeAndMatchFiniteDifferences) {
  const Cam cam{CamSpec{}};
  double max_form = 0, max_fd1 = 0, max_fd2 = 0, max_rho = 0, min_rho = 1e300;
  // FD step: the 5-point formulas have truncation error O(δ⁴) where h is smooth, but
  // h‴ = ρ′ − h′ jumps at the cam angles where a spline knot is the contact point (the
  // spline's third derivative jumps there), so stencils straddling those angles are only
  // O(δ²) (h′) and O(δ) (h″) accurate; round-off is ~ε·h/δ (h′) and ~5ε·h/δ² (h″).
  // With δ = 3e-4 both sources stay below ~1e-6 for h″ and ~1e-8 for h′ (measured max
  // ≈ 9e-7 and 8e-9); the tolerances below leave a factor ~5–10 of margin.
  const double delta = 3e-4, tol_fd1 = 1e-7, tol_fd2 = 5e-6;
  for (int i = 0; i < 1500; ++i) {
    const double th = -kPi + kTwoPi * (i + 0.37) / 1500.0;
    const CamPoint p = cam.evaluate(th);
    ASSERT_GT(p.rho, 0.0);
    min_rho = std::min(min_rho, p.rho);
    max_rho = std::max(max_rho, std::fabs(p.X_C + p.d2X_dtheta2 - p.rho));
    for (const auto& [w, wd] : {std::pair{11.0, 0.0}, std::pair{31.4, -50.0}, std::pair{-2.0, 7.0}}) {
      const CamMotion a = cam.motion(th, w, wd), b = cam.motion_paper(th, w, wd);
      const double scale_d = std::fabs(w) * p.r;
      const double scale_dd = (w * w + std::fabs(wd)) * p.r;
      max_form = std::max({max_form, std::fabs(a.X - b.X) / p.r,
                           std::fabs(a.Xdot - b.Xdot) / scale_d,
                           std::fabs(a.Xddot - b.Xddot) / scale_dd});
    }
    const FD fd = central5(cam, th, delta);
    max_fd1 = std::max(max_fd1, std::fabs(fd.d1 - p.dX_dtheta));
    max_fd2 = std::max(max_fd2, std::fabs(fd.d2 - p.d2X_dtheta2));
  }
  std::printf("paper cam: motion vs motion_paper max rel %.3g; FD(δ=%g) max |Δh′| %.3g, "
              "|Δh″| %.3g; max |h+h″−ρ| %.3g; sampled min ρ %.6f\n",
              max_form, delta, max_fd1, max_fd2, max_rho, min_rho);
  EXPECT_LT(max_form, 1e-9);
  EXPECT_LT(max_fd1, tol_fd1);
  EXPECT_LT(max_fd2, tol_fd2);
  EXPECT_LT(max_rho, 1e-12);
  EXPECT_GE(min_rho, cam.min_radius_of_curvature() - 1e-12);
}

TEST(CamPaper, GlobalMaximumAgainstBruteForceScan) {
  const Cam cam{CamSpec{}};
  constexpr int kScan = 20000;
  std::vector<double> px(kScan), py(kScan);
  for (int k = 0; k < kScan; ++k) {
    const auto q = cam.profile_point(kTwoPi * k / kScan);
    px[k] = q[0];
    py[k] = q[1];
  }
  auto scan_max = [&](double th) {
    const double c = std::cos(th), s = std::sin(th);
    double m = -1e300;
    for (int k = 0; k < kScan; ++k) m = std::max(m, px[k] * c - py[k] * s);
    return m;
  };
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> U(-50.0, 50.0);
  double worst_below = 0, worst_above = 0;
  std::vector<double> thetas;
  for (int i = 0; i < 500; ++i) thetas.push_back(U(rng));
  // Large jumps (the tracking hint must not be trusted blindly).
  for (double th : {0.0, 3.0, -100.0, 1e3, 0.001, -0.001, kPi, -kPi, 1e-300, 7.5}) thetas.push_back(th);
  for (double th : thetas) {
    const CamPoint p = cam.evaluate(th);
    const double m = scan_max(th);
    // Scan max ≤ true max ≤ scan max + ρ_max·(Δα)²/8-ish; X_C must not be below the scan.
    EXPECT_GE(p.X_C, m - 1e-12) << "theta = " << th;
    EXPECT_LE(p.X_C, m + 1e-6) << "theta = " << th;
    worst_below = std::max(worst_below, m - p.X_C);
    worst_above = std::max(worst_above, p.X_C - m);
    // The contact point itself lies on the profile: its X is attained.
    const Cam fresh{CamSpec{}};  // no history
    EXPECT_NEAR(fresh.evaluate(th).X_C, p.X_C, 1e-14 * 3);
  }
  std::printf("global max check: max(scan − X_C) = %.3g, max(X_C − scan) = %.3g\n", worst_below,
              worst_above);
}

TEST(CamPaper, CopiesAreIndependent) {
  const Cam a{CamSpec{}};
  a.evaluate(1.0);
  Cam b = a;
  b.evaluate(-2.0);
  Cam c = std::move(b);
  EXPECT_DOUBLE_EQ(a.evaluate(0.5).X_C, c.evaluate(0.5).X_C);
}

// ---- lift-table cam --------------------------------------------------------------------
TEST(CamLift, KnotsAndCurvature) {
  const CamSpec s = lift_spec();
  const Cam cam(s);
  for (std::size_t i = 0; i < s.lift.size(); ++i) {
    const double th = s.lift_angles_deg[i] * kPi / 180.0;
    EXPECT_NEAR(cam.evaluate(th).X_C, s.base_radius + s.lift[i], 1e-15) << i;
    EXPECT_NEAR(cam.evaluate(th + 3 * kTwoPi).X_C, s.base_radius + s.lift[i], 1e-13) << i;
  }
  double max_rho = 0, max_form = 0, max_fd1 = 0;
  for (int i = 0; i < 1000; ++i) {
    const double th = kTwoPi * (i + 0.5) / 1000.0;
    const CamPoint p = cam.evaluate(th);
    EXPECT_GT(p.rho, 0.0);
    max_rho = std::max(max_rho, std::fabs(p.X_C + p.d2X_dtheta2 - p.rho));
    // contact point (h, −h′) in the fixed frame
    EXPECT_NEAR(p.r, std::hypot(p.X_C, p.dX_dtheta), 1e-14);
    EXPECT_NEAR(p.beta, std::atan2(-p.dX_dtheta, p.X_C), 1e-14);
    const CamMotion a = cam.motion(th, 9.0, -13.0), b = cam.motion_paper(th, 9.0, -13.0);
    max_form = std::max({max_form, std::fabs(a.Xdot - b.Xdot) / 30.0,
                         std::fabs(a.Xddot - b.Xddot) / 300.0});
    max_fd1 = std::max(max_fd1, std::fabs(central5(cam, th, 1e-3).d1 - p.dX_dtheta));
    // The envelope point is on the rotated profile and is its maximum in X.
    const auto q = cam.profile_point(th);
    EXPECT_NEAR(q[0] * std::cos(th) - q[1] * std::sin(th), p.X_C, 1e-14);
  }
  std::printf("lift cam: min rho %.6f lift %.6f; |h+h″−ρ| %.3g, forms %.3g, FD h′ %.3g\n",
              cam.min_radius_of_curvature(), cam.lift(), max_rho, max_form, max_fd1);
  EXPECT_LT(max_rho, 1e-14);
  EXPECT_LT(max_form, 1e-12);
  EXPECT_LT(max_fd1, 1e-6);
  EXPECT_NEAR(cam.lift(), 0.8, 0.05);
}

// ---- validation ------------------------------------------------------------------------
namespace {
struct BadCam {
  const char* name;
  CamSpec spec;
  std::string key, value, rule;
};

CamSpec points(std::vector<double> ang, std::vector<double> rad) {
  CamSpec s;
  s.angles_deg = std::move(ang);
  s.radii = std::move(rad);
  return s;
}
CamSpec lift_with(std::vector<double> L, double rb = 2.0) {
  CamSpec s = lift_spec();
  s.lift = std::move(L);
  s.base_radius = rb;
  return s;
}
/// A 180-entry lift table L = 0.5(1 − cos θ)·0.3 over one turn whose angles were given in
/// radians (θ_i = 2π i/180) instead of degrees.
CamSpec lift_in_radians() {
  CamSpec s = lift_with({0, 0.1, 0.5, 0.7, 0.3, 0.05});
  s.lift_angles_deg.clear();
  s.lift.clear();
  for (int i = 0; i < 180; ++i) {
    const double th = 2 * kPi * i / 180.0;
    s.lift_angles_deg.push_back(th);
    s.lift.push_back(std::stod(std::to_string(0.15 * (1 - std::cos(th)))));
  }
  return s;
}

}  // namespace

TEST(CamValidation, MalformedSpecsGiveExactMessages) {
  const double nan = std::nan(""), inf = HUGE_VAL;
  const std::vector<double> A8{0, 45, 90, 135, 180, 225, 270, 315};
  const std::vector<BadCam> cases = {
      {"too few knots", points({0, 120, 240}, {2, 2, 2}), "cam.angles_deg", "[0, 120, 240]",
       "a periodic cubic spline needs at least 4 knots (got 3)"},
      {"count mismatch", points(A8, {2, 2, 2, 2, 2, 2, 2}), "cam.radii",
       "[2, 2, 2, 2, 2, 2, 2]", "must have as many entries as cam.angles_deg (8), got 7"},
      {"duplicate angle", points({0, 45, 90, 90, 180}, {2, 2, 2, 2, 2}), "cam.angles_deg",
       "[0, 45, 90, 90, 180]",
       "angles must be strictly increasing (entry 3 = 90 does not exceed entry 2 = 90)"},
      {"span 360", points({0, 90, 180, 270, 360}, {2, 2, 2, 2, 2}), "cam.angles_deg",
       "[0, 90, 180, 270, 360]", "angles must span less than 360° (last − first = 360°)"},
      {"zero radius", points(A8, {2, 2, 2, 0, 2, 2, 2, 2}), "cam.radii",
       "[2, 2, 2, 0, 2, 2, 2, 2]", "every radius must be > 0 (entry 3 = 0)"},
      {"nan radius", points(A8, {2, 2, nan, 2, 2, 2, 2, 2}), "cam.radii",
       "[2, 2, nan, 2, 2, 2, 2, 2]", "every radius must be finite (no nan/inf)"},
      {"inf angle", points({0, 45, inf, 135}, {2, 2, 2, 2}), "cam.angles_deg",
       "[0, 45, inf, 135]", "every angle must be finite (no nan/inf)"},
      {"self-intersecting", points(A8, {1, 5, 1, 5, 1, 5, 1, 5}), "cam.radii",
       "[1, 5, 1, 5, 1, 5, 1, 5]",
       "profile is self-intersecting or does not enclose the cam centre: its polar angle is "
       "not monotone (it turns back near polar angle 49.5°)"},
      {"non-convex dent", points(A8, {2, 2, 2, 1.0, 2, 2, 2, 2}), "cam.radii",
       "[2, 2, 2, 1, 2, 2, 2, 2]",
       "profile is not convex: radius of curvature ρ ≤ 0 at cam angles 199.3°..250.7° (the cam "
       "angle θ at which that profile point would face the follower; profile polar angles "
       "103.9°..166.1°) — a flat-faced follower cannot follow a concave flank"},
      {"circle R = 0", circle_spec(0.0, 0.0), "cam.radius", "0", "must be > 0"},
      {"circle e < 0", circle_spec(2.0, -0.1), "cam.eccentricity", "-0.1", "must be ≥ 0"},
      {"circle e = R", circle_spec(2.0, 2.0), "cam.eccentricity", "2",
       "must be < cam.radius (2) so that the cam encloses its centre"},
      {"lift base radius", lift_with({0, 0.1, 0.5, 0.8, 0.4, 0.05}, -1.0), "cam.base_radius", "-1",
       "must be > 0"},
      {"lift r_b + L <= 0", lift_with({0, 0.1, -2.5, 0.8, 0.4, 0.05}), "cam.lift",
       "[0, 0.1, -2.5, 0.8, 0.4, 0.05]", "r_b + L must be > 0 (entry 2: 2 + -2.5)"},
      {"lift count", lift_with({0, 0.1, 0.5}), "cam.lift", "[0, 0.1, 0.5]",
       "must have as many entries as cam.lift_angles_deg (6), got 3"},
      {"lift non-convex", lift_with({0, 0, 3, 0, 0, 0}), "cam.lift", "[0, 0, 3, 0, 0, 0]",
       "profile is not convex: radius of curvature ρ = r_b + L + L″ ≤ 0 at cam angles "
       "357.1°..1.1°, 96.1°..143.9°, 238.8°..242.9° — a flat-faced follower cannot follow a "
       "concave flank; the lift changes too fast for the base circle: a larger "
       "cam.base_radius or a smoother lift table"},
      // Angles in radians (issue 17): a short message with a hint about the unit, and a
      // long table is not dumped value by value.
      {"lift angles in radians", lift_in_radians(), "cam.lift",
       "[0, 9.1e-05, 0.000365, 0.000822, …, 0.000365, 9.1e-05] (180 values)",
       "profile is not convex: radius of curvature ρ = r_b + L + L″ ≤ 0 at cam angles "
       "1.6°..4.7° — a flat-faced follower cannot follow a concave flank; "
       "cam.lift_angles_deg spans only 6.25°: are the angles in radians? "
       "They must be degrees"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    try {
      const Cam cam(c.spec);
      ADD_FAILURE() << "no exception";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.file(), "<cam>");
      EXPECT_EQ(e.line(), 0);
      EXPECT_EQ(e.key(), c.key);
      EXPECT_EQ(e.value(), c.value);
      EXPECT_EQ(e.rule(), c.rule);
      // scene.hpp: what() is "FILE: key 'KEY' = VALUE: RULE" when the line is unknown.
      EXPECT_EQ(std::string(e.what()), "<cam>: key '" + c.key + "' = " + c.value + ": " + c.rule);
    }
  }
}

TEST(CamValidation, NonConvexMessageNamesCamAngles) {
  try {
    const Cam cam(points({0, 45, 90, 135, 180, 225, 270, 315}, {2, 2, 2, 1.0, 2, 2, 2, 2}));
    FAIL() << "no exception";
  } catch (const SceneError& e) {
    const std::string r = e.rule();
    EXPECT_EQ(r.rfind("profile is not convex: radius of curvature ρ ≤ 0 at cam angles ", 0), 0u)
        << r;
    EXPECT_NE(r.find("°.."), std::string::npos) << r;
    // A dent centred on polar angle 135° faces the follower near θ = −135° = 225°.
    EXPECT_NE(r.find("199.3°..250.7°"), std::string::npos) << r;
  }
}

TEST(CamValidation, DriveTable) {
  CamSpec s;
  s.speed_table_t = {0.5, 1.0};
  s.speed_table_rev_s = {1, 2};
  try {
    const CamDrive d(s);
    FAIL() << "no exception";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.speed_table_t");
    EXPECT_EQ(e.value(), "[0.5, 1]");
    EXPECT_EQ(e.rule(), "the first time must be 0");
  }
  s.speed_table_t = {0.0, 1.0, 1.0};
  s.speed_table_rev_s = {1, 2, 3};
  EXPECT_THROW(CamDrive{s}, SceneError);
  s.speed_table_t = {0.0, 1.0};
  s.speed_table_rev_s = {1};
  EXPECT_THROW(CamDrive{s}, SceneError);
}

// ---- drive ------------------------------------------------------------------------------
TEST(CamDrive, ConstantSpeed) {
  CamSpec s;
  s.speed_rev_s = 1.75;
  s.theta0_deg = 30.0;
  const CamDrive d(s);
  EXPECT_TRUE(d.constant_speed());
  for (double t : {0.0, 0.1, 0.37, 2.0, 100.0}) {
    EXPECT_NEAR(d.theta(t), kPi / 6 + kTwoPi * 1.75 * t, 1e-12 * (1 + t));
    EXPECT_DOUBLE_EQ(d.omega(t), kTwoPi * 1.75);
    EXPECT_EQ(d.omega_dot(t), 0.0);
  }
}

TEST(CamDrive, SpeedTableRamp) {
  CamSpec s;
  s.speed_table_t = {0.0, 1.0};
  s.speed_table_rev_s = {0.0, 10.0};
  const CamDrive d(s);
  EXPECT_FALSE(d.constant_speed());
  for (double t : {0.0, 0.25, 0.5, 0.999, 1.0, 1.5, 3.0}) {
    const double exact = t <= 1.0 ? 0.5 * kTwoPi * 10.0 * t * t
                                  : kTwoPi * 5.0 + kTwoPi * 10.0 * (t - 1.0);
    EXPECT_NEAR(d.theta(t), exact, 1e-12 * (1 + exact)) << t;
    EXPECT_NEAR(d.omega(t), kTwoPi * 10.0 * std::min(t, 1.0), 1e-12) << t;
    EXPECT_DOUBLE_EQ(d.omega_dot(t), t < 1.0 ? kTwoPi * 10.0 : 0.0) << t;  // right-continuous
  }
}

TEST(CamDrive, SpeedTableMatchesQuadrature) {
  CamSpec s;
  s.theta0_deg = -45.0;
  s.speed_table_t = {0.0, 0.2, 0.5, 0.6, 1.3};
  s.speed_table_rev_s = {1.0, 3.0, -2.0, 0.5, 4.0};
  const CamDrive d(s);
  // Simpson's rule with many panels on ω(t) (exact on each linear piece; knots are panel
  // boundaries since all knots are multiples of 0.1 and the panel width is 1e-4).
  double theta = -kPi / 4;
  const double dt = 1e-4;
  for (int i = 0; i < 20000; ++i) {
    const double t0 = i * dt, t1 = t0 + dt;
    theta += dt / 6 * (d.omega(t0) + 4 * d.omega(0.5 * (t0 + t1)) + d.omega(t1));
    if ((i + 1) % 1000 == 0) {
      EXPECT_NEAR(d.theta(t1), theta, 1e-9) << t1;
    }
    // ω̇ by central difference inside a segment
    const double tm = t0 + 0.5 * dt;
    if (std::fabs(tm - 0.2) > 1e-3 && std::fabs(tm - 0.5) > 1e-3 && std::fabs(tm - 0.6) > 1e-3 &&
        std::fabs(tm - 1.3) > 1e-3) {
      EXPECT_NEAR(d.omega_dot(tm), (d.omega(t1) - d.omega(t0)) / dt, 1e-6) << tm;
    }
  }
}
