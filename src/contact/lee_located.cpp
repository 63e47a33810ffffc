// camdyn — Lee's method, the located step (contact.lee_step = "located", the default).
//   One consistent trajectory per step (a two-parameter force shape solved for
//   displacement and velocity compatibility from the affine step map), the acceleration
//   level's force error in the error test, separations and impacts located inside the
//   step and landed on, dense output. The method in detail: README "Lee's step, located"
//   and the comment at StepData below.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "lee_step_tools.hpp"
#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

class LeeLocated final : public RunContext {
 public:
  using RunContext::RunContext;

 private:
  StepRamp ramp_;  // the force on the contact node over the step being taken

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
  bool dense_row_at(double to) override {
    if (!dense_ || !(to > dense_->t0)) return false;
    dense_row(*dense_, to);
    return true;
  }
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
  Eigen::VectorXd la_, le_, col0_, zero_;

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
    const double tol = std::min(1e-8, 0.1 * sc_.solver.rtol) * (std::abs(S) + h * std::max(std::abs(ga), std::abs(gb)));
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
    StepRamp& law = ramp_;
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

  void run_method() override {
    StepRamp& law = ramp_;
    engine_->set_contact(&ramp_);
    const double Ms = m_.mstar();
    const int q = engine_->error_order();
    const double e_rest = sc_.contact.restitution;
    const bool land = sc_.run.land_on_output || out_dt() <= 0.0;
    const double rtol = sc_.solver.rtol;
    // Switching thresholds: a gap below −gap_thr is a penetration (far below tol_u, far
    // above round-off in X_C); a separation is declared where the force ≤ F_thr.
    const double gap_thr = 1e-3 * tol_u_;
    col0_ = m_.contact_column();  // M⁻¹e₀ (node 0 entry = M*)
    if (!bilateral_ && contact_ && !(F_ > 0.0)) {
      // Touching but the cam would have to pull: the follower leaves at t = 0.
      contact_ = false;
      const CamMotion c0 = cam_at(t_);
      if (c0.Xddot - m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0) < 0.0) {
        ++sum_.separations;
        record_event(EventKind::Separation, 0.0);
      }
      F_ = 0.0;
    }
    double h = initial_step();
    double h_try = -1.0;  // > 0: retake landing on a switch found inside the last trial
    bool landing_sep = false;  // that switch is the contact force reaching zero
    Eigen::VectorXd y1(2 * n_);
    const double hmin_rel = 1e-14;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      // held on a C0 joint of the cam (the steps land there): its impact, at the instant
      if (cam_joint_impact()) slope_prev_ = 0.0;
      const double t_next = stop_before(land ? next_output_time() : sc_.run.t_end);
      const bool relocating = h_try > 0.0;
      double hs = relocating ? h_try : fit_step(h, t_next);
      h_try = -1.0;
      const bool landed_sep = relocating && landing_sep;
      landing_sep = false;
      if (hs <= hmin_rel * std::max(1.0, std::abs(t_)))
        throw StepSizeUnderflow(hs);
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
        } catch (const SundialsError&) {
          // a trial CVODE cannot complete (it restarts at order 1 inside every trial: at a
          // cam joint after a long dwell its first steps fail its error test): rejected and
          // retried at half the size, as on networks
          ++sum_.rejected_steps;
          ++sum_.iteration_failures;
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
          steps_.failed(hs);
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
          // A force this close to zero is zero; capped at 1e-6 of the largest force: a loose
          // rtol (1e-2) let the follower leave while still pressed (by 1 % of the peak), and
          // it re-struck at once — a chatter of separation/impact pairs (A7, tol_u 1e-3).
          const double F_sep = std::min(rtol, 1e-6) * F_ref_;
          const double x = first_switch(sd_, F_thr);
          if (x >= 0.0 && x < 1.0 - 1e-9) {
            // the force reaches zero inside the step: land there
            const double hx = x * hs;
            if (F_ <= F_sep || hx <= 1e-9 * hs || hx <= hmin_rel * std::max(1.0, std::abs(t_))) {
              // at the step's start: separate now
              ++sum_.separations;
              record_event(EventKind::Separation, 0.0);
              contact_ = false;
              F_ = 0.0;
              continue;
            }
            ++sum_.relocated_steps;
            h_try = hx;
            landing_sep = true;
            continue;
          }
          // A step landed on the force's zero ends there to the accuracy of the force's
          // interpolant, not to F_sep (B2 at rtol = tol_u = 1e-10 landed at F = 8e-6 >
          // F_sep = 2e-6, found the zero again 7.5e-14 s later, and the step size
          // underflowed retaking it): the follower separates once the end force is zero
          // within the step's own force tolerance.
          separate = Fa <= F_sep || x >= 0.0 || (landed_sep && Fa <= tolF);
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
          record_event(EventKind::Separation, 0.0);
          contact_ = false;
          F_ = 0.0;
          slope_prev_ = 0.0;
        }
        dense_ = land ? nullptr : &sd_;
        after_step(hs, dW, P_prev);
        dense_ = nullptr;
        if (!relocating) h = steps_.propose(hs, next_h());
        continue;
      }
      // ---- free step
      law.t0 = t_;
      law.h = hs;
      law.F0 = law.F1 = law.Fc = 0.0;
      double err_e = 0.0;
      try {
        err_e = engine_->step(t_, y_, hs, y1);
      } catch (const SundialsError&) {  // a trial CVODE cannot complete: as above
        ++sum_.rejected_steps;
        ++sum_.iteration_failures;
        h = 0.5 * hs;
        continue;
      }
      if (err_e > 1.0) {
        ++sum_.rejected_steps;
        steps_.failed(hs);
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
          record_event(EventKind::Impact, approach, P);
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
      if (!relocating) h = steps_.propose(hs, err_e > 0 ? 0.9 * std::pow(err_e, -1.0 / q) : 5.0);
    }
  }
  double slope_prev_ = 0.0;
  StepSizeMemory steps_;  // the step-size controller (lee_step_tools.hpp)

  double F_ref_ = 0.0;  // largest contact force so far: the scale of the force tolerance

};

}  // namespace

std::unique_ptr<RunContext> make_lee_located(const Scene& sc, std::shared_ptr<const FollowerModel> model,
                                      Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<LeeLocated>(sc, std::move(model), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
