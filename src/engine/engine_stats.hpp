// camdyn (private) — an engine's work counters (Summary's steps, rhs_evals, lin_setups,
// lin_analyses, engine_restarts).
#pragma once

#include "scene/linear_solver.hpp"  // resolve_linear_solver, for the engines

namespace camdyn {

struct EngineStats {
  long steps = 0;         ///< internal steps taken (accepted by the engine)
  long rhs_evals = 0;     ///< right-hand-side evaluations
  long lin_setups = 0;    ///< numeric factorisations of the Newton matrix (implicit engines)
  long lin_analyses = 0;  ///< symbolic analyses (KLU orderings) of its sparsity pattern
  long reinits = 0;       ///< restarts (CVODE history lost)
  long nonlin_iters = 0;       ///< Newton iterations of the implicit engines
  long nonlin_conv_fails = 0;  ///< steps retried smaller because Newton did not converge
  long err_test_fails = 0;     ///< steps retried smaller because the error test failed
  /// cvode-bdf: the largest BDF order CVODE used for a step (CVodeGetLastOrder after each
  /// call; 0 for the other engines and before a step).
  int max_order_used = 0;
};


}  // namespace camdyn
