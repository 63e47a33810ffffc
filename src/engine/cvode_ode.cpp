// camdyn — the CVODE BDF OdeEngine (ode_engine.hpp; its shared base: ode_engine_base.hpp).
// Trial mode integrates [t, t + h] under CVODE's own control at the spec tolerances
// (restarted each time); native mode: ONE_STEP toward tout, rootfinding, GetDky output.
#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>

#include <algorithm>
#include <memory>

#include "engine/ode_engine_base.hpp"

namespace camdyn {
namespace ode_impl {

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
    set_tolerances(mem, CVodeSVtolerances, "CVodeSVtolerances", CVodeSStolerances, "CVodeSStolerances", spec.rtol,
                   spec.atol);
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
    const InDense scope(*this);
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
    int q = 0;
    check(CVodeGetLastOrder(mem_.get(), &q), "CVodeGetLastOrder");
    stats_.max_order_used = std::max(stats_.max_order_used, q);
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

}  // namespace ode_impl

std::unique_ptr<OdeEngine> make_cvode_ode(const SolverSpec& spec, OdeSystem system, bool trial) {
  return std::make_unique<ode_impl::CvodeOde>(spec, std::move(system), trial);
}

}  // namespace camdyn
