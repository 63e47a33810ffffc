// camdyn (private) — the step sizes and output times every contact method steps by.
#pragma once

#include <algorithm>
#include <cmath>

#include "camdyn/scene.hpp"
#include "contact/run_failure.hpp"

namespace camdyn {
namespace detail {

/// The step to try from t toward t_next (an output time or t_end): at most h and
/// solver.max_step, and no slivers — a remainder below 1e-6 of the step is absorbed into
/// it, a remainder between one and two steps is split into two equal steps. A sliver step
/// cannot correct even round-off in the gap without a force ∝ gap/Δt², which fails the
/// error test, shrinks Δt, needs a still larger force — and Δt underflows
/// (docs/background/method_notes.md). @throws StepSizeUnderflow.
inline double fit_step_size(const Scene& sc, double t, double h, double t_next) {
  double hs = std::min(h, t_next - t);
  if (sc.solver.max_step > 0) hs = std::min(hs, sc.solver.max_step);
  const double rem = t_next - t;
  if (rem - hs < 1e-6 * hs)
    hs = rem;
  else if (rem < 2.0 * hs)
    hs = 0.5 * rem;
  if (hs <= 1e-14 * std::max(1.0, std::abs(t))) throw StepSizeUnderflow(hs);
  return hs;
}

/// The first step: solver.initial_step, or min(1e-4, t_end/100).
inline double first_step_size(const Scene& sc) {
  if (sc.solver.initial_step > 0) return sc.solver.initial_step;
  return std::min(1e-4, sc.run.t_end / 100.0);
}

/// The next output time after `next_out` − 1 outputs (t_end without output_dt).
inline double output_time(const Scene& sc, long next_out) {
  const double dt = sc.run.output_dt;
  return dt > 0 ? std::min(sc.run.t_end, double(next_out) * dt) : sc.run.t_end;
}

}  // namespace detail
}  // namespace camdyn
