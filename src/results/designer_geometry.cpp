// camdyn — the cam-geometry designer results of one run (issue 24; designer_stats.hpp):
// pressure angle and radius of curvature over the cam, side load, Hertz line-contact
// stress, cam torque T = F·dX_C/dθ (power balance: T ω = F Ẋ_C) and power.
#include <algorithm>
#include <cmath>

#include "results/designer_stats.hpp"

namespace camdyn {
namespace detail {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
}

void DesignerStats::geometry_init(const Scene& scene, const Cam& cam) {
  cam_ = std::make_shared<const Cam>(cam);  // a copy: the run's Cam outlives no guarantee here
  cols_ = std::make_shared<const DesignerColumns>(scene);
  // Extremes over the cam located between the samples and at the joints (cam_extremum).
  const CamExtremum phi = cam_extremum(cam, [](const CamPoint& p) { return std::fabs(p.pressure_angle); }, true);
  geo_max_phi_ = std::isnan(phi.value) ? 0.0 : phi.value * 360.0 / kTwoPi;
  geo_min_rho_ = cam.min_radius_of_curvature();
}

void DesignerStats::geometry_sample(double t, double theta, double F) {
  if (!(F > 0.0)) F = 0.0;
  const CamPoint cp = cam_->evaluate(theta);
  const double omega = drive_.omega(t);
  const ContactDesign d = cols_->eval(cp, F, omega);
  const double T = d.torque, P = d.power, side = std::fabs(d.side);
  if (cols_->friction()) {
    const CamFriction f = cols_->friction_at(cp, F, omega);
    if (std::isnan(Ff_max_) || f.force > Ff_max_) Ff_max_ = f.force;
    if (std::isnan(Pf_peak_) || f.power > Pf_peak_) Pf_peak_ = f.power;
    if (t == pend_t1_) {
      pend_Tf1_ = f.torque;
      pend_Pf1_ = f.power;
    }
  }
  if (!std::isnan(side) && (std::isnan(max_side_) || side > max_side_)) max_side_ = side;
  if (std::isnan(T_peak_) || std::fabs(T) > std::fabs(T_peak_)) T_peak_ = T;
  if (std::isnan(P_peak_) || std::fabs(P) > std::fabs(P_peak_)) P_peak_ = P;
  if (!std::isnan(d.stress) && (std::isnan(max_hertz_) || d.stress > max_hertz_)) {
    max_hertz_ = d.stress;
    max_hertz_theta_ = angle_deg_mod360(theta);
  }
  if (t == pend_t1_) {  // the current step end: its value for the time averages
    pend_T1_ = T;
    pend_P1_ = P;
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
