// camdyn (private) — the penalty baseline's normal-force law of one contact (linear or
// Hunt–Crossley), written once: force, stiffness (its derivatives), stored energy and its
// inverse, the depth at a force (methods/penalty.cpp, src/run/initial_state.cpp):
//
//   penetration s > 0, its rate ŝ:
//     linear:        F = max(0, k_p s + c_p ŝ),          elastic part F_el = k_p s
//     hunt_crossley: F = max(0, k_p sⁿ (1 + c_p ŝ)),     elastic part F_el = k_p sⁿ
//   F = 0 for s ≤ 0. The spring stores V_p(s) = ∫₀ˢ F_el = ½k_p s² or k_p sⁿ⁺¹/(n + 1);
//   the rest, F − F_el, is the damper's: its power (F − F_el)·ŝ is dissipated (also where
//   the clipping F = 0 releases V_p). The depth at a force F (ŝ = 0): s = F/k_p or (F/k_p)^{1/n}.
#pragma once

#include <cmath>

#include "camdyn/scene.hpp"

namespace camdyn {

class PenaltyNormalLaw {
 public:
  PenaltyNormalLaw() = default;
  /// @param kind linear or Hunt–Crossley; kp > 0, cp ≥ 0, exponent n (Hunt–Crossley) ≥ 1.
  PenaltyNormalLaw(PenaltyLaw kind, double kp, double cp, double exponent)
      : kind_(kind), kp_(kp), cp_(cp), n_(exponent) {}

  PenaltyLaw kind() const { return kind_; }
  double stiffness() const { return kp_; }  ///< k_p
  double damping() const { return cp_; }    ///< c_p
  double exponent() const { return n_; }    ///< n (Hunt–Crossley)

  /// F(s, ŝ); el (if given) receives F_el(s).
  double force(double s, double sd, double* el = nullptr) const {
    if (el) *el = 0.0;
    if (s <= 0.0) return 0.0;
    double F, E;
    if (kind_ == PenaltyLaw::Linear) {
      E = kp_ * s;
      F = E + cp_ * sd;
    } else {
      E = kp_ * std::pow(s, n_);
      F = E * (1.0 + cp_ * sd);
    }
    if (el) *el = E;
    return F > 0.0 ? F : 0.0;
  }

  /// ∂F/∂s and ∂F/∂ŝ (zero where F is clipped or s ≤ 0).
  void derivatives(double s, double sd, double* dFds, double* dFdsd) const {
    *dFds = 0.0;
    *dFdsd = 0.0;
    if (s <= 0.0) return;
    if (kind_ == PenaltyLaw::Linear) {
      if (kp_ * s + cp_ * sd <= 0.0) return;
      *dFds = kp_;
      *dFdsd = cp_;
    } else {
      if (1.0 + cp_ * sd <= 0.0) return;
      *dFds = kp_ * n_ * std::pow(s, n_ - 1.0) * (1.0 + cp_ * sd);
      *dFdsd = kp_ * std::pow(s, n_) * cp_;
    }
  }

  /// V_p(s).
  double energy(double s) const {
    if (s <= 0.0) return 0.0;
    return kind_ == PenaltyLaw::Linear ? 0.5 * kp_ * s * s : kp_ * std::pow(s, n_ + 1.0) / (n_ + 1.0);
  }

  /// The penetration at which the law carries F at rest (ŝ = 0); 0 for F ≤ 0.
  double depth_at(double F) const {
    if (!(F > 0.0)) return 0.0;
    return kind_ == PenaltyLaw::Linear ? F / kp_ : std::pow(F / kp_, 1.0 / n_);
  }

 private:
  PenaltyLaw kind_ = PenaltyLaw::Linear;
  double kp_ = 0.0, cp_ = 0.0, n_ = 1.5;
};

}  // namespace camdyn
