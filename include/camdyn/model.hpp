// camdyn — follower models (docs/method.md §1, §5).
//
//   Linear follower, n nodes, displacement q (node 0 = contact face, u_c = q₀):
//     M q̈ + C q̇ + K q = f₀ + e₀ F(t),          F = −p ≥ 0 (compressive contact force)
//   rigid:       n = 1, M = m, K = k, C = c.
//   elastic_bar: N 2-node bar elements, K = Σ EA/h [1 −1; −1 1] + k e_N e_Nᵀ,
//                M consistent (ρAh/6 [2 1; 1 2]) or lumped (ρAh/2 I), C = αM + βK.
//   The spring on the far node gives −(k δ₀ + k (q_N − q_N(0))), folded into K and f₀.
//   M* = e₀ᵀ M⁻¹ e₀ (one sparse solve per mesh).
//
// The builder makes only what a scene asks for: a rigid scene builds no sparse matrix and
// no mesh; an undamped scene has C = 0 and no damping term in the right-hand side.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/model_description.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, long>;
/// A linear follower model. Immutable once built; share it between engines.
class FollowerModel {
 public:
  /// @pre spec validated. @throws std::invalid_argument on inconsistent input.
  explicit FollowerModel(const Scene& scene);
  ~FollowerModel();

  int n() const { return n_; }
  bool rigid() const { return rigid_; }
  bool lumped() const { return lumped_; }          ///< diagonal M (rigid counts as lumped)
  bool damped() const { return damped_; }
  double mstar() const { return mstar_; }          ///< M* = e₀ᵀ M⁻¹ e₀
  /// M⁻¹e₀: the velocity change of a unit impulse on node 0 (its entry 0 is M*).
  const Eigen::VectorXd& contact_column() const { return mass_col0_; }
  const SparseMatrix& M() const { return M_; }     ///< empty for rigid
  const SparseMatrix& K() const { return K_; }
  const SparseMatrix& C() const { return C_; }     ///< empty if undamped
  const Eigen::VectorXd& f0() const { return f0_; }
  double m_rigid() const { return m_; }  ///< rigid: m, k, c
  double k_rigid() const { return k_; }
  double c_rigid() const { return c_; }
  double spring_k() const { return spring_k_; }
  /// Far node carrying the spring.
  int far_node() const { return n_ - 1; }
  /// Rest displacement of the far node (q_N(0)), for energies.
  double q_far0() const { return q_far0_; }
  double spring_preload() const { return preload_; }

  /// Initial displacement q(0): static equilibrium under the preload (uniform compression
  /// through the bar) with node 0 at X_C(θ₀) + initial_gap.
  const Eigen::VectorXd& initial_displacement() const { return q0_; }

  /// r = f₀ − K q − C v  (all forces but inertia and contact). O(nnz).
  void internal_force(const double* q, const double* v, double* r) const;
  /// x = M⁻¹ b (factor computed once; diagonal for lumped/rigid). O(n).
  void solve_mass(const double* b, double* x) const;
  /// Node-0 acceleration e₀ᵀ M⁻¹ (f₀ − K q − C v + e₀ F).
  double contact_acceleration(const double* q, const double* v, double F) const;
  /// Kinetic ½vᵀMv; potential ½qᵀKq − f₀ᵀq (strain + spring, up to a constant);
  /// dissipated power vᵀCv.
  double kinetic_energy(const double* v) const;
  double potential_energy(const double* q) const;
  double damping_power(const double* v) const;

  const ModelDescription& description() const { return desc_; }


 private:
  int n_ = 1;
  bool rigid_ = true, lumped_ = true, damped_ = false;
  double m_ = 1, k_ = 0, c_ = 0, spring_k_ = 0, preload_ = 0, q_far0_ = 0;
  double mstar_ = 1;
  SparseMatrix M_, K_, C_;
  Eigen::VectorXd f0_, q0_, Mdiag_inv_, mass_col0_;  // mass_col0_ = M⁻¹ e₀
  double a_f0_ = 0;                 // node-0 acceleration = a_f0_ − a_q_·q − a_v_·v + M*F
  Eigen::VectorXd a_q_, a_v_;
  Eigen::VectorXd r0_;              // f₀ − K q(0) (bar): the shifted internal force's origin
  double a_r0_ = 0;                 // a_f0_ − a_q_·q(0)
  void contact_coupling();          // mass_col0_, mstar_, a_f0_, a_q_, a_v_ (after M, K, C, f₀)
  struct Factor;
  std::unique_ptr<Factor> factor_;  // consistent mass: tridiagonal LDLᵀ
  ModelDescription desc_;
};

/// Build the smallest model for a scene. @pre validate(scene) passed.
std::shared_ptr<const FollowerModel> build_model(const Scene& scene);

}  // namespace camdyn
