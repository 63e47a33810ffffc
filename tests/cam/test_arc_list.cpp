// camdyn — arc cams as a list (cam.profile = "arcs", issue 37): a cam with a concentric top
// dwell between two nose arcs, built in this file from its centres and radii (tangency
// points solved here), against the closed-form lift of each arc for a knife edge, a roller
// and a flat face; the joints' continuity; a cornered cam (C0 joints for a knife edge); the
// join checks naming joint and gap; the jump speed against the closed form of the required
// force; and a held run's contact force against m s″ω² + k(δ₀ + s − s₀).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>
#include <camdyn/designer.hpp>
#include <camdyn/scene.hpp>
#include <camdyn/simulator.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

/// The dwell cam: base circle R_b about O, a concentric top dwell R_d over polar angles
/// [−δ, δ], nose arcs r_n tangent to the dwell at ±δ (centres N± = (R_d − r_n) u(±δ)), and
/// flank arcs R_f tangent to the nose arcs and the base circle (|F| = R_f − R_b,
/// |F − N| = R_f − r_n).
struct DwellCam {
  double Rb = 1.0, Rd = 1.4, delta = 20 * kDeg, rn = 0.25, Rf = 3.0;
  std::array<double, 2> N, F;  // upper nose and upper-flank centres (the lower ones mirrored)
  double gn = 0, gb = 0;       // normal angles of the nose/flank and flank/base tangencies
  DwellCam() {
    const double dn = Rd - rn;
    N = {dn * std::cos(delta), dn * std::sin(delta)};
    const double a = Rf - Rb, b = Rf - rn;
    const double x = (dn * dn + a * a - b * b) / (2 * dn), h = std::sqrt(a * a - x * x);
    const double ux = std::cos(delta), uy = std::sin(delta);
    F = {x * ux + h * uy, x * uy - h * ux};  // the solution clockwise of N
    gn = std::atan2(N[1] - F[1], N[0] - F[0]);
    gb = std::atan2(-F[1], -F[0]);
  }
  /// (centre x, centre y, radius, from, to) [deg], counter-clockwise from the dwell.
  std::vector<std::array<double, 5>> arcs() const {
    const double d = delta / kDeg, n = gn / kDeg, b = gb / kDeg;
    return {{0, 0, Rd, -d, d},           {N[0], N[1], rn, d, n},          {F[0], F[1], Rf, n, b},
            {0, 0, Rb, b, 360 - b},      {F[0], -F[1], Rf, 360 - b, 360 - n}, {N[0], -N[1], rn, 360 - n, 360 - d}};
  }
  CamSpec spec(FollowerFace face, double rr = 0) const {
    CamSpec c;
    c.profile = CamProfileKind::Arcs;
    for (const auto& a : arcs()) {
      c.arc_centre_x.push_back(a[0]);
      c.arc_centre_y.push_back(a[1]);
      c.arc_radius.push_back(a[2]);
      c.arc_from_deg.push_back(a[3]);
      c.arc_to_deg.push_back(a[4]);
    }
    c.follower_face = face;
    c.roller_radius = rr;
    return c;
  }
  /// Knife edge (R_r = 0) or roller on the axis: s(θ) = r(−θ), r(ψ) the pitch curve's polar
  /// radius. On the arc (centre (d, θ_c), pitch radius ρ = R + R_r) holding polar angle ψ:
  /// r = d cos(ψ − θ_c) + √(ρ² − d² sin²(ψ − θ_c)). The arcs' polar ranges come from the
  /// pitch points of the joints (joint point + R_r × its normal). Returns {r, r″}.
  std::array<double, 2> pitch_r(double psi, double rr) const {
    psi = std::remainder(psi, 2 * kPi);
    const double sg = psi < 0 ? -1 : 1, p = std::fabs(psi);
    auto polar = [&](double cx, double cy, double R, double n) {
      return std::atan2(cy + (R + rr) * std::sin(n), cx + (R + rr) * std::cos(n));
    };
    const double p_dn = polar(0, 0, Rd, delta), p_nf = polar(N[0], N[1], rn, gn), p_fb = polar(0, 0, Rb, gb);
    double cx, cy, R;
    if (p <= p_dn) cx = 0, cy = 0, R = Rd;
    else if (p <= p_nf) cx = N[0], cy = sg * N[1], R = rn;
    else if (p <= p_fb) cx = F[0], cy = sg * F[1], R = Rf;
    else cx = 0, cy = 0, R = Rb;
    const double d = std::hypot(cx, cy), tc = std::atan2(cy, cx), rho = R + rr;
    const double A = d * std::cos(psi - tc), B = d * std::sin(psi - tc), S = std::sqrt(rho * rho - B * B);
    // A′ = −B, B′ = A: r″ = −A − (A² − B²)/S − A²B²/S³.
    return {A + S, -A - (A * A - B * B) / S - A * A * B * B / (S * S * S)};
  }
};

}  // namespace

TEST(ArcList, DwellCamKnifeEdgeAndRollerMatchTheClosedFormPerArc) {
  const DwellCam g;
  for (double rr : {0.0, 0.1}) {
    SCOPED_TRACE(rr);
    const Cam cam(g.spec(rr > 0 ? FollowerFace::Roller : FollowerFace::KnifeEdge, rr));
    double err = 0, err2 = 0;
    for (int i = 0; i < 20000; ++i) {
      const double th = 2 * kPi * (i + 0.37) / 20000;
      const auto r = g.pitch_r(-th, rr);
      const CamPoint p = cam.evaluate(th);
      err = std::max(err, std::fabs(p.X_C - r[0]));
      err2 = std::max(err2, std::fabs(p.d2X_dtheta2 - r[1]));
    }
    std::printf("dwell cam, R_r = %g: |s − closed form| ≤ %.2g, |s″ − closed form| ≤ %.2g\n", rr, err, err2);
    EXPECT_LT(err, 4e-15);
    EXPECT_LT(err2, 4e-14);
    EXPECT_NEAR(cam.lift(), g.Rd - g.Rb, 1e-15);
    // Six tangent joints: s and s′ continuous (C1), s″ jumps; on the dwell s′ = s″ = 0.
    ASSERT_EQ(cam.joints().size(), 6u);
    for (const Breakpoint& b : cam.joints()) {
      EXPECT_EQ(b.order, 1) << b.theta;
      EXPECT_LT(std::fabs(b.jump[0]) + std::fabs(b.jump[1]), 1e-13);
    }
    const CamPoint top = cam.evaluate(-0.5 * g.delta);  // the dwell faces the follower at θ ∈ (−δ, δ)
    EXPECT_NEAR(top.X_C, g.Rd + rr, 1e-15);
    EXPECT_NEAR(top.dX_dtheta, 0.0, 1e-15);
  }
}

TEST(ArcList, DwellCamFlatFaceIsTheSupportFunction) {
  // h(θ) = max over the profile of x cos θ − y sin θ, here over 400 000 points of the arcs
  // (exact to R Δn²/8 ≈ 3.4e-10 on the base circle's 198° in 66 666 points); and on the arc
  // whose normal range holds −θ exactly c·u(−θ) + R.
  const DwellCam g;
  const Cam cam(g.spec(FollowerFace::Flat));
  std::vector<std::array<double, 2>> pts;
  for (const auto& a : g.arcs())
    for (int k = 0; k <= 66666; ++k) {
      const double t = (a[3] + (a[4] - a[3]) * k / 66666.0) * kDeg;
      pts.push_back({a[0] + a[2] * std::cos(t), a[1] + a[2] * std::sin(t)});
    }
  double err = 0;
  for (int i = 0; i < 240; ++i) {
    const double th = 2 * kPi * (i + 0.5) / 240;
    double h = -INFINITY;
    for (const auto& q : pts) h = std::max(h, q[0] * std::cos(th) - q[1] * std::sin(th));
    err = std::max(err, std::fabs(cam.evaluate(th).X_C - h));
  }
  std::printf("dwell cam, flat face: |h − sampled support| ≤ %.2g\n", err);
  EXPECT_LT(err, 1e-9);
  // On the nose arc (normal angle 30° faces the follower at θ = −30°): ρ = r_n, X = N·u + r_n.
  const CamPoint p = cam.evaluate(-30 * kDeg);
  EXPECT_NEAR(p.X_C, g.N[0] * std::cos(30 * kDeg) + g.N[1] * std::sin(30 * kDeg) + g.rn, 1e-15);
  EXPECT_DOUBLE_EQ(p.rho, g.rn);
}

TEST(ArcList, CornersAreC0ForAKnifeEdgeAndC1ForAFlatFace) {
  // A lens: the base circle (O, 1) over 60°..300° closed by one convex arc of centre
  // (−0.5, 0) through the same two points — two corners where the tangent turns by
  // 60° − atan2(√3/2, 1) = 19.1°.
  const double R = std::sqrt(1.0 + 0.75), a = std::atan2(std::sqrt(3.0) / 2, 1.0) / kDeg;
  CamSpec c;
  c.profile = CamProfileKind::Arcs;
  c.arc_centre_x = {0.0, -0.5};
  c.arc_centre_y = {0.0, 0.0};
  c.arc_radius = {1.0, R};
  c.arc_from_deg = {60.0, -a};
  c.arc_to_deg = {300.0, a};
  c.follower_face = FollowerFace::KnifeEdge;
  const Cam knife(c);
  ASSERT_EQ(knife.joints().size(), 2u);
  for (const Breakpoint& b : knife.joints()) {
    EXPECT_EQ(b.order, 0);
    // s(θ) = r(−θ): the corner at polar angle ±60° passes the axis at θ = ∓60°.
    EXPECT_NEAR(std::fabs(std::remainder(b.theta, 2 * kPi)), 60 * kDeg, 1e-12);
    EXPECT_GT(std::fabs(b.jump[1]), 0.1);
  }
  EXPECT_EQ(knife.continuity_report().substr(0, 2), "C0");
  c.follower_face = FollowerFace::Flat;
  const Cam flat(c);
  ASSERT_EQ(flat.joints().size(), 4u);  // arc → corner → arc, twice
  for (const Breakpoint& b : flat.joints()) EXPECT_EQ(b.order, 1);
  // While the face pivots on the corner (1/2, √3/2): X = x cos θ − y sin θ, ρ = 0.
  const CamPoint p = flat.evaluate(-50 * kDeg);
  EXPECT_NEAR(p.X_C, 0.5 * std::cos(50 * kDeg) + std::sqrt(0.75) * std::sin(50 * kDeg), 1e-15);
  EXPECT_EQ(p.rho, 0.0);
}

TEST(ArcList, JoinChecksNameTheJointAndTheGap) {
  const DwellCam g;
  CamSpec c = g.spec(FollowerFace::KnifeEdge);
  c.arc_from_deg[2] += 1e-3;  // the flank starts 1e-3° off the nose's end
  try {
    Cam bad(c);
    FAIL() << "accepted arcs that do not meet";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.arc_from_deg[2]");
    EXPECT_NE(e.rule().find("joint 1→2"), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find("apart"), std::string::npos) << e.rule();
  }
  // A concave arc: a knife edge follows it, a flat face is refused naming the cam angles.
  CamSpec k;
  k.profile = CamProfileKind::Arcs;
  k.follower_face = FollowerFace::Flat;
  // Base (O, 1) over 30°..330°, and a concave arc (centre (2, 0), radius −√(1 + 4 − 4 cos 30°))
  // through u(−30°) and u(30°), joined by convex corners.
  const double px = std::cos(30 * kDeg), py = std::sin(30 * kDeg), Rc = std::hypot(2 - px, py);
  const double psi = std::atan2(py, px - 2) / kDeg;  // direction from the centre to u(30°)
  k.arc_centre_x = {0.0, 2.0};
  k.arc_centre_y = {0.0, 0.0};
  k.arc_radius = {1.0, -Rc};
  k.arc_from_deg = {30.0, 360.0 - psi};
  k.arc_to_deg = {330.0, psi};
  try {
    Cam bad(k);
    FAIL() << "a flat face accepted a concave arc";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.arc_radius[1]");
    EXPECT_NE(e.rule().find("concave"), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find("cam angles"), std::string::npos) << e.rule();
  }
  k.follower_face = FollowerFace::KnifeEdge;
  const Cam knife(k);
  // On the axis the knife edge meets the concave arc at θ = 0: x = 2 − R_c.
  EXPECT_NEAR(knife.evaluate(0.0).X_C, 2 - Rc, 1e-15);
  EXPECT_NEAR(knife.evaluate(0.0).rho, -Rc, 1e-15);
  const double q = std::sin(10 * kDeg) * 2;  // θ = 10°: centre at 2 u(10°); X = c_X − √(R² − c_Y²)
  EXPECT_NEAR(knife.evaluate(10 * kDeg).X_C, 2 * std::cos(10 * kDeg) - std::sqrt(Rc * Rc - q * q), 1e-15);
}

TEST(ArcList, JumpSpeedAndHeldForceAgainstTheClosedForm) {
  // Rigid follower m on a spring k, preload k δ₀, knife edge on the dwell cam. Required force
  // F(θ) = m s″ω² + k(δ₀ + s − R_b); jump speed ω² = min over s″ < 0 of k(δ₀ + s − R_b)/(−m s″),
  // the minimum over a 200 000-point scan of the closed form and the one-sided values at the
  // six joints.
  const DwellCam g;
  const double m = 0.2, k = 300.0, d0 = 0.05;
  double w2 = INFINITY;
  auto take = [&](double th) {
    const auto r = g.pitch_r(-th, 0.0);
    if (r[1] < 0) w2 = std::min(w2, k * (d0 + r[0] - g.Rb) / (-m * r[1]));
  };
  for (int i = 0; i < 200000; ++i) take(2 * kPi * i / 200000);
  Scene sc;
  sc.cam = g.spec(FollowerFace::KnifeEdge);
  for (const Breakpoint& b : Cam(sc.cam).joints())
    for (double s : {-1e-12, 1e-12}) take(b.theta + s);
  sc.cam.theta0_deg = 180;
  sc.cam.speed_rev_s = 1.0;
  sc.follower.kind = FollowerKind::Rigid;
  sc.follower.mass = m;
  sc.spring.stiffness = k;
  sc.spring.precompression = d0;
  const JumpResult j = jump_speed(sc);
  const double wj = std::sqrt(w2) / (2 * kPi);
  EXPECT_NEAR(j.jump_speed_rev_s, wj, 1e-9 * wj);

  // Held at 0.8 of the jump speed, two revolutions, Lee: F against the closed form.
  const double rev = 0.8 * wj, w = 2 * kPi * rev;
  sc.cam.speed_rev_s = rev;
  sc.run.t_end = 2.0 / rev;
  sc.run.output_dt = sc.run.t_end / 997;
  sc.solver.rtol = 1e-10;
  sc.solver.atol = 1e-12;
  resolve_defaults(sc);
  const RunResult r = simulate(sc);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_EQ(r.summary.separations, 0);
  double err = 0, Fmax = 0;
  for (const HistoryRow& row : r.rows) {
    const auto s = g.pitch_r(-row.theta, 0.0);
    const double F = m * s[1] * w * w + k * (d0 + s[0] - g.Rb);
    err = std::max(err, std::fabs(row.contact_force - F));
    Fmax = std::max(Fmax, F);
  }
  std::printf("dwell cam, held at %.4g rev/s: max |F − F_closed| = %.3g (peak %.4g); jump speed %.12g, closed form %.12g\n",
              rev, err, Fmax, j.jump_speed_rev_s, wj);
  EXPECT_LT(err, 1e-6 * Fmax) << "max |F − F_closed| = " << err;
}

TEST(ArcList, SceneKeysRoundTripAndPolarCentres) {
  const DwellCam g;
  Scene sc;
  sc.cam = g.spec(FollowerFace::Roller, 0.1);
  const Scene back = parse_scene(to_toml(sc), "<round-trip>");
  EXPECT_TRUE(back.cam == sc.cam);
  // The same arcs with polar centres give the same cam.
  CamSpec p = sc.cam;
  p.arc_centre_r.clear();
  p.arc_centre_deg.clear();
  for (std::size_t i = 0; i < p.arc_centre_x.size(); ++i) {
    p.arc_centre_r.push_back(std::hypot(p.arc_centre_x[i], p.arc_centre_y[i]));
    p.arc_centre_deg.push_back(std::atan2(p.arc_centre_y[i], p.arc_centre_x[i]) / kDeg);
  }
  p.arc_centre_x.clear();
  p.arc_centre_y.clear();
  const Cam a(sc.cam), b(p);
  for (double th = 0.01; th < 2 * kPi; th += 0.1) EXPECT_NEAR(a.evaluate(th).X_C, b.evaluate(th).X_C, 1e-14);
  // The old four-arc cam keeps working under profile = "arc".
  Scene old = parse_scene("[cam]\nprofile = \"arc\"\nnose_radius = 0.6\nnose_distance = 1.8\nflank_radius = 5.0\n"
                          "follower_face = \"knife_edge\"\n",
                          "<test>");
  EXPECT_EQ(Cam(old.cam).joints().size(), 4u);
  try {
    parse_scene("[cam]\nprofile = \"arcs\"\narc_radius = [1.0]\narc_centre_x = [0.0]\narc_centre_y = [0.0]\n"
                "arc_from_deg = [0.0]\narc_to_deg = [180.0]\n",
                "<test>");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.arc_from_deg[0]");
    EXPECT_NE(e.rule().find("joint 0→0"), std::string::npos) << e.rule();
  }
}

TEST(CamExtremes, PressureAngleAtAnArcCornerAgainstItsClosedForm) {
  // Knife edge on the axis: at the joint whose tangency point T (polar angle p_T, normal n_T)
  // crosses the axis (θ = −p_T) the pressure angle is n_T − p_T. Truth: the larger of the
  // corner values and the largest interior value of the closed form φ = atan(s′/s),
  // s(θ) = r(−θ), refined by golden section on a 200 000-point scan of each arc.
  const DwellCam g;
  const Cam cam(g.spec(FollowerFace::KnifeEdge));
  const double p_nf = std::atan2(g.N[1] + g.rn * std::sin(g.gn), g.N[0] + g.rn * std::cos(g.gn));
  const double corner = g.gn - p_nf;
  double interior = 0;
  auto phi = [&](double th) {  // closed form, r′ by the exact derivative of r = A + S: r′ = −B − AB/S
    double psi = std::remainder(-th, 2 * kPi);
    const auto rr = g.pitch_r(psi, 0.0);
    const double h = 1e-6;  // r′ from the closed form's central difference, O(h²) ≈ 1e-12
    const double r1 = (g.pitch_r(psi + h, 0.0)[0] - g.pitch_r(psi - h, 0.0)[0]) / (2 * h);
    return std::fabs(std::atan2(-r1, rr[0]));
  };
  for (int i = 0; i < 200000; ++i) interior = std::max(interior, phi(2 * kPi * (i + 0.5) / 200000));
  const CamExtremum e = cam_extremum(cam, [](const CamPoint& p) { return std::fabs(p.pressure_angle); }, true);
  const double truth = std::max(corner, interior);
  EXPECT_GE(corner, interior);  // this cam's largest pressure angle is at the nose/flank corner
  std::printf("dwell cam: largest pressure angle %.12g° (closed form %.12g°), relative error %.2g\n", e.value / kDeg,
              truth / kDeg, std::fabs(e.value - truth) / truth);
  EXPECT_NEAR(e.value, truth, 1e-9 * truth);
  EXPECT_NEAR(std::fabs(std::remainder(e.theta, 2 * kPi)), p_nf, 1e-9);
  // A 3600-point scan alone misses it.
  double scan = 0;
  for (int k = 0; k < 3600; ++k) scan = std::max(scan, std::fabs(cam.evaluate(2 * kPi * k / 3600).pressure_angle));
  EXPECT_GT(truth - scan, 1e-6 * truth);
}

TEST(CamExtremes, SmallestRadiusOfCurvatureOfALawCamAgainstItsClosedForm) {
  // Flat face on "cycloidal 90 0.5; cycloidal 90 -0.5; dwell 180", r_b = 1.2: ρ = r_b + L + L″.
  // On the rise (x = θ/β): L = h(x − sin 2πx / 2π), L″ = (2πh/β²) sin 2πx; on the fall L = h − (the
  // same), L″ = −(…); the minimum is on the fall where ρ′ = L′ + L‴ = 0, found by Newton in x.
  const double h = 0.5, beta = kPi / 2, rb = 1.2, c = 2 * kPi;
  auto rho = [&](double x) { return rb + h - h * (x - std::sin(c * x) / c) - c * h / (beta * beta) * std::sin(c * x); };
  auto d1 = [&](double x) { return -h * (1 - std::cos(c * x)) - c * c * h / (beta * beta) * std::cos(c * x); };  // dρ/dx
  auto d2 = [&](double x) { return -h * c * std::sin(c * x) + c * c * c * h / (beta * beta) * std::sin(c * x); };
  double best = INFINITY;
  for (double x0 = 0.02; x0 < 1; x0 += 0.02) {
    double x = x0;
    for (int it = 0; it < 60; ++it) x -= d1(x) / d2(x);
    if (x > 0 && x < 1 && d2(x) > 0) best = std::min(best, rho(x));
  }
  best = std::min({best, rho(0.0), rho(1.0)});
  CamSpec s;
  s.profile = CamProfileKind::Law;
  s.law = "cycloidal 90 0.5; cycloidal 90 -0.5; dwell 180";
  s.base_radius = rb;
  const Cam cam(s);
  std::printf("cycloidal law: smallest ρ %.15g, closed form %.15g\n", cam.min_radius_of_curvature(), best);
  EXPECT_NEAR(cam.min_radius_of_curvature(), best, 1e-9 * best);
}

TEST(ArcList, TheFourArcCamAsAListIsTheFourArcCam) {
  // The four-arc cam written as a list (its tangency points solved here from |F| = R_f − R_b,
  // |F − N| = R_f − r_n) gives the same follower motion as profile = "arc" for every face,
  // translating and oscillating.
  const double Rb = 16.0, rn = 6.0, d = 14.0, Rf = 40.0;
  const double a = Rf - Rb, b = Rf - rn, fx = (d * d - b * b + a * a) / (2 * d), fy = std::sqrt(a * a - fx * fx);
  const double gn = std::atan2(fy, d - fx) / kDeg, gb = std::atan2(fy, -fx) / kDeg;
  CamSpec arc;
  arc.profile = CamProfileKind::Arc;
  arc.base_radius = Rb;
  arc.nose_radius = rn;
  arc.nose_distance = d;
  arc.flank_radius = Rf;
  CamSpec list;
  list.profile = CamProfileKind::Arcs;
  list.arc_centre_x = {d, fx, 0.0, fx};
  list.arc_centre_y = {0.0, -fy, 0.0, fy};
  list.arc_radius = {rn, Rf, Rb, Rf};
  list.arc_from_deg = {-gn, gn, gb, 360 - gb};
  list.arc_to_deg = {gn, gb, 360 - gb, 360 - gn};
  struct Setup {
    FollowerFace face;
    FollowerMotion motion;
    double rr, eps;
  };
  for (const Setup& s : {Setup{FollowerFace::Flat, FollowerMotion::Translating, 0, 0},
                         Setup{FollowerFace::KnifeEdge, FollowerMotion::Translating, 0, 2.0},
                         Setup{FollowerFace::Roller, FollowerMotion::Translating, 5.0, -3.0},
                         Setup{FollowerFace::Roller, FollowerMotion::Oscillating, 8.0, 0},
                         Setup{FollowerFace::Flat, FollowerMotion::Oscillating, 0, 0}}) {
    for (CamSpec* c : {&arc, &list}) {
      c->follower_face = s.face;
      c->follower_motion = s.motion;
      c->roller_radius = s.rr;
      c->follower_offset = s.eps;
      c->pivot_x = 40.0;
      c->pivot_y = s.face == FollowerFace::Roller ? 18.0 : 30.0;
      c->arm_length = 30.0;
      c->pad_offset = 5.0;
      c->valve_arm = 45.0;
    }
    SCOPED_TRACE(std::string(to_string(s.face)) + " " + to_string(s.motion));
    const Cam A(arc), L(list);
    ASSERT_EQ(A.breakpoints().size(), L.breakpoints().size());
    double err = 0;
    for (int i = 0; i < 3600; ++i) {
      const double th = 2 * kPi * (i + 0.5) / 3600;
      const CamPoint p = A.evaluate(th), q = L.evaluate(th);
      err = std::max({err, std::fabs(p.X_C - q.X_C), std::fabs(p.d2X_dtheta2 - q.d2X_dtheta2)});
    }
    EXPECT_LT(err, 1e-11);
  }
}
