// camdyn — the generic OdeEngine (ode_engine.hpp) on SUNDIALS 6.4: y' = f(t, y), for the
// network (several-contact) methods. Linear algebra of the implicit engines: a mechanism's
// sparse Schur complement with KLU (OdeSystem::newton, sparse_newton.hpp), else dense.
//
//   arkode-erk   ERKStep, Dormand–Prince 5(4)
//   arkode-dirk  ARKStep, SDIRK 5-stage 4(3); SUNDenseMatrix + SUNLinSol_Dense; Jacobian
//                from OdeSystem::jacobian (copied column-major into the dense matrix) or
//                SUNDIALS' difference quotients
//   cvode-bdf    CVODE BDF, the same linear algebra
//
// Trial mode (step()): ERK/DIRK take exactly one step of h from a reset state; SUNDIALS'
// own error test is disabled by huge tolerances (only our test on the returned WRMS norm
// acts). CVODE integrates [t, t + h] under its own control at the spec tolerances
// (restarted each time) and reports no estimate. Native mode (reinit()/advance()): spec
// tolerances, ONE_STEP toward tout with tout as stop time, rootfinding, GetDky dense output.
//
// Every SUNDIALS flag is checked (negative → SundialsError naming the call). Callbacks
// catch every exception, remember its message and return −1; SUNDIALS treats that as an
// unrecoverable failure, so the step fails and the SundialsError carries the message.
#include "engine/ode_engine.hpp"

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "engine/sparse_newton.hpp"
#include "engine/sundials_raii.hpp"

namespace camdyn {

double OdeEngine::wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const {
  return detail::wrms_norm(err, y, spec_.rtol, spec_.atol);
}

namespace {

using detail::ContextHolder;
using detail::LS;
using detail::Mat;
using detail::not_null;
using detail::kTrialMaxSteps;
using detail::trial_min_step;
using detail::NVec;

using detail::ArkDel;
using detail::CvDel;
using detail::ErkDel;
using detail::make_nvec;
inline Eigen::Map<Eigen::VectorXd> map(N_Vector v) {
  return Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(v), N_VGetLength(v));
}

// Trial steps: SUNDIALS' error test must never reject (our own test acts). The tolerances
// are the spec's scaled by kTrialScale/rtol, so that every weighted norm inside SUNDIALS
// is the native one divided by a constant: the Newton test (coefficient scaled alike) and
// the difference-quotient increments behave as in native mode, the error test never fails.
constexpr double kHugeTol = 1e30;
// With a projection, ERK/DIRK are reset after every step: the first step after a reset may
// grow by ARKODE's normal factor only (its default for a first step is 10⁴).
constexpr double kGrowthAfterReset = 20.0;

// Counter of a SUNDIALS integrator read as a running delta (robust to resets that zero it).
struct Counter {
  long base = 0;
  long delta(long now) {
    const long d = now >= base ? now - base : now;
    base = now;
    return d;
  }
};

// Shared state and callbacks of the three engines.
class EngineBase : public OdeEngine {
 protected:
  EngineBase(const SolverSpec& spec, OdeSystem sys, bool trial)
      : OdeEngine(spec, std::move(sys)), trial_(trial) {
    if (n_ < 1) throw std::invalid_argument("OdeEngine: system size must be ≥ 1");
    if (!sys_.rhs) throw std::invalid_argument("OdeEngine: no right-hand side");
    if (sys_.linear && !sys_.jacobian && !sys_.newton)
      throw std::invalid_argument("OdeEngine: linear = true needs a jacobian or the sparse Newton structure");
    if (sys_.newton && 2 * sys_.newton->M->rows() + sys_.newton->states != n_)
      throw std::invalid_argument("OdeEngine: the sparse Newton structure's size (2n + states) is not the system's");
    y_ = make_nvec(n_, ctx_.ctx);
    tmp_ = make_nvec(n_, ctx_.ctx);
    local_error_ = Eigen::VectorXd::Zero(n_);
  }

  /// check_flag, with the message of an exception a callback caught (if any) appended.
  int check(int flag, const char* call) {
    if (flag < 0 && !callback_error_.empty()) {
      std::string msg = std::string(call) + " [callback threw: " + callback_error_ + "]";
      callback_error_.clear();
      sundials_message_.clear();
      throw SundialsError(msg, flag);
    }
    callback_error_.clear();
    if (flag < 0 && !sundials_message_.empty()) {
      const std::string msg = std::string(call) + " [" + sundials_message_ + "]";
      sundials_message_.clear();
      return check_flag(flag, msg.c_str());
    }
    return check_flag(flag, call);
  }
  void caught(const char* what) {
    if (callback_error_.empty()) callback_error_ = what;
  }
  // A callback's body: 0, or −1 with the exception's message kept for check().
  template <class Body>
  static int guarded(void* ud, Body body) {
    auto* self = static_cast<EngineBase*>(ud);
    try {
      body(self);
      return 0;
    } catch (const std::exception& e) {
      self->caught(e.what());
    } catch (...) {
      self->caught("unknown exception");
    }
    return -1;
  }
  void set_root_count(int n, RootFn fn) {
    if (n < 0) throw std::invalid_argument("OdeEngine::set_roots: n < 0");
    if (n > 0 && !fn) throw std::invalid_argument("OdeEngine::set_roots: no function");
    root_fn_ = n > 0 ? std::move(fn) : RootFn();
    root_info_.assign(std::size_t(n), 0);
    hit_root_ = false;
  }
  void fetch_root_info(int flag, int root_return, int (*get)(void*, int*), void* mem, const char* call) {
    hit_root_ = flag == root_return;
    std::fill(root_info_.begin(), root_info_.end(), 0);
    if (hit_root_ && !root_info_.empty()) check(get(mem, root_info_.data()), call);
  }

  // ERK/DIRK native mode, after a step that ended at tret with state y_: the projected
  // state in y_; true if it moved (the stepper must restart there).
  bool project_step_end(double tret) {
    if (!proj_) return false;
    corr_.setZero(n_);
    proj_(tret, N_VGetArrayPointer(y_.get()), corr_.data());
    if (!(corr_.cwiseAbs().maxCoeff() > 0.0)) return false;
    map(y_.get()) += corr_;
    return true;
  }

  // The sparse Schur path (OdeSystem::newton): our own linear solver; the integrator's
  // linear-system function hands over γ and the state.
  void make_sparse_solver() {
    const bool dense = resolve_linear_solver(spec_, int(sys_.newton->M->rows())) == LinearSolverKind::Dense;
    newton_ = std::make_unique<detail::SparseNewtonSolver>(*sys_.newton, dense, stats_);
    cls_ = std::make_unique<detail::CustomLinearSolver>(
        ctx_.ctx, [this] { newton_->setup(); }, [this](double* x) { newton_->solve(x); });
  }
  // ARKLsLinSysFn / CVLsLinSysFn (ARKODE's has the mass matrix M in addition).
  static int ark_linsys(double t, N_Vector y, N_Vector, SUNMatrix, SUNMatrix, sunbooleantype, sunbooleantype* jcur,
                        double gamma, void* ud, N_Vector, N_Vector, N_Vector) {
    return linsys(t, y, jcur, gamma, ud);
  }
  static int cv_linsys(double t, N_Vector y, N_Vector, SUNMatrix, sunbooleantype, sunbooleantype* jcur, double gamma,
                       void* ud, N_Vector, N_Vector, N_Vector) {
    return linsys(t, y, jcur, gamma, ud);
  }
  static int linsys(double t, N_Vector y, sunbooleantype* jcur, double gamma, void* ud) {
    return guarded(ud, [&](EngineBase* self) {
      self->newton_->prepare(t, N_VGetArrayPointer(y), gamma);
      *jcur = SUNTRUE;
    });
  }

  static int rhs_cb(double t, N_Vector y, N_Vector ydot, void* ud) {
    return guarded(ud, [&](EngineBase* self) {
      ++self->stats_.rhs_evals;
      self->sys_.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    });
  }
  static int root_cb(double t, N_Vector y, double* g, void* ud) {
    return guarded(ud, [&](EngineBase* self) { self->root_fn_(t, N_VGetArrayPointer(y), g); });
  }
  // ARKLsJacFn and CVLsJacFn have the same signature.
  static int jac_cb(double t, N_Vector y, N_Vector, SUNMatrix Jac, void* ud, N_Vector, N_Vector, N_Vector) {
    return guarded(ud, [&](EngineBase* self) {
      Eigen::MatrixXd& J = self->J_;
      J.setZero(self->n_, self->n_);
      self->sys_.jacobian(t, N_VGetArrayPointer(y), J);
      if (J.rows() != self->n_ || J.cols() != self->n_)
        throw std::runtime_error("OdeSystem::jacobian resized its matrix");
      // Both column-major with leading dimension n.
      std::memcpy(SUNDenseMatrix_Data(Jac), J.data(), sizeof(double) * std::size_t(self->n_) * std::size_t(self->n_));
    });
  }

  // The integrator's linear-solver setups up to now (nls): the factorisations of its own
  // dense solver. The sparse Schur path counts its own factorisations (SparseNewtonSolver::
  // setup refactors only when γ or the contact derivatives changed): the integrator calls
  // its setup at every step after a reset — every Lee trial step — mostly with the same γ.
  void count_setups(long nls) {
    const long d = setups_.delta(nls);
    if (!newton_) stats_.lin_setups += d;
  }
  // The integrator's Newton iterations, Newton convergence failures and error-test failures
  // up to now (running totals since its last reset): counted, or (count = false) the base.
  void count_newton(long nni, long ncf, long netf, bool count = true) {
    const long a = nni_.delta(nni), b = ncf_.delta(ncf), c = netf_.delta(netf);
    if (!count) return;
    stats_.nonlin_iters += a;
    stats_.nonlin_conv_fails += b;
    stats_.err_test_fails += c;
  }

  bool trial_;
  ContextHolder ctx_;
  NVec y_, tmp_;
  Eigen::MatrixXd J_;
  Eigen::VectorXd corr_;
  std::unique_ptr<detail::SparseNewtonSolver> newton_;
  std::unique_ptr<detail::CustomLinearSolver> cls_;
  std::string callback_error_;
  std::string sundials_message_;  ///< the last message of SUNDIALS' error handler
  Counter steps_, setups_, nni_, ncf_, netf_;
};

// ---------------------------------------------------------------- ERK ------------
class ErkOde final : public EngineBase {
 public:
  ErkOde(const SolverSpec& spec, OdeSystem sys, bool trial) : EngineBase(spec, std::move(sys), trial) {
    mem_.reset(not_null(ERKStepCreate(&EngineBase::rhs_cb, 0.0, y_.get(), ctx_.ctx), "ERKStepCreate"));
    void* mem = mem_.get();
    check(ERKStepSetTableNum(mem, ARKODE_DORMAND_PRINCE_7_4_5), "ERKStepSetTableNum");
    check(ERKStepSetUserData(mem, this), "ERKStepSetUserData");
    check(ERKStepSetErrHandlerFn(mem, &detail::capture_sundials_message, &sundials_message_), "ERKStepSetErrHandlerFn");
    check(ERKStepSetMaxNumSteps(mem, -1), "ERKStepSetMaxNumSteps");
    if (trial_) {
      check(ERKStepSStolerances(mem, kHugeTol, kHugeTol), "ERKStepSStolerances");
    } else {
      check(ERKStepSStolerances(mem, spec.rtol, spec.atol), "ERKStepSStolerances");
      // Trial steps are sized by the caller: no max_step there (it would clip h).
      if (spec.max_step > 0) check(ERKStepSetMaxStep(mem, spec.max_step), "ERKStepSetMaxStep");
    }
  }
  const char* name() const override { return "arkode-erk"; }
  int error_order() const override { return 5; }  // embedded 4th order
  bool estimates_error() const override { return true; }

  double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) override {
    void* mem = mem_.get();
    map(y_.get()) = y;
    check(ERKStepReset(mem, t, y_.get()), "ERKStepReset");
    check(ERKStepSetInitStep(mem, h), "ERKStepSetInitStep");
    check(ERKStepSetStopTime(mem, t + h), "ERKStepSetStopTime");
    double tret = t;
    // A root inside the step (root functions set): go on to t + h (same step, no new one).
    while (check(ERKStepEvolve(mem, t + h, y_.get(), &tret, ARK_ONE_STEP), "ERKStepEvolve") == ARK_ROOT_RETURN) {
    }
    if (tret != t + h) throw SundialsError("ERKStepEvolve (trial step ended short of t + h)", -1);
    y_out = map(y_.get());
    check(ERKStepGetEstLocalErrors(mem, tmp_.get()), "ERKStepGetEstLocalErrors");
    ++stats_.steps;
    local_error_ = map(tmp_.get());
    return wrms(local_error_, y);
  }
  void reinit(double t, const Eigen::VectorXd& y) override {
    void* mem = mem_.get();
    map(y_.get()) = y;
    check(ERKStepReset(mem, t, y_.get()), "ERKStepReset");
    check(ERKStepSetInitStep(mem, spec_.initial_step), "ERKStepSetInitStep");
    long ns = 0;
    check(ERKStepGetNumSteps(mem, &ns), "ERKStepGetNumSteps");
    steps_.base = ns;
    hit_root_ = false;
  }
  double advance(double tout, Eigen::VectorXd& y_out) override {
    void* mem = mem_.get();
    check(ERKStepSetStopTime(mem, tout), "ERKStepSetStopTime");
    double tret = 0;
    const int flag = check(ERKStepEvolve(mem, tout, y_.get(), &tret, ARK_ONE_STEP), "ERKStepEvolve");
    fetch_root_info(flag, ARK_ROOT_RETURN, &ERKStepGetRootInfo, mem, "ERKStepGetRootInfo");
    long ns = 0;
    check(ERKStepGetNumSteps(mem, &ns), "ERKStepGetNumSteps");
    stats_.steps += steps_.delta(ns);
    if (!hit_root_ && project_step_end(tret)) {
      double hnext = 0;
      check(ERKStepGetCurrentStep(mem, &hnext), "ERKStepGetCurrentStep");
      check(ERKStepReset(mem, tret, y_.get()), "ERKStepReset");
      check(ERKStepSetInitStep(mem, hnext), "ERKStepSetInitStep");
      check(ERKStepGetNumSteps(mem, &ns), "ERKStepGetNumSteps");
      steps_.base = ns;
    }
    y_out = map(y_.get());
    return tret;
  }
  void dense(double t, Eigen::VectorXd& y_out) override {
    check(ERKStepGetDky(mem_.get(), t, 0, tmp_.get()), "ERKStepGetDky");
    y_out = map(tmp_.get());
  }
  void set_projection(ProjFn fn) override {
    // ≤ 1: ARKODE's default (10⁴)
    check(ERKStepSetMaxFirstGrowth(mem_.get(), fn ? kGrowthAfterReset : 0.0), "ERKStepSetMaxFirstGrowth");
    proj_ = std::move(fn);
  }
  void set_roots(int n, RootFn fn) override {
    set_root_count(n, std::move(fn));
    check(ERKStepRootInit(mem_.get(), n, n > 0 ? &EngineBase::root_cb : nullptr), "ERKStepRootInit");
  }

 private:
  std::unique_ptr<void, ErkDel> mem_;
};

// ---------------------------------------------------------------- DIRK -----------
class DirkOde final : public EngineBase {
 public:
  DirkOde(const SolverSpec& spec, OdeSystem sys, bool trial) : EngineBase(spec, std::move(sys), trial) {
    if (!sys_.newton) {
      A_.reset(not_null(SUNDenseMatrix(n_, n_, ctx_.ctx), "SUNDenseMatrix"));
      ls_.reset(not_null(SUNLinSol_Dense(y_.get(), A_.get(), ctx_.ctx), "SUNLinSol_Dense"));
    } else {
      make_sparse_solver();
    }
    mem_.reset(not_null(ARKStepCreate(nullptr, &EngineBase::rhs_cb, 0.0, y_.get(), ctx_.ctx), "ARKStepCreate"));
    void* mem = mem_.get();
    check(ARKStepSetTableNum(mem, ARKODE_SDIRK_5_3_4, ARKODE_ERK_NONE), "ARKStepSetTableNum");
    check(ARKStepSetUserData(mem, this), "ARKStepSetUserData");
    check(ARKStepSetErrHandlerFn(mem, &detail::capture_sundials_message, &sundials_message_), "ARKStepSetErrHandlerFn");
    check(ARKStepSetMaxNumSteps(mem, -1), "ARKStepSetMaxNumSteps");
    if (sys_.newton) {
      check(ARKStepSetLinearSolver(mem, cls_->ls(), cls_->placeholder()), "ARKStepSetLinearSolver");
      check(ARKStepSetLinSysFn(mem, &EngineBase::ark_linsys), "ARKStepSetLinSysFn");
    } else {
      check(ARKStepSetLinearSolver(mem, ls_.get(), A_.get()), "ARKStepSetLinearSolver");
      if (sys_.jacobian) check(ARKStepSetJacFn(mem, &EngineBase::jac_cb), "ARKStepSetJacFn");
    }
    if (trial_) {
      // Spec tolerances scaled up to rtol = 1e30: the error test never rejects, while the
      // Newton test (coefficient 0.01 scaled alike) and the difference-quotient increments
      // see the same weighted norms as in native mode.
      const double scale = kHugeTol / spec.rtol;
      check(ARKStepSStolerances(mem, kHugeTol, spec.atol * scale), "ARKStepSStolerances");
      if (sys_.linear)
        check(ARKStepSetLinear(mem, 0), "ARKStepSetLinear");  // one Newton iteration, exact J
      else
        check(ARKStepSetNonlinConvCoef(mem, 0.01 / scale), "ARKStepSetNonlinConvCoef");
    } else {
      check(ARKStepSStolerances(mem, spec.rtol, spec.atol), "ARKStepSStolerances");
      // The Newton matrix is reused across steps: a Newton tolerance of 0.01 of the error
      // test (ARKODE's default 0.1 costs a stiff penalty run accuracy: method_notes.md).
      check(ARKStepSetNonlinConvCoef(mem, 0.01), "ARKStepSetNonlinConvCoef");
      // Refactor the Newton matrix when γ moved by > 1 % (ARKODE's default: 20 %). With
      // the default, the undamped oscillator of tests/engine/test_ode_engine.cpp (ω = 50, rtol
      // 1e-10) ended 2.4e-5 off at t = 1 (Newton iterations accepted too early with a
      // stale γ; a Newton tolerance 1000× tighter still left 2.8e-6); with 1 %: 7e-11 at
      // the same number of setups (ARKODE keeps h fixed through small changes).
      check(ARKStepSetDeltaGammaMax(mem, 0.01), "ARKStepSetDeltaGammaMax");
      if (spec.max_step > 0) check(ARKStepSetMaxStep(mem, spec.max_step), "ARKStepSetMaxStep");
    }
  }
  ~DirkOde() override { mem_.reset(); }  // ARKStepFree before the solver and matrix it uses
  void newton_count(bool count = true) {  // count = false: set the counters' base
    long nni = 0, ncf = 0, netf = 0;
    check(ARKStepGetNumNonlinSolvIters(mem_.get(), &nni), "ARKStepGetNumNonlinSolvIters");
    check(ARKStepGetNumNonlinSolvConvFails(mem_.get(), &ncf), "ARKStepGetNumNonlinSolvConvFails");
    check(ARKStepGetNumErrTestFails(mem_.get(), &netf), "ARKStepGetNumErrTestFails");
    count_newton(nni, ncf, netf, count);
  }
  const char* name() const override { return "arkode-dirk"; }
  int error_order() const override { return 4; }  // embedded 3rd order
  bool estimates_error() const override { return true; }

  double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) override {
    void* mem = mem_.get();
    map(y_.get()) = y;
    check(ARKStepReset(mem, t, y_.get()), "ARKStepReset");
    check(ARKStepSetInitStep(mem, h), "ARKStepSetInitStep");
    check(ARKStepSetStopTime(mem, t + h), "ARKStepSetStopTime");
    long nls = 0;
    check(ARKStepGetNumLinSolvSetups(mem, &nls), "ARKStepGetNumLinSolvSetups");
    setups_.base = nls;
    newton_count(false);
    double tret = t;
    // A root inside the step (root functions set): go on to t + h (same step, no new one).
    while (check(ARKStepEvolve(mem, t + h, y_.get(), &tret, ARK_ONE_STEP), "ARKStepEvolve") == ARK_ROOT_RETURN) {
    }
    check(ARKStepGetNumLinSolvSetups(mem, &nls), "ARKStepGetNumLinSolvSetups");
    count_setups(nls);
    newton_count();
    // A Newton failure makes ARKODE retry smaller: the step would not be of h.
    if (tret != t + h) throw SundialsError("ARKStepEvolve (trial step ended short of t + h)", -1);
    y_out = map(y_.get());
    check(ARKStepGetEstLocalErrors(mem, tmp_.get()), "ARKStepGetEstLocalErrors");
    ++stats_.steps;
    local_error_ = map(tmp_.get());
    return wrms(local_error_, y);
  }
  void reinit(double t, const Eigen::VectorXd& y) override {
    void* mem = mem_.get();
    map(y_.get()) = y;
    check(ARKStepReset(mem, t, y_.get()), "ARKStepReset");
    check(ARKStepSetInitStep(mem, spec_.initial_step), "ARKStepSetInitStep");
    long ns = 0, nls = 0;
    check(ARKStepGetNumSteps(mem, &ns), "ARKStepGetNumSteps");
    check(ARKStepGetNumLinSolvSetups(mem, &nls), "ARKStepGetNumLinSolvSetups");
    steps_.base = ns;
    setups_.base = nls;
    newton_count(false);
    hit_root_ = false;
  }
  double advance(double tout, Eigen::VectorXd& y_out) override {
    void* mem = mem_.get();
    check(ARKStepSetStopTime(mem, tout), "ARKStepSetStopTime");
    double tret = 0;
    const int flag = check(ARKStepEvolve(mem, tout, y_.get(), &tret, ARK_ONE_STEP), "ARKStepEvolve");
    fetch_root_info(flag, ARK_ROOT_RETURN, &ARKStepGetRootInfo, mem, "ARKStepGetRootInfo");
    long ns = 0, nls = 0;
    check(ARKStepGetNumSteps(mem, &ns), "ARKStepGetNumSteps");
    check(ARKStepGetNumLinSolvSetups(mem, &nls), "ARKStepGetNumLinSolvSetups");
    stats_.steps += steps_.delta(ns);
    count_setups(nls);
    newton_count();
    if (!hit_root_ && project_step_end(tret)) {
      double hnext = 0;
      check(ARKStepGetCurrentStep(mem, &hnext), "ARKStepGetCurrentStep");
      check(ARKStepReset(mem, tret, y_.get()), "ARKStepReset");
      check(ARKStepSetInitStep(mem, hnext), "ARKStepSetInitStep");
      check(ARKStepGetNumSteps(mem, &ns), "ARKStepGetNumSteps");
      check(ARKStepGetNumLinSolvSetups(mem, &nls), "ARKStepGetNumLinSolvSetups");
      steps_.base = ns;
      setups_.base = nls;
      newton_count(false);
    }
    y_out = map(y_.get());
    return tret;
  }
  void dense(double t, Eigen::VectorXd& y_out) override {
    check(ARKStepGetDky(mem_.get(), t, 0, tmp_.get()), "ARKStepGetDky");
    y_out = map(tmp_.get());
  }
  void set_projection(ProjFn fn) override {
    check(ARKStepSetMaxFirstGrowth(mem_.get(), fn ? kGrowthAfterReset : 0.0), "ARKStepSetMaxFirstGrowth");
    proj_ = std::move(fn);
  }
  void set_roots(int n, RootFn fn) override {
    set_root_count(n, std::move(fn));
    check(ARKStepRootInit(mem_.get(), n, n > 0 ? &EngineBase::root_cb : nullptr), "ARKStepRootInit");
  }

 private:
  Mat A_;
  LS ls_;
  std::unique_ptr<void, ArkDel> mem_;
};

// ---------------------------------------------------------------- CVODE ----------
class CvodeOde final : public EngineBase {
 public:
  CvodeOde(const SolverSpec& spec, OdeSystem sys, bool trial) : EngineBase(spec, std::move(sys), trial) {
    if (!sys_.newton) {
      A_.reset(not_null(SUNDenseMatrix(n_, n_, ctx_.ctx), "SUNDenseMatrix"));
      ls_.reset(not_null(SUNLinSol_Dense(y_.get(), A_.get(), ctx_.ctx), "SUNLinSol_Dense"));
    } else {
      make_sparse_solver();
    }
    mem_.reset(not_null(CVodeCreate(CV_BDF, ctx_.ctx), "CVodeCreate"));
    void* mem = mem_.get();
    check(CVodeInit(mem, &EngineBase::rhs_cb, 0.0, y_.get()), "CVodeInit");
    check(CVodeSetUserData(mem, this), "CVodeSetUserData");
    check(CVodeSStolerances(mem, spec.rtol, spec.atol), "CVodeSStolerances");
    check(CVodeSetMaxNumSteps(mem, trial ? kTrialMaxSteps : -1), "CVodeSetMaxNumSteps");
    check(CVodeSetErrHandlerFn(mem, &detail::capture_sundials_message, &sundials_message_), "CVodeSetErrHandlerFn");
    if (spec.max_step > 0) check(CVodeSetMaxStep(mem, spec.max_step), "CVodeSetMaxStep");
    if (sys_.newton) {
      check(CVodeSetLinearSolver(mem, cls_->ls(), cls_->placeholder()), "CVodeSetLinearSolver");
      check(CVodeSetLinSysFn(mem, &EngineBase::cv_linsys), "CVodeSetLinSysFn");
    } else {
      check(CVodeSetLinearSolver(mem, ls_.get(), A_.get()), "CVodeSetLinearSolver");
      if (sys_.jacobian) check(CVodeSetJacFn(mem, &EngineBase::jac_cb), "CVodeSetJacFn");
    }
    if (sys_.max_order > 0) check(CVodeSetMaxOrd(mem, sys_.max_order), "CVodeSetMaxOrd");
    if (sys_.stability_limit_detection) check(CVodeSetStabLimDet(mem, SUNTRUE), "CVodeSetStabLimDet");
  }
  ~CvodeOde() override { mem_.reset(); }  // CVodeFree before the solver and matrix it uses
  const char* name() const override { return "cvode-bdf"; }
  int error_order() const override { return 2; }
  bool estimates_error() const override { return false; }

  // [t, t + h] under CVODE's own error control, restarted from (t, y) (BDF history
  // cannot be saved and restored through the API): the result is the same for the same
  // (t, y, h), but not exactly affine in anything f depends on.
  double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) override {
    void* mem = mem_.get();
    map(y_.get()) = y;
    check(CVodeReInit(mem, t, y_.get()), "CVodeReInit");
    ++stats_.reinits;
    check(CVodeSetInitStep(mem, first_h_ > 0 ? std::min(h, first_h_) : h), "CVodeSetInitStep");
    check(CVodeSetStopTime(mem, t + h), "CVodeSetStopTime");
    check(CVodeSetMinStep(mem, trial_min_step(t, h)), "CVodeSetMinStep");
    steps_.base = 0;
    setups_.base = 0;
    count_newton(0, 0, 0, false);
    double tret = t;
    while (check(CVode(mem, t + h, y_.get(), &tret, CV_NORMAL), "CVode") == CV_ROOT_RETURN) {
    }  // roots (if set) do not end a trial step
    y_out = map(y_.get());
    count();
    double h0 = 0;
    check(CVodeGetActualInitStep(mem, &h0), "CVodeGetActualInitStep");
    first_h_ = 2.0 * h0;  // start the next restart near the first step that worked
    local_error_.setZero();
    return 0.0;
  }
  void reinit(double t, const Eigen::VectorXd& y) override {
    void* mem = mem_.get();
    map(y_.get()) = y;
    check(CVodeReInit(mem, t, y_.get()), "CVodeReInit");  // zeroes CVODE's counters
    check(CVodeSetInitStep(mem, spec_.initial_step), "CVodeSetInitStep");
    check(CVodeSetMinStep(mem, 0.0), "CVodeSetMinStep");  // native stepping: no trial bound
    ++stats_.reinits;
    steps_.base = 0;
    setups_.base = 0;
    count_newton(0, 0, 0, false);
    hit_root_ = false;
  }
  double advance(double tout, Eigen::VectorXd& y_out) override {
    void* mem = mem_.get();
    check(CVodeSetStopTime(mem, tout), "CVodeSetStopTime");
    double tret = 0;
    const int flag = check(CVode(mem, tout, y_.get(), &tret, CV_ONE_STEP), "CVode");
    fetch_root_info(flag, CV_ROOT_RETURN, &CVodeGetRootInfo, mem, "CVodeGetRootInfo");
    y_out = map(y_.get());
    count();
    return tret;
  }
  void set_projection(ProjFn fn) override {
    void* mem = mem_.get();
    if (fn && !projection_set_) {
      check(CVodeSetProjFn(mem, &CvodeOde::project_cb), "CVodeSetProjFn");
      check(CVodeSetProjErrEst(mem, SUNFALSE), "CVodeSetProjErrEst");
      projection_set_ = true;
    }
    if (projection_set_) check(CVodeSetProjFrequency(mem, fn ? 1 : 0), "CVodeSetProjFrequency");
    proj_ = std::move(fn);
  }
  void dense(double t, Eigen::VectorXd& y_out) override {
    check(CVodeGetDky(mem_.get(), t, 0, tmp_.get()), "CVodeGetDky");
    y_out = map(tmp_.get());
  }
  void set_roots(int n, RootFn fn) override {
    set_root_count(n, std::move(fn));
    check(CVodeRootInit(mem_.get(), n, n > 0 ? &EngineBase::root_cb : nullptr), "CVodeRootInit");
  }

 private:
  void count() {
    long ns = 0, nls = 0;
    check(CVodeGetNumSteps(mem_.get(), &ns), "CVodeGetNumSteps");
    check(CVodeGetNumLinSolvSetups(mem_.get(), &nls), "CVodeGetNumLinSolvSetups");
    stats_.steps += steps_.delta(ns);
    count_setups(nls);
    long nni = 0, ncf = 0, netf = 0;
    check(CVodeGetNumNonlinSolvIters(mem_.get(), &nni), "CVodeGetNumNonlinSolvIters");
    check(CVodeGetNumNonlinSolvConvFails(mem_.get(), &ncf), "CVodeGetNumNonlinSolvConvFails");
    check(CVodeGetNumErrTestFails(mem_.get(), &netf), "CVodeGetNumErrTestFails");
    count_newton(nni, ncf, netf);
  }
  static int project_cb(double t, N_Vector ycur, N_Vector corr, double, N_Vector, void* ud) {
    return guarded(ud, [&](EngineBase* self) {
      static_cast<CvodeOde*>(self)->proj_(t, N_VGetArrayPointer(ycur), N_VGetArrayPointer(corr));
    });
  }
  Mat A_;
  LS ls_;
  std::unique_ptr<void, CvDel> mem_;
  double first_h_ = 0;
  bool projection_set_ = false;
};

}  // namespace

std::unique_ptr<OdeEngine> OdeEngine::make(Integrator integrator, const SolverSpec& spec, OdeSystem system,
                                           bool trial) {
  switch (integrator) {
    case Integrator::ArkodeErk:
      return std::make_unique<ErkOde>(spec, std::move(system), trial);
    case Integrator::ArkodeDirk:
      return std::make_unique<DirkOde>(spec, std::move(system), trial);
    case Integrator::CvodeBdf:
      return std::make_unique<CvodeOde>(spec, std::move(system), trial);
    case Integrator::Ida:
      throw std::invalid_argument("OdeEngine: \"ida\" is a DAE integrator, not an OdeEngine");
  }
  throw std::invalid_argument("OdeEngine: unknown integrator");
}

}  // namespace camdyn
