// camdyn (private) — RAII owners of SUNDIALS objects, shared by the ODE engines
// (engines.cpp) and the IDA DAE (ida_engine.cpp). Every creation is checked: a null
// result becomes a SundialsError naming the call.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <memory>

#include "engine.hpp"

namespace camdyn {
namespace detail {

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

/// @throws SundialsError naming `call` if p is null.
template <class T>
T* not_null(T* p, const char* call) {
  if (!p) throw SundialsError(call, -1);
  return p;
}

}  // namespace detail
}  // namespace camdyn
