// camdyn (private) — what a contact method measures while it runs: the RunRecord. The
// methods and ContactRun write it (counters, events, extremes, the energy ledger's numbers,
// how the run ended, the engines' statistics, the run's warnings); they never write the
// public Summary. SummaryBuilder (src/run/summary_builder.hpp) reads the record and the
// run's parts (RunParts) and fills the Summary once.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/history.hpp"
#include "camdyn/model_description.hpp"
#include "camdyn/summary.hpp"  // Termination, LevelStats, ContactResult, ElementResult

namespace camdyn {
namespace detail {

class DesignerStats;
class RunAnalysis;
class FlightLog;
class SurgeTracker;

/// The measurements of one run, in the units of the Summary fields of the same names
/// (summary.hpp documents each).
struct RunRecord {
  // ---- how the run ended (run_to_end, src/contact/run_failure.hpp)
  bool finished = false;
  Termination termination = Termination::Error;
  std::string message;
  double t_end = 0;  ///< time reached
  // ---- steps and the engines' statistics (summed over the run's engines)
  long steps = 0, rejected_steps = 0, rhs_evals = 0;
  long lin_setups = 0, lin_analyses = 0;
  long nonlin_iters = 0, nonlin_conv_fails = 0, err_test_fails = 0;
  long engine_restarts = 0;
  int max_bdf_order_used = 0;  ///< cvode-bdf: the largest BDF order a step used (0: none)
  // ---- the contact method's own statistics
  long contact_iterations = 0;
  LevelStats level_u, level_v, level_a;
  long iteration_failures = 0;
  long relocated_steps = 0;
  // ---- contacts: counts, extremes at the accepted step ends, events, per contact
  long separations = 0, impacts = 0;
  double max_contact_force = 0;
  double min_gap = INFINITY;  ///< smallest gap at the step ends; +inf: none sampled
  double max_penetration = 0;
  double first_tensile_time = -1;  ///< holonomic: first time a held force pulls (−1: never)
  std::vector<ContactEvent> events;
  std::vector<ContactResult> contacts;  ///< one per contact, in the mechanism's order
  std::vector<ElementResult> elements;  ///< the reported element quantities (nonlinear network)
  // ---- the energy ledger (RunContract documents the scale and magnitude)
  double energy_residual = 0;   ///< |W − ΔE − D| at the end
  double energy_scale = 0;      ///< largest |cam work| and |dissipated energy| over the run
  double energy_magnitude = 0;  ///< the ledger's round-off scale
  // ---- the run's clock
  double cpu_seconds = 0, wall_seconds = 0;
  /// The mechanism's description as the run amended it (a camshaft's held frequencies,
  /// IDA's linear solver and unknowns).
  ModelDescription model;
  /// Warnings of the run itself (the atol floor used, …), in the order they arose.
  std::vector<std::string> warnings;
};

/// The parts of a run that each contribute a section of the Summary (their finish()):
/// designer statistics and cam geometry, the run analysis (film, lift deviation, landings,
/// ramp velocity, valve timing), the flight log (the contract's flights) and the surge.
struct RunParts {
  const DesignerStats& designer;
  const RunAnalysis& analysis;
  const FlightLog& flights;
  const SurgeTracker& surge;
};

}  // namespace detail
}  // namespace camdyn
