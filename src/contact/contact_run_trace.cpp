// camdyn — the designer extremes of an accepted step located inside it (contact_run.hpp
// trace_step; results/step_extremes.hpp): every method hands its accepted step here, with
// the step's own dense state and contact forces.
#include <algorithm>
#include <cmath>
#include <functional>

#include "contact/contact_run.hpp"

namespace camdyn {
namespace detail {

void ContactRun::trace_step(double t0, double t1, const StateFn& state, const ForcesFn& forces,
                            const std::vector<int>& set, bool energy_alike, const Eigen::VectorXd* y_end,
                            const Eigen::VectorXd* F_end, const Eigen::VectorXd* y_start) {
  const double h = t1 - t0;
  if (!(h > 0)) return;
  traced_ = true;
  const int p = mk_.primary();
  trace_in_.assign(std::size_t(m_), 0);
  for (int j : set) trace_in_[std::size_t(j)] = 1;
  const bool want_gaps = analysis_.wants_gaps(), want_nodes = analysis_.wants_nodes();
  // The cam at a step end on a cam breakpoint: just inside the step (a cam joint is a step
  // end: each side's value from its own step). Elsewhere the cam at the sample's own angle
  // (a step end away from the breakpoints is the same point of the cam for the steps on
  // both sides, and for after_step's samples there).
  const double eps = 1e-12 * h;
  auto one_sided_theta = [&](double tau) {
    const double inside = std::min(t1 - eps, std::max(t0 + eps, tau));
    if (inside == tau) return drive_.theta(tau);
    const double th = drive_.theta(tau);
    return near_cam_breakpoint(th) ? drive_.theta(inside) : th;
  };
  // the sample at x from the state y at tau and its forces F_in (nullptr: evaluated)
  auto fill = [&](double x, double tau, StepSample& s, const Eigen::VectorXd& y,
                  const Eigen::VectorXd* F_in = nullptr) {
    s.x = x;
    s.t = tau;
    s.theta = one_sided_theta(tau);
    s.cam_valid = false;
    s.omega = drive_.omega(tau);
    const CamMotion cm = cam_at(tau);
    if (!F_in) {
      trace_F_.setZero(m_);
      forces(tau, y, cm, trace_F_);
    }
    const Eigen::VectorXd& F = F_in ? *F_in : trace_F_;
    s.X = cm.X;
    s.Xdot = cm.Xdot;
    s.forces.assign(F.data(), F.data() + m_);
    s.in_set = trace_in_;
    s.Fc = 0.0;
    for (int j = 0; j < m_; ++j)
      if (mk_.contacts()[j].cam) s.Fc += std::max(F[j], 0.0);
    // gaps and gap rates only for the statistics that read them (the seats' landings)
    s.gaps.resize(want_gaps ? std::size_t(m_) : 0);
    s.gap_rates.resize(want_gaps ? std::size_t(m_) : 0);
    if (want_gaps)
      for (int j = 0; j < m_; ++j) {
        s.gaps[std::size_t(j)] = gap(j, y, cm);
        s.gap_rates[std::size_t(j)] = gap_rate(j, y, cm);
      }
    s.F = F[p];
    if (want_nodes) {
      const Eigen::VectorXd u = mk_.L() * y.head(n_);
      s.nodes.assign(u.data(), u.data() + u.size());
    }
    s.held = trace_in_[std::size_t(p)] != 0;
  };
  auto probe = [&](double x, StepSample& s) {
    const double tau = x >= 1.0 ? t1 : t0 + x * h;
    state(tau, trace_y_);
    fill(x, tau, s, trace_y_);
  };
  std::vector<StepSample>& s = trace_samples_;
  s.resize(kStepSamples);
  // The start: the previous step's end probe when this step starts where that one ended,
  // from the same state (bitwise: no impact, projection or restart between them) and with
  // the same held set; only the one-sided cam angle is this step's own (a cam joint at t0).
  // The state compared: the one the method started the step from (y_start), else the
  // step's own state at t0.
  const bool continues = trace_prev_valid_ && trace_prev_end_.t == t0 && trace_prev_end_.in_set == trace_in_;
  const Eigen::VectorXd* y0 = y_start;
  if (!(continues && y0)) {
    state(t0, trace_y_);
    y0 = &trace_y_;
  }
  if (continues && trace_prev_y_.size() == y0->size() && trace_prev_y_ == *y0) {
    std::swap(s[0], trace_prev_end_);
    s[0].x = 0.0;
    const double th0 = one_sided_theta(t0);
    if (th0 != s[0].theta) {  // a cam breakpoint at t0: this step's side
      s[0].theta = th0;
      s[0].cam_valid = false;
    }
  } else {
    if (y0 != &trace_y_) state(t0, trace_y_);
    fill(0.0, t0, s[0], trace_y_);
  }
  for (int k = 1; k < kStepSamples; ++k) {
    const double x = double(k) / (kStepSamples - 1);
    // the middle: step_energy's middle Gauss point of this step, when it is the same
    if (energy_alike && 2 * k == kStepSamples - 1 && se_mid_t0_ == t0 && se_mid_t1_ == t1 &&
        se_mid_F_.size() == m_) {
      fill(x, t0 + x * h, s[std::size_t(k)], se_mid_y_, &se_mid_F_);
    } else if (k == kStepSamples - 1 && y_end && F_end) {  // the end: the method's own
      fill(1.0, t1, s[std::size_t(k)], *y_end, F_end);
    } else {
      probe(x, s[std::size_t(k)]);
    }
  }
  trace_prev_y_ = y_end && F_end ? *y_end : trace_y_;  // the state at t1 (else the last probe)
  // per held contact: its least force outside the lash take-up window, its side load
  StepSample tmp;
  double x[kStepSamples], q[kStepSamples];
  for (int k = 0; k < kStepSamples; ++k) x[k] = s[std::size_t(k)].x;
  auto tan_phi = [&](const StepSample& a) { return std::tan(a.cam_point(cam_).pressure_angle); };
  for (int j : set) {
    ContactResult& cr = rec_.contacts[std::size_t(j)];
    auto force = [&](const StepSample& a) { return in_take_up(a.t) ? NAN : std::max(a.forces[std::size_t(j)], 0.0); };
    for (int k = 0; k < kStepSamples; ++k) q[k] = force(s[std::size_t(k)]);
    auto force_at = [&](double xx) {
      probe(xx, tmp);
      return force(tmp);
    };
    const LocatedExtreme lf = locate_extreme(x, q, kStepSamples, -1, cr.min_force, std::cref(force_at));
    if (lf.found) sample_contact(j, lf.value, angle_deg_mod360(drive_.theta(t0 + lf.x * h)));
    // an edge of the take-up window inside the step: the force there (bisection on the
    // cam's lift to the edge, taken on its outer side) is a sample too — a least force
    // that falls toward the window is found at its edge, not at the sample before it
    for (int k = 0; k + 1 < kStepSamples; ++k) {
      const bool in0 = std::isnan(q[k]), in1 = std::isnan(q[k + 1]);
      if (in0 == in1) continue;
      double lo = x[k], hi = x[k + 1];  // lo on the side of sample k
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (in_take_up(t0 + mid * h) == in0 ? lo : hi) = mid;
      }
      probe(in0 ? hi : lo, tmp);
      const double F = force(tmp);
      if (!std::isnan(F)) sample_contact(j, F, angle_deg_mod360(tmp.theta));
    }
    if (!mk_.contacts()[j].cam) continue;
    auto side = [&](const StepSample& a) { return std::abs(a.forces[std::size_t(j)] * tan_phi(a)); };
    for (int k = 0; k < kStepSamples; ++k) q[k] = side(s[std::size_t(k)]);
    auto side_at = [&](double xx) {
      probe(xx, tmp);
      return side(tmp);
    };
    const LocatedExtreme ls = locate_extreme(x, q, kStepSamples, 1, cr.max_side_load, std::cref(side_at));
    if (ls.found && (std::isnan(cr.max_side_load) || ls.value > cr.max_side_load)) {
      cr.max_side_load = ls.value;
      cr.max_side_load_theta_deg = angle_deg_mod360(drive_.theta(t0 + ls.x * h));
    }
  }
  // (the functions by reference: std::function holds a reference without allocating)
  designer_.step_inside(s, std::cref(probe));
  analysis_.step_inside(s, std::cref(probe));
  // the end sample, with the cam point the results evaluated there (s is filled anew by
  // the next step)
  std::swap(trace_prev_end_, s[kStepSamples - 1]);
  trace_prev_valid_ = true;
}

const CamPoint* ContactRun::traced_end_cam(double t, double theta) const {
  const StepSample& e = trace_prev_end_;
  return trace_prev_valid_ && e.t == t && e.theta == theta && e.cam_valid ? &e.cam_pt : nullptr;
}

bool ContactRun::near_cam_breakpoint(double theta) const {
  const std::vector<double>& b = cam_.breakpoints();  // sorted, in [0, 2π)
  if (b.empty()) return false;
  constexpr double kTwoPi = 6.283185307179586476925286766559;
  double phi = std::fmod(theta, kTwoPi);
  if (phi < 0) phi += kTwoPi;
  const auto it = std::lower_bound(b.begin(), b.end(), phi);
  const double above = it == b.end() ? b.front() + kTwoPi : *it;
  const double below = it == b.begin() ? b.back() - kTwoPi : *(it - 1);
  return std::min(above - phi, phi - below) <= 1e-9;
}

}  // namespace detail
}  // namespace camdyn
