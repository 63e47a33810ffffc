// camdyn (private) — each valve's timing on a camshaft (issue 40 item 4; summary.json
// "valve_timing", include/camdyn/summary.hpp ValveTimingResult).
//
//   The valves: for every cam contact of a scene with a [camshaft], each seat (a stop contact
//   on side "below") whose node its kinematic path reaches (results/kinematic_path.hpp); a
//   train without a seat has its follower (the cam contact's node) as its valve.
//   The valve is open while its displacement u exceeds the threshold h = 1 % of its kinematic
//   lift, h = 0.01·a·(X_max − b) (a, b its path's gain and take-up, X_max the cam's largest
//   lift above the base circle): the 1 % of the lift the take-up band and the float test use.
//   Kinematic angles: the cam angles ψ (the cam's own angle, station angle − offset) where the
//   kinematic lift a·max(0, X_L(ψ) − b) crosses h: the opening the first upward crossing after
//   the middle of the longest closed interval, the closing the last downward crossing before
//   it (one lift event per revolution; a cam with several lobes spans them all).
//   Dynamic angles: the crank's angle minus the cam's offset, θ_c(t) − α_i (the angle the cam
//   would have on a rigid shaft and drive; camshaft degrees, twice in crank degrees), at the
//   times u(t) crosses h: per cycle (one cam revolution of that angle from the middle of the
//   longest closed interval) the first upward and the last downward crossing, located inside
//   each accepted step (the root of u − h on the step's interpolant), linear between output
//   rows for a method that does not trace its steps. The timing error is dynamic − kinematic
//   (> 0: late), wrapped to (−180°, 180°]: the shaft's and drive's wind-up, the train's
//   compliance and its dynamics together. The result is the last cycle with both crossings.
#pragma once

#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"
#include "results/kinematic_path.hpp"
#include "results/step_extremes.hpp"

namespace camdyn {
namespace detail {

class ValveTiming {
 public:
  /// The valves of `scene`'s camshaft (none without a [camshaft]); `nodes`: the named nodes
  /// in the order of the displacements sample() and StepSample::nodes give.
  ValveTiming(const Scene& scene, const KinematicPath& path, const std::vector<std::string>& nodes);
  /// There is a valve to time.
  bool active() const { return !valves_.empty(); }
  /// One output row: θ the [cam] drive's angle [rad], u the named nodes' displacements
  /// (crossings linear between rows). Ignored once step() has run.
  void row(double theta, const std::vector<double>& u);
  /// One accepted step (StepSample::nodes filled): crossings located on the step's interpolant.
  void step(const std::vector<StepSample>& s, const StepProbe& probe);
  /// The valves' results, in the order of the cam contacts and their seats.
  std::vector<ValveTimingResult> results() const;

  /// The crank's angle θ_c = θ + Σ a_k sin(n_k θ + p_k) at the drive angle θ [rad]
  /// (mechanism/camshaft.hpp CamShaft::crank).
  double crank_angle(double theta) const;

 private:
  struct Valve {
    ValveTimingResult res;
    int node = -1;           // index in the named nodes
    double alpha = 0.0;      // the cam's offset [rad]
    double open_kin = 0.0, close_kin = 0.0, boundary = 0.0;  // [rad]: ψ_open, ψ_close < ψ_open + 2π, cycle start
    // the cycle being observed
    long cycle = 0;
    bool started = false, above = false, complete = false;
    double up = 0.0, down = 0.0;  // its first upward and last downward crossing [rad], NaN: none
    double prev_a = 0.0, prev_u = 0.0;  // the previous row
  };
  static void advance(Valve& v, double a);  // to the dynamic angle a: a new cycle closes the last
  static void close_cycle(Valve& v);
  static void crossing(Valve& v, double a, bool upward);
  std::vector<double> order_, amp_, phase_;
  std::vector<Valve> valves_;
  bool traced_ = false;
};

}  // namespace detail
}  // namespace camdyn
