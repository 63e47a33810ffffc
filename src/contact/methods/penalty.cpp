// camdyn — the penalty baseline (every follower kind): every contact its own spring–damper law,
//   F_j = max(0, k_p,j s_j + c_p,j ŝ_j)  (linear)   or   k_p,j s_jⁿ(1 + c_p,j ŝ_j)  (Hunt–Crossley)
// while s_j = −g_j > 0 (ŝ_j = −ġ_j), inside the right-hand side; the engine steps natively
// with its own error control, lands on the output times, and restarts where a gap
// crosses zero (rootfinding: the force law has a kink there). Implicit engines get the
// exact Jacobian [[0, I], [−M⁻¹(K + Σ k̃_j t_jᵀt_j), −M⁻¹(C + Σ c̃_j t_jᵀt_j)]].
// Cam friction at an oscillating follower's pad (docs/contacts.md): a cam contact's law gives
// the normal force's share N a/ℓ_v of the force on X; the contact puts G_j(t) = 1 + κ_j
// times it on X (the friction's moment about the pivot), G_j from the held kinematics, so
// the Jacobian scales by G_j and the friction power beyond the held sliding speed,
// (G_j − 1)·F_law·ŝ_j, is booked as dissipated.
#include <Eigen/Dense>
#include <cmath>

#include "contact/contact_run.hpp"
#include "contact/laws/contact_law.hpp"
#include "contact/methods/bdf_order.hpp"

namespace camdyn {
namespace detail {
namespace {

class PenaltyMethod final : public ContactRun {
 public:
  PenaltyMethod(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
                 const std::atomic<bool>* stop)
      : ContactRun(sc, std::move(mech), obs, stop) {
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
            yv_ = Eigen::Map<const Eigen::VectorXd>(y, ny_);
            const CamMotion cm = cam_at(t);
            dFdg.resize(m_);
            dFdgd.resize(m_);
            for (int j = 0; j < m_; ++j) {
              double dq = 0, dv = 0;
              params(j).derivatives(-gap(j, yv_, cm), -gap_rate(j, yv_, cm), &dq, &dv);
              const double G = gain(j, t);
              dFdg[j] = -G * dq;
              dFdgd[j] = -G * dv;
            }
          };
      // a camshaft: the cam contacts' rows at the state and their stiffness at the laws' forces
      shaft_newton(*sn, [this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& F, Eigen::VectorXd& dFdgd) {
        const CamMotion cm = cam_at(t);
        for (int j = 0; j < m_; ++j) {
          double dq = 0, dv = 0;
          const double s = -gap(j, y, cm), sd = -gap_rate(j, y, cm);
          const double G = gain(j, t);
          F[j] = G * law(j, s, sd);
          params(j).derivatives(s, sd, &dq, &dv);
          dFdgd[j] = -G * dv;
        }
      });
    } else if (mk_.acceleration_jacobian(0.0, q0.data(), v0.data(), dq0, dv0))
      sys.jacobian = [this](double t, const double* y, Eigen::MatrixXd& J) {
        const Eigen::Map<const Eigen::VectorXd> Y(y, ny_);
        yv_ = Y;
        const CamMotion cm = cam_at(t);
        Eigen::MatrixXd dadq, dadv;
        mk_.acceleration_jacobian(t, y, y + n_, dadq, dadv);
        for (int j = 0; j < m_; ++j) {
          double dq = 0, dv = 0;  // dF/ds, dF/dŝ
          params(j).derivatives(-gap(j, yv_, cm), -gap_rate(j, yv_, cm), &dq, &dv);
          const double G = gain(j, t);
          dq *= G;
          dv *= G;
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
    // cvode-bdf's order limits (cvode_bdf_order, methods/bdf_order.hpp)
    set_cvode_bdf_order(sc, *mech_, sys);
    engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, sys, false));
    eng_ = engines_.back().get();
  }

 private:
  OdeEngine* eng_;
  Eigen::VectorXd yv_;
  mutable Eigen::VectorXd pot_y_;  // contact_potential's state
  bool penetration_checked() const override { return false; }  // the law penetrates

  // The penalty law of contact j; its force at penetration s and its rate ŝ (el: the elastic part).
  const PenaltyNormalLaw& params(int j) const { return mk_.contacts()[j].law.penalty; }
  double law(int j, double s, double sd, double* el = nullptr) const { return params(j).force(s, sd, el); }
  /// The factor G_j(t) on contact j's law force: 1 + κ at a cam contact with pad friction
  /// (designer_columns.hpp PadFriction), else 1.
  double gain(int j, double t) const {
    if (!design_cols_.pad_friction_on() || !mk_.contacts()[j].cam) return 1.0;
    return design_cols_.contact_gain(cam_.evaluate(drive_.theta(t)), drive_.omega(t));
  }
  void forces(double t, const Eigen::VectorXd& y, Eigen::VectorXd& F) const {
    const CamMotion cm = cam_at(t);
    F.resize(m_);
    for (int j = 0; j < m_; ++j) F[j] = law(j, -gap(j, y, cm), -gap_rate(j, y, cm));
    if (design_cols_.pad_friction_on())
      for (int j = 0; j < m_; ++j) F[j] *= gain(j, t);
  }
  double contact_potential(double t, const double* q) const override {
    const CamMotion cm = cam_at(t);
    double V = 0.0;
    Eigen::VectorXd& y = pot_y_;  // gap() reads q only
    y.resize(2 * n_);
    y.head(n_) = Eigen::Map<const Eigen::VectorXd>(q, n_);
    for (int j = 0; j < m_; ++j) {
      const double s = -gap(j, y, cm);
      if (s > 0.0) V += params(j).energy(s);
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
      if (s > 0.0 && design_cols_.pad_friction_on()) P += (gain(j, t) - 1.0) * F * sd;
    }
    return P;
  }

  void prepare_start() override {
    // The penalty's own equilibrium at t = 0: the closed contacts start penetrated by the s_j
    // at which their laws (ŝ as at the start) carry the forces of the acceleration level, from
    // wherever they start on the contact (gap 0, or inside by at most s_j + tol_u: the start
    // check, src/run/initial_check.hpp), solved by Newton on the shift μ (q → q − Pμ):
    //  * a single follower (rigid, elastic_bar): the dynamic equilibrium, the forces at the
    //    shifted state, g̈_S = 0,
    //      r(μ) = T_S a_free(q − Pμ) + W_SS F(s(μ)) − Ẍ_C,S = 0,   s(μ) = −g_S(q) + T_S P μ,
    //    the follower moved rigidly (P = 1: its preloaded shape kept, only the return spring
    //    relaxes, so F(0) = F₀ k_p/(k_p + k) for a rigid one); ∂(T_S a_free)/∂μ by columns at
    //    shifts of the static s (exact for a linear mechanism: a linear law takes one step);
    //  * a network: F(s(μ)) = F_S of the unshifted state, by the M-weighted smallest shift
    //    P = M⁻¹T_Sᵀ (a network has no rigid shift, and along M⁻¹T_Sᵀ a lumped bar's contact
    //    node alone moves: the dynamic balance would load its first element, 2 % on the bar
    //    of tests/contact/test_initial_state.cpp).
    std::vector<int> set = active_list();
    if (!set.empty()) start_equilibrium(set);
    forces(0.0, y_, F_);
    for (int j = 0; j < m_; ++j) active_[j] = F_[j] > 0.0;
  }

  void start_equilibrium(const std::vector<int>& set) {
    const int k = int(set.size());
    const CamMotion cm0 = cam_at(0.0);
    const Eigen::VectorXd q0 = y_.head(n_), v0 = y_.segment(n_, n_);
    const bool one_body = mk_.traits().one_body;  // its static correction: the rigid translation
    Eigen::MatrixXd P(n_, k), TP(k, k), Wss(k, k);
    Eigen::VectorXd g0(k), sd(k), mu(k), s_static(k), Fs(k);
    for (int i = 0; i < k; ++i) {
      const int j = set[i];
      P.col(i) = one_body ? Eigen::VectorXd::Ones(n_) : Eigen::VectorXd(mk_.MinvTt().col(j));
      g0[i] = gap(j, y_, cm0);
      Fs[i] = F_[j];
      sd[i] = -gap_rate(j, y_, cm0);
      s_static[i] = params(j).depth_at(F_[j] / gain(j, 0.0));
      for (int l = 0; l < k; ++l) Wss(i, l) = mk_.W()(j, set[l]);
    }
    for (int i = 0; i < k; ++i)
      for (int l = 0; l < k; ++l) TP(i, l) = mk_.contacts()[set[i]].t.dot(P.col(l));
    // g̈_S of the free motion at q − Pμ (its T a_free part)
    Eigen::VectorXd Ta, q(n_);
    auto free_acc = [&](const Eigen::VectorXd& m, Eigen::VectorXd& out) {
      if (!one_body) {  // the network's: the forces of the unshifted state, r = W_SS(F(s) − F_S)
        out = -Wss * Fs;
        return;
      }
      q = q0 - P * m;
      mk_.contact_free_acceleration(0.0, q.data(), v0.data(), Ta);
      out.resize(k);
      for (int i = 0; i < k; ++i) out[i] = Ta[set[i]] - cam_acc(set[i], cm0);
    };
    const auto tp_solve = TP.completeOrthogonalDecomposition();
    mu = tp_solve.solve(s_static + g0);  // the static start
    Eigen::VectorXd b0, b1, s, F(k), dF(k), r;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(k, k), J(k, k);
    free_acc(mu, b0);
    for (int i = 0; one_body && i < k; ++i) {  // ∂(T_S a_free)/∂μ by columns (exact for a linear mechanism)
      const double d = std::max(std::abs(mu[i]), 1e-12 * (1.0 + q0.cwiseAbs().maxCoeff()));
      Eigen::VectorXd m1 = mu;
      m1[i] += d;
      free_acc(m1, b1);
      A.col(i) = (b1 - b0) / d;
    }
    for (int it = 0; it < 50; ++it) {
      free_acc(mu, b0);
      s = TP * mu - g0;
      for (int i = 0; i < k; ++i) {
        double dq = 0, dv = 0;
        const double G = gain(set[i], 0.0);
        F[i] = G * law(set[i], s[i], sd[i]);
        params(set[i]).derivatives(s[i], sd[i], &dq, &dv);
        dF[i] = G * dq;
      }
      r = b0 + Wss * F;
      J = A + Wss * dF.asDiagonal() * TP;
      const Eigen::VectorXd dmu = J.completeOrthogonalDecomposition().solve(r);
      mu -= dmu;
      if (dmu.cwiseAbs().maxCoeff() <= 1e-15 * mu.cwiseAbs().maxCoeff()) break;
    }
    y_.head(n_) = q0 - P * mu;
  }

  void run_method() override {
    // every gap is a root: the law's kink
    eng_->set_roots(m_, [this](double t, const double* y, double* g) {
      const Eigen::Map<const Eigen::VectorXd> Y(y, ny_);
      yv_ = Y;
      const CamMotion cm = cam_at(t);
      for (int j = 0; j < m_; ++j) g[j] = gap(j, yv_, cm);
    });
    eng_->reinit(t_, y_);
    Eigen::VectorXd y1(ny_), Fprev;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_stop_time();
      Fprev = F_;
      const double P_prev = dissipation_power(t_, y_);
      const double t1 = eng_->advance(tout, y1);
      eng_->keep_dense_rhs(true);  // the step's interpolant, read by its energy and trace
      const double h = t1 - t_;
      t_ = t1;
      y_ = y1;
      forces(t_, y_, F_);
      // the cam's work and the dissipated energy: each step's own quadrature on the engine's
      // dense output (before a restart; the step ends on the law's kink: a root; smooth inside)
      const StepEnergy dE = step_energy(
          t_ - h, t_, [this](double tau, Eigen::VectorXd& y) { eng_->dense(tau, y); },
          [this](double tau, const Eigen::VectorXd& y, const CamMotion&, Eigen::VectorXd& F) { forces(tau, y, F); });
      trace_step(
          t_ - h, t_, [this](double tau, Eigen::VectorXd& y) { eng_->dense(tau, y); },
          [this](double tau, const Eigen::VectorXd& y, const CamMotion&, Eigen::VectorXd& F) { forces(tau, y, F); },
          active_list(), /*energy_alike=*/true, &y_, &F_);
      eng_->keep_dense_rhs(false);
      const CamMotion cm = cam_at(t_);
      for (int j = 0; j < m_; ++j) {
        const bool now = F_[j] > 0.0 || (eng_->hit_root() && eng_->root_info()[j] < 0);
        if (!active_[j] && now) {
          ++rec_.impacts;
          record_event(EventKind::Impact, j, -gap_rate(j, y_, cm));
        } else if (active_[j] && !now) {
          ++rec_.separations;
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

std::unique_ptr<ContactRun> make_penalty_method(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                                Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<PenaltyMethod>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
