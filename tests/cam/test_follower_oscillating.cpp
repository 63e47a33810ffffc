// camdyn — oscillating followers (finger followers, rockers) against independent geometry:
//   flat pad on an eccentric circle cam — ψ by bisection on the tangency of the pad line
//     (distance of the cam circle's centre from the pad line = R), derivatives by
//     high-order finite differences of that brute-force ψ;
//   roller on a circle cam — the roller centre from the intersection of two circles
//     (pivot, arm) and (cam-circle centre, R + r_r), closed form;
//   law cams — the synthesised profile sampled densely, the follower placed on it again by
//     bisection (roller: distance of the roller centre from the profile = r_r; pad: the
//     profile's largest signed distance from the pad line = 0) returns the law;
//   the moment arm from power balance: N a ψ̇ = N (Q × n̂) ω (the cam's torque).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>
#include <camdyn/scene.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;

double bisect(const std::function<double(double)>& f, double lo, double hi) {
  double flo = f(lo);
  EXPECT_LT(flo * f(hi), 0.0) << "no bracket";
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi), fm = f(mid);
    if ((fm < 0) == (flo < 0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

// 6th-order central differences of f at x (first, second derivative).
double d1(const std::function<double(double)>& f, double x, double h) {
  return (45 * (f(x + h) - f(x - h)) - 9 * (f(x + 2 * h) - f(x - 2 * h)) + (f(x + 3 * h) - f(x - 3 * h))) / (60 * h);
}
double d2(const std::function<double(double)>& f, double x, double h) {
  return (270 * (f(x + h) + f(x - h)) - 27 * (f(x + 2 * h) + f(x - 2 * h)) + 2 * (f(x + 3 * h) + f(x - 3 * h)) -
          490 * f(x)) /
         (180 * h * h);
}

CamSpec circle_spec(FollowerFace face) {
  CamSpec c;
  c.profile = CamProfileKind::Circle;
  c.radius = 20.0;
  c.eccentricity = 5.0;
  c.follower_motion = FollowerMotion::Oscillating;
  c.follower_face = face;
  c.valve_arm = 45.0;
  return c;
}
}  // namespace

TEST(OscillatingFollower, FlatPadOnCircleCamMatchesBruteForceTangency) {
  CamSpec c = circle_spec(FollowerFace::Flat);
  c.pivot_x = 40.0;  // finger above the cam's +X side, pad 4 mm off the pivot line
  c.pivot_y = 45.0;
  c.pad_offset = 4.0;
  const Cam cam(c);
  const double R = c.radius, e = c.eccentricity, f = c.pad_offset, px = c.pivot_x, py = c.pivot_y;
  // Brute force: the arm angle α at which the pad line {Z: n(α)·(Z − P) = f} lies at
  // distance R from the cam circle's centre K, with K on its clockwise side and ahead of
  // the pivot along the arm. Bisection in α over the half-turn facing K.
  auto alpha = [&](double th) {
    const double kx = e * std::cos(th), ky = e * std::sin(th);
    const double beta = std::atan2(ky - py, kx - px);
    auto sd = [&](double a) {  // signed distance of K from the pad line + R
      return -std::sin(a) * (kx - px) + std::cos(a) * (ky - py) - f + R;
    };
    return bisect(sd, beta - kPi / 2 + 1e-9, beta + kPi / 2 - 1e-9);
  };
  const double a0 = alpha(0.0);
  const CamPoint p0 = cam.evaluate(0.0);
  double worst_psi = 0, worst_d1 = 0, worst_d2 = 0, worst_arm = 0;
  for (int i = 0; i < 72; ++i) {
    const double th = 2 * kPi * i / 72 + 0.013;
    const CamPoint p = cam.evaluate(th);
    worst_psi = std::max(worst_psi, std::fabs((p.psi - p0.psi) - (alpha(th) - a0)));
    worst_d1 = std::max(worst_d1, std::fabs(p.dpsi_dtheta - d1(alpha, th, 2e-3)));
    worst_d2 = std::max(worst_d2, std::fabs(p.d2psi_dtheta2 - d2(alpha, th, 2e-3)));
    EXPECT_NEAR(p.X_C - p0.X_C, c.valve_arm * (p.psi - p0.psi), 1e-12);
    // Contact point and normal from the brute-force pad: Q = K + R n, n̂ = n (cam below).
    const double a = alpha(th), nx = -std::sin(a), ny = std::cos(a);
    const double qx = e * std::cos(th) + R * nx, qy = e * std::sin(th) + R * ny;
    const double arm = (qx - px) * std::cos(a) + (qy - py) * std::sin(a);
    worst_arm = std::max(worst_arm, std::fabs(p.moment_arm - arm));
    EXPECT_NEAR(p.r, std::hypot(qx, qy), 1e-9);
    // Power balance: the normal force's moment about the pivot times ψ′ equals its torque
    // about the cam centre: a ψ′ = Q × n̂.
    EXPECT_NEAR(p.moment_arm * p.dpsi_dtheta, qx * ny - qy * nx, 1e-8);
    EXPECT_NEAR(p.normal_force_ratio, c.valve_arm / arm, 1e-9);
  }
  EXPECT_LT(worst_psi, 1e-12);
  EXPECT_LT(worst_d1, 1e-9);
  EXPECT_LT(worst_d2, 1e-7);
  EXPECT_LT(worst_arm, 1e-10);
  // X = valve_arm·ψ measured from the lowest position: min 0, lift = ℓ_v (max α − min α).
  double amin = 1e9, amax = -1e9;
  for (int i = 0; i < 3600; ++i) {
    const double a = alpha(2 * kPi * i / 3600);
    amin = std::min(amin, a);
    amax = std::max(amax, a);
  }
  EXPECT_NEAR(cam.lift(), c.valve_arm * (amax - amin), 1e-6);
  EXPECT_NEAR(cam.min_radius_of_curvature(), R, 1e-12);
}

TEST(OscillatingFollower, RollerOnCircleCamMatchesTriangleClosedForm) {
  CamSpec c = circle_spec(FollowerFace::Roller);
  c.pivot_x = 45.0;
  c.pivot_y = 35.0;
  c.arm_length = 38.0;
  c.roller_radius = 7.0;
  const Cam cam(c);
  const double R = c.radius, e = c.eccentricity, l = c.arm_length, A = R + c.roller_radius;
  const double px = c.pivot_x, py = c.pivot_y;
  // Triangle pivot P, cam-circle centre K, roller centre C: |C − P| = ℓ, |C − K| = R + r_r.
  // Of the two intersections, the one where the cam's push turns the arm counter-clockwise
  // about P: (C − P) × (C − K) > 0.
  auto centre = [&](double th, double* cx, double* cy) {
    const double kx = e * std::cos(th), ky = e * std::sin(th);
    const double dx = kx - px, dy = ky - py, d = std::hypot(dx, dy);
    const double a = (d * d + l * l - A * A) / (2 * d), h = std::sqrt(l * l - a * a);
    const double mx = px + a * dx / d, my = py + a * dy / d;
    for (int s : {1, -1}) {
      *cx = mx - s * h * dy / d;
      *cy = my + s * h * dx / d;
      if ((*cx - px) * (*cy - ky) - (*cy - py) * (*cx - kx) > 0) return;
    }
  };
  auto alpha = [&](double th) {
    double cx, cy;
    centre(th, &cx, &cy);
    return std::atan2(cy - py, cx - px);
  };
  const double a0 = alpha(0.0);
  const CamPoint p0 = cam.evaluate(0.0);
  for (int i = 0; i < 72; ++i) {
    const double th = 2 * kPi * i / 72 + 0.021;
    const CamPoint p = cam.evaluate(th);
    EXPECT_NEAR(p.psi - p0.psi, alpha(th) - a0, 1e-12) << th;
    EXPECT_NEAR(p.dpsi_dtheta, d1(alpha, th, 2e-3), 1e-9) << th;
    EXPECT_NEAR(p.d2psi_dtheta2, d2(alpha, th, 2e-3), 1e-7) << th;
    EXPECT_NEAR(p.d3X_dtheta3 / c.valve_arm, (d2(alpha, th + 1e-3, 2e-3) - d2(alpha, th - 1e-3, 2e-3)) / 2e-3, 1e-5);
    double cx, cy;
    centre(th, &cx, &cy);
    const double kx = e * std::cos(th), ky = e * std::sin(th);
    const double nx = (cx - kx) / A, ny = (cy - ky) / A, qx = kx + R * nx, qy = ky + R * ny;
    const double arm = (cx - px) * ny - (cy - py) * nx;  // ℓ cos φ
    EXPECT_NEAR(p.moment_arm, arm, 1e-10);
    EXPECT_NEAR(p.moment_arm * p.dpsi_dtheta, qx * ny - qy * nx, 1e-8);
    // Pressure angle: between the roller centre's direction of motion and the normal.
    const double ux = (cx - px) / l, uy = (cy - py) / l;
    EXPECT_NEAR(std::cos(p.pressure_angle), -uy * nx + ux * ny, 1e-10);
  }
}

namespace {
// Dense cam-frame profile of a Cam.
std::vector<std::array<double, 2>> profile(const Cam& cam, int n) {
  std::vector<std::array<double, 2>> v(n);
  for (int i = 0; i < n; ++i) v[i] = cam.profile_point(2 * kPi * i / n);
  return v;
}
CamSpec law_spec(FollowerFace face) {
  CamSpec c;
  c.profile = CamProfileKind::Law;
  c.law = "dwell 100; cycloidal 70 9; dwell 10; poly345 70 -9; dwell 110";  // valve lift [mm]
  c.base_radius = 16.0;
  c.follower_motion = FollowerMotion::Oscillating;
  c.follower_face = face;
  c.valve_arm = 45.0;
  return c;
}
}  // namespace

TEST(OscillatingFollower, LawRollerProfileRoundTrip) {
  CamSpec c = law_spec(FollowerFace::Roller);
  c.pivot_x = 40.0;  // roller finger follower: pivot above, valve end beyond the roller
  c.pivot_y = 18.0;
  c.arm_length = 30.0;
  c.roller_radius = 8.0;
  const Cam cam(c);
  const auto prof = profile(cam, 40000);
  const MotionLaw& law = *cam.law();
  const CamPoint b = cam.evaluate(0.0);  // base circle
  EXPECT_NEAR(b.X_C, 0.0, 1e-12);
  EXPECT_NEAR(std::hypot(prof[0][0], prof[0][1]), c.base_radius, 1e-9);
  auto dist_to_profile = [&](double x, double y) {
    double m = 1e300;
    for (const auto& q : prof) m = std::min(m, std::hypot(q[0] - x, q[1] - y));
    return m;
  };
  const double px = c.pivot_x, py = c.pivot_y, l = c.arm_length;
  for (double deg : {0.0, 120.0, 135.0, 170.0, 205.0, 230.0, 300.0}) {
    const double th = deg * kPi / 180;
    const CamPoint p = cam.evaluate(th);
    // Place the roller on the sampled profile: the arm angle at which the roller centre
    // (turned into the cam frame) is r_r from the profile, near the implementation's.
    auto gap = [&](double a) {
      const double cx = px + l * std::cos(a), cy = py + l * std::sin(a);
      const double xc = cx * std::cos(th) + cy * std::sin(th), yc = -cx * std::sin(th) + cy * std::cos(th);
      return dist_to_profile(xc, yc) - c.roller_radius;
    };
    // α from ψ: α = α_b + ψ (lifting is counter-clockwise for this layout); α_b solved
    // independently from the base-circle triangle.
    const double d = std::hypot(px, py), Ab = c.base_radius + c.roller_radius;
    const double ga = std::acos((l * l + d * d - Ab * Ab) / (2 * l * d));
    const double alpha_b = std::atan2(-py, -px) + ga;
    const double a_law = alpha_b + law.eval(th).L / c.valve_arm;
    const double a_bf = bisect(gap, a_law - 0.05, a_law + 0.05);
    EXPECT_NEAR(a_bf, a_law, 2e-6) << deg;
    EXPECT_NEAR(p.X_C, law.eval(th).L, 1e-12) << deg;
  }
}

TEST(OscillatingFollower, LawFlatPadProfileRoundTrip) {
  CamSpec c = law_spec(FollowerFace::Flat);
  c.law = "dwell 60; cycloidal 110 9; dwell 10; poly345 110 -9; dwell 70";  // gentler: a flat pad needs ρ > 0
  c.base_radius = 30.0;
  c.pivot_x = 40.0;
  c.pivot_y = 45.0;
  c.pad_offset = 4.0;
  const Cam cam(c);
  const auto prof = profile(cam, 40000);
  const MotionLaw& law = *cam.law();
  const double px = c.pivot_x, py = c.pivot_y, f = c.pad_offset;
  const double d = std::hypot(px, py);
  const double alpha_b = std::atan2(-py, -px) - std::asin((f - c.base_radius) / d);
  for (double deg : {0.0, 120.0, 135.0, 170.0, 205.0, 230.0, 300.0}) {
    const double th = deg * kPi / 180;
    // The pad at arm angle a: the profile's largest signed distance from the pad line
    // (cam frame) is zero when the pad touches.
    auto touch = [&](double a) {
      const double nx = -std::sin(a - th), ny = std::cos(a - th);
      const double pxc = px * std::cos(th) + py * std::sin(th), pyc = -px * std::sin(th) + py * std::cos(th);
      double m = -1e300;
      for (const auto& q : prof) m = std::max(m, nx * (q[0] - pxc) + ny * (q[1] - pyc) - f);
      return m;
    };
    const double a_law = alpha_b + law.eval(th).L / c.valve_arm;
    const double a_bf = bisect(touch, a_law - 0.05, a_law + 0.05);
    EXPECT_NEAR(a_bf, a_law, 2e-6) << deg;
  }
}

TEST(OscillatingFollower, BadInputNamesKeyAndRule) {
  auto msg = [](CamSpec c) {
    try {
      Cam cam(c);
    } catch (const SceneError& e) {
      return e.key() + " | " + e.rule();
    }
    return std::string("no error");
  };
  CamSpec c = circle_spec(FollowerFace::Roller);
  c.pivot_x = 45.0;
  c.pivot_y = 35.0;
  c.arm_length = 5.0;
  c.roller_radius = 7.0;
  EXPECT_NE(msg(c).find("cam.arm_length | the roller cannot reach the cam"), std::string::npos) << msg(c);
  c.arm_length = 38.0;
  c.valve_arm = 0.0;
  EXPECT_NE(msg(c).find("cam.valve_arm | must be finite and > 0"), std::string::npos) << msg(c);
  c.valve_arm = 45.0;
  c.follower_face = FollowerFace::KnifeEdge;
  EXPECT_NE(msg(c).find("cam.follower_face | an oscillating follower has a flat pad or a roller"), std::string::npos);
  c.follower_face = FollowerFace::Roller;
  c.profile = CamProfileKind::Points;
  EXPECT_NE(msg(c).find("cam.profile | an oscillating follower needs"), std::string::npos);
  // A law the roller cannot follow: a tiny base circle under a big roller → undercut.
  CamSpec l = law_spec(FollowerFace::Roller);
  l.base_radius = 6.0;
  l.pivot_x = 30.0;
  l.pivot_y = 10.0;
  l.arm_length = 22.0;
  l.roller_radius = 8.0;
  l.law = "dwell 100; cycloidal 30 12; poly345 30 -12; dwell 200";
  const std::string m = msg(l);
  EXPECT_TRUE(m.find("undercut") != std::string::npos || m.find("moment arm") != std::string::npos) << m;
  EXPECT_NE(m.find("cam angles"), std::string::npos) << m;
}

TEST(OscillatingFollower, ArcCamRollerIsSmoothAcrossTheTangencyPoints) {
  // Base, flank and nose arcs are tangent: the pitch curve is C1, so ψ and ψ′ are
  // continuous at the arc switches (ψ″ jumps); inside each arc ψ′ and ψ″ match
  // differences of ψ itself.
  CamSpec c;
  c.profile = CamProfileKind::Arc;
  c.base_radius = 16.0;
  c.nose_radius = 6.0;
  c.nose_distance = 14.0;
  c.flank_radius = 40.0;
  c.follower_motion = FollowerMotion::Oscillating;
  c.follower_face = FollowerFace::Roller;
  c.pivot_x = 40.0;
  c.pivot_y = 18.0;
  c.arm_length = 30.0;
  c.roller_radius = 8.0;
  c.valve_arm = 45.0;
  const Cam cam(c);
  ASSERT_EQ(cam.breakpoints().size(), 4u);
  const double e = 1e-7;
  for (double b : cam.breakpoints()) {
    const CamPoint lo = cam.evaluate(b - e), hi = cam.evaluate(b + e);
    EXPECT_NEAR(lo.psi + e * lo.dpsi_dtheta, hi.psi - e * hi.dpsi_dtheta, 1e-12) << b;  // ψ at b from both sides
    EXPECT_NEAR(lo.dpsi_dtheta, hi.dpsi_dtheta, 1e-5) << b;
    EXPECT_NE(lo.rho, hi.rho) << b;  // a different arc on each side
  }
  auto psi = [&](double th) { return cam.evaluate(th).psi; };
  for (int i = 0; i < 90; ++i) {
    const double th = 2 * kPi * i / 90 + 0.007;
    bool near_break = false;
    for (double b : cam.breakpoints()) near_break |= std::fabs(std::remainder(th - b, 2 * kPi)) < 0.02;
    if (near_break) continue;
    const CamPoint p = cam.evaluate(th);
    EXPECT_NEAR(p.dpsi_dtheta, d1(psi, th, 2e-3), 1e-9) << th;
    EXPECT_NEAR(p.d2psi_dtheta2, d2(psi, th, 2e-3), 1e-7) << th;
  }
  EXPECT_NEAR(cam.min_radius_of_curvature(), c.nose_radius, 1e-12);
}
