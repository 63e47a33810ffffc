// camdyn — cam geometry and kinematics (docs/method.md §2). See include/camdyn/cam.hpp.
//
// Profiles
//   points — periodic cubic splines x(α), y(α) (period 2π) through the knots
//            (r_i cos α_i, r_i sin α_i). The contact point at cam angle θ is the global
//            maximum over α of X(α, θ) = x cos θ − y sin θ: the profile point whose
//            cam-frame outward normal points at angle −θ. The normal angle φ(α) is
//            tabulated densely at construction (monotone for a convex profile); a call
//            inverts the table (hint from the previous call, else binary search) and
//            polishes α by safeguarded Newton on X_α(α) = 0.
//   circle — closed form.
//   lift   — support function h(θ) = r_b + L(θ), L a periodic cubic spline in θ.
//
// Profile construction and validation: cam_profiles.cpp. Cam::Impl: cam_impl.hpp.
#include "camdyn/cam.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cam/format.hpp"
#include "cam/impl.hpp"
#include "cam/follower_geometry.hpp"
#include "cam/follower_oscillating.hpp"

namespace camdyn {

using namespace cam_detail;  // cam_impl.hpp

namespace {

/// X, Y of a point and its first and second derivatives w.r.t. some curve parameter, in
/// the momentarily coincident (fixed) frame → the paper's eqs. 8, 9, A7.
CamMotion paper_form(double X, double Y, double Xa, double Ya, double Xaa, double Yaa,
                     double omega, double omega_dot) {
  const double r = std::hypot(X, Y);
  const double beta = std::atan2(Y, X);
  // x_yy = d²X/dY² along the profile (parameter invariant); X_α ≈ 0 at C.
  const double x_yy = (Xaa * Ya - Xa * Yaa) / (Ya * Ya * Ya);
  const double q = omega / (Ya * x_yy);
  CamMotion m;
  m.X = r * std::cos(beta);
  m.Xdot = -r * omega * std::sin(beta);
  m.Xddot = -r * omega * omega * std::cos(beta) - r * omega_dot * std::sin(beta) -
            2.0 * omega * omega / x_yy + q * q * Xaa;
  return m;
}

}  // namespace

// ---- evaluation -----------------------------------------------------------------------
CamPoint Cam::Impl::evaluate(double theta) const {
  CamPoint p;
  p.theta = theta;
  if (osc) {
    osc->fill(p, theta);
    return p;
  }
  if (geo) {
    const detail::FollowerState f = geo->eval(theta);
    detail::fill_cam_point(p, f);
    p.normal_force_ratio = 1.0 / std::cos(f.phi);
    return p;
  }
  const double ct = std::cos(theta), st = std::sin(theta);
  switch (kind) {
    case CamProfileKind::Circle: {
      const double X = e * ct + R, Y = e * st;
      p.X_C = X;
      p.dX_dtheta = -e * st;
      p.d2X_dtheta2 = -e * ct;
      p.d3X_dtheta3 = e * st;
      p.rho = R;
      p.beta = std::atan2(Y, X);
      p.r = std::hypot(X, Y);
      break;
    }
    case CamProfileKind::Lift: {
      double h, h1, h2, h3;
      Ls.eval(theta, &h, &h1, &h2, &h3);
      h += rb;
      p.X_C = h;
      p.dX_dtheta = h1;
      p.d2X_dtheta2 = h2;
      p.d3X_dtheta3 = h3;
      p.rho = h + h2;
      p.beta = std::atan2(-h1, h);
      p.r = std::hypot(h, h1);
      break;
    }
    case CamProfileKind::Points: {
      Derivs d;
      contact_alpha(theta, ct, st, &d);
      const double X = d.x * ct - d.y * st, Y = d.x * st + d.y * ct;
      const double s2 = d.x1 * d.x1 + d.y1 * d.y1;
      const double rho = s2 * std::sqrt(s2) / (d.x1 * d.y2 - d.y1 * d.x2);
      p.X_C = X;
      p.d3X_dtheta3 = std::numeric_limits<double>::quiet_NaN();
      p.dX_dtheta = -Y;  // envelope theorem: ∂X/∂θ = −Y at the maximiser
      p.rho = rho;
      p.d2X_dtheta2 = rho - X;
      p.beta = std::atan2(Y, X);
      p.r = std::hypot(X, Y);
      break;
    }
    default: break;
  }
  return p;
}

// =====================================================================================
Cam::Cam(const CamSpec& spec) : impl_(std::make_unique<Impl>()) {
  impl_->kind = spec.profile;
  if (spec.follower_motion == FollowerMotion::Oscillating) {
    if (spec.profile == CamProfileKind::Circle) impl_->build_circle(spec);  // its checks
    auto g = std::make_shared<detail::OscillatingGeometry>(spec);
    impl_->lift = g->lift();
    impl_->min_rho = g->min_rho();
    impl_->breaks = g->breaks();
    impl_->osc = std::move(g);
    refine_min_rho();
    return;
  }
  const bool geo = spec.profile == CamProfileKind::Law || spec.profile == CamProfileKind::Table || spec.profile == CamProfileKind::Arc ||
                   spec.profile == CamProfileKind::Arcs ||
                   spec.follower_face != FollowerFace::Flat;
  if (geo && spec.profile == CamProfileKind::Circle) impl_->build_circle(spec);  // its checks
  if (geo) {
    auto g = std::make_shared<detail::TranslatingGeometry>(spec);
    impl_->lift = g->lift();
    impl_->min_rho = g->min_rho();
    impl_->breaks = g->breaks();
    impl_->geo = std::move(g);
    refine_min_rho();
    return;
  }
  switch (spec.profile) {
    case CamProfileKind::Points: impl_->build_points(spec); break;
    case CamProfileKind::Circle: impl_->build_circle(spec); break;
    case CamProfileKind::Lift: impl_->build_lift(spec); break;
    case CamProfileKind::Law:
    case CamProfileKind::Table:
    case CamProfileKind::Arc:
    case CamProfileKind::Arcs: break;  // handled above
  }
}
void Cam::refine_min_rho() {
  // The smallest radius of curvature of the convex parts, located between the geometry's
  // samples and at its joints.
  const CamExtremum r = cam_extremum(
      *this, [](const CamPoint& p) { return p.rho > 0 ? p.rho : std::numeric_limits<double>::quiet_NaN(); }, false);
  if (!std::isnan(r.value) && !(impl_->min_rho <= r.value)) impl_->min_rho = r.value;
}
const std::vector<double>& Cam::breakpoints() const { return impl_->breaks; }
const MotionLaw* Cam::law() const {
  if (impl_->osc) return impl_->osc->law();
  return impl_->geo ? impl_->geo->law() : nullptr;
}
const std::vector<Breakpoint>& Cam::joints() const {
  static const std::vector<Breakpoint> kNone;
  if (const MotionLaw* l = law()) return l->breakpoints();
  return impl_->geo ? impl_->geo->arc_joints() : kNone;
}
std::string Cam::continuity_report() const {
  if (const MotionLaw* l = law()) return l->continuity_report();
  std::string s;
  for (const Breakpoint& b : joints()) {
    if (!s.empty()) s += ", ";
    s += "C" + std::to_string(std::min(b.order, 2)) + " at " + fmt_num(std::round(b.theta / kDeg * 1e6) / 1e6) + "°";
  }
  return s;
}
Cam::Cam(const Cam& o) : impl_(std::make_unique<Impl>(*o.impl_)) {}
Cam& Cam::operator=(const Cam& o) {
  if (this != &o) impl_ = std::make_unique<Impl>(*o.impl_);
  return *this;
}
Cam::Cam(Cam&&) noexcept = default;
Cam& Cam::operator=(Cam&&) noexcept = default;
Cam::~Cam() = default;

CamPoint Cam::evaluate(double theta) const { return impl_->evaluate(theta); }

CamMotion Cam::motion(double theta, double omega, double omega_dot) const {
  // X_C and its θ-derivatives only: the law/arc geometry and the lift spline directly,
  // without the contact point's polar angle and radius (atan2, hypot) of evaluate().
  const Impl& I = *impl_;
  double X, X1, X2;
  if (I.geo) {
    const detail::FollowerState f = I.geo->eval(theta);
    X = f.s, X1 = f.s1, X2 = f.s2;
  } else if (I.kind == CamProfileKind::Lift) {
    I.Ls.eval(theta, &X, &X1, &X2);
    X += I.rb;
  } else {
    const CamPoint p = I.evaluate(theta);
    X = p.X_C, X1 = p.dX_dtheta, X2 = p.d2X_dtheta2;
  }
  CamMotion m;
  m.X = X;
  m.Xdot = X1 * omega;
  m.Xddot = X2 * omega * omega + X1 * omega_dot;
  return m;
}

CamMotion Cam::motion_paper(double theta, double omega, double omega_dot) const {
  const Impl& I = *impl_;
  if (I.geo || I.osc) return motion(theta, omega, omega_dot);  // no paper form for these followers
  const double ct = std::cos(theta), st = std::sin(theta);
  // Rotate a cam-frame vector into the momentarily coincident fixed frame.
  auto rotX = [&](double x, double y) { return x * ct - y * st; };
  auto rotY = [&](double x, double y) { return x * st + y * ct; };
  switch (I.kind) {
    case CamProfileKind::Circle: {
      // Profile (e + R cos ψ, R sin ψ); the contact point has ψ = −θ.
      const double psi = -theta, cp = std::cos(psi), sp = std::sin(psi);
      const double x = I.e + I.R * cp, y = I.R * sp;
      const double x1 = -I.R * sp, y1 = I.R * cp;
      const double x2 = -I.R * cp, y2 = -I.R * sp;
      return paper_form(rotX(x, y), rotY(x, y), rotX(x1, y1), rotY(x1, y1), rotX(x2, y2),
                        rotY(x2, y2), omega, omega_dot);
    }
    case CamProfileKind::Lift: {
      // Envelope point parameterised by φ: P(φ) = R(−φ)·c(φ), c = (h, −h′). In the frame
      // turned by θ, Q(φ) = R(θ − φ)·c(φ); at φ = θ (J = rotation by +90°):
      //   Q = c,  Q′ = −J c + c′,  Q″ = −c − 2 J c′ + c″.
      double h, h1, h2, h3;
      I.Ls.eval(theta, &h, &h1, &h2, &h3);
      h += I.rb;
      const double cx = h, cy = -h1, c1x = h1, c1y = -h2, c2x = h2, c2y = -h3;
      const double Qx = cx, Qy = cy;
      const double Q1x = cy + c1x, Q1y = -cx + c1y;               // −J c = (c_y, −c_x)
      const double Q2x = -cx + 2.0 * c1y + c2x, Q2y = -cy - 2.0 * c1x + c2y;  // −2Jc′ = (2c′_y, −2c′_x)
      return paper_form(Qx, Qy, Q1x, Q1y, Q2x, Q2y, omega, omega_dot);
    }
    case CamProfileKind::Points: {
      Derivs d;
      I.contact_alpha(theta, ct, st, &d);
      return paper_form(rotX(d.x, d.y), rotY(d.x, d.y), rotX(d.x1, d.y1), rotY(d.x1, d.y1),
                        rotX(d.x2, d.y2), rotY(d.x2, d.y2), omega, omega_dot);
    }
    default: break;
  }
  return {};
}

double Cam::lift() const { return impl_->lift; }
double Cam::min_radius_of_curvature() const { return impl_->min_rho; }

std::array<double, 2> Cam::profile_point(double a) const {
  const Impl& I = *impl_;
  if (I.osc) return I.osc->profile_point(a);
  if (I.geo) return I.geo->profile_point(a);
  switch (I.kind) {
    case CamProfileKind::Circle: return {I.e + I.R * std::cos(a), I.R * std::sin(a)};
    case CamProfileKind::Lift: {
      double h, h1, h2;
      I.Ls.eval(a, &h, &h1, &h2);
      h += I.rb;
      const double c = std::cos(a), s = std::sin(a);
      return {h * c - h1 * s, -h * s - h1 * c};
    }
    case CamProfileKind::Points: {
      const Derivs d = I.derivs(a);
      return {d.x, d.y};
    }
    default: break;
  }
  return {0.0, 0.0};
}

// =====================================================================================
CamDrive::CamDrive(const CamSpec& spec) {
  if (!std::isfinite(spec.theta0_deg))
    fail("cam.theta0_deg", fmt_num(spec.theta0_deg), "must be finite (no nan/inf)");
  theta0_ = spec.theta0_deg * kDeg;
  const auto& T = spec.speed_table_t;
  const auto& S = spec.speed_table_rev_s;
  if (T.empty() && S.empty()) {
    if (!std::isfinite(spec.speed_rev_s))
      fail("cam.speed_rev_s", fmt_num(spec.speed_rev_s), "must be finite (no nan/inf)");
    omega0_ = kTwoPi * spec.speed_rev_s;
    return;
  }
  if (!all_finite(T)) fail("cam.speed_table_t", fmt_list(T), "every time must be finite (no nan/inf)");
  if (!all_finite(S))
    fail("cam.speed_table_rev_s", fmt_list(S), "every speed must be finite (no nan/inf)");
  if (T.empty()) fail("cam.speed_table_t", fmt_list(T), "must not be empty when cam.speed_table_rev_s is given");
  if (S.size() != T.size())
    fail("cam.speed_table_rev_s", fmt_list(S),
         "must have as many entries as cam.speed_table_t (" + std::to_string(T.size()) +
             "), got " + std::to_string(S.size()));
  if (T[0] != 0.0) fail("cam.speed_table_t", fmt_list(T), "the first time must be 0");
  for (std::size_t i = 1; i < T.size(); ++i)
    if (!(T[i] > T[i - 1]))
      fail("cam.speed_table_t", fmt_list(T),
           "times must be strictly increasing (entry " + std::to_string(i) + " = " +
               fmt_num(T[i]) + " does not exceed entry " + std::to_string(i - 1) + " = " +
               fmt_num(T[i - 1]) + ")");
  table_t_ = T;
  table_w_.resize(S.size());
  for (std::size_t i = 0; i < S.size(); ++i) table_w_[i] = kTwoPi * S[i];
  table_theta_.assign(T.size(), 0.0);  // ∫₀^{t_i} ω dt (trapezoid is exact for linear ω)
  for (std::size_t i = 1; i < T.size(); ++i)
    table_theta_[i] =
        table_theta_[i - 1] + 0.5 * (table_w_[i - 1] + table_w_[i]) * (T[i] - T[i - 1]);
  omega0_ = table_w_[0];
}

namespace {
/// Index k of the table segment [t_k, t_{k+1}) holding t; t < t_0 → 0 (extrapolated at ω_0
/// constant by the callers); t ≥ t_last → last index.
std::size_t drive_segment(const std::vector<double>& T, double t) {
  const auto it = std::upper_bound(T.begin(), T.end(), t);
  return it == T.begin() ? 0 : static_cast<std::size_t>(it - T.begin()) - 1;
}
}  // namespace

double CamDrive::theta(double t) const {
  if (table_t_.empty() || t < 0.0) return theta0_ + omega0_ * t;
  const std::size_t k = drive_segment(table_t_, t);
  const double dt = t - table_t_[k];
  if (k + 1 >= table_t_.size()) return theta0_ + table_theta_[k] + table_w_[k] * dt;
  const double a = (table_w_[k + 1] - table_w_[k]) / (table_t_[k + 1] - table_t_[k]);
  return theta0_ + table_theta_[k] + table_w_[k] * dt + 0.5 * a * dt * dt;
}

double CamDrive::omega(double t) const {
  if (table_t_.empty() || t < 0.0) return omega0_;
  const std::size_t k = drive_segment(table_t_, t);
  if (k + 1 >= table_t_.size()) return table_w_[k];
  const double a = (table_w_[k + 1] - table_w_[k]) / (table_t_[k + 1] - table_t_[k]);
  return table_w_[k] + a * (t - table_t_[k]);
}

double CamDrive::omega_dot(double t) const {
  if (table_t_.empty() || t < 0.0) return 0.0;
  const std::size_t k = drive_segment(table_t_, t);
  if (k + 1 >= table_t_.size()) return 0.0;
  return (table_w_[k + 1] - table_w_[k]) / (table_t_[k + 1] - table_t_[k]);
}

}  // namespace camdyn
