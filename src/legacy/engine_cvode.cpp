// camdyn — the cvode-bdf engine on SUNDIALS 6.4 CVODE: BDF (orders 1–5, ≤ 2 for bars),
// v̇ = M⁻¹ r; the Newton systems through the Schur-complement solver of
// engine_internal.hpp (see engines.cpp for the equations). Split from engines.cpp.
//
// Every SUNDIALS flag is checked (negative → SundialsError naming the call); callbacks
// catch every exception and return −1 so none crosses SUNDIALS.
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

#include "legacy/engine.hpp"
#include "legacy/engine_internal.hpp"
#include "engine/sparse_lu.hpp"
#include "engine/sundials_raii.hpp"

namespace camdyn {
namespace engine_detail {

namespace {

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
    // Our own direct solver for (I − γJ) x = b (SchurLinearSolver); CVODE hands γ to the
    // linear-system function.
    check_flag(CVodeSetLinearSolver(mem, sls_.ls(), sls_.placeholder()), "CVodeSetLinearSolver");
    check_flag(CVodeSetLinSysFn(mem, &CvodeEngine::linsys), "CVodeSetLinSysFn");
  }
  ~CvodeEngine() override {
    mem_.reset();  // CVodeFree before the linear solver it references
  }
  const char* name() const override { return "cvode-bdf"; }
  int error_order() const override { return 2; }
  bool estimates_error() const override { return false; }

  // A trial step of exactly h: CVODE integrates [t, t+h] under its own error control,
  // restarted from (t, y). Lee's iteration retakes the step with other force ramps and
  // needs the same step map each time (the response is then affine in the end force, up
  // to the Newton tolerance, which is tightened for this reason); CVODE's multistep
  // history cannot be saved and restored through its API, so each contact step starts
  // at order 1 (Lee's classic step; the mechanism's methods step CVODE natively,
  // src/engine/ode_engine.cpp).
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
    return 0.0;
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
  static int linsys(double, N_Vector, N_Vector, SUNMatrix, sunbooleantype, sunbooleantype* jcur,
                    double gamma, void* ud, N_Vector, N_Vector, N_Vector) {
    try {
      auto* self = static_cast<CvodeEngine*>(ud);
      self->sls_.prepare(gamma);
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
  double first_h_ = 0;
};

}  // namespace

std::unique_ptr<Engine> make_cvode_engine(std::shared_ptr<const FollowerModel> model,
                                          const SolverSpec& solver, LinearSolverKind lsk,
                                          bool trial, double tol_u) {
  return std::make_unique<CvodeEngine>(std::move(model), solver, lsk, trial, tol_u);
}

}  // namespace engine_detail
}  // namespace camdyn
