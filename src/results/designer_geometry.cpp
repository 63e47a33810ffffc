// camdyn — the cam-geometry designer results of one run (issue 24; designer_stats.hpp):
// pressure angle and radius of curvature over the cam, side load, Hertz line-contact
// stress, cam torque T = F·dX_C/dθ (power balance: T ω = F Ẋ_C) and power.
#include <algorithm>
#include <cmath>
#include <functional>

#include "results/designer_stats.hpp"
#include "results/step_extremes.hpp"

namespace camdyn {
namespace detail {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
}

void DesignerStats::geometry_init(const Scene& scene, std::shared_ptr<const Cam> cam_ptr) {
  cam_ = std::move(cam_ptr);
  const Cam& cam = *cam_;
  cols_ = std::make_shared<const DesignerColumns>(scene);
  // Extremes over the cam located between the samples and at the joints (cam_extremum).
  const CamExtremum phi = cam_extremum(cam, [](const CamPoint& p) { return std::fabs(p.pressure_angle); }, true);
  geo_max_phi_ = std::isnan(phi.value) ? 0.0 : phi.value * 360.0 / kTwoPi;
  geo_min_rho_ = cam.min_radius_of_curvature();
}

DesignerStats::Design DesignerStats::design_at(double theta, double F, double omega) const {
  return design_at(cam_->evaluate(theta), F, omega);
}

DesignerStats::Design DesignerStats::design_at(const CamPoint& cp, double F, double omega) const {
  if (!(F > 0.0)) F = 0.0;
  const ContactDesign d = cols_->eval(cp, F, omega);
  Design r;
  r.hertz = d.stress;
  r.side = std::fabs(d.side);
  r.torque = d.torque;
  r.power = d.power;
  if (cols_->friction()) {
    const CamFriction f = cols_->friction_at(cp, F, omega);
    r.friction = f.force;
    r.friction_power = f.power;
  }
  return r;
}

void DesignerStats::keep_extremes(double theta, const Design& d) {
  if (!std::isnan(d.friction) && (std::isnan(Ff_max_) || d.friction > Ff_max_)) Ff_max_ = d.friction;
  if (!std::isnan(d.friction_power) && (std::isnan(Pf_peak_) || d.friction_power > Pf_peak_))
    Pf_peak_ = d.friction_power;
  if (!std::isnan(d.side) && (std::isnan(max_side_) || d.side > max_side_)) max_side_ = d.side;
  if (!std::isnan(d.torque) && (std::isnan(T_peak_) || std::fabs(d.torque) > std::fabs(T_peak_))) T_peak_ = d.torque;
  if (!std::isnan(d.power) && (std::isnan(P_peak_) || std::fabs(d.power) > std::fabs(P_peak_))) P_peak_ = d.power;
  if (!std::isnan(d.hertz) && (std::isnan(max_hertz_) || d.hertz > max_hertz_)) {
    max_hertz_ = d.hertz;
    max_hertz_theta_ = angle_deg_mod360(theta);
  }
}

void DesignerStats::geometry_sample(double t, double theta, double F, const CamPoint* cp) {
  const double omega = drive_.omega(t);
  const CamPoint at = cp ? *cp : cam_->evaluate(theta);
  const Design d = design_at(at, F, omega);
  keep_extremes(theta, d);
  if (t == pend_t1_) {  // the current step end: its value for the time averages
    pend_T1_ = d.torque;
    pend_P1_ = d.power;
    if (cols_->friction()) {
      const CamFriction f = cols_->friction_at(at, F > 0 ? F : 0.0, omega);
      pend_Tf1_ = f.torque;
      pend_Pf1_ = f.power;
    }
  }
}

void DesignerStats::step_inside(const std::vector<StepSample>& s, const StepProbe& probe) {
  const int n = int(s.size());
  if (n < 2 || !s[0].held) return;
  const double t0 = s.front().t, h = s.back().t - t0;
  double x[kStepSamples], q[kStepSamples];
  StepSample tmp;
  // the least held force (the force margin), located inside the step
  for (int k = 0; k < n; ++k) x[k] = s[k].x, q[k] = std::max(s[k].F, 0.0);
  auto force_at = [&](double xx) {
    probe(xx, tmp);
    return std::max(tmp.F, 0.0);
  };
  const LocatedExtreme lf = locate_extreme(x, q, n, -1, min_F_, std::cref(force_at));
  if (lf.found && (std::isnan(min_F_) || lf.value < min_F_)) {
    min_F_ = lf.value;
    min_F_theta_ = angle_deg_mod360(drive_.theta(t0 + lf.x * h));
  }
  if (!cam_) return;
  Design d[kStepSamples];
  for (int k = 0; k < n; ++k) d[k] = design_at(s[k].cam_point(*cam_), s[k].F, s[k].omega);
  // each quantity: its samples, its record, and where it is located
  auto locate = [&](double Design::*m, int sign, double record, bool absolute) {
    for (int k = 0; k < n; ++k) q[k] = absolute ? std::fabs(d[k].*m) : d[k].*m;
    auto value_at = [&](double xx) {
      probe(xx, tmp);
      const double v = design_at(tmp.cam_point(*cam_), tmp.F, tmp.omega).*m;
      return absolute ? std::fabs(v) : v;
    };
    const LocatedExtreme e = locate_extreme(x, q, n, sign, absolute ? std::fabs(record) : record, std::cref(value_at));
    if (!e.found) return;
    for (int k = 0; k < n; ++k)
      if (e.x == x[k]) return;  // a sample: kept already
    probe(e.x, tmp);  // the located point: every quantity there is a sample too
    keep_extremes(tmp.theta, design_at(tmp.cam_point(*cam_), tmp.F, tmp.omega));
  };
  for (int k = 0; k < n; ++k) keep_extremes(s[k].theta, d[k]);
  locate(&Design::hertz, 1, max_hertz_, false);
  locate(&Design::side, 1, max_side_, false);
  locate(&Design::torque, 1, T_peak_, true);
  locate(&Design::power, 1, P_peak_, true);
  if (cols_->friction()) {
    locate(&Design::friction, 1, Ff_max_, false);
    locate(&Design::friction_power, 1, Pf_peak_, false);
  }
}

void DesignerStats::geometry_step(double t) {
  if (std::isnan(t_first_)) t_first_ = t;
  if (!std::isnan(pend_t1_)) {
    if (!std::isnan(pend_t0_)) {
      const double h = pend_t1_ - pend_t0_;
      T_int_ += 0.5 * h * (pend_T0_ + pend_T1_);
      P_int_ += 0.5 * h * (pend_P0_ + pend_P1_);
      Tf_int_ += 0.5 * h * (pend_Tf0_ + pend_Tf1_);
      Pf_int_ += 0.5 * h * (pend_Pf0_ + pend_Pf1_);
    }
    pend_t0_ = pend_t1_;
    pend_T0_ = pend_T1_;
    pend_P0_ = pend_P1_;
    pend_Tf0_ = pend_Tf1_;
    pend_Pf0_ = pend_Pf1_;
  }
  pend_t1_ = t;
  pend_T1_ = pend_P1_ = pend_Tf1_ = pend_Pf1_ = 0.0;  // apart unless sample_force(t, …) follows
}

void DesignerStats::geometry_finish(Summary& s) const {
  s.max_pressure_angle_deg = geo_max_phi_;
  s.cam_continuity = cam_->continuity_report();
  s.min_radius_of_curvature = geo_min_rho_;
  s.max_side_load = max_side_;
  s.max_hertz_stress = max_hertz_;
  s.max_hertz_theta_deg = max_hertz_theta_;
  s.cam_torque_peak = T_peak_;
  s.cam_power_peak = P_peak_;
  double Ti = T_int_, Pi = P_int_, Tfi = Tf_int_, Pfi = Pf_int_;
  if (!std::isnan(pend_t0_) && !std::isnan(pend_t1_)) {
    const double h = pend_t1_ - pend_t0_;
    Ti += 0.5 * h * (pend_T0_ + pend_T1_);
    Pi += 0.5 * h * (pend_P0_ + pend_P1_);
    Tfi += 0.5 * h * (pend_Tf0_ + pend_Tf1_);
    Pfi += 0.5 * h * (pend_Pf0_ + pend_Pf1_);
  }
  const double span = std::isnan(pend_t1_) ? 0.0 : pend_t1_ - t_first_;
  if (span > 0) {
    s.cam_torque_mean = Ti / span;
    s.cam_power_mean = Pi / span;
  }
  if (cols_->friction()) {
    s.cam_friction_force_max = std::isnan(Ff_max_) ? 0.0 : Ff_max_;
    s.cam_friction_power_peak = std::isnan(Pf_peak_) ? 0.0 : Pf_peak_;
    s.cam_friction_work = Pfi;
    if (span > 0) {
      s.cam_friction_torque_mean = Tfi / span;
      s.cam_friction_power_mean = Pfi / span;
    }
  }
}

}  // namespace detail
}  // namespace camdyn
