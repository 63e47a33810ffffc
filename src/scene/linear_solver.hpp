// camdyn (private) — the scene's solver.linear_solver with "auto" resolved: what the
// mechanism's description reports and what the engines use.
#pragma once

#include "camdyn/scene.hpp"

namespace camdyn {

/// solver.linear_solver, with "auto" resolved: dense for at most 16 unknowns (2 per node,
/// plus IDA's contact force and multiplier), KLU beyond.
inline LinearSolverKind resolve_linear_solver(const SolverSpec& solver, int nodes) {
  const int unknowns = 2 * nodes + (solver.integrator == Integrator::Ida ? 2 : 0);
  if (solver.linear_solver != LinearSolverKind::Auto) return solver.linear_solver;
  return unknowns <= 16 ? LinearSolverKind::Dense : LinearSolverKind::Klu;
}

}  // namespace camdyn
