// camdyn — work–precision benchmark ("what accuracy costs in time", `camdyn bench`).
//
// For each scene, run_bench() sweeps Lee's method (engines × tolerances), the penalty
// baseline at its best (linear and Hunt–Crossley laws × implicit engines × k_p × c_p ×
// rtol), and the event-driven (engines × rtol) and holonomic baselines,
// and compares every run with an event-driven reference on a common output grid. It writes
// DIR/work_precision.csv (one row per run), DIR/headlines.csv and DIR/work_precision.md
// (the headlines with their goals, and the tables). The figures are drawn by scripts/camdyn_bench_plot.py (the CLI calls it).
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"

namespace camdyn {

struct BenchOptions {
  /// Scenes to benchmark, with a short label each (same length). Empty: bench_case() of
  /// "A", "A7", "B1", "B2", and in the full sweep also "stiff" and "B1_1000".
  std::vector<Scene> scenes;
  std::vector<std::string> labels;
  /// Quick mode: Lee at two tolerances (a rigid follower on arkode-erk, others on
  /// arkode-dirk and cvode-bdf), penalty critically damped, both laws, at three k_p and one
  /// rtol (1e-8 rigid, 1e-6 otherwise) on cvode-bdf, event at two rtol (1e-4 and 1e-6;
  /// elastic bars 1e-5) on the scene's engine, holonomic at the scene's rtol (elastic bars:
  /// at least 1e-4); elastic-bar scenes cut to
  /// quick_elastic_t_end (unless t_end is given). In both modes the reference of an elastic
  /// bar is the event method on arkode-erk (elastic_reference_rtol), and the full sweep
  /// cuts elastic bars to full_elastic_t_end.
  bool quick = false;
  /// Timing repeats (median of Summary::cpu_seconds), ≥ 1 (3 recommended). A run whose
  /// first timing exceeds repeat_cap_seconds is timed once (noted in the row).
  int repeats = 3;
  double repeat_cap_seconds = 1.0;
  /// Output directory for work_precision.csv / .md (created if missing).
  std::string out_dir = "camdyn-bench";
  /// Common output grid of every run and of the reference [time]; every run lands its
  /// steps on it. 0 (default): per scene, 1e-2 for a rigid follower (coarse enough that
  /// each method's own step control sets its steps; a 1e-4 grid forces Lee to 1e-4 steps,
  /// at which it is exact to round-off on case A at every tolerance) and 1e-4 for an
  /// elastic one (its 1 ms impulse windows and ~3.6 ms axial mode need it).
  double output_dt = 0.0;
  /// CPU budget of one run [s]: a run over it is stopped and the tighter settings of its
  /// series are skipped (rows recorded with the reason). The references have no budget.
  double time_budget_seconds = 20.0;
  /// > 0: overrides every scene's run.t_end.
  double t_end = 0.0;
  /// Quick mode: t_end of elastic scenes when t_end is not given.
  double quick_elastic_t_end = 0.01;
  /// Full mode: t_end of elastic scenes when t_end is not given (at most the scene's own).
  double full_elastic_t_end = 0.05;
  /// Full mode: t_end of an elastic bar on a fine mesh (element crossing time h_e/c under
  /// 2 µs: the stiff bar, B1 on 1000 elements), whose every run costs 10–40× a B1 run per
  /// simulated second (at most the scene's own; docs/bench/measured_tables.md "The full mode").
  double full_fine_bar_t_end = 0.02;
  /// rtol (= atol) of an elastic bar's reference, the event method on arkode-erk; its check
  /// row runs at 10× both. In (0, 1e-8].
  double elastic_reference_rtol = 1e-10;
  /// Directory of cached reference runs (bench_compare.hpp: reference_run(), keyed by the
  /// reference scene and the build); empty: every reference is run.
  std::string reference_cache_dir;
  /// Progress lines (one per run); may be empty.
  std::function<void(const std::string&)> log;
};

/// One benchmark run (one CSV row).
struct BenchRow {
  std::string scene, method, engine, variant;
  double tol = std::numeric_limits<double>::quiet_NaN();  ///< Lee: tol_u; others: rtol
  double kp = std::numeric_limits<double>::quiet_NaN();   ///< penalty only
  double cp = std::numeric_limits<double>::quiet_NaN();   ///< penalty only
  double cpu_seconds = std::numeric_limits<double>::quiet_NaN();  ///< median over repeats
  long steps = 0, rhs_evals = 0;
  /// Implicit engines: Newton-matrix factorisations, Newton iterations, Newton convergence
  /// failures and error-test failures (Summary's counters; 0 on an explicit engine).
  long lin_setups = 0, nonlin_iters = 0, nonlin_conv_fails = 0, err_test_fails = 0;
  long rejected_steps = 0;
  double err_u = std::numeric_limits<double>::quiet_NaN();
  /// rigid: max |F − F_ref| / max F_ref; elastic: 1 ms window impulse error / max window
  /// impulse (chaotic scenes: over the first revolution only).
  double err_force = std::numeric_limits<double>::quiet_NaN();
  /// max |F − F_ref| / max |F_ref| pointwise on the grid (within the pointwise horizon).
  double err_force_pointwise = std::numeric_limits<double>::quiet_NaN();
  /// Impact speeds: max relative error at the reference's impacts (NaN: it has none).
  double impact_speed_err = std::numeric_limits<double>::quiet_NaN();
  /// total variation of F over that of the reference (below 1: smoothing; above: ringing).
  double osc_index = std::numeric_limits<double>::quiet_NaN();
  /// contact impulse per revolution: max relative error over complete revolutions (whole
  /// run when shorter than one revolution).
  double impulse_err = std::numeric_limits<double>::quiet_NaN();
  /// Lee's step-size cap (solver.max_step) of a "step-cap" series; NaN: none.
  double max_step = std::numeric_limits<double>::quiet_NaN();
  /// Separation and impact times: max over the reference's events (within the pointwise
  /// horizon) of |t − t_ref| to the nearest event of the same kind in the run (the run's
  /// t_end when it has none of that kind); NaN when the reference has no events.
  double event_err = std::numeric_limits<double>::quiet_NaN();
  bool finished = false;
  std::string note;
};

/// One headline: the cheapest run of `versus` ("penalty" or "event") over the cheapest Lee
/// run, both with err_force ≤ target (equal accuracy), and its goal.
struct BenchHeadline {
  std::string scene, versus;
  double target = 1e-3;
  double ratio = std::numeric_limits<double>::quiet_NaN();  ///< CPU(versus) / CPU(Lee)
  double goal = std::numeric_limits<double>::quiet_NaN();   ///< NaN: none
  std::string verdict;     ///< "goal met", "goal not met", "no goal", or why there is no ratio
  std::string lee, other;  ///< the two runs (method, engine, settings, CPU, errors)
  std::string text;        ///< one sentence
};

struct BenchResult {
  std::vector<BenchRow> rows;
  /// Per scene label: the headline text (both headlines), and the penalty/Lee ratio (NaN
  /// when it cannot be formed).
  std::vector<std::string> headline_scene;
  std::vector<std::string> headline_text;
  std::vector<double> headline_ratio;
  /// Per scene label: against penalty, then against the event method.
  std::vector<BenchHeadline> headlines;
  std::string csv_path, md_path, headlines_path;
};

/// headlines.csv text (one row per BenchHeadline).
std::string bench_headlines_csv(const std::vector<BenchHeadline>& headlines);

/// The bench's named scenes: the paper's cases "A", "B1", "B2" (paper_case()) and "A7",
/// case A at 7 rev/s — above the rigid follower's separation speed (≈ 6.4 rev/s), so it
/// separates near the cam's nose and lands again with an impact once per revolution;
/// "stiff", a stiff elastic follower (B2's cam with E = 5e8 on 200 elements, 0.05 s:
/// examples/stiff_bar.toml), and "B1_1000", case B1 on 1000 elements (0.05 s).
/// @throws SceneError for another name.
Scene bench_case(const std::string& name);
/// True for a name bench_case() knows.
bool is_bench_case(const std::string& name);

/// Header of work_precision.csv.
const std::vector<std::string>& bench_columns();
/// work_precision.csv text.
std::string bench_csv(const std::vector<BenchRow>& rows);

namespace bench_detail {
/// The headline of `scene` against `versus` (src/study/bench_tables.cpp): the cheapest
/// finished Lee run and the cheapest `versus` run with err_force <= 1e-3, their CPU ratio
/// and the goal's verdict.
BenchHeadline headline(const std::vector<BenchRow>& rows, const std::string& scene, const std::string& versus);
}  // namespace bench_detail

/// Run the sweep and write DIR/work_precision.csv and DIR/work_precision.md.
/// @throws SceneError on a bad option or unwritable directory.
BenchResult run_bench(const BenchOptions& options);

}  // namespace camdyn
