// camdyn (private) — the cylinder's gas load on a valve head (scene type "gas_load",
// docs/interface.md "Networks", docs/guide/elements.md).
//
//   nodes [valve, body] ("ground": the cylinder head), valve-head area A, a pressure table
//   p(φ) over the crank angle φ [deg] (linear between the points, periodic over the engine
//   cycle of 360·crank_ratio degrees: from the last point back to the first one cycle on;
//   one point: a constant pressure), φ = crank_ratio·θ_deg + crank_offset_deg with θ the
//   cam angle of the scene's drive (θ(t), cam.theta0_deg included):
//     force on the valve f₀ = −p(φ(t))·A (toward its seat: against the lift), on the body +pA
//   The force depends on t only (∂f/∂x = ∂f/∂ẋ = 0). It is an external force: the work the
//   gas does enters the run's energy ledger as a signed dissipated power
//   P = −f₀(ẋ₀ − ẋ₁) = pA(ẋ₀ − ẋ₁) (negative while the gas pushes the valve along its motion).
#pragma once

#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "mechanism/element.hpp"

namespace camdyn {

class GasLoad final : public Element {
 public:
  /// @pre spec validated (kind gas_load); cam the scene's [cam] (its drive θ(t)).
  GasLoad(const ElementSpec& spec, std::string name, const CamSpec& cam);
  const char* kind() const override { return "gas_load"; }
  std::string describe() const override;
  void force(const ElementState& e, double* f) const override;
  void force_jacobian(const ElementState& e, double* dfdx, double* dfdxd) const override;
  bool damps() const override { return false; }
  double stored_energy(const ElementState&) const override { return 0.0; }
  double dissipated_power(const ElementState& e) const override;
  /// force_<name>: p·A, the gas force pushing the valve toward its seat.
  void forces(const ElementState& e, double* out) const override;

  /// The crank angle φ(t) [deg] in [0, 360·crank_ratio) and the table's p(φ).
  double crank_angle_deg(double t) const;
  double pressure(double crank_deg) const;

 private:
  std::vector<double> phi_, p_;
  double area_, ratio_, offset_;
  CamDrive drive_;
  std::vector<std::string> nodes_;
};

}  // namespace camdyn
