// camdyn — Lee's method, the classic step (contact.lee_step = "classic").
//
// Lee's method (docs/method.md §3–4), one step t → t+Δt from the accepted state (q, v, F):
//   F = −p ≥ 0 is the compressive contact force; within the step F is linear in time
//   from the accepted Fᵗ to the trial end value.
//   1. displacement level  p^m = min(0, p^{m−1} − b v^{m−1}),  b = 6/(M*Δt²)
//        v = s if p < 0 or s > 0, else 0;   s = X_C(t+Δt) − q₀(t+Δt)
//      (each iterate integrates the step again from the saved state) until |v| < tol_u.
//   2. step control on the engine's local error estimate of the converged step.
//   3. velocity level      p̂^m = min(0, p̂^{m−1} − b̂ v̂^{m−1}), b̂ = 2/(M*Δt)
//        eq12: v̂ = ŝ if p < 0 and (ŝ > 0 or p̂ < 0)
//        eq17: v̂ = ŝ if (p < 0 or p̃ᵗ < 0) and (ŝ > 0 or p̂ < 0)
//   4. acceleration level  p̃^m = min(0, p̃^{m−1} − b̃ ṽ^{m−1}), b̃ = 1/M*
//        eq13: ṽ = s̃ if p̂ < 0 and (s̃ > 0 or p̃ < 0)
//        eq18: ṽ = s̃ if (p̂ < 0 or p̃ᵗ < 0) and (s̃ > 0 or p̃ < 0)
//      (no integration: ü₀ is affine in p̃ through the equation of motion).
//   The accepted state takes q from level 1, v from level 3, (a, F) from level 4.
//   b, b̂, b̃ are the Newton constants for a force ramp acting on a mass M*: for a rigid
//   follower each level converges in one correction; where an error does not fall
//   (separation, clipping at 0) the constant is halved and the update retried; a level
//   that does not converge in max_iterations is a recoverable step failure (Δt/2).
//   Without separation (contact.separation = false, or model "holonomic") the same
//   iteration runs without the clipping and with v = s, v̂ = ŝ, ṽ = s̃: a bilateral
//   (holonomic) constraint; the first time its force turns tensile is reported.
//   Restitution e > 0 (Lee): at an impact (contact closing in this step after a free
//   phase) the velocity-level target becomes ŝ⁺ = −e ŝ⁻, i.e. v̂ = ŝ + e ŝ⁻.

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "legacy/run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

class LeeClassic final : public RunContext {
 public:
  using RunContext::RunContext;

 private:
  StepRamp ramp_;  // the force on the contact node over the step being taken

  // ------------------------------------------------------------ Lee's method ------
  // One level's fixed-point iteration with constant halving. `eval(F)` returns the
  // error for the trial force F (integrating if needed); returns the converged F.
  // min_updates = 1 forces one correction even if the start value already meets tol
  // (used at the acceleration level, where a correction costs no integration).
  template <class Eval>
  double iterate(double F_start, double b, double tol, LevelStats& st, Eval eval,
                 int min_updates = 0) {
    const int max_it = sc_.contact.max_iterations;
    double F_last = F_start;
    double v_last = eval(F_last);
    int it = 0;
    double F = F_last;
    while (std::abs(v_last) >= tol || (it < min_updates && v_last != 0.0)) {
      if (++it > max_it) {
        ++sum_.iteration_failures;
        throw IterationFailure();
      }
      // p = min(0, p − b v)  ⇔  F = max(0, F + b v)  (no clipping if bilateral)
      F = F_last + b * v_last;
      if (!bilateral_ && F < 0.0) F = 0.0;
      const double v = eval(F);
      ++sum_.contact_iterations;
      if (std::abs(v) >= std::abs(v_last) && std::abs(v) >= tol && v != 0.0) {
        b *= 0.5;  // error did not fall: halve the constant, retry from the last iterate
        eval(F_last);
        continue;
      }
      F_last = F;
      v_last = v;
    }
    st.total += it;
    st.max = std::max(st.max, it);
    ++st.steps;
    return F_last;
  }

  // Work of the contact force over an accepted Lee step [t_ − h, t_], ∫ F Ẋ_C dt.
  // What the step knows of F: the accepted forces at both ends, Fᵗ and F̃ (acceleration
  // level: the force the equation of motion demands there), and the impulse ∫F dt =
  // ½(Fᵗ + F̂)h of the velocity-level ramp that produced the accepted velocity. The ramp
  // itself is only a linear stand-in (F̂ = F(t+h) − h²F″/6 + …): using it here left an
  // O(h²) global error in W whose sign does not average out (−∫(d³X_C/dt³)² < 0) — 2 % of
  // the work over 100 revolutions of case A with 3 ms steps. The quadratic through both
  // end forces with the step's impulse is O(h³) accurate; Simpson's rule on F·Ẋ_C with it:
  //   F(h/2) = ¾(Fᵗ + F̂) − ¼(Fᵗ + F̃)   (from ∫₀ʰ F = h/6 (F(0) + 4F(h/2) + F(h))).
  double lee_step_work(double h, double Ft, double Fv, double Fa, double Xdot0,
                       double Xdot1) const {
    const double Fm = 0.75 * (Ft + Fv) - 0.25 * (Ft + Fa);
    const double Xm = cam_at(t_ - 0.5 * h).Xdot;
    return h / 6.0 * (Ft * Xdot0 + 4.0 * Fm * Xm + Fa * Xdot1);
  }

  // ∫ F Ẋ_C dt over a Lee step [t0, t1] in contact throughout (no impact, no separation).
  // A long step may straddle a sharp feature of the contact force (on the paper's cam F
  // rises from 3900 to 5300 and falls back within 8 ms near θ = 120°, where the profile
  // is nearly flat), which no polynomial through the step's data resolves. But while
  // node 0 rides the cam its force is known pointwise from the equation of motion,
  //   F(τ) = (Ẍ_C(τ) − ü₀,free(q(τ), v(τ))) / M*,
  // with node 0 on the cam (q₀ = X_C, v₀ = Ẋ_C) and the other nodes by cubic Hermite
  // interpolation of the step's end states (q̇ = v, v̇ = M⁻¹(f₀ − Kq − Cv + e₀F)).
  // Adaptive Simpson on F·Ẋ_C to 1e-8 of the step's work scale. For a rigid follower
  // F(τ) is exact (ü₀,free depends on node 0 only); costs O(n) per sample. The samples
  // also enter max_contact_force, which step ends alone would miss inside long steps.
  double held_contact_work(double t0, const Eigen::VectorXd& ya, double Fa0, double t1,
                           const Eigen::VectorXd& yb, double Fb1) {
    const double h = t1 - t0, Ms = m_.mstar();
    const int n = n_;
    hq_.resize(n);
    hv_.resize(n);
    if (!m_.rigid()) {
      // v̇ = M⁻¹(f₀ − Kq − Cv + e₀F) at an end state.
      full_acceleration(ya, Fa0, ha_);
      full_acceleration(yb, Fb1, hb_);
    }
    auto g = [&](double tau) {
      const CamMotion c = cam_at(tau);
      if (!m_.rigid()) {
        const double x = (tau - t0) / h, x2 = x * x, x3 = x2 * x;
        const double h00 = 2 * x3 - 3 * x2 + 1, h10 = (x3 - 2 * x2 + x) * h;
        const double h01 = -2 * x3 + 3 * x2, h11 = (x3 - x2) * h;
        hq_ = h00 * ya.head(n) + h10 * ya.tail(n) + h01 * yb.head(n) + h11 * yb.tail(n);
        hv_ = h00 * ya.tail(n) + h10 * ha_ + h01 * yb.tail(n) + h11 * hb_;
      }
      hq_[0] = c.X;
      hv_[0] = c.Xdot;
      double F = (c.Xddot - m_.contact_acceleration(hq_.data(), hv_.data(), 0.0)) / Ms;
      if (!bilateral_ && F < 0.0) F = 0.0;
      // The samples also show the force between step ends (a peak inside a long step).
      sum_.max_contact_force = std::max(sum_.max_contact_force, F);
      designer_.sample_force(tau, drive_.theta(tau), F);
      return F * c.Xdot;
    };
    const double ga = Fa0 * cam_at(t0).Xdot, gb = Fb1 * cam_at(t1).Xdot;
    const double gm = g(0.5 * (t0 + t1));
    const double S = h / 6.0 * (ga + 4.0 * gm + gb);
    const double tol = 1e-8 * (std::abs(S) + h * std::max(std::abs(ga), std::abs(gb)));
    return adaptive_simpson(g, t0, t1, ga, gm, gb, S, tol, 12);
  }

  void run_method() override {
    StepRamp& law = ramp_;
    engine_->set_contact(&ramp_);
    const double Ms = m_.mstar();
    const int q = engine_->error_order();
    const bool eq17 = sc_.contact.error_variant == ErrorVariant::Eq17;
    const double e_rest = sc_.contact.restitution;
    double h = initial_step();
    double slope_prev = 0.0;  // dF/dt of the previous accepted ramp
    Eigen::VectorXd y1(2 * n_), yv(2 * n_), y_free(2 * n_), y_alt(2 * n_);
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      // Land on output times and t_end exactly.
      const double t_next = next_stop_time();
      const double h_planned = h;
      const double hs = fit_step(h, t_next);
      const bool lands = hs == t_next - t_;
      const double t1 = lands ? t_next : t_ + hs;  // land exactly, no round-off sliver
      const CamMotion cm = cam_at(t1);
      const double Ft = F_;
      const bool pt_active = Ft > 0.0;  // p̃ᵗ < 0
      law.t0 = t_;
      law.h = hs;
      law.F0 = Ft;
      double err = 0.0;
      double F1 = 0, Fv = 0, Fa = 0;
      try {
        // 1. displacement level
        const double b = 6.0 / (Ms * hs * hs);
        bool free_taken = false;
        bool have_alt = false, have_y1 = false;
        double F_y1 = 0.0, F_alt = 0.0;
        auto disp_err = [&](double F) {
          // Keep the previous iterate with a different force: with it the step map,
          // affine in the ramp's end force, is known without integrating (velocity level).
          if (have_y1 && F != F_y1) {
            y_alt.swap(y1);
            F_alt = F_y1;
            have_alt = true;
          }
          law.F1 = F;
          err = engine_->step(t_, y_, hs, y1);
          have_y1 = true;
          F_y1 = F;
          if (!free_taken && !contact_ && Ft == 0.0 && F == 0.0) {
            y_free = y1;  // free flight over the step (for the impact velocity)
            free_taken = true;
          }
          const double s = cm.X - y1[0];
          if (bilateral_) return s;
          return (F > 0.0 || s > 0.0) ? s : 0.0;
        };
        // At least one correction while in contact: stopping at the first iterate with
        // |v| < tol_u leaves the face penetrating by up to tol_u, and the next step's
        // correction must then remove that in one step with a force jump ∝ tol_u/Δt²,
        // which excites an elastic follower, fails the error test, and shrinks Δt until
        // it underflows (seen on case B1 with arkode-dirk). One Newton correction puts
        // s(t+Δt) at ≈ 0 (exactly, for a linear follower).
        F1 = iterate(Ft, b, tol_u_, sum_.level_u, disp_err, 1);
        // 2. step control
        if (err > 1.0) {
          ++sum_.rejected_steps;
          h = hs * std::max(0.2, 0.9 * std::pow(err, -1.0 / q));
          continue;
        }
        const double err_acc = err;
        // 3. velocity level (re-integrates with the ramp ending at F̂)
        // Approach speed ŝ⁻ at the impact instant: the free-flight gap crosses zero at
        // τ ≈ g₀/(g₀ − g₁)·Δt (linear in the gaps at t and, without contact, at t+Δt);
        // ŝ is interpolated there (O(Δt²)). Without a free-flight iterate: ŝ at t.
        double sdot_minus = cam_at(t_).Xdot - y_[n_];
        if (free_taken) {
          const double g0 = y_[0] - cam_at(t_).X, g1 = y_free[0] - cm.X;
          const double s1 = cm.Xdot - y_free[n_];
          if (g0 > 0.0 && g1 < 0.0) sdot_minus += (s1 - sdot_minus) * g0 / (g0 - g1);
        }
        const bool impact = !contact_ && F1 > 0.0;
        const double target = (impact && e_rest > 0.0) ? -e_rest * sdot_minus : 0.0;
        const double tol_v = sc_.contact.tol_v > 0 ? sc_.contact.tol_v : tol_u_ / hs;
        yv = y1;
        const bool p_active = F1 > 0.0;
        // The step map of a linear follower on a one-step engine (ERK; DIRK with its
        // linear stage solves) is affine in the ramp's end force: y(F) = y(F₁) +
        // (F − F₁)·(y(F₁) − y(F_alt))/(F₁ − F_alt), exact up to round-off. The velocity
        // level uses it instead of another integration (a third fewer integrations per
        // step) when the displacement level left two iterates with well-separated forces.
        // CVODE picks its internal steps from the solution, so it integrates.
        const bool affine = engine_->estimates_error() && have_alt && F_y1 == F1 &&
                            std::abs(F1 - F_alt) > 1e-6 * std::max(std::abs(F1), std::abs(F_alt));
        auto vel_err = [&](double F) {
          if (F == F1) {
            yv = y1;
          } else if (affine) {
            yv = y1 + ((F - F1) / (F1 - F_alt)) * (y1 - y_alt);
          } else {
            law.F1 = F;
            engine_->step(t_, y_, hs, yv);
          }
          const double sd = cm.Xdot - yv[n_] - target;
          if (bilateral_) return sd;
          const bool gate = eq17 ? (p_active || pt_active) : p_active;
          return (gate && (sd > 0.0 || F > 0.0)) ? sd : 0.0;
        };
        // Also one velocity correction at least: the displacement level alone maps a
        // velocity error ŝ at t to ≈ −2ŝ at t+Δt (a linear ramp that cancels the drift
        // over the step overshoots the velocity), so velocity errors below tol_v = tol_u/Δt
        // would double every step until corrected — an oscillation of the contact node
        // that shakes an elastic follower (seen on a preloaded bar on a still cam).
        Fv = iterate(F1, 2.0 / (Ms * hs), tol_v, sum_.level_v, vel_err, 1);
        // 4. acceleration level (no integration)
        const double tol_a = sc_.contact.tol_a > 0 ? sc_.contact.tol_a : tol_u_ / (hs * hs);
        const bool pv_active = Fv > 0.0;
        auto acc_err = [&](double F) {
          const double a = m_.contact_acceleration(y1.data(), yv.data() + n_, F);
          const double sdd = cm.Xddot - a;
          if (bilateral_) return sdd;
          const bool gate = eq17 ? (pv_active || pt_active) : pv_active;
          return (gate && (sdd > 0.0 || F > 0.0)) ? sdd : 0.0;
        };
        // The acceleration level is algebraic (ü₀ is affine in p̃ with slope M*), so one
        // correction is always made: it costs no integration and takes the contact force
        // from the velocity-level ramp end value to the force the equation of motion
        // demands at t+Δt. Further iterations follow the paper's tol_a = tol_u/Δt².
        Fa = iterate(Fv, 1.0 / Ms, tol_a, sum_.level_a, acc_err, 1);
        if (obs_) obs_->on_lee_step(t_, hs, Ft, Fv);  // the accepted velocity's ramp
        // accept
        const double Xdot_prev = cam_at(t_).Xdot;
        const double P_prev = dissipation_power();
        const double t_prev = t_;
        y_prev_ = y_;
        const bool was_contact = contact_;
        y_.head(n_) = y1.head(n_);
        y_.tail(n_) = yv.tail(n_);
        t_ = t1;
        F_ = Fa;
        const bool now_contact = bilateral_ || F_ > 0.0 || Fv > 0.0;
        if (!contact_ && now_contact && !bilateral_) {
          ++sum_.impacts;
          record_event(EventKind::Impact, sdot_minus);
          dissipated_ += 0.5 * (1.0 - e_rest * e_rest) * sdot_minus * sdot_minus / Ms;
        } else if (contact_ && !now_contact) {
          ++sum_.separations;
          record_event(EventKind::Separation, 0.0);
        }
        contact_ = now_contact;
        const bool held_throughout =
            bilateral_ || (!impact && was_contact && Ft > 0.0 && Fv > 0.0 && Fa > 0.0);
        const double dW = held_throughout
                              ? held_contact_work(t_prev, y_prev_, Ft, t_, y_, Fa)
                              : lee_step_work(hs, Ft, Fv, Fa, Xdot_prev, cm.Xdot);
        after_step(hs, dW, P_prev);
        // next step size
        if (engine_->estimates_error()) {
          const double fac = err_acc > 0 ? 0.9 * std::pow(err_acc, -1.0 / q) : 5.0;
          h = hs * std::min(5.0, std::max(0.2, fac));
        } else {
          // The engine controls its own error inside the step (CVODE). What remains is
          // the piecewise-linear contact force: its deviation from the previous slope,
          // d ≈ F″h², moves u₀ by ≈ M* d h²/12 ∝ h⁴; keep that within the tolerance.
          const double slope = (F1 - Ft) / hs;
          const double d = std::abs(slope - slope_prev) * hs;
          const double du = Ms * d * hs * hs / 12.0;
          const double e = du / (sc_.solver.rtol * std::abs(y_[0]) + sc_.solver.atol);
          const double fac = e > 0 ? 0.9 * std::pow(e, -0.25) : 5.0;
          h = hs * std::min(5.0, std::max(0.2, fac));
          slope_prev = slope;
        }
        // A step shortened to land on an output time does not shrink the proposal.
        if (hs < h_planned) h = std::max(h, h_planned);
      } catch (const IterationFailure&) {
        ++sum_.rejected_steps;
        h = 0.5 * hs;
      }
    }
  }

};

}  // namespace

std::unique_ptr<RunContext> make_lee_classic(const Scene& sc, std::shared_ptr<const FollowerModel> model,
                                      Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<LeeClassic>(sc, std::move(model), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
