// camdyn — SUNDIALS return flags in words (SundialsError's message). A user reads "the
// error test failed repeatedly", not "flag -3".
//
// CVODE, ARKODE (ARKStep, ERKStep) and the SUNDIALS objects share the meanings of flags
// −1 … −12 and −20 … −27 (cvode.h, arkode.h); IDA (ida.h) differs from −8 on.
#include <string>

#include "engine/sundials_error.hpp"

namespace camdyn {
namespace {

bool starts_with(const std::string& s, const char* p) { return s.rfind(p, 0) == 0; }

const char* ode_words(int flag) {
  switch (flag) {
    case -1: return "took the maximum number of internal steps without reaching the output time";
    case -2: return "could not satisfy the accuracy requested (tolerances too small for double precision)";
    case -3: return "the error test failed repeatedly (the step size fell to its minimum without meeting the tolerance: a solution too fast, or a non-finite or overflowing state)";
    case -4: return "the Newton iteration failed to converge repeatedly";
    case -5: return "the linear solver could not be initialised";
    case -6: return "the linear solver's setup (factorisation) failed";
    case -7: return "the linear solve failed";
    case -8: return "the right-hand side failed unrecoverably";
    case -9: return "the right-hand side failed at the first call";
    case -10: return "the right-hand side failed repeatedly (recoverable errors at every step size)";
    case -11: return "the right-hand side failed and could not recover";
    case -12: return "the root function failed";
    case -20: return "out of memory";
    case -21: return "integrator memory missing (internal error)";
    case -22: return "an input was illegal (non-finite or out of range)";
    case -23: return "integrator not initialised (internal error)";
    case -24: return "bad derivative order requested (internal error)";
    case -25: return "the requested time is outside the last step (internal error)";
    case -26: return "bad output vector (internal error)";
    case -27: return "the output time is too close to the start time";
    default: return nullptr;
  }
}

const char* ida_words(int flag) {
  switch (flag) {
    case -1: return "took the maximum number of internal steps without reaching the output time";
    case -2: return "could not satisfy the accuracy requested (tolerances too small for double precision)";
    case -3: return "the error test failed repeatedly (the step size fell to its minimum without meeting the tolerance)";
    case -4: return "the Newton iteration failed to converge repeatedly";
    case -5: return "the linear solver could not be initialised";
    case -6: return "the linear solver's setup (factorisation) failed";
    case -7: return "the linear solve failed";
    case -8: return "the residual function failed unrecoverably";
    case -9: return "the residual function failed repeatedly";
    case -10: return "the root function failed";
    case -11: return "the inequality constraints could not be met";
    case -12: return "the residual function failed at the first call";
    case -13: return "the line search of the initial-condition calculation failed";
    case -14: return "the residual or linear solver failed recoverably but could not recover";
    case -20: return "out of memory";
    case -22: return "an input was illegal (non-finite or out of range)";
    default: return ode_words(flag);
  }
}

}  // namespace

std::string sundials_flag_words(const std::string& call, int flag) {
  // Creation failures and our own checks name themselves ("klu_l_factor",
  // "ERKStepEvolve (trial step ended short of t + h)"): no flag meaning.
  if (call.find(" (") != std::string::npos) return "failed";
  const char* w = nullptr;
  if (starts_with(call, "IDA"))
    w = ida_words(flag);
  else if (starts_with(call, "CVode") || starts_with(call, "ARKStep") || starts_with(call, "ERKStep"))
    w = ode_words(flag);
  if (!w) return flag < 0 ? "failed" : "returned a warning";
  return w;
}

}  // namespace camdyn
