// camdyn — cam motion laws: the follower's lift as piecewise segments over the
// cam angle, with exact derivatives up to the jerk.
//
//   A law is a list of segments that together span exactly 360°. Segment i starts at cam
//   angle θ_i (θ_0 = 0), lasts β_i and changes the lift by H_i:
//     L(θ) = L_i + H_i f(x),   x = (θ − θ_i)/β_i ∈ [0, 1],   f(0) = 0, f(1) = 1,
//     L′ = H f′/β,  L″ = H f″/β²,  L‴ = H f‴/β³   (per radian of cam angle).
//   Normalised laws f (Norton, Cam Design and Manufacturing Handbook, ch. 3):
//     dwell                 f = 0 (H must be 0)
//     ramp                  f = x (constant velocity: lash take-up ramps)
//     harmonic (shm)        f = (1 − cos πx)/2                          C_v = π/2,  C_a = π²/2
//     cycloidal             f = x − sin(2πx)/(2π)                       C_v = 2,    C_a = 2π
//     poly345               f = 10x³ − 15x⁴ + 6x⁵                       C_v = 1.875, C_a = 5.7735
//     poly4567              f = 35x⁴ − 84x⁵ + 70x⁶ − 20x⁷               C_v = 2.1875, C_a = 7.5132
//     poly                  f = Σ c_k x^k (given coefficients; c_0 = 0, Σ c_k = 1)
//     modtrap               modified trapezoid: sine / constant / cosine / constant / sine
//                           acceleration in eighths                      C_v = 2,    C_a = 4.888
//     modsine               modified sine: sine quarter-waves of period β/2 and 3β/2
//                                                                        C_v = 1.76, C_a = 5.528
//     polydyne              Dudley's polydyne: the valve's intended motion x = H p(x),
//                           p = 126x⁵ − 420x⁶ + 540x⁷ − 315x⁸ + 70x⁹ (C⁴ at both ends), and
//                           the cam lift that makes a valve of mass m on a valve spring k_s,
//                           driven through a train of stiffness k, follow it exactly at
//                           the design speed ω:  m ẍ = k (y − x) − k_s x  ⇒
//                             y = (1 + k_s/k) x + (m ω²/k) x″(θ).
//                           The segment's cam lift therefore changes by (1 + k_s/k) H.
//   Angles are in degrees in the scene, radians in this API.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace camdyn {

/// One segment of a motion law.
enum class MotionSegmentKind {
  Dwell, Ramp, Harmonic, Cycloidal, Poly345, Poly4567, Poly, ModTrap, ModSine, Polydyne
};

const char* to_string(MotionSegmentKind k);

/// A segment as the user gives it (cam.law, docs/interface.md).
struct MotionSegment {
  MotionSegmentKind kind = MotionSegmentKind::Dwell;
  double duration_deg = 0;  ///< β [deg], > 0
  double rise = 0;          ///< H [length]: > 0 a rise, < 0 a fall (the valve's for polydyne)
  std::vector<double> coefficients;  ///< poly: c_0 … c_n
  /// polydyne: train stiffness k [force/length] > 0, valve mass m > 0, valve spring k_s ≥ 0,
  /// design speed [rev/s] ≠ 0.
  double k = 0, m = 0, ks = 0, speed_rev_s = 0;
};

/// L, L′, L″, L‴ at one cam angle [length, length/rad, length/rad², length/rad³].
struct LiftDerivs {
  double L = 0, L1 = 0, L2 = 0, L3 = 0;
};

/// Continuity at the start of a segment (the joint with the previous one).
struct Breakpoint {
  double theta = 0;  ///< cam angle [rad], in [0, 2π)
  /// Highest derivative order continuous across the joint: 0 (C0: velocity jumps),
  /// 1 (C1: acceleration jumps), 2 (C2: jerk jumps), 3 (jerk continuous).
  int order = 0;
  std::array<double, 4> jump{};  ///< right − left of L, L′, L″, L‴
};

/// Peak coefficients of a normalised law f on [0, 1]: max |f′|, max |f″|, max |f‴|.
struct PeakCoefficients {
  double Cv = 0, Ca = 0, Cj = 0;
};

/// A validated periodic motion law. Evaluation is O(1) per call after locating the segment
/// (≤ log₂ n comparisons). Thread-safe (immutable after construction).
class MotionLaw {
 public:
  /// @throws SceneError (key `key`) naming the segment and rule: durations > 0 summing to
  /// 360°, finite values, dwell with a rise, poly coefficients with c_0 ≠ 0 or Σ ≠ 1,
  /// polydyne parameters out of range, a lift that does not close over the revolution.
  explicit MotionLaw(std::vector<MotionSegment> segments, const std::string& key = "cam.law");
  /// Parses the cam.law string (grammar in docs/cam_laws.md) and builds the law.
  /// @throws SceneError (file "<cam>", the key) on a syntax error, naming the segment and token.
  static MotionLaw parse(const std::string& text, const std::string& key = "cam.law");
  /// A law interpolating a lift table (cam.profile = "table", docs/cam_laws.md "Lift
  /// tables"): cam angles [deg], lifts L [length] and, when given (both or neither), dL/dθ
  /// [length/deg] and d²L/dθ² [length/deg²]. With the derivatives each interval is the
  /// quintic Hermite polynomial matching L, L′, L″ at both ends (C² across the knots; exact
  /// for any quintic); without them, the periodic C² cubic spline through the lifts.
  /// Periodic over 360°; segments() is empty; breakpoints() lists the knots where a dwell
  /// of the table (L constant, L′ = L″ = 0) meets motion (order 2), so that steps land on
  /// them (the interpolant is C² at every knot). @throws SceneError (key `key`) on fewer than 4 rows, angles not strictly
  /// increasing or spanning 360° or more, sizes that differ, non-finite values.
  static MotionLaw from_table(const std::vector<double>& angle_deg, const std::vector<double>& lift,
                              const std::vector<double>& dlift_ddeg, const std::vector<double>& d2lift_ddeg2,
                              const std::string& key = "cam.lift_table");
  /// True for a law built by from_table.
  bool is_table() const { return !tab_t_.empty(); }

  /// L and derivatives at cam angle θ [rad] (any real θ; periodic).
  LiftDerivs eval(double theta) const;
  /// The joints between segments (cam angles and continuity order), one per segment start.
  const std::vector<Breakpoint>& breakpoints() const { return breaks_; }
  /// Lift range max L − min L over the revolution [length].
  double lift() const { return lmax_ - lmin_; }
  double min_lift() const { return lmin_; }
  const std::vector<MotionSegment>& segments() const { return segs_; }
  /// "C2 at 0°, C0 at 20°, …" (one entry per joint).
  std::string continuity_report() const;

  /// The normalised law of a segment kind evaluated at x ∈ [0, 1]: {f, f′, f″, f‴}
  /// (Poly uses `coefficients`; Polydyne returns the valve's p).
  static std::array<double, 4> normalised(MotionSegmentKind kind, double x,
                                          const std::vector<double>& coefficients = {});

 private:
  std::vector<MotionSegment> segs_;
  std::vector<double> start_;  // θ_i [rad], n + 1 entries (last = 2π)
  std::vector<double> beta_;   // β_i [rad]
  std::vector<double> L0_;     // lift at segment start
  std::vector<Breakpoint> breaks_;
  double lmin_ = 0, lmax_ = 0;
  // from_table: knots [rad] (n + 1, the last = first + 2π) with L, L′, L″ there
  std::vector<double> tab_t_, tab_L_, tab_L1_, tab_L2_;
  MotionLaw() = default;
  LiftDerivs eval_table(double theta) const;
  LiftDerivs eval_segment(std::size_t i, double u) const;  // u = θ − θ_i
};

}  // namespace camdyn
