// camdyn — extremes of a designer quantity over one turn of the cam (cam_extremum,
// include/camdyn/cam.hpp): a scan, golden-section refinement of every local extremum of
// the scan between its neighbours (the bracket cut at the breakpoints, where the quantity
// may jump or kink), and the one-sided values at the breakpoints; and cam_lift_base (cam/lift_base.hpp), the
// least X_C over a turn.
#include <algorithm>
#include <cmath>
#include <vector>

#include "cam/lift_base.hpp"

namespace camdyn {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kSide = 1e-12;  // [rad] one-sided offset at a breakpoint
}  // namespace

CamExtremum cam_extremum(const Cam& cam, const std::function<double(const CamPoint&)>& f, bool maximise,
                         int samples) {
  const int n = std::max(samples, 16);
  const double sg = maximise ? 1.0 : -1.0;
  // g = ±f: the largest g is wanted; NaN → −inf.
  auto g = [&](double th) {
    const double v = f(cam.evaluate(th));
    return std::isnan(v) ? -INFINITY : sg * v;
  };
  CamExtremum best;
  double gbest = -INFINITY;
  auto take = [&](double th, double v) {
    if (v > gbest) {
      gbest = v;
      best.theta = th;
    }
  };
  const double dth = kTwoPi / n;
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    v[std::size_t(i)] = g(dth * i);
    take(dth * i, v[std::size_t(i)]);
  }
  const std::vector<double>& br = cam.breakpoints();
  for (double b : br) {
    take(b - kSide, g(b - kSide));
    take(b + kSide, g(b + kSide));
  }
  // Golden-section maximum of g on [a, b] (no breakpoint inside).
  auto golden = [&](double a, double b) {
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - r * (b - a), d = a + r * (b - a), gc = g(c), gd = g(d);
    for (int it = 0; it < 200 && b - a > 4e-16 * (1.0 + std::fabs(a)); ++it) {
      if (gc >= gd) {
        b = d, d = c, gd = gc, c = b - r * (b - a), gc = g(c);
      } else {
        a = c, c = d, gc = gd, d = a + r * (b - a), gd = g(d);
      }
    }
    take(c, gc);
    take(d, gd);
  };
  for (int i = 0; i < n; ++i) {
    const double vi = v[std::size_t(i)], vl = v[std::size_t((i + n - 1) % n)], vr = v[std::size_t((i + 1) % n)];
    // A local maximum of the scan; not inside a plateau (a constant stretch, an arc's ρ: its
    // ends are refined from the neighbouring samples, and the breakpoints are taken anyway).
    if (!(vi >= vl && vi >= vr) || (vi == vl && vi == vr) || !std::isfinite(vi)) continue;
    // Bracket [θ_{i−1}, θ_{i+1}] cut at the breakpoints inside it.
    const double a = dth * (i - 1), b = dth * (i + 1);
    std::vector<double> cuts{a};
    for (double x : br)
      for (double t : {x - kTwoPi, x, x + kTwoPi})
        if (t > a && t < b) cuts.push_back(t);
    cuts.push_back(b);
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const double lo = cuts[k] + (k > 0 ? kSide : 0.0), hi = cuts[k + 1] - (k + 2 < cuts.size() ? kSide : 0.0);
      if (hi > lo) golden(lo, hi);
    }
  }
  if (std::isfinite(gbest)) {
    best.value = sg * gbest;
    best.theta = std::fmod(best.theta, kTwoPi);
    if (best.theta < 0) best.theta += kTwoPi;
  }
  return best;
}

double cam_lift_base(const Cam& cam, const CamSpec& spec) {
  if (spec.profile == CamProfileKind::Lift) return spec.base_radius;
  const double d = 2.0 * M_PI / 3600.0;
  double best = INFINITY, th_best = 0.0;
  for (int i = 0; i < 3600; ++i) {
    const double X = cam.evaluate(i * d).X_C;
    if (X < best) {
      best = X;
      th_best = i * d;
    }
  }
  double a = th_best - d, b = th_best + d;
  const double gr = 0.6180339887498949;
  double c = b - gr * (b - a), e = a + gr * (b - a);
  double fc = cam.evaluate(c).X_C, fe = cam.evaluate(e).X_C;
  for (int i = 0; i < 60; ++i) {
    if (fc < fe) {
      b = e; e = c; fe = fc; c = b - gr * (b - a); fc = cam.evaluate(c).X_C;
    } else {
      a = c; c = e; fc = fe; e = a + gr * (b - a); fe = cam.evaluate(e).X_C;
    }
  }
  return std::min({best, fc, fe});
}

}  // namespace camdyn
