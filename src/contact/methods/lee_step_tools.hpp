// camdyn (private) — pieces of Lee's located step (methods/lee_located.cpp, for one contact or
// many; once shared with the single-follower located step, deleted in issue 23).
#pragma once

#include <algorithm>
#include <cmath>

namespace camdyn {
namespace detail {

/// Step sizes on the grid 2^(k/8) (the shape responses are cached per size).
inline double grid_step(double h) { return std::exp2(std::floor(std::log2(h) * 8.0) / 8.0); }

/// The quintic p(x) on [0, 1] with p, p', p'' given in time at both ends of a step of h
/// (u, u̇, ü at t and t + h): value u, rate v and acceleration a at x (null: not wanted).
inline void quintic(double u0, double v0, double a0, double u1, double v1, double a1, double h, double x,
                    double* u, double* v, double* a) {
  const double p0 = u0, d0 = v0 * h, s0 = a0 * h * h, p1 = u1, d1 = v1 * h, s1 = a1 * h * h;
  const double c0 = p0, c1 = d0, c2 = 0.5 * s0;
  const double c3 = 10 * (p1 - p0) - 6 * d0 - 4 * d1 - 1.5 * s0 + 0.5 * s1;
  const double c4 = -15 * (p1 - p0) + 8 * d0 + 7 * d1 + 1.5 * s0 - s1;
  const double c5 = 6 * (p1 - p0) - 3 * d0 - 3 * d1 - 0.5 * s0 + 0.5 * s1;
  if (u) *u = c0 + x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5))));
  if (v) *v = (c1 + x * (2 * c2 + x * (3 * c3 + x * (4 * c4 + x * 5 * c5)))) / h;
  if (a) *a = (2 * c2 + x * (6 * c3 + x * (12 * c4 + x * 20 * c5))) / (h * h);
}

/// The step-size controller of the located step. After an accepted step of hs whose error
/// asks for a factor fac, the next step grows only with a margin and not past 0.95 of the
/// last size that failed the error test (an explicit engine's error estimate jumps at its
/// stability limit: without the memory a bar on arkode-erk had 8–17 % of its steps
/// rejected there); that memory relaxes by 2 % per step. Shrinks at once. Sizes on the
/// grid 2^(k/8).
class StepSizeMemory {
 public:
  /// A step of hs failed the error test.
  void failed(double hs) { h_fail_ = hs; }
  double propose(double hs, double fac) {
    h_fail_ *= 1.02;
    fac = std::min(5.0, std::max(0.2, fac));
    if (fac < 1.25) return grid_step(hs * std::min(fac, 1.0));
    return grid_step(std::max(std::min(hs * fac / 1.1, 0.95 * h_fail_), grid_step(hs)));
  }

 private:
  double h_fail_ = INFINITY;
};

}  // namespace detail
}  // namespace camdyn
