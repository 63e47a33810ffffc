// camdyn (private) — the surge amplitude of springs with coil masses (summary.json "surge";
// docs/guide/elements.md "Surge amplitude"): the largest departure of the coils from the
// quasi-static (linear) deflection shape, over the run and per camshaft revolution.
#pragma once

#include <string>
#include <vector>

#include "camdyn/summary.hpp"

namespace camdyn {
namespace detail {

class SurgeTracker {
 public:
  /// `springs`: the springs' report names (MechanicalSystem::surge_names); `theta0` the cam
  /// angle at t = 0 [rad] (revolutions count from it).
  SurgeTracker(const std::vector<std::string>& springs, double theta0);
  bool empty() const { return out_.empty(); }
  /// One sample at cam angle θ [rad]: `amp[i]` the surge of spring i (|x − x_static| max).
  void sample(double theta, const double* amp);
  /// The results into s.surge.
  void finish(Summary& s) const { s.surge = out_; }

 private:
  std::vector<SurgeResult> out_;
  double theta0_ = 0;
};

}  // namespace detail
}  // namespace camdyn
