// camdyn — the exact event-driven baseline (contact.model = "event") and the holonomic
// baseline (contact.model = "holonomic": the contact phase alone, reporting where the
// reaction turns tensile). See the comment at reaction_rigid below.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

class EventDriven final : public RunContext {
 public:
  using RunContext::RunContext;

 private:

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

  void run_method() override {
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
      // The BDF2 cap of elastic followers (engines.cpp) made cvode-bdf resolve the undamped
      // bar's modes with ever smaller steps once impacts excite them (B2 at rtol 1e-10:
      // 41·10⁶ steps for 0.2 s). At tight tolerances the event method allows orders up to
      // 5 with CVODE's stability-limit detection; at rtol 1e-6 order 5 was worse (the stiff
      // bar took 161 k steps against 16 k), hence the measured threshold 1e-8.
      if (sc_.solver.rtol <= 1e-8) {
        held_engine->set_max_order(5);
        engine_->set_max_order(5);
      }
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
            record_event(EventKind::Impact, approach, (y_[n_] - v0_pre) / Ms);
          }
        }
      }
      if (separation) {
        ++sum_.separations;
        record_event(EventKind::Separation, 0.0);
      }
      contact_ = in_contact;
      const double dW = std::isnan(dW_override) ? trapezoid_work(t_ - t_prev, Ft, Xdot_prev) : dW_override;
      after_step(t_ - t_prev, dW, P_prev, P_end);
    }
    sum_.rhs_evals += held_engine ? held_engine->stats().rhs_evals : 0;
  }

};

}  // namespace

std::unique_ptr<RunContext> make_event_driven(const Scene& sc, std::shared_ptr<const FollowerModel> model,
                                      Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<EventDriven>(sc, std::move(model), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
