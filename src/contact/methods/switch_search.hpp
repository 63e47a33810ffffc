// camdyn (private) — the search for switches (a held contact's force reaching zero, an
// open gap closing) inside an accepted step of Lee's located step, on a function of the
// step's fraction x ∈ [0, 1] (src/contact/methods/lee_located.cpp).
#pragma once

#include <functional>

namespace camdyn {
namespace detail {

/// Samples of first_below over a step: x = k / kSwitchSamples, k = 0 … kSwitchSamples.
constexpr int kSwitchSamples = 8;

/// A point of a golden-section search and its value.
struct Sample {
  double x, f;
};
/// Golden-section search for the smallest f on [a, b] (n iterations): the better inner point.
Sample golden_min(const std::function<double(double)>& f, double a, double b, int n);
/// f(lo) ≥ 0 > f(hi): the fall through zero, bisected to round-off in time (step h ending at t1).
double bisect_fall(const std::function<double(double)>& f, double lo, double hi, double h, double t1);
/// First x ∈ (0, 1] where f falls below −thr: a sign change between kSwitchSamples + 1
/// samples, or a sampled minimum refined by golden section (grazing). −1 if none; else the
/// root of f = 0 after the last point where f ≥ 0 (bisection to round-off in time h).
/// `samples` (kSwitchSamples + 1 entries, may be null): the samples taken, f0 and f1 at the ends.
double first_below(const std::function<double(double)>& f, double f0, double f1, double thr, double h,
                   double t1, double* samples = nullptr);
/// ∫₀^xb p(x) dx of samples p_k = p(k / kSwitchSamples) (k = 0 … kSwitchSamples), on their
/// piecewise quartic interpolant (panels of four intervals: composite Boole over [0, 1]).
double sampled_integral(const double* p, double xb);
/// For a gap that starts a round-off below zero while opening: the first x where it falls
/// below zero after rising to its highest; −1 if it never reaches zero or does not fall back.
double reclosing(const std::function<double(double)>& f, double h, double t1);

}  // namespace detail
}  // namespace camdyn
