// camdyn — the exact event-driven baseline (contact.model = "event") and the holonomic
// baseline (contact.model = "holonomic": the contact phase alone, reporting where the
// reaction turns tensile). See the comment at reaction_rigid below.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "../held_phase.hpp"
#include "free_flight.hpp"
#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

// The held phase's load from the cam on the free part (held_phase.hpp), whatever the state.
class HeldCoupling final : public ContactForce {
 public:
  HeldCoupling(const Cam& cam, const CamDrive& drive, const HeldPhase& held) : cam_(cam, drive), held_(held) {}
  double force(double t, double, double) const override { return held_.coupling_load(cam_.at(t)); }

 private:
  CamPath cam_;
  const HeldPhase& held_;
};

class EventDriven final : public RunContext {
 public:
  using RunContext::RunContext;

 private:
  HeldPhase phase_{m_};                          // the contact row held (coordinate partitioning)
  HeldCoupling coupling_{cam_, drive_, phase_};  // the cam's load on its free part
  Eigen::VectorXd hbuf_, abuf_;  // the free part's right-hand side and acceleration

  // ------------------------------------------------------------ event-driven -------
  // Contact phase: node 0 moves with the cam (u₀ = X_C, u̇₀ = Ẋ_C, ü₀ = Ẍ_C); the other
  // nodes obey M_rr q̈_r = f_r − K_rr q_r − C_rr v_r − (K_r0X_C + C_r0Ẋ_C + M_r0Ẍ_C), and the
  // reaction is F = M₀₀Ẍ_C + M_0r q̈_r − (f₀ − K q − C v)₀ (src/held_phase.hpp). Free phase: F = 0.
  // Switches: the reaction reaching zero (decreasing) → separation; the gap closing
  // (decreasing) → impact, a Newton impulse P = (1 + e) ŝ⁻ / M* on node 0, Δv = M⁻¹e₀ P,
  // then contact if the reaction is compressive (plastic), else free flight (bounce).
  // Roots are located by SUNDIALS rootfinding (rigid contact phase: bisection on the
  // closed-form reaction) to round-off in time.
  // "holonomic" is the contact phase alone, reporting where the reaction turns tensile.
  double reaction_rigid(double t) const { return phase_.reaction(cam_at(t), nullptr, nullptr, nullptr); }
  // Work of the closed-form rigid reaction, ∫ F Ẋ_C dt over [a, b] by adaptive Simpson
  // (Richardson-corrected, at most 20 halvings), to 0.1·rtol of ∫|F Ẋ_C| dt; pa, pb: the power at a and b.
  double contact_work_rigid(double a, double b, double pa, double pb) const {
    auto power = [&](double t) { return reaction_rigid(t) * cam_at(t).Xdot; };
    const double m = 0.5 * (a + b), pm = power(m);
    const double abs_est = (b - a) / 6.0 * (std::abs(pa) + 4.0 * std::abs(pm) + std::abs(pb));
    const double tol = 0.1 * sc_.solver.rtol * abs_est;
    return adaptive_simpson(power, a, b, pa, pm, pb, (b - a) / 6.0 * (pa + 4.0 * pm + pb), tol, 20);
  }
  double reaction_held(double t, const double* yr) {
    const FollowerModel& h = *phase_.free_part();
    const int r = h.n();
    const CamMotion c = cam_at(t);
    // q̈_r from the held model's equation of motion.
    hbuf_.resize(r);
    h.internal_force(yr, yr + r, hbuf_.data());
    hbuf_[0] += phase_.coupling_load(c);
    abuf_.resize(r);
    h.solve_mass(hbuf_.data(), abuf_.data());
    return phase_.reaction(c, yr, yr + r, abuf_.data());
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
    std::unique_ptr<Engine> held_engine;
    if (!rigid) {
      held_engine = make_engine(phase_.free_part(), sc_.solver, /*trial=*/false);
      held_engine->set_contact(&coupling_);
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
    FreeFlight free(*this);  // the free phase's roots and the impact (free_flight.hpp)
    auto start_free = [&]() { free.start(); };
    // Initial phase.
    bool in_contact = holonomic || (contact_ && F_ > 0.0);
    contact_ = in_contact;
    if (!in_contact) F_ = 0.0;
    Eigen::VectorXd yr, y1;
    if (in_contact && !rigid) held_engine->reinit(t_, held_from_full());
    if (!in_contact) start_free();
    const double dt_scan = std::min(1e-4, sc_.run.t_end / 100.0);
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      if (in_contact && cam_joint_impact()) {  // held on a C0 joint of the cam: its impact
        in_contact = contact_;
        if (!in_contact) start_free();
        else if (!rigid) held_engine->reinit(t_, held_from_full());
      }
      const double tout = next_stop_time();
      const double Ft = F_, Xdot_prev = cam_at(t_).Xdot, P_prev = dissipation_power();
      const double t_prev = t_;
      bool separation = false;
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
          // The reaction is known in closed form: adaptive Simpson on F·Ẋ_C over the
          // step to rtol of the step's ∫|F·Ẋ_C| (the trapezoid's O(h²) error reached
          // 3.5e-3 of the work on a fast speed ramp with 1e-4 steps; plain Simpson
          // left 1.2e-6 of case A's work at every rtol, the O(h²) error at the cam
          // spline's knots, where Ẍ_C has a kink).
          const double tm = 0.5 * (t_prev + t_);
          designer_.sample_force(tm, drive_.theta(tm), reaction_rigid(tm));
          dW_override = contact_work_rigid(t_prev, t_, Ft * Xdot_prev, F_ * cam_at(t_).Xdot);
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
        // Free flight: no contact work over the step (an impact at its end books its
        // impulse's work P·Ẋ_C itself), damping power at the pre-impact state.
        dW_override = 0.0;
        const FreeFlight::Outcome o = free.advance(tout, y1, &P_end, [&]() {
          return rigid ? reaction_rigid(t_) : reaction_held(t_, held_from_full().data());
        });
        if (o == FreeFlight::Outcome::Contact) {
          in_contact = true;
          if (!rigid) held_engine->reinit(t_, held_from_full());
        } else if (o == FreeFlight::Outcome::Restart) {
          start_free();
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
    if (held_engine) {
      sum_.rhs_evals += held_engine->stats().rhs_evals;
      sum_.engine_restarts += held_engine->stats().reinits;
    }
  }

};

}  // namespace

std::unique_ptr<RunContext> make_event_driven(const Scene& sc, std::shared_ptr<const FollowerModel> model,
                                      Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<EventDriven>(sc, std::move(model), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
