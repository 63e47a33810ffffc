// camdyn — what the mechanism builder built (printed in Summary::FullReport, in
// summary.json): plain strings and numbers, no matrices.
#pragma once

#include <string>
#include <vector>

namespace camdyn {

/// What the model builder built (tested, and printed in the full report).
struct ModelDescription {
  std::string follower;        ///< "rigid" | "elastic_bar" | "network"
  int nodes = 0;               ///< n
  int unknowns = 0;            ///< first-order unknowns handed to the integrator (2n)
  std::string mass;            ///< "scalar" | "consistent" | "lumped"
  bool sparse = false;         ///< sparse matrices assembled
  std::string linear_solver;   ///< "none" (explicit) | "dense" | "klu"
  bool damping = false;        ///< C ≠ 0 (damping term present in the right-hand side)
  bool preload = false;        ///< k δ₀ ≠ 0
  bool varying_speed = false;  ///< ω(t) table (ω̇ ≠ 0)
  std::string contact;         ///< "unilateral" | "holonomic"
  std::vector<std::string> rhs_terms;  ///< e.g. {"inertia", "stiffness", "spring", ...}
  /// Network followers: one line per assembled element and contact (empty otherwise).
  std::vector<std::string> network;
  std::string ToString() const;
};

}  // namespace camdyn
