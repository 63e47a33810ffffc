// camdyn — the event-driven method (any follower): the active contacts are constraint rows,
//   M q̈ = f₀ − K q − C q̇ + T_Aᵀ F_A,   W_AA F_A = Ẍ_C,A − T_A M⁻¹(f₀ − K q − C q̇)
// (the acceleration level of every active contact, g̈_A = 0), integrated natively with the
// engine's error control. Rootfinding on one function per contact: the force F_j of an
// active contact (it separates where F_j reaches zero) and the gap g_j of an open one (it
// impacts where g_j reaches zero). At an impact all contacts taking part get a Newton
// impulse at once (contact_run.cpp: resolve_impact), then the engine restarts.
//
// The acceleration level alone lets the closed gaps drift (g̈_A = 0 integrated: g_A and ġ_A
// carry the integration error, −1.8e-8 m at rtol 1e-8 on a valve train, and a tappet that
// creeps into the cam after a seat impact). The displacement and velocity levels are held
// by projecting every accepted step's end state onto g_A = 0, ġ_A = 0, M-orthogonally
// (the smallest correction in kinetic-energy metric):
//   Δq = −M⁻¹T_Aᵀ W_AA⁺ g_A,   Δv = −M⁻¹T_Aᵀ W_AA⁺ ġ_A   (W_AA⁺: minimum-norm least squares)
// — on cvode-bdf inside CVODE's step (CVodeSetProjFn), on arkode-erk / arkode-dirk after
// the step, the stepper reset there (ode_engine.hpp: set_projection); a root's state too.
// Steps land on the cam's breakpoints and see the cam one-sided there (their own segment):
// where its acceleration jumps under held contacts the engine restarts (enter_segment).
#include "contact/methods/event.hpp"

#include <algorithm>
#include <cmath>

#include "cam/joints.hpp"  // one_sided_motion
#include "contact/methods/bdf_order.hpp"

namespace camdyn {
namespace detail {

EventMethod::EventMethod(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
                           const std::atomic<bool>* stop)
    : ContactRun(sc, std::move(mech), obs, stop) {
  stick_gap_tol_ = gap_tol_;  // an impact's sticking speed from the gap tolerance the roots use
  OdeSystem sys = contact_system([this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& F) {
    held_forces_into(t, y, cam_at(t), set_, F);
  });
  // A Mechanism: the sparse Newton structure, bordered with the held contacts' rows (the
  // exact Jacobian of the acceleration level). A user's follower with a force Jacobian: the
  // dense J = [0 I; P ∂a/∂q P ∂a/∂v], P = I − M⁻¹T_Sᵀ W_SS⁺ T_S the held set's projection
  // (a = a_free + M⁻¹T_SᵀF_S with F_S = W_SS⁻¹(Ẍ_C,S − T_S a_free): ∂a/∂y = P ∂a_free/∂y);
  // without one, SUNDIALS' difference quotients.
  if (auto sn = sparse_newton()) {
    sn->held = &set_;
    // a camshaft: the held rows at the state, their stiffness at the held forces
    shaft_newton(*sn, [this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& F, Eigen::VectorXd&) {
      held_forces_into(t, y, cam_at(t), set_, F);
    });
    sys.newton = sn;
  } else {
    sys.jacobian = dense_jacobian(&set_);
  }
  set_cvode_bdf_order(sc, *mech_, sys);
  engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, sys, false));
  eng_ = engines_.back().get();
  eng_->set_projection([this](double t, const double* y, double* corr) { project(t, y, corr); });
}

void EventMethod::restart() {
  set_ = active_list();
  const int k = int(set_.size());
  set_metric();
  // the state the engine starts from is on the active set's manifold too
  if (k) {
    Eigen::VectorXd corr(ny_);
    project(t_, y_.data(), corr.data());
    y_ += corr;
  }
  eng_->reinit(t_, y_);
}

void EventMethod::set_metric() {
  const int k = int(set_.size());
  MTa_.resize(n_, k);
  Eigen::MatrixXd Waa(k, k);
  if (gamma_p_ > 0) {  // S⁻¹T_Aᵀ, T_A S⁻¹ T_Aᵀ
    for (int i = 0; i < k; ++i) MTa_.col(i) = S_ldlt_.solve(Eigen::VectorXd(mk_.contacts()[set_[i]].t.transpose()));
    for (int i = 0; i < k; ++i)
      for (int l = 0; l < k; ++l) Waa(i, l) = mk_.contacts()[set_[i]].t.dot(MTa_.col(l));
  } else {  // M⁻¹T_Aᵀ, W_AA (a camshaft: at the state, refreshed by project())
    const Rows R = rows_at(y_.data());
    for (int i = 0; i < k; ++i) {
      MTa_.col(i) = R.MinvTt.col(set_[i]);
      for (int l = 0; l < k; ++l) Waa(i, l) = R.W(set_[i], set_[l]);
    }
  }
  if (k) Waa_.compute(Waa);
}

void EventMethod::stiff_metric(double h) {
  if (!stiff_metric_ || !(h > 0)) return;
  const double g = std::exp2(std::round(std::log2(h * metric_scale_)));  // on the grid 2^k: few factorisations
  if (g == gamma_p_) return;
  const auto& mech = static_cast<const Mechanism&>(mk_);
  SparseMatrix S = mech.M() + (g * g) * mech.K();
  if (mech.damped()) S += g * mech.C();
  if (gamma_p_ == 0) S_ldlt_.analyzePattern(S);
  S_ldlt_.factorize(S);
  if (S_ldlt_.info() != Eigen::Success) return;  // keep the metric in use
  gamma_p_ = g;
  set_metric();
}

void EventMethod::project(double t, const double* y, double* corr) {
  const int k = int(set_.size());
  Eigen::Map<Eigen::VectorXd> C(corr, ny_);
  if (k == 0) {
    C.setZero();
    return;
  }
  const CamMotion cm = cam_at(t);
  pg_.resize(k);
  pgd_.resize(k);
  const Eigen::Map<const Eigen::VectorXd> Q(y, n_), V(y + n_, n_);
  if (mk_.camshaft()) {  // rows and gaps at this state (the rows depend on the shaft angle)
    yp_ = Eigen::Map<const Eigen::VectorXd>(y, 2 * n_);
    const Rows R = rows_at(y);
    Eigen::MatrixXd Waa(k, k);
    for (int i = 0; i < k; ++i) {
      MTa_.col(i) = R.MinvTt.col(set_[i]);
      for (int l = 0; l < k; ++l) Waa(i, l) = R.W(set_[i], set_[l]);
      pg_[i] = gap(set_[i], yp_, cm);
      pgd_[i] = gap_rate(set_[i], yp_, cm);
    }
    Waa_.compute(Waa);
  } else {
    for (int i = 0; i < k; ++i) {
      const MechanismContact& c = mk_.contacts()[set_[i]];
      pg_[i] = c.t.dot(Q) + c.g0 - (c.cam ? cm.X : 0.0);
      pgd_[i] = c.t.dot(V) - (c.cam ? cm.Xdot : 0.0);
    }
  }
  if (k == 1) {  // W_AA⁺g = g/W (what the 1 × 1 factorisation gives), without its temporaries
    const double w = Waa_.matrixQTZ()(0, 0);
    const double x = Waa_.rank() ? pg_[0] / w : 0.0, xd = Waa_.rank() ? pgd_[0] / w : 0.0;
    C.head(n_).noalias() = -(MTa_.col(0) * x);
    C.segment(n_, n_).noalias() = -(MTa_.col(0) * xd);
    C.tail(ns_).setZero();  // the elements' internal states are not projected
    return;
  }
  C.head(n_).noalias() = -MTa_ * Waa_.solve(pg_);
  C.segment(n_, n_).noalias() = -MTa_ * Waa_.solve(pgd_);
  C.tail(ns_).setZero();
}

// The cam's work over [ta, tb] inside the last step: 3-point Gauss–Legendre on the
// engine's own dense output (the trapezoid on step ends was 3e-4 of the work off on a rigid
// follower that CVODE/ERK step across in 150 steps per revolution).
double EventMethod::held_work(double ta, double tb) {
  static const double xg[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double wg[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double h = tb - ta;
  double dW = 0.0;
  if (!(h > 0)) return 0.0;
  for (int g = 0; g < 3; ++g) {
    const double tau = ta + 0.5 * h * (1.0 + xg[g]);
    eng_->dense(tau, yg_);
    const CamMotion cg = cam_at(tau);
    dW += 0.5 * h * wg[g] * cam_power(held_forces(tau, yg_, cg, set_), cg);
  }
  return dW;
}

ContactRun::StepEnergy EventMethod::advance_energy(double t0, double t1) {
  // no held contact on an undamped mechanism: nothing works or dissipates, and the three
  // dense states are not needed
  if (set_.empty() && !mk_.dissipative()) return StepEnergy{};
  // A step longer than kScanDeg of cam rotation (held contacts carried it across part of
  // a lift, scan_switches): composite panels of at most kScanDeg, on the interpolant put on
  // the held manifold (the raw one leaves the cam there: its held forces and the cam's
  // work were 6e-5 J off on examples/ohc_roller_finger.toml with one row per revolution)
  const double turn = std::abs(drive_.theta(t1) - drive_.theta(t0)) * (180.0 / 3.141592653589793);
  const int P = turn > kScanDeg ? int(std::min(std::ceil(turn / kScanDeg), 4096.0)) : 1;
  auto state = [this, P](double tau, Eigen::VectorXd& y) {
    eng_->dense(tau, y);
    if (P > 1 && !set_.empty()) {
      rc_.resize(ny_);
      project(tau, y.data(), rc_.data());
      y += rc_;
    }
  };
  auto forces = [this](double tau, const Eigen::VectorXd& y, const CamMotion& c, Eigen::VectorXd& F) {
    if (set_.empty())
      F.setZero(m_);
    else
      held_forces_into(tau, y, c, set_, F);
  };
  StepEnergy sum;
  for (int p = 0; p < P; ++p) {
    const StepEnergy e = step_energy(t0 + (t1 - t0) * p / P, p + 1 == P ? t1 : t0 + (t1 - t0) * (p + 1) / P, state, forces);
    sum.work += e.work;
    sum.dissipated += e.dissipated;
  }
  // one panel: step_energy's middle Gauss point (se_mid_y_) is the interpolant at the
  // step's middle, which the trace's middle sample reads (run_method)
  if (P == 1 && se_mid_t0_ == t0 && se_mid_t1_ == t1) mid_t_ = t0 + 0.5 * (t1 - t0);
  return sum;
}

void EventMethod::run_method() {
  eng_->set_roots(m_, [this](double t, const double* y, double* g) {
    const Eigen::Map<const Eigen::VectorXd> Y(y, ny_);
    yv_ = Y;
    if (on_manifold_roots_ && !set_.empty()) {  // see the header: on_manifold_roots_
      rc_.resize(ny_);
      project(t, yv_.data(), rc_.data());
      yv_ += rc_;
    }
    const CamMotion cm = cam_at(t);
    Eigen::VectorXd& F = rF_;  // the separation function of the active contacts (force units)
    if (!set_.empty()) held_forces_into(t, yv_, cm, set_, rFh_, &F);
    // Offsets keep every function away from zero at a restart (SUNDIALS stops with
    // "root found at and very near t" on a function that stays at zero): a gap triggers
    // at −10⁻³ tol_u, an active contact's margin F − g̈/W_jj (its force while held, −its
    // opening acceleration as a force once complementarity opens it) at −10⁻¹² of the
    // largest force so far.
    const double F_thr = 1e-12 * std::max(F_ref_, mk_.force_scale());
    for (int j = 0; j < m_; ++j) g[j] = active_[j] ? F[j] + F_thr : gap(j, yv_, cm) + gap_thr_;
  });
  // A start on a cam breakpoint (a law's first joint at θ = 0): the segment after it.
  {
    CamMotion m;
    on_break_ = one_sided_motion(cam_, drive_, break_angles_, t_, 1, &m);
  }
  set_cam_window(on_break_ ? t_ : NAN, NAN);
  restart();
  Eigen::VectorXd y1(ny_);
  const double gap_thr = gap_thr_;
  while (t_ < sc_.run.t_end * (1 - 1e-15)) {
    if (cam_joint_impact()) restart();  // closed contacts on a C0 joint of the cam
    const double horizon = step_horizon(), tout = stop_before(horizon), t_brk = next_break_time();
    // the step's cam: the segment after a breakpoint it starts from, the one before a
    // breakpoint it lands on
    set_cam_window(on_break_ ? t_ : NAN, tout == t_brk ? tout : NAN);
    const double P_prev = dissipation_power(t_, y_);
    double t1 = eng_->advance(tout, y1);
    // the step's interpolant is read with this step's held set until the events below
    eng_->keep_dense_rhs(true);
    int scanned = -1;
    if (unilateral_ && !eng_->hit_root()) scan_switches(t_, t1, y1, scanned);
    const bool hit = eng_->hit_root() || scanned >= 0;
    auto root_info = [&](int j) { return scanned >= 0 ? (j == scanned ? -1 : 0) : eng_->root_info()[j]; };
    const double h = t1 - t_;
    on_break_ = t1 == t_brk;
    stiff_metric(h);  // for the next steps' projections
    t_ = t1;
    y_.swap(y1);  // y1: the state the step started from (the trace's start), until the next advance
    // A root's state (interpolated inside the step) on the held contacts' g = 0, ġ = 0, as
    // every step end is: a contact released there leaves the cam from exactly where it was
    // held. ERK's interpolant of the held step is off that manifold by its interpolation
    // error (case A7 at rtol 1e-11: the free flights started up to 6.1e-10 m off the
    // rtol-1e-12 run, 2.5e-12 m with the projection).
    if (hit && !set_.empty()) {
      rc_.resize(ny_);
      project(t_, y_.data(), rc_.data());
      y_ += rc_;
    }
    const CamMotion cm = cam_at(t_);
    F_ = held_forces(t_, y_, cm, set_);
    if (m_) F_ref_ = std::max(F_ref_, F_.cwiseAbs().maxCoeff());
    // the cam's work and the dissipated energy over the step: 3-point Gauss–Legendre on
    // the engine's own dense output (issue 25: each step's own quadrature)
    const StepEnergy dE = advance_energy(t_ - h, t_);
    // The trace's end sample is the step's end (y_, F_): the engine's state, which its
    // projection has put on the held set's manifold (a root's state just above); its start
    // the previous end when the step started from that state (y1, swapped above); its
    // middle sample the interpolant advance_energy evaluated at the step's middle.
    trace_step(
        t_ - h, t_,
        [this](double tau, Eigen::VectorXd& y) {
          // no held contact: the forces are zero, and the samples read no state unless the
          // results ask for gaps or node displacements (trace_reads_state)
          if (set_.empty() && !trace_reads_state()) return;
          if (tau == mid_t_)
            y = se_mid_y_;
          else
            eng_->dense(tau, y);
          if (!set_.empty()) {
            rc_.resize(ny_);
            project(tau, y.data(), rc_.data());
            y += rc_;
          }
        },
        [this](double tau, const Eigen::VectorXd& y, const CamMotion& c, Eigen::VectorXd& F) {
          if (set_.empty()) F.setZero(m_);
          else held_forces_into(tau, y, c, set_, F);
        },
        set_, false, &y_, &F_, &y1);
    mid_t_ = NAN;
    after_advance(t_ - h, P_prev);
    eng_->keep_dense_rhs(false);
    const double P_end = dissipation_power(t_, y_);
    bool changed = false, released_only = false;
    if (hit && unilateral_) {
      std::vector<int> closing;
      bool released = false;
      for (int j = 0; j < m_; ++j) {
        if (root_info(j) >= 0) continue;  // only downward crossings act
        if (active_[j]) {
          active_[j] = 0;
          ++rec_.separations;
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
        if (!active_[j] && root_info(j) == 0 && gap(j, y_, cm) <= gap_thr &&
            gap_rate(j, y_, cm) < -v_eps)
          closing.push_back(j);
      if (!closing.empty())
        resolve_impact(closing, cm);
      else if (released)
        settle_active(cm);
      changed = !closing.empty() || released;
      released_only = closing.empty() && released;
    } else if (hit) {  // bilateral: a contact that closes stays closed
      std::vector<int> closing;
      for (int j = 0; j < m_; ++j)
        if (!active_[j] && root_info(j) < 0 && gap_rate(j, y_, cm) < 0.0) closing.push_back(j);
      if (!closing.empty()) {
        resolve_impact(closing, cm);
        changed = true;
      }
    }
    for (int j : set_)
      if (active_[j] && unilateral_) F_[j] = std::max(F_[j], 0.0);
    if (changed && released_only && continue_on_release_ && scanned < 0) {
      // A release alone: the contact leaves where its force has reached zero, so the
      // right-hand side is continuous there and CVODE's history stays valid: it goes on
      // from its own step end (the next advance returns it) with the smaller held set.
      // A restart there began again at order 1, whose first steps' error (h²|g̈|/2 in the
      // gap, of the order of rtol·|q|) put the follower of A7 1.9e-7 into the cam 14 µs
      // after its separation (the issue-28 check at 10 tol_u = 1e-7 stopped the run).
      set_ = active_list();
      set_metric();
    } else if (changed || scanned >= 0) {
      restart();  // projects onto the new active set (a scanned root: the engine is past it)
    }
    after_step(h, dE.work, P_prev, changed ? P_end : NAN, dE.dissipated);
    if (on_break_) enter_segment();
  }
}

bool EventMethod::scan_switches(double t0, double& t1, Eigen::VectorXd& y1, int& who) {
  const double turn = std::abs(drive_.theta(t1) - drive_.theta(t0)) * (180.0 / 3.141592653589793);
  const int K = int(std::min(std::ceil(turn / kScanDeg), 4096.0));
  if (K < 2) return false;
  // the smallest switching function at τ (on the held manifold), its contact in j: an open
  // contact's gap over the gap tolerance, a held contact's separation margin (the root
  // function's, run_method) over the force scale
  const double F_thr = 1e-12 * std::max(F_ref_, mk_.force_scale());
  const double F_scale = std::max(F_ref_, mk_.force_scale());
  auto lowest = [&](double tau, int& j) {
    eng_->dense(tau, yg_);
    if (!set_.empty()) {
      rc_.resize(ny_);
      project(tau, yg_.data(), rc_.data());
      yg_ += rc_;
    }
    const CamMotion cm = cam_at(tau);
    if (!set_.empty()) held_forces_into(tau, yg_, cm, set_, rFh_, &rF_);
    double lo = INFINITY;
    for (int i = 0; i < m_; ++i) {
      const double g = active_[i] ? (rF_[i] + F_thr) / F_scale : (gap(i, yg_, cm) + gap_thr_) / gap_tol_;
      if (g < lo) lo = g, j = i;
    }
    return lo;
  };
  double a = t0;
  for (int k = 1; k < K; ++k) {
    double b = t0 + (t1 - t0) * double(k) / K;
    int j = -1;
    if (!(lowest(b, j) < 0.0)) {
      a = b;
      continue;
    }
    for (int it = 0; it < 200 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++it) {
      const double c = 0.5 * (a + b);
      int jc = -1;
      if (lowest(c, jc) < 0.0)
        b = c, j = jc;
      else
        a = c;
    }
    lowest(b, j);
    t1 = b;
    y1 = yg_;
    who = j;
    return true;
  }
  return false;
}

void EventMethod::enter_segment() {
  const CamMotion left = cam_at(t_);  // the step just taken: the segment before t_
  set_cam_window(t_, NAN);
  const CamMotion right = cam_at(t_);
  if (set_.empty()) return;
  const double w = drive_.omega(t_);
  const double scale = std::abs(left.Xddot) + std::abs(right.Xddot) + 1e-4 * cam_.lift() * w * w;
  if (std::abs(right.Xddot - left.Xddot) > 1e-8 * scale) {
    // The cam's acceleration jumps (a C1 joint, an arc cam's tangency point): the held
    // contacts take the new segment's forces — those the new acceleration pulls off
    // separate here — and the engine restarts, its first stage on the new segment (an
    // explicit method's first stage is the last one's right-hand side, a BDF history the
    // old segment's: their error estimate does not fall with h across a jump).
    settle_active(right);
    for (int j = 0; j < m_; ++j)
      if (active_[j]) sample_held_force(j, t_, F_[j]);
    restart();
  } else if (restart_at_breaks_ && int(set_.size()) < n_) {
    restart();  // a cam breakpoint under held contacts, with unknowns they leave free (header)
  }
}

std::unique_ptr<ContactRun> make_event_method(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                              Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<EventMethod>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
