// camdyn — the cam's input: its profile, drive, follower geometry and designer data
// (CamSpec, the [cam] table of a scene) with its enumerations. The cam (camdyn/cam.hpp) is
// built from it alone; camdyn/scene.hpp includes it, so a Scene's `cam` is this CamSpec.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace camdyn {

// ---- the cam's enumerations, each with a to_string / parse_enum pair (src/cam/cam_spec.cpp);
// ---- parse_enum returns false on an unknown spelling.
enum class CamProfileKind { Points, Lift, Circle, Law, Arc, Arcs, Table };
enum class FollowerFace { Flat, KnifeEdge, Roller, Point };
enum class FollowerMotion { Translating, Oscillating };

const char* to_string(CamProfileKind v);    // "points" | "lift" | "circle" | "law" | "arc" | "arcs" | "table"
const char* to_string(FollowerFace v);      // "flat" | "knife_edge" | "roller" | "point"
const char* to_string(FollowerMotion v);    // "translating" | "oscillating"

bool parse_enum(std::string_view s, CamProfileKind* out);
bool parse_enum(std::string_view s, FollowerFace* out);
bool parse_enum(std::string_view s, FollowerMotion* out);

/// The cam: profile and drive.
struct CamSpec {
  /// Profile representation.
  CamProfileKind profile = CamProfileKind::Points;
  /// points: polar angles of the spline knots [deg], strictly increasing, span < 360, ≥ 4.
  std::vector<double> angles_deg{0, 45, 90, 135, 180, 225, 270, 315};
  /// points: radii of the knots [length], > 0, same count as angles_deg.
  std::vector<double> radii{2.0, 2.0, 2.0, 2.1, 3.0, 2.1, 2.0, 2.0};
  /// lift: base-circle radius r_b [length], > 0.
  double base_radius = 2.0;
  /// lift: cam angles of the lift table [deg], strictly increasing, span < 360, ≥ 4.
  std::vector<double> lift_angles_deg;
  /// lift: follower lift L(θ) [length] at lift_angles_deg; r_b + L > 0; periodic spline.
  std::vector<double> lift;
  /// circle: radius R [length], > 0.
  double radius = 2.0;
  /// circle: eccentricity e [length], 0 ≤ e < R (centre at (e, 0) in the cam frame).
  double eccentricity = 0.5;
  /// Constant cam speed [rev/s], finite (any sign). Ignored when a speed table is given.
  double speed_rev_s = 1.75;
  /// Optional speed table: times [s] (strictly increasing, first = 0) and speeds [rev/s];
  /// ω(t) is piecewise linear between entries and constant after the last one.
  std::vector<double> speed_table_t;
  std::vector<double> speed_table_rev_s;
  /// Cam angle at t = 0 [deg], finite.
  double theta0_deg = 0.0;

  // ---- motion laws, arc cams, follower geometry, designer results
  // ---- (docs/cam_laws.md). Defaults leave the three profiles above unchanged.
  /// law: the segments, "KIND DURATION_DEG [RISE] …; …" spanning 360° (MotionLaw::parse).
  std::string law;
  /// table: the lift-table CSV file (docs/cam_laws.md "Lift tables"; a relative path is
  /// taken relative to the scene file when the scene is loaded from a file). Its lift is
  /// the follower coordinate's as cam.law's would be (flat/knife edge/roller: r_b + L;
  /// oscillating: X = ℓ_v ψ).
  std::string lift_table;
  /// arc: nose radius r_n [length], 0 < r_n < base_radius.
  double nose_radius = 0.5;
  /// arc: distance d of the nose centre from the cam centre [length], > 0.
  double nose_distance = 1.5;
  /// arc: flank radius R_f [length], > base_radius (tangent to base and nose arcs).
  double flank_radius = 6.0;
  /// arcs: the arcs of cam.profile = "arcs", one entry per arc in each list, in order
  /// counter-clockwise round the cam (docs/cam_laws.md "Arc cams as a list"). The centre
  /// in the cam frame, Cartesian (arc_centre_x, arc_centre_y) [length] or polar
  /// (arc_centre_r [length], arc_centre_deg [deg]): one of the two pairs.
  std::vector<double> arc_centre_x, arc_centre_y, arc_centre_r, arc_centre_deg;
  /// arcs: signed radius [length]: > 0 a convex arc (the cam on the centre's side), < 0 a
  /// concave arc (the centre outside the cam).
  std::vector<double> arc_radius;
  /// arcs: the arc's first and last point as directions from its own centre [deg],
  /// traversed counter-clockwise round the cam: to > from for a convex arc, to < from for
  /// a concave one; 0 < |to − from| ≤ 360. Consecutive arcs (and the last and the first)
  /// must meet; where their tangents differ the joint is a corner.
  std::vector<double> arc_from_deg, arc_to_deg;
  /// Contact face of the translating follower: flat (the paper's), knife_edge, roller, or
  /// point (law only: the lift is imposed, no cam shape, no base radius needed).
  FollowerFace follower_face = FollowerFace::Flat;
  /// knife_edge/roller: offset ε of the follower axis from the cam centre, along +Y [length].
  double follower_offset = 0.0;
  /// roller: roller radius R_r [length], > 0.
  double roller_radius = 0.0;
  /// translating (the default) or oscillating: a finger follower or rocker turning about a
  /// pivot, with a flat pad or a roller (follower_face "flat" or "roller"; profile law,
  /// circle or arc). docs/cam_laws.md "Oscillating followers".
  FollowerMotion follower_motion = FollowerMotion::Translating;
  /// oscillating: the pivot's position relative to the cam centre, fixed frame [length].
  double pivot_x = 0.0;
  double pivot_y = 0.0;
  /// oscillating roller: distance from the pivot to the roller centre [length], > 0.
  double arm_length = 0.0;
  /// oscillating flat: signed distance of the pad line from the pivot [length].
  double pad_offset = 0.0;
  /// oscillating: distance ℓ_v from the pivot to the valve end [length], > 0; the follower
  /// coordinate is X = ℓ_v ψ (ψ: the arm's rotation), and a law gives X.
  double valve_arm = 0.0;
  /// Hand the cam's breakpoints (law joints, arc tangency points) to the integrator as
  /// stop times, so that steps land on them.
  bool land_on_breaks = true;
  /// Designer results: cam width b [length] (0: no Hertz stress), Young's moduli
  /// [force/length²] > 0 and Poisson ratios in [0, 0.5) of cam and follower face.
  double width = 0.0;
  double youngs_modulus = 2.1e5;
  double poisson_ratio = 0.3;
  double follower_youngs_modulus = 2.1e5;
  double follower_poisson_ratio = 0.3;
  /// Friction at the cam contact (results only: history columns sliding_speed,
  /// cam_friction_force, cam_friction_torque, cam_friction_power and summary fields; a
  /// translating follower): Coulomb coefficient μ ≥ 0 (0: off), with a Stribeck rise to
  /// friction_static_coefficient μ_s ≥ μ at low sliding speed when friction_stribeck_speed
  /// v_st > 0: μ(v) = μ + (μ_s − μ)·exp(−(v/v_st)²). roller_slip ∈ [0, 1]: a roller's sliding
  /// speed as a fraction of its rolling speed (0: pure rolling, no sliding friction).
  double friction_coefficient = 0.0;
  double friction_static_coefficient = 0.0;
  double friction_stribeck_speed = 0.0;
  double roller_slip = 0.0;
};

}  // namespace camdyn
