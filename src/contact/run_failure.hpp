// camdyn (private) — how a run ends early: the failures a contact method throws (each with
// its Termination) and run_to_end, which turns them into the run record's termination.
#pragma once

#include <stdexcept>
#include <string>

#include "camdyn/summary.hpp"
#include "contact/run_record.hpp"
#include "cam/format.hpp"
#include "engine/sundials_error.hpp"

namespace camdyn {
namespace detail {

/// A run that cannot go on (or is asked to stop); the run ends (finished = false) with
/// its termination kind and message.
class StepFailure : public std::runtime_error {
 public:
  StepFailure(Termination kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  /// A step that failed for a reason without its own Termination value.
  explicit StepFailure(const std::string& what) : StepFailure(Termination::StepFailure, what) {}
  Termination kind() const { return kind_; }

 private:
  Termination kind_;
};

/// A contact iteration that did not converge: recoverable, the step is retried with Δt/2.
class IterationFailure : public StepFailure {
 public:
  /// why: what made it fail, if known (a non-finite residual's cause).
  explicit IterationFailure(const std::string& why = "")
      : StepFailure(Termination::IterationFailure, "contact iteration did not converge" + (why.empty() ? "" : " (" + why + ")")) {}
};

/// The step size fell below the floor (message "step size underflow (h = …)").
class StepSizeUnderflow : public StepFailure {
 public:
  /// why: what made the last steps fail, if known (a right-hand side that threw).
  explicit StepSizeUnderflow(double h, const std::string& why = "")
      : StepFailure(Termination::StepSizeUnderflow,
                    "step size underflow (h = " + fmt(h) + ")" + (why.empty() ? "" : ": the last trial failed with " + why)) {}
};

/// Runs a method's loop `body` and sets how the run ended: Finished, or through
/// end_run(kind, what) for a StepFailure (its kind), a SundialsError (SolverError) or any
/// other exception (Error).
template <class EndRun, class Body>
void run_to_end(RunRecord& sum, EndRun end_run, Body body) {
  try {
    body();
    sum.finished = true;
    sum.termination = Termination::Finished;
    sum.message = "finished";
  } catch (const StepFailure& e) {
    end_run(e.kind(), e.what());
  } catch (const SundialsError& e) {
    end_run(Termination::SolverError, e.what());
  } catch (const std::exception& e) {
    end_run(Termination::Error, e.what());
  }
}

}  // namespace detail
}  // namespace camdyn
