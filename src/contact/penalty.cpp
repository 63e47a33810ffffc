// camdyn — the penalty baseline (Cardona–Géradin): F = max(0, k_p s + c_p ŝ) while s > 0
// (or Hunt–Crossley k_p sⁿ(1 + c_p ŝ)) inside the right-hand side; the engine steps
// natively with its own error control and lands on the output times.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "penalty_law.hpp"
#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

// The law on the contact node: s = X_C − q₀ (penetration), ŝ = Ẋ_C − v₀.
class PenaltyForce final : public ContactForce {
 public:
  PenaltyForce(const Cam& cam, const CamDrive& drive, const PenaltyParams& p) : cam_(cam, drive), p_(p) {}
  double force(double t, double q0, double v0) const override {
    const CamMotion m = cam_.at(t);
    return penalty_force(p_, m.X - q0, m.Xdot - v0);
  }
  void derivatives(double t, double q0, double v0, double* dFdq, double* dFdv) const override {
    const CamMotion m = cam_.at(t);
    double dFds, dFdsd;
    penalty_derivatives(p_, m.X - q0, m.Xdot - v0, &dFds, &dFdsd);
    *dFdq = -dFds;
    *dFdv = -dFdsd;
  }
  double elastic_force(double t, double q0) const {
    const CamMotion m = cam_.at(t);
    double el = 0.0;
    penalty_force(p_, m.X - q0, 0.0, &el);
    return el;
  }
  double stored_energy(double t, double q0) const { return penalty_energy(p_, cam_.at(t).X - q0); }

 private:
  CamPath cam_;
  PenaltyParams p_;
};

class Penalty final : public RunContext {
 public:
  Penalty(const Scene& sc, std::shared_ptr<const FollowerModel> model, Observer* obs, const std::atomic<bool>* stop)
      : RunContext(sc, std::move(model), obs, stop),
        law_(cam_, drive_,
             {sc.contact.penalty_law, sc.contact.penalty_stiffness, sc.contact.penalty_damping,
              sc.contact.penalty_exponent}) {}

 private:
  PenaltyForce law_;

  // (the law acts once set on the engine, at the start state)
  double contact_potential() const override { return engine_->contact() ? law_.stored_energy(t_, y_[0]) : 0.0; }
  double contact_dissipation() const override {
    return engine_->contact() ? (F_ - law_.elastic_force(t_, y_[0])) * (cam_at(t_).Xdot - y_[n_]) : 0.0;
  }
  void prepare_start(const CamMotion& cm0, bool touching) override {
    if (touching && F_ > 0.0) y_.head(n_).array() -= penalty_start_penetration(cm0.Xddot);
    // ŝ = 0 at t = 0: the force the penalty law gives there (also in the t = 0 row).
    engine_->set_contact(&law_);
    F_ = law_.force(0.0, y_[0], y_[n_]);
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

  void run_method() override {
    engine_->set_contact(&law_);
    engine_->reinit(t_, y_);
    Eigen::VectorXd y1(2 * n_);
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_stop_time();
      const double Ft = F_;
      const double Xdot_prev = cam_at(t_).Xdot;
      const double P_prev = dissipation_power();
      const double t1 = engine_->advance(tout, y1);
      const double h = t1 - t_;
      t_ = t1;
      y_ = y1;
      F_ = law_.force(t_, y_[0], y_[n_]);
      const bool now_contact = F_ > 0.0;
      if (!contact_ && now_contact) {
        ++sum_.impacts;
        record_event(EventKind::Impact, cam_at(t_).Xdot - y_[n_]);
      } else if (contact_ && !now_contact) {
        ++sum_.separations;
        record_event(EventKind::Separation, 0.0);
      }
      contact_ = now_contact;
      after_step(h, trapezoid_work(h, Ft, Xdot_prev), P_prev);
    }
  }

};

}  // namespace

std::unique_ptr<RunContext> make_penalty(const Scene& sc, std::shared_ptr<const FollowerModel> model,
                                      Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<Penalty>(sc, std::move(model), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
