// camdyn — tolerance sweep (`camdyn bench --tolerance-sweep`, issue 25).
//
// Every contact method × engine × scene over rtol from 1e-2 to 1e-12 (contact.tol_u scaled
// alike, in the scene's own ratio tol_u/rtol; atol = min(scene atol, 1e-3·rtol)). Each run
// either finishes, or is refused at the start (SceneError: a tolerance below what double
// precision holds for the scene, see docs/tolerances.md), or is stopped by the CPU budget.
// Its errors against a tight reference of the same scene and contact model (rtol 1e-12)
// are written to DIR/tol_sweep.csv; DIR/tol_sweep_series.csv and DIR/tol_sweep.md say per
// series whether the error falls as rtol falls (within a factor 2) down to the floor the
// sweep names. The figures (DIR/tol_sweep_<scene>.png) are drawn by
// scripts/camdyn_tol_sweep_plot.py.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"

namespace camdyn {

struct ToleranceSweepOptions {
  /// Scenes with a label each (same length). Empty: none (the CLI fills the set).
  std::vector<Scene> scenes;
  std::vector<std::string> labels;
  /// rtol grid, loosest first, each in [1e-14, 0.1]. Default: 1e-2, 1e-3, …, 1e-12.
  std::vector<double> rtols{1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  /// rtol grid of elastic and network scenes (empty: `rtols`).
  std::vector<double> heavy_rtols;
  /// Contact methods ("lee", "event", "holonomic", "penalty") and engines ("arkode-erk",
  /// "arkode-dirk", "cvode-bdf", "ida"); empty: all. A method × engine the scene does not
  /// allow (e.g. ida without holonomic) is recorded once as "unsupported" with the reason.
  std::vector<std::string> methods, engines;
  /// rtol of the references (atol = 1e-2 × it); their own error is measured against the
  /// same run at 10 × both. 1e-12 by default; 1e-10 makes elastic and network scenes
  /// affordable (the floor the sweep names rises accordingly).
  double reference_rtol = 1e-12;
  /// CPU budget of one run [s]; a run over it is stopped and the tighter runs of its series
  /// are recorded as skipped. References have no budget.
  double time_budget_seconds = 20.0;
  /// > 0: overrides every scene's run.t_end.
  double t_end = 0.0;
  /// Output directory (created if missing).
  std::string out_dir = "camdyn-tol-sweep";
  /// Progress lines; may be empty.
  std::function<void(const std::string&)> log;
};

/// One run (a row of tol_sweep.csv). status: "finished", "refused" (SceneError at the
/// start: message is its text), "failed" (the run stopped: message says why), "over
/// budget", "skipped" (after an over-budget run of the same series), "unsupported",
/// "reference" (the reference run itself).
struct ToleranceRow {
  std::string scene, method, engine;
  double rtol = std::numeric_limits<double>::quiet_NaN();
  double tol_u = std::numeric_limits<double>::quiet_NaN();  ///< Lee only
  double atol = std::numeric_limits<double>::quiet_NaN();
  double cpu_seconds = std::numeric_limits<double>::quiet_NaN();
  long steps = 0;
  /// max |u_c − u_ref| on the scene's output grid [length].
  double err_u = std::numeric_limits<double>::quiet_NaN();
  /// Contact force, relative: as in `camdyn bench` (a rigid follower that never separates:
  /// max |F − F_ref| / max F_ref; otherwise the 1 ms impulse error / largest 1 ms impulse).
  double err_force = std::numeric_limits<double>::quiet_NaN();
  std::string status, message;
  /// The run's contract (Summary::contract): 1 held, 0 not held, −1 not checked (the run
  /// did not finish). Column "contract_held" (empty when not checked).
  int contract_held = -1;
};

/// Whether one error series falls as rtol falls. Built by check_series().
struct SeriesCheck {
  std::string scene, method, engine, quantity;  ///< quantity: "err_u" or "err_force"
  /// The floor this series cannot go below: the larger of the reference's own error (its
  /// distance to the reference one decade looser) and 4 ulps of the quantity's scale.
  double floor = std::numeric_limits<double>::quiet_NaN();
  /// Smallest error in the series and the loosest rtol at which the series is within a
  /// factor 2 of it (where it levels off).
  double err_min = std::numeric_limits<double>::quiet_NaN();
  double rtol_level = std::numeric_limits<double>::quiet_NaN();
  int finished = 0;  ///< finished runs in the series
  /// No finished run's error exceeds 2 × max(the previous finished run's error, floor).
  bool monotone = true;
  /// err_min ≤ 10 × floor: the series reaches the named floor.
  bool reaches_floor = false;
  std::string verdict;  ///< one sentence, every violation named with its numbers
};

/// The check on one series: `rtols` loosest first, `errs` the errors (NaN: not finished).
/// Monotone unless some finished error exceeds 2·max(previous finished error, floor).
SeriesCheck check_series(const std::vector<double>& rtols, const std::vector<double>& errs,
                         double floor);

struct ToleranceSweepResult {
  std::vector<ToleranceRow> rows;
  std::vector<SeriesCheck> checks;
  std::string csv_path, series_path, md_path;
};

/// Header of tol_sweep.csv, and its text.
const std::vector<std::string>& tolerance_sweep_columns();
std::string tolerance_sweep_csv(const std::vector<ToleranceRow>& rows);

/// Run the sweep and write DIR/tol_sweep.csv, DIR/tol_sweep_series.csv, DIR/tol_sweep.md.
/// @throws SceneError (an option out of range, an unknown method or engine name, an
/// unwritable directory, or a scene that does not validate).
ToleranceSweepResult run_tolerance_sweep(const ToleranceSweepOptions& options);

}  // namespace camdyn
