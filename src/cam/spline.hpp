// camdyn (private) — periodic cubic spline (C², period P) through n ≥ 3 knots.
//
//   Knots t_0 < t_1 < … < t_{n−1} < t_0 + P with values y_i; the spline closes on itself
//   (y(t + P) = y(t), and y, y′, y″ are continuous across t_0 + P). The knot second
//   derivatives M_i solve the cyclic tridiagonal system
//     h_{i−1} M_{i−1} + 2(h_{i−1} + h_i) M_i + h_i M_{i+1}
//         = 6 [(y_{i+1} − y_i)/h_i − (y_i − y_{i−1})/h_{i−1}],   indices mod n,
//   solved by the Thomas algorithm with a Sherman–Morrison correction (O(n)).
//   Each segment is stored as a cubic a + b s + c s² + d s³ in s = t − t_i.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace camdyn::detail {

class PeriodicSpline {
 public:
  PeriodicSpline() = default;

  /// t strictly increasing with t.back() − t.front() < period; y same size, ≥ 3 entries.
  PeriodicSpline(const std::vector<double>& t, const std::vector<double>& y, double period) {
    const std::size_t n = t.size();
    period_ = period;
    t0_ = t[0];
    knots_.resize(n + 1);
    for (std::size_t i = 0; i < n; ++i) knots_[i] = t[i] - t0_;
    knots_[n] = period;
    std::vector<double> h(n), rhs(n);
    for (std::size_t i = 0; i < n; ++i) h[i] = knots_[i + 1] - knots_[i];
    auto Y = [&](std::size_t i) { return y[i % n]; };
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t im = (i + n - 1) % n;
      rhs[i] = 6.0 * ((Y(i + 1) - Y(i)) / h[i] - (Y(i) - Y(im)) / h[im]);
    }
    // Cyclic tridiagonal: sub a_i = h_{i−1}, diag b_i = 2(h_{i−1}+h_i), super c_i = h_i;
    // corners A(0, n−1) = h_{n−1}, A(n−1, 0) = h_{n−1}.
    std::vector<double> a(n), b(n), c(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t im = (i + n - 1) % n;
      a[i] = h[im];
      b[i] = 2.0 * (h[im] + h[i]);
      c[i] = h[i];
    }
    const double alpha = c[n - 1];  // A(n−1, 0)
    const double beta = a[0];       // A(0, n−1)
    const double gamma = -b[0];
    std::vector<double> bb = b;
    bb[0] -= gamma;
    bb[n - 1] -= alpha * beta / gamma;
    std::vector<double> x = thomas(a, bb, c, rhs);
    std::vector<double> u(n, 0.0);
    u[0] = gamma;
    u[n - 1] = alpha;
    std::vector<double> z = thomas(a, bb, c, u);
    const double fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
    std::vector<double> M(n);
    for (std::size_t i = 0; i < n; ++i) M[i] = x[i] - fact * z[i];

    coef_.resize(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const double hi = h[i], y0 = Y(i), y1 = Y(i + 1), m0 = M[i], m1 = M[(i + 1) % n];
      coef_[4 * i + 0] = y0;
      coef_[4 * i + 1] = (y1 - y0) / hi - hi * (2.0 * m0 + m1) / 6.0;
      coef_[4 * i + 2] = 0.5 * m0;
      coef_[4 * i + 3] = (m1 - m0) / (6.0 * hi);
    }
  }

  std::size_t size() const { return knots_.size() - 1; }
  double period() const { return period_; }

  /// Segment index and local coordinate s of parameter t (any real t).
  void locate(double t, std::size_t* seg, double* s) const {
    double u = std::fmod(t - t0_, period_);
    if (u < 0) u += period_;
    if (!(u < period_)) u = 0.0;
    const std::size_t n = size();
    std::size_t i;
    if (n <= 16) {
      i = 0;
      while (i + 1 < n && knots_[i + 1] <= u) ++i;
    } else {
      i = static_cast<std::size_t>(std::upper_bound(knots_.begin(), knots_.end(), u) -
                                   knots_.begin());
      i = (i == 0) ? 0 : std::min(i - 1, n - 1);
    }
    *seg = i;
    *s = u - knots_[i];
  }

  /// Value and first three derivatives on segment seg at local coordinate s.
  void eval_local(std::size_t seg, double s, double* d0, double* d1, double* d2,
                  double* d3 = nullptr) const {
    const double* k = &coef_[4 * seg];
    *d0 = k[0] + s * (k[1] + s * (k[2] + s * k[3]));
    *d1 = k[1] + s * (2.0 * k[2] + 3.0 * s * k[3]);
    *d2 = 2.0 * k[2] + 6.0 * s * k[3];
    if (d3) *d3 = 6.0 * k[3];
  }

  void eval(double t, double* d0, double* d1, double* d2, double* d3 = nullptr) const {
    std::size_t seg;
    double s;
    locate(t, &seg, &s);
    eval_local(seg, s, d0, d1, d2, d3);
  }

  double value(double t) const {
    double d0, d1, d2;
    eval(t, &d0, &d1, &d2);
    return d0;
  }

 private:
  static std::vector<double> thomas(const std::vector<double>& a, const std::vector<double>& b,
                                    const std::vector<double>& c, const std::vector<double>& d) {
    const std::size_t n = d.size();
    std::vector<double> cp(n), dp(n), x(n);
    cp[0] = c[0] / b[0];
    dp[0] = d[0] / b[0];
    for (std::size_t i = 1; i < n; ++i) {
      const double m = b[i] - a[i] * cp[i - 1];
      cp[i] = c[i] / m;
      dp[i] = (d[i] - a[i] * dp[i - 1]) / m;
    }
    x[n - 1] = dp[n - 1];
    for (std::size_t i = n - 1; i-- > 0;) x[i] = dp[i] - cp[i] * x[i + 1];
    return x;
  }

  double period_ = 0, t0_ = 0;
  std::vector<double> knots_;  // relative to t0_, n + 1 entries, last = period
  std::vector<double> coef_;   // 4 per segment
};

}  // namespace camdyn::detail
