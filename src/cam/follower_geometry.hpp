// camdyn (private) — exact contact kinematics of translating followers (issue 24).
//
//   Fixed frame (X, Y), cam turning counter-clockwise by θ; the follower translates along
//   X on the axis Y = ε (the offset) and touches the cam from the +X side. s(θ) is the
//   follower's position along X: the flat face's plane, the knife edge, the roller centre.
//   The contact normal n̂ = (cos φ, sin φ) (φ: pressure angle, from the follower axis to
//   the normal, positive toward +Y). The cam's driving torque for a follower force F along
//   X is T = F s′(θ) (power balance), and the side load on the guide is F tan φ.
//
//   Cams handled here:
//     law  — the law is the follower's motion. flat: s = r_b + L (profile the envelope,
//            ρ = s + s″); knife_edge/roller: the pitch point P = (d + L, ε),
//            d = √(R_p² − ε²), R_p = r_b + R_r; pressure angle tan φ = (s′ + ε)/s; pitch
//            curve radius ρ_p = −|c′|³/(c′ × c″) with c′ = (s′+ε, −s), c″ = (s″−s, −2s′−ε);
//            the cam ρ = ρ_p − R_r; point: s = L (no profile).
//     circle, arc — the profile is a chain of tangent circular arcs (centre c_i, radius
//            R_i, outward normal angles [n0_i, n1_i] in the cam frame). flat: the arc whose
//            normal range holds −θ, s = c_X + R_i; knife_edge/roller: the arc whose pitch
//            circle (R_i + R_r) meets the axis with its normal in range,
//            s = c_X + √((R_i+R_r)² − (ε − c_Y)²). Derivatives by 3rd-order jets in θ.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/motion_law.hpp"
#include "camdyn/cam_spec.hpp"
#include "camdyn/scene_error.hpp"

namespace camdyn {
namespace detail {

/// Follower kinematics at one cam angle.
struct FollowerState {
  double s = 0, s1 = 0, s2 = 0, s3 = 0;  ///< follower position along X and d/dθ, d²/dθ², d³/dθ³
  double phi = 0;                       ///< pressure angle [rad]
  double rho = 0;                       ///< cam's radius of curvature at the contact (NaN: none)
  double cx = 0, cy = 0;                ///< contact point, fixed frame (NaN: none)
  int arc = -1;                         ///< arc index (circle/arc cams), else −1
};

/// One circular arc of a cam profile: centre (cam frame), signed radius R (> 0 convex,
/// < 0 concave, 0 a corner: the point c itself, its normal sweeping the range), and the
/// range [n0, n1] (n0 < n1) of its outward normal angle [rad]. The point with outward
/// normal angle n is c + R (cos n, sin n). `drawn`: the index of the arc in cam.arc_*
/// (−1: a corner inserted between two drawn arcs, or the four-arc/circle cams' arcs).
struct Arc {
  double cx, cy, R, n0, n1;
  int drawn = -1;
  /// The arc's length parameter for plots: its share of the chain [0, 1) (set by the chain).
  double u0 = 0, u1 = 0;
};

/// The profile kind the geometry works with: a lift table (cam.profile = "table") is a law.
inline CamProfileKind geometry_kind(CamProfileKind k) {
  return k == CamProfileKind::Table ? CamProfileKind::Law : k;
}
/// The law of cam.profile "law" (cam.law parsed) or "table" (cam.lift_table read and
/// interpolated, MotionLaw::from_table). @throws SceneError naming the key.
std::shared_ptr<const MotionLaw> law_of(const CamSpec& spec);

class TranslatingGeometry {
 public:
  /// @throws SceneError naming key, value and rule (undercut, concave flank under a flat
  /// face, offset too large, bad arc dimensions, a follower face the profile cannot take).
  explicit TranslatingGeometry(const CamSpec& spec);
  FollowerState eval(double theta) const;
  /// Cam angles [rad, in [0, 2π)] where s″ or s‴ may jump (law joints, arc switches).
  const std::vector<double>& breaks() const { return breaks_; }
  /// The arc joints (circle/arc/arcs cams) with their continuity order and jumps, one per
  /// entry of breaks(); empty for a law (its joints are the law's).
  const std::vector<Breakpoint>& arc_joints() const { return joints_; }
  double lift() const { return smax_ - smin_; }
  double min_position() const { return smin_; }
  /// Smallest radius of curvature of the convex parts of the profile (NaN: none/point).
  double min_rho() const { return min_rho_; }
  /// Cam-frame profile point for plots: law — the contact point at cam angle a turned
  /// back into the cam frame; circle/arc — the arc point with outward normal angle a.
  std::array<double, 2> profile_point(double a) const;
  const MotionLaw* law() const { return law_.get(); }

 private:
  CamProfileKind kind_;
  FollowerFace face_;
  double eps_ = 0, rr_ = 0, rb_ = 0, d_ = 0;
  std::shared_ptr<const MotionLaw> law_;
  std::vector<Arc> arcs_;
  std::vector<double> breaks_;
  std::vector<Breakpoint> joints_;
  double smin_ = 0, smax_ = 0, min_rho_ = 0;
  FollowerState eval_law(double theta) const;
  FollowerState eval_arcs(double theta) const;
  FollowerState on_arc(const Arc& a, int i, double theta) const;
  int select_arc(double theta) const;
  void check_law_profile(const CamSpec& spec);
};

/// The arcs of an arc cam (base, upper flank, nose, lower flank; nose centre on +x) or of
/// a circle cam (one arc). @throws SceneError on dimensions that do not close tangently.
std::vector<Arc> make_arcs(const CamSpec& spec);
/// The arcs of cam.profile = "arcs" (cam.arc_*), in order round the cam, with a corner arc
/// (R = 0) inserted at each convex corner. Checks: list lengths, radii, each arc's range,
/// that consecutive arcs meet (naming the joint and the gap), that the tangent turns once
/// round in total, and what the follower face can take (a flat face: no concave arc or
/// corner; a roller: no concave corner, no concave arc tighter than the roller).
/// @throws SceneError naming key, value and rule.
std::vector<Arc> make_arc_list(const CamSpec& spec);
/// The cam-frame point of a chain of arcs at plot parameter a ∈ [0, 2π) (the arcs' u ranges
/// scaled by 2π; every arc of a cam.arc_* chain carries them).
std::array<double, 2> arc_chain_point(const std::vector<Arc>& arcs, double a);
/// The cam-frame point of a chain of arcs with outward normal angle a [rad].
std::array<double, 2> arc_profile_point(const std::vector<Arc>& arcs, double a);
/// Sorted cam angles in [0, 2π) where select(θ) (the arc in contact) changes: found on an
/// n-point scan, each bisected to round-off.
std::vector<double> arc_switches(const std::function<int(double)>& select, int n);

}  // namespace detail
}  // namespace camdyn
