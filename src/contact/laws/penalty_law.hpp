// camdyn (private) — the penalty baseline's normal-force laws, for every contact of a
// mechanism, one contact or many (methods/penalty.cpp):
//
//   penetration s > 0, its rate ŝ:
//     linear:        F = max(0, k_p s + c_p ŝ),          elastic part F_el = k_p s
//     hunt_crossley: F = max(0, k_p sⁿ (1 + c_p ŝ)),     elastic part F_el = k_p sⁿ
//   F = 0 for s ≤ 0. The spring stores V_p(s) = ∫₀ˢ F_el = ½k_p s² or k_p sⁿ⁺¹/(n + 1);
//   the rest, F − F_el, is the damper's: its power (F − F_el)·ŝ is dissipated (also where
//   the clipping F = 0 releases V_p).
#pragma once

#include <cmath>

#include "camdyn/scene.hpp"

namespace camdyn {
namespace detail {

struct PenaltyParams {
  PenaltyLaw law = PenaltyLaw::Linear;
  double kp = 0, cp = 0, exponent = 1.5;
};

/// F(s, ŝ); el (if given) receives F_el(s).
inline double penalty_force(const PenaltyParams& p, double s, double sd, double* el = nullptr) {
  if (el) *el = 0.0;
  if (s <= 0.0) return 0.0;
  double F, E;
  if (p.law == PenaltyLaw::Linear) {
    E = p.kp * s;
    F = E + p.cp * sd;
  } else {
    E = p.kp * std::pow(s, p.exponent);
    F = E * (1.0 + p.cp * sd);
  }
  if (el) *el = E;
  return F > 0.0 ? F : 0.0;
}

/// ∂F/∂s and ∂F/∂ŝ (zero where F is clipped or s ≤ 0).
inline void penalty_derivatives(const PenaltyParams& p, double s, double sd, double* dFds, double* dFdsd) {
  *dFds = 0.0;
  *dFdsd = 0.0;
  if (s <= 0.0) return;
  if (p.law == PenaltyLaw::Linear) {
    if (p.kp * s + p.cp * sd <= 0.0) return;
    *dFds = p.kp;
    *dFdsd = p.cp;
  } else {
    if (1.0 + p.cp * sd <= 0.0) return;
    *dFds = p.kp * p.exponent * std::pow(s, p.exponent - 1.0) * (1.0 + p.cp * sd);
    *dFdsd = p.kp * std::pow(s, p.exponent) * p.cp;
  }
}

/// V_p(s).
inline double penalty_energy(const PenaltyParams& p, double s) {
  if (s <= 0.0) return 0.0;
  return p.law == PenaltyLaw::Linear ? 0.5 * p.kp * s * s
                                     : p.kp * std::pow(s, p.exponent + 1.0) / (p.exponent + 1.0);
}

}  // namespace detail
}  // namespace camdyn
