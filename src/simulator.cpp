// camdyn — the simulator: one step loop, contact methods plugged in.
//
//   scene → FollowerModel (only the effects asked for) → Engine (SUNDIALS) + contact
//   method → HistoryRow stream (Observer) + Summary.
//
// Lee's method (METHOD.md §3–4), one step t → t+Δt from the accepted state (q, v, F):
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
//
// Penalty (Cardona–Géradin): F = max(0, k_p s + c_p ŝ) while s > 0 (or Hunt–Crossley
// k_p sⁿ(1 + c_p ŝ)) inside the right-hand side; the engine steps natively.
#include "camdyn/simulator.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <ctime>
#include <sstream>

#include "camdyn/cam.hpp"
#include "designer_stats.hpp"
#include "engine.hpp"

namespace camdyn {

const std::vector<std::string>& history_columns() {
  static const std::vector<std::string> cols{"t",       "theta",     "u_c",      "v_c",
                                             "a_c",     "contact_force", "gap", "in_contact",
                                             "kinetic", "potential", "work_cam", "dissipated"};
  return cols;
}

namespace {

std::string fmt(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

class StepFailure : public std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Clock {
  std::clock_t c0 = std::clock();
  std::chrono::steady_clock::time_point w0 = std::chrono::steady_clock::now();
  double cpu() const { return double(std::clock() - c0) / CLOCKS_PER_SEC; }
  double wall() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  }
};

// The common run machinery: output times, statistics, energy bookkeeping, rows.
class Runner {
 public:
  Runner(const Scene& sc, std::shared_ptr<const FollowerModel> model, Observer* obs,
         const std::atomic<bool>* stop)
      : sc_(sc), model_(std::move(model)), m_(*model_), cam_(sc.cam), drive_(sc.cam),
        obs_(obs), stop_(stop), n_(m_.n()), designer_(sc, cam_.lift()) {
    engine_ = make_engine(model_, sc_);
    sum_.scene = sc.title;
    sum_.integrator = to_string(sc.solver.integrator);
    sum_.contact_model = to_string(sc.contact.model);
    sum_.model = m_.description();
    sum_.min_gap = INFINITY;
    bilateral_ = !sc.contact.separation || sc.contact.model == ContactModel::Holonomic;
    tol_u_ = sc.contact.tol_u;
  }

  Summary run() {
    Clock clock;
    // Initial state: q(0) from the model; node 0 at the cam's velocity if touching.
    const double th0 = drive_.theta(0.0);
    const CamMotion cm0 = cam_.motion(th0, drive_.omega(0.0), drive_.omega_dot(0.0));
    y_ = Eigen::VectorXd::Zero(2 * n_);
    y_.head(n_) = m_.initial_displacement();
    const bool touching = sc_.contact.initial_gap == 0.0;
    if (touching) y_[n_] = cm0.Xdot;
    t_ = 0.0;
    contact_ = touching;
    // Initial contact force from the acceleration level (eq. 16 at t = 0).
    F_ = 0.0;
    if (touching) {
      const double a_free = m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0);
      F_ = (cm0.Xddot - a_free) / m_.mstar();
      if (!bilateral_ && F_ < 0.0) F_ = 0.0;
    }
    if (sc_.contact.model == ContactModel::Penalty) {
      if (touching && F_ > 0.0) y_.head(n_).array() -= penalty_start_penetration(cm0.Xddot);
      // ŝ = 0 at t = 0: the force the penalty law gives there (also in the t = 0 row).
      setup_penalty_law();
      F_ = engine_->law().force(0.0, y_[0], y_[n_]);
    }
    V0_ = potential();
    E0_ = m_.kinetic_energy(y_.data() + n_) + V0_;
    emit_row();
    designer_step(cm0.X);
    next_out_ = 1;
    try {
      if (sc_.contact.model == ContactModel::Penalty)
        run_native();
      else if (sc_.contact.model == ContactModel::Event ||
               sc_.contact.model == ContactModel::Holonomic)
        run_event();
      else
        run_lee();
      sum_.finished = true;
      sum_.message = "finished";
    } catch (const std::exception& e) {
      sum_.finished = false;
      sum_.message = "at t = " + fmt(t_) + ": " + e.what();
      if (last_row_t_ < t_) emit_row();  // keep the last accepted state
    }
    sum_.t_end = t_;
    sum_.rhs_evals += engine_->stats().rhs_evals;
    sum_.lin_setups += engine_->stats().lin_setups;
    sum_.lin_analyses += engine_->stats().lin_analyses;
    sum_.cpu_seconds = clock.cpu();
    sum_.wall_seconds = clock.wall();
    if (!std::isfinite(sum_.min_gap)) sum_.min_gap = 0.0;
    sum_.energy_residual = std::abs(energy_residual());
    designer_.finish(sum_);
    return sum_;
  }

 private:
  double out_dt() const { return sc_.run.output_dt; }
  double next_output_time() const {
    return out_dt() > 0 ? std::min(sc_.run.t_end, double(next_out_) * out_dt()) : sc_.run.t_end;
  }
  CamMotion cam_at(double t) const {
    return cam_.motion(drive_.theta(t), drive_.omega(t), drive_.omega_dot(t));
  }
  double energy_residual() const {
    const double E = m_.kinetic_energy(y_.data() + n_) + potential();
    return work_ - (E - E0_) - dissipated_;
  }
  // Energy bookkeeping of the history columns (all methods):
  //   work_cam   W = ∫ F Ẋ_C dt         the cam's work on the follower through the contact
  //   kinetic    T = ½ vᵀ M v
  //   potential  V = ½ qᵀ K q − f₀ᵀ q (strain + return spring) + V_p(s) (penalty spring)
  //   dissipated D = ∫ vᵀ C v dt + ∫ (F − F_el) ŝ dt (penalty damper) + impact losses
  // and W = ΔT + ΔV + D is the balance checked by the stability suite.
  double potential() const {
    return m_.potential_energy(y_.data()) + engine_->law().stored_energy(t_, y_[0]);
  }
  // Power dissipated at the current state: damping, plus the penalty damper's
  // (F − F_el)·ŝ (zero for the other methods, whose contact losses are impacts).
  double dissipation_power() const {
    double P = m_.damping_power(y_.data() + n_);
    const ContactLaw& law = engine_->law();
    if (law.kind == ContactLaw::Kind::Penalty)
      P += (F_ - law.elastic_force(t_, y_[0])) * (cam_at(t_).Xdot - y_[n_]);
    return P;
  }

  void emit_row() {
    HistoryRow r;
    r.t = t_;
    r.theta = drive_.theta(t_);
    const CamMotion cm = cam_at(t_);
    r.u_c = y_[0];
    r.v_c = y_[n_];
    r.a_c = m_.contact_acceleration(y_.data(), y_.data() + n_, F_);
    r.contact_force = F_;
    r.gap = y_[0] - cm.X;
    r.in_contact = contact_ ? 1 : 0;
    r.kinetic = m_.kinetic_energy(y_.data() + n_);
    r.potential = potential() - V0_;
    r.work_cam = work_;
    r.dissipated = dissipated_;
    last_row_t_ = t_;
    if (obs_) obs_->on_row(r);
  }

  // t_event: the located event time when the caller knows it (NaN: the current time t_);
  // the event's cam angle is taken there.
  void record_event(const char* kind, double v, double t_event = NAN) {
    const double te = std::isnan(t_event) ? t_ : t_event;
    ContactEvent e{te, kind, v, drive_.theta(te)};
    designer_.event(e);
    sum_.events.push_back(e);
    if (obs_) obs_->on_event(e);
  }

  // Work of the contact force over the step just taken by the trapezoid rule on F·Ẋ_C
  // (state already updated to the step's end).
  double trapezoid_work(double h, double F_prev, double Xdot_prev) const {
    return 0.5 * h * (F_prev * Xdot_prev + F_ * cam_at(t_).Xdot);
  }

  // Statistics and output after an accepted step (state already updated); dW is the
  // work the contact force did over the step.
  // P_end: dissipated power at the end of the step if it differs from the current
  // state's (the pre-impact state of a free flight ended by an impact); NaN: the state's.
  void after_step(double h, double dW, double P_prev, double P_end = NAN) {
    ++sum_.steps;
    const CamMotion cm = cam_at(t_);
    const double P = std::isnan(P_end) ? dissipation_power() : P_end;
    work_ += dW;
    dissipated_ += 0.5 * h * (P_prev + P);
    const double gap = y_[0] - cm.X;
    sum_.max_contact_force = std::max(sum_.max_contact_force, F_);
    sum_.min_gap = std::min(sum_.min_gap, gap);
    sum_.max_penetration = std::max(sum_.max_penetration, -gap);
    designer_step(cm.X);
    if (bilateral_ && F_ < 0.0 && sum_.first_tensile_time < 0) {
      sum_.first_tensile_time = t_;
      record_event("tensile", 0.0);
    }
    if (out_dt() <= 0.0) {
      emit_row();
    } else {
      while (next_out_ * out_dt() <= t_ * (1 + 1e-12) + 1e-300 && next_out_ * out_dt() <= sc_.run.t_end * (1 + 1e-12)) {
        ++next_out_;
        emit_row();
      }
      if (t_ >= sc_.run.t_end && last_row_t_ < t_) emit_row();
    }
    if (stop_ && stop_->load()) throw StepFailure("interrupted (SIGINT)");
    if (sum_.steps + sum_.rejected_steps > sc_.run.max_steps)
      throw StepFailure("run.max_steps = " + std::to_string(sc_.run.max_steps) + " reached");
    if (!y_.allFinite() || !std::isfinite(F_)) throw StepFailure("non-finite state");
    if (obs_ && (sum_.steps & 255) == 0) {
      const double w = progress_clock_.wall();
      if (w - last_progress_ > 0.2) {
        last_progress_ = w;
        obs_->on_progress(t_, sc_.run.t_end, sum_.steps);
      }
    }
  }

  // Designer results (designer_stats.hpp) at an accepted state: the step end, and the
  // contact force while in contact.
  // `X_C`: the cam's X at t_ (the caller has it).
  void designer_step(double X_C) {
    const double th = drive_.theta(t_);
    designer_.step(t_, th, y_[0], y_[n_], m_.contact_acceleration(y_.data(), y_.data() + n_, F_),
                   y_[0] - X_C);
    if (contact_) designer_.sample_force(t_, th, F_);
  }

  double initial_step() const {
    if (sc_.solver.initial_step > 0) return sc_.solver.initial_step;
    double h = std::min(1e-4, sc_.run.t_end / 100.0);
    return h;
  }

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
        throw StepFailure("contact iteration did not converge");
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
      auto acceleration = [&](const Eigen::VectorXd& y, double F, Eigen::VectorXd& a) {
        a.resize(n);
        rbuf_.resize(n);
        m_.internal_force(y.data(), y.data() + n, rbuf_.data());
        rbuf_[0] += F;
        m_.solve_mass(rbuf_.data(), a.data());
      };
      acceleration(ya, Fa0, ha_);
      acceleration(yb, Fb1, hb_);
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
  template <class G>
  static double adaptive_simpson(G& g, double a, double b, double fa, double fm, double fb,
                                 double S, double tol, int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = g(lm), frm = g(rm);
    const double Sl = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const double Sr = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const double S2 = Sl + Sr;
    if (depth <= 0 || std::abs(S2 - S) <= 15.0 * tol) return S2 + (S2 - S) / 15.0;
    return adaptive_simpson(g, a, m, fa, flm, fm, Sl, 0.5 * tol, depth - 1) +
           adaptive_simpson(g, m, b, fm, frm, fb, Sr, 0.5 * tol, depth - 1);
  }

  void run_lee() {
    ContactLaw& law = engine_->law();
    law.kind = ContactLaw::Kind::Ramp;
    const double Ms = m_.mstar();
    const int q = engine_->error_order();
    const bool eq17 = sc_.contact.error_variant == ErrorVariant::Eq17;
    const double e_rest = sc_.contact.restitution;
    double h = initial_step();
    double slope_prev = 0.0;  // dF/dt of the previous accepted ramp
    Eigen::VectorXd y1(2 * n_), yv(2 * n_), y_free(2 * n_), y_alt(2 * n_);
    const double hmin_rel = 1e-14;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      // Land on output times and t_end exactly.
      const double t_next = next_output_time();
      const double h_planned = h;
      double hs = std::min(h, t_next - t_);
      if (sc_.solver.max_step > 0) hs = std::min(hs, sc_.solver.max_step);
      // No slivers. A remainder below 1e-6 of the step is absorbed into it; a remainder
      // between one and two steps is split into two equal steps. A sliver step (seen:
      // 1.6e-10 s left before an output time after a 3e-6 s step, B1 at t = 44 s) cannot
      // correct even round-off in the gap without a force ∝ gap/Δt², which fails the
      // error test, shrinks Δt, needs a still larger force — and Δt underflows.
      {
        const double rem = t_next - t_;
        if (rem - hs < 1e-6 * hs)
          hs = rem;
        else if (rem < 2.0 * hs)
          hs = 0.5 * rem;
      }
      if (hs <= hmin_rel * std::max(1.0, std::abs(t_)))
        throw StepFailure("step size underflow (h = " + fmt(hs) + ")");
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
          record_event("impact", sdot_minus);
          dissipated_ += 0.5 * (1.0 - e_rest * e_rest) * sdot_minus * sdot_minus / Ms;
        } else if (contact_ && !now_contact) {
          ++sum_.separations;
          record_event("separation", 0.0);
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
      } catch (const StepFailure& e) {
        if (std::string(e.what()) != "contact iteration did not converge") throw;
        ++sum_.rejected_steps;
        h = 0.5 * hs;
      }
    }
  }

  // ------------------------------------------------------------ native stepping ----
  // The fair start of the penalty baseline: penalty contact starts in its own equilibrium. The
  // follower is shifted rigidly into the cam by the penetration s₀ (returned) at
  // which the penalty force carries what the contact must carry at t = 0, i.e. the
  // force F_req(s₀) = (Ẍ_C − a_free(q − s₀))/M* that gives the contact face the cam's
  // acceleration. F_req is affine in s₀ (the return spring relaxes by s₀; rigid:
  // F_req = mẌ_C + kδ₀ − k s₀). Linear law: k_p s₀ = F_req(s₀); Hunt–Crossley:
  // k_p s₀ⁿ = F_req(s₀) (Newton; ŝ = 0 at t = 0, so c_p plays no part). So
  // F(0) = F₀·k_p/(k_p + k) for a rigid follower, → F₀ as k_p grows. Without it the
  // penalty run starts with no force against the preload.
  // @pre F_ = the contact force the acceleration level demands at t = 0 (> 0).
  double penalty_start_penetration(double Xddot0) const {
    Eigen::VectorXd q1 = y_.head(n_).array() - 1.0;  // a unit shift (the model is affine)
    const double a1 = m_.contact_acceleration(q1.data(), y_.data() + n_, 0.0);
    const double slope = (Xddot0 - a1) / m_.mstar() - F_;  // dF_req/ds₀ (< 0)
    const double kp = sc_.contact.penalty_stiffness, n = sc_.contact.penalty_exponent;
    if (sc_.contact.penalty_law == PenaltyLaw::Linear) return F_ / (kp - slope);
    double s0 = std::pow(F_ / kp, 1.0 / n);  // right of the root: Newton falls monotonically
    for (int i = 0; i < 100; ++i) {
      const double g = kp * std::pow(s0, n) - F_ - slope * s0;
      const double ds = g / (n * kp * std::pow(s0, n - 1.0) - slope);
      s0 -= ds;
      if (std::abs(ds) <= 1e-15 * s0) break;
    }
    return s0;
  }

  void setup_penalty_law() {
    ContactLaw& law = engine_->law();
    law.kind = ContactLaw::Kind::Penalty;
    law.cam = &cam_;
    law.drive = &drive_;
    law.law = sc_.contact.penalty_law;
    law.kp = sc_.contact.penalty_stiffness;
    law.cp = sc_.contact.penalty_damping;
    law.exponent = sc_.contact.penalty_exponent;
  }

  void run_native() {
    ContactLaw& law = engine_->law();
    engine_->reinit(t_, y_);
    Eigen::VectorXd y1(2 * n_);
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_output_time();
      const double Ft = F_;
      const double Xdot_prev = cam_at(t_).Xdot;
      const double P_prev = dissipation_power();
      const double t1 = engine_->advance(tout, y1);
      const double h = t1 - t_;
      t_ = t1;
      y_ = y1;
      F_ = law.force(t_, y_[0], y_[n_]);
      const bool now_contact = F_ > 0.0;
      if (!contact_ && now_contact) {
        ++sum_.impacts;
        record_event("impact", cam_at(t_).Xdot - y_[n_]);
      } else if (contact_ && !now_contact) {
        ++sum_.separations;
        record_event("separation", 0.0);
      }
      contact_ = now_contact;
      after_step(h, trapezoid_work(h, Ft, Xdot_prev), P_prev);
    }
  }

  // ------------------------------------------------------------ event-driven -------
  // Contact phase: node 0 moves with the cam (u₀ = X_C, u̇₀ = Ẋ_C, ü₀ = Ẍ_C); the other
  // nodes obey the held bar M_rr q̈_r = f_r − K_rr q_r − C_rr v_r − (K₁₀X_C + C₁₀Ẋ_C + M₁₀Ẍ_C)e₁,
  // and the reaction is F = M₀₀Ẍ_C + M₀₁q̈₁ − (f₀ − K q − C v)₀. Free phase: F = 0.
  // Switches: the reaction reaching zero (decreasing) → separation; the gap closing
  // (decreasing) → impact, a Newton impulse P = (1 + e) ŝ⁻ / M* on node 0, Δv = M⁻¹e₀ P,
  // then contact if the reaction is compressive (plastic), else free flight (bounce).
  // Roots are located by SUNDIALS rootfinding (rigid contact phase: bisection on the
  // closed-form reaction) to round-off in time.
  // "holonomic" is the contact phase alone, reporting where the reaction turns tensile.
  double reaction_rigid(double t) const {
    const CamMotion c = cam_at(t);
    return m_.m_rigid() * c.Xddot - (m_.f0()[0] - m_.k_rigid() * c.X - m_.c_rigid() * c.Xdot);
  }
  double reaction_held(double t, const double* yr) {
    const FollowerModel& h = *held_;
    const int r = h.n();
    const CamMotion c = cam_at(t);
    held_law_->kind = ContactLaw::Kind::Prescribed;
    // q̈_r from the held model's equation of motion.
    rbuf_.resize(r);
    h.internal_force(yr, yr + r, rbuf_.data());
    rbuf_[0] += held_law_->force(t, 0, 0);
    abuf_.resize(r);
    h.solve_mass(rbuf_.data(), abuf_.data());
    const double r0 = m_.f0()[0] - m_.k00() * c.X - m_.k10() * yr[0] - m_.c00() * c.Xdot - m_.c10() * yr[r];
    return m_.m00() * c.Xddot + m_.m10() * abuf_[0] - r0;
  }
  void full_from_held(double t, const Eigen::VectorXd& yr) {
    const CamMotion c = cam_at(t);
    const int r = n_ - 1;
    y_[0] = c.X;
    y_[n_] = c.Xdot;
    y_.segment(1, r) = yr.head(r);
    y_.segment(n_ + 1, r) = yr.tail(r);
  }
  Eigen::VectorXd held_from_full() const {
    const int r = n_ - 1;
    Eigen::VectorXd yr(2 * r);
    yr.head(r) = y_.segment(1, r);
    yr.tail(r) = y_.segment(n_ + 1, r);
    return yr;
  }

  void run_event() {
    const bool holonomic = sc_.contact.model == ContactModel::Holonomic;
    const bool rigid = m_.rigid();
    const double Ms = m_.mstar(), e_rest = sc_.contact.restitution;
    ContactLaw& law = engine_->law();
    law.kind = ContactLaw::Kind::None;
    std::unique_ptr<Engine> held_engine;
    if (!rigid) {
      held_ = m_.held_model();
      held_engine = make_engine(held_, sc_);
      held_law_ = &held_engine->law();
      held_law_->kind = ContactLaw::Kind::Prescribed;
      held_law_->cam = &cam_;
      held_law_->drive = &drive_;
      held_law_->k10 = m_.k10();
      held_law_->c10 = m_.c10();
      held_law_->m10 = m_.m10();
      if (!holonomic)
        held_engine->set_root([this](double t, const double* yr) { return reaction_held(t, yr); }, -1);
    }
    // Free phase: the gap closing, g = gap + δ. Right after a switch the state sits on
    // the cam (gap = 0 exactly); the offset δ (a few ulps of X) keeps SUNDIALS from
    // stopping with "root at and very near t" and from re-detecting the event just
    // handled, at the price of a penetration of δ when the root is reported.
    auto gap_root = [this](double t, const double* y) {
      const double X = cam_at(t).X;
      return y[0] - X + 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(X));
    };
    engine_->set_root(gap_root, -1);
    auto start_free = [&]() { engine_->reinit(t_, y_); };
    // Initial phase.
    bool in_contact = holonomic || (contact_ && F_ > 0.0);
    contact_ = in_contact;
    if (!in_contact) F_ = 0.0;
    Eigen::VectorXd yr, y1;
    if (in_contact && !rigid) held_engine->reinit(t_, held_from_full());
    if (!in_contact) engine_->reinit(t_, y_);
    const double dt_scan = std::min(1e-4, sc_.run.t_end / 100.0);
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_output_time();
      const double Ft = F_, Xdot_prev = cam_at(t_).Xdot, P_prev = dissipation_power();
      const double t_prev = t_;
      bool separation = false, impact = false;
      double dW_override = NAN, P_end = NAN;
      if (in_contact) {
        if (rigid) {
          double t1 = std::min(tout, t_ + dt_scan);
          if (!holonomic && reaction_rigid(t1) < 0.0 && reaction_rigid(t_) >= 0.0) {
            double a = t_, b = t1;  // bisection to round-off on the closed-form reaction
            for (int i = 0; i < 200 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++i) {
              const double mid = 0.5 * (a + b);
              (reaction_rigid(mid) >= 0.0 ? a : b) = mid;
            }
            t1 = b;
            separation = true;
          }
          t_ = t1;
          const CamMotion c = cam_at(t_);
          y_[0] = c.X;
          y_[1] = c.Xdot;
          F_ = separation ? 0.0 : reaction_rigid(t_);
          // The reaction is known in closed form: Simpson's rule on F·Ẋ_C over the
          // step (the trapezoid's O(h²) error reached 3.5e-3 of the work on a fast
          // speed ramp with 1e-4 steps).
          const double tm = 0.5 * (t_prev + t_);
          designer_.sample_force(tm, drive_.theta(tm), reaction_rigid(tm));
          dW_override = (t_ - t_prev) / 6.0 *
                        (Ft * Xdot_prev + 4.0 * reaction_rigid(tm) * cam_at(tm).Xdot +
                         reaction_rigid(t_) * cam_at(t_).Xdot);
          ++sum_.steps;
        } else {
          t_ = held_engine->advance(tout, y1);
          full_from_held(t_, y1);
          separation = held_engine->hit_root();
          F_ = separation ? 0.0 : reaction_held(t_, y1.data());
        }
        if (separation) {
          in_contact = false;
          start_free();
        }
      } else {
        t_ = engine_->advance(tout, y1);
        y_ = y1;
        F_ = 0.0;
        // Free flight: no contact work over the step (an impact at its end books its
        // impulse's work P·Ẋ_C itself), damping power at the pre-impact state.
        dW_override = 0.0;
        P_end = dissipation_power();
        if (engine_->hit_root()) {
          const CamMotion c = cam_at(t_);
          const double approach = c.Xdot - y_[n_];  // ŝ⁻ > 0: closing
          y_[0] = c.X;                               // the root is located to round-off
          if (approach > 0.0) {
            impact = true;
            const double P = (1.0 + e_rest) * approach / Ms;
            Eigen::VectorXd e0 = Eigen::VectorXd::Zero(n_), dv(n_);
            e0[0] = P;
            m_.solve_mass(e0.data(), dv.data());
            y_.tail(n_) += dv;
            work_ += P * c.Xdot;  // the cam's impulse does work P·Ẋ_C
            dissipated_ += 0.5 * (1.0 - e_rest * e_rest) * approach * approach / Ms;
            // Chattering guard: a bounce slower than this sticks (plastic).
            // (bounces of a coefficient e < 1 on a still surface form a Zeno sequence;
            // below 1e-6 of the first impact speed the follower is taken to rest on it)
            // The root offset δ itself lets the follower gain √(2|s̈|δ) before each root
            // is reported; bounces slower than a few times that are round-off, not motion.
            if (v_impact_ref_ == 0.0) v_impact_ref_ = approach;
            const double rel_acc = std::abs(c.Xddot - m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0));
            const double delta = 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(c.X));
            const double v_stick = std::max(1e-6 * std::max(v_impact_ref_, 1e-3), 8.0 * std::sqrt(2.0 * rel_acc * delta));
            if (e_rest == 0.0 || (1.0 + e_rest) * approach < v_stick) {
              y_[n_] = c.Xdot;
              const double Fr = rigid ? reaction_rigid(t_) : reaction_held(t_, held_from_full().data());
              if (Fr > 0.0) {
                in_contact = true;
                F_ = Fr;
              }
            }
          }
          if (in_contact && !rigid) held_engine->reinit(t_, held_from_full());
          if (!in_contact) start_free();
          if (impact) {
            ++sum_.impacts;
            record_event("impact", approach);
          }
        }
      }
      if (separation) {
        ++sum_.separations;
        record_event("separation", 0.0);
      }
      contact_ = in_contact;
      const double dW = std::isnan(dW_override) ? trapezoid_work(t_ - t_prev, Ft, Xdot_prev) : dW_override;
      after_step(t_ - t_prev, dW, P_prev, P_end);
    }
    sum_.rhs_evals += held_engine ? held_engine->stats().rhs_evals : 0;
  }

  std::shared_ptr<const FollowerModel> held_;
  ContactLaw* held_law_ = nullptr;
  double v_impact_ref_ = 0.0;
  Eigen::VectorXd rbuf_, abuf_;
  Eigen::VectorXd y_prev_, hq_, hv_, ha_, hb_;  // Lee's contact-work quadrature

  const Scene& sc_;
  std::shared_ptr<const FollowerModel> model_;
  const FollowerModel& m_;
  Cam cam_;
  CamDrive drive_;
  Observer* obs_;
  const std::atomic<bool>* stop_;
  int n_;
  std::unique_ptr<Engine> engine_;
  detail::DesignerStats designer_;
  Summary sum_;
  bool bilateral_ = false, contact_ = false;
  double tol_u_ = 1e-8;
  double t_ = 0, F_ = 0, E0_ = 0, V0_ = 0, work_ = 0, dissipated_ = 0, last_row_t_ = -1;
  long next_out_ = 1;
  Eigen::VectorXd y_;
  Clock progress_clock_;
  double last_progress_ = 0;
};

}  // namespace

Simulator::Simulator(Scene scene) : scene_(std::move(scene)) {
  resolve_defaults(scene_);
  validate(scene_);
  model_ = build_model(scene_);
}

Simulator::~Simulator() = default;

Summary Simulator::run(Observer* observer, const std::atomic<bool>* stop) {
  Runner r(scene_, model_, observer, stop);
  return r.run();
}

namespace {
struct Collector : Observer {
  std::vector<HistoryRow>* rows;
  void on_row(const HistoryRow& r) override { rows->push_back(r); }
};
}  // namespace

RunResult simulate(const Scene& scene) {
  RunResult res;
  Collector c;
  c.rows = &res.rows;
  Simulator sim(scene);
  res.summary = sim.run(&c);
  return res;
}

std::string Summary::BriefReport() const {
  std::ostringstream o;
  o << "camdyn: " << (finished ? "finished" : "NOT finished") << " — " << scene << " — "
    << contact_model << " on " << integrator << ": t = " << fmt(t_end) << ", " << steps
    << " steps (" << rejected_steps << " rejected), " << rhs_evals << " rhs evals, "
    << separations << " separations, " << impacts << " impacts, max force "
    << fmt(max_contact_force) << ", cpu " << fmt(cpu_seconds) << " s";
  if (!finished) o << " — " << message;
  return o.str();
}

std::string Summary::FullReport() const {
  std::ostringstream o;
  auto lv = [&](const char* name, const LevelStats& s) {
    o << "  " << name << ": mean " << fmt(s.mean()) << ", max " << s.max << ", total " << s.total
      << "\n";
  };
  o << "camdyn run summary\n"
    << "  scene:              " << scene << "\n"
    << "  model:              " << model.ToString() << "\n"
    << "  contact model:      " << contact_model << "\n"
    << "  integrator:         " << integrator << "\n"
    << "  finished:           " << (finished ? "yes" : "no") << " (" << message << ")\n"
    << "  t reached:          " << fmt(t_end) << "\n"
    << "  steps:              " << steps << " accepted, " << rejected_steps << " rejected\n"
    << "  rhs evaluations:    " << rhs_evals << "\n"
    << "  contact iterations: " << contact_iterations << " (" << iteration_failures
    << " iteration failures)\n";
  lv("displacement level", level_u);
  lv("velocity level    ", level_v);
  lv("acceleration level", level_a);
  o << "  separations:        " << separations << "\n"
    << "  impacts:            " << impacts << "\n"
    << "  max contact force:  " << fmt(max_contact_force) << "\n"
    << "  min gap:            " << fmt(min_gap) << "\n"
    << "  max penetration:    " << fmt(max_penetration) << "\n";
  if (first_tensile_time >= 0)
    o << "  constraint force first tensile at t = " << fmt(first_tensile_time) << "\n";
  o << "  energy residual:    " << fmt(energy_residual) << "\n"
    << "  cpu / wall:         " << fmt(cpu_seconds) << " s / " << fmt(wall_seconds) << " s\n";
  return o.str();
}

}  // namespace camdyn
