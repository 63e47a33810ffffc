// camdyn — what a run reports at its end: the Summary (summary.json, BriefReport,
// FullReport) and the results it holds (per contact, per element, the verdict, the
// criteria, the run's contract).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/history.hpp"
#include "camdyn/model_description.hpp"

namespace camdyn {

/// One Poincaré sample: the follower's contact face when the cam passes the section angle
/// (run.poincare_angle_deg) in revolution k (k = 0, 1, …; k ≥ run.settle_revolutions).
/// u_c, v_c are cubic Hermite interpolants between the accepted steps around the crossing.
struct PoincareSample {
  long revolution = 0;
  double t = 0, u_c = 0, v_c = 0;
};

/// Iteration statistics of one level of Lee's method.
struct LevelStats {
  long total = 0;  ///< iterations summed over accepted steps
  int max = 0;     ///< most iterations in one accepted step
  long steps = 0;  ///< accepted steps counted
  double mean() const { return steps ? double(total) / double(steps) : 0.0; }
};

/// How a run ended (Summary::termination). Every end of a run sets exactly one; the
/// message (Summary::message) gives the details ("at t = T: …").
enum class Termination {
  Finished,           ///< reached run.t_end (finished = true; the only such value)
  StoppedByObserver,  ///< an Observer returned ObserverAction::Stop from on_output
  StoppedByCaller,    ///< the caller's stop flag was set (Simulator::run's `stop`: Ctrl-C in
                      ///< the CLI, a sweep's point timeout, Python's observer returning False)
  MaxSteps,           ///< run.max_steps (accepted + rejected steps) reached
  StepSizeUnderflow,  ///< the step size fell below 1e-14·max(1, t)
  IterationFailure,   ///< a contact iteration did not converge and was not retried
  NonFinite,          ///< the state or the contact force became NaN or infinite
  StepFailure,        ///< a step could not be completed for another reason (see message)
  SolverError,        ///< a SUNDIALS call failed (e.g. CVODE's error test or convergence)
  InvalidScene,       ///< run_batch only: the scene failed validation (message: SceneError)
  Error,              ///< any other exception (e.g. a mass matrix that is not positive
                      ///< definite); the message is its what()
};
/// "finished", "stopped_by_observer", "stopped_by_caller", "max_steps",
/// "step_size_underflow", "iteration_failure", "non_finite", "step_failure",
/// "solver_error", "invalid_scene", "error" (summary.json's "termination").
const char* to_string(Termination v);

/// One reported quantity of a network's elements (a history column force_<name> with
/// run.element_forces, whatever that flag): its extremes over the accepted step ends, its
/// value at the end and its range (max − min) over the last whole camshaft revolution (NaN
/// before one is complete). A hydraulic_lash_adjuster 'h' reports h (force), h_pressure,
/// h_travel (plunger travel: its cycle_range is the travel per cycle), h_pumped and
/// h_leaked (oil volumes through the check valve and the leak-down clearance since t = 0:
/// their `end` values are the pump-up and leak-down totals).
struct ElementResult {
  std::string name;
  double min = NAN, max = NAN, end = NAN, cycle_range = NAN;
};

/// Results of one contact of a network or user follower (summary.json
/// "contacts", FullReport, Python). Angles: cam degrees in [0, 360); NaN (null) when the
/// thing did not happen. The lash take-up window: the cam angles where the cam's lift X
/// lies between the lowest and the highest take-up level on the path from the cam, each
/// widened by 1 % of the lift (the levels: every cam contact's clearance and the cam lift at
/// which each lash contact reached from a cam contact closes, through levers and rigid
/// links; docs/contacts.md): the load passes between the cam, the lashes and the stops
/// there, the forces fall to zero by design; min_force leaves that window out, and a
/// separation inside it is no loss of margin.
struct ContactResult {
  std::string name;
  /// Smallest force while closed outside the lash take-up window, located inside each
  /// accepted step (docs/contacts.md "Extremes inside the steps": independent of the output
  /// grid; 0 if the contact separated outside it); NaN if never closed there.
  double min_force = NAN;
  double min_force_theta_deg = NAN;
  double max_impact_velocity = 0;     ///< largest approach speed at its impacts
  double max_impact_theta_deg = NAN;
  double first_separation_theta_deg = NAN;
  double first_impact_theta_deg = NAN;
  long impacts = 0, separations = 0;
  /// Cam contacts: largest side load |F tan φ| on the follower's guide at the
  /// accepted step ends while closed (F the contact's axial force, φ the pressure angle;
  /// 0 for a flat face) and its cam angle; NaN for the other contacts and if never closed.
  double max_side_load = NAN;
  double max_side_load_theta_deg = NAN;
  /// A coil-to-coil contact of a spring whose coils clash: the spring's name ("" otherwise).
  std::string coil_spring;
};

/// The coil clash of one spring whose coils clash (summary.json "coil_clash"): its coil
/// contacts' impacts together.
struct CoilClashResult {
  std::string spring;
  long impacts = 0;                    ///< coil-to-coil impacts, all coils
  double first_impact_theta_deg = NAN; ///< cam angle of the first one [deg, 0..360)
  double max_impact_velocity = 0;      ///< largest closing speed of two coils at an impact
  long coils_closed = 0;               ///< coil contacts that closed at least once
};

/// One phenomenon of the verdict (docs/contacts.md "The verdict"), the first
/// occurrence of its kind on its contact. Kinds: "opening_liftoff" (lift-off on the
/// opening flank), "nose_float" (float on the nose), "closing_bounce" (bounce on the
/// closing flank), "seat_bounce" (a stop re-impacts after its closing impact),
/// "no_separation" (none of these: the only item then, contact "", angles NaN).
struct VerdictItem {
  std::string kind;
  std::string contact;              ///< the contact's name ("cam" for a single follower)
  double theta_deg = NAN;           ///< cam angle of the first occurrence [deg, 0..360)
  double speed_rev_s = NAN;         ///< cam speed there [rev/s] (signed, as cam.speed_rev_s)
  long count = 0;                   ///< occurrences in the run
  std::string text;                 ///< in words, e.g. "float on the nose: contact 'cam' at 159.2 deg, 70 rev/s"
};

/// The surge of one spring with coil masses (summary.json "surge"): how far its coils move
/// from the quasi-static (linear) deflection shape, max over the inner coil masses of
/// |x_i − x_i,static| with x_i,static the two ends' displacements interpolated linearly, at
/// the accepted step ends.
struct SurgeResult {
  std::string spring;
  double amplitude = 0;              ///< largest over the run [length]
  double theta_deg = NAN;            ///< cam angle of that largest [deg, 0..360)
  /// The largest in each camshaft revolution from the start angle (the last one partial).
  std::vector<double> per_revolution;
  std::vector<double> per_revolution_theta_deg;  ///< their cam angles [deg, 0..360)
};

/// The flights of one contact (RunContract::flights): separation → next impact, and those
/// the gap tolerance cannot resolve (apex ≤ RunContract::flight_threshold, 10⁻³ of the
/// method's gap tolerance, or a duration below the rootfinder's time resolution; docs/tolerances.md "Flights below the gap tolerance").
struct FlightCount {
  std::string contact;
  long flights = 0;                    ///< separation → impact pairs
  long unresolved = 0;                 ///< of them, below what the tolerance resolves
  double min_apex = NAN;               ///< least apex (largest gap) of a flight [length]
  double max_unresolved_apex = 0;      ///< largest apex among the unresolved ones
  double max_unresolved_duration = 0;  ///< longest duration among the unresolved ones [s]
};

/// What a finished run checks about itself before it calls its result good (issue 35;
/// docs/tolerances.md "The run's contract"). Checked only for runs that reached t_end.
struct RunContract {
  bool checked = false;  ///< the checks ran (the run finished)
  bool held = true;      ///< every check passed (true when not checked)
  /// One line per failed check, each naming the measured number, the bound and the key to
  /// tighten (summary.json "contract": {"held", "violations"}).
  std::vector<std::string> violations;
  /// Largest |cam work| and |dissipated energy| over the run: the energy ledger's scale.
  double energy_scale = 0;
  /// The ledger's round-off scale: the largest of |stored energy| at the run's start and end
  /// and the largest contact force times the cam's lift (the energies whose differences and
  /// integrals the ledger W − ΔE − D adds up).
  double energy_magnitude = 0;
  /// The energy residual the contract allows: min(max(100·rtol, 1e-5), 0.01)·energy_scale,
  /// but at least the round-off 1000ε·energy_magnitude (a run in which almost nothing moves).
  double energy_bound = 0;
  /// Warnings of a finished run (the contract still holds): one line per contact with
  /// flights the gap tolerance cannot resolve, naming contact.tol_u and the numbers.
  std::vector<std::string> warnings;
  /// Per contact with flights (contacts without any are left out).
  std::vector<FlightCount> flights;
  /// The apex at or below which a flight is unresolved: 10⁻³ of the method's gap tolerance
  /// (Lee: contact.tol_u; event: min(tol_u, max(rtol·X, 1000ε·X))); 0 for penalty.
  double flight_threshold = 0;
};

/// One acceptance criterion of a run ([criteria]; Summary::criteria): its measured value,
/// the cam angle where it is worst and whether it holds. Names: "seating_velocity",
/// "bounce_height", "bounce_count", "force_margin_<contact>" (one per contact; "force_margin"
/// for a single follower), "hertz_stress", "film_thickness", "lambda", "ramp_velocity",
/// "lift_deviation".
struct CriterionResult {
  std::string name;
  std::string key;          ///< the scene key of its limit ("criteria.max_seating_velocity")
  bool is_max = true;       ///< true: value ≤ limit passes; false: value ≥ limit passes
  double limit = NAN;
  /// The worst value over the run (largest for a maximum, least for a minimum); NaN when
  /// the run has nothing to judge (no seat impact, a contact never closed, …): that passes,
  /// and `note` says why.
  double value = NAN;
  double theta_deg = NAN;   ///< cam angle of the worst value [deg, 0..360) (NaN: none)
  bool pass = true;
  std::string note;         ///< why value is NaN, else ""
};

/// One landing of a seat (a stop contact on side "below"): an impact on it after the cam
/// lifted its node past the take-up, and the re-impacts (bounces) before the cam lifts it
/// again. Every seat impact's approach speed is a seating velocity.
struct SeatLanding {
  std::string contact;
  double t = 0, theta_deg = NAN;
  double velocity = 0;        ///< approach speed of the landing impact
  long bounces = 0;           ///< re-impacts after it before the cam lifts the node again
  double bounce_height = 0;   ///< largest seat gap between consecutive impacts (the apex inside the flight)
                              ///< of this landing (0: no bounce)
  double max_velocity = 0;    ///< largest approach speed among the landing and its bounces
  double max_velocity_theta_deg = NAN;
  double bounce_height_theta_deg = NAN;  ///< cam angle of the re-impact ending the highest bounce
};

/// Extremes of the valve's dynamic minus kinematic lift over one cam revolution (revolution
/// k = 0, 1, … holds the cam progress from the run's start in (360°k, 360°(k + 1)], the first
/// also the start), located inside each accepted step.
struct LiftDeviationRevolution {
  long revolution = 0;
  double min = NAN, min_theta_deg = NAN, max = NAN, max_theta_deg = NAN;
};

/// The timing of one valve of a camshaft run (summary.json "valve_timing"; issue 40;
/// src/results/valve_timing.hpp). The valve is open while its displacement exceeds
/// `threshold`, 1 % of its kinematic lift. Kinematic angles: the cam's own angle (station
/// angle − offset) where the kinematic lift (every part rigid, the clearances on the path
/// taken up) crosses the threshold. Dynamic angles: the crank's angle − the cam's offset
/// (the angle the cam would have on a rigid shaft and drive) where the valve's displacement
/// crosses it, located inside the steps: the first opening and the last closing of a cam
/// revolution, of the last revolution with both. Angles in camshaft degrees [0, 360) (crank
/// degrees are twice); errors dynamic − kinematic in (−180, 180] (> 0: late); NaN: did not
/// happen.
struct ValveTimingResult {
  std::string valve;    ///< the valve's node: a seat's node its cam contact's path reaches, else its follower
  std::string contact;  ///< the cam contact that drives it
  int cam = 0;          ///< its cam (the index in camshaft.cam_stations)
  double threshold = NAN;  ///< the lift above which it is open [length]
  double kinematic_opening_deg = NAN, kinematic_closing_deg = NAN;
  double opening_deg = NAN, closing_deg = NAN;
  double opening_error_deg = NAN, closing_error_deg = NAN;
  long openings = 0;    ///< openings seen in the run
};

struct Summary {
  std::string scene;
  bool finished = false;  ///< termination == Termination::Finished
  Termination termination = Termination::Error;
  std::string message;
  double t_end = 0;  ///< time reached
  long steps = 0, rejected_steps = 0, rhs_evals = 0;
  /// Implicit engines: numeric factorisations of the Newton matrix (redone only when the
  /// step size changed) and symbolic analyses of its pattern (once per engine).
  long lin_setups = 0, lin_analyses = 0;
  /// Implicit engines (arkode-dirk, cvode-bdf, ida): Newton iterations, steps retried
  /// smaller because Newton did not converge, and steps retried because the error test
  /// failed (the integrator's own counters, summed over its restarts).
  long nonlin_iters = 0, nonlin_conv_fails = 0, err_test_fails = 0;
  /// Multistep engine (cvode-bdf): restarts, each losing CVODE's history and order
  /// (at the start, and where the state jumps or its equations change: impacts,
  /// separations; Lee's trial steps on networks: every trial).
  long engine_restarts = 0;
  long contact_iterations = 0;
  LevelStats level_u, level_v, level_a;  ///< Lee's three levels
  long iteration_failures = 0;           ///< steps retried because an iteration failed
  /// Lee "located": trial steps retaken shorter to land on a separation or an impact
  /// found inside them (not counted as rejected steps).
  long relocated_steps = 0;
  long separations = 0, impacts = 0;
  double max_contact_force = 0;
  double min_gap = 0;          ///< smallest gap (−s) seen
  double max_penetration = 0;  ///< max(0, −gap)
  double first_tensile_time = -1;  ///< holonomic: first time the constraint force pulls
  double energy_residual = 0;      ///< |W − ΔT − ΔV − D| at the end
  /// What solver.rtol (and contact.tol_u) bound on this run's engine and method, in words
  /// (FullReport's "tolerance" line; docs/tolerances.md).
  std::string tolerance_meaning;
  /// Non-empty when the requested tolerance is known to buy less accuracy on this engine
  /// than on the one-step engines (cvode-bdf on an elastic follower: BDF orders ≤ 2 damp
  /// the modes the step resolves). FullReport prints it as a warning line.
  std::string tolerance_warning;
  /// Plausibility warnings of the scene as a valve train (scene_warnings(): a
  /// lash larger than the lift, masses or stiffnesses far outside valve-train ranges, …):
  /// the run goes on. summary.json "warnings"; the CLI prints each on stderr.
  std::vector<std::string> warnings;
  // ---- designer results. Angles are cam angles in degrees in [0, 360);
  // ---- NaN (null in summary.json) when the thing did not happen.
  /// Smallest contact force while in contact (the margin; 0 if the follower separated:
  /// the force reaches zero at a separation). NaN if never in contact.
  double min_contact_force = NAN;
  double min_force_theta_deg = NAN;    ///< cam angle of min_contact_force
  double first_separation_theta_deg = NAN;
  double first_impact_theta_deg = NAN;
  double max_impact_velocity = 0;      ///< largest approach velocity at an impact
  double max_impact_theta_deg = NAN;   ///< cam angle of that impact
  double max_gap = 0;                  ///< largest gap (−s) seen at step ends, ≥ 0
  /// Per-revolution samples at run.poincare_angle_deg after run.settle_revolutions.
  std::vector<PoincareSample> poincare;
  /// Period of the Poincaré samples in revolutions (smallest p ≤ 16 with every sample
  /// equal to the one p before within run.period_tol, needing ≥ 2p + 1 samples); 0 = none.
  int period = 0;
  /// "period-1", "period-2", …, "not periodic", or "too few samples" (< 3 samples).
  std::string period_kind = "too few samples";
  // ---- cam geometry results (docs/cam_laws.md). NaN (null) where undefined.
  /// Largest |pressure angle| over the cam's revolution [deg] (0 for a flat face).
  double max_pressure_angle_deg = NAN;
  /// Smallest radius of curvature of the cam profile [length] (NaN: point follower).
  double min_radius_of_curvature = NAN;
  /// Largest side load F·|tan φ| on the follower's guide while in contact [force].
  double max_side_load = NAN;
  /// Largest Hertz line-contact pressure p₀ while in contact [force/length²] (cam.width > 0
  /// and a flat or roller face) and its cam angle [deg].
  double max_hertz_stress = NAN;
  double max_hertz_theta_deg = NAN;
  /// Cam driving torque T = F·dX_C/dθ [force·length] and power T·ω: largest magnitude while
  /// in contact, and time averages over the run (step ends, trapezoid; 0 while apart).
  double cam_torque_peak = NAN, cam_torque_mean = NAN;
  double cam_power_peak = NAN, cam_power_mean = NAN;
  /// Friction at the cam contact (cam.friction_coefficient > 0; NaN otherwise): largest
  /// friction force, mean friction torque and power over the run (whole revolutions: their
  /// means over a revolution), peak power, and the energy it dissipated ∫P_f dt.
  double cam_friction_force_max = NAN, cam_friction_torque_mean = NAN;
  double cam_friction_power_mean = NAN, cam_friction_power_peak = NAN, cam_friction_work = NAN;
  /// Springs whose coils clash (empty when the scene has none).
  std::vector<CoilClashResult> coil_clash;
  /// Springs with coil masses: their surge amplitude (empty when the scene has none).
  std::vector<SurgeResult> surge;
  /// Motion law (cam.profile = "law"): continuity order at each joint, "C2 at 0°, …".
  std::string cam_continuity;
  double cpu_seconds = 0, wall_seconds = 0;
  std::string integrator, contact_model;
  ModelDescription model;
  std::vector<ContactEvent> events;
  /// Per contact (network and user followers; empty otherwise), in the contacts' order.
  /// The top-level designer fields above follow the primary (first cam) contact only.
  std::vector<ContactResult> contacts;
  /// Per reported element quantity of a network with nonlinear elements (empty otherwise).
  std::vector<ElementResult> elements;
  /// The verdict in words (every follower kind): what the follower does, per contact, in
  /// the order of first occurrence; one "no_separation" item when nothing happens.
  std::vector<VerdictItem> verdict;
  /// The verdict's texts joined by "; " (summary.json "verdict_text").
  std::string verdict_text;
  /// The run's own checks of its result (RunContract). A finished run whose contract does
  /// not hold is a result not to be trusted: the CLI exits 3.
  RunContract contract;
  // ---- oil film, lift deviation, acceleration criteria (issue 38; NaN/empty when not asked)
  /// [lubricant]: least EHL film thickness at the cam contact while in contact (the
  /// history's film_thickness), located inside each accepted step, and its cam angle;
  /// λ = film / roughness there.
  double min_film_thickness = NAN, min_film_theta_deg = NAN;
  double min_lambda = NAN;
  /// run.valve_node: the lift deviation's extremes per revolution (the history's
  /// lift_deviation).
  std::vector<LiftDeviationRevolution> lift_deviation;
  /// Largest cam velocity |Ẋ| where the cam lift crosses a lash take-up level over the
  /// output rows (linear between rows), and its cam angle; NaN if never crossed.
  double max_ramp_velocity = NAN, max_ramp_theta_deg = NAN;
  /// Network seats (stop contacts on side "below"): every landing, in time order.
  std::vector<SeatLanding> landings;
  /// The [criteria] of the scene judged on this run, in the key table's order.
  std::vector<CriterionResult> criteria;
  /// Every criterion passes (true when there is none).
  bool criteria_pass = true;
  /// A [camshaft]: each valve's timing (ValveTimingResult), in the order of the cam contacts
  /// and their seats; empty without a camshaft.
  std::vector<ValveTimingResult> valve_timing;

  std::string BriefReport() const;
  std::string FullReport() const;
};

}  // namespace camdyn
