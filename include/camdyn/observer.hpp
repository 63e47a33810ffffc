// camdyn — the Observer: receives a run's rows, events and accepted steps as they are made.
#pragma once

#include "camdyn/history.hpp"

namespace camdyn {

/// An accepted step [t0, t0 + h] (Observer::on_step). The pointers are valid during the
/// call only. The holonomic method on ida reports one step per output interval (IDA's
/// internal steps are not seen).
struct StepInfo {
  double t0 = 0;  ///< the step's start
  double h = 0;   ///< its length: it ends at t0 + h, the state the rows after it report
  long step = 0;  ///< accepted steps so far, this one included (Summary::steps)
  int contacts = 0;  ///< entries of the force arrays: one per contact, in the contacts'
                     ///< order (one for a rigid or elastic_bar follower: the cam)
  /// Contact forces (≥ 0 unilateral) at t0, as the previous step ended (the initial forces
  /// for the first step). An impact, separation or cam joint at t0 (on_event) changes the
  /// forces the step starts from after that.
  const double* force_start = nullptr;
  /// Contact forces at t0 + h (after an impact resolved at t0 + h: the held forces then).
  const double* force_end = nullptr;
};

/// What an observer wants after seeing a row (Observer::on_output).
enum class ObserverAction { Continue, Stop };

/// Receives output as it is computed (so a failing run keeps what it computed).
struct Observer {
  virtual ~Observer() = default;
  /// Called for every history row, in time order (through the default on_output).
  virtual void on_row(const HistoryRow&) {}
  /// Called for every history row; the run calls this, not on_row. The default calls
  /// on_row and continues, so an observer that only overrides on_row works unchanged.
  /// Returning Stop ends the run cleanly at the accepted step that produced the row: no
  /// further rows are delivered (the stopping row is the last), and the Summary says
  /// finished = false, termination = StoppedByObserver, message "at t = T: stopped by
  /// observer", t_end = T = that step's end (= row.t unless the row is dense output
  /// inside the step). Stop on the initial row (t = 0) ends the run before any step.
  virtual ObserverAction on_output(const HistoryRow& row) {
    on_row(row);
    return ObserverAction::Continue;
  }
  virtual void on_event(const ContactEvent&) {}
  /// Called about every 0.2 s of wall time.
  virtual void on_progress(double /*t*/, double /*t_end*/, long /*steps*/) {}
  /// Called once per accepted step of every contact method, before the step's rows
  /// (StepInfo: the step and its contact forces at both ends).
  virtual void on_step(const StepInfo& /*step*/) {}
};

}  // namespace camdyn
