// camdyn — what cam designers do all day: the contact force a rigid follower
// needs, the jump (separation) speed, and speed sweeps run in parallel.
//
//   Required contact force of a rigid follower riding the cam (docs/method.md §1–2):
//     F_req(θ, ω, ω̇) = m Ẍ_C + c Ẋ_C + k δ₀ + k (X_C(θ) − x₀),   x₀ = X_C(θ₀) + initial_gap
//   (the return spring's force on the follower is −(k δ₀ + k (u − x₀))), with
//   X_C = h(θ), Ẋ_C = h′ω, Ẍ_C = h″ω² + h′ω̇. At constant speed F_req is a quadratic
//   in ω per cam angle; the follower leaves the cam at the smallest ω where
//   min_θ F_req(θ, ω, 0) reaches zero: the jump speed.
#pragma once

#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/batch.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"

namespace camdyn {

// ---- required force and jump speed ----------------------------------------------------

/// The contact force [force] a rigid follower needs to stay on the cam at cam angle θ [rad]
/// with speed ω [rad/s] and acceleration ω̇ [rad/s²] (formula above; follower.damping is c).
/// Negative: the spring cannot hold the follower there (it separates).
/// @pre follower.kind = "rigid". @throws SceneError for an elastic follower or a bad cam.
double required_contact_force(const Scene& scene, double theta, double omega, double omega_dot);

/// Same at the scene's constant speed cam.speed_rev_s (ω̇ = 0).
/// @throws SceneError as above, and when the scene has a speed table.
double required_contact_force(const Scene& scene, double theta);

/// Options of jump_speed(). Defaults in brackets; validate() names field, value and rule.
struct JumpOptions {
  /// Closed form (rigid follower): cam angles of the scan before the local refinement
  /// (golden section to 1e-12 rad) [7200], ≥ 16.
  int scan_points = 7200;
  /// Simulation (the speed-range map): relative width [1e-3] to which every boundary of
  /// the map (a speed where a phenomenon appears or disappears) is bisected,
  /// 1e-12 ≤ rel_tol ≤ 0.5. The lowest separation speed is its bracket's midpoint.
  double rel_tol = 1e-3;
  /// Simulation: the speed range of the map [rev/s]; 0 = automatic [0, 0]: the rigid-body
  /// closed form (total mass; a network or user follower: |cam.speed_rev_s|) × 0.5 and
  /// × 1.5; an automatic upper end is doubled (up to 6 times, each new range scanned on the
  /// same number of points) while nothing separates, an automatic lower end halved (up to
  /// 6 times) while the lowest speed already separates.
  double lo_rev_s = 0.0, hi_rev_s = 0.0;
  /// Simulation: trial speeds of the map's first scan, equally spaced over [lo, hi] [40],
  /// 2 ≤ grid_points ≤ 100000. A band narrower than the spacing can fall between two
  /// trial speeds unseen.
  int grid_points = 40;
  /// Simulation: worker threads for the trials (a round of the map runs its speeds in
  /// parallel); ≤ 0: all cores [0].
  int jobs = 0;
  /// Simulation: force "simulation" also for a rigid follower [false].
  bool force_simulation = false;
  /// Simulation: called after each trial with (speed, separated); calls are serialised
  /// (made from the worker threads under a lock).
  std::function<void(double, bool)> log;
  /// @throws SceneError naming the field, its value and the rule.
  void validate() const;
};

/// One interval of trial speeds where a phenomenon occurs (the speed-range map). Speeds
/// carry the sign of cam.speed_rev_s; "lower"/"upper" are in |speed|.
struct SpeedBand {
  /// The verdict kind: "opening_liftoff", "nose_float", "closing_bounce", "seat_bounce".
  std::string kind;
  /// Lower end bracketed by [from_out, from_in]: from_out without the phenomenon, from_in
  /// with it. from_out NaN: it occurs at the lowest trial speed (the band may reach lower).
  double from_out = NAN, from_in = NAN;
  /// Upper end bracketed by [to_in, to_out]: to_in with it, to_out without. to_out NaN: it
  /// occurs up to the highest trial speed (the band may reach higher).
  double to_in = NAN, to_out = NAN;
  /// The contact and cam angle [deg] of its first occurrence at from_in.
  std::string contact;
  double theta_deg = NAN;
};

/// One trial speed of the map.
struct SpeedTrial {
  double speed_rev_s = 0;
  bool finished = false;
  /// The verdict kinds of the judged revolutions (empty: no separation), in the order
  /// opening_liftoff, nose_float, closing_bounce, seat_bounce.
  std::vector<std::string> kinds;
  /// The judged revolutions' verdict in words, or the failure's message.
  std::string text;
  /// The scene's acceptance criteria ([criteria]) judged on the whole trial run (settling
  /// revolutions included); empty when the scene sets none or the trial failed.
  std::vector<CriterionResult> criteria;
};

struct JumpResult {
  /// The jump speed [rev/s], with the sign of cam.speed_rev_s (+ if 0); +inf if the
  /// follower never separates (closed form: no cam angle with F_req reaching 0;
  /// simulation: no trial speed departs). Simulation: the lowest separation speed of the
  /// map, the lowest speed where the cam chain departs (opening_liftoff, nose_float or
  /// closing_bounce; a seat bounce alone does not count).
  double jump_speed_rev_s = 0;
  /// "closed-form" (rigid follower) or "simulation" (the speed-range map).
  std::string method;
  /// Cam angle [deg, in [0, 360)] where the margin min_θ F_req first reaches zero
  /// (closed form), or of the first departure at hi_rev_s (simulation).
  double theta_deg = 0;
  /// Simulation: the bracket of the lowest separation speed [rev/s] (lo: no departure in
  /// the judged revolutions, hi: one), and the trials run in all.
  double lo_rev_s = 0, hi_rev_s = 0;
  int simulations = 0;
  /// What the follower does at the jump speed, as a verdict kind (VerdictItem::kind;
  /// docs/contacts.md "The verdict"): closed form — the cam region of theta_deg
  /// ("opening_liftoff", "nose_float", "closing_bounce"); simulation — the first departure
  /// of the judged revolutions at hi_rev_s.
  std::string phenomenon;
  /// Simulation: the verdict of the judged revolutions at hi_rev_s; closed form: the
  /// phenomenon in words with its angle.
  std::string phenomenon_text;
  // ---- the speed-range map (simulation only)
  /// Every band of every phenomenon, by kind (the order above), then by speed.
  std::vector<SpeedBand> bands;
  /// Every trial, by |speed|.
  std::vector<SpeedTrial> trials;
  /// The range scanned [rev/s] (signed as the speeds) and its grids' largest spacing.
  double range_lo_rev_s = NAN, range_hi_rev_s = NAN, grid_spacing_rev_s = NAN;
  /// Trials on the grid (the rest refine the boundaries).
  int grid_simulations = 0;
  /// false when the departure of the cam chain is not monotone in speed: a trial speed
  /// keeps contact above one that departs (a bisection on "it separates" can then miss
  /// the lowest separation speed); monotone_text says where.
  bool monotone = true;
  std::string monotone_text;
  /// Trials that failed (left out of the bands; SpeedTrial::text has the message).
  int failed_simulations = 0;
};

/// The map in words: the lowest separation speed, then every band ("nose_float: from
/// 74.6 (bracket [74.59, 74.61]) to above 120 rev/s"), the monotonicity note. `rpm_per_rev_s`
/// > 0 adds rpm (60: camshaft rpm, 120: engine rpm of a four-stroke).
std::string speed_map_text(const JumpResult& r, double rpm_per_rev_s = 0);

/// The jump speed in words with only the digits its bracket supports: simulation —
/// "24.99 rev/s, bracket [24.987, 24.990] rev/s, width 0.0025 rev/s" (the midpoint rounded
/// to the decimal place of the width, the ends rounded outwards one place further, the
/// width to 2 digits); closed form — 10 significant digits and "(closed form)"; "+inf"
/// when it never separates.
std::string jump_speed_text(const JumpResult& r);

/// The jump speed of `scene` at constant cam speed: closed form for a rigid follower,
/// else the speed-range map: trial speeds on a grid over [lo, hi] run in parallel
/// (jump.settle_revolutions then jump.judge_revolutions revolutions each at its own
/// speed), then every boundary where a phenomenon of the judged revolutions' verdict
/// appears or disappears bisected to rel_tol (the midpoints of a round run in parallel).
/// @throws SceneError on bad input (speed table given, bad options).
JumpResult jump_speed(const Scene& scene, const JumpOptions& options = JumpOptions{});

/// The jump speed of `scene` with a user follower instead of the scene's (camdyn/follower_system.hpp): the speed-range map above with Simulator(scene,
/// follower) trials, the range starting at 0.5× and 1.5× |cam.speed_rev_s| unless options
/// give it; method "simulation". The follower must be safe to share between threads
/// (its methods const and free of shared mutable state), else set options.jobs = 1.
/// @throws SceneError as above, and (file "jump_speed", key "follower") for a null follower.
JumpResult jump_speed(const Scene& scene, std::shared_ptr<const FollowerSystem> follower,
                      const JumpOptions& options = JumpOptions{});

// Batch runs (run_batch, simulate_batch, thread_cpu_seconds): camdyn/batch.hpp, included
// above for the callers that found them here.

// ---- sweeps -------------------------------------------------------------------------------

/// One swept key and its values.
struct SweepAxis {
  std::string key;            ///< dotted scene key, e.g. "cam.speed_rev_s"
  std::vector<double> values;
};

/// The values of an axis: from A to B by `step` (A, A+S, …, ≤ B(1+1e-12)) or in
/// `points` equal steps (linear, or geometric with log). Integer keys are rounded.
/// @throws SceneError ("--from"/"--step"/"--points"/"--log") naming the rule: A < B,
/// finite, step > 0, points ≥ 2, ≤ 10⁶ points, log needs A > 0.
SweepAxis make_sweep_axis(const Scene& scene, const std::string& key, double from, double to,
                          double step, long points, bool log);

/// @throws SceneError("--key") unless `key` is a numeric (real or integer) scene key.
void check_sweep_key(const Scene& scene, const std::string& key);

/// Options of a sweep. Defaults in brackets.
struct SweepOptions {
  /// One axis, or two (a grid; the first key varies slowest) [none].
  std::vector<SweepAxis> axes;
  /// Worker threads; ≤ 0: std::thread::hardware_concurrency() [0].
  int jobs = 0;
  /// Output directory [camdyn-sweep].
  std::string out_dir = "camdyn-sweep";
  /// Keep the points already in DIR/sweep.journal (same sweep only) [false].
  bool resume = false;
  /// false: cpu_seconds written as 0, so whole files compare byte for byte [true].
  bool timing = true;
  /// CPU seconds a point may take before it is stopped and recorded as failed; 0 = no
  /// limit [0].
  double point_timeout_seconds = 0.0;
  /// Polled between and inside points (Ctrl-C); may be null.
  const std::atomic<bool>* stop = nullptr;
  /// Progress after every finished point: (done, total, failed, elapsed wall seconds).
  std::function<void(long, long, long, double)> progress;
  /// A user follower for every point (batch.hpp): called once per point on the
  /// worker's thread. Empty: the scene's follower. With a follower, keys of follower.*,
  /// [spring] and the network tables cannot be swept (the follower replaces them:
  /// SceneError "--key"), and sweep.meta.json's fingerprint includes the follower's name().
  FollowerFactory follower;
  /// @throws SceneError naming field, value and rule (no axis, > 2 axes, > 10⁶ points).
  void validate() const;
};

/// A prepared sweep: points, header and fingerprint (shared by the threaded driver and the
/// MPI driver of the CLI).
struct SweepPlan {
  Scene base;                      ///< resolved base scene
  std::vector<SweepAxis> axes;
  long total = 0;                  ///< number of points
  std::string header;              ///< sweep.csv header line (with '\n')
  std::string fingerprint;         ///< hash of the resolved scene TOML, keys and values
  FollowerFactory follower;        ///< SweepOptions::follower (empty: the scene's follower)
  /// The acceptance criteria the base scene sets ([criteria]): sweep.csv has the columns
  /// criterion_<name>_value and criterion_<name>_pass (1/0; empty when the point failed or
  /// has nothing to judge) for each, before `message`.
  std::vector<std::string> criteria;
  /// The key values of point i (grid: first axis slowest).
  std::vector<double> values(long index) const;
};

/// @throws SceneError on bad options.
SweepPlan plan_sweep(const Scene& base, const SweepOptions& options);

/// The result of one point as journal text: lines "R\tI\tROW", "Q\tI\tPOINCARE_ROW"…,
/// "E\tI" (the E line marks a complete point). Never throws for a failing run or an
/// invalid swept value (recorded with finished = 0 and the message).
std::string run_sweep_point(const SweepPlan& plan, long index, bool timing,
                            double timeout_seconds, const std::atomic<bool>* stop);

/// The journal DIR/sweep.journal and metadata DIR/sweep.meta.json of a sweep.
class SweepJournal {
 public:
  /// Opens (resume: reads and keeps complete points, checking sweep.meta.json's
  /// fingerprint; else starts empty). @throws SceneError("--resume") for another sweep's
  /// files; std::runtime_error on I/O errors.
  SweepJournal(const SweepPlan& plan, const std::string& dir, bool resume);
  ~SweepJournal();
  SweepJournal(const SweepJournal&) = delete;
  SweepJournal& operator=(const SweepJournal&) = delete;
  bool done(long index) const { return done_[static_cast<std::size_t>(index)] != 0; }
  long done_count() const { return n_done_; }
  long failed_count() const { return n_failed_; }
  /// Append one point's journal text (from run_sweep_point) and fsync. Not thread-safe.
  void append(const std::string& block);
  /// Write DIR/sweep.csv and DIR/poincare.csv sorted by point index (atomic rename).
  void write_outputs() const;

 private:
  void take(const std::string& block, bool write);
  const SweepPlan& plan_;
  std::string dir_;
  int fd_ = -1;
  std::vector<char> done_;
  std::vector<std::string> rows_;
  std::vector<std::string> pc_;
  long n_done_ = 0, n_failed_ = 0;
};

struct SweepResult {
  long total = 0, computed = 0, skipped = 0, failed = 0;
  bool interrupted = false;
  std::string csv_path, poincare_path;
};

/// Run a sweep: plan, journal, `jobs` threads from a dynamic queue, sorted outputs.
/// @throws SceneError on bad input; std::runtime_error on I/O errors.
SweepResult run_sweep(const Scene& base, const SweepOptions& options);

/// The sweep.csv columns after the keys (then the criterion columns, SweepPlan::criteria,
/// then `message`).
const std::vector<std::string>& sweep_result_columns();

/// One acceptance criterion over a finished sweep (sweep_criteria_table()).
struct SweepCriterion {
  std::string name;
  long points = 0, judged = 0, failed = 0;  ///< points in sweep.csv, with a pass value, failing
  /// The smallest value of the first key at which the criterion fails (NaN: none fails).
  double first_failure = NAN;
};
/// The criteria of a sweep from its sweep.csv (columns criterion_<name>_pass): per criterion
/// the points judged and failed and the first failing value of the first key (the speed
/// in a speed sweep). Empty when the sweep has no criterion columns.
/// @throws std::runtime_error when the file cannot be read.
std::vector<SweepCriterion> sweep_criteria_table(const std::string& csv_path);

}  // namespace camdyn
