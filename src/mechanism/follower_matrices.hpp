// camdyn (private) — the matrices of a rigid or elastic_bar follower (docs/method.md §1, §5),
// from which src/mechanism/follower_builder.cpp makes a one-contact Mechanism.
//
//   Linear follower, n nodes, displacement q (node 0 = contact face, u_c = q₀):
//     M q̈ + C q̇ + K q = f₀ + e₀ F(t),          F = −p ≥ 0 (compressive contact force)
//   rigid:       n = 1, M = [m], K = [k], C = [c].
//   elastic_bar: N 2-node bar elements, K = Σ EA/h [1 −1; −1 1] + k e_N e_Nᵀ,
//                M consistent (ρAh/6 [2 1; 1 2]) or lumped (ρAh/2 I), C = αM + βK.
//   The spring on the far node gives −(k δ₀ + k (q_N − q_N(0))), folded into K and f₀.
#pragma once

#include <Eigen/Core>

#include "camdyn/model_description.hpp"
#include "camdyn/scene.hpp"
#include "mechanism/sparse_matrix.hpp"

namespace camdyn {

/// M, C, K, f₀ and the preloaded initial shape q(0) of a rigid or elastic_bar follower.
struct FollowerMatrices {
  int n = 1;                 ///< nodes (= unknowns)
  SparseMatrix M, K, C;      ///< C zero-sized if undamped; one tridiagonal pattern (bar)
  Eigen::VectorXd f0, q0;    ///< constant force; q(0): node 0 at X_C(θ₀) + initial_gap
  double spring_preload = 0; ///< k δ₀
  ModelDescription description;
};

/// The matrices of the scene's follower. @pre validate(scene) passed and follower.kind is
/// rigid or elastic_bar.
FollowerMatrices follower_matrices(const Scene& scene);

}  // namespace camdyn
