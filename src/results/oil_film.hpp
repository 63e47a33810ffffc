// camdyn — elastohydrodynamic film at a line contact (docs/contacts.md "Oil film").
//
// Hamrock's minimum film thickness of a rectangular (line) conjunction, isothermal and
// fully flooded (B. J. Hamrock, S. R. Schmid, B. O. Jacobson, "Fundamentals of Machine
// Elements", 2nd ed., §8.8 / eq. "H_min = 1.714 W'^-0.128 U^0.694 G^0.568"; Hamrock &
// Jacobson 1984):
//   h_min = R_x · 1.714 · W′^−0.128 · U^0.694 · G^0.568,
//   W′ = w′ / (E′ R_x)   (w′ the load per unit width),
//   U  = η₀ ũ / (E′ R_x) (ũ the mean entrainment velocity, ½(u_a + u_b)),
//   G  = ξ E′            (ξ the pressure–viscosity coefficient),
//   E′ = 2 / ((1 − ν_a²)/E_a + (1 − ν_b²)/E_b) (the effective modulus: twice the Hertz E*).
#pragma once

namespace camdyn {

/// The lubricant and surfaces of a film calculation. validate() names field, value, rule.
struct Lubricant {
  double viscosity = 0;              ///< η₀ at the inlet [force·time/length²], > 0
  double pressure_viscosity = 0;     ///< ξ [length²/force], ≥ 0
  double composite_roughness = 0;    ///< √(R_qa² + R_qb²) [length], ≥ 0 (0: no λ)
  void validate() const;
};

/// E′ = 2 / ((1 − ν_a²)/E_a + (1 − ν_b²)/E_b).
double effective_modulus(double E_a, double nu_a, double E_b, double nu_b);

/// Hamrock's h_min for load per width w′ > 0, reduced radius R_x > 0 (1/R_x = 1/R_a +
/// 1/R_b; a flat face: the cam's radius of curvature), entrainment speed |ũ| ≥ 0, E′ > 0.
/// 0 when ũ = 0 (no entrainment: no film); NaN when w′ ≤ 0 or R_x ≤ 0 (no conjunction).
double line_contact_min_film(double load_per_width, double reduced_radius, double entrainment_speed,
                             const Lubricant& oil, double effective_modulus);

/// The mean entrainment velocity ũ at a cam and a flat-faced translating follower: the
/// surfaces move past the contact point at −ω(r_b + s + s″) (cam) and −ω s″ (face), so
/// ũ = −½ ω (r_b + s + 2 s″) (s, s″: lift and its second derivative in θ).
double flat_face_entrainment(double omega, double base_radius, double lift, double lift_dd);

/// The same at a roller (radius r_r) on an in-line translating follower, the roller
/// rolling: both surfaces move past the contact at the contact point's speed along the
/// cam profile, V_c ρ/(ρ + r_r), with V_c = |ω| √((r_b + r_r + s)² + s′²) the roller centre's
/// speed relative to the cam and ρ the cam's radius of curvature there (convex > 0).
double roller_entrainment(double omega, double base_radius, double roller_radius, double lift, double lift_d,
                          double cam_curvature_radius);

}  // namespace camdyn
