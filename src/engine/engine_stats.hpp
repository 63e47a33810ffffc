// camdyn (private) — an engine's work counters (Summary's steps, rhs_evals, lin_setups,
// lin_analyses, engine_restarts) and the choice of its linear solver.
#pragma once

#include "camdyn/scene.hpp"

namespace camdyn {

struct EngineStats {
  long steps = 0;         ///< internal steps taken (accepted by the engine)
  long rhs_evals = 0;     ///< right-hand-side evaluations
  long lin_setups = 0;    ///< numeric factorisations of the Newton matrix (implicit engines)
  long lin_analyses = 0;  ///< symbolic analyses (KLU orderings) of its sparsity pattern
  long reinits = 0;       ///< restarts (CVODE history lost)
};

/// solver.linear_solver, with "auto" resolved: dense for at most 16 unknowns (2 per node,
/// plus IDA's contact force and multiplier), KLU beyond.
inline LinearSolverKind resolve_linear_solver(const SolverSpec& solver, int nodes) {
  const int unknowns = 2 * nodes + (solver.integrator == Integrator::Ida ? 2 : 0);
  if (solver.linear_solver != LinearSolverKind::Auto) return solver.linear_solver;
  return unknowns <= 16 ? LinearSolverKind::Dense : LinearSolverKind::Klu;
}

}  // namespace camdyn
