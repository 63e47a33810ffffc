// The hydraulic lash adjuster's check valve as a ball with mass and spring (check_ball_mass
// > 0, src/mechanism/elements/hydraulic_lash_adjuster.cpp), against independent truth:
//   * the ball's free response off its seat at a fixed chamber pressure: the element's own
//     state equations (integrated here by classic RK4) against the closed form of the
//     damped mass–spring oscillator;
//   * the opening pressure: at rest the ball leaves its seat exactly when p_s − p exceeds
//     the opening pressure (its spring's preload over the seat area), at the rest lift
//     ((p_s − p) − Δp_open) A_s / k_b;
//   * the Jacobian blocks with the ball (off its seat, on it, beyond full open) against
//     difference quotients;
//   * pump-up with the ball: a lash above the plunger closes in the time the ball valve's
//     quasi-static flow predicts;
//   * a mass on an HLA with the ball (the ball opening and closing on its seat) on
//     arkode-erk, arkode-dirk, cvode-bdf and IDA against an RK4 of the same five-state ODE
//     written here, the energy ledger closing on each;
//   * bad values named (key, value, rule); the written scene reads back equal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "mechanism/elements/hydraulic_lash_adjuster.hpp"
#include "../network_run_support.hpp"
#include "hla_test_support.hpp"

namespace camdyn {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMass = 0.1;       // kg, the plunger
constexpr double kArea = 1e-4;      // m²
constexpr double kPref = 101325.0;  // Pa
constexpr double kBall = 3.3e-5;    // kg: a 2 mm steel ball
constexpr double kSeat = 1.4e-3;    // m, seat bore
constexpr double kOpen = 3e4;       // Pa, opening pressure
const double kAs = 0.25 * kPi * kSeat * kSeat;  // 1.539e-6 m²

/// An HLA on [ground, plunger] with a ball check valve: k_b, c_b as given, seat stiffness k_s.
ElementSpec ball_hla(double kb, double cb, double ks) {
  ElementSpec e;
  e.name = "hla";
  e.kind = ElementKind::HydraulicLashAdjuster;
  e.nodes = {"ground", "plunger"};
  e.area = kArea;
  e.chamber_volume = 2e-7;
  e.bulk_modulus = 1.5e9;
  e.air_fraction = 0.01;
  e.plunger_diameter = 0.011;
  e.leak_clearance = 5e-6;
  e.leak_length = 0.005;
  e.viscosity = 0.01;
  e.supply_pressure = 3e5;
  e.check_opening_pressure = kOpen;
  e.check_ball_mass = kBall;
  e.check_ball_stiffness = kb;
  e.check_ball_damping = cb;
  e.check_seat_diameter = kSeat;
  e.check_seat_stiffness = ks;
  return e;
}

/// A plunger of kMass on the HLA to ground, pushed down by a constant load, a stop `lash`
/// above it.
Scene plunger_scene(const ElementSpec& e, double load, double lash, Integrator integ, ContactModel model) {
  return camdyn_test::hla_plunger_scene(e, kMass, load, lash, integ, model);
}

/// The test's own model of the HLA with the ball (the formulas of docs/interface.md).
struct TestBallHla {
  ElementSpec e;
  double As() const { return 0.25 * kPi * e.check_seat_diameter * e.check_seat_diameter; }
  double beta(double p) const {
    const double pa = std::max(e.air_reference_pressure + p, 1e-3 * e.air_reference_pressure);
    const double vl = 1 - e.air_fraction, vg = e.air_fraction * e.air_reference_pressure / pa;
    return (vl + vg) / (vl / e.bulk_modulus + vg / pa);
  }
  double leak(double p) const {
    const double c = e.leak_clearance;
    return kPi * e.plunger_diameter * c * c * c * (p - e.supply_pressure) / (12 * e.viscosity * e.leak_length);
  }
  // C_d · curtain area π d_s x (up to the bore's A_s) · √(2|Δ|/ρ) sign Δ, with Δ² → Δ²/√(Δ² + Δ_t²)
  double flow(double p, double x) const {
    if (x <= 0) return 0.0;
    const double area = std::min(kPi * e.check_seat_diameter * x, As());
    const double d = e.supply_pressure - p, t = e.check_transition_pressure;
    const double deff = d * d / std::sqrt(d * d + t * t);
    return e.check_discharge_coefficient * area * std::sqrt(2 * deff / e.oil_density) * (d < 0 ? -1.0 : 1.0);
  }
  double ball_acc(double p, double x, double w) const {
    const double seat = x < 0 ? -e.check_seat_stiffness * x : 0.0;
    return ((e.supply_pressure - p) * As() - e.check_opening_pressure * As() - e.check_ball_stiffness * x -
            e.check_ball_damping * w + seat) /
           e.check_ball_mass;
  }
  double rest_lift(double p) const {
    const double f = (e.supply_pressure - p - e.check_opening_pressure) * As();
    return f > 0 ? f / e.check_ball_stiffness : f / (e.check_ball_stiffness + e.check_seat_stiffness);
  }
};

/// The element's ball rows (ṡ₃, ṡ₄) at a fixed gauge pressure p, by classic RK4 from (x0, w0).
std::vector<double> element_ball_rk4(const HydraulicLashAdjuster& h, double p, double x0, double dt, long steps) {
  const double xx[2] = {0.0, 0.0}, vv[2] = {0.0, 0.0};
  auto f = [&](const double* y, double* d) {
    const double st[5] = {1 + p / kPref, 0.0, 0.0, y[0], y[1]};
    ElementState e;
    e.x = xx;
    e.xd = vv;
    e.s = st;
    double r[5];
    h.state_rate(e, r);
    d[0] = r[3];
    d[1] = r[4];
  };
  std::vector<double> xs{x0};
  double y[2] = {x0, 0.0};
  for (long i = 0; i < steps; ++i) {
    camdyn_test::rk4_step(f, y, dt);
    xs.push_back(y[0]);
  }
  return xs;
}

// Free response off the seat: p_s − p = 0.15 N / A_s + Δp_open, rest lift x_e = 0.75 mm on
// k_b = 200 N/m, released from x_e + 0.2 mm at rest with ζ = 0.1:
// x(t) = x_e + a e^(−ζωt)(cos ω_d t + ζω/ω_d sin ω_d t). RK4 at T/4000 over five periods
// (RK4's own error ~ (ω dt)⁴/120 per step). Measured max |x − closed form| / a: 1.9e-13.
TEST(HlaCheckBall, FreeResponseIsTheDampedOscillator) {
  const double kb = 200.0, w = std::sqrt(kb / kBall), zeta = 0.1;
  const HydraulicLashAdjuster h(ball_hla(kb, 2 * zeta * std::sqrt(kb * kBall), 1e6), "hla");
  ASSERT_TRUE(h.has_ball());
  ASSERT_EQ(h.states(), 5);
  const double p = 3e5 - kOpen - 0.15 / kAs, xe = 0.15 / kb, a = 2e-4;
  const double T = 2 * kPi / w, dt = T / 4000, wd = w * std::sqrt(1 - zeta * zeta);
  const std::vector<double> xs = element_ball_rk4(h, p, xe + a, dt, 20000);
  double err = 0.0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double t = dt * double(i);
    const double exact = xe + a * std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
    err = std::max(err, std::abs(xs[i] - exact));
    ASSERT_GT(xs[i], 0.0);  // off the seat throughout: the linear oscillator
  }
  EXPECT_LT(err / a, 1e-9);
}

// The opening pressure: at rest (critically damped off the seat, 30/ω of settling: the
// transient e^(−ωt)(1 + ωt) ≈ 3e-12) the ball sits at ((p_s − p) − Δp_open) A_s / k_b above
// Δp_open and on its seat (no flow) below. Bisection on the sign of the rest lift finds the
// opening at Δp_open: measured relative difference 9.5e-8 (20 halvings of ±10 %: 1e-7).
TEST(HlaCheckBall, OpensAtTheOpeningPressure) {
  const double kb = 200.0, w = std::sqrt(kb / kBall);
  const HydraulicLashAdjuster h(ball_hla(kb, 2 * std::sqrt(kb * kBall), 1e5), "hla");
  const TestBallHla m{ball_hla(kb, 0.0, 1e5)};
  const double ps = 3e5, dt = 0.5 / std::sqrt(1e5 / kBall);  // resolves the seat's own mode
  const long steps = long(30.0 / w / dt);
  auto rest = [&](double d) { return element_ball_rk4(h, ps - d, 0.0, dt, steps).back(); };
  for (double f : {1.01, 1.5, 3.0}) {
    const double d = f * kOpen, x = rest(d);
    EXPECT_NEAR(x, m.rest_lift(ps - d), 1e-8 * m.rest_lift(ps - d)) << f;
    EXPECT_GT(h.ball_flow(ps - d, x), 0.0);
    EXPECT_NEAR(h.ball_flow(ps - d, x), m.flow(ps - d, x), 1e-12 * m.flow(ps - d, x));
  }
  for (double f : {0.99, 0.5}) {
    const double x = rest(f * kOpen);
    EXPECT_LE(x, 0.0) << f;
    EXPECT_NEAR(x, m.rest_lift(ps - f * kOpen), 1e-6 * std::abs(m.rest_lift(ps - f * kOpen)));
    EXPECT_EQ(h.ball_flow(ps - f * kOpen, x), 0.0);
  }
  double lo = 0.9 * kOpen, hi = 1.1 * kOpen;
  for (int i = 0; i < 20; ++i) {
    const double c = 0.5 * (lo + hi);
    (rest(c) > 0.0 ? hi : lo) = c;
  }
  EXPECT_NEAR(0.5 * (lo + hi), kOpen, 2e-7 * kOpen);
}

// ∂g/∂s, ∂g/∂x, ∂g/∂ẋ and ∂f/∂s with the ball off its seat, on it and beyond full open (the
// curtain area capped at A_s: lift > d_s/4), against central differences.
TEST(HlaCheckBall, StateJacobianMatchesDifferenceQuotients) {
  const HydraulicLashAdjuster h(ball_hla(300.0, 0.05, 1e6), "hla");
  for (double lift : {3e-4, -2e-6, 5e-4}) {
    for (double p : {1e5, 4e5}) {  // the flow into and out of the chamber
      SCOPED_TRACE(std::to_string(lift) + " " + std::to_string(p));
      const double x[2] = {1e-5, -3e-5}, xd[2] = {0.02, -0.05};
      const double st[5] = {1 + p / kPref, 0.1, 0.2, lift, 0.05};
      ElementState e;
      e.x = x;
      e.xd = xd;
      e.s = st;
      double dgdx[10], dgdxd[10], dgds[25], dfds[10];
      h.state_jacobian(e, dgdx, dgdxd, dgds, dfds);
      auto rate = [&](const double* xx, const double* vv, const double* ss, double* r) {
        ElementState f;
        f.x = xx;
        f.xd = vv;
        f.s = ss;
        h.state_rate(f, r);
      };
      for (int c = 0; c < 5; ++c) {
        const double ds = c == 0 ? 1e-7 * st[0] : c == 3 ? 1e-10 : 1e-6;
        double sp[5], sm[5], rp[5], rm[5];
        std::copy(st, st + 5, sp);
        std::copy(st, st + 5, sm);
        sp[c] += ds, sm[c] -= ds;
        rate(x, xd, sp, rp);
        rate(x, xd, sm, rm);
        for (int l = 0; l < 5; ++l) {
          const double fd = (rp[l] - rm[l]) / (2 * ds);
          EXPECT_NEAR(dgds[l + 5 * c], fd, 1e-5 * std::abs(fd) + 1e-6) << "row " << l << " col " << c;
        }
        ElementState fp = e, fm = e;
        fp.s = sp;
        fm.s = sm;
        double op[2], om[2];
        h.force(fp, op);
        h.force(fm, om);
        EXPECT_NEAR(dfds[1 + 2 * c], (op[1] - om[1]) / (2 * ds), 1e-7 * std::abs(dfds[1 + 2 * c]) + 1e-9);
      }
      for (int i = 0; i < 2; ++i) {
        double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]}, vp[2] = {xd[0], xd[1]}, vm[2] = {xd[0], xd[1]};
        xp[i] += 1e-9, xm[i] -= 1e-9, vp[i] += 1e-6, vm[i] -= 1e-6;
        double rp[5], rm[5];
        rate(xp, xd, st, rp);
        rate(xm, xd, st, rm);
        for (int l = 0; l < 5; ++l)
          EXPECT_NEAR(dgdx[l + 5 * i], (rp[l] - rm[l]) / 2e-9, 1e-5 * std::abs(dgdx[l + 5 * i]) + 1e-3) << l;
        rate(x, vp, st, rp);
        rate(x, vm, st, rm);
        for (int l = 0; l < 5; ++l)
          EXPECT_NEAR(dgdxd[l + 5 * i], (rp[l] - rm[l]) / 2e-6, 1e-6 * std::abs(dgdxd[l + 5 * i]) + 1e-6) << l;
      }
    }
  }
}

// Pump-up with the ball: the plunger spring (preload 5 N, no load) lifts the plunger toward a
// stop 1 mm above; the chamber sits at p = −P/A (no air: no compliance), the ball at its rest
// lift ((p_s − p) − Δp_open)A_s/k_b = 0.098 mm (k_b = 5000 N/m, near critical damping) and
// the plunger rises at (Q_ball − Q_leak)/A; started there (initial_pressure = −P/A, the
// plunger at that speed: without it the 0.1 kg plunger's start on the chamber lags the rise
// by 0.4 ms). The lash closes at t ≈ A·lash/(Q_ball − Q_leak) = 11.49 ms; measured: the row after the estimate
// (rows every t_est/2000: +5e-4), the ball's lift and flow just before it equal to the model's.
TEST(HlaCheckBall, PumpUpClosesTheLashInThePredictedTime) {
  const double P = 5.0, lash = 1e-3, kb = 5000.0;
  ElementSpec e = ball_hla(kb, 0.8, 1e6);
  e.air_fraction = 0.0;
  e.preload = P;
  e.initial_pressure = -P / kArea;
  const TestBallHla m{e};
  const double p = -P / kArea, x = m.rest_lift(p);
  ASSERT_LT(kPi * kSeat * x, kAs);  // below full open: the curtain area sets the flow
  const double t_est = kArea * lash / (m.flow(p, x) - m.leak(p));
  Scene s = plunger_scene(e, 0.0, lash, Integrator::CvodeBdf, ContactModel::Event);
  s.network.nodes[0].initial_velocity = lash / t_est;  // already rising: no start transient
  s.run.t_end = 1.2 * t_est;
  s.run.output_dt = t_est / 2000;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  double t_close = NAN;
  for (std::size_t i = 1; i < r.rows.size(); ++i)
    if (r.col(r.rows[i], "in_stop") > 0.5) {
      t_close = r.rows[i].t;
      // just before: the ball at its rest lift, the flow the model's
      EXPECT_NEAR(r.col(r.rows[i - 1], "force_hla_ball_lift"), x, 1e-6 * x);
      EXPECT_NEAR(r.col(r.rows[i - 1], "force_hla_check_flow"), m.flow(p, x), 1e-6 * m.flow(p, x));
      break;
    }
  EXPECT_NEAR(t_close, t_est, 1e-3 * t_est) << "estimate " << t_est;
  bool found = false;
  for (const ElementResult& er : r.sum.elements)
    if (er.name == "hla_ball_lift") {
      found = true;
      EXPECT_NEAR(er.max, x, 0.05 * x);
    }
  EXPECT_TRUE(found);
}

// u(t), p(t), x(t) of the plunger on the HLA with the ball: m ü = pA + P_hla − F_load (δ = −u),
// ṗ = β(p)/V(δ)(−A u̇ − Q_leak + Q_ball), m_b ẍ = … (TestBallHla), by classic RK4.
struct Traj {
  std::vector<double> u, p, x;
};
Traj rk4(const TestBallHla& m, double load, double h, int steps, int every) {
  auto f = [&](const double* y, double* d) {
    const double u = y[0], v = y[1], p = y[2], x = y[3], w = y[4];
    d[0] = v;
    d[1] = (p * m.e.area + m.e.preload - m.e.stiffness * u - load) / kMass;
    d[2] = m.beta(p) / (m.e.chamber_volume + m.e.area * u) * (-m.e.area * v - m.leak(p) + m.flow(p, x));
    d[3] = w;
    d[4] = m.ball_acc(p, x, w);
  };
  double y[5] = {0.0, 0.0, m.e.initial_pressure, m.rest_lift(m.e.initial_pressure), 0.0};
  Traj t{{y[0]}, {y[2]}, {y[3]}};
  for (int i = 1; i <= steps; ++i) {
    camdyn_test::rk4_step(f, y, h);
    if (i % every == 0) {
      t.u.push_back(y[0]);
      t.p.push_back(y[2]);
      t.x.push_back(y[3]);
    }
  }
  return t;
}

// Load 60 N on the plunger, p(0) = 0: the ball starts open (p_s − p = 3 bar > 0.3 bar, lift
// 0.14 mm on k_b = 3000 N/m), the plunger falls onto the chamber, lets oil back out through
// the open ball, the pressure rises and the ball lands on its seat (down to −2.3 µm into it)
// as the plunger oscillates on the chamber (1 % air). Every engine against RK4 at h = 5e-9 s
// (at 1e-8 s it differs by 3.1e-12 m in u and 1.5e-10 m in x: the kinks of the seat and of
// the valve's flow at x = 0 cut RK4's order near them). Measured max |u − u_RK4| (m) /
// |p − p_RK4| (Pa) / |x − x_RK4| (m) over 41 rows, rtol 1e-10: arkode-erk event 3.2e-13 /
// 0.05 / 6.4e-12; cvode-bdf event 5.4e-13 / 0.047 / 8.7e-12, lee 3.4e-13 / 0.032 / 1.2e-11;
// ida holonomic 1.2e-13 / 0.022 / 2.7e-12; arkode-dirk event 4.0e-11 / 5.9 / 1.7e-9 (its
// error falls slowly with rtol across the seat's kink: 2.2e-10, 4.0e-11, 1.8e-11, 5.9e-12 m in
// u at rtol 1e-9 … 1e-12). Energy residual ≤ 3.8e-10 J (dirk; the others ≤ 3.2e-12 J), the
// contract held on every one.
TEST(HlaCheckBall, MassOnHlaWithBallMatchesRk4OnEveryEngine) {
  const ElementSpec e = ball_hla(3000.0, 0.05, 1e6);
  const double load = 60.0, t_end = 2e-3, dt = 5e-5;
  const TestBallHla m{e};
  const Traj a = rk4(m, load, 1e-8, 200000, 5000), b = rk4(m, load, 5e-9, 400000, 10000);
  double rk_u = 0.0, rk_x = 0.0, x_min = 0.0, x_max = 0.0;
  for (std::size_t i = 0; i < a.u.size(); ++i) {
    rk_u = std::max(rk_u, std::abs(a.u[i] - b.u[i]));
    rk_x = std::max(rk_x, std::abs(a.x[i] - b.x[i]));
    x_min = std::min(x_min, b.x[i]);
    x_max = std::max(x_max, b.x[i]);
  }
  EXPECT_LT(rk_u, 1e-11);
  EXPECT_LT(rk_x, 3e-10);
  ASSERT_LT(x_min, 0.0);  // the ball closes on its seat ...
  ASSERT_GT(x_max, 1e-4);  // ... after starting open
  struct Case {
    Integrator integ;
    ContactModel model;
    double tol_u, tol_p, tol_x;
  };
  const Case cases[] = {{Integrator::ArkodeErk, ContactModel::Event, 3e-12, 0.5, 1e-10},
                        {Integrator::ArkodeDirk, ContactModel::Event, 1e-10, 20.0, 5e-9},
                        {Integrator::CvodeBdf, ContactModel::Event, 3e-12, 0.5, 1e-10},
                        {Integrator::CvodeBdf, ContactModel::Lee, 3e-12, 0.5, 1e-10},
                        {Integrator::Ida, ContactModel::Holonomic, 3e-12, 0.5, 1e-10}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(to_string(c.integ)) + " " + to_string(c.model));
    Scene s = plunger_scene(e, load, 0.01, c.integ, c.model);
    s.run.t_end = t_end;
    s.run.output_dt = dt;
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    double eu = 0.0, ep = 0.0, ex = 0.0;
    int n = 0;
    for (const HistoryRow& row : r.rows) {
      const double k = row.t / dt;
      if (std::abs(k - std::round(k)) > 1e-6) continue;
      const std::size_t i = std::size_t(std::lround(k));
      eu = std::max(eu, std::abs(r.col(row, "u_plunger") - b.u.at(i)));
      ep = std::max(ep, std::abs(r.col(row, "force_hla_pressure") - b.p.at(i)));
      ex = std::max(ex, std::abs(r.col(row, "force_hla_ball_lift") - b.x.at(i)));
      ++n;
    }
    EXPECT_GE(n, 40);
    EXPECT_LT(eu, c.tol_u);
    EXPECT_LT(ep, c.tol_p);
    EXPECT_LT(ex, c.tol_x);
    EXPECT_TRUE(r.sum.contract.held) << r.sum.energy_residual;
  }
}

TEST(HlaCheckBall, BadValuesNamedAndTheSceneReadsBack) {
  auto error_of = [&](void (*set)(ElementSpec&)) -> std::string {
    Scene t = plunger_scene(ball_hla(300.0, 0.02, 1e6), 20.0, 0.01, Integrator::CvodeBdf, ContactModel::Event);
    set(t.network.elements[0]);
    try {
      validate(t);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_of([](ElementSpec&) {}), "");
  std::string e = error_of([](ElementSpec& x) { x.check_ball_mass = -1e-5; });
  EXPECT_NE(e.find("key 'elements[0].check_ball_mass' = -1e-05: must be >= 0"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.check_ball_stiffness = -300.0; });
  EXPECT_NE(e.find("key 'elements[0].check_ball_stiffness' = -300: must be >= 0"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.check_seat_diameter = -1e-3; });
  EXPECT_NE(e.find("key 'elements[0].check_seat_diameter' = -0.001: must be >= 0"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.check_ball_damping = -1.0; });
  EXPECT_NE(e.find("key 'elements[0].check_ball_damping' = -1: must be >= 0"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.check_seat_stiffness = 0.0; });
  EXPECT_NE(e.find("key 'elements[0].check_seat_stiffness' = 0: must be > 0 with a check ball"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.check_ball_stiffness = 0.0; });
  EXPECT_NE(e.find("key 'elements[0].check_ball_stiffness' = 0: must be > 0 with a check ball"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.check_seat_diameter = std::nan(""); });
  EXPECT_NE(e.find("elements[0].check_seat_diameter"), std::string::npos) << e;
  // a ball key without a ball: named, not ignored
  e = error_of([](ElementSpec& x) {
    x.check_ball_mass = 0.0;
    x.check_seat_stiffness = 0.0;
    x.check_seat_diameter = 0.0;
    x.check_ball_damping = 0.0;
  });
  EXPECT_NE(e.find("key 'elements[0].check_ball_stiffness' = 300: needs a check ball: elements[0].check_ball_mass > 0"),
            std::string::npos)
      << e;
  // the written scene (its ball keys written because check_ball_mass > 0) reads back equal,
  // and --set reaches a ball key
  const Scene w = plunger_scene(ball_hla(300.0, 0.02, 1e6), 20.0, 0.01, Integrator::CvodeBdf, ContactModel::Event);
  const std::string toml = to_toml(w);
  EXPECT_NE(toml.find("check_seat_stiffness = 1000000"), std::string::npos) << toml;
  EXPECT_TRUE(parse_scene(toml, "w.toml") == w);
  Scene set = w;
  apply_override(set, "elements.hla.check_ball_stiffness=450");
  EXPECT_EQ(set.network.elements[0].check_ball_stiffness, 450.0);
  // an HLA without the ball writes none of the ball's keys
  ElementSpec plain = ball_hla(0.0, 0.0, 0.0);
  plain.check_ball_mass = plain.check_seat_diameter = 0.0;
  plain.check_area = 1e-6;
  const std::string plain_toml =
      to_toml(plunger_scene(plain, 20.0, 0.01, Integrator::CvodeBdf, ContactModel::Event));
  EXPECT_EQ(plain_toml.find("check_ball"), std::string::npos) << plain_toml;
  EXPECT_EQ(plain_toml.find("check_seat"), std::string::npos) << plain_toml;
}

}  // namespace
}  // namespace camdyn
