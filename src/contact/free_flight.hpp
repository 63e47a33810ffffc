// camdyn (private) — the free phase shared by the methods that integrate natively and
// switch phases at located events (event-driven; Lee on the multistep engine): its roots,
// and the impact at its end.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "run_context.hpp"

namespace camdyn {
namespace detail {

// Free phase: the gap closing, g = gap + δ. Right after a switch the state sits on the cam
// (gap = 0 exactly); the offset δ (a few ulps of X) keeps SUNDIALS from stopping with "root
// at and very near t" and from re-detecting the event just handled, at the price of a
// penetration of δ when the root is reported.
//
// A free phase that starts on the cam (after a separation, a bounce, or at t = 0) has a gap
// that opens from 0, slowly (≈ t³ after a separation, where the reaction passes through 0),
// while the integrator's error in q₀ after its restart is of the order of its local
// tolerance (BDF1's first steps: h²ü₀/2, ≫ δ). Armed at once, the gap root fired on that
// error again and again — each time the follower was put back on the cam and the
// integrator restarted with tiny steps (cvode-bdf, A7 at rtol 1e-9: 6.0 M steps in 7 ms
// after the first separation). So such a phase first watches |gap| − ε (rising) with
// ε = 10 (rtol·max(1, |X_C|) + atol), the integration error's scale: the gap opening past
// ε arms the closing-gap root (one restart); a penetration past ε before that is a
// re-contact (handled as an impact, located to ε).
//
// Impact: a Newton impulse P = (1 + e) ŝ⁻ / M* on node 0 (Δv = M⁻¹e₀P); the follower
// stays on the cam if the bounce is slower than the chattering guard (below) and the
// contact force there is compressive.
class RunContext::FreeFlight {
 public:
  enum class Outcome {
    None,     ///< no root: the free flight goes on
    Restart,  ///< a root that starts a new free phase (gap armed, bounce, grazing)
    Contact,  ///< an impact after which the follower holds the cam (F_ set)
  };
  explicit FreeFlight(RunContext& rc) : rc_(rc) {}

  /// Arms the phase's root and restarts the engine's free phase at (t_, y_).
  void start() {
    RunContext& r = rc_;
    const double X = r.cam_at(r.t_).X;
    eps_leave_ = 10.0 * (r.sc_.solver.rtol * std::max(1.0, std::abs(X)) + r.sc_.solver.atol);
    leaving_ = r.y_[0] - X < eps_leave_;
    if (leaving_)
      r.engine_->set_root([this](double t, const double* y) { return std::abs(y[0] - rc_.cam_at(t).X) - eps_leave_; }, +1);
    else
      r.engine_->set_root([this](double t, const double* y) {
        const double Xc = rc_.cam_at(t).X;
        return y[0] - Xc + 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(Xc));
      }, -1);
    r.engine_->reinit(r.t_, r.y_);
  }

  /// One engine step of the free phase toward tout (F = 0), then its root if any
  /// (after_advance). *P_end: the damping power at the step's end before an impact.
  template <class Reaction>
  Outcome advance(double tout, Eigen::VectorXd& y1, double* P_end, Reaction reaction) {
    RunContext& r = rc_;
    r.t_ = r.engine_->advance(tout, y1);
    r.y_ = y1;
    r.F_ = 0.0;
    *P_end = r.dissipation_power();
    return after_advance(reaction);
  }

  /// After an engine advance of the free phase (state in t_, y_): handles a root. The
  /// caller restarts the phase its outcome names. `reaction()`: the contact force that
  /// would hold node 0 on the cam at (t_, y_) (called with node 0 put on the cam).
  template <class Reaction>
  Outcome after_advance(Reaction reaction) {
    RunContext& r = rc_;
    if (!r.engine_->hit_root()) return Outcome::None;
    if (leaving_ && r.y_[0] - r.cam_at(r.t_).X > 0.0) return Outcome::Restart;  // arm the gap root
    const int n = r.n_;
    const double Ms = r.m_.mstar(), e_rest = r.sc_.contact.restitution;
    const CamMotion c = r.cam_at(r.t_);
    const double approach = c.Xdot - r.y_[n];  // ŝ⁻ > 0: closing
    const double v0_pre = r.y_[n];
    r.y_[0] = c.X;  // the root is located to round-off
    bool contact = false;
    if (approach > 0.0) {
      const double P = (1.0 + e_rest) * approach / Ms;
      Eigen::VectorXd e0 = Eigen::VectorXd::Zero(n), dv(n);
      e0[0] = P;
      r.m_.solve_mass(e0.data(), dv.data());
      r.y_.tail(n) += dv;
      r.work_ += P * c.Xdot;  // the cam's impulse does work P·Ẋ_C
      r.dissipated_ += 0.5 * (1.0 - e_rest * e_rest) * approach * approach / Ms;
      // Chattering guard: a bounce slower than this sticks (plastic).
      // (bounces of a coefficient e < 1 on a still surface form a Zeno sequence;
      // below 1e-6 of the first impact speed the follower is taken to rest on it)
      // The root offset δ itself lets the follower gain √(2|s̈|δ) before each root
      // is reported; bounces slower than a few times that are round-off, not motion.
      if (r.v_impact_ref_ == 0.0) r.v_impact_ref_ = approach;
      const double rel_acc = std::abs(c.Xddot - r.m_.contact_acceleration(r.y_.data(), r.y_.data() + n, 0.0));
      // (A re-contact found by the leaving phase's band root is located at a
      // penetration of ε, not δ: the same argument with ε.)
      const double delta = leaving_ ? eps_leave_
                                    : 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(c.X));
      const double v_stick = std::max(1e-6 * std::max(r.v_impact_ref_, 1e-3), 8.0 * std::sqrt(2.0 * rel_acc * delta));
      if (e_rest == 0.0 || (1.0 + e_rest) * approach < v_stick) {
        r.y_[n] = c.Xdot;
        const double Fr = reaction();
        if (Fr > 0.0) {
          contact = true;
          r.F_ = Fr;
        }
      }
      ++r.sum_.impacts;
      r.record_event(EventKind::Impact, approach, (r.y_[n] - v0_pre) / Ms);
    }
    return contact ? Outcome::Contact : Outcome::Restart;
  }

 private:
  RunContext& rc_;
  double eps_leave_ = 0.0;
  bool leaving_ = false;
};

}  // namespace detail
}  // namespace camdyn
