// camdyn (private) — a progressive spring: a compression spring whose force–deflection curve
// is a table (scene type "progressive_spring", docs/interface.md "Networks").
//
//   nodes [lower, upper], deflection δ = δ_i + q_lower − q_upper (δ_i: installed_deflection,
//   the deflection at q = 0), F(δ) the table's monotone piecewise-cubic Hermite interpolant
//   (PCHIP, Fritsch–Carlson slopes: monotone where the table is, no overshoot), linear beyond
//   the table with its end slopes. The preload is F(δ_i). With damping c:
//     force on lower −(F(δ) + cδ̇), on upper +(F(δ) + cδ̇)
//   stored energy V = ∫_{δ_i}^{δ} F (exact: the cubic's integral), dissipated power cδ̇².
#pragma once

#include <vector>

#include "mechanism/element.hpp"

namespace camdyn {

/// The table's monotone cubic F(δ) and its integral.
class MonotoneCurve {
 public:
  /// @pre x strictly increasing, ≥ 2 points, y the same length.
  MonotoneCurve(std::vector<double> x, std::vector<double> y);
  double value(double x) const;
  double slope(double x) const;
  /// ∫_{x(0)}^{x} F.
  double integral(double x) const;
  /// The deflection at which F = y (bisection on the monotone F; the first such on a flat
  /// part). @pre F increasing somewhere and y within its range or beyond (linear ends).
  double inverse(double y) const;

 private:
  std::size_t segment(double x) const;  // k with x_k ≤ x < x_{k+1}, clamped to [0, n − 2]
  std::vector<double> x_, y_, m_, area_;  // knots, values, slopes, ∫ from x_0 to x_k
  // per segment k, the cubic in u = x − x_k: y = c₀ + c₁u + c₂u² + c₃u³ (4k … 4k + 3)
  std::vector<double> poly_;
  // equally spaced knots (to round-off): segment() guesses k = ⌊(x − x_0)/spacing⌋ and
  // corrects it by the knots, without a bisection
  bool uniform_ = false;
  double inv_spacing_ = 0.0;
};

class ProgressiveSpring final : public Element {
 public:
  /// @pre spec validated (kind progressive_spring).
  ProgressiveSpring(const ElementSpec& spec, std::string name);
  const char* kind() const override { return "progressive_spring"; }
  std::string describe() const override;
  void force(const ElementState& e, double* f) const override;
  void force_jacobian(const ElementState& e, double* dfdx, double* dfdxd) const override;
  bool damps() const override { return c_ != 0.0; }
  double stored_energy(const ElementState& e) const override;
  double dissipated_power(const ElementState& e) const override;
  void forces(const ElementState& e, double* out) const override;
  const MonotoneCurve& curve() const { return curve_; }
  double preload() const { return curve_.value(d0_); }

 private:
  double deflection(const ElementState& e) const { return d0_ + e.x[0] - e.x[1]; }
  MonotoneCurve curve_;
  double d0_, c_;
  std::vector<std::string> nodes_;
};

}  // namespace camdyn
