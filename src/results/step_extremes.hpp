// camdyn (private) — extremes of a designer quantity located inside each accepted step, not
// at the output rows or the step ends only (a result that depends on the output grid is a
// defect; issue 37 "exact extremes", issue 38 "per landing").
//
// Every contact method hands its accepted step [t0, t1] to ContactRun::trace_step with the
// step's own dense state (the interpolant the rows are made from) and its contact forces
// there; trace_step samples the step at kStepSamples points x = k/(kStepSamples − 1) of it
// (StepSample) and the results (DesignerStats, RunAnalysis, the per-contact results) locate
// each quantity's extreme in the step with locate_extreme: the best sample, and where the
// parabola through it and its neighbours puts an extreme inside the step that may beat the
// extreme so far, golden-section search on the step's interpolant (StepProbe) to its
// resolution. The step ends are one-sided (the cam is evaluated just inside the step: a
// cam joint is a step end, so a corner's two values come from the two steps beside it).
#pragma once

#include <functional>
#include <vector>

#include "camdyn/cam.hpp"

namespace camdyn {
namespace detail {

/// The state of one accepted step at its fraction x ∈ [0, 1].
struct StepSample {
  double x = 0, t = 0;
  double theta = 0;       ///< cam angle [rad] (just inside the step at its ends)
  double omega = 0;       ///< cam speed [rad/s]
  double X = 0;           ///< the cam's lift above its base circle
  double Xdot = 0;        ///< its rate dX/dt
  double F = 0;           ///< the primary (cam) contact's force, 0 unless held over the step
  double Fc = 0;          ///< Σ of the cam contacts' forces
  bool held = false;      ///< the primary contact is held over the step
  std::vector<double> forces, gaps, gap_rates;  ///< per contact
  std::vector<char> in_set;                     ///< per contact: held over the step
  std::vector<double> nodes;                    ///< named nodes' displacements (when asked for)
  /// The cam at theta, evaluated on first use and kept: the side load, the designer's
  /// quantities and the film all read it. Every reader passes the run's cam.
  const CamPoint& cam_point(const Cam& cam) const {
    if (!cam_valid) {
      cam_pt = cam.evaluate(theta);
      cam_valid = true;
    }
    return cam_pt;
  }
  mutable CamPoint cam_pt;         ///< cam_point's value (valid when cam_valid)
  mutable bool cam_valid = false;  ///< cleared whenever theta is set
};
/// The step's state at x (fills every field of the sample).
using StepProbe = std::function<void(double x, StepSample&)>;

/// Samples per step, the ends included.
constexpr int kStepSamples = 3;

/// The extreme of a quantity over one step located by locate_extreme.
struct LocatedExtreme {
  double x = 0;        ///< where in the step (fraction)
  double value = 0;    ///< the quantity there
  bool found = false;  ///< false: every sample was NaN
};

/// The least gain, relative to the samples' magnitude, that the parabola's vertex must
/// promise over the best sample for locate_extreme to search (below it the search could
/// move the extreme by less than that).
constexpr double kSearchGain = 1e-13;

/// The largest (sign = +1) or least (sign = −1) value of a quantity over one step from its
/// samples q[k] at x[k] (k = 0..n−1, ascending, x[0] = 0, x[n−1] = 1; NaN samples are
/// skipped): the best sample; and where the parabola through the best sample and its two
/// neighbours has its extreme inside the step (between the neighbours), better than the
/// best sample by more than kSearchGain of the samples' magnitude and beyond `record` (the
/// extreme so far, NaN: none), golden-section search of f (the quantity on the step's
/// interpolant) between those neighbours, to 1e-9 of the step.
LocatedExtreme locate_extreme(const double* x, const double* q, int n, int sign, double record,
                              const std::function<double(double)>& f);

/// Golden-section search for the largest f on [a, b] (unimodal there), `iters` reductions;
/// the best point evaluated (the ends included as fa, fb).
LocatedExtreme golden_max(const std::function<double(double)>& f, double a, double fa, double b, double fb,
                          int iters = 44);

/// The root of f on [a, b] with f(a) > 0 ≥ f(b) (Illinois false position), to 1e-12 of
/// b − a or |f| = 0.
double falling_root(const std::function<double(double)>& f, double a, double fa, double b, double fb);

}  // namespace detail
}  // namespace camdyn
