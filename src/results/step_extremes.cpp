// camdyn — extremes located inside an accepted step (step_extremes.hpp).
#include "results/step_extremes.hpp"

#include <algorithm>
#include <cmath>

namespace camdyn {
namespace detail {

LocatedExtreme golden_max(const std::function<double(double)>& f, double a, double fa, double b, double fb,
                          int iters) {
  constexpr double r = 0.6180339887498949;
  LocatedExtreme best;
  auto keep = [&](double x, double v) {
    if (!std::isnan(v) && (!best.found || v > best.value)) best = {x, v, true};
  };
  keep(a, fa);
  keep(b, fb);
  double c = b - r * (b - a), d = a + r * (b - a);
  double fc = f(c), fd = f(d);
  keep(c, fc);
  keep(d, fd);
  for (int i = 0; i < iters; ++i) {
    if (fc >= fd || std::isnan(fd)) {
      b = d;
      d = c;
      fd = fc;
      c = b - r * (b - a);
      fc = f(c);
      keep(c, fc);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + r * (b - a);
      fd = f(d);
      keep(d, fd);
    }
  }
  return best;
}

LocatedExtreme locate_extreme(const double* x, const double* q, int n, int sign, double record,
                              const std::function<double(double)>& f) {
  const double s = sign < 0 ? -1.0 : 1.0;
  int k = -1;
  for (int i = 0; i < n; ++i)
    if (!std::isnan(q[i]) && (k < 0 || s * q[i] > s * q[k])) k = i;
  LocatedExtreme out;
  if (k < 0) return out;
  out = {x[k], q[k], true};
  // the parabola through the best sample and its neighbours (the two before an end)
  const int c = k == 0 ? 1 : k == n - 1 ? n - 2 : k;
  if (n < 3 || std::isnan(q[c - 1]) || std::isnan(q[c]) || std::isnan(q[c + 1])) return out;
  const double x0 = x[c - 1], x1 = x[c], x2 = x[c + 1];
  const double y0 = s * q[c - 1], y1 = s * q[c], y2 = s * q[c + 1];
  const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1);
  const double a2 = (d12 - d01) / (x2 - x0);  // curvature/2
  if (!(a2 < 0)) return out;                  // no interior maximum of s·q on this parabola
  const double xv = 0.5 * (x0 + x1) - d01 / (2 * a2);
  // the bracket: the best sample's neighbours (at an end, the interval next to it)
  double lo = x[k > 0 ? k - 1 : 0], hi = x[k < n - 1 ? k + 1 : n - 1];
  if (!(xv > lo && xv < hi)) return out;
  const double yv = y1 + d01 * (xv - x1) + a2 * (xv - x0) * (xv - x1);  // parabola at xv
  // the vertex no better than the best sample by more than the search's resolution: the
  // search could add no more than that
  const double scale = std::max({std::fabs(y0), std::fabs(y1), std::fabs(y2)});
  if (!(yv - s * q[k] > kSearchGain * scale)) return out;
  if (!std::isnan(record) && !(std::max(yv, s * q[k]) > s * record)) return out;
  const double flo = s * q[k > 0 ? k - 1 : 0], fhi = s * q[k < n - 1 ? k + 1 : n - 1];
  const LocatedExtreme g = golden_max([&](double xx) { return s * f(xx); }, lo, flo, hi, fhi);
  if (g.found && g.value > s * out.value) out = {g.x, s * g.value, true};
  return out;
}

double falling_root(const std::function<double(double)>& f, double a, double fa, double b, double fb) {
  int side = 0;
  for (int i = 0; i < 200 && b - a > 1e-12; ++i) {
    double c = (fa - fb) != 0 ? (a * (-fb) + b * fa) / (fa - fb) : 0.5 * (a + b);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double fc = f(c);
    if (fc == 0 || std::isnan(fc)) return c;
    if (fc > 0) {
      a = c, fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    } else {
      b = c, fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    }
  }
  return fa < -fb ? a : b;  // the end nearer the root by |f|
}

}  // namespace detail
}  // namespace camdyn
