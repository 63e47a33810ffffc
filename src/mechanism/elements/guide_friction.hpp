// camdyn (private) — Coulomb friction of a node in its guide (scene type "guide_friction",
// docs/interface.md "Networks", docs/guide/elements.md).
//
//   nodes [node, guide] ("ground": a fixed guide), sliding speed v = ẋ_node − ẋ_guide,
//   constant normal load N, coefficient μ and regularisation speed v_s:
//     force on node  f₀ = −μN tanh(v / v_s),  on the guide f₁ = −f₀
//     ∂f₀/∂ẋ_node = −(μN / v_s) sech²(v / v_s)   (a dashpot of rate μN/v_s at v = 0)
//   dissipated power P = μN tanh(v/v_s)·v ≥ 0, no stored energy.
//
//   The stick phase is regularised, not exact: below |v| ≈ v_s the law is a steep viscous
//   damper, so a node held by a force F < μN creeps at v ≈ v_s·artanh(F/μN) instead of
//   sticking, and a node sliding to rest under friction alone overshoots the Coulomb
//   stopping distance v₀²/(2a) (a = μN/m) by π² v_s²/(12 a) and decays exponentially with
//   the time constant m v_s/(μN) after the Coulomb stop time v₀/a (closed forms in
//   tests/mechanism/test_guide_friction.cpp). A smaller v_s is closer to Coulomb and stiffer:
//   the damper rate μN/v_s sets an explicit engine's stable step, m v_s/(μN).
#pragma once

#include <string>
#include <vector>

#include "mechanism/element.hpp"

namespace camdyn {

class GuideFriction final : public Element {
 public:
  /// @pre spec validated (kind guide_friction).
  GuideFriction(const ElementSpec& spec, std::string name);
  const char* kind() const override { return "guide_friction"; }
  std::string describe() const override;
  void force(const ElementState& e, double* f) const override;
  void force_jacobian(const ElementState& e, double* dfdx, double* dfdxd) const override;
  bool damps() const override { return muN_ > 0.0; }
  double stored_energy(const ElementState&) const override { return 0.0; }
  double dissipated_power(const ElementState& e) const override;
  /// force_<name>: the friction force on the node, −μN tanh(v/v_s).
  void forces(const ElementState& e, double* out) const override;

 private:
  double muN_, vs_;
  std::vector<std::string> nodes_;
};

}  // namespace camdyn
