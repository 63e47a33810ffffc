// camdyn — Hertz line contact (two parallel cylinders, or a cylinder on a plane), for the
// cam–follower contact stress.
//
//   Johnson, Contact Mechanics (1985), §4.3: a load P per unit length between cylinders of
//   radii R₁, R₂ (R = ∞ a plane, R < 0 a concave surface) gives the half-width b and the
//   peak pressure p₀:
//     1/R′ = 1/R₁ + 1/R₂,   1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂,
//     b = √(4 P R′ / (π E*)),   p₀ = 2P/(π b) = √(P E* / (π R′)).
#pragma once

namespace camdyn {

struct HertzLine {
  double half_width = 0;    ///< b [length]
  double max_pressure = 0;  ///< p₀ [force/length²] (the largest contact stress)
};

/// Contact modulus E* [force/length²].
/// @throws std::invalid_argument unless E₁, E₂ > 0 and 0 ≤ ν < 0.5.
double contact_modulus(double E1, double nu1, double E2, double nu2);

/// Hertz line contact for a force F [force] over the width `width` [length] between radii
/// R1 and R2 [length] (±inf: a plane; negative: concave). F ≤ 0 gives zeros.
/// @throws std::invalid_argument if width ≤ 0, E* ≤ 0, or the surfaces do not touch
/// convexly (1/R₁ + 1/R₂ ≤ 0: a concave surface no more curved than the other).
HertzLine hertz_line(double F, double width, double R1, double R2, double E_star);

}  // namespace camdyn
