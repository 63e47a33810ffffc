// camdyn — the designer extremes of an accepted step located inside it (contact_run.hpp
// trace_step; results/step_extremes.hpp): every method hands its accepted step here, with
// the step's own dense state and contact forces.
#include <algorithm>
#include <cmath>

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
  // the cam just inside the step at its ends (a cam joint is a step end: each side's value
  // from its own step)
  const double eps = 1e-12 * h;
  auto one_sided_theta = [&](double tau) { return drive_.theta(std::min(t1 - eps, std::max(t0 + eps, tau))); };
  // the sample at x from the state at tau already in trace_y_ (and its forces in trace_F_
  // when `have_forces`)
  auto fill = [&](double x, double tau, StepSample& s, bool have_forces = false) {
    s.x = x;
    s.t = tau;
    s.theta = one_sided_theta(tau);
    s.cam_valid = false;
    s.omega = drive_.omega(tau);
    const CamMotion cm = cam_at(tau);
    if (!have_forces) {
      trace_F_.setZero(m_);
      forces(tau, trace_y_, cm, trace_F_);
    }
    s.X = cm.X;
    s.Xdot = cm.Xdot;
    s.forces.assign(trace_F_.data(), trace_F_.data() + m_);
    s.in_set = trace_in_;
    s.Fc = 0.0;
    for (int j = 0; j < m_; ++j)
      if (mk_.contacts()[j].cam) s.Fc += std::max(trace_F_[j], 0.0);
    // gaps and gap rates only for the statistics that read them (the seats' landings)
    s.gaps.resize(want_gaps ? std::size_t(m_) : 0);
    s.gap_rates.resize(want_gaps ? std::size_t(m_) : 0);
    if (want_gaps)
      for (int j = 0; j < m_; ++j) {
        s.gaps[std::size_t(j)] = gap(j, trace_y_, cm);
        s.gap_rates[std::size_t(j)] = gap_rate(j, trace_y_, cm);
      }
    s.F = trace_F_[p];
    if (want_nodes) {
      const Eigen::VectorXd u = mk_.L() * trace_y_.head(n_);
      s.nodes.assign(u.data(), u.data() + u.size());
    }
    s.held = trace_in_[std::size_t(p)] != 0;
  };
  auto probe = [&](double x, StepSample& s) {
    const double tau = x >= 1.0 ? t1 : t0 + x * h;
    state(tau, trace_y_);
    fill(x, tau, s);
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
    s[0].theta = one_sided_theta(t0);
    s[0].cam_valid = false;
  } else {
    if (y0 != &trace_y_) state(t0, trace_y_);
    fill(0.0, t0, s[0]);
  }
  for (int k = 1; k < kStepSamples; ++k) {
    const double x = double(k) / (kStepSamples - 1);
    // the middle: step_energy's middle Gauss point of this step, when it is the same
    if (energy_alike && 2 * k == kStepSamples - 1 && se_mid_t0_ == t0 && se_mid_t1_ == t1 &&
        se_mid_F_.size() == m_) {
      trace_y_ = se_mid_y_;
      trace_F_ = se_mid_F_;
      fill(x, t0 + x * h, s[std::size_t(k)], true);
    } else if (k == kStepSamples - 1 && y_end && F_end) {  // the end: the method's own
      trace_y_ = *y_end;
      trace_F_ = *F_end;
      fill(1.0, t1, s[std::size_t(k)], true);
    } else {
      probe(x, s[std::size_t(k)]);
    }
  }
  trace_prev_end_ = s[kStepSamples - 1];
  trace_prev_y_ = trace_y_;  // the state at t1 (the last probe)
  trace_prev_valid_ = true;
  // per held contact: its least force outside the lash take-up window, its side load
  StepSample tmp;
  double x[kStepSamples], q[kStepSamples];
  for (int k = 0; k < kStepSamples; ++k) x[k] = s[std::size_t(k)].x;
  auto tan_phi = [&](const StepSample& a) { return std::tan(a.cam_point(cam_).pressure_angle); };
  for (int j : set) {
    ContactResult& cr = rec_.contacts[std::size_t(j)];
    auto force = [&](const StepSample& a) { return in_take_up(a.t) ? NAN : std::max(a.forces[std::size_t(j)], 0.0); };
    for (int k = 0; k < kStepSamples; ++k) q[k] = force(s[std::size_t(k)]);
    const LocatedExtreme lf = locate_extreme(x, q, kStepSamples, -1, cr.min_force, [&](double xx) {
      probe(xx, tmp);
      return force(tmp);
    });
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
    const LocatedExtreme ls = locate_extreme(x, q, kStepSamples, 1, cr.max_side_load, [&](double xx) {
      probe(xx, tmp);
      return side(tmp);
    });
    if (ls.found && (std::isnan(cr.max_side_load) || ls.value > cr.max_side_load)) {
      cr.max_side_load = ls.value;
      cr.max_side_load_theta_deg = angle_deg_mod360(drive_.theta(t0 + ls.x * h));
    }
  }
  designer_.step_inside(s, probe);
  analysis_.step_inside(s, probe);
}

}  // namespace detail
}  // namespace camdyn
