// camdyn — follower geometry (issue 24): knife-edge and roller followers with offset on an
// eccentric circle cam against the closed form, pressure angle against the kinematic
// identity tan φ = (s′ + ε)/s, cam torque against the power balance, arc cams (tangency,
// jump speed against the closed form of the arcs), Hertz line contact against textbook
// numbers, and undercut / convexity checks naming the cam angles.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>
#include <camdyn/designer.hpp>
#include <camdyn/hertz.hpp>
#include <camdyn/scene.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;

CamSpec circle(double R, double e, FollowerFace face, double eps, double rr) {
  CamSpec c;
  c.profile = CamProfileKind::Circle;
  c.radius = R;
  c.eccentricity = e;
  c.follower_face = face;
  c.follower_offset = eps;
  c.roller_radius = rr;
  return c;
}
CamSpec law_roller(const char* law, double rb, double rr, double eps) {
  CamSpec c;
  c.profile = CamProfileKind::Law;
  c.law = law;
  c.base_radius = rb;
  c.follower_face = FollowerFace::Roller;
  c.roller_radius = rr;
  c.follower_offset = eps;
  return c;
}
}  // namespace

TEST(FollowerGeometry, KnifeEdgeAndRollerWithOffsetOnCircleCam) {
  const double R = 2.0, e = 0.5, eps = 0.3;
  for (double rr : {0.0, 0.4}) {
    SCOPED_TRACE(rr);
    const Cam cam(circle(R, e, rr > 0 ? FollowerFace::Roller : FollowerFace::KnifeEdge, eps, rr));
    // Closed form: the roller centre (knife edge) on the axis Y = ε at distance R + R_r
    // from the cam centre (e cos θ, e sin θ).
    auto s = [&](double th) {
      const double q = eps - e * std::sin(th);
      return e * std::cos(th) + std::sqrt((R + rr) * (R + rr) - q * q);
    };
    const double h = 1e-4;
    for (double th = 0.05; th < 2 * kPi; th += 0.29) {
      const CamPoint p = cam.evaluate(th);
      EXPECT_NEAR(p.X_C, s(th), 1e-13);
      const double s1 = (s(th + h) - s(th - h)) / (2 * h);
      const double s2 = (s(th + h) - 2 * s(th) + s(th - h)) / (h * h);
      const double g = 2e-3;  // third difference: a wider step (round-off ∝ 1/g³)
      const double s3 = (s(th + 2 * g) - 2 * s(th + g) + 2 * s(th - g) - s(th - 2 * g)) / (2 * g * g * g);
      EXPECT_NEAR(p.dX_dtheta, s1, 1e-7);
      EXPECT_NEAR(p.d2X_dtheta2, s2, 1e-6);
      EXPECT_NEAR(p.d3X_dtheta3, s3, 2e-5);
      // Pressure angle: the kinematic identity of a translating follower with offset.
      EXPECT_NEAR(std::tan(p.pressure_angle), (s1 + eps) / s(th), 1e-7);
      // The contact point lies on the cam circle and on the roller.
      const double cx = p.r * std::cos(p.beta), cy = p.r * std::sin(p.beta);
      EXPECT_NEAR(std::hypot(cx - e * std::cos(th), cy - e * std::sin(th)), R, 1e-12);
      EXPECT_NEAR(std::hypot(cx - s(th), cy - eps), rr, 1e-12);
      EXPECT_NEAR(p.rho, R, 1e-15);
    }
    double smin = INFINITY, smax = -INFINITY;
    for (int i = 0; i < 72000; ++i) {
      smin = std::min(smin, s(2 * kPi * i / 72000));
      smax = std::max(smax, s(2 * kPi * i / 72000));
    }
    EXPECT_NEAR(cam.lift(), smax - smin, 1e-6);  // the cam samples 7200 angles
  }
}

TEST(FollowerGeometry, TorqueFromContactGeometryEqualsPowerBalance) {
  // T = N (C × n̂), N = F / cos φ (moment of the normal force about the cam centre) against
  // T = F s′(θ) (power: T ω = F ṡ). Law + offset roller, circle + offset knife edge.
  const CamSpec law = law_roller("dwell 90; cycloidal 80 8; dwell 20; modsine 80 -8; dwell 90", 30, 8, 5);
  const CamSpec specs[] = {law, circle(2.0, 0.6, FollowerFace::KnifeEdge, -0.4, 0.0)};
  for (const CamSpec& sp : specs) {
    const Cam cam(sp);
    for (double th = 0.01; th < 2 * kPi; th += 0.07) {
      const CamPoint p = cam.evaluate(th);
      const double F = 1.0, N = F / std::cos(p.pressure_angle);
      const double cx = p.r * std::cos(p.beta), cy = p.r * std::sin(p.beta);
      const double T = N * (cx * std::sin(p.pressure_angle) - cy * std::cos(p.pressure_angle));
      EXPECT_NEAR(T, F * p.dX_dtheta, 1e-9 * (1 + std::fabs(T)));
    }
  }
}

TEST(FollowerGeometry, LawProfileNormalMatchesPressureAngle) {
  // The synthesised profile (cam frame) is traced by profile_point; its normal at the
  // contact, turned into the fixed frame, must make the pressure angle with the axis.
  const Cam cam(law_roller("dwell 60; poly345 100 10; dwell 40; poly345 100 -10; dwell 60", 25, 6, -4));
  for (double th = 1.1; th < 2.9; th += 0.13) {
    const auto a = cam.profile_point(th - 1e-6), b = cam.profile_point(th + 1e-6);
    const double tx = b[0] - a[0], ty = b[1] - a[1];
    const double ct = std::cos(th), st = std::sin(th);  // cam → fixed frame
    const double TX = tx * ct - ty * st, TY = tx * st + ty * ct;
    const double phi = cam.evaluate(th).pressure_angle;
    EXPECT_NEAR(TX * std::cos(phi) + TY * std::sin(phi), 0.0, 1e-6 * std::hypot(TX, TY));
  }
}

TEST(FollowerGeometry, UndercutAndConvexityNameCamAngles) {
  CamSpec c = law_roller("dwell 150; cycloidal 30 10; cycloidal 30 -10; dwell 150", 10, 9, 0);
  try {
    Cam cam(c);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.roller_radius");
    EXPECT_NE(e.rule().find("undercut"), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find("cam angles 1"), std::string::npos) << e.rule();  // around 180°
  }
  {  // 800 undercut runs (400 tiny lobes): six listed, the rest counted
    std::string law;
    for (int k = 0; k < 400; ++k) law += std::string(k ? "; " : "") + "cycloidal 0.45 1; cycloidal 0.45 -1";
    try {
      Cam cam(law_roller(law.c_str(), 20, 8, 0));
      FAIL();
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), "cam.roller_radius");
      EXPECT_NE(e.rule().find(" and 794 more"), std::string::npos) << e.rule().substr(0, 300);
      EXPECT_LT(e.rule().size(), 400u);
    }
  }
  c.follower_face = FollowerFace::Flat;
  c.roller_radius = 0;
  EXPECT_THROW(Cam{c}, SceneError);
  // A spline profile takes a flat face only.
  CamSpec p;
  p.follower_face = FollowerFace::Roller;
  p.roller_radius = 1;
  EXPECT_THROW(Cam{p}, SceneError);
}

namespace {
CamSpec arc_cam(FollowerFace face) {
  CamSpec c;
  c.profile = CamProfileKind::Arc;
  c.base_radius = 2.0;
  c.nose_radius = 0.6;
  c.nose_distance = 1.8;
  c.flank_radius = 5.0;
  c.follower_face = face;
  return c;
}
}  // namespace

TEST(ArcCam, TangentArcsAndBreakpoints) {
  for (FollowerFace f : {FollowerFace::Flat, FollowerFace::KnifeEdge}) {
    const Cam cam(arc_cam(f));
    ASSERT_EQ(cam.breakpoints().size(), 4u);
    EXPECT_NEAR(cam.lift(), 1.8 + 0.6 - 2.0, 1e-6);
    for (double b : cam.breakpoints()) {
      const CamPoint l = cam.evaluate(b - 1e-7), r = cam.evaluate(b + 1e-7);
      EXPECT_NEAR(l.X_C, r.X_C, 1e-6);
      EXPECT_NEAR(l.dX_dtheta, r.dX_dtheta, 1e-5);  // tangent arcs: C1
      EXPECT_GT(std::fabs(l.d2X_dtheta2 - r.d2X_dtheta2), 1e-3);  // curvature jumps
    }
  }
}

TEST(ArcCam, KnifeEdgeJumpSpeedMatchesClosedFormOfTheArcs) {
  // Knife edge on the axis (ε = 0): the follower sits where the ray at polar angle −θ (cam
  // frame) leaves the profile. Each arc (centre c, radius R) gives along the ray at angle ψ
  // r(ψ) = c·u + √(R² − (c × u)²), u = (cos ψ, sin ψ); the arcs' polar ranges come from the
  // tangency points. Jump speed ω² = min over θ with s″ < 0 of k(δ₀ + s − r_b)/(−m s″).
  const double Rb = 2.0, rn = 0.6, d = 1.8, Rf = 5.0;
  const double a = Rf - Rb, b = Rf - rn, fx = (d * d - b * b + a * a) / (2 * d), fy = std::sqrt(a * a - fx * fx);
  // Tangency points (upper half): base/flank on the ray from F=(fx,−fy) through O; flank/nose
  // on the ray from F through N.
  const double pb = std::atan2(Rb * fy / a, -Rb * fx / a);
  const double nx = d + rn * (d - fx) / b, ny = rn * fy / b;
  const double pn = std::atan2(ny, nx);
  // r(ψ) and r″(ψ) in closed form on the arc that holds polar angle ψ: a = c·u, b = c × u,
  // a′ = −b, b′ = a, S = √(R² − b²): r = a + S, r″ = −a − (a² − b²)/S − a² b²/S³
  // (s(θ) = r(−θ), s″(θ) = r″(−θ)).
  auto r_of = [&](double psi) {
    psi = std::remainder(psi, 2 * kPi);
    const double ux = std::cos(psi), uy = std::sin(psi);
    double cx, cy, R;
    if (std::fabs(psi) <= pn) { cx = d; cy = 0; R = rn; }
    else if (std::fabs(psi) <= pb) { cx = fx; cy = psi > 0 ? -fy : fy; R = Rf; }
    else { cx = 0; cy = 0; R = Rb; }
    const double A = cx * ux + cy * uy, B = cx * uy - cy * ux, S = std::sqrt(R * R - B * B);
    return std::array<double, 2>{A + S, -A - (A * A - B * B) / S - A * A * B * B / (S * S * S)};
  };
  const double m = 1.0, k = 500.0, delta0 = 1.0;
  double w2 = INFINITY;
  for (int i = 0; i < 72000; ++i) {
    const double th = 2 * kPi * i / 72000;
    const auto r = r_of(-th);
    const double s = r[0], s2 = r[1];
    if (s2 < 0) w2 = std::min(w2, k * (delta0 + s - Rb) / (-m * s2));
  }
  Scene sc;
  sc.cam = arc_cam(FollowerFace::KnifeEdge);
  sc.cam.theta0_deg = 180;  // start on the base circle
  sc.cam.speed_rev_s = 1.0;
  sc.follower.kind = FollowerKind::Rigid;
  sc.follower.mass = m;
  sc.spring.stiffness = k;
  sc.spring.precompression = delta0;
  const JumpResult j = jump_speed(sc);
  EXPECT_NEAR(j.jump_speed_rev_s, std::sqrt(w2) / (2 * kPi), 2e-4 * std::sqrt(w2) / (2 * kPi));
}

TEST(Hertz, LineContactAgainstTextbook) {
  // Steel on steel, E = 210 GPa, ν = 0.3 (units N, mm, MPa): E* = E/(2(1 − ν²)) =
  // 115384.6 MPa. A roller of radius 10 mm on a plane, 1000 N over 10 mm:
  // p₀ = √(P E*/(π R)) = √(100 · 115384.6 / (10π)) = 606.04 MPa, b = 2P/(π p₀) = 0.10505 mm.
  const double Es = contact_modulus(210e3, 0.3, 210e3, 0.3);
  EXPECT_NEAR(Es, 115384.615, 1e-3);
  const HertzLine p = hertz_line(1000.0, 10.0, 10.0, INFINITY, Es);
  EXPECT_NEAR(p.max_pressure, 606.04, 0.01);
  EXPECT_NEAR(p.half_width, 0.10505, 1e-5);
  // Two cylinders of 20 mm: R′ = 10 mm, the same contact.
  const HertzLine q = hertz_line(1000.0, 10.0, 20.0, 20.0, Es);
  EXPECT_NEAR(q.max_pressure, p.max_pressure, 1e-9);
  // Convex 10 mm roller in a concave 20 mm groove: R′ = 20 mm, p₀ lower by √2.
  const HertzLine g = hertz_line(1000.0, 10.0, 10.0, -20.0, Es);
  EXPECT_NEAR(g.max_pressure, p.max_pressure / std::sqrt(2.0), 1e-9);
  EXPECT_THROW(hertz_line(1.0, 10.0, 10.0, -10.0, Es), std::invalid_argument);
}
