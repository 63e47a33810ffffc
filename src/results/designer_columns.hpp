// camdyn (private) — the designer quantities of one contact state (issue 24): what the
// summary's cam-geometry results (designer_geometry.cpp) and the history's designer columns
// (run.designer_columns) are made of.
//
//   The follower translates along X in a frictionless guide; the cam's force on it acts
//   along the contact normal n̂ = (cos φ, sin φ) (φ: pressure angle). The contact force F
//   of the run (history's contact_force, a network's F_<cam contact>) is its axial
//   component, the one the follower's axial dynamics see; the normal force is
//   N = F / cos φ and the side load F tan φ (the Y component of the cam's force on the
//   follower; the guide carries its opposite). Cam torque T = F s′(θ) (power balance:
//   T ω = F Ẋ_C), power P = T ω. Hertz line-contact pressure p₀ from N between the cam's
//   radius of curvature ρ at the contact and the follower face (roller radius, or a plane).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {
namespace detail {

class OscillatingGeometry;

/// The designer quantities at one contact state.
struct ContactDesign {
  double pressure_angle_deg = 0;  ///< φ [deg]
  double rho = 0;                 ///< cam's radius of curvature at the contact (NaN: none)
  double stress = 0;              ///< Hertz p₀ (NaN: cam.width = 0, knife edge, point, ρ undefined)
  double side = 0;                ///< F tan φ (signed: + toward +Y)
  double torque = 0;              ///< F s′(θ)
  double power = 0;               ///< T ω
};

/// Friction at the cam contact (cam.friction_coefficient > 0; a translating follower). The
/// sliding speed v: a flat face slides at v = |ω|·X_C (the cam's surface past the face, X_C
/// the face's distance from the cam centre); a roller rolls, and slides at roller_slip times
/// its rolling speed V_c ρ/(ρ + r_r) (V_c = |ω|·√(X_C² + X′²), X_C the roller centre's
/// distance). Friction force μ(v)·N along the contact tangent (N the normal force), power
/// P_f = μ(v)·N·v ≥ 0, torque T_f = P_f/ω (the drive torque it takes; a flat face: μN·X_C,
/// the force's moment about the cam centre). Results only: a translating follower takes the
/// flat face's friction force as a side load across its axis, not along its motion.
///
/// An oscillating follower's flat pad (docs/contacts.md "Friction at an oscillating
/// follower"): the friction force f = μ(v)·N·s along t̂ = J n̂ (s = sign of the sliding speed
/// w = ω h − ψ̇ b of the cam's surface past the arm, v = |w|) has the moment arm b about the
/// pivot, so the contact's generalised force on X is F = N (a + μ s b)/ℓ_v: the run's F is
/// that force, the normal force N = F ℓ_v/(a + μ s b). The drive torque is F·X′ (the power
/// into the follower over ω) plus T_f = P_f/ω, P_f = μ N v. Evaluated on the held kinematics
/// (ψ̇ = ψ′ω): where the contact carries force, it is held (penalty: to its penetration rate).
struct CamFriction {
  double sliding_speed = 0;  ///< v [length/time]
  double force = 0;          ///< μ(v)·N [force]
  double torque = 0;         ///< T_f [force·length]
  double power = 0;          ///< P_f [force·length/time]
};

/// The friction's part of an oscillating follower's contact force at one cam state.
struct PadFriction {
  double sliding_speed = 0;  ///< v = |w| [length/time]
  double mu = 0;             ///< μ(v)
  double sign = 0;           ///< s = sign(w): the sense of the friction force along t̂
  /// 1 + κ = 1 + μ s b/a: the factor by which the friction's moment about the pivot scales
  /// the force N a/ℓ_v the normal force alone puts on X.
  double gain = 1;
  double normal_ratio = 1;  ///< N per unit of the generalised force F: ℓ_v/(a + μ s b)
};

class DesignerColumns {
 public:
  /// The friction columns (cam.friction_coefficient > 0): sliding_speed,
  /// cam_friction_force, cam_friction_torque, cam_friction_power.
  static const std::vector<std::string>& friction_names();
  bool friction() const { return mu_ > 0 || mu_s_ > 0; }
  /// μ(v) of the scene's cam friction (constant or Stribeck).
  double friction_coefficient(double sliding_speed) const;
  /// The cam friction at a contact state (zeros when friction() is false or F ≤ 0).
  CamFriction friction_at(const CamPoint& p, double F, double omega) const;
  /// true: cam friction on an oscillating follower's flat pad, where the friction's moment
  /// about the pivot enters the follower's dynamics (pad_friction, contact_gain).
  bool pad_friction_on() const { return static_cast<bool>(osc_); }
  /// The pad's friction at cam point p and cam speed ω (held kinematics).
  /// @pre pad_friction_on()
  PadFriction pad_friction(const CamPoint& p, double omega) const;
  /// The factor 1 + κ on a cam contact's normal-law force (penalty): pad_friction's gain, 1
  /// without pad friction.
  double contact_gain(const CamPoint& p, double omega) const {
    return osc_ ? pad_friction(p, omega).gain : 1.0;
  }
  /// The normal force of the generalised contact force F at cam point p.
  double normal_force(const CamPoint& p, double F, double omega) const;
  /// Appends the four columns of friction_at() to `out`.
  void append_friction(const CamPoint& p, double F, double omega, std::vector<double>& out) const;
  /// The history columns, in order: pressure_angle_deg, radius_of_curvature,
  /// contact_stress, side_load, cam_torque, cam_power.
  static const std::vector<std::string>& names();

  /// Reads cam.width, the moduli and the follower face (Hertz stress when cam.width > 0
  /// and the face is flat or a roller).
  explicit DesignerColumns(const Scene& scene);
  /// @param p the cam point at the row's angle; F the axial contact force; omega [rad/s].
  ContactDesign eval(const CamPoint& p, double F, double omega) const;
  /// Appends the six columns of eval() to `out` in the order of names().
  void append(const CamPoint& p, double F, double omega, std::vector<double>& out) const;

 private:
  double E_star_ = 0, width_ = 0, Rf_ = 0;  // Rf_: follower face radius (inf: flat)
  double mu_ = 0, mu_s_ = 0, v_st_ = 0, slip_ = 0, rr_ = 0;  // cam friction
  bool roller_ = false;
  double lv_ = 0;                                      // valve_arm (pad friction)
  std::shared_ptr<const OscillatingGeometry> osc_;     // pad friction's geometry (else null)
};

}  // namespace detail
}  // namespace camdyn
