// camdyn — integrator engines on SUNDIALS 6.4 (ARKODE ERKStep / ARKStep, CVODE).
//
//   y = [q; v],  q̇ = v,  M v̇ = r(q, v, t) = f₀ − K q − C v + e₀ F(t, q₀, v₀)
//
//   arkode-erk   Dormand–Prince 5(4), v̇ = M⁻¹ r (lumped: diagonal; consistent: LDLᵀ
//                factor of M computed once).
//   arkode-dirk  ARKStep, SDIRK 5-stage 4(3) (L-stable), v̇ = M⁻¹ r.
//   cvode-bdf    CVODE BDF (orders 1–5, ≤ 2 for bars), v̇ = M⁻¹ r (engine_cvode.cpp).
//   The Newton systems (I − γJ) x = b of both implicit engines (Lee's force shape over a
//   step does not depend on the state) are solved by our own direct linear solver through
//   the n × n Schur complement
//                  (M + γC + γ²K) x_v = M b_v − γ K b_u,   x_u = b_u + γ x_v,
//   which is sparse (tridiagonal for a bar) for consistent and lumped mass alike: no
//   dense M⁻¹K, no 2n × 2n matrix, no O(n²) SUNMatScaleAdd. KLU (dense LU for a handful
//   of unknowns): symbolic analysis once per engine, numeric refactorisation only when
//   γ (the step size) changed; O(nnz) per factorisation/solve.
//
// Every SUNDIALS flag is checked (negative → SundialsError naming the call); callbacks
// catch every exception and return −1 so none crosses SUNDIALS.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "legacy/engine.hpp"
#include "legacy/engine_internal.hpp"
#include "engine/sparse_lu.hpp"
#include "engine/sundials_raii.hpp"

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
  out[n_] += contact_ ? contact_->force(t, q[0], v[0]) : 0.0;
  ++stats_.rhs_evals;
}

void Engine::rhs(double t, const double* y, double* ydot) {
  rhs_unscaled(t, y, ydot);
  std::copy(ydot + n_, ydot + 2 * n_, work_.data());
  model_->solve_mass(work_.data(), ydot + n_);
}

double Engine::wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const {
  return detail::wrms_norm(err, y, spec_.rtol, spec_.atol);
}

namespace {

using namespace engine_detail;

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

 private:
  static int f(double t, N_Vector y, N_Vector ydot, void* ud) {
    try {
      static_cast<ErkEngine*>(ud)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      return 0;
    } catch (...) {
      return -1;
    }
  }
  bool trial_;
  ContextHolder ctx_;
  NVec y_, ele_;
  std::unique_ptr<void, ErkDel> mem_;
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
      // Native stepping (trial = false: an engine without a contact method, the engine
      // tests; measured when the single-follower stack's penalty and event methods ran
      // here) reuses the Newton matrix across steps (refactored only when γ moves by
      // > 20 %): with ARKODE's default Newton
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

 private:
  static int fi(double t, N_Vector y, N_Vector ydot, void* ud) {
    try {
      static_cast<DirkEngine*>(ud)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int linsys(double, N_Vector, N_Vector, SUNMatrix, SUNMatrix, sunbooleantype,
                    sunbooleantype* jcur, double gamma, void* ud, N_Vector, N_Vector, N_Vector) {
    try {
      auto* self = static_cast<DirkEngine*>(ud);
      self->sls_.prepare(gamma);
      *jcur = SUNTRUE;
      return 0;
    } catch (...) {
      return -1;
    }
  }

  bool trial_;
  ContextHolder ctx_;
  NVec y_, ele_;
  SchurLinearSolver sls_;
  std::unique_ptr<void, ArkDel> mem_;
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
      return engine_detail::make_cvode_engine(std::move(model), solver, lsk, trial, tol_u);
    case Integrator::Ida:
      break;  // ida runs on the mechanism (src/engine/ida_engine.cpp)
  }
  throw std::invalid_argument("unknown integrator");
}

}  // namespace camdyn