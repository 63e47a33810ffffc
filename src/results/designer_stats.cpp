// camdyn — designer results of one run (see designer_stats.hpp).
#include "results/designer_stats.hpp"

#include <algorithm>
#include <cmath>

namespace camdyn {
namespace detail {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
constexpr double kPi = 3.14159265358979323846264338327950;
}  // namespace

double angle_deg_mod360(double theta) {
  double d = std::fmod(theta * (180.0 / kPi), 360.0);
  if (d < 0) d += 360.0;
  if (d >= 360.0) d = 0.0;  // −tiny + 360 rounds to 360
  return d;
}

DesignerStats::DesignerStats(const Scene& scene, double lift) : drive_(scene.cam), lift_(lift) {
  if (!(lift_ > 0)) lift_ = 1.0;
  theta0_ = drive_.theta(0.0);
  const double th_end = drive_.theta(scene.run.t_end);
  dir_ = th_end < theta0_ ? -1.0 : 1.0;
  const double ths = scene.run.poincare_angle_deg * (kPi / 180.0);
  phi_s_ = std::fmod(dir_ * (ths - theta0_), kTwoPi);
  if (phi_s_ < 0) phi_s_ += kTwoPi;
  if (phi_s_ >= kTwoPi) phi_s_ = 0.0;
  settle_ = scene.run.settle_revolutions;
  tol_ = scene.run.period_tol;
}

DesignerStats::DesignerStats(const Scene& scene, const Cam& cam)
    : DesignerStats(scene, std::make_shared<const Cam>(cam)) {}

DesignerStats::DesignerStats(const Scene& scene, std::shared_ptr<const Cam> cam) : DesignerStats(scene, cam->lift()) {
  geometry_init(scene, std::move(cam));
}

void DesignerStats::sample_force(double t, double theta, double F, const CamPoint* cp) {
  if (cam_) geometry_sample(t, theta, F, cp);
  if (!(F >= 0.0)) F = 0.0;  // NaN or a bilateral pull: the margin is gone
  if (std::isnan(min_F_) || F < min_F_) {
    min_F_ = F;
    min_F_theta_ = angle_deg_mod360(theta);
  }
}

void DesignerStats::event(const ContactEvent& e) {
  if (e.type == EventKind::Separation) {
    if (std::isnan(first_sep_)) first_sep_ = angle_deg_mod360(e.theta);
    sample_force(e.t, e.theta, 0.0);  // the force reaches zero at a separation
  } else if (e.type == EventKind::Impact) {
    if (std::isnan(first_imp_)) first_imp_ = angle_deg_mod360(e.theta);
    if (std::isnan(max_vimp_theta_) || e.impact_velocity > max_vimp_) {
      max_vimp_ = e.impact_velocity;
      max_vimp_theta_ = angle_deg_mod360(e.theta);
    }
  }
}

void DesignerStats::step(double t, double theta, double u, double v, double a, double gap) {
  if (cam_) geometry_step(t);
  max_gap_ = std::max(max_gap_, gap);
  if (!drive_.constant_speed() || !have_prev_) max_omega_ = std::max(max_omega_, std::abs(drive_.omega(t)));
  // Section crossings in revolution units: x = (φ − φ_s)/2π, φ = dir (θ − θ₀); revolution
  // k is sampled the first time x ≥ k (one expression for x throughout, so no crossing is
  // missed or taken twice by round-off).
  const double pb = dir_ * (theta - theta0_);
  const double xb = (pb - phi_s_) / kTwoPi;
  if (!have_prev_) {
    next_k_ = settle_;
    // The start: a section exactly at θ₀ is revolution 0, sampled here.
    if (settle_ == 0 && xb >= 0.0) {
      poincare_.push_back({0, t, u, v});
      next_k_ = 1;
    }
  } else if (xb >= double(next_k_) && t > t0_) {
    const double pa = dir_ * (th0_ - theta0_);
    const long k_hi = static_cast<long>(std::floor(xb));
    for (long k = next_k_; k <= k_hi; ++k) {
      const double target = phi_s_ + kTwoPi * double(k);
      // Crossing time: linear in θ at constant speed, else bisection on the drive's θ(t)
      // (monotone within the step).
      double tc = pb > pa ? t0_ + (target - pa) / (pb - pa) * (t - t0_) : t;
      if (!drive_.constant_speed()) {
        double lo = t0_, hi = t;
        for (int i = 0; i < 200 && hi - lo > 4e-16 * std::max(1.0, std::abs(hi)); ++i) {
          const double mid = 0.5 * (lo + hi);
          (dir_ * (drive_.theta(mid) - theta0_) < target ? lo : hi) = mid;
        }
        tc = 0.5 * (lo + hi);
      }
      tc = std::min(t, std::max(t0_, tc));
      const double h = t - t0_, x = (tc - t0_) / h, x2 = x * x, x3 = x2 * x;
      const double h00 = 2 * x3 - 3 * x2 + 1, h10 = (x3 - 2 * x2 + x) * h;
      const double h01 = -2 * x3 + 3 * x2, h11 = (x3 - x2) * h;
      PoincareSample s;
      s.revolution = k;
      s.t = tc;
      s.u_c = h00 * u0_ + h10 * v0_ + h01 * u + h11 * v;
      s.v_c = h00 * v0_ + h10 * a0_ + h01 * v + h11 * a;
      poincare_.push_back(s);
    }
    next_k_ = std::max(next_k_, k_hi + 1);
  }
  have_prev_ = true;
  t0_ = t;
  th0_ = theta;
  u0_ = u;
  v0_ = v;
  a0_ = a;
}

int DesignerStats::detect_period(const std::vector<PoincareSample>& x, double scale_u,
                                 double scale_v, double tol, std::string* kind) {
  const int n = static_cast<int>(x.size());
  if (n < 3) {
    if (kind) *kind = "too few samples";
    return 0;
  }
  const int pmax = std::min(16, (n - 1) / 2);
  for (int p = 1; p <= pmax; ++p) {
    bool ok = true;
    for (int i = p; i < n && ok; ++i) {
      ok = std::abs(x[i].u_c - x[i - p].u_c) <= tol * scale_u &&
           std::abs(x[i].v_c - x[i - p].v_c) <= tol * scale_v;
    }
    if (ok) {
      if (kind) *kind = "period-" + std::to_string(p);
      return p;
    }
  }
  if (kind) *kind = "not periodic";
  return 0;
}

void DesignerStats::finish(Summary& s) const {
  s.min_contact_force = min_F_;
  s.min_force_theta_deg = min_F_theta_;
  s.first_separation_theta_deg = first_sep_;
  s.first_impact_theta_deg = first_imp_;
  s.max_impact_velocity = max_vimp_;
  s.max_impact_theta_deg = max_vimp_theta_;
  s.max_gap = max_gap_;
  s.poincare = poincare_;
  const double sv = lift_ * (max_omega_ > 0 ? max_omega_ : 1.0);
  s.period = detect_period(poincare_, lift_, sv, tol_, &s.period_kind);
  if (cam_) geometry_finish(s);
}

}  // namespace detail
}  // namespace camdyn
