// camdyn — stop times at the cam's breakpoints (issue 24): CamDrive::next_time_at_angles.
//
// θ(t) is linear (constant speed) or piecewise quadratic (speed table). On each piece where
// θ is monotone, the next angle ≡ b (mod 2π) beyond θ(t) in the direction of motion is
// found in closed form and its time by the quadratic's stable root (bisection as a
// fallback). A target must lie at least 1e-9 rad beyond θ(t): a step that has just landed
// on a breakpoint is not stopped again by the round-off of that landing. The time returned
#include <algorithm>
#include <cmath>

#include "camdyn/cam.hpp"

namespace camdyn {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kMargin = 1e-9;  // [rad]

/// The next angle T ≡ some a ∈ angles (mod 2π) with T > th (dir > 0) or T < th (dir < 0).
double next_angle(double th, int dir, const std::vector<double>& angles) {
  const double base = std::floor(th / kTwoPi) * kTwoPi;
  double best = dir > 0 ? INFINITY : -INFINITY;
  for (int k = -1; k <= 1; ++k)
    for (double a : angles) {
      const double T = base + k * kTwoPi + a;
      if (dir > 0 && T > th + kMargin) best = std::min(best, T);
      if (dir < 0 && T < th - kMargin) best = std::max(best, T);
    }
  return best;
}
}  // namespace

double CamDrive::next_time_at_angles(double t, const std::vector<double>& angles, double horizon) const {
  if (angles.empty() || !(horizon > t)) return INFINITY;
  // Pieces [a, b] with θ(τ) = th_a + w (τ − a) + ½ acc (τ − a)².
  auto solve_piece = [&](double a, double b, double th_a, double w, double acc) -> double {
    auto theta_at = [&](double tau) { const double u = tau - a; return th_a + w * u + 0.5 * acc * u * u; };
    // Split at ω = 0 inside the piece.
    double cuts[3] = {a, b, b};
    int nc = 2;
    if (acc != 0.0) {
      const double tz = a - w / acc;
      if (tz > a && tz < b) {
        cuts[1] = tz;
        cuts[2] = b;
        nc = 3;
      }
    }
    for (int i = 0; i + 1 < nc; ++i) {
      const double p0 = std::max(cuts[i], t), p1 = cuts[i + 1];
      if (!(p1 > p0)) continue;
      const double th0 = theta_at(p0), th1 = theta_at(p1);
      if (th1 == th0) continue;
      const int dir = th1 > th0 ? 1 : -1;
      const double T = next_angle(th0, dir, angles);
      if (dir > 0 ? T > th1 : T < th1) continue;
      // Time of θ = T on [p0, p1]: the quadratic's root, polished by bisection.
      double lo = p0, hi = p1;
      double guess;
      if (acc == 0.0) {
        guess = a + (T - th_a) / w;
      } else {
        const double c = th_a - T, disc = std::max(0.0, w * w - 2.0 * acc * c);
        const double q = -0.5 * (w + std::copysign(std::sqrt(disc), w));
        const double r1 = q / (0.5 * acc), r2 = q != 0.0 ? c / q : r1;
        guess = a + ((a + r1 >= p0 && a + r1 <= p1) ? r1 : r2);
      }
      if (guess >= lo && guess <= hi && std::fabs(theta_at(guess) - T) <= 1e-12 * (1.0 + std::fabs(T)))
        return guess;
      for (int it = 0; it < 200 && hi - lo > 4e-16 * std::max(1.0, std::fabs(hi)); ++it) {
        const double mid = 0.5 * (lo + hi);
        ((theta_at(mid) - T) * dir < 0 ? lo : hi) = mid;
      }
      return hi;
    }
    return INFINITY;
  };
  if (table_t_.empty()) return solve_piece(t, horizon, theta(t), omega0_, 0.0);
  if (t < 0.0) {
    const double r = solve_piece(t, std::min(horizon, 0.0), theta(t), omega0_, 0.0);
    if (r < INFINITY) return r;
  }
  const std::size_t n = table_t_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double a = table_t_[k], b = k + 1 < n ? table_t_[k + 1] : horizon;
    if (b <= t || a >= horizon) continue;
    const double acc = k + 1 < n ? (table_w_[k + 1] - table_w_[k]) / (table_t_[k + 1] - table_t_[k]) : 0.0;
    const double r = solve_piece(a, std::min(b, horizon), theta0_ + table_theta_[k], table_w_[k], acc);
    if (r < INFINITY) return r;
  }
  return INFINITY;
}

}  // namespace camdyn
