// camdyn (private) — exact contact kinematics of oscillating followers: finger followers
// and rockers with a flat pad or a roller (issue 24; docs/cam_laws.md "Oscillating
// followers").
//
//   Fixed frame (X, Y), cam centre O at the origin, cam turning counter-clockwise by θ.
//   The arm turns about the pivot P = (pivot_x, pivot_y); α is its absolute angle from +X,
//   u(α) = (cos α, sin α) along the arm, n(α) = (−sin α, cos α) = J u (J: +90°).
//     roller:   roller centre C = P + ℓ u(α)  (ℓ = arm_length, roller radius r_r);
//     flat pad: the pad is the line {Z : n(α)·(Z − P) = f}  (f = pad_offset).
//   Of the two assemblies touching the cam (mirror images about the line from the pivot to
//   the cam), the one whose contact lies nearer the +X axis on the base circle (law) or the
//   profile's innermost circle (circle, arc); σ = ±1 is the sense in which it lifts
//   (+1: counter-clockwise), ψ = σ(α − α_ref). The branch with σ(C − P)×(C − K) > 0 (the
//   cam's push turns the arm in the lifting sense) is kept at every angle.
//
//   The follower coordinate handed to the dynamics is X = ℓ_v ψ, ℓ_v =
//   valve_arm: the lift of the arm's point at distance ℓ_v from the pivot measured along
//   its arc (the valve end of a finger follower, linear in the rotation). A node of mass
//   J/ℓ_v² on X is the arm's rotation about the pivot exactly (J ψ̈ = M ⇔ (J/ℓ_v²) Ẍ =
//   M/ℓ_v). α_ref: law — the base-circle position (X = L, the law is the valve-end lift);
//   circle/arc — the lowest position over a revolution (X ≥ 0).
//
//   Profile cams (circle, arc: tangent circular arcs of centre k_i, radius R_i): the
//   contact condition on arc i is g(α, θ) = 0 with K = Rot(θ) k_i,
//     roller: g = |C(α) − K|² − (R_i + r_r)²   (C on the cam's pitch curve),
//     flat:   g = n(α)·(K − P) − f + R_i        (the pad line tangent to the arc).
//   α from the closed form (triangle P, K, C: α = β + γ; pad: α = β − asin((f − R_i)/d),
//   β = arg(K − P), d = |K − P|); α′, α″, α‴ by implicit differentiation of g = 0 with g's
//   exact partial derivatives (no finite differences).
//   Law cams: the law is X (the valve-end lift): α = α_b + L/ℓ_v; the profile for the
//   chosen follower is synthesised (roller: the pitch curve, the cam curve at r_r inside;
//   flat: the envelope of the pad lines) with undercut/convexity checks naming cam angles.
//
//   At the contact: normal n̂ (from cam to follower), contact point Q, the moment arm
//   a = σ (Q − P) × n̂ (> 0: the contact force lifts the arm), pressure angle φ from the
//   direction of motion σ J(C − P) of the roller centre C (flat pad: of the pad's point at
//   Q, C = Q) to n̂; a = |C − P| cos φ. The normal
//   force is N = F ℓ_v / a for the force F on X (virtual work: F δX = N a δα).
//   Cam friction (docs/contacts.md): a force f t̂ at Q (t̂ = J n̂) has the moment σ f b
//   about P, b = σ (Q − P)·n̂, so the generalised force on X is (N a + f b)/ℓ_v; the cam's
//   surface slides past the arm's point at Q at w = ω Q·n̂ − ψ̇ b.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/motion_law.hpp"
#include "camdyn/cam_spec.hpp"
#include "camdyn/scene_error.hpp"
#include "cam/follower_geometry.hpp"

namespace camdyn {
namespace detail {

/// Oscillating-follower kinematics at one cam angle (the FollowerState part is X = ℓ_v ψ).
struct OscillatingState {
  FollowerState f;          ///< s = X, s1..s3 its θ-derivatives, phi, rho, contact point
  double psi = 0;           ///< rotation ψ = α − α_ref [rad]
  double psi1 = 0, psi2 = 0, psi3 = 0;  ///< dψ/dθ, d²ψ/dθ², d³ψ/dθ³
  double alpha = 0;         ///< absolute arm angle α [rad]
  double moment_arm = 0;    ///< a = (Q − P) × n̂ [length]
  /// b = σ (Q − P)·n̂ [length]: the moment arm about the pivot of a tangential force at Q
  /// along t̂ = J n̂ (cam friction: docs/contacts.md "Friction at an oscillating follower").
  double tangent_arm = 0;
  /// h = Q·n̂ [length]: the cam's support distance; its surface passes the contact at
  /// ω h along t̂ (Q × t̂ = Q·n̂).
  double normal_distance = 0;
  double nx = 0, ny = 0;    ///< contact normal n̂ (cam → follower), fixed frame
};

/// CamPoint's X_C and derivatives, ρ, pressure angle and contact point (β, r) from f.
void fill_cam_point(CamPoint& p, const FollowerState& f);

/// A plane vector of the fixed frame.
struct OscVec {
  double x = 0, y = 0;
};

class OscillatingGeometry {
 public:
  /// @throws SceneError naming key, value and rule: bad pivot/arm/roller/pad dimensions,
  /// a profile cam out of the follower's reach (cam angles named), a toggle position,
  /// an undercut or concave synthesised profile (cam angles named).
  explicit OscillatingGeometry(const CamSpec& spec);
  OscillatingState eval(double theta) const;
  /// The Cam's view at cam angle θ: X = ℓ_v ψ and its derivatives, ψ, moment arm, N/F.
  void fill(CamPoint& p, double theta) const;
  const std::vector<double>& breaks() const { return breaks_; }
  double lift() const { return xmax_ - xmin_; }
  double min_rho() const { return min_rho_; }
  double valve_arm() const { return lv_; }
  /// Cam-frame profile point: law — the contact point at cam angle a turned back into
  /// the cam frame; circle/arc — the arc point with outward normal angle a.
  std::array<double, 2> profile_point(double a) const;
  const MotionLaw* law() const { return law_.get(); }

 private:
  CamProfileKind kind_;
  FollowerFace face_;
  double px_ = 0, py_ = 0, arm_ = 0, pad_ = 0, rr_ = 0, lv_ = 0, rb_ = 0;
  int sigma_ = 1;  // +1: lifting turns the arm counter-clockwise
  double alpha_ref_ = 0, alpha_b_ = 0;
  std::shared_ptr<const MotionLaw> law_;
  std::vector<Arc> arcs_;
  std::vector<double> breaks_;
  double xmin_ = 0, xmax_ = 0, min_rho_ = 0;
  /// α on arc i at cam angle θ (NaN: no contact there); n̂'s cam-frame angle in *nu.
  double arc_alpha(const Arc& a, double theta, double* nu) const;
  int select_arc(double theta) const;
  OscillatingState eval_arc(double theta) const;
  OscillatingState eval_law(double theta) const;
  /// Contact point Q, normal n̂ → X, ψ scaled, moment arm, pressure angle.
  void finish(OscillatingState& s, OscVec Q, OscVec nh) const;
  void check_law_profile(const CamSpec& spec);
  void check_arcs(const CamSpec& spec);
  /// Cam friction at a flat pad: a − μ_max|b| > 0 at every angle (else cam.friction_coefficient).
  void check_friction_lock(const CamSpec& spec);
};

}  // namespace detail
}  // namespace camdyn
