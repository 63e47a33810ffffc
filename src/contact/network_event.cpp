// camdyn — the event-driven method on a network: the active contacts are constraint rows,
//   M q̈ = f₀ − K q − C q̇ + T_Aᵀ F_A,   W_AA F_A = Ẍ_C,A − T_A M⁻¹(f₀ − K q − C q̇)
// (the acceleration level of every active contact, g̈_A = 0), integrated natively with the
// engine's error control. Rootfinding on one function per contact: the force F_j of an
// active contact (it separates where F_j reaches zero) and the gap g_j of an open one (it
// impacts where g_j reaches zero). At an impact all contacts taking part get a Newton
// impulse at once (network_run.cpp: resolve_impact), then the engine restarts.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "network_run.hpp"
#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

class NetworkEvent final : public NetworkRun {
 public:
  NetworkEvent(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
               const std::atomic<bool>* stop)
      : NetworkRun(sc, std::move(mech), obs, stop) {
    OdeSystem sys = contact_system([this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& F) {
      F = held_forces(t, y, cam_at(t), set_);
    });
    // Jacobian: SUNDIALS' difference quotients (the constraint forces couple every unknown).
    engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, sys, false));
    eng_ = engines_.back().get();
  }

 private:
  OdeEngine* eng_;
  Eigen::VectorXd yv_, yg_;
  std::vector<int> set_;  // the active set the right-hand side uses
  double gap_thr_ = 1e-3 * sc_.contact.tol_u;

  void restart() {
    set_ = active_list();
    eng_->reinit(t_, y_);
  }

  void run_method() override {
    eng_->set_roots(m_, [this](double t, const double* y, double* g) {
      const Eigen::Map<const Eigen::VectorXd> Y(y, 2 * n_);
      yv_ = Y;
      const CamMotion cm = cam_at(t);
      Eigen::VectorXd F;  // the separation function of the active contacts (force units)
      if (!set_.empty()) held_forces(t, yv_, cm, set_, &F);
      // Offsets keep every function away from zero at a restart (SUNDIALS stops with
      // "root found at and very near t" on a function that stays at zero): a gap triggers
      // at −10⁻³ tol_u, an active contact's margin F − g̈/W_jj (its force while held, −its
      // opening acceleration as a force once complementarity opens it) at −10⁻¹² of the
      // largest force so far.
      const double F_thr = 1e-12 * std::max(F_ref_, mk_.force_scale());
      for (int j = 0; j < m_; ++j) g[j] = active_[j] ? F[j] + F_thr : gap(j, yv_, cm) + gap_thr_;
    });
    restart();
    Eigen::VectorXd y1(2 * n_);
    const double gap_thr = gap_thr_;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_output_time();
      const double P_prev = dissipation_power(t_, y_);
      const double t1 = eng_->advance(tout, y1);
      const double h = t1 - t_;
      t_ = t1;
      y_ = y1;
      const CamMotion cm = cam_at(t_);
      F_ = held_forces(t_, y_, cm, set_);
      if (m_) F_ref_ = std::max(F_ref_, F_.cwiseAbs().maxCoeff());
      // the cam's work over the step: 3-point Gauss–Legendre on the engine's own dense
      // output (the trapezoid on step ends was 3e-4 of the work off on a rigid follower
      // that CVODE/ERK step across in 150 steps per revolution)
      double dW = 0.0;
      if (!set_.empty() && h > 0) {
        static const double xg[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
        static const double wg[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
        for (int g = 0; g < 3; ++g) {
          const double tau = t_ - h + 0.5 * h * (1.0 + xg[g]);
          eng_->dense(tau, yg_);
          const CamMotion cg = cam_at(tau);
          dW += 0.5 * h * wg[g] * cam_power(held_forces(tau, yg_, cg, set_), cg);
        }
      }
      const double P_end = dissipation_power(t_, y_);
      bool changed = false;
      if (eng_->hit_root() && unilateral_) {
        std::vector<int> closing;
        bool released = false;
        for (int j = 0; j < m_; ++j) {
          if (eng_->root_info()[j] >= 0) continue;  // only downward crossings act
          if (active_[j]) {
            active_[j] = 0;
            ++sum_.separations;
            record_event(EventKind::Separation, j, 0.0);
            released = true;
          } else if (gap_rate(j, y_, cm) < 0.0) {
            // a gap that crosses its root while opening is the engine's interpolation
            // error around a contact that has just let go (CVODE: 61 phantom re-closures
            // in 5 revolutions of the OHC train at 75 rev/s): no impact
            closing.push_back(j);
          }
        }
        // other open contacts closing at the same instant take part too (not one that
        // has just been released: it leaves at zero speed)
        const double v_eps = 1e-6 * v_impact_ref_;
        for (int j = 0; j < m_; ++j)
          if (!active_[j] && eng_->root_info()[j] == 0 && gap(j, y_, cm) <= gap_thr &&
              gap_rate(j, y_, cm) < -v_eps)
            closing.push_back(j);
        if (!closing.empty())
          resolve_impact(closing, cm);
        else if (released)
          settle_active(cm);
        changed = !closing.empty() || released;
      } else if (eng_->hit_root()) {  // bilateral: a contact that closes stays closed
        std::vector<int> closing;
        for (int j = 0; j < m_; ++j)
          if (!active_[j] && eng_->root_info()[j] < 0 && gap_rate(j, y_, cm) < 0.0) closing.push_back(j);
        if (!closing.empty()) {
          resolve_impact(closing, cm);
          changed = true;
        }
      }
      for (int j : set_)
        if (active_[j] && unilateral_) F_[j] = std::max(F_[j], 0.0);
      if (changed) restart();
      after_step(h, dW, P_prev, changed ? P_end : NAN);
    }
  }
};

}  // namespace

std::unique_ptr<NetworkRun> make_network_event(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                               Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<NetworkEvent>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
