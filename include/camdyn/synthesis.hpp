// camdyn — the cam from the valve lift: the follower motion a valve train needs, through its
// kinematics (lever ratio, finger follower, lash), written as a lift table (docs/cam_laws.md
// "From the valve lift to the cam").
#pragma once

#include <string>

#include "camdyn/cam.hpp"
#include "camdyn/cam_spec.hpp"
#include "camdyn/lift_table.hpp"
#include "camdyn/motion_law.hpp"
#include "camdyn/scene_error.hpp"

namespace camdyn {

/// The valve side of the train: how the follower coordinate q moves the valve.
///   translating follower (rocker of constant ratio, or a bucket with ratio 1):
///     q = s (the follower's lift), G(s) = ratio · s;
///   oscillating follower (cam.follower_motion = "oscillating", a finger): q = ψ (the arm's
///     rotation), the valve end at cam.valve_arm ℓ_v from the pivot pushing a flat valve
///     tip, the pivot-to-valve-end line at valve_end_angle_deg ψ₀ from the normal to the
///     valve axis at rest: G(ψ) = ℓ_v (sin(ψ₀ + ψ) − sin ψ₀), whose ratio dG/dψ =
///     ℓ_v cos(ψ₀ + ψ) changes with the angle.
/// The valve lift is V = G(q) − lash where G(q) > lash, 0 elsewhere (lash measured at the
/// valve, as a feeler gauge does).
struct ValveTrainOptions {
  /// translating: dV/ds, > 0 (default 1: a direct-acting bucket).
  double ratio = 1.0;
  /// oscillating: ψ₀ [deg], |ψ₀| < 90 (default 0: the arm normal to the valve axis at rest).
  double valve_end_angle_deg = 0.0;
  /// Valve lash [length], ≥ 0 (default 0).
  double lash = 0.0;
  /// With lash > 0: the cam takes up the lash over ramp_deg [deg] > 0 before the valve
  /// opens and after it closes (a 3-4-5 polynomial from the base circle to G⁻¹(lash); the
  /// valve lift must be 0 over both ramps).
  double ramp_deg = 0.0;
  /// Rows of the lift table, ≥ 16 (default 3600: every 0.1°).
  int points = 3600;
};

/// The synthesised cam: the follower coordinate's lift table and the designer checks of
/// the cam built from it (the profile by the follower's exact kinematics).
struct CamSynthesis {
  /// The follower coordinate as a lift table (with its derivatives): translating — the
  /// lift s; oscillating — X = ℓ_v ψ (what cam.profile = "table" reads).
  LiftTable table;
  double max_pressure_angle_deg = 0, max_pressure_angle_at_deg = 0;
  /// Smallest radius of curvature of the cam profile (convex parts) [length], and where.
  double min_radius_of_curvature = 0, min_radius_of_curvature_at_deg = 0;
  /// The follower coordinate's total lift [length].
  double lift = 0;
  /// The cam to run with: the given CamSpec with profile "table" reading the table file.
  CamSpec spec;
};

/// G⁻¹(y): the follower coordinate q (s, or ψ [rad]) that moves the valve side by y ≥ 0
/// (Newton on G, safeguarded by bisection; to round-off). @throws SceneError as
/// synthesise_cam_from_valve_lift does for y beyond the finger's reach.
double follower_coordinate_for_valve(const CamSpec& cam, const ValveTrainOptions& train, double y);

/// The cam that gives the valve lift `valve_lift` (L(θ) of a law or of a lift table,
/// MotionLaw::from_table) through the train: q(θ) = G⁻¹(V(θ) + lash) on the lobe, the
/// lash ramps off it, q′ = V′/G′(q), q″ = (V″ − G″(q) q′²)/G′(q); then the cam of
/// the table written to `table_path` (lift_table_csv) and the cam of `cam` with profile
/// "table" read back from that file (its profile and checks: undercut, concavity, toggle),
/// its extremes located by cam_extremum.
/// @pre valve_lift's minimum is 0 (the valve closed on the base circle).
/// @throws SceneError naming the key (ratio, valve_end_angle_deg, lash, ramp_deg, points,
/// cam.law, cam.valve_arm, …), the value and the rule: ratio ≤ 0, |ψ₀| ≥ 90°, lash < 0,
/// lash > 0 without a ramp, a ramp where the valve is open, a valve lift + lash beyond the
/// finger's reach ℓ_v (1 − sin ψ₀), a valve lift below 0, a file that cannot be written; and the Cam's own errors for a
/// profile the follower cannot make (undercut, concave under a flat face).
CamSynthesis synthesise_cam_from_valve_lift(const CamSpec& cam, const MotionLaw& valve_lift,
                                            const ValveTrainOptions& train, const std::string& table_path);

}  // namespace camdyn
