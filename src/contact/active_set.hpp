// camdyn (private) — the active set of several unilateral contacts by complementarity
// (issue 28): dependent contact sets (two contacts on one node, linearly dependent rows,
// W = T M⁻¹ Tᵀ singular) at the acceleration and the impact level.
//
//   Find F ≥ 0 with w = W F + b ≥ 0 and Fᵀw = 0 (a linear complementarity problem):
//     acceleration level: w = g̈ of the closed contacts, b = T a_free − Ẍ_C·[cam]
//     (an open-going contact carries no force, a force-carrying one does not accelerate
//     away, and no contact pulls);
//     impact level: w = ġ⁺ − target, b = ġ⁻ − target (target −e ġ⁻ or 0).
//   W is symmetric positive semidefinite, so w (the motion) is unique while F need not be:
//   redundant contacts (equal or dependent rows) get the minimal-norm split.
//
//   Solution: the equality solve on the whole set first (W_SS F = −b by a complete
//   orthogonal decomposition, the minimal-norm least-squares solution); if it is
//   consistent and F ≥ 0 that is the answer (the usual case: unchanged results). Otherwise
//   every support P ⊆ S is tried (k ≤ kMaxEnumerated contacts; more: a greedy active-set
//   pass), each with its minimal-norm F_P: the valid ones (consistent, F_P ≥ 0, w ≥ 0
//   off P) share one motion, and the smallest ‖F‖ wins. None valid: the contacts jam (a
//   node pushed by a cam into a stop): no bounded force holds them.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace camdyn {
namespace detail {

struct ContactLcpResult {
  Eigen::VectorXd F;  ///< forces (impulses), ≥ 0
  Eigen::VectorXd w;  ///< W F + b: the gap accelerations (velocity changes), ≥ 0 up to round-off
  bool ok = false;    ///< false: no bounded solution (the contacts jam)
};

/// Solve the LCP F ≥ 0, W F + b ≥ 0, Fᵀ(W F + b) = 0 with the smallest ‖F‖.
/// @pre W square symmetric positive semidefinite, b of its size.
ContactLcpResult solve_contact_lcp(const Eigen::MatrixXd& W, const Eigen::VectorXd& b);

/// The LCP of one contact (k = 1), without allocations, with solve_contact_lcp's
/// arithmetic (which calls it for k = 1): F ≥ 0, w = W F + b; returns false if the contact
/// jams (no bounded solution; F = 0 then).
bool solve_contact_lcp1(double W, double b, double& F, double& w);

/// Put a state on the held set's manifold g_S = 0, ġ_S = 0, M-orthogonally:
///   q ← q − M⁻¹T_Sᵀ W_SS⁺ g_S,   v ← v − M⁻¹T_Sᵀ W_SS⁺ ġ_S
/// (W_SS⁺: minimal-norm least squares, for dependent sets). `MinvTt` = M⁻¹Tᵀ (n × m),
/// `W` = T M⁻¹ Tᵀ, `g`, `gd` the gaps and their rates over all m contacts; y = [q; v; s] (s, the elements' internal states, unchanged).
void project_on_set(const Eigen::MatrixXd& MinvTt, const Eigen::MatrixXd& W, const std::vector<int>& set,
                    const Eigen::VectorXd& g, const Eigen::VectorXd& gd, Eigen::VectorXd& y);

}  // namespace detail
}  // namespace camdyn
