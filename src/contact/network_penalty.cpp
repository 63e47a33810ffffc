// camdyn — the penalty baseline on a network: every contact its own spring–damper law,
//   F_j = max(0, k_p,j s_j + c_p,j ŝ_j)  (linear)   or   k_p,j s_jⁿ(1 + c_p,j ŝ_j)  (Hunt–Crossley)
// while s_j = −g_j > 0 (ŝ_j = −ġ_j), inside the right-hand side; the engine steps natively
// with its own error control, lands on the output times, and restarts where a gap
// crosses zero (rootfinding: the force law has a kink there). Implicit engines get the
// exact Jacobian [[0, I], [−M⁻¹(K + Σ k̃_j t_jᵀt_j), −M⁻¹(C + Σ c̃_j t_jᵀt_j)]].
#include <Eigen/Dense>
#include <cmath>

#include "network_run.hpp"
#include "penalty_law.hpp"
#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

class NetworkPenalty final : public NetworkRun {
 public:
  NetworkPenalty(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
                 const std::atomic<bool>* stop)
      : NetworkRun(sc, std::move(mech), obs, stop) {
    OdeSystem sys = contact_system([this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& F) {
      forces(t, y, F);
    });
    Eigen::MatrixXd dq0, dv0;
    const Eigen::VectorXd q0 = mk_.q0(), v0 = mk_.v0();
    // a Mechanism: the sparse Newton structure with the laws' derivatives along the
    // contacts, K̃ = K + dF/ds TᵀT (F = f(s, ŝ), s = −g)
    if (auto sn = sparse_newton()) {
      sys.newton = sn;
      sn->contact_derivatives =
          [this](double t, const double* y, Eigen::VectorXd& dFdg, Eigen::VectorXd& dFdgd) {
            yv_ = Eigen::Map<const Eigen::VectorXd>(y, 2 * n_);
            const CamMotion cm = cam_at(t);
            dFdg.resize(m_);
            dFdgd.resize(m_);
            for (int j = 0; j < m_; ++j) {
              double dq = 0, dv = 0;
              penalty_derivatives(params(j), -gap(j, yv_, cm), -gap_rate(j, yv_, cm), &dq, &dv);
              dFdg[j] = -dq;
              dFdgd[j] = -dv;
            }
          };
    } else if (mk_.acceleration_jacobian(0.0, q0.data(), v0.data(), dq0, dv0))
      sys.jacobian = [this](double t, const double* y, Eigen::MatrixXd& J) {
        const Eigen::Map<const Eigen::VectorXd> Y(y, 2 * n_);
        yv_ = Y;
        const CamMotion cm = cam_at(t);
        Eigen::MatrixXd dadq, dadv;
        mk_.acceleration_jacobian(t, y, y + n_, dadq, dadv);
        for (int j = 0; j < m_; ++j) {
          double dq = 0, dv = 0;  // dF/ds, dF/dŝ
          penalty_derivatives(params(j), -gap(j, yv_, cm), -gap_rate(j, yv_, cm), &dq, &dv);
          // F = f(s, ŝ), s = −T_j q: ∂(M⁻¹T_jᵀF)/∂q = −dq M⁻¹T_jᵀT_j
          const Eigen::RowVectorXd& tj = mk_.contacts()[j].t;
          dadq.noalias() -= dq * mk_.MinvTt().col(j) * tj;
          dadv.noalias() -= dv * mk_.MinvTt().col(j) * tj;
        }
        J.setZero();
        J.topRightCorner(n_, n_).setIdentity();
        J.bottomLeftCorner(n_, n_) = dadq;
        J.bottomRightCorner(n_, n_) = dadv;
      };
    engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, sys, false));
    eng_ = engines_.back().get();
  }

 private:
  OdeEngine* eng_;
  Eigen::VectorXd yv_;
  bool penetration_checked() const override { return false; }  // the law penetrates

  // The law of contact j at penetration s and its rate ŝ; el: the elastic part.
  PenaltyParams params(int j) const {
    const MechanismContact& c = mk_.contacts()[j];
    return {sc_.contact.penalty_law, c.penalty_stiffness, c.penalty_damping, sc_.contact.penalty_exponent};
  }
  double law(int j, double s, double sd, double* el = nullptr) const {
    return penalty_force(params(j), s, sd, el);
  }
  void forces(double t, const Eigen::VectorXd& y, Eigen::VectorXd& F) const {
    const CamMotion cm = cam_at(t);
    F.resize(m_);
    for (int j = 0; j < m_; ++j) F[j] = law(j, -gap(j, y, cm), -gap_rate(j, y, cm));
  }
  double contact_potential(double t, const double* q) const override {
    const CamMotion cm = cam_at(t);
    double V = 0.0;
    for (int j = 0; j < m_; ++j) {
      const MechanismContact& c = mk_.contacts()[j];
      const double s = -(c.t.dot(Eigen::Map<const Eigen::VectorXd>(q, n_)) + c.g0 - (c.cam ? cm.X : 0.0));
      if (s > 0.0) V += penalty_energy(params(j), s);
    }
    return V;
  }
  double contact_dissipation(double t, const Eigen::VectorXd& y) const override {
    const CamMotion cm = cam_at(t);
    double P = 0.0;
    for (int j = 0; j < m_; ++j) {
      const double s = -gap(j, y, cm), sd = -gap_rate(j, y, cm);
      double el = 0.0;
      const double F = law(j, s, sd, &el);
      if (s > 0.0) P += (F - el) * sd;
    }
    return P;
  }

  void prepare_start() override {
    // The penalty's own equilibrium at t = 0: each contact carrying force F_j starts
    // penetrated by the s_j its law needs (ŝ = 0), by the M-weighted smallest shift, from
    // wherever it starts on the contact (gap 0, or inside by at most s_j + tol_u: the
    // start check, src/initial_check.hpp).
    std::vector<int> set = active_list();
    if (!set.empty()) {
      const int k = int(set.size());
      Eigen::VectorXd s(k);
      Eigen::MatrixXd Wss(k, k), MTs(n_, k);
      const CamMotion cm0 = cam_at(0.0);
      for (int i = 0; i < k; ++i) {
        const int j = set[i];
        const double kp = mk_.contacts()[j].penalty_stiffness;
        s[i] = sc_.contact.penalty_law == PenaltyLaw::Linear ? F_[j] / kp
                                                              : std::pow(F_[j] / kp, 1.0 / sc_.contact.penalty_exponent);
        s[i] += gap(j, y_, cm0);  // shift to the gap −s_j
        MTs.col(i) = mk_.MinvTt().col(j);
        for (int l = 0; l < k; ++l) Wss(i, l) = mk_.W()(j, set[l]);
      }
      y_.head(n_) -= MTs * Wss.completeOrthogonalDecomposition().solve(s);
    }
    forces(0.0, y_, F_);
    for (int j = 0; j < m_; ++j) active_[j] = F_[j] > 0.0;
  }

  void run_method() override {
    // every gap is a root: the law's kink
    eng_->set_roots(m_, [this](double t, const double* y, double* g) {
      const Eigen::Map<const Eigen::VectorXd> Y(y, 2 * n_);
      yv_ = Y;
      const CamMotion cm = cam_at(t);
      for (int j = 0; j < m_; ++j) g[j] = gap(j, yv_, cm);
    });
    eng_->reinit(t_, y_);
    Eigen::VectorXd y1(2 * n_), Fprev;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_stop_time();
      Fprev = F_;
      const double P_prev = dissipation_power(t_, y_);
      const double t1 = eng_->advance(tout, y1);
      const double h = t1 - t_;
      t_ = t1;
      y_ = y1;
      forces(t_, y_, F_);
      // the cam's work and the dissipated energy: each step's own quadrature on the engine's
      // dense output (before a restart; the step ends on the law's kink: a root; smooth inside)
      const StepEnergy dE = step_energy(
          t_ - h, t_, [this](double tau, Eigen::VectorXd& y) { eng_->dense(tau, y); },
          [this](double tau, const Eigen::VectorXd& y, const CamMotion&, Eigen::VectorXd& F) { forces(tau, y, F); });
      const CamMotion cm = cam_at(t_);
      for (int j = 0; j < m_; ++j) {
        const bool now = F_[j] > 0.0 || (eng_->hit_root() && eng_->root_info()[j] < 0);
        if (!active_[j] && now) {
          ++sum_.impacts;
          record_event(EventKind::Impact, j, -gap_rate(j, y_, cm));
        } else if (active_[j] && !now) {
          ++sum_.separations;
          record_event(EventKind::Separation, j, 0.0);
        }
        active_[j] = now;
      }
      if (eng_->hit_root()) eng_->reinit(t_, y_);  // the law's kink: restart the history
      after_step(h, dE.work, P_prev, NAN, dE.dissipated);
    }
  }
};

}  // namespace

std::unique_ptr<NetworkRun> make_network_penalty(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                                 Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<NetworkPenalty>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
