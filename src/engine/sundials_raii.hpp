// camdyn (private) — RAII owners of SUNDIALS objects, shared by the ODE engines
// (ode_engine.cpp) and the IDA DAE (ida_engine.cpp). Every creation is checked: a null
// result becomes a SundialsError naming the call.
#pragma once

#include <string>

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <memory>

#include "engine/sundials_error.hpp"

namespace camdyn {
namespace detail {

// A CVODE trial step (one Lee step, CV_NORMAL to its end) takes at most kTrialMaxSteps
// internal steps, none shorter than trial_min_step: CVODE would otherwise keep stepping
// with t + h = t ("the solver will continue anyway") and never return where the
// integrator cannot follow a trial force (its error test failing at every h). Either
// limit makes CVode fail; Lee's step then rejects and halves.
constexpr long kTrialMaxSteps = 100000;
inline double trial_min_step(double t, double h) {
  return std::min(0.5 * h, 16.0 * DBL_EPSILON * std::abs(t + h));
}
/// CVODE's message handler for trial steps: silent. A trial step CVODE cannot complete is
/// an expected outcome (Lee's step rejects it and halves; Summary::iteration_failures
/// counts it), not a message for the user's terminal.
inline void quiet_cvode_errors(int, const char*, const char*, char*, void*) {}

/// SUNDIALS' error handler for every integrator (ERKStep/ARKStep/CVode/IDA SetErrHandlerFn,
/// eh_data = a std::string): keeps the last message, never prints it. The failing call's
/// SundialsError carries it into the run's message (no raw SUNDIALS text on stderr).
inline void capture_sundials_message(int, const char* module, const char* function, char* msg, void* data) noexcept {
  if (!data) return;
  try {
    *static_cast<std::string*>(data) =
        std::string(module ? module : "SUNDIALS") + " " + (function ? function : "") + ": " + (msg ? msg : "");
  } catch (...) {
  }
}

struct ContextHolder {
  SUNContext ctx = nullptr;
  ContextHolder() { check_flag(SUNContext_Create(nullptr, &ctx), "SUNContext_Create"); }
  ~ContextHolder() { SUNContext_Free(&ctx); }
  ContextHolder(const ContextHolder&) = delete;
  ContextHolder& operator=(const ContextHolder&) = delete;
};
struct NVecDel {
  void operator()(_generic_N_Vector* v) const { N_VDestroy(v); }
};
struct MatDel {
  void operator()(_generic_SUNMatrix* m) const { SUNMatDestroy(m); }
};
struct LSDel {
  void operator()(_generic_SUNLinearSolver* s) const { SUNLinSolFree(s); }
};
using NVec = std::unique_ptr<_generic_N_Vector, NVecDel>;
using Mat = std::unique_ptr<_generic_SUNMatrix, MatDel>;
using LS = std::unique_ptr<_generic_SUNLinearSolver, LSDel>;
struct NLSDel {
  void operator()(_generic_SUNNonlinearSolver* s) const { SUNNonlinSolFree(s); }
};
using NLS = std::unique_ptr<_generic_SUNNonlinearSolver, NLSDel>;

/// Owners of the integrators' memory blocks (std::unique_ptr<void, …>).
struct ArkDel {
  void operator()(void* m) const { ARKStepFree(&m); }
};
struct ErkDel {
  void operator()(void* m) const { ERKStepFree(&m); }
};
struct CvDel {
  void operator()(void* m) const { CVodeFree(&m); }
};

/// A serial N_Vector of length n, zero. @throws SundialsError if it cannot be made.
inline NVec make_nvec(long n, SUNContext ctx) {
  N_Vector v = N_VNew_Serial(n, ctx);
  if (!v) throw SundialsError("N_VNew_Serial", -1);
  N_VConst(0.0, v);
  return NVec(v);
}

/// WRMS norm of err with weights rtol·|y_i| + atol (0 for an empty err).
template <class V>
double wrms_norm(const V& err, const V& y, double rtol, double atol) {
  if (err.size() == 0) return 0.0;
  double s = 0.0;
  for (decltype(err.size()) i = 0; i < err.size(); ++i) {
    const double w = rtol * std::abs(y[i]) + atol;
    s += (err[i] / w) * (err[i] / w);
  }
  return std::sqrt(s / double(err.size()));
}

/// @throws SundialsError naming `call` if p is null.
template <class T>
T* not_null(T* p, const char* call) {
  if (!p) throw SundialsError(call, -1);
  return p;
}

}  // namespace detail
}  // namespace camdyn
