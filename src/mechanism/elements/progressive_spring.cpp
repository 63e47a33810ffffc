// camdyn — the progressive spring (progressive_spring.hpp has the maths).
#include "mechanism/elements/progressive_spring.hpp"

#include <cmath>
#include <sstream>

#include "camdyn/network.hpp"
#include "scene/key_table.hpp"  // format_number

namespace camdyn {

namespace {
int sign(double v) { return (v > 0) - (v < 0); }
}  // namespace

MonotoneCurve::MonotoneCurve(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
  const std::size_t n = x_.size();
  std::vector<double> h(n - 1), d(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = x_[k + 1] - x_[k];
    d[k] = (y_[k + 1] - y_[k]) / h[k];
  }
  m_.assign(n, 0.0);
  if (n == 2) {
    m_[0] = m_[1] = d[0];
  } else {
    // interior: the weighted harmonic mean of the neighbouring secants (0 at an extremum)
    for (std::size_t k = 1; k + 1 < n; ++k) {
      if (d[k - 1] * d[k] <= 0.0) continue;
      const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
      m_[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
    }
    // ends: the one-sided three-point slope, limited to keep the shape
    auto end = [](double h0, double h1, double d0, double d1) {
      double m = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
      if (sign(m) != sign(d0)) m = 0.0;
      else if (sign(d0) != sign(d1) && std::abs(m) > 3 * std::abs(d0)) m = 3 * d0;
      return m;
    };
    m_[0] = end(h[0], h[1], d[0], d[1]);
    m_[n - 1] = end(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);
  }
  poly_.assign(4 * (n - 1), 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    double* c = &poly_[4 * k];
    c[0] = y_[k];
    c[1] = m_[k];
    c[2] = (3 * d[k] - 2 * m_[k] - m_[k + 1]) / h[k];
    c[3] = (m_[k] + m_[k + 1] - 2 * d[k]) / (h[k] * h[k]);
  }
  const double spacing = (x_[n - 1] - x_[0]) / double(n - 1);
  uniform_ = true;
  for (std::size_t k = 0; k + 1 < n; ++k) uniform_ = uniform_ && std::abs(h[k] - spacing) <= 1e-9 * spacing;
  inv_spacing_ = 1.0 / spacing;
  // ∫ of the Hermite cubic over a whole segment: h(y0 + y1)/2 + h²(m0 − m1)/12
  area_.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k)
    area_[k + 1] = area_[k] + h[k] * (y_[k] + y_[k + 1]) / 2 + h[k] * h[k] * (m_[k] - m_[k + 1]) / 12;
}

std::size_t MonotoneCurve::segment(double x) const {
  std::size_t lo = 0, hi = x_.size() - 1;  // x_lo ≤ x < x_hi
  if (!(x > x_[1])) return 0;  // also a NaN
  if (x >= x_[hi - 1]) return hi - 1;
  if (uniform_) {  // x_1 < x < x_{n−2}: the guess is off by round-off at most
    std::size_t k = std::size_t((x - x_[0]) * inv_spacing_);
    while (x < x_[k]) --k;
    while (x >= x_[k + 1]) ++k;
    return k;
  }
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (x < x_[mid] ? hi : lo) = mid;
  }
  return lo;
}

double MonotoneCurve::value(double x) const {
  const std::size_t n = x_.size();
  if (x <= x_[0]) return y_[0] + m_[0] * (x - x_[0]);
  if (x >= x_[n - 1]) return y_[n - 1] + m_[n - 1] * (x - x_[n - 1]);
  const std::size_t k = segment(x);
  const double* c = &poly_[4 * k];
  const double u = x - x_[k];
  return c[0] + u * (c[1] + u * (c[2] + u * c[3]));
}

double MonotoneCurve::slope(double x) const {
  const std::size_t n = x_.size();
  if (x <= x_[0]) return m_[0];
  if (x >= x_[n - 1]) return m_[n - 1];
  const std::size_t k = segment(x);
  const double* c = &poly_[4 * k];
  const double u = x - x_[k];
  return c[1] + u * (2 * c[2] + 3 * u * c[3]);
}

double MonotoneCurve::integral(double x) const {
  const std::size_t n = x_.size();
  if (x <= x_[0]) {
    const double u = x - x_[0];
    return y_[0] * u + 0.5 * m_[0] * u * u;
  }
  if (x >= x_[n - 1]) {
    const double u = x - x_[n - 1];
    return area_[n - 1] + y_[n - 1] * u + 0.5 * m_[n - 1] * u * u;
  }
  const std::size_t k = segment(x);
  const double h = x_[k + 1] - x_[k], t = (x - x_[k]) / h, t2 = t * t, t3 = t2 * t, t4 = t3 * t;
  // antiderivatives of the Hermite basis over [0, t]
  const double H00 = t4 / 2 - t3 + t, H10 = t4 / 4 - 2 * t3 / 3 + t2 / 2, H01 = -t4 / 2 + t3, H11 = t4 / 4 - t3 / 3;
  return area_[k] + h * (H00 * y_[k] + H10 * h * m_[k] + H01 * y_[k + 1] + H11 * h * m_[k + 1]);
}

double MonotoneCurve::inverse(double y) const {
  double lo = x_.front(), hi = x_.back();
  const double span = hi - lo;
  while (value(lo) > y) lo -= span;
  while (value(hi) < y) hi += span;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * (std::abs(lo) + std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (value(mid) < y ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ProgressiveSpring::ProgressiveSpring(const ElementSpec& spec, std::string name)
    : Element(std::move(name), 2), curve_(spec.deflections, spec.forces), d0_(spec.installed_deflection),
      c_(spec.damping), nodes_(spec.nodes) {}

std::string ProgressiveSpring::describe() const {
  std::ostringstream d;
  d << "progressive_spring '" << name() << "' [" << nodes_.at(0) << " → " << nodes_.at(1) << "] table of "
    << "points, installed deflection " << detail::format_number(d0_) << ", preload "
    << detail::format_number(preload()) << ", rate at install " << detail::format_number(curve_.slope(d0_));
  if (c_ != 0.0) d << ", c " << detail::format_number(c_);
  return d.str();
}

void ProgressiveSpring::force(const ElementState& e, double* f) const {
  const double F = curve_.value(deflection(e)) + c_ * (e.xd[0] - e.xd[1]);
  f[0] = -F;
  f[1] = F;
}

void ProgressiveSpring::force_jacobian(const ElementState& e, double* dfdx, double* dfdxd) const {
  const double k = curve_.slope(deflection(e));
  // f = [−F, F], ∂δ/∂x = [1, −1]: column-major [∂f₀/∂x₀, ∂f₁/∂x₀, ∂f₀/∂x₁, ∂f₁/∂x₁]
  dfdx[0] = -k, dfdx[1] = k, dfdx[2] = k, dfdx[3] = -k;
  if (dfdxd) dfdxd[0] = -c_, dfdxd[1] = c_, dfdxd[2] = c_, dfdxd[3] = -c_;
}

double ProgressiveSpring::stored_energy(const ElementState& e) const {
  return curve_.integral(deflection(e)) - curve_.integral(d0_);
}

double ProgressiveSpring::dissipated_power(const ElementState& e) const {
  const double r = e.xd[0] - e.xd[1];
  return c_ * r * r;
}

void ProgressiveSpring::forces(const ElementState& e, double* out) const {
  out[0] = curve_.value(deflection(e)) + c_ * (e.xd[0] - e.xd[1]);
}

}  // namespace camdyn
