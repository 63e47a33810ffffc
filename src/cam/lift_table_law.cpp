// camdyn — a motion law interpolating a lift table (MotionLaw::from_table,
// include/camdyn/motion_law.hpp; docs/cam_laws.md "Lift tables").
//
//   On the interval [t_i, t_{i+1}], h = t_{i+1} − t_i, x = (θ − t_i)/h, the quintic Hermite
//   polynomial p(x) = p0 + v0 x + a0 x²/2 + c3 x³ + c4 x⁴ + c5 x⁵ with p = L, v = h L′,
//   a = h² L″ at the ends (Δ = p1 − p0):
//     c3 = 10Δ − 6v0 − 4v1 − 3a0/2 + a1/2,  c4 = −15Δ + 8v0 + 7v1 + 3a0/2 − a1,
//     c5 = 6Δ − 3v0 − 3v1 − a0/2 + a1/2.
//   Without the derivatives, L′ and L″ at the knots are the periodic C² cubic spline's, and
//   the quintic through them is that cubic.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camdyn/motion_law.hpp"
#include "camdyn/cam_spec.hpp"
#include "camdyn/scene_error.hpp"
#include "cam/format.hpp"
#include "cam/spline.hpp"

namespace camdyn {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kDeg = kTwoPi / 360.0;

[[noreturn]] void fail_table(const std::string& key, const std::string& value, const std::string& rule) {
  throw SceneError("<cam>", 0, key, value, rule);
}
}  // namespace

MotionLaw MotionLaw::from_table(const std::vector<double>& angle_deg, const std::vector<double>& lift,
                                const std::vector<double>& dlift_ddeg, const std::vector<double>& d2lift_ddeg2,
                                const std::string& key) {
  const std::size_t n = angle_deg.size();
  if (n < 4) fail_table(key, std::to_string(n) + " rows", "a lift table needs at least 4 rows");
  if (lift.size() != n) fail_table(key, std::to_string(lift.size()) + " lifts", "must have one lift per angle");
  const bool given = !dlift_ddeg.empty() || !d2lift_ddeg2.empty();
  if (given && (dlift_ddeg.size() != n || d2lift_ddeg2.size() != n))
    fail_table(key, std::to_string(dlift_ddeg.size()) + "/" + std::to_string(d2lift_ddeg2.size()) + " derivatives",
               "give dlift_ddeg and d2lift_ddeg2 for every row, or neither");
  for (std::size_t i = 0; i < n; ++i) {
    const bool ok = std::isfinite(angle_deg[i]) && std::isfinite(lift[i]) &&
                    (!given || (std::isfinite(dlift_ddeg[i]) && std::isfinite(d2lift_ddeg2[i])));
    if (!ok) fail_table(key, "row " + std::to_string(i + 1), "every value must be finite");
    if (i > 0 && !(angle_deg[i] > angle_deg[i - 1]))
      fail_table(key, fmt_num(angle_deg[i]), "angles must be strictly increasing (row " + std::to_string(i + 1) + ")");
  }
  if (!(angle_deg.back() - angle_deg.front() < 360.0))
    fail_table(key, fmt_num(angle_deg.back()), "the table must span less than 360°");

  MotionLaw m;
  m.tab_t_.resize(n + 1);
  m.tab_L_.resize(n + 1);
  m.tab_L1_.resize(n + 1);
  m.tab_L2_.resize(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    m.tab_t_[i] = angle_deg[i] * kDeg;
    m.tab_L_[i] = lift[i];
  }
  if (given) {
    for (std::size_t i = 0; i < n; ++i) {
      m.tab_L1_[i] = dlift_ddeg[i] / kDeg;
      m.tab_L2_[i] = d2lift_ddeg2[i] / (kDeg * kDeg);
    }
  } else {
    const std::vector<double> t(m.tab_t_.begin(), m.tab_t_.begin() + long(n));
    const detail::PeriodicSpline sp(t, lift, kTwoPi);
    for (std::size_t i = 0; i < n; ++i) {
      double y, y1, y2, y3;
      sp.eval(t[i], &y, &y1, &y2, &y3);
      m.tab_L1_[i] = y1;
      m.tab_L2_[i] = y2;
    }
  }
  m.tab_t_[n] = m.tab_t_[0] + kTwoPi;
  m.tab_L_[n] = m.tab_L_[0];
  m.tab_L1_[n] = m.tab_L1_[0];
  m.tab_L2_[n] = m.tab_L2_[0];
  // Joints: where a dwell of the table (an interval with L constant and L′ = L″ = 0 at both
  // ends) meets motion; the jerk may jump there (order 2). Steps land on them, as on a law's.
  auto dwell = [&](std::size_t k) {  // interval k (mod n)
    k %= n;
    return m.tab_L_[k] == m.tab_L_[k + 1] && m.tab_L1_[k] == 0 && m.tab_L1_[k + 1] == 0 && m.tab_L2_[k] == 0 &&
           m.tab_L2_[k + 1] == 0;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (dwell(i + n - 1) == dwell(i)) continue;
    Breakpoint b;
    b.theta = m.tab_t_[i] - kTwoPi * std::floor(m.tab_t_[i] / kTwoPi);
    b.order = 2;
    const double h = 1e-9;
    b.jump[3] = m.eval_table(m.tab_t_[i] + h).L3 - m.eval_table(m.tab_t_[i] - h).L3;
    m.breaks_.push_back(b);
  }
  std::sort(m.breaks_.begin(), m.breaks_.end(),
            [](const Breakpoint& x, const Breakpoint& y) { return x.theta < y.theta; });
  // The lift range: the knots and 16 points inside each interval.
  m.lmin_ = m.lmax_ = m.tab_L_[0];
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 16; ++k) {
      const double L = m.eval_table(m.tab_t_[i] + (m.tab_t_[i + 1] - m.tab_t_[i]) * k / 16.0).L;
      m.lmin_ = std::min(m.lmin_, L);
      m.lmax_ = std::max(m.lmax_, L);
    }
  return m;
}

LiftDerivs MotionLaw::eval_table(double theta) const {
  const double t0 = tab_t_.front();
  double u = theta - t0 - kTwoPi * std::floor((theta - t0) * (1.0 / kTwoPi));
  if (u < 0) u += kTwoPi;
  if (!(u < kTwoPi)) u = 0.0;
  u += t0;
  const std::size_t last = tab_t_.size() - 2;
  std::size_t i = std::size_t(std::upper_bound(tab_t_.begin(), tab_t_.end(), u) - tab_t_.begin());
  i = i == 0 ? 0 : std::min(i - 1, last);
  const double h = tab_t_[i + 1] - tab_t_[i], ih = 1.0 / h;
  const double x = (u - tab_t_[i]) * ih;
  const double p0 = tab_L_[i], p1 = tab_L_[i + 1], D = p1 - p0;
  const double v0 = h * tab_L1_[i], v1 = h * tab_L1_[i + 1];
  const double a0 = h * h * tab_L2_[i], a1 = h * h * tab_L2_[i + 1];
  const double c2 = 0.5 * a0;
  const double c3 = 10 * D - 6 * v0 - 4 * v1 - 1.5 * a0 + 0.5 * a1;
  const double c4 = -15 * D + 8 * v0 + 7 * v1 + 1.5 * a0 - a1;
  const double c5 = 6 * D - 3 * v0 - 3 * v1 - 0.5 * a0 + 0.5 * a1;
  LiftDerivs d;
  d.L = p0 + x * (v0 + x * (c2 + x * (c3 + x * (c4 + x * c5))));
  d.L1 = (v0 + x * (2 * c2 + x * (3 * c3 + x * (4 * c4 + x * 5 * c5)))) * ih;
  d.L2 = (2 * c2 + x * (6 * c3 + x * (12 * c4 + x * 20 * c5))) * ih * ih;
  d.L3 = (6 * c3 + x * (24 * c4 + x * 60 * c5)) * ih * ih * ih;
  return d;
}

}  // namespace camdyn
