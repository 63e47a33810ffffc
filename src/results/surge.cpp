// camdyn — the surge amplitude of springs with coil masses (surge.hpp).
#include "results/surge.hpp"

#include <cmath>

#include "results/designer_stats.hpp"  // angle_deg_mod360

namespace camdyn {
namespace detail {

SurgeTracker::SurgeTracker(const std::vector<std::string>& springs, double theta0) : theta0_(theta0) {
  for (const std::string& n : springs) {
    out_.emplace_back();
    out_.back().spring = n;
  }
}

void SurgeTracker::sample(double theta, const double* amp) {
  const double turn = std::abs(theta - theta0_) / (2.0 * M_PI);
  const std::size_t rev = std::size_t(std::floor(turn * (1 + 1e-12)));
  for (std::size_t i = 0; i < out_.size(); ++i) {
    SurgeResult& r = out_[i];
    const double a = amp[i], th = angle_deg_mod360(theta);
    if (std::isnan(r.theta_deg) || a > r.amplitude) {
      r.amplitude = a;
      r.theta_deg = th;
    }
    while (r.per_revolution.size() <= rev) {
      r.per_revolution.push_back(NAN);
      r.per_revolution_theta_deg.push_back(NAN);
    }
    if (std::isnan(r.per_revolution[rev]) || a > r.per_revolution[rev]) {
      r.per_revolution[rev] = a;
      r.per_revolution_theta_deg[rev] = th;
    }
  }
}

}  // namespace detail
}  // namespace camdyn
