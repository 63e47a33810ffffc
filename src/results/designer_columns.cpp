// camdyn — the designer quantities of one contact state (designer_columns.hpp).
#include "results/designer_columns.hpp"

#include <cmath>

#include "cam/follower_oscillating.hpp"
#include "camdyn/hertz.hpp"

namespace camdyn {
namespace detail {

namespace {
constexpr double kDegPerRad = 57.295779513082320876798154814105;
}

const std::vector<std::string>& DesignerColumns::names() {
  static const std::vector<std::string> n{"pressure_angle_deg", "radius_of_curvature", "contact_stress",
                                          "side_load",          "cam_torque",          "cam_power"};
  return n;
}

const std::vector<std::string>& DesignerColumns::friction_names() {
  static const std::vector<std::string> n{"sliding_speed", "cam_friction_force", "cam_friction_torque",
                                          "cam_friction_power"};
  return n;
}

double DesignerColumns::friction_coefficient(double v) const {
  if (!(v_st_ > 0)) return mu_;
  const double x = v / v_st_;
  return mu_ + (mu_s_ - mu_) * std::exp(-x * x);
}

PadFriction DesignerColumns::pad_friction(const CamPoint& p, double omega) const {
  PadFriction r;
  const OscillatingState o = osc_->eval(p.theta);
  const double w = omega * (o.normal_distance - o.psi1 * o.tangent_arm);  // ω h − ψ̇ b
  r.sliding_speed = std::abs(w);
  r.sign = w > 0 ? 1.0 : (w < 0 ? -1.0 : 0.0);
  r.mu = friction_coefficient(r.sliding_speed);
  const double a_eff = o.moment_arm + r.mu * r.sign * o.tangent_arm;  // > 0: check_friction_lock
  r.gain = a_eff / o.moment_arm;
  r.normal_ratio = lv_ / a_eff;
  return r;
}

double DesignerColumns::normal_force(const CamPoint& p, double F, double omega) const {
  return osc_ ? F * pad_friction(p, omega).normal_ratio : F * p.normal_force_ratio;
}

CamFriction DesignerColumns::friction_at(const CamPoint& p, double F, double omega) const {
  CamFriction f;
  if (!friction() || !(F > 0)) return f;
  if (osc_) {
    const PadFriction pf = pad_friction(p, omega);
    f.sliding_speed = pf.sliding_speed;
    f.force = pf.mu * std::abs(pf.sign) * F * pf.normal_ratio;  // w = 0: no sliding, no force
    f.power = f.force * f.sliding_speed;
    f.torque = omega != 0 ? f.power / omega : 0.0;
    return f;
  }
  const double N = F * p.normal_force_ratio;
  if (roller_ && slip_ == 0) return f;  // a rolling roller: no sliding friction
  if (roller_) {
    const double Vc = std::abs(omega) * std::hypot(p.X_C, p.dX_dtheta);
    f.sliding_speed = slip_ * (std::isfinite(p.rho) && p.rho + rr_ != 0 ? Vc * p.rho / (p.rho + rr_) : Vc);
    f.sliding_speed = std::abs(f.sliding_speed);
  } else {
    f.sliding_speed = std::abs(omega * p.X_C);
  }
  f.force = friction_coefficient(f.sliding_speed) * N;
  f.power = f.force * f.sliding_speed;
  f.torque = omega != 0 ? f.power / omega : 0.0;
  return f;
}

void DesignerColumns::append_friction(const CamPoint& p, double F, double omega, std::vector<double>& out) const {
  const CamFriction f = friction_at(p, F, omega);
  out.insert(out.end(), {f.sliding_speed, f.force, f.torque, f.power});
}

DesignerColumns::DesignerColumns(const Scene& scene) {
  const CamSpec& c = scene.cam;
  mu_ = c.friction_coefficient;
  mu_s_ = c.friction_static_coefficient;
  v_st_ = c.friction_stribeck_speed;
  slip_ = c.roller_slip;
  roller_ = c.follower_face == FollowerFace::Roller;
  rr_ = c.roller_radius;
  if (friction() && c.follower_motion == FollowerMotion::Oscillating && c.follower_face == FollowerFace::Flat) {
    lv_ = c.valve_arm;
    osc_ = std::make_shared<const OscillatingGeometry>(c);
  }
  const bool face_ok = c.follower_face == FollowerFace::Flat || c.follower_face == FollowerFace::Roller;
  if (c.width > 0 && face_ok) {
    width_ = c.width;
    E_star_ = contact_modulus(c.youngs_modulus, c.poisson_ratio, c.follower_youngs_modulus,
                              c.follower_poisson_ratio);
    Rf_ = c.follower_face == FollowerFace::Roller ? c.roller_radius : INFINITY;
  }
}

ContactDesign DesignerColumns::eval(const CamPoint& p, double F, double omega) const {
  ContactDesign d;
  d.pressure_angle_deg = p.pressure_angle * kDegPerRad;
  d.rho = p.rho;
  // translating: the guide's side load; oscillating: the pivot takes it (NaN)
  d.side = std::isnan(p.moment_arm) ? F * std::tan(p.pressure_angle) : NAN;
  d.torque = F * p.dX_dtheta;
  d.power = d.torque * omega;
  d.stress = NAN;
  const double curv = (std::isinf(Rf_) ? 0.0 : 1.0 / Rf_) + 1.0 / p.rho;
  if (E_star_ > 0 && std::isfinite(p.rho) && curv > 0)
    d.stress = hertz_line(normal_force(p, F, omega), width_, p.rho, Rf_, E_star_).max_pressure;
  return d;
}

void DesignerColumns::append(const CamPoint& p, double F, double omega, std::vector<double>& out) const {
  const ContactDesign d = eval(p, F, omega);
  out.insert(out.end(), {d.pressure_angle_deg, d.rho, d.stress, d.side, d.torque, d.power});
}

}  // namespace detail
}  // namespace camdyn
