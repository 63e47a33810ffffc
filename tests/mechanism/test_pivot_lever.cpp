// A lever on a moving pivot (issue 39 item 2): `lever` with nodes = [input, output, pivot],
// q_output = ratio·q_input + (1 − ratio)·q_pivot, ratio = output arm / input arm (signed
// distances from the pivot along the lever, small rotations). A finger follower: pivot at 0
// (on a lash adjuster spring), roller (input) at 20 mm, valve (output) at 40 mm: ratio 2.
// Against closed forms:
//   * the reduced M, K, f₀ and the node map L against their hand derivation
//     (M = Lᵀ diag(m) L, K = Lᵀ K_f L with L = [1 0; 0 1; a b]);
//   * static force balance: the roller held by a stop, the pivot's spring balancing the
//     valve spring's moment — stop force a·F_v and pivot force (a − 1)·F_v (moments about
//     the pivot and the vertical balance of the finger), pivot and valve at the closed-form
//     static position when the pivot spring's preload does not balance;
//   * bad input: ratio 1 with a pivot, four nodes, a pivot on ground, a cycle through a pivot.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "camdyn/simulator.hpp"
#include "mechanism/mechanism.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

constexpr double kLi = 0.020, kLo = 0.040, kA = kLo / kLi, kB = 1.0 - kA;  // a = 2, b = −1
constexpr double kMr = 0.03, kMp = 0.02, kMv = 0.05;                      // kg
constexpr double kKv = 3e4, kPv = 250.0, kKh = 2e5, kCh = 60.0;          // N/m, N, N/m, N·s/m

Scene finger(double pivot_preload) {
  Scene s = default_scene();
  s.title = "finger on a moving pivot";
  s.follower.kind = FollowerKind::Network;
  auto node = [](const char* name, double m) {
    NodeSpec n;
    n.name = name;
    n.mass = m;
    return n;
  };
  s.network.nodes = {node("roller", kMr), node("pivot", kMp), node("valve", kMv)};
  ElementSpec lever;
  lever.name = "finger";
  lever.kind = ElementKind::Lever;
  lever.nodes = {"roller", "valve", "pivot"};
  lever.ratio = kA;
  ElementSpec vs;
  vs.name = "valve_spring";
  vs.kind = ElementKind::Spring;
  vs.nodes = {"valve", "ground"};
  vs.stiffness = kKv;
  vs.preload = kPv;
  ElementSpec hla;
  hla.name = "hla";
  hla.kind = ElementKind::Spring;
  hla.nodes = {"pivot", "ground"};
  hla.stiffness = kKh;
  hla.preload = pivot_preload;
  hla.damping = kCh;
  s.network.elements = {lever, vs, hla};
  ContactPointSpec stop;
  stop.name = "roller_stop";
  stop.kind = ContactPointKind::Stop;
  stop.nodes = {"roller"};
  stop.side = StopSide::Below;
  s.network.contacts = {stop};
  s.contact.model = ContactModel::Event;
  s.solver.integrator = Integrator::ArkodeDirk;
  s.solver.rtol = 1e-9;
  s.solver.atol = 1e-13;
  s.run.t_end = 0.15;
  s.run.output_dt = 0.005;
  s.run.element_forces = true;
  return s;
}

TEST(PivotLever, ReducedMatricesMatchTheHandDerivation) {
  Scene s = finger(kPv);
  resolve_defaults(s);
  validate(s);
  const Mechanism mech(s);
  ASSERT_EQ(mech.n(), 2);  // roller, pivot (the valve is the lever's output)
  Eigen::Matrix2d M, K;
  M << kMr + kA * kA * kMv, kA * kB * kMv, kA * kB * kMv, kMp + kB * kB * kMv;
  K << kA * kA * kKv, kA * kB * kKv, kA * kB * kKv, kKh + kB * kB * kKv;
  const Eigen::Vector2d f0(-kA * kPv, -kB * kPv - kPv);
  EXPECT_LT((Eigen::MatrixXd(mech.M()) - M).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((Eigen::MatrixXd(mech.K()) - K).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((mech.f0() - f0).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::MatrixXd L(mech.L());
  EXPECT_EQ(L(2, 0), kA);  // valve = a·roller + b·pivot
  EXPECT_EQ(L(2, 1), kB);
}

TEST(PivotLever, StaticForceBalanceAboutThePivot) {
  // (1) the pivot spring's preload balances the valve spring through the finger: nothing
  // moves, the stop carries a·F_v and the pivot spring (a − 1)·F_v = −b·F_v.
  {
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(finger(-kB * kPv));
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    const HistoryRow& last = r.rows.back();
    EXPECT_NEAR(r.col(last, "F_roller_stop"), kA * kPv, 1e-9);  // 500 N
    EXPECT_NEAR(r.col(last, "force_hla"), -kB * kPv, 1e-9);     // 250 N
    EXPECT_NEAR(r.col(last, "u_pivot"), 0.0, 1e-15);
  }
  // (2) a weaker pivot spring preload: the pivot settles where the valve spring's moment
  // and the pivot spring balance with the roller held, q_p = (−b P_v − P_h)/(k_h + b² k_v),
  // valve at b·q_p; the stop then carries a·F_v(q_v) and the pivot spring −b·F_v(q_v)
  // (after 0.15 s at ζ ≈ 0.24 of the pivot's mode; measured |Δq| 9e-18 m, |ΔF| ≤ 3e-12 N).
  const double Ph = 100.0;
  const double qp = (-kB * kPv - Ph) / (kKh + kB * kB * kKv), qv = kB * qp;
  const double Fv = kPv + kKv * qv;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(finger(Ph));
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  const HistoryRow& last = r.rows.back();
  EXPECT_NEAR(r.col(last, "u_pivot"), qp, 1e-12);
  EXPECT_NEAR(r.col(last, "u_valve"), qv, 1e-12);
  EXPECT_NEAR(r.col(last, "force_valve_spring"), Fv, 1e-6);
  EXPECT_NEAR(r.col(last, "F_roller_stop"), kA * Fv, 1e-6);
  EXPECT_NEAR(r.col(last, "force_hla"), -kB * Fv, 1e-6);
  // the kinematic tie at every row
  for (const HistoryRow& row : r.rows)
    EXPECT_NEAR(r.col(row, "u_valve"), kA * r.col(row, "u_roller") + kB * r.col(row, "u_pivot"), 1e-15);
}

TEST(PivotLever, BadLeversNameKeyAndRule) {
  auto error_of = [](Scene s) -> std::string {
    try {
      resolve_defaults(s);
      validate(s);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  Scene s = finger(kPv);
  s.network.elements[0].ratio = 1.0;
  std::string e = error_of(s);
  EXPECT_NE(e.find("elements[0].ratio"), std::string::npos) << e;
  EXPECT_NE(e.find("!= 1"), std::string::npos) << e;
  s = finger(kPv);
  s.network.elements[0].nodes.push_back("ground");
  e = error_of(s);
  EXPECT_NE(e.find("elements[0].nodes"), std::string::npos) << e;
  EXPECT_NE(e.find("3 [input, output, pivot]"), std::string::npos) << e;
  s = finger(kPv);
  s.network.elements[0].nodes[2] = "ground";
  e = error_of(s);
  EXPECT_NE(e.find("elements[0].nodes[2]"), std::string::npos) << e;
  // a second lever whose output is the first one's pivot, fed by the first one's output
  s = finger(kPv);
  ElementSpec back;
  back.kind = ElementKind::Lever;
  back.nodes = {"valve", "pivot"};
  back.ratio = 0.5;
  s.network.elements.push_back(back);
  e = error_of(s);
  EXPECT_NE(e.find("cycle"), std::string::npos) << e;
  EXPECT_EQ(error_of(finger(kPv)), "");
}

}  // namespace
}  // namespace camdyn
