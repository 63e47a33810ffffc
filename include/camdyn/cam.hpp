// camdyn — cam geometry and kinematics (docs/method.md §2).
//
//   Cam frame (x, y) turns with angle θ; a cam point sits at
//     X = x cos θ − y sin θ,   Y = x sin θ + y cos θ.
//   A flat-faced follower translating along X touches the cam at C, the point of the
//   rotated profile with the largest X (eq. 2). Its support function
//     h(θ) = max_α X(α, θ)  gives  X_C = h,  Ẋ_C = h′ω,  Ẍ_C = h″ω² + h′ω̇,
//   and for a convex profile h + h″ = ρ (radius of curvature at C, > 0).
//   The paper's form (eqs. 8, 9, A7), with β, r the polar angle and radius of C in the
//   fixed frame:
//     Ẋ_C = −r ω sin β
//     Ẍ_C = −r ω² cos β − r ω̇ sin β − 2ω²/x_yy + (ω/(y_α x_yy))² x_αα.
#pragma once

#include <cmath>

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/cam_spec.hpp"
#include "camdyn/motion_law.hpp"
#include "camdyn/scene_error.hpp"

namespace camdyn {

/// Geometry of the contact point at one cam angle (support-function form).
struct CamPoint {
  double theta = 0;        ///< cam angle θ [rad]
  double X_C = 0;          ///< h(θ): X of the contact point [length]
  double dX_dtheta = 0;    ///< h′(θ) [length/rad]
  double d2X_dtheta2 = 0;  ///< h″(θ) [length/rad²]
  double beta = 0;         ///< polar angle of C in the fixed frame [rad], in (−π, π]
  double r = 0;            ///< distance of C from O [length]
  double rho = 0;          ///< radius of curvature of the profile at C [length], > 0
                           ///< (NaN for a law with follower_face = "point": no profile)
  double d3X_dtheta3 = 0;  ///< h‴(θ) [length/rad³] (NaN for a points spline: not exact)
  double pressure_angle = 0;  ///< angle from the follower axis to the contact normal [rad]
                              ///< (0 for a flat face; knife edge, roller: docs/cam_laws.md)
  /// Oscillating follower (cam.follower_motion = "oscillating"; NaN otherwise): the arm's
  /// rotation ψ [rad] (X_C = valve_arm·ψ), its θ-derivatives, and the moment arm of the
  /// contact normal about the pivot [length]. The contact's normal force is
  /// N = F·valve_arm/moment_arm for the force F on X (virtual work).
  double psi = std::numeric_limits<double>::quiet_NaN();
  double dpsi_dtheta = std::numeric_limits<double>::quiet_NaN();
  double d2psi_dtheta2 = std::numeric_limits<double>::quiet_NaN();
  double moment_arm = std::numeric_limits<double>::quiet_NaN();
  /// Normal contact force per unit force on X: 1/cos(pressure_angle) for a translating
  /// follower, valve_arm/moment_arm for an oscillating one.
  double normal_force_ratio = 1.0;
};

/// Position, velocity and acceleration of C along X. X is absolute (the face's distance
/// from O: a rigid or elastic_bar follower's gap is u_c − X); a network's or user
/// follower's cam contact subtracts the lift X − X_base instead (cam_lift_base,
/// camdyn/initial_state.hpp).
struct CamMotion {
  double X = 0, Xdot = 0, Xddot = 0;
  /// The time this motion is at, where a run evaluates the cam (a camshaft's cams on a
  /// prescribed drive station are evaluated at the crank's angle at that time); NaN from
  /// Cam::motion, which knows only the angle.
  double t = NAN;
};

/// A convex cam profile. Construction validates it; evaluation tracks the contact point
/// from the previous call (O(1) per call, no dense scan). Thread-safe: the const members
/// may be called concurrently on one Cam (the hint is a relaxed atomic, and the contact
/// point found does not depend on it, only the search's cost); copies are independent.
class Cam {
 public:
  /// @throws SceneError (file "<cam>") with the offending key, value and rule: too few
  /// knots, non-increasing/duplicate angles, non-positive radii, NaN/inf, a
  /// self-intersecting or non-convex profile (naming the cam angles where ρ ≤ 0).
  explicit Cam(const CamSpec& spec);
  Cam(const Cam&);
  Cam& operator=(const Cam&);
  Cam(Cam&&) noexcept;
  Cam& operator=(Cam&&) noexcept;
  ~Cam();

  /// Support-function geometry at cam angle θ [rad] (any real θ).
  CamPoint evaluate(double theta) const;
  /// X_C, Ẋ_C, Ẍ_C by the support-function form.
  CamMotion motion(double theta, double omega, double omega_dot) const;
  /// X_C, Ẋ_C, Ẍ_C by the paper's form (eqs. 8, 9, A7), computed from the profile's own
  /// derivatives at C (an independent path, used to cross-check motion()).
  CamMotion motion_paper(double theta, double omega, double omega_dot) const;

  /// max_θ h − min_θ h (the follower's total lift) [length].
  double lift() const;
  /// Smallest radius of curvature over the profile [length].
  double min_radius_of_curvature() const;

  /// A cam-frame point {x, y} of the profile at parameter a [rad] (for tests and plots):
  /// points — the spline at polar-angle parameter a; circle — (e + R cos a, R sin a);
  /// lift — the envelope point that is the contact point at cam angle a,
  /// R(−a)·(h(a), −h′(a)). As a runs over [0, 2π) the whole profile is traced.
  std::array<double, 2> profile_point(double a) const;

  /// Cam angles [rad, in [0, 2π), sorted] where the follower's acceleration or jerk may
  /// jump: the joints of a law, the tangency points of an arc cam (empty for the splines).
  const std::vector<double>& breakpoints() const;
  /// The motion law of cam.profile = "law" (nullptr otherwise).
  const MotionLaw* law() const;
  /// The cam's joints with their continuity order and jumps: a law's joints, or where a
  /// translating follower passes from one arc to the next (circle/arc/arcs cams); empty
  /// otherwise. A C0 joint (order 0: the follower's velocity jumps, a knife edge over a
  /// corner) is an impact of the cam on a held follower (docs/cam_laws.md).
  const std::vector<Breakpoint>& joints() const;
  /// "C1 at 12.5°, C0 at 40°, …" over joints() ("" when there are none).
  std::string continuity_report() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  void refine_min_rho();
};

/// An extreme of a quantity over one turn of the cam and the cam angle where it is taken.
struct CamExtremum {
  double value = std::numeric_limits<double>::quiet_NaN();
  double theta = std::numeric_limits<double>::quiet_NaN();  ///< [rad, in [0, 2π)]
};

/// The largest (`maximise`) or smallest value of f(cam.evaluate(θ)) over one turn: a scan of
/// `samples` cam angles; each local extremum of the scan refined by golden section between
/// its neighbours, the bracket cut at the cam's breakpoints; and the one-sided values at
/// every breakpoint (θ_b ∓ 1e-12 rad), so that an extreme at an arc joint or a law joint is
/// found to ~1e-12 of its slope, not to the scan's spacing. NaN values of f are skipped
/// (all NaN: a NaN result). @pre samples ≥ 16.
CamExtremum cam_extremum(const Cam& cam, const std::function<double(const CamPoint&)>& f, bool maximise,
                         int samples = 3600);

/// Cam drive θ(t), ω(t), ω̇(t): constant speed, or a piecewise-linear speed table
/// (θ integrated exactly, ω̇ piecewise constant).
class CamDrive {
 public:
  explicit CamDrive(const CamSpec& spec);
  double theta(double t) const;      ///< [rad]
  double omega(double t) const;      ///< [rad/s]
  double omega_dot(double t) const;  ///< [rad/s²]
  bool constant_speed() const { return table_t_.empty(); }
  /// The first time t* > t (at most `horizon`) at which θ(t*) ≡ one of `angles` (mod 2π);
  /// +inf if none before the horizon. Exact for the constant speed and for the speed
  /// table (θ piecewise quadratic). `angles` sorted in [0, 2π).
  double next_time_at_angles(double t, const std::vector<double>& angles, double horizon) const;

 private:
  double theta0_ = 0, omega0_ = 0;
  std::vector<double> table_t_, table_w_, table_theta_;  // knots, ω [rad/s], θ at knots
};

}  // namespace camdyn
