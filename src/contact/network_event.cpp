// camdyn — the event-driven method on a network: the active contacts are constraint rows,
//   M q̈ = f₀ − K q − C q̇ + T_Aᵀ F_A,   W_AA F_A = Ẍ_C,A − T_A M⁻¹(f₀ − K q − C q̇)
// (the acceleration level of every active contact, g̈_A = 0), integrated natively with the
// engine's error control. Rootfinding on one function per contact: the force F_j of an
// active contact (it separates where F_j reaches zero) and the gap g_j of an open one (it
// impacts where g_j reaches zero). At an impact all contacts taking part get a Newton
// impulse at once (network_run.cpp: resolve_impact), then the engine restarts.
//
// The acceleration level alone lets the closed gaps drift (g̈_A = 0 integrated: g_A and ġ_A
// carry the integration error, −1.8e-8 m at rtol 1e-8 on a valve train, and a tappet that
// creeps into the cam after a seat impact). The displacement and velocity levels are held
// by projecting every accepted step's end state onto g_A = 0, ġ_A = 0, M-orthogonally
// (the smallest correction in kinetic-energy metric):
//   Δq = −M⁻¹T_Aᵀ W_AA⁺ g_A,   Δv = −M⁻¹T_Aᵀ W_AA⁺ ġ_A   (W_AA⁺: minimum-norm least squares)
// — on cvode-bdf inside CVODE's step (CVodeSetProjFn), on arkode-erk / arkode-dirk after
// the step, the stepper reset there (ode_engine.hpp: set_projection).
#include <Eigen/Dense>
#include <Eigen/QR>
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
    // A Mechanism: the sparse Newton structure, bordered with the held contacts' rows (the
    // exact Jacobian of the acceleration level); a user's follower: SUNDIALS' difference
    // quotients (the constraint forces couple every unknown).
    if (auto sn = sparse_newton()) {
      sn->held = &set_;
      sys.newton = sn;
    }
    engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, sys, false));
    eng_ = engines_.back().get();
    eng_->set_projection([this](double t, const double* y, double* corr) { project(t, y, corr); });
  }

 private:
  OdeEngine* eng_;
  Eigen::VectorXd yv_, yg_;
  std::vector<int> set_;  // the active set the right-hand side uses
  double gap_thr_ = 1e-3 * sc_.contact.tol_u;
  // A contact released where its force reaches zero leaves at zero gap, speed and
  // (nearly) acceleration: for a while its gap is the integration error of the steps after the
  // release, of order rtol·|q| + atol — above gap_thr_ at tight tol_u (a user follower on
  // cvode-bdf at rtol 1e-10, tol_u 1e-11: 20 "impacts" of ~1e-11 m/s 3e-10 s apart). Its
  // root sits at −fresh_thr_ until its gap has once exceeded fresh_thr_ (the sign of its
  // root function does not change at the switch).
  double fresh_thr_ = 10.0 * (sc_.solver.rtol * std::max(cam_.lift(), mk_.q0().cwiseAbs().maxCoeff()) +
                              sc_.solver.atol);
  std::vector<char> fresh_ = std::vector<char>(std::size_t(m_), 0);
  double open_thr(int j) const { return fresh_[std::size_t(j)] ? std::max(gap_thr_, fresh_thr_) : gap_thr_; }

  // The projection onto the active set's g = 0, ġ = 0 (see the top): M⁻¹T_Aᵀ and the
  // factorisation of W_AA, made once per active set.
  Eigen::MatrixXd MTa_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> Waa_;
  Eigen::VectorXd pg_, pgd_;

  void restart() {
    set_ = active_list();
    for (int j : set_) fresh_[std::size_t(j)] = 0;
    const int k = int(set_.size());
    MTa_.resize(n_, k);
    Eigen::MatrixXd Waa(k, k);
    for (int i = 0; i < k; ++i) {
      MTa_.col(i) = mk_.MinvTt().col(set_[i]);
      for (int l = 0; l < k; ++l) Waa(i, l) = mk_.W()(set_[i], set_[l]);
    }
    if (k) Waa_.compute(Waa);
    // the state the engine starts from is on the active set's manifold too
    if (k) {
      Eigen::VectorXd corr(2 * n_);
      project(t_, y_.data(), corr.data());
      y_ += corr;
    }
    eng_->reinit(t_, y_);
  }

  void project(double t, const double* y, double* corr) {
    const int k = int(set_.size());
    Eigen::Map<Eigen::VectorXd> C(corr, 2 * n_);
    if (k == 0) {
      C.setZero();
      return;
    }
    const CamMotion cm = cam_at(t);
    pg_.resize(k);
    pgd_.resize(k);
    const Eigen::Map<const Eigen::VectorXd> Q(y, n_), V(y + n_, n_);
    for (int i = 0; i < k; ++i) {
      const MechanismContact& c = mk_.contacts()[set_[i]];
      pg_[i] = c.t.dot(Q) + c.g0 - (c.cam ? cm.X : 0.0);
      pgd_[i] = c.t.dot(V) - (c.cam ? cm.Xdot : 0.0);
    }
    C.head(n_).noalias() = -MTa_ * Waa_.solve(pg_);
    C.tail(n_).noalias() = -MTa_ * Waa_.solve(pgd_);
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
      for (int j = 0; j < m_; ++j) g[j] = active_[j] ? F[j] + F_thr : gap(j, yv_, cm) + open_thr(j);
    });
    restart();
    Eigen::VectorXd y1(2 * n_);
    const double gap_thr = gap_thr_;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_stop_time();
      const double P_prev = dissipation_power(t_, y_);
      const double t1 = eng_->advance(tout, y1);
      const double h = t1 - t_;
      t_ = t1;
      y_ = y1;
      const CamMotion cm = cam_at(t_);
      F_ = held_forces(t_, y_, cm, set_);
      if (m_) F_ref_ = std::max(F_ref_, F_.cwiseAbs().maxCoeff());
      // the cam's work and the dissipated energy over the step: 3-point Gauss–Legendre on
      // the engine's own dense output (the trapezoid on step ends was 3e-4 of the work off
      // on a rigid follower that CVODE/ERK step across in 150 steps per revolution)
      const StepEnergy dE = step_energy(
          t_ - h, t_, [this](double tau, Eigen::VectorXd& y) { eng_->dense(tau, y); },
          [this](double tau, const Eigen::VectorXd& y, const CamMotion& c, Eigen::VectorXd& F) {
            if (set_.empty())
              F.setZero(m_);
            else
              F = held_forces(tau, y, c, set_);
          });
      const double P_end = dissipation_power(t_, y_);
      for (int j = 0; j < m_; ++j)  // a released contact that has opened: the normal root
        if (fresh_[std::size_t(j)] && !active_[j] && gap(j, y_, cm) > fresh_thr_) fresh_[std::size_t(j)] = 0;
      bool changed = false;
      if (eng_->hit_root() && unilateral_) {
        std::vector<int> closing;
        bool released = false;
        for (int j = 0; j < m_; ++j) {
          if (eng_->root_info()[j] >= 0) continue;  // only downward crossings act
          if (active_[j]) {
            active_[j] = 0;
            fresh_[std::size_t(j)] = 1;
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
          if (!active_[j] && eng_->root_info()[j] == 0 && gap(j, y_, cm) <= std::max(gap_thr, open_thr(j)) &&
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
      if (changed) {
        restart();  // projects onto the new active set
      } else if (eng_->hit_root() && !set_.empty()) {
        // a root that changed nothing: the interpolated state, put on the closed contacts
        // (a copy: the engine goes on from its own step end)
        Eigen::VectorXd corr(2 * n_);
        project(t_, y_.data(), corr.data());
        y_ += corr;
        F_ = held_forces(t_, y_, cm, set_);
      }
      after_step(h, dE.work, P_prev, changed ? P_end : NAN, dE.dissipated);
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
