// camdyn (private) — a hydraulic lash adjuster (HLA): a plunger in a body over a high-pressure
// oil chamber, fed from the oil gallery through a check valve, leaking down through the
// plunger clearance, with a plunger spring (scene type "hydraulic_lash_adjuster",
// docs/interface.md "Networks").
//
//   nodes [lower, upper] as a spring (body and plunger, in the order the train's coordinate
//   compresses them); plunger travel into the body δ = q_lower − q_upper; chamber
//   volume V(δ) = V₀ − Aδ (held at ≥ V₀/100: a plunger bottoming out is not modelled).
//   Internal states: the chamber pressure, carried as s₀ = p_abs/p_ref (p_ref =
//   air_reference_pressure; gauge p = p_ref(s₀ − 1)), and the oil volumes pumped in through
//   the check valve and leaked out since t = 0 over V₀ (s₁, s₂: ṡ₁ = Q_check/V₀,
//   ṡ₂ = Q_leak/V₀; results only, nothing depends on them).
//     compressive force  F = p·A + P + kδ   (on lower −F, on upper +F)
//     ṗ = β_eff(p)/V(δ) · (A δ̇ − Q_leak + Q_check)
//     Q_leak  = π d c³ (p − p_s) / (12 μ L)          laminar flow through the concentric
//                                                    annular clearance (both directions)
//     Q_check = C_d A_v √(2/ρ) · Δ / (Δ² + Δ_t²)^¼,  Δ = p_s − p − Δp_open > 0, else 0:
//               the orifice law √(2Δ/ρ) above the transition pressure Δ_t, linear
//               (laminar) below it, so Q_check is C¹ in p away from the valve's opening
//     β_eff(p) = (v_l + v_g) / (v_l/β + v_g/p_abs),  v_l = 1 − α, v_g = α p_ref/p_abs
//               the isothermal mixture of oil (bulk modulus β) with entrained air of volume
//               fraction α at p_ref (H. E. Merritt, Hydraulic Control Systems, Wiley 1967,
//               §2.5 "effective bulk modulus"); p_abs ≥ p_ref/1000 in β_eff (cavitation
//               is not modelled).
//   The check valve as a ball (check_ball_mass m_b > 0) instead of the orifice law: two
//   more internal states, the ball's lift x off its seat (into the chamber) and its speed
//   w (s₃ = x, s₄ = w):
//     ẋ = w,  m_b ẇ = (p_s − p) A_s − P_b − k_b x − c_b w + k_s·max(−x, 0)
//     Q_check = C_d π d_s min(x, x_o)⁺ √(2/ρ) · Δ/(Δ² + Δ_t²)^¼,  Δ = p_s − p (both
//               directions while the ball is off its seat): the curtain area π d_s x up to
//               the full-open area A_o = π d_s x_o (check_area, or the seat bore's area
//               A_s = π d_s²/4 when check_area is 0)
//   with P_b = Δp_open A_s, the preload that holds the ball on its seat up to the opening
//   pressure; the seat a regularised elastic stop of stiffness k_s (no restitution law:
//   the ball's own damping c_b dissipates its bounces); no cage stop above (the spring
//   limits the lift); the ball's displaced volume is neglected. At rest it opens for
//   p_s − p > Δp_open. It starts at rest in its static equilibrium at initial_pressure.
//   Energy: stored V = ½kδ² + Pδ + V(δ)·ε(p), ε(p) = ∫₀^p p′/β_eff(p′) dp′ (closed form); the
//   ledger's dissipated power is the net power the chamber exchanges with the gallery,
//   P = p(Q_leak − Q_check) − ε(p) dV/dδ δ̇ (throttling losses less the gallery's pumping
//   work: negative while the check valve fills the chamber), so that F δ̇ = dV/dt + P holds
//   exactly along the model's solutions. The ball adds ½m_b w² + ½k_b x² + P_b x + ½k_s x²
//   (x < 0) to V and c_b w² − (p_s − p) A_s w to P (the pressures' work on it).
//   Reported (history columns with run.element_forces, Summary::elements): force_<name> (F),
//   force_<name>_pressure (gauge p), force_<name>_travel (δ), force_<name>_pumped and
//   force_<name>_leaked (the volumes); with the ball also force_<name>_ball_lift (x) and
//   force_<name>_check_flow (Q_check).
#pragma once

#include <string>
#include <vector>

#include "mechanism/element.hpp"

namespace camdyn {

class HydraulicLashAdjuster final : public Element {
 public:
  /// @pre spec validated (kind hydraulic_lash_adjuster).
  HydraulicLashAdjuster(const ElementSpec& spec, std::string name);
  const char* kind() const override { return "hydraulic_lash_adjuster"; }
  std::string describe() const override;
  void force(const ElementState& e, double* f) const override;
  void force_jacobian(const ElementState& e, double* dfdx, double* dfdxd) const override;
  bool damps() const override { return false; }
  void state_rate(const ElementState& e, double* sdot) const override;
  void state_jacobian(const ElementState& e, double* dgdx, double* dgdxd, double* dgds, double* dfds) const override;
  void initial_states(double* s0) const override;
  double stored_energy(const ElementState& e) const override;
  double dissipated_power(const ElementState& e) const override;
  std::vector<std::string> force_names() const override;
  void forces(const ElementState& e, double* out) const override;

  /// The model's pieces at gauge pressure p [force/length²] (public for the tests).
  double bulk_modulus(double p) const;
  double leak_flow(double p) const { return leak_ * (p - p_s_); }
  double check_flow(double p) const;
  /// The ball's flow at lift x (0 without a ball) and the ball's acceleration.
  double ball_flow(double p, double x) const;
  double ball_acceleration(double p, double x, double w) const;
  bool has_ball() const { return mb_ > 0.0; }
  double seat_area() const { return As_; }
  /// ε(p) = ∫₀^p p′/β_eff(p′) dp′.
  double strain_energy_density(double p) const;
  double chamber_volume(double delta) const;
  double area() const { return A_; }

 private:
  double pressure(const ElementState& e) const { return p_ref_ * (e.s[0] - 1.0); }
  double travel(const ElementState& e) const { return e.x[0] - e.x[1]; }
  double dbulk_dp(double p) const;
  double dcheck_dp(double p) const;
  /// Q_check and its derivatives in p and x, the orifice law or the ball's (s: the states).
  double inflow(const ElementState& e, double* dQdp, double* dQdx) const;
  double A_, V0_, beta_, alpha_, p_ref_, leak_, p_s_, dp_open_, check_c_, dp_t_, k_, P_, p0_;
  double p_abs_min_;
  double mb_, kb_, cb_, As_, Pb_, ks_, ball_c_, x_open_;
  std::vector<std::string> nodes_;
};

}  // namespace camdyn
