// camdyn (private) — the nonlinear elements of a mechanism placed on its unknowns
// (element.hpp has the element interface).
//
//   Node i of element e reads x_i = Σ_k w_ik q[dof_ik] (its row of the lever elimination
//   q_full = L q: one entry for an independent node or a fixed-pivot lever's output, two or
//   more below a moving pivot, none for ground). The
//   generalised force r_e = Σ_e Bₑᵀ fₑ, its tangent K_e = −∂r_e/∂q = −Σ Bₑᵀ (∂fₑ/∂x) Bₑ and
//   C_e = −∂r_e/∂q̇ on sparse patterns fixed by finish() (an implicit engine's KLU analyses
//   them once per run).
//   Internal states: the elements' states in element order, s = [s_1; s_2; …] (states()
//   entries; element e's at state_offset). The engines carry them after q and v,
//   y = [q; v; s], with ṡ = g(t, q, v, s) (state_rate) and, for the implicit engines'
//   Newton matrix, the blocks R_s = ∂r_e/∂s (n × states), G_q = ∂g/∂q, G_v = ∂g/∂q̇
//   (states × n) on patterns fixed by finish(), and G_s = ∂g/∂s (dense, block-diagonal).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "mechanism/sparse_matrix.hpp"
#include "mechanism/element.hpp"

namespace camdyn {

class ElementSet {
 public:
  using Row = std::vector<std::pair<int, double>>;  ///< (unknown, coefficient)
  struct Placed {
    std::unique_ptr<const Element> element;
    std::vector<Row> rows;    ///< per element node: x_i = Σ coefficient · q[unknown]
    std::vector<long> pos_k;  ///< per (j, i, entry of row j, entry of row i) in tangent(): K_e position
    std::vector<long> pos_c;  ///< the same in C_e (empty if the element does not damp)
    int state_offset = 0;     ///< its first internal state in s
    /// Every node on at most one unknown: x_i = coefficient[i] · q[unknown[i]] (unknown −1:
    /// ground, x_i = 0), the right-hand sides' path; empty otherwise.
    std::vector<int> unknown;
    std::vector<double> coefficient;
  };

  /// @pre rows has element->nodes() entries.
  void add(std::unique_ptr<const Element> element, std::vector<Row> rows);
  /// Builds the tangent patterns over n unknowns (after the last add()).
  void finish(int n);
  bool empty() const { return placed_.empty(); }
  /// Total internal states (0: none; then every s below may be null).
  int states() const { return ns_; }
  const std::vector<Placed>& elements() const { return placed_; }

  /// r += r_e(t, q, v, s) (n entries). s: states() entries (null only when states() = 0;
  /// @throws std::logic_error otherwise).
  void add_force(double t, const double* q, const double* v, double* r, const double* s = nullptr) const;
  /// The values of K_e and C_e at (t, q, v, s) on the patterns below (overwritten).
  void tangent(double t, const double* q, const double* v, SparseMatrix& Ke, SparseMatrix& Ce,
               const double* s = nullptr) const;
  /// s(0) (states() entries).
  void initial_states(double* s0) const;
  /// ṡ = g(t, q, v, s) (states() entries).
  void state_rate(double t, const double* q, const double* v, const double* s, double* sdot) const;
  /// The state blocks at (t, q, v, s): R_s = ∂r_e/∂s, G_q = ∂g/∂q, G_v = ∂g/∂q̇ on the patterns
  /// state_patterns() (values overwritten; a default-constructed matrix gets the pattern)
  /// and G_s = ∂g/∂s (states() × states(), dense).
  void state_tangent(double t, const double* q, const double* v, const double* s, SparseMatrix& Rs,
                     SparseMatrix& Gq, SparseMatrix& Gv, Eigen::MatrixXd& Gs) const;
  const SparseMatrix& rs_pattern() const { return Rs_; }
  const SparseMatrix& gq_pattern() const { return Gq_; }
  /// The patterns (values zero); C_e is 0 × 0 when no element damps.
  const SparseMatrix& stiffness_pattern() const { return Ke_; }
  const SparseMatrix& damping_pattern() const { return Ce_; }
  bool damps() const { return Ce_.size() > 0; }
  /// true: some element dissipates (it damps, or exchanges power through its states).
  bool dissipates() const { return damps() || ns_ > 0; }

  /// Σ Vₑ (zero at q = 0) and Σ Pₑ.
  double stored_energy(const double* q, const double* s = nullptr) const;
  double dissipated_power(double t, const double* q, const double* v, const double* s = nullptr) const;
  /// Every element's force names, in element order, and their values at (t, q, v, s).
  std::vector<std::string> force_names() const;
  void forces(double t, const double* q, const double* v, double* out, const double* s = nullptr) const;

 private:
  /// The element's x and ẋ from q, v (into the scratch buffers) and its states in s.
  ElementState gather(const Placed& p, double t, const double* q, const double* v, const double* s) const;
  std::vector<Placed> placed_;
  SparseMatrix Ke_, Ce_, Rs_, Gq_;
  int n_ = 0, ns_ = 0;
};

}  // namespace camdyn
