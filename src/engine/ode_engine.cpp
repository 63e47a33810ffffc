// camdyn — the generic OdeEngine (ode_engine.hpp) on SUNDIALS 6.4: y' = f(t, y), for every
// contact method (src/contact/methods/). Linear algebra of the implicit engines: a mechanism's
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
#include <sunnonlinsol/sunnonlinsol_newton.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "engine/ode_engine_base.hpp"

namespace camdyn {

double OdeEngine::wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const {
  if (sys_.atol.size() == 0) return detail::wrms_norm(err, y, spec_.rtol, spec_.atol);
  if (err.size() == 0) return 0.0;
  double s = 0.0;
  for (Eigen::Index i = 0; i < err.size(); ++i) {
    const double w = spec_.rtol * std::abs(y[i]) + sys_.atol[i];
    s += (err[i] / w) * (err[i] / w);
  }
  return std::sqrt(s / double(err.size()));
}

/// The CVODE engine (cvode_ode.cpp).
std::unique_ptr<OdeEngine> make_cvode_ode(const SolverSpec& spec, OdeSystem system, bool trial);

namespace ode_impl {

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
      set_tolerances(mem, ERKStepSVtolerances, "ERKStepSVtolerances", ERKStepSStolerances, "ERKStepSStolerances",
                     spec.rtol, spec.atol);
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
    const InDense scope(*this);
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
      set_tolerances(mem, ARKStepSVtolerances, "ARKStepSVtolerances", ARKStepSStolerances, "ARKStepSStolerances",
                     kHugeTol, spec.atol, scale);
      if (sys_.linear) {
        check(ARKStepSetLinear(mem, 0), "ARKStepSetLinear");  // one Newton iteration, exact J
      } else {
        // Every trial step starts from a reset: each stage's Newton iteration starts from
        // y_n (ARKODE's predictor after a reset) and the Newton matrix is set up there at
        // the first stage. The contraction rate the first stage measures is kept for the
        // step's later stages (no decay floor: the measured rate itself), so a stage whose
        // first iterate is already within the Newton tolerance stops there. A first
        // iterate's error, the Jacobian's change over the stage's distance from y_n times
        // that distance, grows with c_i/c_1 over the first stage's: the Newton coefficient
        // 0.01 is divided by the table's largest c_i/c_1.
        check(ARKStepSetNonlinCRDown(mem, kRateFloor), "ARKStepSetNonlinCRDown");
        check(ARKStepSetNonlinConvCoef(mem, 0.01 / (stage_reach(mem) * scale)), "ARKStepSetNonlinConvCoef");
        // The elements' force the only nonlinearity: the rate after a setup is predicted
        // (conv_test) instead of measured by a second iteration of the first stage.
        if (newton_ && newton_->predicts_next_correction()) {
          nls_.reset(not_null(SUNNonlinSol_Newton(y_.get(), ctx_.ctx), "SUNNonlinSol_Newton"));
          check(ARKStepSetNonlinearSolver(mem, nls_.get()), "ARKStepSetNonlinearSolver");
          check(SUNNonlinSolSetConvTestFn(nls_.get(), &DirkOde::conv_test, this), "SUNNonlinSolSetConvTestFn");
          next_ = make_nvec(n_, ctx_.ctx);
        }
      }
    } else {
      set_tolerances(mem, ARKStepSVtolerances, "ARKStepSVtolerances", ARKStepSStolerances, "ARKStepSStolerances",
                     spec.rtol, spec.atol);
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
  ~DirkOde() override { mem_.reset(); }
  // ARKODE's divergence ratio (ARKStepSetNonlinRDiv's default).
  static constexpr double kDivergence = 2.3;
  // The Newton convergence test of a trial engine whose only nonlinearity is the elements'
  // force (SparseNewton::element_force): ARKODE's own test (arkStep_NlsConvTest: rate
  // estimate c, c = max(kRateFloor·c, ‖δ_m‖/‖δ_{m−1}‖) from the second iteration on,
  // converged when min(c, 1)‖δ_m‖ ≤ the Newton tolerance, diverging when ‖δ_m‖ >
  // kDivergence‖δ_{m−1}‖), except that the first iteration after a linear-system setup,
  // where ARKODE takes c = 1, predicts the next correction δ₂ (SparseNewtonSolver::
  // next_correction) and takes c = ‖δ₂‖/‖δ₁‖, the rate a second iteration would measure.
  // Weighted RMS norms with ARKODE's weights.
  static int conv_test(SUNNonlinearSolver nls, N_Vector ycor, N_Vector del, sunrealtype tol, N_Vector ewt,
                       void* ud) {
    auto* self = static_cast<DirkOde*>(ud);
    try {
      return self->newton_test(nls, ycor, del, tol, ewt);
    } catch (const std::exception& e) {
      self->caught(e.what());
    } catch (...) {
      self->caught("unknown exception");
    }
    return -1;
  }
  int newton_test(SUNNonlinearSolver nls, N_Vector, N_Vector del, double tol, N_Vector ewt) {
    int m = 0;
    check(SUNNonlinSolGetCurIter(nls, &m), "SUNNonlinSolGetCurIter");
    const double* w = N_VGetArrayPointer(ewt);
    auto norm = [&](const double* x, long len) {
      double s = 0.0;
      for (long i = 0; i < len; ++i) s += (x[i] * w[i]) * (x[i] * w[i]);
      return std::sqrt(s / double(n_));
    };
    const double* d = N_VGetArrayPointer(del);
    const double dn = norm(d, n_);
    if (m > 0) {
      rate_ = std::max(kRateFloor * rate_, dn / delp_);
    } else if (rate_unknown_) {
      rate_ = 1.0;
      double t = 0.0, gamma = 0.0;
      N_Vector zpred = nullptr, z = nullptr, Fi = nullptr, sdata = nullptr;
      void* user = nullptr;
      check(ARKStepGetNonlinearSystemData(mem_.get(), &t, &zpred, &z, &Fi, &gamma, &sdata, &user),
            "ARKStepGetNonlinearSystemData");
      // the residual was evaluated at z; the setup's γ (a later stage with another γ: ARKODE's rate)
      if (gamma == newton_->gamma() && dn > 0.0) {
        double* x = N_VGetArrayPointer(next_.get());
        newton_->next_correction(t, N_VGetArrayPointer(z), d, x);
        const double next = norm(x, n_);
        if (std::isfinite(next)) rate_ = next / dn;
      }
      rate_unknown_ = false;
    }
    if (std::min(rate_, 1.0) * dn <= tol) return SUN_NLS_SUCCESS;
    if (m >= 1 && dn > kDivergence * delp_) return SUN_NLS_CONV_RECVR;
    delp_ = dn;
    return SUN_NLS_CONTINUE;
  }
  // The smallest contraction-rate estimate ARKODE may keep (ARKStepSetNonlinCRDown: the
  // estimate after an iteration is max(kRateFloor · the previous one, the measured ratio)).
  static constexpr double kRateFloor = 1e-12;
  // The implicit table's largest c_i over its first stage's c_1 (> 0 for an SDIRK).
  double stage_reach(void* mem) {
    ARKodeButcherTable Bi = nullptr, Be = nullptr;
    check(ARKStepGetCurrentButcherTables(mem, &Bi, &Be), "ARKStepGetCurrentButcherTables");
    if (!Bi || !(Bi->c[0] > 0.0)) throw std::logic_error("DirkOde: the implicit table's first stage has no c_1 > 0");
    double r = 1.0;
    for (int i = 0; i < Bi->stages; ++i) r = std::max(r, Bi->c[i] / Bi->c[0]);
    return r;
  }  // ARKStepFree before the solver and matrix it uses
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
    const InDense scope(*this);
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
  NLS nls_;      // the Newton solver with conv_test (null: ARKODE's own)
  NVec next_;    // conv_test's predicted next correction
  double rate_ = 1.0, delp_ = 0.0;  // conv_test's rate estimate and last correction norm
  std::unique_ptr<void, ArkDel> mem_;
};

}  // namespace ode_impl


std::unique_ptr<OdeEngine> OdeEngine::make(Integrator integrator, const SolverSpec& spec, OdeSystem system,
                                           bool trial) {
  switch (integrator) {
    case Integrator::ArkodeErk:
      return std::make_unique<ode_impl::ErkOde>(spec, std::move(system), trial);
    case Integrator::ArkodeDirk:
      return std::make_unique<ode_impl::DirkOde>(spec, std::move(system), trial);
    case Integrator::CvodeBdf:
      return make_cvode_ode(spec, std::move(system), trial);
    case Integrator::Ida:
      throw std::invalid_argument("OdeEngine: \"ida\" is a DAE integrator, not an OdeEngine");
  }
  throw std::invalid_argument("OdeEngine: unknown integrator");
}

}  // namespace camdyn
