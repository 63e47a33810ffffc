// camdyn (private) — results of a run that an acceptance criterion judges (issue 38), made
// from the output rows and the events only:
//   oil film     [lubricant]: Hamrock's line-contact film at the cam contact per row
//                (results/oil_film.hpp) from the cam's force per width, the reduced radius
//                (cam curvature with the roller or the flat face) and the entrainment speed
//                (flat face: ũ = −½ω(X_C + 2X_C″); roller, rolling: the contact point's speed
//                over the cam's surface, entrainment());
//                history columns film_thickness (and lambda), the least with its cam angle;
//   lift deviation  run.valve_node: the valve's displacement minus its kinematic lift
//                (results/kinematic_path.hpp); history column lift_deviation, extremes per revolution;
//   seat landings  every impact on a seat (stop contact, side "below"): a landing when the
//                cam lifted the seat's node past its take-up since the previous impact on that
//                seat, else a bounce of the current landing, its height the largest seat gap
//                between the two impacts: the apex of the flight located inside the step
//                (the root of the gap rate on the step's interpolant; the rows for a method
//                that does not trace its steps);
//   ramp velocity  the cam's |Ẋ| where its lift crosses a take-up level > 0 (the root of
//                X(t) − L inside each traced step; linear between rows only when not traced);
//   valve timing  a [camshaft]: each valve's dynamic opening and closing angles against its
//                kinematic ones (results/valve_timing.hpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"
#include "results/kinematic_path.hpp"
#include "results/oil_film.hpp"
#include "results/step_extremes.hpp"
#include "results/valve_timing.hpp"

namespace camdyn {
namespace detail {

/// A seat: a stop contact below its node in the scene's [[contacts]]; its impacts are the
/// seat landings and bounces (RunAnalysis, Summary::landings).
inline bool is_seat(const ContactPointSpec& cp) {
  return cp.kind == ContactPointKind::Stop && cp.side == StopSide::Below && !cp.nodes.empty();
}

class OscillatingGeometry;
class DesignerColumns;

class RunAnalysis {
 public:
  /// The history columns it adds for `scene` (after the designer columns): film_thickness
  /// and lambda ([lubricant], lambda with a roughness > 0), lift_deviation (run.valve_node).
  /// @throws SceneError (run.valve_node) when the valve is not reached from a cam contact.
  static std::vector<std::string> columns(const Scene& scene);

  /// `contacts`, `nodes`: the mechanism's contact names and named nodes (the order of the
  /// gaps and displacements row() is given); `lift`: the cam's lift (the 1 % take-up band).
  RunAnalysis(const Scene& scene, const std::vector<std::string>& contacts, const std::vector<std::string>& nodes,
              double lift, const Cam* cam = nullptr);

  /// The cam lifts where a clearance on a path from the cam is taken up (KinematicPath).
  const std::vector<double>& take_up_levels() const { return path_.take_up_levels(); }
  /// Anything to compute per row (a film, a valve, a seat or a take-up level > 0).
  bool per_row() const { return per_row_; }
  /// An output row: cam angle θ [rad], the cam point there, the cam's lift X above its base
  /// and Ẋ, ω, the cam's axial force Fc, each contact's gap, each named node's displacement.
  /// Appends the columns of columns() to `out`.
  void row(double t, double theta, const CamPoint& p, double X, double Xdot, double omega, double Fc,
           const std::vector<double>& gaps, const std::vector<double>& u, std::vector<double>& out);
  /// One accepted step (step_extremes.hpp): the least film located inside it, and each
  /// open seat's highest gap (the apex: the root of its gap rate inside the step). Once a
  /// method traces its steps, these come from the steps only, not from the rows.
  void step_inside(const std::vector<StepSample>& s, const StepProbe& probe);
  /// The named nodes' displacements are needed in the step samples (run.valve_node, a
  /// camshaft's valve timing).
  bool wants_nodes() const { return valve_ >= 0 || timing_.active(); }
  /// Every contact's gap and gap rate are needed in the step samples (the seats' landings).
  bool wants_gaps() const { return !seats_.empty(); }
  /// An event of contact `j`.
  void event(const ContactEvent& e, int j);
  /// Film, lift deviation, ramp velocity, landings and valve timing into `s`.
  void finish(Summary& s) const;

  /// The film at one state (exposed for tests): h_min, NaN when apart or no conjunction.
  double film(const CamPoint& p, double omega, double Fc) const;
  /// The entrainment speed |ũ| at the cam point p (exposed for tests). Flat face
  /// (translating): |½ω(X_C + 2X_C″)|. Roller, rolling: the speed at which the contact point
  /// travels over the cam's surface, |ω|·|dc/dθ| with c(θ) = r(θ)(cos(β − θ), sin(β − θ)) the
  /// contact point in the cam's frame (the cam turns counter-clockwise), by central
  /// differences (δθ = 1e-6) on the cam: any roller follower, translating with an offset or
  /// oscillating.
  double entrainment(const CamPoint& p, double omega) const;
  /// The flat pad of an oscillating follower: |ũ| at cam angle θ from the contact point's
  /// travel over the cam and along the pad (run_analysis.cpp; exposed for tests).
  double pad_entrainment(double theta, double omega) const;

 private:
  const Scene& sc_;
  const Cam* cam_ = nullptr;
  KinematicPath path_;
  ValveTiming timing_;
  bool film_ = false, lambda_ = false, per_row_ = false;
  Lubricant oil_;
  double Ep_ = 0, width_ = 0, rr_ = 0;
  bool roller_ = false;
  std::shared_ptr<const OscillatingGeometry> pad_;  // an oscillating flat pad's kinematics
  std::shared_ptr<const DesignerColumns> pad_friction_;  // its friction: the normal force of F
  double pivot_x_ = 0, pivot_y_ = 0;
  int valve_ = -1;  // index in the nodes
  KinematicNode valve_path_;
  double band_ = 0;  // 1 % of the cam's lift
  double theta0_ = NAN;
  bool traced_ = false;  // step_inside has run: the rows add no extreme
  void keep_deviation(double theta, double d);  // the lift deviation d at θ into its revolution
  // results
  double min_h_ = NAN, min_h_theta_ = NAN, min_lambda_ = NAN;
  std::vector<LiftDeviationRevolution> dev_;
  double ramp_ = NAN, ramp_theta_ = NAN;
  double prev_X_ = NAN, prev_Xdot_ = 0, prev_theta_ = 0;
  // seats: per seat contact, its rows (t, gap, X) and its impacts
  struct Seat {
    int contact = -1;
    std::string name;
    double opened_at = 0;  // the cam lift past which the seat's node is lifted
    std::vector<double> t, gap, X;  // per row, or per run of traced steps between impacts
    std::vector<ContactEvent> impacts;
    std::size_t merged_impacts = std::size_t(-1);  // impacts when the last traced entry was made
  };
  std::vector<Seat> seats_;
};

}  // namespace detail
}  // namespace camdyn
