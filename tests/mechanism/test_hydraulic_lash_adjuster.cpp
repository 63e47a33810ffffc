// The hydraulic lash adjuster (src/mechanism/elements/hydraulic_lash_adjuster.cpp), the first
// element with an internal state (the chamber pressure, carried by every engine as
// y = [q; v; s]), against independent truth:
//   * its pieces: β_eff against the mixture formula written here, ε(p) = ∫ p/β_eff against
//     composite Simpson quadrature, the check valve's flow against the orifice law, and the
//     state Jacobian blocks (∂g/∂x, ∂g/∂ẋ, ∂g/∂s, ∂f/∂s) against difference quotients;
//   * (a) the closed chamber: a mass on it oscillates at f = (1/2π)√(βA²/(V m));
//   * (b) leak-down: under a constant load the plunger sinks at π d c³ F/(12 μ L A²);
//   * (c) pump-up: a lash above the plunger closes in the time the check valve's flow
//     predicts (quasi-static estimate written here);
//   * (d) a mass on an HLA with leak and check valve flowing: the node's motion and the
//     chamber pressure on every method and engine against a fixed-step RK4 of the same
//     ODE written here (Richardson-checked); the energy ledger closes (the run's contract);
//     (IDA included: the states in its DAE);
//   * bad values named (key, value, rule); the written scene reads back equal.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "mechanism/elements/hydraulic_lash_adjuster.hpp"
#include "mechanism/mechanism.hpp"
#include "../network_run_support.hpp"
#include "hla_test_support.hpp"

namespace camdyn {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMass = 0.1;       // kg
constexpr double kArea = 1e-4;      // m²
constexpr double kVolume = 2e-7;    // m³
constexpr double kBeta = 1.5e9;     // Pa
constexpr double kPref = 101325.0;  // Pa

ElementSpec hla(double air, double clearance, double check_area) {
  ElementSpec e;
  e.name = "hla";
  e.kind = ElementKind::HydraulicLashAdjuster;
  e.nodes = {"ground", "plunger"};  // body fixed: travel δ = −u_plunger
  e.area = kArea;
  e.chamber_volume = kVolume;
  e.bulk_modulus = kBeta;
  e.air_fraction = air;
  e.plunger_diameter = 0.011;
  e.leak_clearance = clearance;
  e.leak_length = 0.005;
  e.viscosity = 0.01;
  e.supply_pressure = 3e5;
  e.check_opening_pressure = 1e4;
  e.check_area = check_area;
  e.check_discharge_coefficient = 0.7;
  e.check_transition_pressure = 1000.0;
  e.oil_density = 850.0;
  return e;
}

// A plunger of kMass on an HLA to ground, pushed down by a constant load (a spring
// [plunger, ground] of stiffness 0 and preload `load`), a stop `lash` above it.
Scene plunger_scene(const ElementSpec& e, double load, double lash, Integrator integ, ContactModel model) {
  return camdyn_test::hla_plunger_scene(e, kMass, load, lash, integ, model);
}

// The test's own model (the formulas of the file comment of hydraulic_lash_adjuster.hpp).
struct TestHla {
  ElementSpec e;
  double beta(double p) const {
    const double pa = std::max(e.air_reference_pressure + p, 1e-3 * e.air_reference_pressure);
    const double vl = 1 - e.air_fraction, vg = e.air_fraction * e.air_reference_pressure / pa;
    return (vl + vg) / (vl / e.bulk_modulus + vg / pa);
  }
  double leak(double p) const {
    const double c = e.leak_clearance;
    return kPi * e.plunger_diameter * c * c * c * (p - e.supply_pressure) / (12 * e.viscosity * e.leak_length);
  }
  double check(double p) const {
    const double d = e.supply_pressure - p - e.check_opening_pressure;
    if (d <= 0) return 0.0;
    // C_d A_v √(2|Δ|/ρ) with Δ replaced by Δ²/√(Δ² + Δ_t²) (regularised near 0)
    const double deff = d * d / std::sqrt(d * d + e.check_transition_pressure * e.check_transition_pressure);
    return e.check_discharge_coefficient * e.check_area * std::sqrt(2 * deff / e.oil_density);
  }
  double volume(double delta) const { return e.chamber_volume - e.area * delta; }
};

// u(t), p(t) of m ü = pA + P_hla − F_load (δ = −u), ṗ = β(p)/V(δ)(−A u̇ − Q_leak + Q_check) by
// classic RK4 with step h, sampled every `every` steps.
struct Traj {
  std::vector<double> u, p;
};
Traj rk4(const TestHla& m, double load, double p0, double v0, double h, int steps, int every) {
  auto f = [&](const double* y, double* d) {
    const double u = y[0], v = y[1], p = y[2];
    d[0] = v;
    d[1] = (p * m.e.area + m.e.preload - m.e.stiffness * u - load) / kMass;
    d[2] = m.beta(p) / m.volume(-u) * (-m.e.area * v - m.leak(p) + m.check(p));
  };
  double y[3] = {0.0, v0, p0};
  Traj t{{y[0]}, {y[2]}};
  for (int i = 1; i <= steps; ++i) {
    camdyn_test::rk4_step(f, y, h);
    if (i % every == 0) {
      t.u.push_back(y[0]);
      t.p.push_back(y[2]);
    }
  }
  return t;
}

TEST(HydraulicLashAdjuster, PiecesAgainstTheirFormulas) {
  const TestHla m{hla(0.02, 5e-6, 1e-6)};
  const HydraulicLashAdjuster h(m.e, "hla");
  for (double p : {-9e4, -5e4, 0.0, 1e5, 1e6, 2e7}) {
    EXPECT_NEAR(h.bulk_modulus(p), m.beta(p), 1e-12 * m.beta(p)) << p;
    EXPECT_NEAR(h.leak_flow(p), m.leak(p), 1e-12 * std::abs(m.leak(p)) + 1e-30) << p;
    EXPECT_NEAR(h.check_flow(p), m.check(p), 1e-12 * m.check(p) + 1e-30) << p;
  }
  // ε(p) = ∫₀^p p′/β_eff(p′) dp′ against composite Simpson with 20000 panels (its own error
  // by halving below 1e-9 relative); measured relative difference ≤ 3e-13
  auto simpson = [&](double b, int n) {
    const double hh = b / n;
    double s = 0;
    for (int i = 0; i <= n; ++i) {
      const double x = i * hh, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
      s += w * x / m.beta(x);
    }
    return s * hh / 3;
  };
  for (double p : {-8e4, -2e4, 3e5, 5e6, 2e7}) {
    const double a = simpson(p, 20000), b = simpson(p, 40000);
    EXPECT_LT(std::abs(a - b), 1e-9 * std::abs(b));
    EXPECT_NEAR(h.strain_energy_density(p), b, 1e-9 * std::abs(b)) << p;
  }
  // α = 0: ε = p²/(2β) exactly
  const HydraulicLashAdjuster h0(hla(0.0, 5e-6, 1e-6), "h0");
  EXPECT_NEAR(h0.strain_energy_density(4e6), 4e6 * 4e6 / (2 * kBeta), 1e-14);
}

TEST(HydraulicLashAdjuster, StateJacobianMatchesDifferenceQuotients) {
  ElementSpec spec = hla(0.02, 5e-6, 1e-6);
  spec.stiffness = 2e4;
  spec.preload = 10.0;
  const HydraulicLashAdjuster h(spec, "hla");
  // states on both sides of the check valve's opening (s = p_abs/p_ref)
  for (double p : {-5e4, 2e5, 4e6}) {
    const double x[2] = {1e-5, -3e-5}, xd[2] = {0.02, -0.05};
    const double s = 1 + p / kPref;
    ASSERT_EQ(h.states(), 3);  // pressure, pumped and leaked volume
    const double st[3] = {s, 0.1, 0.2};
    ElementState e;
    e.x = x;
    e.xd = xd;
    e.s = st;
    double dgdx[6], dgdxd[6], dgds[9], dfds[6];
    h.state_jacobian(e, dgdx, dgdxd, dgds, dfds);
    // row l of g (ṡ_l) at (x, ẋ, s₀)
    auto gl = [&](int l, const double* xx, const double* vv, double ss) {
      ElementState f;
      const double sv[3] = {ss, 0.1, 0.2};
      f.x = xx;
      f.xd = vv;
      f.s = sv;
      double r[3];
      h.state_rate(f, r);
      return r[l];
    };
    auto g = [&](const double* xx, const double* vv, double ss) { return gl(0, xx, vv, ss); };
    auto force1 = [&](double ss) {
      ElementState f;
      const double sv[3] = {ss, 0.1, 0.2};
      f.x = x;
      f.xd = xd;
      f.s = sv;
      double out[2];
      h.force(f, out);
      return out[1];
    };
    const double g0 = std::abs(g(x, xd, s));
    for (int i = 0; i < 2; ++i) {
      double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]}, vp[2] = {xd[0], xd[1]}, vm[2] = {xd[0], xd[1]};
      const double dx = 1e-9, dv = 1e-6;
      xp[i] += dx, xm[i] -= dx, vp[i] += dv, vm[i] -= dv;
      EXPECT_NEAR(dgdx[3 * i], (g(xp, xd, s) - g(xm, xd, s)) / (2 * dx), 1e-6 * std::abs(dgdx[3 * i]) + 1e-6 * g0 / 1e-9);
      EXPECT_NEAR(dgdxd[3 * i], (g(x, vp, s) - g(x, vm, s)) / (2 * dv), 1e-6 * std::abs(dgdxd[3 * i]));
    }
    const double ds = 1e-6 * s;
    EXPECT_NEAR(dgds[0], (g(x, xd, s + ds) - g(x, xd, s - ds)) / (2 * ds), 1e-5 * std::abs(dgds[0]) + 1e-9) << p;
    for (int l = 1; l < 3; ++l)  // the volumes' rows: ∂/∂s₀ only
      EXPECT_NEAR(dgds[l], (gl(l, x, xd, s + ds) - gl(l, x, xd, s - ds)) / (2 * ds),
                  1e-5 * std::abs(dgds[l]) + 1e-12) << p << " row " << l;
    EXPECT_NEAR(dfds[1], (force1(s + ds) - force1(s - ds)) / (2 * ds), 1e-8 * std::abs(dfds[1]));
  }
}

// (a) the closed chamber (no leak, no check valve, no air): a mass on it, loaded by F with
// p(0) = F/A (at rest in equilibrium) and kicked with v₀, oscillates as u = (v₀/ω) sin ωt,
// ω² = βA²/(V m). Amplitude 3.7e-9 m, so the chamber's volume change (Aδ/V ≈ 2e-6) leaves
// the frequency within 1e-6. Measured max |u − (v₀/ω) sin ωt| over ten periods / amplitude:
// event on cvode-bdf 1.3e-6, arkode-erk 1.2e-6, arkode-dirk 5.5e-6 (a 1e-4 error in ω would
// show as 6e-3).
TEST(HydraulicLashAdjuster, ClosedChamberStiffnessGivesTheOscillationFrequency) {
  const double F = 100.0, v0 = 1e-4;
  ElementSpec e = hla(0.0, 0.0, 0.0);
  e.initial_pressure = F / kArea;
  const double w = std::sqrt(kBeta * kArea * kArea / (kVolume * kMass));
  const double period = 2 * kPi / w, amp = v0 / w;
  for (Integrator integ : {Integrator::CvodeBdf, Integrator::ArkodeErk, Integrator::ArkodeDirk}) {
    SCOPED_TRACE(to_string(integ));
    Scene s = plunger_scene(e, F, 0.01, integ, ContactModel::Event);
    s.network.nodes[0].initial_velocity = v0;
    s.run.t_end = 10 * period;
    s.run.output_dt = period / 50;
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    double err = 0.0;
    for (const HistoryRow& row : r.rows) err = std::max(err, std::abs(r.col(row, "u_plunger") - amp * std::sin(w * row.t)));
    EXPECT_LT(err / amp, 1e-4);
  }
}

// (b) leak-down: load F, leak only (supply 0), from rest at p(0) = F/A; after the transient
// (relaxation time V/(βG) = 0.019 s) the plunger sinks at π d c³ F/(12 μ L A²) = 3.6e-4 m/s.
// Measured relative error of the sink rate over [0.3, 0.4] s: 8.4e-8 (cvode-bdf, event).
TEST(HydraulicLashAdjuster, LeakDownSinkRateIsTheClosedForm) {
  const double F = 500.0, c = 5e-6;
  ElementSpec e = hla(0.0, c, 0.0);
  e.supply_pressure = 0.0;
  e.initial_pressure = F / kArea;
  Scene s = plunger_scene(e, F, 0.01, Integrator::CvodeBdf, ContactModel::Event);
  s.run.t_end = 0.4;
  s.run.output_dt = 0.1;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  ASSERT_GE(r.rows.size(), 5u);
  const double rate = -(r.col(r.rows[4], "u_plunger") - r.col(r.rows[3], "u_plunger")) / 0.1;
  const double expect = kPi * e.plunger_diameter * c * c * c * F / (12 * e.viscosity * e.leak_length * kArea * kArea);
  EXPECT_NEAR(rate, expect, 1e-6 * expect);
  EXPECT_NEAR(r.col(r.rows[4], "force_hla_pressure"), F / kArea, 1e-6 * F / kArea);
  EXPECT_TRUE(r.sum.contract.held);
  // mass conservation: the leaked volume is the volume the plunger swept (the chamber's
  // pressure is back at F/A), and Summary::elements reports it as the leak-down total;
  // measured relative difference 4.7e-10
  const double swept = -kArea * r.col(r.rows[4], "u_plunger");
  EXPECT_NEAR(r.col(r.rows[4], "force_hla_leaked"), swept, 1e-6 * swept);
  EXPECT_EQ(r.col(r.rows[4], "force_hla_pumped"), 0.0);
  bool found = false;
  for (const ElementResult& er : r.sum.elements)
    if (er.name == "hla_leaked") {
      found = true;
      EXPECT_EQ(er.end, r.col(r.rows[4], "force_hla_leaked"));
    }
  EXPECT_TRUE(found);
}

// (c) pump-up: the plunger spring (preload P, no load) lifts the plunger toward a stop `lash`
// above; the chamber's pressure falls to p = −P/A, the check valve opens (Δ = p_s − p −
// Δp_open) and the plunger rises at (Q_check(p) + G(p_s − p))/A (quasi-static: the mass's
// inertia and the chamber's compliance settle within ~2e-5 s; no air: the chamber's own
// expansion is 7e-8 m of the 0.1 mm lash). The lash closes at t ≈ lash·A/(Q_check +
// Q_leak-in) = 0.0251 s; measured: the contact closes at the row of the estimate (rows every
// t_est/2000: within 5e-4 of it). With 1 % air the chamber's air expands by 2e-5 m at −0.5
// bar and the 0.1 kg plunger oscillates on the soft chamber: not a quasi-static case.
TEST(HydraulicLashAdjuster, PumpUpClosesTheLashInThePredictedTime) {
  const double P = 5.0, lash = 1e-4;
  ElementSpec e = hla(0.0, 5e-6, 2e-8);
  e.preload = P;
  const TestHla m{e};
  const double p = -P / kArea;
  const double rate = (m.check(p) - m.leak(p)) / kArea;
  const double t_est = lash / rate;
  Scene s = plunger_scene(e, 0.0, lash, Integrator::CvodeBdf, ContactModel::Event);
  s.run.t_end = 1.5 * t_est;
  s.run.output_dt = t_est / 2000;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  double t_close = NAN;
  const HistoryRow* closed = nullptr;
  for (const HistoryRow& row : r.rows)
    if (r.col(row, "in_stop") > 0.5) {
      t_close = row.t;
      closed = &row;
      break;
    }
  ASSERT_TRUE(std::isfinite(t_close));
  // the pump-up total at the closing: the volume the plunger's rise swept (A·lash) less the
  // leak's inflow, to the oil's expansion V₀Δp/β = 7e-12 m³ (7e-4 of A·lash); measured
  // relative difference −3.1e-4
  EXPECT_NEAR(r.col(*closed, "force_hla_pumped") - r.col(*closed, "force_hla_leaked"), kArea * lash,
              2e-3 * kArea * lash);
  EXPECT_NEAR(t_close, t_est, 0.005 * t_est) << "estimate " << t_est;
}

struct Case {
  Integrator integ;
  ContactModel model;
  double tol_u, tol_p;
};

// (d) the same ODE by RK4 here: load 20 N, p(0) = 0, supply 3 bar: the plunger falls onto
// the chamber, oscillates against it while the check valve and the leak exchange oil (air
// 1 %). RK4 at h = 2e-8 s and h/2 differ by 2.7e-14 m (Richardson: RK4's own error below
// 3e-14). Measured max |u − u_RK4| (m) / |p − p_RK4| (Pa) over 41 rows, rtol 1e-10
// (amplitudes 1.8e-5 m, 9.8e5 Pa): erk lee 9.9e-14 / 0.0082, event 3.9e-14 / 0.0023,
// penalty 2.2e-14 / 0.0023; dirk lee 1.2e-13 / 0.0031, event 2.4e-14 / 0.0012, penalty
// 5.6e-15 / 2.4e-4; cvode-bdf lee 9.5e-13 / 0.073, event 7.2e-13 / 0.049, holonomic
// 9.5e-13 / 0.073; ida (holonomic, the states in its DAE) 2.0e-13 / 0.018; energy residual
// ≤ 2.4e-12 J (ida 6.2e-13; the contract holds on every one).
TEST(HydraulicLashAdjuster, MassOnHlaMatchesRk4OnEveryMethodAndEngine) {
  ElementSpec e = hla(0.01, 5e-6, 2e-8);
  const double load = 20.0, t_end = 2e-3, dt = 5e-5;
  const TestHla m{e};
  const Traj a = rk4(m, load, 0.0, 0.0, 2e-8, 100000, 2500), b = rk4(m, load, 0.0, 0.0, 1e-8, 200000, 5000);
  double rk_u = 0.0;
  for (std::size_t i = 0; i < a.u.size(); ++i) rk_u = std::max(rk_u, std::abs(a.u[i] - b.u[i]));
  EXPECT_LT(rk_u, 1e-13);
  const Case cases[] = {
      {Integrator::ArkodeErk, ContactModel::Lee, 1e-12, 0.1},    {Integrator::ArkodeErk, ContactModel::Event, 1e-12, 0.1},
      {Integrator::ArkodeErk, ContactModel::Penalty, 1e-12, 0.1}, {Integrator::ArkodeDirk, ContactModel::Lee, 1e-12, 0.1},
      {Integrator::ArkodeDirk, ContactModel::Event, 1e-12, 0.1}, {Integrator::ArkodeDirk, ContactModel::Penalty, 1e-12, 0.1},
      {Integrator::CvodeBdf, ContactModel::Lee, 3e-12, 0.3},     {Integrator::CvodeBdf, ContactModel::Event, 3e-12, 0.3},
      {Integrator::CvodeBdf, ContactModel::Holonomic, 3e-12, 0.3}, {Integrator::Ida, ContactModel::Holonomic, 3e-12, 0.3},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(to_string(c.integ)) + " " + to_string(c.model));
    Scene s = plunger_scene(e, load, 0.01, c.integ, c.model);
    s.run.t_end = t_end;
    s.run.output_dt = dt;
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    double eu = 0.0, ep = 0.0;
    int n = 0;
    for (const HistoryRow& row : r.rows) {
      const double k = row.t / dt;
      if (std::abs(k - std::round(k)) > 1e-6) continue;
      const std::size_t i = std::size_t(std::lround(k));
      eu = std::max(eu, std::abs(r.col(row, "u_plunger") - b.u.at(i)));
      ep = std::max(ep, std::abs(r.col(row, "force_hla_pressure") - b.p.at(i)));
      ++n;
    }
    EXPECT_GE(n, 40);
    EXPECT_LT(eu, c.tol_u);
    EXPECT_LT(ep, c.tol_p);
    EXPECT_TRUE(r.sum.contract.held) << r.sum.energy_residual;
  }
}

TEST(HydraulicLashAdjuster, BadValuesNamed) {
  auto error_of = [&](void (*set)(ElementSpec&)) -> std::string {
    Scene t = plunger_scene(hla(0.01, 5e-6, 2e-8), 20.0, 0.01, Integrator::CvodeBdf, ContactModel::Event);
    set(t.network.elements[0]);
    try {
      validate(t);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  std::string e = error_of([](ElementSpec& x) { x.leak_clearance = -1e-6; });
  EXPECT_NE(e.find("elements[0].leak_clearance"), std::string::npos) << e;
  EXPECT_NE(e.find("-1e-06"), std::string::npos) << e;
  EXPECT_NE(e.find(">= 0"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.chamber_volume = 0.0; });
  EXPECT_NE(e.find("elements[0].chamber_volume"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.viscosity = -0.01; });
  EXPECT_NE(e.find("elements[0].viscosity"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.air_fraction = 1.0; });
  EXPECT_NE(e.find("elements[0].air_fraction"), std::string::npos) << e;
  EXPECT_NE(e.find("< 1"), std::string::npos) << e;
  e = error_of([](ElementSpec& x) { x.air_fraction = -0.1; });
  EXPECT_NE(e.find("elements[0].air_fraction"), std::string::npos) << e;
  EXPECT_EQ(error_of([](ElementSpec&) {}), "");
  // the written scene reads back equal
  const Scene w = plunger_scene(hla(0.01, 5e-6, 2e-8), 20.0, 0.01, Integrator::CvodeBdf, ContactModel::Event);
  EXPECT_TRUE(parse_scene(to_toml(w), "w.toml").network == w.network);
}

}  // namespace
}  // namespace camdyn
