// camdyn — integrator engines on SUNDIALS 6.4 (ARKODE ERKStep / ARKStep, CVODE).
//
//   y = [q; v],  q̇ = v,  M v̇ = r(q, v, t) = f₀ − K q − C v + e₀ F(t, q₀, v₀)
//
//   arkode-erk   Dormand–Prince 5(4), v̇ = M⁻¹ r (lumped: diagonal; consistent: LDLᵀ
//                factor of M computed once).
//   arkode-dirk  ARKStep, SDIRK 5-stage 4(3) (L-stable), v̇ = M⁻¹ r.
//   cvode-bdf    CVODE BDF (orders 1–5, ≤ 2 for bars), v̇ = M⁻¹ r.
//   The Newton systems (I − γJ) x = b of both implicit engines, K̃ = K − e₀e₀ᵀ∂F/∂q₀,
//   C̃ = C − e₀e₀ᵀ∂F/∂v₀, are solved by our own direct linear solver through the n × n
//   Schur complement
//                  (M + γC̃ + γ²K̃) x_v = M b_v − γ K̃ b_u,   x_u = b_u + γ x_v,
//   which is sparse (tridiagonal for a bar) for consistent and lumped mass alike: no
//   dense M⁻¹K, no 2n × 2n matrix, no O(n²) SUNMatScaleAdd. KLU (dense LU for a handful
//   of unknowns): symbolic analysis once per engine, numeric refactorisation only when
//   γ (the step size) or the penalty derivatives changed; O(nnz) per factorisation/solve.
//
// Every SUNDIALS flag is checked (negative → SundialsError naming the call); callbacks
// catch every exception and return −1 so none crosses SUNDIALS.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine.hpp"
#include "sparse_lu.hpp"
#include "sundials_raii.hpp"

namespace camdyn {

int check_flag(int flag, const char* call) {
  if (flag < 0) throw SundialsError(call, flag);
  return flag;
}

LinearSolverKind resolve_linear_solver(const SolverSpec& solver, int nodes) {
  LinearSolverKind k = solver.linear_solver;
  // IDA's DAE carries the contact force λ and the GGL multiplier μ besides q, v.
  const int unknowns = 2 * nodes + (solver.integrator == Integrator::Ida ? 2 : 0);
  if (k == LinearSolverKind::Auto) k = (unknowns <= 16) ? LinearSolverKind::Dense : LinearSolverKind::Klu;
  return k;
}

// ---------------------------------------------------------------- engine base ----
void Engine::rhs_unscaled(double t, const double* y, double* out) {
  const double* q = y;
  const double* v = y + n_;
  std::copy(v, v + n_, out);
  model_->internal_force(q, v, out + n_);
  if (homogeneous_)
    for (int i = 0; i < n_; ++i) out[n_ + i] -= model_->f0()[i];
  out[n_] += contact_ ? contact_->force(t, q[0], v[0]) : 0.0;
  ++stats_.rhs_evals;
}

void Engine::rhs(double t, const double* y, double* ydot) {
  rhs_unscaled(t, y, ydot);
  std::copy(ydot + n_, ydot + 2 * n_, work_.data());
  model_->solve_mass(work_.data(), ydot + n_);
  if (held_) {
    // v̇ = a_free + M⁻¹e₀ F with F = (Ẍ_C − a_free,0) / M*: node 0 accelerates with the cam.
    const double F = (held_->path(t).Xddot - ydot[n_]) / model_->mstar();
    Eigen::Map<Eigen::VectorXd>(ydot + n_, n_) += F * model_->contact_column();
  }
}

double Engine::held_force(const CamMotion& c, const double* y) const {
  // node 0 on the cam: the state the projection gives (an interpolated state between step
  // ends is off the cam by the integration error, which the stiff first element would
  // turn into force: k_e·δ)
  held_y_.resize(2 * n_);
  std::copy(y, y + 2 * n_, held_y_.data());
  held_y_[0] = c.X;
  held_y_[n_] = c.Xdot;
  return (c.Xddot - model_->contact_acceleration(held_y_.data(), held_y_.data() + n_, 0.0)) / model_->mstar();
}

int Engine::root_callback(double t, const double* y, double* g, void* ud) noexcept {
  try {
    g[0] = static_cast<Engine*>(ud)->root_fn_(t, y);
    return 0;
  } catch (...) {
    return -1;
  }
}

double Engine::wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const {
  return detail::wrms_norm(err, y, spec_.rtol, spec_.atol);
}

namespace {

// ---------------------------------------------------------------- RAII ----------
using detail::ContextHolder;
using detail::LS;
using detail::Mat;
using detail::NVec;
using detail::ArkDel;
using detail::CvDel;
using detail::ErkDel;
using detail::make_nvec;
using detail::not_null;
using detail::kTrialMaxSteps;
using detail::trial_min_step;
inline Eigen::Map<Eigen::VectorXd> map(N_Vector v) {
  return Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(v), N_VGetLength(v));
}

constexpr double kHugeTol = 1e30;  // trial steps: our own error test, never ARKODE's

// ---------------------------------------------------------------- ERK ------------
class ErkEngine final : public Engine {
 public:
  ErkEngine(std::shared_ptr<const FollowerModel> model, const SolverSpec& spec, bool trial)
      : Engine(std::move(model), spec), trial_(trial), y_(make_nvec(2 * n_, ctx_.ctx)),
        ele_(make_nvec(2 * n_, ctx_.ctx)) {
    N_VConst(0.0, y_.get());
    mem_.reset(not_null(ERKStepCreate(&ErkEngine::f, 0.0, y_.get(), ctx_.ctx), "ERKStepCreate"));
    check_flag(ERKStepSetTableNum(mem_.get(), ARKODE_DORMAND_PRINCE_7_4_5), "ERKStepSetTableNum");
    check_flag(ERKStepSetUserData(mem_.get(), this), "ERKStepSetUserData");
    check_flag(ERKStepSetMaxNumSteps(mem_.get(), -1), "ERKStepSetMaxNumSteps");
    if (trial_)
      check_flag(ERKStepSStolerances(mem_.get(), kHugeTol, kHugeTol), "ERKStepSStolerances");
    else
      check_flag(ERKStepSStolerances(mem_.get(), spec.rtol, spec.atol), "ERKStepSStolerances");
    if (spec.max_step > 0) check_flag(ERKStepSetMaxStep(mem_.get(), spec.max_step), "ERKStepSetMaxStep");
  }
  const char* name() const override { return "arkode-erk"; }
  int error_order() const override { return 5; }  // embedded 4th order

  double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) override {
    map(y_.get()) = y;
    check_flag(ERKStepReset(mem_.get(), t, y_.get()), "ERKStepReset");
    check_flag(ERKStepSetInitStep(mem_.get(), h), "ERKStepSetInitStep");
    check_flag(ERKStepSetStopTime(mem_.get(), t + h), "ERKStepSetStopTime");
    double tret = t;
    check_flag(ERKStepEvolve(mem_.get(), t + h, y_.get(), &tret, ARK_ONE_STEP), "ERKStepEvolve");
    y_out = map(y_.get());
    check_flag(ERKStepGetEstLocalErrors(mem_.get(), ele_.get()), "ERKStepGetEstLocalErrors");
    ++stats_.steps;
    local_error_ = map(ele_.get());
    return wrms(local_error_, y);
  }
  void reinit(double t, const Eigen::VectorXd& y) override {
    map(y_.get()) = y;
    check_flag(ERKStepReset(mem_.get(), t, y_.get()), "ERKStepReset");
    check_flag(ERKStepSetInitStep(mem_.get(), spec_.initial_step), "ERKStepSetInitStep");
  }
  double advance(double tout, Eigen::VectorXd& y_out) override {
    check_flag(ERKStepSetStopTime(mem_.get(), tout), "ERKStepSetStopTime");
    double tret = 0;
    const int flag = check_flag(ERKStepEvolve(mem_.get(), tout, y_.get(), &tret, ARK_ONE_STEP), "ERKStepEvolve");
    hit_root_ = flag == ARK_ROOT_RETURN;
    y_out = map(y_.get());
    ++stats_.steps;
    return tret;
  }
  void set_root(RootFn fn, int direction) override {
    root_fn_ = std::move(fn);
    check_flag(ERKStepRootInit(mem_.get(), root_fn_ ? 1 : 0, &ErkEngine::g), "ERKStepRootInit");
    if (root_fn_) check_flag(ERKStepSetRootDirection(mem_.get(), &direction), "ERKStepSetRootDirection");
  }

 private:
  static int f(double t, N_Vector y, N_Vector ydot, void* ud) {
    try {
      static_cast<ErkEngine*>(ud)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int g(double t, N_Vector y, double* gout, void* ud) {
    return root_callback(t, N_VGetArrayPointer(y), gout, ud);
  }
  bool trial_;
  ContextHolder ctx_;
  NVec y_, ele_;
  std::unique_ptr<void, ErkDel> mem_;
};

// Values of K, M, C at pattern position p of column j (rigid: scalars).
struct ModelEntries {
  const FollowerModel& m;
  double K(long p) const { return m.rigid() ? m.k_rigid() : m.K().valuePtr()[p]; }
  double M(long p) const { return m.rigid() ? m.m_rigid() : m.M().valuePtr()[p]; }
  double C(long p) const {
    if (!m.damped()) return 0.0;
    return m.rigid() ? m.c_rigid() : m.C().valuePtr()[p];
  }
  long begin(long j) const { return m.rigid() ? 0 : m.K().outerIndexPtr()[j]; }
  long end(long j) const { return m.rigid() ? 1 : m.K().outerIndexPtr()[j + 1]; }
  long row(long p) const { return m.rigid() ? 0 : m.K().innerIndexPtr()[p]; }
};

// ---------------------------------------------------------------- Schur solver ---
// The Newton systems of both implicit engines, (I − γJ) x = b with
// J = [[0, I], [−M⁻¹K̃, −M⁻¹C̃]], through the n × n system
//   S x_v = M b_v − γ K̃ b_u,   S = M + γC̃ + γ²K̃,   x_u = b_u + γ x_v.
// S has the pattern of K (tridiagonal for a bar). KLU's symbolic analysis is done once
// for that pattern; the numeric factorisation is redone only when (γ, ∂F/∂q₀, ∂F/∂v₀)
// changed since the last one — Lee's trial steps retake the same step size several
// times, and ARKODE asks for a setup at the first stage after every reset.
class SchurSolver {
 public:
  SchurSolver(const FollowerModel& m, bool dense, EngineStats& stats)
      : m_(m), n_(m.n()), stats_(stats), lu_(dense, stats) {
    if (!m.rigid()) S_ = m.K();  // copy of the shared pattern
  }

  void setup(double g, double dFdq, double dFdv) {
    if (factored_ && g == g_ && dFdq == dFdq_ && dFdv == dFdv_) return;  // S unchanged
    g_ = g;
    dFdq_ = dFdq;
    dFdv_ = dFdv;
    factored_ = true;
    z_valid_ = false;
    ++stats_.lin_setups;
    if (m_.rigid()) {
      s_rigid_ = m_.m_rigid() + g * (m_.c_rigid() - dFdv) + g * g * (m_.k_rigid() - dFdq);
      return;
    }
    const ModelEntries e{m_};
    double* x = S_.valuePtr();
    for (long j = 0; j < n_; ++j)
      for (long p = e.begin(j); p < e.end(j); ++p) {
        double v = e.M(p) + g * e.C(p) + g * g * e.K(p);
        if (j == 0 && e.row(p) == 0) v -= g * dFdv + g * g * dFdq;
        x[p] = v;
      }
    lu_.factor(S_);
  }
  // x = (I − γJ)⁻¹ b, in place on b (length 2n).
  //
  // Held contact (a HeldContact set): v̇ = P M⁻¹(f₀ − Kq − Cv) + M⁻¹e₀Ẍ_C/M* with
  // P = I − M⁻¹e₀e₀ᵀ/M*, so J's velocity rows are P M⁻¹[−K, −C] and e₀ᵀP = 0. The
  // system becomes S x_v = M b_v − γK b_u + e₀λ with x_v,0 = b_v,0 (node 0's velocity
  // row is the identity): bordered with z = S⁻¹e₀ (one solve per factorisation),
  // x_v = w + λz, w = S⁻¹(M b_v − γK b_u), λ = (b_v,0 − w₀)/z₀.
  void solve(double* b, bool held = false) {
    const long n = n_;
    double* bu = b;
    double* bv = b + n;
    if (m_.rigid()) {
      if (held) {  // q̈ = Ẍ_C(t): x_v = b_v
        bu[0] += g_ * bv[0];
        return;
      }
      const double rhs = m_.m_rigid() * bv[0] - g_ * (m_.k_rigid() - dFdq_) * bu[0];
      bv[0] = rhs / s_rigid_;
      bu[0] += g_ * bv[0];
      return;
    }
    const double bv0 = bv[0];
    Eigen::Map<Eigen::VectorXd> U(bu, n), V(bv, n);
    rhs_.noalias() = m_.M() * V;
    rhs_.noalias() -= g_ * (m_.K() * U);
    rhs_[0] += g_ * dFdq_ * U[0];
    lu_.solve(rhs_.data());
    V = rhs_;
    if (held) {
      if (!z_valid_) {
        z_.setZero(n);
        z_[0] = 1.0;
        lu_.solve(z_.data());
        z_valid_ = true;
      }
      const double lambda = (bv0 - V[0]) / z_[0];
      V += lambda * z_;
      V[0] = bv0;
    }
    U += g_ * V;
  }

 private:
  const FollowerModel& m_;
  long n_;
  EngineStats& stats_;
  bool factored_ = false, z_valid_ = false;
  Eigen::VectorXd z_;  // S⁻¹e₀ (held contact)
  double g_ = 0, dFdq_ = 0, dFdv_ = 0, s_rigid_ = 1;
  SparseMatrix S_;
  Eigen::VectorXd rhs_;
  detail::SparseLu lu_;
};

// The SchurSolver as a SUNDIALS linear solver (detail::CustomLinearSolver). The engine's
// linear-system function hands over γ and the contact law's derivatives (prepare), the
// solver's setup factorises (if they changed), its solve applies (I − γJ)⁻¹.
class SchurLinearSolver {
 public:
  SchurLinearSolver(const FollowerModel& m, bool dense, EngineStats& stats, SUNContext ctx)
      : schur_(m, dense, stats), n_(m.n()),
        cls_(ctx, [this] { schur_.setup(gamma_, dFdq_, dFdv_); },
             [this](double* x) { schur_.solve(x, held_ && *held_); }) {}
  SUNLinearSolver ls() { return cls_.ls(); }
  SUNMatrix placeholder() { return cls_.placeholder(); }
  // From the linear-system function: the system I − γJ at (t, y) under the contact force f.
  void prepare(const ContactForce* f, double t, const double* y, double gamma) {
    if (f)
      f->derivatives(t, y[0], y[n_], &dFdq_, &dFdv_);
    else
      dFdq_ = dFdv_ = 0.0;
    gamma_ = gamma;
  }
  /// Where each solve reads whether the contact is held (the engine's held contact, or
  /// null): the held contact's system has the same S, bordered (SchurSolver::solve), so
  /// a phase switch needs no new factorisation.
  void watch(const HeldContact* const* held) { held_ = held; }

 private:
  SchurSolver schur_;
  long n_;
  double gamma_ = 0, dFdq_ = 0, dFdv_ = 0;
  const HeldContact* const* held_ = nullptr;
  detail::CustomLinearSolver cls_;
};

// ---------------------------------------------------------------- DIRK -----------
class DirkEngine final : public Engine {
 public:
  DirkEngine(std::shared_ptr<const FollowerModel> model, const SolverSpec& spec, bool trial,
             LinearSolverKind lsk)
      : Engine(std::move(model), spec), trial_(trial), y_(make_nvec(2 * n_, ctx_.ctx)),
        ele_(make_nvec(2 * n_, ctx_.ctx)), sls_(*model_, lsk == LinearSolverKind::Dense, stats_, ctx_.ctx) {
    N_VConst(0.0, y_.get());
    mem_.reset(not_null(ARKStepCreate(nullptr, &DirkEngine::fi, 0.0, y_.get(), ctx_.ctx), "ARKStepCreate"));
    void* mem = mem_.get();
    check_flag(ARKStepSetTableNum(mem, ARKODE_SDIRK_5_3_4, ARKODE_ERK_NONE), "ARKStepSetTableNum");
    check_flag(ARKStepSetUserData(mem, this), "ARKStepSetUserData");
    check_flag(ARKStepSetMaxNumSteps(mem, -1), "ARKStepSetMaxNumSteps");
    check_flag(ARKStepSetLinearSolver(mem, sls_.ls(), sls_.placeholder()), "ARKStepSetLinearSolver");
    check_flag(ARKStepSetLinSysFn(mem, &DirkEngine::linsys), "ARKStepSetLinSysFn");
    if (trial_) {
      // Lee's steps see a prescribed force ramp: the problem is linear in y, one Newton
      // iteration with an exact matrix solves each stage exactly.
      check_flag(ARKStepSetLinear(mem, 0), "ARKStepSetLinear");
      check_flag(ARKStepSStolerances(mem, kHugeTol, kHugeTol), "ARKStepSStolerances");
    } else {
      check_flag(ARKStepSStolerances(mem, spec.rtol, spec.atol), "ARKStepSStolerances");
      // Native stepping (penalty, event) is nonlinear and reuses the Newton matrix across
      // steps (refactored only when γ moves by > 20 %): with ARKODE's default Newton
      // tolerance (0.1 of the local error test) a stiff penalty run (k_p = 1e9, rtol 1e-7)
      // ended 6.6e-7 off the converged solution, 34× the error of ERK/CVODE at the same
      // rtol; 0.01 brings it to 3e-8 at ~10 % more right-hand-side evaluations.
      check_flag(ARKStepSetNonlinConvCoef(mem, 0.01), "ARKStepSetNonlinConvCoef");
      // Refactor the Newton matrix when γ moved by > 1 % (ARKODE's default: 20 %, as
      // ode_engine.cpp measured on an undamped oscillator). With the default, the event
      // method's held phase on the stiff bar (E = 5e8, 200 elements, rtol 1e-6) had 1 ms
      // impulses 1.1e-4 of the peak off the reference after 0.02 s and 2.0e-3 after
      // 0.05 s (Lee on DIRK: 7e-6): Newton iterations on its undamped stiff modes accepted
      // with a stale γ.
      check_flag(ARKStepSetDeltaGammaMax(mem, 0.01), "ARKStepSetDeltaGammaMax");
    }
    if (spec.max_step > 0) check_flag(ARKStepSetMaxStep(mem, spec.max_step), "ARKStepSetMaxStep");
  }
  const char* name() const override { return "arkode-dirk"; }
  int error_order() const override { return 4; }  // embedded 3rd order

  double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) override {
    map(y_.get()) = y;
    check_flag(ARKStepReset(mem_.get(), t, y_.get()), "ARKStepReset");
    check_flag(ARKStepSetInitStep(mem_.get(), h), "ARKStepSetInitStep");
    check_flag(ARKStepSetStopTime(mem_.get(), t + h), "ARKStepSetStopTime");
    double tret = t;
    check_flag(ARKStepEvolve(mem_.get(), t + h, y_.get(), &tret, ARK_ONE_STEP), "ARKStepEvolve");
    y_out = map(y_.get());
    check_flag(ARKStepGetEstLocalErrors(mem_.get(), ele_.get()), "ARKStepGetEstLocalErrors");
    ++stats_.steps;
    local_error_ = map(ele_.get());
    return wrms(local_error_, y);
  }
  void reinit(double t, const Eigen::VectorXd& y) override {
    map(y_.get()) = y;
    check_flag(ARKStepReset(mem_.get(), t, y_.get()), "ARKStepReset");
    check_flag(ARKStepSetInitStep(mem_.get(), spec_.initial_step), "ARKStepSetInitStep");
  }
  double advance(double tout, Eigen::VectorXd& y_out) override {
    check_flag(ARKStepSetStopTime(mem_.get(), tout), "ARKStepSetStopTime");
    double tret = 0;
    const int flag = check_flag(ARKStepEvolve(mem_.get(), tout, y_.get(), &tret, ARK_ONE_STEP), "ARKStepEvolve");
    hit_root_ = flag == ARK_ROOT_RETURN;
    y_out = map(y_.get());
    ++stats_.steps;
    return tret;
  }
  void set_root(RootFn fn, int direction) override {
    root_fn_ = std::move(fn);
    check_flag(ARKStepRootInit(mem_.get(), root_fn_ ? 1 : 0, &DirkEngine::g), "ARKStepRootInit");
    if (root_fn_) check_flag(ARKStepSetRootDirection(mem_.get(), &direction), "ARKStepSetRootDirection");
  }

 private:
  static int fi(double t, N_Vector y, N_Vector ydot, void* ud) {
    try {
      static_cast<DirkEngine*>(ud)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int linsys(double t, N_Vector y, N_Vector, SUNMatrix, SUNMatrix, sunbooleantype,
                    sunbooleantype* jcur, double gamma, void* ud, N_Vector, N_Vector, N_Vector) {
    try {
      auto* self = static_cast<DirkEngine*>(ud);
      self->sls_.prepare(self->contact_, t, N_VGetArrayPointer(y), gamma);
      *jcur = SUNTRUE;
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int g(double t, N_Vector y, double* gout, void* ud) {
    return root_callback(t, N_VGetArrayPointer(y), gout, ud);
  }

  bool trial_;
  ContextHolder ctx_;
  NVec y_, ele_;
  SchurLinearSolver sls_;
  std::unique_ptr<void, ArkDel> mem_;
};

// ---------------------------------------------------------------- CVODE ----------
class CvodeEngine final : public Engine {
 public:
  CvodeEngine(std::shared_ptr<const FollowerModel> model, const SolverSpec& spec, LinearSolverKind lsk,
              bool trial, double tol_u)
      : Engine(std::move(model), spec), y_(make_nvec(2 * n_, ctx_.ctx)),
        sls_(*model_, lsk == LinearSolverKind::Dense, stats_, ctx_.ctx) {
    N_VConst(0.0, y_.get());
    mem_.reset(not_null(CVodeCreate(CV_BDF, ctx_.ctx), "CVodeCreate"));
    void* mem = mem_.get();
    check_flag(CVodeInit(mem, &CvodeEngine::f, 0.0, y_.get()), "CVodeInit");
    check_flag(CVodeSetUserData(mem, this), "CVodeSetUserData");
    check_flag(CVodeSStolerances(mem, spec.rtol, spec.atol), "CVodeSStolerances");
    check_flag(CVodeSetMaxNumSteps(mem, trial ? kTrialMaxSteps : -1), "CVodeSetMaxNumSteps");
    if (trial) check_flag(CVodeSetErrHandlerFn(mem, &detail::quiet_cvode_errors, nullptr), "CVodeSetErrHandlerFn");
    // BDF orders 3–5 are not A-stable: an undamped stiff bar has modes on the imaginary
    // axis far beyond the step's resolution, which they amplify (seen as step sizes
    // collapsing to ~0.5/ω_max). Elastic followers therefore run A-stable BDF1–2; the
    // rigid follower (no stiff modes) keeps orders up to 5.
    if (!model_->rigid()) check_flag(CVodeSetMaxOrd(mem, 2), "CVodeSetMaxOrd");
    // Trial steps: solve the (linear) corrector far below the error tolerance so that
    // the step map is affine in the contact force to well below tol_u.
    if (trial) check_flag(CVodeSetNonlinConvCoef(mem, 1e-4), "CVodeSetNonlinConvCoef");
    // Trial steps restart CVODE, so each contact step carries a full local tolerance of
    // error; keep it well below the contact tolerance tol_u (else the displacement level
    // sees integration error as gap and can clip a real contact force to zero).
    if (trial && tol_u > 0) {
      const double scale = std::max(1.0, model_->initial_displacement().cwiseAbs().maxCoeff());
      check_flag(CVodeSStolerances(mem, std::min(spec.rtol, 1e-2 * tol_u / scale),
                                   std::min(spec.atol, 1e-2 * tol_u)),
                 "CVodeSStolerances");
    }
    if (spec.max_step > 0) check_flag(CVodeSetMaxStep(mem, spec.max_step), "CVodeSetMaxStep");
    // Our own direct solver for (I − γJ) x = b (SchurLinearSolver); CVODE hands γ (and
    // the state, for the penalty Jacobian) to the linear-system function.
    check_flag(CVodeSetLinearSolver(mem, sls_.ls(), sls_.placeholder()), "CVodeSetLinearSolver");
    check_flag(CVodeSetLinSysFn(mem, &CvodeEngine::linsys), "CVodeSetLinSysFn");
    sls_.watch(&held_);
  }
  ~CvodeEngine() override {
    mem_.reset();  // CVodeFree before the linear solver it references
  }
  const char* name() const override { return "cvode-bdf"; }
  int error_order() const override { return 2; }
  bool estimates_error() const override { return false; }
  double suggested_step() const override { return hcur_; }

  // A trial step of exactly h: CVODE integrates [t, t+h] under its own error control,
  // restarted from (t, y). Lee's iteration retakes the step with other force ramps and
  // needs the same step map each time (the response is then affine in the end force, up
  // to the Newton tolerance, which is tightened for this reason); CVODE's multistep
  // history cannot be saved and restored through its API, so each contact step starts
  // at order 1. CVODE keeps its full history in native stepping (penalty, event).
  double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) override {
    map(y_.get()) = y;
    check_flag(CVodeReInit(mem_.get(), t, y_.get()), "CVodeReInit");
    check_flag(CVodeSetInitStep(mem_.get(), first_h_ > 0 ? std::min(h, first_h_) : h), "CVodeSetInitStep");
    ++stats_.reinits;
    check_flag(CVodeSetStopTime(mem_.get(), t + h), "CVodeSetStopTime");
    check_flag(CVodeSetMinStep(mem_.get(), trial_min_step(t, h)), "CVodeSetMinStep");
    double tret = t;
    long ns0 = 0, ns1 = 0;
    CVodeGetNumSteps(mem_.get(), &ns0);
    check_flag(CVode(mem_.get(), t + h, y_.get(), &tret, CV_NORMAL), "CVode");
    CVodeGetNumSteps(mem_.get(), &ns1);
    stats_.steps += ns1 - ns0;
    y_out = map(y_.get());
    double h0 = 0;
    CVodeGetActualInitStep(mem_.get(), &h0);
    first_h_ = 2.0 * h0;  // start the next restart near the first step that worked
    CVodeGetCurrentStep(mem_.get(), &hcur_);
    return 0.0;
  }
  void reinit(double t, const Eigen::VectorXd& y) override {
    map(y_.get()) = y;
    check_flag(CVodeReInit(mem_.get(), t, y_.get()), "CVodeReInit");
    check_flag(CVodeSetInitStep(mem_.get(), spec_.initial_step), "CVodeSetInitStep");
    check_flag(CVodeSetMinStep(mem_.get(), 0.0), "CVodeSetMinStep");  // native: no trial bound
    ++stats_.reinits;
  }
  double advance(double tout, Eigen::VectorXd& y_out) override {
    check_flag(CVodeSetStopTime(mem_.get(), tout), "CVodeSetStopTime");
    double tret = 0;
    const int flag = check_flag(CVode(mem_.get(), tout, y_.get(), &tret, CV_ONE_STEP), "CVode");
    hit_root_ = flag == CV_ROOT_RETURN;
    y_out = map(y_.get());
    ++stats_.steps;
    return tret;
  }
  void set_max_order(int q) override {
    check_flag(CVodeSetMaxOrd(mem_.get(), q), "CVodeSetMaxOrd");
    check_flag(CVodeSetStabLimDet(mem_.get(), q >= 3 ? SUNTRUE : SUNFALSE), "CVodeSetStabLimDet");
  }
  void set_held_projection(bool on) override {
    if (on && !projection_set_) {
      check_flag(CVodeSetProjFn(mem_.get(), &CvodeEngine::project), "CVodeSetProjFn");
      // The error test keeps the unprojected estimate (node 0's drift included:
      // conservative).
      check_flag(CVodeSetProjErrEst(mem_.get(), SUNFALSE), "CVodeSetProjErrEst");
      projection_set_ = true;
    }
    if (projection_set_) check_flag(CVodeSetProjFrequency(mem_.get(), on ? 1 : 0), "CVodeSetProjFrequency");
  }
  void set_root(RootFn fn, int direction) override {
    root_fn_ = std::move(fn);
    check_flag(CVodeRootInit(mem_.get(), root_fn_ ? 1 : 0, &CvodeEngine::g), "CVodeRootInit");
    if (root_fn_) check_flag(CVodeSetRootDirection(mem_.get(), &direction), "CVodeSetRootDirection");
  }

 private:
  static int f(double t, N_Vector y, N_Vector ydot, void* ud) {
    try {
      static_cast<CvodeEngine*>(ud)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int g(double t, N_Vector y, double* gout, void* ud) {
    return root_callback(t, N_VGetArrayPointer(y), gout, ud);
  }
  // The held contact's displacement and velocity levels: the corrected state is put on
  // u₀ = X_C, u̇₀ = Ẋ_C by translating the follower rigidly, c = (s·1, ŝ·1) with
  // s = X_C − u₀, ŝ = Ẋ_C − u̇₀ — the correction that changes no strain and so no internal
  // force. (Projecting along M⁻¹e₀, or moving node 0 alone, put the drift — up to
  // rtol·|X_C| — into the first element's strain, k_e·s: on the stiff bar, k_e = 1.25e10,
  // that gave force spikes and spurious separations at rtol ≥ 1e-4.) CVODE adds c to the
  // step's correction and to its history.
  static int project(double t, N_Vector ycur, N_Vector corr, double, N_Vector, void* ud) {
    try {
      auto* self = static_cast<CvodeEngine*>(ud);
      const int n = self->n_;
      const double* y = N_VGetArrayPointer(ycur);
      const CamMotion c = self->held_->path(t);
      Eigen::Map<Eigen::VectorXd> C(N_VGetArrayPointer(corr), 2 * n);
      C.head(n).setConstant(c.X - y[0]);
      C.tail(n).setConstant(c.Xdot - y[n]);
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int linsys(double t, N_Vector y, N_Vector, SUNMatrix, sunbooleantype, sunbooleantype* jcur,
                    double gamma, void* ud, N_Vector, N_Vector, N_Vector) {
    try {
      auto* self = static_cast<CvodeEngine*>(ud);
      self->sls_.prepare(self->contact_, t, N_VGetArrayPointer(y), gamma);
      *jcur = SUNTRUE;
      return 0;
    } catch (...) {
      return -1;
    }
  }

  ContextHolder ctx_;
  NVec y_;
  SchurLinearSolver sls_;
  std::unique_ptr<void, CvDel> mem_;
  double hcur_ = 0, first_h_ = 0;
  bool projection_set_ = false;
};

}  // namespace

std::unique_ptr<Engine> make_engine(std::shared_ptr<const FollowerModel> model, const SolverSpec& solver,
                                    bool trial, double tol_u) {
  const LinearSolverKind lsk = resolve_linear_solver(solver, model->n());
  switch (solver.integrator) {
    case Integrator::ArkodeErk:
      return std::make_unique<ErkEngine>(std::move(model), solver, trial);
    case Integrator::ArkodeDirk:
      return std::make_unique<DirkEngine>(std::move(model), solver, trial, lsk);
    case Integrator::CvodeBdf:
      return std::make_unique<CvodeEngine>(std::move(model), solver, lsk, trial, tol_u);
    case Integrator::Ida:
      // The DAE engine (ida_engine.cpp) integrates the held contact itself; the runner
      // still wants an Engine for its bookkeeping (no contact force): an ERK engine in
      // native mode that is never stepped.
      return std::make_unique<ErkEngine>(std::move(model), solver, false);
  }
  throw std::invalid_argument("unknown integrator");
}

}  // namespace camdyn
