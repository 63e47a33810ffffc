// camdyn (private) — the cam's breakpoints as stop times of a run (issue 24). A method asks
// before(t, t_next) for the time to step toward: t_next, or the first breakpoint time in
// (t, t_next) — the joints of a motion law, the tangency points of an arc cam — so that
// steps land on them (cam.land_on_breaks).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/cam_spec.hpp"

namespace camdyn {
namespace detail {

class CamStops {
 public:
  /// `horizon`: the run's end time (no breakpoint time is looked for beyond it).
  CamStops(const CamSpec& spec, double horizon, const Cam& cam) : drive_(spec), horizon_(horizon) {
    if (spec.land_on_breaks) angles_ = cam.breakpoints();
  }
  bool empty() const { return angles_.empty(); }
  /// min(t_next, first breakpoint time after t).
  double before(double t, double t_next) const {
    if (angles_.empty()) return t_next;
    if (!(next_ > t && from_ <= t)) {
      from_ = t;
      next_ = drive_.next_time_at_angles(t, angles_, horizon_);
    }
    return std::min(t_next, next_);
  }

 private:
  CamDrive drive_;
  double horizon_;
  std::vector<double> angles_;
  mutable double from_ = INFINITY, next_ = -INFINITY;
};

}  // namespace detail
}  // namespace camdyn
