// camdyn — the search for switches inside an accepted step of Lee's located step
// (switch_search.hpp).
#include "contact/methods/switch_search.hpp"

#include <algorithm>
#include <cmath>

namespace camdyn {
namespace detail {

Sample golden_min(const std::function<double(double)>& f, double a, double b, int n) {
  const double gr = 0.6180339887498949;
  double c = b - gr * (b - a), d = a + gr * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < n; ++i) {
    if (fc < fd) {
      b = d; d = c; fd = fc; c = b - gr * (b - a); fc = f(c);
    } else {
      a = c; c = d; fc = fd; d = a + gr * (b - a); fd = f(d);
    }
  }
  return fc < fd ? Sample{c, fc} : Sample{d, fd};
}

// f(lo) ≥ 0 > f(hi): the fall through zero, bisected to round-off in time (step h ending
// at t1); returns the first point found below zero.
double bisect_fall(const std::function<double(double)>& f, double lo, double hi, double h, double t1) {
  for (int i = 0; i < 100 && (hi - lo) * h > 4e-16 * std::max(1.0, std::abs(t1)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) >= 0.0 ? lo : hi) = mid;
  }
  return hi;
}

// First x ∈ (0, 1] where f falls below −thr: a sign change between K + 1 samples, or a
// sampled minimum refined by golden section (grazing). −1 if none; else the root of f = 0
// after the last point where f ≥ 0 (bisection to round-off in time h).
double first_below(const std::function<double(double)>& f, double f0, double f1, double thr, double h,
                   double t1, double* samples) {
  constexpr int K = kSwitchSamples;
  double s_own[K + 1];
  double* s = samples ? samples : s_own;
  s[0] = f0;
  s[K] = f1;
  for (int k = 1; k < K; ++k) s[k] = f(double(k) / K);
  double lo = -1, hi = -1;
  for (int k = 1; k <= K; ++k) {
    if (s[k] < -thr) {
      lo = double(k - 1) / K;
      hi = double(k) / K;
      break;
    }
    if (k < K && s[k] <= s[k - 1] && s[k] <= s[k + 1] &&
        s[k] < thr + std::abs(s[k - 1] - s[k]) + std::abs(s[k + 1] - s[k])) {
      const Sample m = golden_min(f, double(k - 1) / K, double(k + 1) / K, 40);
      if (m.f < -thr) {
        lo = double(k - 1) / K;
        hi = m.x;
        break;
      }
    }
  }
  if (lo < 0) return -1.0;
  if (f(lo) < 0) return lo;
  return bisect_fall(f, lo, hi, h, t1);
}

double sampled_integral(const double* p, double xb) {
  static_assert(kSwitchSamples % 4 == 0, "quartic panels");
  constexpr double d = 1.0 / kSwitchSamples;
  static const double xg[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double wg[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  xb = std::min(std::max(xb, 0.0), 1.0);
  double sum = 0.0;
  for (int k0 = 0; k0 < kSwitchSamples && k0 * d < xb; k0 += 4) {
    const double a = k0 * d, b = std::min((k0 + 4) * d, xb);
    if (b == (k0 + 4) * d) {  // a whole panel: Boole's rule
      sum += d * (2.0 / 45.0) * (7.0 * (p[k0] + p[k0 + 4]) + 32.0 * (p[k0 + 1] + p[k0 + 3]) + 12.0 * p[k0 + 2]);
      continue;
    }
    for (int g = 0; g < 3; ++g) {  // part of one: its quartic by 3-point Gauss (exact)
      const double u = (a + 0.5 * (b - a) * (1.0 + xg[g])) / d - k0;  // in samples from a
      double l = 0.0;
      for (int i = 0; i <= 4; ++i) {
        double c = p[k0 + i];
        for (int q = 0; q <= 4; ++q)
          if (q != i) c *= (u - q) / double(i - q);
        l += c;
      }
      sum += 0.5 * (b - a) * wg[g] * l;
    }
  }
  return sum;
}

// For a gap that starts a round-off below zero while opening: the first x where it falls
// below zero after rising to its highest (16 samples, the highest refined by golden
// section: a bounce shorter than a sample), bisected to round-off in time; −1 if it never
// reaches zero or does not fall back.
double reclosing(const std::function<double(double)>& f, double h, double t1) {
  constexpr int K = 16;
  int kmax = 0;
  double fmax = f(0.0);
  for (int k = 1; k <= K; ++k) {
    const double v = f(double(k) / K);
    if (v > fmax) {
      fmax = v;
      kmax = k;
    }
  }
  const Sample m = golden_min([&f](double x) { return -f(x); }, std::max(0.0, double(kmax - 1) / K),
                              std::min(1.0, double(kmax + 1) / K), 60);
  if (-m.f < 0.0) return -1.0;
  // the first sample after the highest point where the gap is below zero
  for (int k = int(std::floor(m.x * K)) + 1; k <= K; ++k)
    if (f(double(k) / K) < 0.0) return bisect_fall(f, std::max(m.x, double(k - 1) / K), double(k) / K, h, t1);
  return -1.0;
}

}  // namespace detail
}  // namespace camdyn
