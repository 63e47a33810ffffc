// camdyn — the designer extremes of an accepted step located inside it (contact_run.hpp
// trace_step; results/step_extremes.hpp): every method hands its accepted step here, with
// the step's own dense state and contact forces.
#include <algorithm>
#include <cmath>

#include "contact/contact_run.hpp"

namespace camdyn {
namespace detail {

void ContactRun::trace_step(double t0, double t1, const StateFn& state, const ForcesFn& forces,
                            const std::vector<int>& set) {
  const double h = t1 - t0;
  if (!(h > 0)) return;
  traced_ = true;
  const int p = mk_.primary();
  trace_in_.assign(std::size_t(m_), 0);
  for (int j : set) trace_in_[std::size_t(j)] = 1;
  // the cam just inside the step at its ends (a cam joint is a step end: each side's value
  // from its own step)
  const double eps = 1e-12 * h;
  auto probe = [&](double x, StepSample& s) {
    const double tau = x >= 1.0 ? t1 : t0 + x * h;
    s.x = x;
    s.t = tau;
    s.theta = drive_.theta(std::min(t1 - eps, std::max(t0 + eps, tau)));
    s.omega = drive_.omega(tau);
    state(tau, trace_y_);
    const CamMotion cm = cam_at(tau);
    trace_F_.setZero(m_);
    forces(tau, trace_y_, cm, trace_F_);
    s.X = cm.X;
    s.Xdot = cm.Xdot;
    s.forces.assign(trace_F_.data(), trace_F_.data() + m_);
    s.gaps.resize(std::size_t(m_));
    s.gap_rates.resize(std::size_t(m_));
    s.in_set = trace_in_;
    s.Fc = 0.0;
    for (int j = 0; j < m_; ++j) {
      s.gaps[std::size_t(j)] = gap(j, trace_y_, cm);
      s.gap_rates[std::size_t(j)] = gap_rate(j, trace_y_, cm);
      if (mk_.contacts()[j].cam) s.Fc += std::max(trace_F_[j], 0.0);
    }
    s.F = trace_F_[p];
    if (analysis_.wants_nodes()) {
      const Eigen::VectorXd u = mk_.L() * trace_y_.head(n_);
      s.nodes.assign(u.data(), u.data() + u.size());
    }
    s.held = trace_in_[std::size_t(p)] != 0;
  };
  std::vector<StepSample>& s = trace_samples_;
  s.resize(kStepSamples);
  for (int k = 0; k < kStepSamples; ++k) probe(double(k) / (kStepSamples - 1), s[std::size_t(k)]);
  // per held contact: its least force outside the lash take-up window, its side load
  StepSample tmp;
  double x[kStepSamples], q[kStepSamples];
  for (int k = 0; k < kStepSamples; ++k) x[k] = s[std::size_t(k)].x;
  auto tan_phi = [&](const StepSample& a) { return std::tan(cam_.evaluate(a.theta).pressure_angle); };
  for (int j : set) {
    ContactResult& cr = sum_.contacts[std::size_t(j)];
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
