// camdyn (private) — the nonlinear elements of a mechanism placed on its unknowns
// (element.hpp has the element interface).
//
//   Node i of element e reads x_i = Σ_k w_ik q[dof_ik] (its row of the lever elimination
//   q_full = L q: one entry for an independent node or a fixed-pivot lever's output, two or
//   more below a moving pivot, none for ground). The
//   generalised force r_e = Σ_e Bₑᵀ fₑ, its tangent K_e = −∂r_e/∂q = −Σ Bₑᵀ (∂fₑ/∂x) Bₑ and
//   C_e = −∂r_e/∂q̇ on sparse patterns fixed by finish() (an implicit engine's KLU analyses
//   them once per run).
#pragma once

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
  };

  /// @pre rows has element->nodes() entries; @throws std::invalid_argument for an element
  /// with internal states (the engines do not carry element states).
  void add(std::unique_ptr<const Element> element, std::vector<Row> rows);
  /// Builds the tangent patterns over n unknowns (after the last add()).
  void finish(int n);
  bool empty() const { return placed_.empty(); }
  const std::vector<Placed>& elements() const { return placed_; }

  /// r += r_e(t, q, v) (n entries).
  void add_force(double t, const double* q, const double* v, double* r) const;
  /// The values of K_e and C_e at (t, q, v) on the patterns below (overwritten).
  void tangent(double t, const double* q, const double* v, SparseMatrix& Ke, SparseMatrix& Ce) const;
  /// The patterns (values zero); C_e is 0 × 0 when no element damps.
  const SparseMatrix& stiffness_pattern() const { return Ke_; }
  const SparseMatrix& damping_pattern() const { return Ce_; }
  bool damps() const { return Ce_.size() > 0; }

  /// Σ Vₑ (zero at q = 0) and Σ Pₑ.
  double stored_energy(const double* q) const;
  double dissipated_power(double t, const double* q, const double* v) const;
  /// Every element's force names, in element order, and their values at (t, q, v).
  std::vector<std::string> force_names() const;
  void forces(double t, const double* q, const double* v, double* out) const;

 private:
  /// The element's x and ẋ from q, v (into the scratch buffers).
  ElementState gather(const Placed& p, double t, const double* q, const double* v) const;
  std::vector<Placed> placed_;
  SparseMatrix Ke_, Ce_;
  int n_ = 0;
};

}  // namespace camdyn
