// camdyn (private) — the Newton systems of a mechanism's implicit engines (ode_engine.cpp)
// through the sparse Schur complement (SparseNewton in ode_engine.hpp has the maths).
//
// S's pattern is the union of M, C, K, the elements' tangent and, when F depends on the
// state, Tᵀ T; it is fixed at construction, so KLU analyses it once per run. setup() refills
// S's values in O(nnz) and refactors only when γ, the contact derivatives or the elements'
// tangent changed; solve() costs one sparse
// product with M and K, one KLU solve, and for k held contacts a k × k bordering
// (Z = S⁻¹T_Aᵀ: k solves per factorisation and held set).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "engine/ode_engine.hpp"
#include "engine/sparse_lu.hpp"

namespace camdyn {
namespace detail {

class SparseNewtonSolver {
 public:
  SparseNewtonSolver(const SparseNewton& sys, bool dense, EngineStats& stats);
  /// From the integrator's linear-system function: the system I − γJ at (t, y).
  void prepare(double t, const double* y, double gamma);
  /// Factorise S (if γ or the contact derivatives changed since the last time).
  void setup();
  /// x = (I − γJ)⁻¹ b in place (length 2n + states).
  void solve(double* b);
  /// True if next_correction() applies: SparseNewton::element_force is set and f has no
  /// other dependence on y beyond the factored matrix (no contact derivatives, state-dependent
  /// rows or internal states).
  bool predicts_next_correction() const;
  /// γ of the factored matrix.
  double gamma() const { return gamma_f_; }
  /// The Newton correction that follows the correction dz from the iterate z0 (the residual
  /// evaluated at z0, 2n entries each) of a stage equation z − γf(t, z) = data, with the
  /// factored matrix's γ and J: x = (I − γJ)⁻¹ γ [0; P M⁻¹ m] (x: 2n entries), where
  /// m = r_e(z0 + dz) − r_e(z0) + K_e dz_q + C_e dz_v is the elements' force change that J
  /// (its tangent K_e, C_e) does not carry and P the projection of the held contacts. This is
  /// the next Newton iteration's correction up to rounding, at two element-force evaluations
  /// and one solve instead of a right-hand side, a solve and the iteration's vector updates.
  /// @pre predicts_next_correction(), setup() called.
  void next_correction(double t, const double* z0, const double* dz, double* x);

 private:
  const SparseNewton& sys_;
  long n_;
  int m_;
  EngineStats& stats_;
  SparseLu lu_;
  SparseMatrix S_;
  // positions in S_ of the entries of M, K, C and of the contacts' tⱼᵀtⱼ (row, col pairs)
  std::vector<long> pos_m_, pos_k_, pos_c_;
  struct Outer { long pos; int j; long a, b; };  // S(pos) += coefficient_j · T(j, a) T(j, b)
  std::vector<Outer> outer_;
  // the contact rows: prepared (T_) and factorised (T_f_); state-dependent rows' stiffness
  // (Kr_, Kr_f_) and its positions in S_
  Eigen::MatrixXd T_, T_f_;
  SparseMatrix Kr_, Kr_f_;
  std::vector<long> pos_kr_;
  Eigen::VectorXd dFdg_, dFdgd_, dFdg_f_, dFdgd_f_;  // prepared / factorised
  // the elements' tangent: prepared (Ke_, Ce_) and factorised (Ke_f_, Ce_f_); positions in S_
  SparseMatrix Ke_, Ce_, Ke_f_, Ce_f_;
  std::vector<long> pos_ke_, pos_ce_;
  // the elements' internal states: prepared blocks (Rs_, Gq_, Gv_, Gs_), factorised ones
  // (…_f_), H = (I − γG_s)⁻¹ and the condensed term D = R_s H (γG_q + G_v) of the last setup
  int ns_ = 0;
  SparseMatrix Rs_, Gq_, Gv_, Rs_f_, Gq_f_, Gv_f_, D_;
  Eigen::MatrixXd Gs_, Gs_f_, H_;
  Eigen::VectorXd w_;
  double gamma_ = 0, gamma_f_ = -1;
  bool factored_ = false;
  Eigen::VectorXd rhs_, r_;
  Eigen::VectorXd z1_, re_;  // next_correction's iterate and force change
  // rhs_ = S⁻¹(…) bordered so that T_A x_v = T_A b_v (bv: b's velocity part; null: zero)
  void border_held(const double* bv);
  // bordering for the held set
  std::vector<int> held_f_;
  Eigen::MatrixXd Z_;
  Eigen::PartialPivLU<Eigen::MatrixXd> G_;
};

}  // namespace detail
}  // namespace camdyn
