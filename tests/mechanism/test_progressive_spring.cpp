// The progressive spring (src/mechanism/elements/progressive_spring.cpp), the first nonlinear
// element, against independent truth:
//   * its curve: through the table's points, monotone between them, linear data reproduced,
//     its integral (the stored energy) against composite Simpson quadrature;
//   * the mechanism's tangent (ElementSet::tangent through acceleration_jacobian) against
//     central difference quotients of the acceleration;
//   * a mass on the spring under a constant load, undamped: the node's motion on every
//     method and engine against a fixed-step RK4 of the same ODE written here (with its own
//     PCHIP), Richardson-checked;
//   * damped, the static deflection under a load against the table's inverse (a load equal
//     to a table force: the table's deflection exactly);
//   * run.element_forces columns against F(δ) of the test's own interpolant;
//   * bad tables: SceneError naming key, value and rule.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "mechanism/elements/progressive_spring.hpp"
#include "mechanism/mechanism.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

const std::vector<double> kDefl = {0.0, 0.002, 0.004, 0.006, 0.008, 0.010};  // m
const std::vector<double> kForce = {0.0, 200.0, 420.0, 680.0, 1000.0, 1400.0};  // N

// The test's own monotone cubic (Fritsch–Carlson / PCHIP, as in Moler, "Numerical Computing
// with MATLAB" §3.4), written from the formulas independently of the library.
struct TestPchip {
  std::vector<double> x, y, d;
  TestPchip(std::vector<double> xs, std::vector<double> ys) : x(std::move(xs)), y(std::move(ys)) {
    const std::size_t n = x.size();
    std::vector<double> h(n - 1), del(n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k) {
      h[k] = x[k + 1] - x[k];
      del[k] = (y[k + 1] - y[k]) / h[k];
    }
    d.assign(n, 0.0);
    for (std::size_t k = 1; k + 1 < n; ++k)
      if (del[k - 1] > 0 && del[k] > 0) {
        const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
        d[k] = (w1 + w2) / (w1 / del[k - 1] + w2 / del[k]);
      }
    auto endslope = [](double h1, double h2, double d1, double d2) {
      double s = ((2 * h1 + h2) * d1 - h1 * d2) / (h1 + h2);
      if (s * d1 <= 0) s = 0;
      else if (d1 * d2 < 0 && std::abs(s) > 3 * std::abs(d1)) s = 3 * d1;
      return s;
    };
    d[0] = endslope(h[0], h[1], del[0], del[1]);
    d[n - 1] = endslope(h[n - 2], h[n - 3], del[n - 2], del[n - 3]);
  }
  double operator()(double s) const {
    const std::size_t n = x.size();
    if (s <= x[0]) return y[0] + d[0] * (s - x[0]);
    if (s >= x[n - 1]) return y[n - 1] + d[n - 1] * (s - x[n - 1]);
    std::size_t k = 0;
    while (s >= x[k + 1]) ++k;
    // Moler's form: c, b coefficients of the cubic in (s − x_k)
    const double h = x[k + 1] - x[k], del = (y[k + 1] - y[k]) / h;
    const double c = (3 * del - 2 * d[k] - d[k + 1]) / h, b = (d[k] - 2 * del + d[k + 1]) / (h * h);
    const double u = s - x[k];
    return y[k] + u * (d[k] + u * (c + u * b));
  }
  double inverse(double F) const {
    double lo = x.front() - 1, hi = x.back() + 1;
    for (int i = 0; i < 200; ++i) {
      const double m = 0.5 * (lo + hi);
      ((*this)(m) < F ? lo : hi) = m;
    }
    return 0.5 * (lo + hi);
  }
};

ElementSpec progressive(std::string name, std::vector<std::string> nodes, double installed, double damping = 0.0) {
  ElementSpec e;
  e.name = std::move(name);
  e.kind = ElementKind::ProgressiveSpring;
  e.nodes = std::move(nodes);
  e.deflections = kDefl;
  e.forces = kForce;
  e.installed_deflection = installed;
  e.damping = damping;
  return e;
}

// A mass m on a progressive spring [mass, ground] installed at δ_i = 4 mm (preload 420 N),
// a constant load P upward (a spring [ground, mass] of stiffness 0 and preload P) and a stop
// 50 mm above that it never reaches: m ẍ = P − F(δ_i + x) − c ẋ, x(0) = 0, ẋ(0) = 0.
constexpr double kMass = 0.05, kInstalled = 0.004;
Scene mass_on_spring(double load, double damping, Integrator integ, ContactModel model) {
  Scene s = default_scene();
  s.title = "progressive spring";
  s.follower.kind = FollowerKind::Network;
  NodeSpec n;
  n.name = "mass";
  n.mass = kMass;
  s.network.nodes = {n};
  ElementSpec loadspring;
  loadspring.name = "load";
  loadspring.kind = ElementKind::Spring;
  loadspring.nodes = {"ground", "mass"};
  loadspring.stiffness = 0.0;
  loadspring.preload = load;
  s.network.elements = {progressive("valve_spring", {"mass", "ground"}, kInstalled, damping), loadspring};
  ContactPointSpec stop;
  stop.name = "stop";
  stop.kind = ContactPointKind::Stop;
  stop.nodes = {"mass"};
  stop.side = StopSide::Above;
  stop.clearance = 0.05;
  s.network.contacts = {stop};
  s.contact.model = model;
  s.solver.integrator = integ;
  s.solver.rtol = 1e-9;
  s.solver.atol = 1e-13;
  s.run.t_end = 0.01;
  s.run.output_dt = 1e-4;
  s.run.element_forces = true;
  return s;
}

// x(t) of m ẍ = P − F(δ_i + x) by classic RK4 with step h, sampled every `every` steps.
std::vector<double> rk4(const TestPchip& F, double P, double h, int steps, int every) {
  auto acc = [&](double x) { return (P - F(kInstalled + x)) / kMass; };
  double x = 0, v = 0;
  std::vector<double> out{x};
  for (int i = 1; i <= steps; ++i) {
    const double k1x = v, k1v = acc(x);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (i % every == 0) out.push_back(x);
  }
  return out;
}

TEST(ProgressiveSpring, CurveThroughPointsMonotoneWithExactIntegral) {
  const MonotoneCurve c(kDefl, kForce);
  const TestPchip ref(kDefl, kForce);
  for (std::size_t k = 0; k < kDefl.size(); ++k) EXPECT_NEAR(c.value(kDefl[k]), kForce[k], 1e-12);
  double prev = -INFINITY, err = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    const double s = -0.001 + 0.012 * i / 2000.0;
    const double F = c.value(s);
    EXPECT_GE(F, prev - 1e-12) << "not monotone at " << s;
    prev = F;
    err = std::max(err, std::abs(F - ref(s)));
    // the slope against a central difference quotient (measured: < 1e-6 N/m of ~2e5)
    const double e = 1e-8;
    EXPECT_NEAR(c.slope(s + 2e-7), (c.value(s + 2e-7 + e) - c.value(s + 2e-7 - e)) / (2 * e), 1e-3 * 2e5 * 1e-3);
  }
  EXPECT_LT(err, 1e-9);  // the library's Hermite form and the test's Moler form (measured 4.5e-13 N)
  // the integral against composite Simpson with 20 000 panels (a cubic per segment: exact
  // per panel inside a segment; measured differences 2e-18 to 5e-14 J)
  for (double s : {-0.0005, 0.0013, 0.004, 0.0071, 0.0115}) {
    const int N = 20000;
    const double a = kDefl[0], hh = (s - a) / N;
    double sum = c.value(a) + c.value(s);
    for (int i = 1; i < N; ++i) sum += (i % 2 ? 4 : 2) * c.value(a + i * hh);
    EXPECT_NEAR(c.integral(s), sum * hh / 3, 1e-9) << s;
  }
  // linear data is reproduced exactly
  const MonotoneCurve lin({0.0, 1.0, 3.0, 4.0}, {1.0, 3.0, 7.0, 9.0});
  for (double s : {-1.0, 0.3, 2.2, 3.9, 5.0}) EXPECT_NEAR(lin.value(s), 1.0 + 2.0 * s, 1e-12);
  EXPECT_NEAR(c.inverse(680.0), 0.006, 1e-14);
}

TEST(ProgressiveSpring, TangentMatchesDifferenceQuotients) {
  Scene s = mass_on_spring(680.0, 3.0, Integrator::ArkodeDirk, ContactModel::Event);
  // a second mass on a lever output, so the tangent has off-diagonal entries through a lever
  NodeSpec m2;
  m2.name = "top";
  m2.mass = 0.02;
  s.network.nodes.push_back(m2);
  ElementSpec lv;
  lv.kind = ElementKind::Lever;
  lv.nodes = {"mass", "arm"};
  lv.ratio = 1.5;
  NodeSpec arm;
  arm.name = "arm";
  s.network.nodes.push_back(arm);
  s.network.elements.push_back(lv);
  s.network.elements.push_back(progressive("link", {"arm", "top"}, 0.003, 1.0));
  ElementSpec hold;
  hold.kind = ElementKind::Spring;
  hold.nodes = {"top", "ground"};
  hold.stiffness = 1e4;
  s.network.elements.push_back(hold);
  resolve_defaults(s);
  validate(s);
  const Mechanism mech(s);
  ASSERT_FALSE(mech.linear());
  const int n = mech.n();
  ASSERT_EQ(n, 2);
  Eigen::VectorXd q(n), v(n), F;
  q << 0.0013, -0.0004;
  v << 0.3, -0.2;
  Eigen::MatrixXd dq, dv;
  ASSERT_TRUE(mech.acceleration_jacobian(0.0, q.data(), v.data(), dq, dv));
  for (int j = 0; j < n; ++j) {
    // a is linear in v (ev large: no truncation, less round-off), cubic in q (eq small)
    const double e = 1e-8, ev = 1e-3;
    Eigen::VectorXd qp = q, qm = q, vp = v, vm = v, ap(n), am(n), bp(n), bm(n);
    qp[j] += e, qm[j] -= e, vp[j] += ev, vm[j] -= ev;
    mech.acceleration(0.0, qp.data(), v.data(), F, ap.data());
    mech.acceleration(0.0, qm.data(), v.data(), F, am.data());
    mech.acceleration(0.0, q.data(), vp.data(), F, bp.data());
    mech.acceleration(0.0, q.data(), vm.data(), F, bm.data());
    // measured: relative differences < 1e-7
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(dq(i, j), (ap[i] - am[i]) / (2 * e), 1e-6 * dq.cwiseAbs().maxCoeff()) << i << "," << j;
      EXPECT_NEAR(dv(i, j), (bp[i] - bm[i]) / (2 * ev), 1e-6 * dv.cwiseAbs().maxCoeff() + 1e-9) << i << "," << j;
    }
  }
}

struct Case {
  Integrator integ;
  ContactModel model;
  double tol;  // bound on |x − x_RK4| [m] over the run (the amplitude is 4 mm)
};

TEST(ProgressiveSpring, MassOnSpringMatchesRk4OnEveryMethodAndEngine) {
  const TestPchip F(kDefl, kForce);
  const double P = 680.0;
  // RK4 at h = 1e-7 s (10⁵ steps) and h/2: their difference bounds RK4's own error
  // (Richardson, order 4: error(h) ≈ 16/15 · difference); measured 5.5e-17 m.
  const std::vector<double> xa = rk4(F, P, 1e-7, 100000, 1000), xb = rk4(F, P, 5e-8, 200000, 2000);
  double rk_err = 0.0;
  for (std::size_t i = 0; i < xa.size(); ++i) rk_err = std::max(rk_err, std::abs(xa[i] - xb[i]));
  EXPECT_LT(rk_err, 1e-11);
  // measured max |x − x_RK4| over 101 rows (m), rtol 1e-9: erk lee 4.1e-11, event 5.6e-12,
  // penalty 4.8e-12; dirk lee 1.1e-12, event 7e-13, penalty 7e-13; cvode-bdf lee 2.8e-10,
  // event 2.1e-10; ida holonomic 2.9e-10 (amplitude 4e-3 m)
  const Case cases[] = {
      {Integrator::ArkodeErk, ContactModel::Lee, 2e-10},     {Integrator::ArkodeErk, ContactModel::Event, 2e-10},
      {Integrator::ArkodeErk, ContactModel::Penalty, 2e-10}, {Integrator::ArkodeDirk, ContactModel::Lee, 2e-10},
      {Integrator::ArkodeDirk, ContactModel::Event, 2e-10},  {Integrator::ArkodeDirk, ContactModel::Penalty, 2e-10},
      {Integrator::CvodeBdf, ContactModel::Lee, 2e-9},       {Integrator::CvodeBdf, ContactModel::Event, 2e-9},
      {Integrator::Ida, ContactModel::Holonomic, 2e-9},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(to_string(c.integ)) + " " + to_string(c.model));
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(mass_on_spring(P, 0.0, c.integ, c.model));
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    double err = 0.0;
    int n = 0;
    for (const HistoryRow& row : r.rows) {
      const double k = row.t / 1e-4;
      if (std::abs(k - std::round(k)) > 1e-6) continue;
      const std::size_t i = std::size_t(std::lround(k));
      err = std::max(err, std::abs(r.col(row, "u_mass") - xa.at(i)));
      ++n;
    }
    EXPECT_GE(n, 100);
    EXPECT_LT(err, c.tol);
  }
}

TEST(ProgressiveSpring, StaticDeflectionUnderLoadIsTheTablesInverse) {
  const TestPchip F(kDefl, kForce);
  // ζ ≈ 0.2 at the equilibrium's rate: after 0.12 s the motion has decayed by e^{-40}
  for (double P : {680.0, 550.0}) {
    Scene s = mass_on_spring(P, 40.0, Integrator::ArkodeDirk, ContactModel::Event);
    s.run.t_end = 0.12;
    s.run.output_dt = 0.01;
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    const double x = r.col(r.rows.back(), "u_mass");
    // P = 680 N is the table's force at 6 mm: δ = 6 mm exactly; 550 N: the test's PCHIP
    // inverse (measured |Δx| 6e-18 m and 4e-19 m, |F − P| 3e-12 N and 1e-12 N)
    const double want = (P == 680.0 ? 0.006 : F.inverse(P)) - kInstalled;
    EXPECT_NEAR(x, want, 1e-11) << P;
    EXPECT_NEAR(r.col(r.rows.back(), "force_valve_spring"), P, 1e-6);
  }
}

TEST(ProgressiveSpring, ElementForceColumns) {
  const TestPchip F(kDefl, kForce);
  const Scene s = mass_on_spring(680.0, 0.0, Integrator::ArkodeErk, ContactModel::Event);
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  double err = 0.0;
  for (const HistoryRow& row : r.rows) {
    err = std::max(err, std::abs(r.col(row, "force_valve_spring") - F(kInstalled + r.col(row, "u_mass"))));
    EXPECT_EQ(r.col(row, "force_load"), 680.0);  // k = 0: its preload
  }
  EXPECT_LT(err, 1e-8);  // measured 2.3e-13 N
  // without the key, no force columns
  Scene s2 = s;
  s2.run.element_forces = false;
  const Simulator sim2(s2);
  for (const std::string& c : sim2.extra_columns()) EXPECT_NE(c.rfind("force_", 0), 0u) << c;
}

// A linear spring's column is P + kδ + cδ̇ from the node columns (the two-mass OHC train's
// stem [tappet, valve] k = 5e7, c = 30, and valve spring [valve, ground] k = 35e3, P = 250,
// c = 2; measured |Δ| = 0: the same terms, so any sign, lever factor or missing term shows).
TEST(ProgressiveSpring, LinearSpringForceColumns) {
  Scene s = camdyn_test::two_mass_train();
  s.run.t_end = 0.02;
  s.run.output_dt = 1e-4;
  s.run.element_forces = true;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  double es = 0.0, ev = 0.0;
  for (const HistoryRow& row : r.rows) {
    const double ut = r.col(row, "u_tappet"), uv = r.col(row, "u_valve");
    const double vt = r.col(row, "v_tappet"), vv = r.col(row, "v_valve");
    es = std::max(es, std::abs(r.col(row, "force_stem") - (5e7 * (ut - uv) + 30.0 * (vt - vv))));
    ev = std::max(ev, std::abs(r.col(row, "force_valve_spring") - (250.0 + 35e3 * uv + 2.0 * vv)));
  }
  EXPECT_LT(es, 1e-8);
  EXPECT_LT(ev, 1e-9);
}

TEST(ProgressiveSpring, BadTablesNameKeyValueAndRule) {
  const std::string head = R"(
[cam]
profile = "circle"
radius = 0.02
eccentricity = 0.004
[follower]
kind = "network"
[[nodes]]
name = "valve"
mass = 0.05
[[contacts]]
name = "cam"
type = "cam"
nodes = ["valve"]
[[elements]]
name = "vs"
type = "progressive_spring"
nodes = ["valve", "ground"]
)";
  auto error_of = [&](const std::string& tail) -> std::string {
    try {
      Scene s = parse_scene(head + tail, "t.toml");
      resolve_defaults(s);
      validate(s);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  std::string e = error_of("deflections = [0, 1, 2, 3]\nforces = [0, 10, 9, 20]\n");
  EXPECT_NE(e.find("elements[0].forces[2]"), std::string::npos) << e;
  EXPECT_NE(e.find("non-decreasing"), std::string::npos) << e;
  e = error_of("deflections = [0, 1, 1, 3]\nforces = [0, 10, 11, 20]\n");
  EXPECT_NE(e.find("elements[0].deflections[2]"), std::string::npos) << e;
  EXPECT_NE(e.find("strictly increasing"), std::string::npos) << e;
  e = error_of("deflections = [0, 1, 2]\nforces = [0, 10]\n");
  EXPECT_NE(e.find("elements[0].forces"), std::string::npos) << e;
  e = error_of("deflections = [0]\nforces = [0]\n");
  EXPECT_NE(e.find("at least 2"), std::string::npos) << e;
  e = error_of("deflections = [0, 1]\nforces = [0, 10]\nstiffness = 5\n");
  EXPECT_NE(e.find("elements[0].stiffness"), std::string::npos) << e;
  EXPECT_EQ(error_of("deflections = [0, 1]\nforces = [0, 10]\ninstalled_deflection = 0.5\n"), "");
  // the written scene reads back equal
  Scene s = parse_scene(head + "deflections = [0, 0.001, 0.003]\nforces = [0, 10, 45]\ninstalled_deflection = 0.0005\n"
                               "damping = 2\n",
                        "t.toml");
  EXPECT_TRUE(parse_scene(to_toml(s), "w.toml").network == s.network);
}

}  // namespace
}  // namespace camdyn
