// The first Newton iteration after a setup of a system whose only nonlinearity is its elements'
// force (SparseNewton::element_force): SparseNewtonSolver::next_correction against the next
// Newton correction computed densely in the test, and DIRK trial steps of a Duffing oscillator
// written as a mechanism with an element, against RK4.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/ode_engine.hpp"
#include "engine/sparse_newton.hpp"

namespace camdyn {
namespace {

SparseMatrix sparse(const Eigen::MatrixXd& A) {
  SparseMatrix S = A.sparseView(0.0, 0.0);
  S.makeCompressed();
  return S;
}

// Two masses, linear M, C, K, an element between them r_e = [−g, g] with
// g = β(q₀ − q₁)³ + c(v₀ − v₁)³, and the contact on mass 0 held at the acceleration level:
// f(y) = [v; P M⁻¹(−Kq − Cv + r_e)], P = I − M⁻¹Tᵀ(TM⁻¹Tᵀ)⁻¹T.
struct TwoMass {
  Eigen::MatrixXd M{{2.0, 0.0}, {0.0, 3.0}}, K{{5e3, -1e3}, {-1e3, 2e3}}, C{{1.0, 0.0}, {0.0, 2.0}};
  Eigen::MatrixXd T{{1.0, 0.0}};
  double beta = 4e6, c = 30.0;
  SparseMatrix Ms = sparse(M), Ks = sparse(K), Cs = sparse(C), full = sparse(Eigen::MatrixXd::Ones(2, 2));
  std::vector<int> held{0};

  Eigen::VectorXd element(const Eigen::VectorXd& y) const {
    const double d = y[0] - y[1], dv = y[2] - y[3];
    const double g = beta * d * d * d + c * dv * dv * dv;
    Eigen::VectorXd e(2);
    e << -g, g;
    return e;
  }
  Eigen::MatrixXd P() const {
    const Eigen::MatrixXd Mi = M.inverse();
    return Eigen::MatrixXd::Identity(2, 2) - Mi * T.transpose() * (T * Mi * T.transpose()).inverse() * T;
  }
  Eigen::VectorXd f(const Eigen::VectorXd& y) const {
    const Eigen::VectorXd r = -K * y.head(2) - C * y.tail(2) + element(y);
    const Eigen::VectorXd a = P() * (M.inverse() * r);
    Eigen::VectorXd out(4);
    out << y.tail(2), a;
    return out;
  }
  // J at y: the element's tangent K_e = −∂r_e/∂q, C_e = −∂r_e/∂q̇ with the linear part
  Eigen::MatrixXd J(const Eigen::VectorXd& y) const {
    const double d = y[0] - y[1], dv = y[2] - y[3];
    const Eigen::Matrix2d E{{1.0, -1.0}, {-1.0, 1.0}};
    const Eigen::MatrixXd Ke = 3.0 * beta * d * d * E, Ce = 3.0 * c * dv * dv * E;
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(4, 4);
    out.block(0, 2, 2, 2).setIdentity();
    out.block(2, 0, 2, 2) = P() * M.inverse() * (-K - Ke);
    out.block(2, 2, 2, 2) = P() * M.inverse() * (-C - Ce);
    return out;
  }
  SparseNewton newton() const {
    SparseNewton sn;
    sn.M = &Ms;
    sn.K = &Ks;
    sn.C = &Cs;
    sn.T = T;
    sn.held = &held;
    sn.Ke_pattern = &full;
    sn.Ce_pattern = &full;
    sn.element_tangent = [this](double, const double* y, SparseMatrix& Ke, SparseMatrix& Ce) {
      const double d = y[0] - y[1], dv = y[2] - y[3];
      const double k = 3.0 * beta * d * d, cc = 3.0 * c * dv * dv;
      Ke.coeffRef(0, 0) = k, Ke.coeffRef(1, 1) = k, Ke.coeffRef(0, 1) = -k, Ke.coeffRef(1, 0) = -k;
      Ce.coeffRef(0, 0) = cc, Ce.coeffRef(1, 1) = cc, Ce.coeffRef(0, 1) = -cc, Ce.coeffRef(1, 0) = -cc;
    };
    sn.element_force = [this](double, const double* y, double* r) {
      const Eigen::VectorXd e = element(Eigen::Map<const Eigen::VectorXd>(y, 4));
      r[0] += e[0];
      r[1] += e[1];
    };
    return sn;
  }
};

// The stage equation G(z) = z − γf(z) − b solved by Newton with the matrix I − γJ(y_s) of a
// setup at y_s: from z₀ the correction dz = −(I − γJ)⁻¹G(z₀), then δ₂ = −(I − γJ)⁻¹G(z₀ + dz),
// which next_correction(z₀, dz) must give without evaluating G. Measured: 7e-17 off, |δ₂| 0.01.
TEST(NewtonPrediction, NextCorrectionIsTheNextNewtonCorrection) {
  const TwoMass sys;
  const SparseNewton sn = sys.newton();
  EngineStats stats;
  detail::SparseNewtonSolver solver(sn, true, stats);
  ASSERT_TRUE(solver.predicts_next_correction());
  const double gamma = 2e-3;
  const Eigen::Vector4d ys(1e-3, -2e-3, 0.4, -0.3);
  solver.prepare(0.0, ys.data(), gamma);
  solver.setup();
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(4, 4) - gamma * sys.J(ys);
  const Eigen::Vector4d b(2e-4, -1e-4, 0.05, 0.02);
  auto G = [&](const Eigen::VectorXd& z) -> Eigen::VectorXd { return z - gamma * sys.f(z) - b; };
  for (const Eigen::Vector4d& z0 : {Eigen::Vector4d(ys), Eigen::Vector4d(ys + Eigen::Vector4d(3e-4, 1e-4, -0.05, 0.1))}) {
    const Eigen::VectorXd dz = -A.partialPivLu().solve(G(z0));
    const Eigen::VectorXd next = -A.partialPivLu().solve(G(z0 + dz));
    Eigen::VectorXd predicted(4);
    solver.next_correction(0.0, z0.data(), dz.data(), predicted.data());
    std::printf("  |δ₂| %.3g, |dz| %.3g, prediction off by %.3g\n", next.norm(), dz.norm(),
                (predicted - next).norm());
    EXPECT_GT(next.norm(), 1e-8 * dz.norm());  // a nonlinear step: the next correction is not nothing
    EXPECT_LT((predicted - next).norm(), 1e-10 * next.norm());
    // the held contact's velocity stays on its row: T δ₂,v = 0
    EXPECT_LT(std::abs(sys.T.row(0).dot(predicted.tail(2))), 1e-12 * next.norm());
  }
}

// A Duffing oscillator ẍ = −ω²x − βx³ as a one-mass mechanism whose cubic is an element:
// DIRK trial steps with the predicted first iteration against RK4 (4000 substeps), and the
// iterations they take. Measured: error / estimate 0.05 (mild, βx² = 7.2e-5 ω², rtol 1e-8) in
// 5 iterations per step (one per stage); strongly nonlinear (βx² = 0.72 ω², rtol 1e-10) the
// prediction refuses and the stages iterate (11 per step), error / estimate 0.03.
double duffing_steps(double beta, double rtol, double* iterations_per_step) {
  constexpr double kW = 50.0;
  static const SparseMatrix M = sparse(Eigen::MatrixXd::Ones(1, 1)), K = sparse(kW * kW * Eigen::MatrixXd::Ones(1, 1)),
                            pattern = sparse(Eigen::MatrixXd::Ones(1, 1));
  auto sn = std::make_shared<SparseNewton>();
  sn->M = &M;
  sn->K = &K;
  sn->T = Eigen::MatrixXd(0, 1);
  sn->Ke_pattern = &pattern;
  sn->element_tangent = [beta](double, const double* y, SparseMatrix& Ke, SparseMatrix&) {
    Ke.coeffRef(0, 0) = 3.0 * beta * y[0] * y[0];
  };
  sn->element_force = [beta](double, const double* y, double* r) { r[0] -= beta * y[0] * y[0] * y[0]; };
  OdeSystem s;
  s.size = 2;
  s.rhs = [beta](double, const double* y, double* yd) {
    yd[0] = y[1];
    yd[1] = -kW * kW * y[0] - beta * y[0] * y[0] * y[0];
  };
  s.newton = sn;
  SolverSpec spec;
  spec.integrator = Integrator::ArkodeDirk;
  spec.rtol = rtol;
  spec.atol = 1e-2 * rtol;
  auto e = OdeEngine::make(Integrator::ArkodeDirk, spec, s, true);
  auto rk4 = [&](Eigen::VectorXd y, double h) {
    const int n = 4000;
    const double d = h / n;
    Eigen::Vector2d k1, k2, k3, k4, z;
    for (int i = 0; i < n; ++i) {
      s.rhs(0.0, y.data(), k1.data());
      z = y + 0.5 * d * k1;
      s.rhs(0.0, z.data(), k2.data());
      z = y + 0.5 * d * k2;
      s.rhs(0.0, z.data(), k3.data());
      z = y + d * k3;
      s.rhs(0.0, z.data(), k4.data());
      y += d / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return y;
  };
  const Eigen::VectorXd y = Eigen::Vector2d(0.6, -20.0);
  Eigen::VectorXd y1;
  long steps = 0;
  double worst = 0.0;
  for (double h : {0.01 / kW, 0.005 / kW, 0.0025 / kW, 0.00125 / kW}) {
    e->step(0.1, y, h, y1);
    ++steps;
    const Eigen::VectorXd& le = e->local_error();
    const double est = std::hypot(le[0], le[1] / kW);
    const Eigen::VectorXd ref = rk4(y, h);
    worst = std::max(worst, std::hypot(y1[0] - ref[0], (y1[1] - ref[1]) / kW) / (est + 1e-14));
  }
  *iterations_per_step = double(e->stats().nonlin_iters) / double(steps);
  return worst;
}

TEST(NewtonPrediction, DirkTrialStepsAsAccurateAsTheirEstimate) {
  double strong = 0.0, mild = 0.0;
  const double e_strong = duffing_steps(2.0 * 2500.0, 1e-10, &strong);
  const double e_mild = duffing_steps(2e-4 * 2500.0, 1e-8, &mild);
  std::printf("  error / estimate: %.3g (strong), %.3g (mild); Newton iterations per step: %.2f, %.2f\n", e_strong,
              e_mild, strong, mild);
  EXPECT_LT(e_strong, 1.0);
  EXPECT_LT(e_mild, 1.0);
  EXPECT_LE(mild, 5.0);   // one iteration per stage of SDIRK 5(4)
  EXPECT_GT(strong, 5.0);  // the prediction refuses: the stages iterate
}

}  // namespace
}  // namespace camdyn
