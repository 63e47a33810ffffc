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
#include "ida_engine.hpp"

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
/// A contact iteration that did not converge: recoverable, the step is retried with Δt/2.
class IterationFailure : public StepFailure {
 public:
  IterationFailure() : StepFailure("contact iteration did not converge") {}
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
      else if (sc_.solver.integrator == Integrator::Ida)
        run_ida_holonomic();  // validated: contact.model = "holonomic"
      else if (sc_.contact.model == ContactModel::Event ||
               sc_.contact.model == ContactModel::Holonomic)
        run_event();
      else if (sc_.contact.lee_step == LeeStepKind::Classic)
        run_lee();
      else
        run_lee_located();
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

  void emit_row() { emit_row_at(t_, y_, F_, contact_, potential(), work_, dissipated_); }
  void emit_row_at(double t, const Eigen::VectorXd& y, double F, bool contact, double V,
                   double W, double D, const CamMotion* c = nullptr) {
    HistoryRow r;
    r.t = t;
    r.theta = drive_.theta(t);
    const CamMotion cm = c ? *c : cam_at(t);
    r.u_c = y[0];
    r.v_c = y[n_];
    r.a_c = m_.contact_acceleration(y.data(), y.data() + n_, F);
    r.contact_force = F;
    r.gap = y[0] - cm.X;
    r.in_contact = contact ? 1 : 0;
    r.kinetic = m_.kinetic_energy(y.data() + n_);
    r.potential = V - V0_;
    r.work_cam = W;
    r.dissipated = D;
    last_row_t_ = t;
    if (obs_) obs_->on_row(r);
  }

  // impulse: the impact impulse applied at the instant (0: none); t_event: the event time
  // when it is not the current time t_ (NaN); the event's cam angle is taken there.
  void record_event(const char* kind, double v, double impulse = 0.0, double t_event = NAN) {
    const double te = std::isnan(t_event) ? t_ : t_event;
    ContactEvent e{te, kind, v, drive_.theta(te), impulse};
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
        const double to = double(next_out_) * out_dt();
        ++next_out_;
        if (dense_ && to < t_ && to > dense_->t0)
          dense_row(*dense_, to);  // inside the accepted step (dense output)
        else
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
      } catch (const IterationFailure&) {
        ++sum_.rejected_steps;
        h = 0.5 * hs;
      }
    }
  }

  // ------------------------------------------------- Lee's method: the located step ----
  // One step t → t+h from the accepted state (q, v, F), F the acceleration level's force
  // at t (docs: "Lee's step, located").
  //
  // Contact step. The force over the step has two free parameters,
  //   F(τ) = F + (F₁ − F)x + F_c·4x(1 − x),   x = (τ − t)/h,
  // and the displacement and velocity levels are solved together: s = X_C − u₀ = 0 and
  // ŝ = Ẋ_C − u̇₀ = 0 at t+h. For a linear follower on a one-step engine the end state is
  // affine in (F₁, F_c), y = y_a + D₁ΔF₁ + D_c ΔF_c (also the local error estimate), and the
  // responses D depend on h only (the follower is time-invariant and the shape is fixed in
  // x): the 2 × 2 Newton system is Lee's iteration with its exact matrix of constants and
  // converges in one correction; D is computed by two extra integrations when h changes
  // and reused while h stays (CVODE: re-integrated and iterated to tol_u, tol_v). The
  // accepted q and v are one trajectory of one force history. The acceleration level
  // gives the force the equation of motion demands at t+h,
  //   F̃ = (Ẍ_C − ü₀,free(q, v)) / M*,
  // which starts the next step (F continuous). F̃ − F₁ is the acceleration-level error
  // of the shape: the error test includes it as a force error against
  //   rtol·|F| + 2 tol_u / (M* h²)   (the force whose impulse over h moves M* by tol_u).
  // While node 0 rides the cam its force is known pointwise,
  //   F(τ) = (Ẍ_C(τ) − ü₀,free(q(τ), v(τ))) / M*,  node 0 on the cam, other nodes by
  //   cubic Hermite interpolation of the step's end states (exact for a rigid follower);
  // where it reaches zero inside the step (a sign change, or a sampled minimum below zero
  // — grazing), the step is retaken to land there and the follower separates.
  //
  // Free step. F = 0; one integration with the engine's error test. The gap
  // g = u₀ − X_C on the quintic Hermite of node 0 (u, u̇, ü at both ends) is scanned for a
  // sign change or a minimum below zero; the step is retaken to land on the first root.
  // There the impact is resolved at the instant: the velocity level with a zero-length
  // step is a Newton impulse P = (1 + e)ŝ⁻/M* on node 0 (Δv = M⁻¹e₀P), and the contact
  // holds if the acceleration level's force F̃ is compressive.
  //
  // Output rows inside accepted steps are interpolated (dense output) unless
  // run.land_on_output is set.
  struct StepData {
    double t0 = 0, t1 = 0;
    bool held = false;                 // node 0 on the cam throughout
    Eigen::VectorXd y0, y1, a0, a1;    // end states and full accelerations
    double F0 = 0, F1 = 0;             // forces at the ends
    double W0 = 0, D0 = 0, P0 = 0;     // work, dissipation, damping power at t0
    double t_row = 0, W_row = 0, g_row = 0;  // dense rows: last row's time, work, F·Ẋ_C
  };
  StepData* dense_ = nullptr;
  StepData sd_;
  // Responses of the end state and of the local error estimate to F₁ and F_c (per unit).
  struct ShapeResponse {
    double h = -1;
    Eigen::VectorXd D1, Dc, E1, Ec;
  };
  // A few step sizes' responses: the step-size controller proposes sizes on a geometric
  // grid 2^(k/8), so that a run revisits the same few sizes and the responses (two
  // integrations) are reused instead of recomputed whenever the size changes.
  static constexpr int kResponses = 12;
  ShapeResponse resp_cache_[kResponses];
  int resp_next_ = 0;
  ShapeResponse& response_slot(double hs, bool* hit) {
    for (ShapeResponse& r : resp_cache_)
      if (r.h == hs) {
        *hit = true;
        return r;
      }
    *hit = false;
    ShapeResponse& r = resp_cache_[resp_next_];
    resp_next_ = (resp_next_ + 1) % kResponses;
    return r;
  }
  static double grid_step(double h) { return std::exp2(std::floor(std::log2(h) * 8.0) / 8.0); }
  Eigen::VectorXd la_, le_, col0_, zero_;

  // Full acceleration M⁻¹(f₀ − Kq − Cv + e₀F).
  void full_acceleration(const Eigen::VectorXd& y, double F, Eigen::VectorXd& a) {
    a.resize(n_);
    rbuf_.resize(n_);
    m_.internal_force(y.data(), y.data() + n_, rbuf_.data());
    rbuf_[0] += F;
    m_.solve_mass(rbuf_.data(), a.data());
  }
  void fill_step_data(StepData& s, double t0, const Eigen::VectorXd& y0, double F0, double t1,
                      const Eigen::VectorXd& y1, double F1, bool held) {
    s.t0 = t0;
    s.t1 = t1;
    s.held = held;
    s.y0 = y0;
    s.y1 = y1;
    s.F0 = F0;
    s.F1 = F1;
    full_acceleration(y0, F0, s.a0);
    full_acceleration(y1, F1, s.a1);
  }
  // State at τ inside the step: other nodes cubic Hermite; node 0 on the cam (held) or
  // quintic Hermite (free). Returns the contact force there (held: pointwise; free: 0).
  double interpolate(const StepData& s, double tau, Eigen::VectorXd& y, CamMotion* cm = nullptr) {
    const int n = n_;
    const double h = s.t1 - s.t0, x = (tau - s.t0) / h;
    y.resize(2 * n);
    if (n > 1) {
      const double x2 = x * x, x3 = x2 * x;
      const double h00 = 2 * x3 - 3 * x2 + 1, h10 = (x3 - 2 * x2 + x) * h;
      const double h01 = -2 * x3 + 3 * x2, h11 = (x3 - x2) * h;
      y.head(n) = h00 * s.y0.head(n) + h10 * s.y0.tail(n) + h01 * s.y1.head(n) + h11 * s.y1.tail(n);
      y.tail(n) = h00 * s.y0.tail(n) + h10 * s.a0 + h01 * s.y1.tail(n) + h11 * s.a1;
    }
    const CamMotion c = cam_at(tau);
    if (cm) *cm = c;
    if (s.held) {
      y[0] = c.X;
      y[n] = c.Xdot;
      double F = (c.Xddot - m_.contact_acceleration(y.data(), y.data() + n, 0.0)) / m_.mstar();
      if (!bilateral_ && F < 0.0) F = 0.0;
      return F;
    }
    // Quintic Hermite of node 0 from (u, u̇, ü) at both ends.
    double u, v;
    quintic(s.y0[0], s.y0[n], s.a0[0], s.y1[0], s.y1[n], s.a1[0], h, x, &u, &v, nullptr);
    y[0] = u;
    y[n] = v;
    return 0.0;
  }
  static void quintic(double u0, double v0, double a0, double u1, double v1, double a1, double h,
                      double x, double* u, double* v, double* a) {
    // p(x) on [0, 1] with p, p', p'' (in x) given at both ends.
    const double p0 = u0, d0 = v0 * h, s0 = a0 * h * h, p1 = u1, d1 = v1 * h, s1 = a1 * h * h;
    const double c0 = p0, c1 = d0, c2 = 0.5 * s0;
    const double c3 = 10 * (p1 - p0) - 6 * d0 - 4 * d1 - 1.5 * s0 + 0.5 * s1;
    const double c4 = -15 * (p1 - p0) + 8 * d0 + 7 * d1 + 1.5 * s0 - s1;
    const double c5 = 6 * (p1 - p0) - 3 * d0 - 3 * d1 - 0.5 * s0 + 0.5 * s1;
    if (u) *u = c0 + x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5))));
    if (v) *v = (c1 + x * (2 * c2 + x * (3 * c3 + x * (4 * c4 + x * 5 * c5)))) / h;
    if (a) *a = (2 * c2 + x * (6 * c3 + x * (12 * c4 + x * 20 * c5))) / (h * h);
  }
  // Gap (free) or force (held) along the step at x ∈ [0, 1].
  double switching_function(const StepData& s, double x) {
    const double tau = s.t0 + x * (s.t1 - s.t0);
    if (s.held) {
      Eigen::VectorXd& y = hq_;
      interpolate(s, tau, y);
      // unclipped pointwise force
      const CamMotion c = cam_at(tau);
      return (c.Xddot - m_.contact_acceleration(y.data(), y.data() + n_, 0.0)) / m_.mstar();
    }
    double u;
    quintic(s.y0[0], s.y0[n_], s.a0[0], s.y1[0], s.y1[n_], s.a1[0], s.t1 - s.t0, x, &u, nullptr, nullptr);
    return u - cam_at(tau).X;
  }
  // First x ∈ (0, 1] where the switching function falls below −thr: a sign change between
  // samples, or a sampled minimum (parabola through three samples, refined by golden
  // section) below −thr (grazing). Returns −1 if none; else the root of f = 0 (bisection
  // to round-off) after the last point where f ≥ 0.
  double first_switch(const StepData& s, double thr) {
    constexpr int K = 8;
    double f[K + 1];
    for (int k = 0; k <= K; ++k) f[k] = k == 0 ? (s.held ? s.F0 : s.y0[0] - cam_at(s.t0).X)
                                                : k == K ? (s.held ? s.F1 : s.y1[0] - cam_at(s.t1).X)
                                                         : switching_function(s, double(k) / K);
    double lo = -1, hi = -1;
    for (int k = 1; k <= K && lo < 0; ++k) {
      if (f[k] < -thr) {
        lo = double(k - 1) / K;
        hi = double(k) / K;
        break;
      }
      // a minimum between samples k−1, k, k+1 that dips below −thr?
      if (k < K && f[k] <= f[k - 1] && f[k] <= f[k + 1]) {
        const double den = f[k - 1] - 2 * f[k] + f[k + 1];
        const double vert = den > 0 ? f[k] - (f[k + 1] - f[k - 1]) * (f[k + 1] - f[k - 1]) / (8 * den) : f[k];
        // close to zero compared with the variation around it (the parabola's own error):
        // refine the minimum on the function itself
        if (vert < thr + std::abs(f[k - 1] - f[k]) + std::abs(f[k + 1] - f[k])) {
          double a = double(k - 1) / K, b = double(k + 1) / K;
          const double gr = 0.6180339887498949;
          double c = b - gr * (b - a), d = a + gr * (b - a);
          double fc = switching_function(s, c), fd = switching_function(s, d);
          for (int i = 0; i < 40; ++i) {
            if (fc < fd) { b = d; d = c; fd = fc; c = b - gr * (b - a); fc = switching_function(s, c); }
            else { a = c; c = d; fc = fd; d = a + gr * (b - a); fd = switching_function(s, d); }
          }
          const double xm = fc < fd ? c : d, fm = std::min(fc, fd);
          if (s.held) {  // the force's minimum inside the step: the contact margin
            const double tm = s.t0 + xm * (s.t1 - s.t0);
            designer_.sample_force(tm, drive_.theta(tm), std::max(fm, 0.0));
          }
          if (fm < -thr) {
            lo = double(k - 1) / K;
            hi = xm;
            break;
          }
        }
      }
    }
    if (lo < 0) return -1.0;
    // f(lo) ≥ −thr, f(hi) < −thr: bisect on f = 0 between them.
    double flo = switching_function(s, lo);
    if (flo < 0) return lo;  // already below zero at the bracket's start (round-off level)
    for (int i = 0; i < 100 && (hi - lo) * (s.t1 - s.t0) > 4e-16 * std::max(1.0, std::abs(s.t1)); ++i) {
      const double mid = 0.5 * (lo + hi);
      (switching_function(s, mid) >= 0.0 ? lo : hi) = mid;
    }
    return hi;
  }

  // ∫ F Ẋ_C dt over [s.t0, tb] of a held step, adaptive Simpson on the pointwise force.
  double held_work(const StepData& s, double tb) {
    auto g = [&](double tau) {
      const double F = interpolate(s, tau, hv_);
      sum_.max_contact_force = std::max(sum_.max_contact_force, F);
      designer_.sample_force(tau, drive_.theta(tau), F);
      return F * cam_at(tau).Xdot;
    };
    const double ta = s.t0, h = tb - ta;
    if (h <= 0) return 0.0;
    const double ga = s.F0 * cam_at(ta).Xdot, gb = g(tb), gm = g(0.5 * (ta + tb));
    const double S = h / 6.0 * (ga + 4.0 * gm + gb);
    const double tol = 1e-8 * (std::abs(S) + h * std::max(std::abs(ga), std::abs(gb)));
    return adaptive_simpson(g, ta, tb, ga, gm, gb, S, tol, 12);
  }
  // One interpolated output row at τ inside the accepted step s. The work column is
  // accumulated row to row by Simpson's rule on F·Ẋ_C over [previous row, τ] (O(Δτ⁵) per
  // interval; the step's own work, booked at its end, is the adaptive quadrature above).
  void dense_row(StepData& s, double tau) {
    Eigen::VectorXd& y = dense_y_;
    CamMotion c, cmid;
    const double F = interpolate(s, tau, y, &c);
    if (s.held) {
      const double ta = s.t_row, tm = 0.5 * (ta + tau);
      const double gm = interpolate(s, tm, hv_, &cmid) * cmid.Xdot;
      const double gb = F * c.Xdot;
      s.W_row += (tau - ta) / 6.0 * (s.g_row + 4.0 * gm + gb);
      s.t_row = tau;
      s.g_row = gb;
    }
    const double P = m_.damping_power(y.data() + n_);
    const double D = s.D0 + 0.5 * (tau - s.t0) * (s.P0 + P);
    emit_row_at(tau, y, F, s.held, m_.potential_energy(y.data()), s.held ? s.W_row : s.W0, D, &c);
  }
  Eigen::VectorXd dense_y_;

  // Solve the contact step's force shape for a step of hs (from t_, y_, F_): returns the
  // end state in y1 and the engine's local error norm; (F1, Fc) the shape.
  double solve_held_step(double hs, double t1, Eigen::VectorXd& y1, double& F1, double& Fc) {
    ContactLaw& law = engine_->law();
    law.t0 = t_;
    law.h = hs;
    law.F0 = F_;
    const CamMotion cm = cam_at(t1);
    const bool affine = engine_->affine_steps();
    bool hit = false;
    ShapeResponse& resp_ = affine ? response_slot(hs, &hit) : resp_cache_[0];
    auto integrate = [&](double a, double c, Eigen::VectorXd& out, const Eigen::VectorXd& from) {
      law.F1 = a;
      law.Fc = c;
      return engine_->step(t_, from, hs, out);
    };
    F1 = F_ + slope_prev_ * hs;  // start from the previous step's slope
    Fc = 0.0;
    double err = integrate(F1, Fc, la_, y_);
    if (affine) le_ = engine_->local_error();
    if (!affine) {
      // CVODE (its internal steps depend on the solution, so the step map is not exactly
      // affine, and each trial restarts it): Lee's constants, the response of the contact
      // mass M* alone, (Δu₀, Δu̇₀) = M*(h²/6, h/2) per unit F₁ and M*(h²/3, 2h/3) per unit
      // F_c, iterated to tol_u, tol_v (exact for a rigid follower, linear convergence for
      // a bar). Finite-difference responses by two more CVODE integrations converged in
      // fewer iterations but cost 10× more on B1 (each integration restarts CVODE at
      // order 1 with a tolerance of 1e-2 tol_u).
      const double Ms = m_.mstar();
      resp_.D1.setZero(2 * n_);
      resp_.Dc.setZero(2 * n_);
      resp_.D1[0] = Ms * hs * hs / 6.0;
      resp_.D1[n_] = Ms * hs / 2.0;
      resp_.Dc[0] = Ms * hs * hs / 3.0;
      resp_.Dc[n_] = 2.0 * Ms * hs / 3.0;
      resp_.h = -1.0;
    } else if (!hit) {
      // Responses to a unit F₁ and a unit F_c from rest without preload (exact for any h
      // on the affine engines), with an amplitude that makes them of order one.
      zero_.setZero(2 * n_);
      law.F0 = 0.0;
      engine_->set_homogeneous(true);
      const double amp = 1.0 / (m_.mstar() * hs * hs);
      integrate(amp, 0.0, resp_.D1, zero_);
      resp_.D1 /= amp;
      resp_.E1 = engine_->local_error() / amp;
      integrate(0.0, amp, resp_.Dc, zero_);
      resp_.Dc /= amp;
      resp_.Ec = engine_->local_error() / amp;
      engine_->set_homogeneous(false);
      law.F0 = F_;
      law.F1 = F1;
      law.Fc = Fc;
      resp_.h = hs;
      sum_.contact_iterations += 2;
    }
    const double a11 = resp_.D1[0], a12 = resp_.Dc[0], a21 = resp_.D1[n_], a22 = resp_.Dc[n_];
    const double det = a11 * a22 - a12 * a21;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
      ++sum_.iteration_failures;
      throw IterationFailure();
    }
    const double tol_v = sc_.contact.tol_v > 0 ? sc_.contact.tol_v : tol_u_ / hs;
    y1 = la_;
    int it = 0;
    for (;;) {
      // residuals: the end state must sit on the cam with the cam's velocity
      const double r0 = cm.X - y1[0], r1 = cm.Xdot - y1[n_];
      if (it > 0 && (affine || (std::abs(r0) < tol_u_ && std::abs(r1) < tol_v))) break;
      if (it >= sc_.contact.max_iterations) {
        ++sum_.iteration_failures;
        throw IterationFailure();
      }
      const double d1 = (r0 * a22 - a12 * r1) / det, dc = (a11 * r1 - a21 * r0) / det;
      F1 += d1;
      Fc += dc;
      ++it;
      ++sum_.contact_iterations;
      if (affine) {
        y1 += d1 * resp_.D1 + dc * resp_.Dc;
        le_ += d1 * resp_.E1 + dc * resp_.Ec;
        err = engine_->wrms(le_, y_);
      } else {
        err = integrate(F1, Fc, y1, y_);
      }
    }
    sum_.level_u.total += it;
    sum_.level_u.max = std::max(sum_.level_u.max, it);
    ++sum_.level_u.steps;
    sum_.level_v.total += it;
    sum_.level_v.max = std::max(sum_.level_v.max, it);
    ++sum_.level_v.steps;
    y1[0] = cm.X;  // round-off of the affine combination
    y1[n_] = cm.Xdot;
    return err;
  }

  void run_lee_located() {
    ContactLaw& law = engine_->law();
    law.kind = ContactLaw::Kind::Ramp;
    const double Ms = m_.mstar();
    const int q = engine_->error_order();
    const double e_rest = sc_.contact.restitution;
    const bool land = sc_.run.land_on_output || out_dt() <= 0.0;
    const double rtol = sc_.solver.rtol;
    // Switching thresholds: a gap below −gap_thr is a penetration (far below tol_u, far
    // above round-off in X_C); a separation is declared where the force ≤ F_thr.
    const double gap_thr = 1e-3 * tol_u_;
    col0_.resize(n_);
    {
      Eigen::VectorXd e0 = Eigen::VectorXd::Zero(n_);
      e0[0] = 1.0;
      m_.solve_mass(e0.data(), col0_.data());  // M⁻¹e₀ (node 0 entry = M*)
    }
    if (!bilateral_ && contact_ && !(F_ > 0.0)) {
      // Touching but the cam would have to pull: the follower leaves at t = 0.
      contact_ = false;
      const CamMotion c0 = cam_at(t_);
      if (c0.Xddot - m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0) < 0.0) {
        ++sum_.separations;
        record_event("separation", 0.0);
      }
      F_ = 0.0;
    }
    double h = initial_step();
    double h_try = -1.0;  // > 0: retake landing on a switch found inside the last trial
    Eigen::VectorXd y1(2 * n_);
    const double hmin_rel = 1e-14;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double t_next = land ? next_output_time() : sc_.run.t_end;
      const bool relocating = h_try > 0.0;
      double hs = relocating ? h_try : h;
      h_try = -1.0;
      if (!relocating) {
        if (sc_.solver.max_step > 0) hs = std::min(hs, sc_.solver.max_step);
        const double rem = t_next - t_;
        if (rem - hs < 1e-6 * hs)
          hs = rem;
        else if (rem < 2.0 * hs)
          hs = 0.5 * rem;
      }
      if (hs <= hmin_rel * std::max(1.0, std::abs(t_)))
        throw StepFailure("step size underflow (h = " + fmt(hs) + ")");
      const double t1 = (!relocating && hs == t_next - t_) ? t_next : t_ + hs;
      hs = t1 - t_;
      const CamMotion cm = cam_at(t1);
      const double P_prev = dissipation_power();
      if (contact_) {
        double F1 = 0, Fc = 0, err_e = 0;
        try {
          err_e = solve_held_step(hs, t1, y1, F1, Fc);
        } catch (const IterationFailure&) {
          ++sum_.rejected_steps;
          h = 0.5 * hs;
          continue;
        }
        // acceleration level: the force the equation of motion demands at t+h
        const double Fa = (cm.Xddot - m_.contact_acceleration(y1.data(), y1.data() + n_, 0.0)) / Ms;
        ++sum_.level_a.total;
        sum_.level_a.max = std::max(sum_.level_a.max, 1);
        ++sum_.level_a.steps;
        const double Fscale = std::max(std::abs(F_), std::abs(Fa));
        const double tolF = rtol * Fscale + 2.0 * tol_u_ / (Ms * hs * hs);
        const double err_c = std::abs(Fa - F1) / tolF;
        const double err = std::max(err_e, err_c);
        auto next_h = [&]() {
          // F̃ − F₁ ∝ h³ (a quadratic shape): against rtol·|F| the error ratio goes as h³,
          // against the absolute part ∝ h⁻² as h⁵; the exponent blends the two.
          const double w_rel = rtol * Fscale, w_abs = tolF - w_rel;
          const double pc = (3.0 * w_rel + 5.0 * w_abs) / tolF;
          const double fe = err_e > 0 ? 0.9 * std::pow(err_e, -1.0 / q) : 5.0;
          const double fc = err_c > 0 ? 0.9 * std::pow(err_c, -1.0 / pc) : 5.0;
          return std::min(5.0, std::max(0.2, std::min(fe, fc)));
        };
        if (err > 1.0) {
          ++sum_.rejected_steps;
          h_fail_ = hs;
          h = grid_step(hs * std::min(0.9, next_h()));
          continue;
        }
        fill_step_data(sd_, t_, y_, F_, t1, y1, Fa, true);
        bool separate = false;
        if (!bilateral_) {
          // A switch is looked for where the pointwise force falls below zero (a round-off
          // margin), and declared at the landed step's end once the force there is within
          // the force tolerance rtol·|F| of zero.
          const double F_thr = 1e-12 * Fscale;
          F_ref_ = std::max({F_ref_, std::abs(F_), std::abs(Fa)});
          const double F_sep = rtol * F_ref_;  // a force this close to zero is zero
          const double x = first_switch(sd_, F_thr);
          if (x >= 0.0 && x < 1.0 - 1e-9) {
            // the force reaches zero inside the step: land there
            const double hx = x * hs;
            if (F_ <= F_sep || hx <= 1e-9 * hs || hx <= hmin_rel * std::max(1.0, std::abs(t_))) {
              // at the step's start: separate now
              ++sum_.separations;
              record_event("separation", 0.0);
              contact_ = false;
              F_ = 0.0;
              continue;
            }
            ++sum_.relocated_steps;
            h_try = hx;
            continue;
          }
          separate = Fa <= F_sep || x >= 0.0;
        }
        if (obs_) obs_->on_lee_shape(t_, hs, F_, F1, Fc, 0.0);
        // accept
        sd_.W0 = sd_.W_row = work_;
        sd_.D0 = dissipated_;
        sd_.P0 = P_prev;
        sd_.t_row = t_;
        sd_.g_row = F_ * cam_at(t_).Xdot;
        const double dW = held_work(sd_, t1);
        slope_prev_ = (Fa - F_) / hs;
        y_ = y1;
        t_ = t1;
        F_ = Fa;
        if (separate) {
          ++sum_.separations;
          record_event("separation", 0.0);
          contact_ = false;
          F_ = 0.0;
          slope_prev_ = 0.0;
        }
        dense_ = land ? nullptr : &sd_;
        after_step(hs, dW, P_prev);
        dense_ = nullptr;
        if (!relocating) h = propose_step(hs, next_h());
        continue;
      }
      // ---- free step
      law.t0 = t_;
      law.h = hs;
      law.F0 = law.F1 = law.Fc = 0.0;
      const double err_e = engine_->step(t_, y_, hs, y1);
      if (err_e > 1.0) {
        ++sum_.rejected_steps;
        h_fail_ = hs;
        h = grid_step(hs * std::max(0.2, std::min(0.9, 0.9 * std::pow(err_e, -1.0 / q))));
        continue;
      }
      fill_step_data(sd_, t_, y_, 0.0, t1, y1, 0.0, false);
      const double x = first_switch(sd_, gap_thr);
      if (x >= 0.0 && x < 1.0 - 1e-9) {
        ++sum_.relocated_steps;
        h_try = std::max(x, 1e-9) * hs;
        continue;
      }
      const double gap1 = y1[0] - cm.X;
      // A landed step ends on the root to the engine's accuracy: within tol_u of the cam
      // is the impact (left open, the next step would find the root again at x ≈ 0).
      const bool impact_now = x >= 0.0 || gap1 <= gap_thr || (relocating && gap1 <= tol_u_);
      sd_.W0 = work_;
      sd_.D0 = dissipated_;
      sd_.P0 = P_prev;
      y_ = y1;
      t_ = t1;
      F_ = 0.0;
      const double P_end = dissipation_power();  // before the impulse
      double P_applied = 0.0;
      if (impact_now) {
        const double approach = cm.Xdot - y_[n_];  // ŝ⁻ > 0: closing
        y_[0] = cm.X;                               // the root is located to tolerance
        const double rel_acc = std::abs(cm.Xddot - m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0));
        if (v_impact_ref_ == 0.0 && approach > 0.0) v_impact_ref_ = approach;
        const double v_stick = std::max(1e-6 * v_impact_ref_, 4.0 * std::sqrt(2.0 * rel_acc * gap_thr));
        const bool stick = bilateral_ || e_rest == 0.0 || (1.0 + e_rest) * approach < v_stick;
        const double ap = std::max(approach, 0.0);
        const double P = (stick ? 1.0 : 1.0 + e_rest) * ap / Ms;
        y_.tail(n_) += P * col0_;
        P_applied = P;
        if (stick) y_[n_] = cm.Xdot;
        work_ += P * cm.Xdot;
        dissipated_ += 0.5 * (stick ? 1.0 : 1.0 - e_rest * e_rest) * ap * ap / Ms;
        if (approach > 0.0) {
          ++sum_.impacts;
          record_event("impact", approach, P);
        }
        if (stick) {
          const double Fh = (cm.Xddot - m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0)) / Ms;
          if (bilateral_ || Fh > 0.0) {
            contact_ = true;
            F_ = Fh;
            slope_prev_ = 0.0;
          }
        }
      }
      if (obs_) obs_->on_lee_shape(sd_.t0, hs, 0.0, 0.0, 0.0, P_applied);
      dense_ = land ? nullptr : &sd_;
      after_step(hs, 0.0, P_prev, P_end);
      dense_ = nullptr;
      if (!relocating) h = propose_step(hs, err_e > 0 ? 0.9 * std::pow(err_e, -1.0 / q) : 5.0);
    }
  }
  double slope_prev_ = 0.0;
  // The next step after an accepted one of hs whose error asks for a factor fac. Grows
  // only with a margin and not past 0.95 of the last size that failed the error test (an
  // explicit engine's error estimate jumps at its stability limit: without the memory a
  // bar on arkode-erk had 8–17 % of its steps rejected there); that memory relaxes by 2 %
  // per step. Shrinks at once. Sizes on the grid 2^(k/8) (cached responses).
  double h_fail_ = INFINITY;
  double propose_step(double hs, double fac) {
    h_fail_ *= 1.02;
    fac = std::min(5.0, std::max(0.2, fac));
    if (fac < 1.25) return grid_step(hs * std::min(fac, 1.0));
    return grid_step(std::max(std::min(hs * fac / 1.1, 0.95 * h_fail_), grid_step(hs)));
  }
  double F_ref_ = 0.0;  // largest contact force so far: the scale of the force tolerance

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
    // A free phase that starts on the cam (after a separation, a bounce, or at t = 0) has
    // a gap that opens from 0, slowly (≈ t³ after a separation, where the reaction passes
    // through 0), while the integrator's error in q₀ after its restart is of the order of
    // its local tolerance (BDF1's first steps: h²ü₀/2, ≫ δ). Armed at once, the gap root
    // fired on that error again and again — each time the follower was put back on the
    // cam and the integrator restarted with tiny steps (cvode-bdf, A7 at rtol 1e-9: 6.0 M
    // steps in 7 ms after the first separation). So such a phase first watches
    // |gap| − ε (rising) with ε = 10 (rtol·max(1, |X_C|) + atol), the integration error's
    // scale: the gap opening past ε arms the closing-gap root (one restart); a penetration
    // past ε before that is a re-contact (handled as an impact, located to ε).
    const double rtol = sc_.solver.rtol, atol = sc_.solver.atol;
    double eps_leave = 0.0;
    bool leaving = false;
    auto band_root = [this, &eps_leave](double t, const double* y) {
      return std::abs(y[0] - cam_at(t).X) - eps_leave;
    };
    auto start_free = [&]() {
      const double X = cam_at(t_).X;
      eps_leave = 10.0 * (rtol * std::max(1.0, std::abs(X)) + atol);
      leaving = y_[0] - X < eps_leave;
      if (leaving)
        engine_->set_root(band_root, +1);
      else
        engine_->set_root(gap_root, -1);
      engine_->reinit(t_, y_);
    };
    // Initial phase.
    bool in_contact = holonomic || (contact_ && F_ > 0.0);
    contact_ = in_contact;
    if (!in_contact) F_ = 0.0;
    Eigen::VectorXd yr, y1;
    if (in_contact && !rigid) held_engine->reinit(t_, held_from_full());
    if (!in_contact) start_free();
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
        if (engine_->hit_root() && leaving && y_[0] - cam_at(t_).X > 0.0) {
          start_free();  // the gap opened past ε: arm the closing-gap root
        } else if (engine_->hit_root()) {
          const CamMotion c = cam_at(t_);
          const double approach = c.Xdot - y_[n_];  // ŝ⁻ > 0: closing
          const double v0_pre = y_[n_];
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
            // (A re-contact found by the leaving phase's band root is located at a
            // penetration of ε, not δ: the same argument with ε.)
            const double delta = leaving ? eps_leave
                                         : 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(c.X));
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
            record_event("impact", approach, (y_[n_] - v0_pre) / Ms);
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

  // ------------------------------------------------------------ holonomic on IDA ---
  // The held contact as an index-2 GGL DAE (ida_engine.cpp): IDA steps natively and stops
  // on every output time (rows are step values); the force is the multiplier λ, the cam's
  // work W = ∫ λ Ẋ_C dt a DAE component; a root of λ (decreasing) is the first tensile time.
  void run_ida_holonomic() {
    IdaHeldContact ida(model_, sc_, [this](double t) { return cam_at(t); });
    ida.set_tensile_root(true);
    ida.init(t_, y_, sc_.run.t_end);
    y_ = ida.state();
    F_ = ida.lambda();
    contact_ = true;
    sum_.model.linear_solver = to_string(ida.linear_solver());
    sum_.model.unknowns = ida.unknowns();
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_output_time();
      const double P_prev = dissipation_power(), t_prev = t_, W_prev = ida.work();
      t_ = ida.advance(tout, out_dt() <= 0.0);  // output_dt = 0: one row per IDA step
      y_ = ida.state();
      F_ = ida.lambda();
      if (ida.hit_root() && sum_.first_tensile_time < 0) {
        sum_.first_tensile_time = t_;
        record_event("tensile", 0.0);
        ida.set_tensile_root(false);
      }
      after_step(t_ - t_prev, ida.work() - W_prev, P_prev);
      sum_.steps = ida.stats().steps;  // after_step counts output intervals: IDA's steps
    }
    const EngineStats st = ida.stats();
    sum_.steps = st.steps;
    sum_.rejected_steps = ida.rejected_steps();
    sum_.rhs_evals += st.rhs_evals;
    sum_.lin_setups += st.lin_setups;
    sum_.lin_analyses += st.lin_analyses;
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
