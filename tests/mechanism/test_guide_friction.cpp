// Coulomb friction in a guide (scene type guide_friction, regularised −μN tanh(v/v_s);
// src/mechanism/elements/guide_friction.hpp) against independent truth:
//   * a block sliding to rest on every method and engine: its velocity against the exact
//     solution of the regularised law m v̇ = −μN tanh(v/v_s),
//       v(t) = v_s asinh(sinh(v₀/v_s) e^{−a t / v_s}),  a = μN/m,
//     and the regularisation's error against Coulomb's closed forms (stop time v₀/a,
//     distance v₀²/(2a)): the block travels v₀²/(2a) + π² v_s²/(12a) in all (∫₀^∞ u(coth u − 1)
//     du = π²/12), its velocity at the Coulomb stop time is v_s·asinh(½), then decays with the
//     time constant v_s/a;
//   * the energy ledger: dissipated = ½ m v₀² (the kinetic energy it had), and μN·distance
//     exceeds it by exactly μN·π² v_s²/(12a) (the regularised stick phase);
//   * the mechanism's tangent ∂a/∂v against difference quotients (the implicit engines'
//     Jacobian);
//   * bad keys: SceneError naming key, value and rule.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "mechanism/mechanism.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

constexpr double kM = 0.1, kMu = 0.3, kN = 0.981, kV0 = 1.0, kVs = 1e-3;
constexpr double kA = kMu * kN / kM;  // deceleration μN/m [m/s²]

Scene sliding_block(ContactModel model, Integrator integ) {
  Scene s = default_scene();
  s.title = "block sliding to rest";
  s.follower.kind = FollowerKind::Network;
  NodeSpec b;
  b.name = "block";
  b.mass = kM;
  b.initial_velocity = kV0;
  s.network.nodes = {b};
  ElementSpec f;
  f.name = "guide";
  f.kind = ElementKind::GuideFriction;
  f.nodes = {"block", "ground"};
  f.friction_coefficient = kMu;
  f.normal_load = kN;
  f.velocity_scale = kVs;
  s.network.elements = {f};
  ContactPointSpec stop;  // never reached: the block stops after 0.17 m
  stop.name = "end";
  stop.kind = ContactPointKind::Stop;
  stop.nodes = {"block"};
  stop.side = StopSide::Above;
  stop.clearance = 10.0;
  s.network.contacts = {stop};
  s.contact.model = model;
  s.solver.integrator = integ;
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-13;
  s.run.t_end = 0.4;
  s.run.output_dt = 1e-3;
  s.run.element_forces = true;
  return s;
}

// The exact velocity of the regularised law (in logs: sinh(v₀/v_s) overflows).
double exact_velocity(double t) {
  const double u0 = kV0 / kVs;
  const double L = u0 + std::log1p(-std::exp(-2 * u0)) - std::log(2.0) - kA * t / kVs;  // ln y
  const double as = L > 20 ? L + std::log(2.0) : std::asinh(std::exp(L));
  return kVs * as;
}

struct Case {
  ContactModel model;
  Integrator integ;
};

TEST(GuideFriction, BlockSlidesToRestAsTheClosedForms) {
  const double t_stop = kV0 / kA, d_coulomb = kV0 * kV0 / (2 * kA);
  const double d_excess = M_PI * M_PI * kVs * kVs / (12 * kA);  // 2.795e-7 m
  const Case cases[] = {{ContactModel::Lee, Integrator::ArkodeErk},     {ContactModel::Event, Integrator::ArkodeDirk},
                        {ContactModel::Penalty, Integrator::CvodeBdf}, {ContactModel::Lee, Integrator::CvodeBdf},
                        {ContactModel::Lee, Integrator::ArkodeDirk},   {ContactModel::Event, Integrator::ArkodeErk}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(to_string(c.integ)) + " " + to_string(c.model));
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(sliding_block(c.model, c.integ));
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    double ev = 0.0;
    for (const HistoryRow& row : r.rows) {
      ev = std::max(ev, std::abs(r.col(row, "v_block") - exact_velocity(row.t)));
      // the force column: −μN tanh(v/v_s)
      EXPECT_NEAR(r.col(row, "force_guide"), -kMu * kN * std::tanh(r.col(row, "v_block") / kVs), 1e-9);
    }
    // measured max |v − v_exact| over 401 rows: ≤ 1.6e-10 m/s (v₀ = 1 m/s) on every case
    EXPECT_LT(ev, 1e-6);
    const HistoryRow& end = r.rows.back();
    const double x_end = r.col(end, "u_block");
    // after t_stop + 0.06 s = 176 time constants v_s/a the block is at rest: its distance is
    // Coulomb's plus the regularisation's π² v_s²/(12a) = 2.8e-7 m (measured |Δ| ≤ 3.4e-13 m)
    EXPECT_NEAR(x_end, d_coulomb + d_excess, 2e-9);
    EXPECT_GT(x_end - d_coulomb, 0.9 * d_excess);
    // at the Coulomb stop time the regularised block still moves at v_s·asinh(½)
    for (const HistoryRow& row : r.rows)
      if (std::abs(row.t - 0.34) < 1e-9) {
        const double v = exact_velocity(0.34);
        EXPECT_NEAR(r.col(row, "v_block"), v, 1e-7);
        EXPECT_NEAR(exact_velocity(t_stop), kVs * std::asinh(0.5), 1e-12);
      }
    // energy: all the kinetic energy dissipated by the friction (ledger), μN·distance
    // larger by μN·π² v_s²/(12a) = 8.2e-8 J of 0.05 J (measured |ΔD| ≤ 4.1e-14 J)
    const double E0 = 0.5 * kM * kV0 * kV0;
    EXPECT_NEAR(end.dissipated, E0, 1e-9);
    EXPECT_NEAR(kMu * kN * x_end - end.dissipated, kMu * kN * d_excess, 1e-9);
    EXPECT_LT(r.sum.energy_residual, 1e-8);
  }
}

TEST(GuideFriction, TangentMatchesDifferenceQuotients) {
  Scene s = sliding_block(ContactModel::Event, Integrator::ArkodeDirk);
  resolve_defaults(s);
  validate(s);
  const Mechanism mech(s);
  ASSERT_FALSE(mech.linear());
  Eigen::VectorXd q(1), F;
  for (double v0 : {0.0, 0.3 * kVs, -2 * kVs, 0.5}) {
    Eigen::VectorXd v(1), ap(1), am(1);
    v << v0;
    q << 0.01;
    Eigen::MatrixXd dq, dv;
    ASSERT_TRUE(mech.acceleration_jacobian(0.0, q.data(), v.data(), dq, dv));
    const double e = 1e-9;
    Eigen::VectorXd vp = v, vm = v;
    vp[0] += e, vm[0] -= e;
    mech.acceleration(0.0, q.data(), vp.data(), F, ap.data());
    mech.acceleration(0.0, q.data(), vm.data(), F, am.data());
    // measured relative difference < 1e-6; at v = 0 the rate is μN/(m v_s) = 2943 1/s
    EXPECT_NEAR(dv(0, 0), (ap[0] - am[0]) / (2 * e), 1e-5 * kA / kVs + 1e-6) << v0;
    EXPECT_EQ(dq(0, 0), 0.0);
  }
}

TEST(GuideFriction, BadKeysNameKeyValueAndRule) {
  auto expect_error = [](Scene bad, const std::string& key, const std::string& rule_part) {
    try {
      validate(bad);
      ADD_FAILURE() << "no error for " << key;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), key);
      EXPECT_NE(e.rule().find(rule_part), std::string::npos) << e.rule();
    }
  };
  const Scene s = sliding_block(ContactModel::Event, Integrator::ArkodeDirk);
  Scene b = s;
  b.network.elements[0].velocity_scale = 0.0;
  expect_error(b, "elements[0].velocity_scale", "must be > 0");
  b = s;
  b.network.elements[0].friction_coefficient = -0.1;
  expect_error(b, "elements[0].friction_coefficient", "must be >= 0");
  b = s;
  b.network.elements[0].normal_load = NAN;
  expect_error(b, "elements[0].normal_load", "finite");
}

}  // namespace
}  // namespace camdyn
