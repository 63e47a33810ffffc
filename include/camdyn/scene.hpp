// camdyn — scene description (what the user asks to simulate).
//
// A Scene is the resolved, validated content of a TOML scene file (docs/interface.md): every
// field has a default and a comment with units and valid range. The mechanism builder
// turns a Scene into the smallest mechanism with exactly the effects it asks for.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "camdyn/cam_spec.hpp"
#include "camdyn/network.hpp"
#include "camdyn/scene_error.hpp"

namespace camdyn {

// ---- enumerations, each with a to_string / parse pair so the CLI and reports need no
// ---- extra code. parse_enum returns false on an unknown spelling.
enum class FollowerKind { Rigid, ElasticBar, Network };
enum class MassMatrixKind { Consistent, Lumped };
enum class ContactModel { Lee, Penalty, Holonomic, Event };
enum class ErrorVariant { Eq12, Eq17 };
enum class LeeStepKind { Located, Classic };
enum class PenaltyLaw { Linear, HuntCrossley };
enum class Integrator { ArkodeErk, ArkodeDirk, CvodeBdf, Ida };
enum class LinearSolverKind { Auto, Dense, Klu };
enum class StackKind { Auto, Follower, Mechanism };
enum class CamshaftDrive { Compliant, Prescribed };

const char* to_string(FollowerKind v);      // "rigid" | "elastic_bar" | "network"
const char* to_string(MassMatrixKind v);    // "consistent" | "lumped"
const char* to_string(ContactModel v);      // "lee" | "penalty" | "holonomic" | "event"
const char* to_string(ErrorVariant v);      // "eq12" | "eq17"
const char* to_string(LeeStepKind v);           // "located" | "classic"
const char* to_string(PenaltyLaw v);        // "linear" | "hunt_crossley"
const char* to_string(Integrator v);        // "arkode-erk" | "arkode-dirk" | "cvode-bdf" | "ida"
const char* to_string(LinearSolverKind v);  // "auto" | "dense" | "klu"
const char* to_string(StackKind v);         // "auto" | "follower" | "mechanism"
const char* to_string(CamshaftDrive v);     // "compliant" | "prescribed"

bool parse_enum(std::string_view s, FollowerKind* out);
bool parse_enum(std::string_view s, MassMatrixKind* out);
bool parse_enum(std::string_view s, ContactModel* out);
bool parse_enum(std::string_view s, ErrorVariant* out);
bool parse_enum(std::string_view s, LeeStepKind* out);
bool parse_enum(std::string_view s, PenaltyLaw* out);
bool parse_enum(std::string_view s, Integrator* out);
bool parse_enum(std::string_view s, LinearSolverKind* out);
bool parse_enum(std::string_view s, StackKind* out);
bool parse_enum(std::string_view s, CamshaftDrive* out);

/// The follower: rigid mass or elastic bar.
struct FollowerSpec {
  FollowerKind kind = FollowerKind::Rigid;
  /// Total mass [mass], > 0.
  double mass = 1.0;
  /// Viscous damper on the rigid mass (to ground) [force·time/length], ≥ 0. rigid only.
  double damping = 0.0;
  /// elastic_bar: Young's modulus E [force/length²], > 0.
  double youngs_modulus = 1e7;
  /// elastic_bar: cross-section area A [length²], > 0.
  double area = 3.0;
  /// elastic_bar: bar length L [length], > 0.
  double length = 24.0;
  /// elastic_bar: number of 2-node linear elements N, 1 ≤ N ≤ 10⁷.
  int elements = 40;
  /// elastic_bar: consistent or lumped mass matrix.
  MassMatrixKind mass_matrix = MassMatrixKind::Consistent;
  /// elastic_bar: Rayleigh damping C = α M + β K; α [1/time] ≥ 0, β [time] ≥ 0.
  double rayleigh_alpha = 0.0;
  double rayleigh_beta = 0.0;
};

/// The return spring on the follower's far end.
struct SpringSpec {
  /// Stiffness k [force/length], ≥ 0.
  double stiffness = 500.0;
  /// Pre-compression δ₀ [length], finite (k·δ₀ is the preload).
  double precompression = 7.0;
};

/// The contact law and its method.
struct ContactSpec {
  ContactModel model = ContactModel::Lee;
  /// Deprecated and ignored (one release): chose the retired classic step's equations.
  /// Simulator warns when a scene sets "eq17".
  ErrorVariant error_variant = ErrorVariant::Eq12;
  /// Lee's step: "located", one consistent trajectory per step (a two-parameter force
  /// shape solved for displacement and velocity compatibility together), separations and
  /// impacts located inside the step and landed on, error control that includes the
  /// contact force, dense output. "classic" (the retired round-1 step) is refused by
  /// Simulator with a SceneError naming the key.
  LeeStepKind lee_step = LeeStepKind::Located;
  /// Displacement-level tolerance [length], > 0. 0 in a scene file means "paper default":
  /// 1e-8 for a rigid follower, 1e-7 for an elastic one (resolved by resolve_defaults()).
  double tol_u = 0.0;
  /// Velocity tolerance; 0 means tol_u/Δt (per step).
  double tol_v = 0.0;
  /// Deprecated and ignored (one release): the retired classic step's acceleration-level
  /// tolerance. Simulator warns when a scene sets it.
  double tol_a = 0.0;
  /// Maximum iterations per level before the step is retried with Δt/2, 1 ≤ n ≤ 10⁴.
  int max_iterations = 60;
  /// false: the follower never leaves the cam (holonomic constraint).
  bool separation = true;
  /// Newton restitution coefficient at impact, 0 ≤ e ≤ 1 (0 = plastic, as in the paper).
  double restitution = 0.0;
  /// Clearance between cam and follower at t = 0 [length], ≥ 0 (valve lash).
  double initial_gap = 0.0;
  PenaltyLaw penalty_law = PenaltyLaw::Linear;
  /// Penalty stiffness k_p [force/length] (linear) or [force/lengthⁿ] (Hunt–Crossley), > 0.
  double penalty_stiffness = 1e6;
  /// Penalty damping c_p [force·time/length] (linear), or Hunt–Crossley's α [time/length], ≥ 0.
  double penalty_damping = 0.0;
  /// Hunt–Crossley exponent n, 1 ≤ n ≤ 3.
  double penalty_exponent = 1.5;
};

/// The time integrator.
struct SolverSpec {
  /// "ida" (SUNDIALS IDA, the held contacts as an index-2 GGL DAE, any number of them: a
  /// single follower or a network; not a user FollowerSystem) needs contact.model =
  /// "holonomic".
  Integrator integrator = Integrator::ArkodeErk;
  /// Relative and absolute local error tolerances, 1e-14 ≤ rtol ≤ 1e-1, 0 < atol ≤ 1.
  double rtol = 1e-7;
  double atol = 1e-10;
  LinearSolverKind linear_solver = LinearSolverKind::Auto;
  /// Largest step [time], ≥ 0; 0 = no limit beyond output times.
  double max_step = 0.0;
  /// First step [time], ≥ 0; 0 = automatic.
  double initial_step = 0.0;
  /// Deprecated and ignored (one release): every follower runs as a mechanism. Simulator
  /// warns when a scene sets "follower" or "mechanism".
  StackKind stack = StackKind::Auto;
};

/// What to run and what to write.
struct RunSpec {
  /// Final time [time], > 0.
  double t_end = 1.0;
  /// Output spacing [time], ≥ 0; 0 = one row per accepted step.
  double output_dt = 1e-4;
  /// true: every step is cut to land on the output times (the round-1 behaviour);
  /// false: rows are interpolated inside accepted steps with step-end accuracy (dense
  /// output), so output_dt does not change the solution. Lee "classic", penalty and the
  /// event-driven method always land on output times.
  bool land_on_output = false;
  /// Safety bound on accepted + rejected steps, ≥ 1.
  long max_steps = 50'000'000;
  /// Poincaré section: the cam angle [deg], finite, at which the follower's (u_c, v_c) is
  /// sampled once per revolution (Summary::poincare; sweep bifurcation diagrams). Taken
  /// modulo 360 relative to cam.theta0_deg: the k-th sample (k = 0, 1, …) is at
  /// θ = θ₀ + ((poincare_angle_deg − theta0_deg) mod 360)° + 360°·k.
  double poincare_angle_deg = 0.0;
  /// Revolutions left out of the Poincaré samples and the period detection (transient),
  /// 0 ≤ n ≤ 10⁹: samples k < settle_revolutions are not kept.
  long settle_revolutions = 0;
  /// Relative tolerance of the period detector, 0 < tol ≤ 1: samples p revolutions apart
  /// are "equal" when |Δu_c| ≤ tol·lift and |Δv_c| ≤ tol·lift·|ω|.
  double period_tol = 1e-3;
  /// true: history.csv gets the designer columns after the others
  /// (docs/cam_laws.md): pressure_angle_deg, radius_of_curvature, contact_stress, side_load,
  /// cam_torque, cam_power, from the row's cam contact force. false: no such columns.
  bool designer_columns = false;
  /// true: history.csv gets one column force_<name> per reported element force (after the
  /// network columns and before the designer columns): every spring (without mass), dashpot
  /// and nonlinear element (progressive_spring), unnamed ones as <type>_<index>; the
  /// compressive force of the element along [lower, upper]. Networks only.
  bool element_forces = false;
  /// The network node that is "the valve" of the designer results (docs/interface.md
  /// "[criteria]"): history column `lift_deviation` = q_valve − kinematic valve lift (the
  /// cam lift through the levers with every clearance on the path taken up), its extremes per
  /// revolution in Summary::lift_deviation. "" (the default): no such results. Networks only;
  /// must name a node reached from a cam contact through lash contacts, levers, bars and
  /// springs between nodes.
  std::string valve_node;
};

/// How the speed-range map (`camdyn jump`, jump_speed(); docs/guide/sweeps.md) judges one
/// trial speed v: it runs settle_revolutions + judge_revolutions camshaft revolutions at v
/// (t_end = that count / |v|, whatever run.t_end says) and judges the events of the last
/// judge_revolutions only.
struct JumpSpec {
  /// Revolutions run before the judged ones (the start's transient), 0 ≤ n ≤ 10000 [1].
  long settle_revolutions = 1;
  /// Revolutions whose events are judged, 1 ≤ n ≤ 10000 [2].
  long judge_revolutions = 2;
};

/// Acceptance criteria ([criteria]; docs/interface.md "[criteria]"): every run judges each
/// limit that is set (Summary::criteria: value, cam angle where worst, pass/fail). A real
/// limit of 0 and max_bounce_count = -1 (the defaults) set no criterion; a limit set must be
/// > 0 (max_bounce_count ≥ 0).
struct CriteriaSpec {
  double max_seating_velocity = 0;   ///< largest approach speed at a seat (stop) impact [length/time]
  double max_bounce_height = 0;      ///< largest seat gap between a landing and its re-impact [length]
  long max_bounce_count = -1;        ///< most re-impacts on a seat after one landing (per cycle) [1]
  double min_force_margin = 0;       ///< least force of each contact while closed, outside the
                                     ///< lash take-up window [force]; one criterion per contact
  double max_hertz_stress = 0;       ///< largest Hertz p₀ at the cam (needs cam.width > 0) [force/length²]
  double min_film_thickness = 0;     ///< least EHL film at the cam (needs [lubricant]) [length]
  double min_lambda = 0;             ///< least film / roughness (needs lubricant.roughness > 0) [1]
  double max_ramp_velocity = 0;      ///< largest cam velocity |Ẋ| where the cam lift crosses a
                                     ///< lash take-up level (the ramp's closing speed) [length/time]
  double max_lift_deviation = 0;     ///< largest |valve lift − kinematic lift| (needs run.valve_node) [length]
};

/// The lubricant of the cam contact's oil film ([lubricant]; docs/interface.md). viscosity
/// = 0 (the default): no film is computed (no history column, no cost).
struct LubricantSpec {
  double viscosity = 0;           ///< dynamic viscosity η₀ at the inlet [force·time/length²], ≥ 0
  double pressure_viscosity = 0;  ///< pressure–viscosity coefficient ξ [length²/force], ≥ 0
  double roughness = 0;           ///< composite roughness √(R_q,cam² + R_q,follower²) [length], ≥ 0 (0: no λ)
};

/// The valve train the cam is synthesised through ([synthesis]; `camdyn cam
/// --synthesise-from-valve-lift`, synthesise_cam_from_valve_lift: camdyn/synthesis.hpp
/// ValveTrainOptions). Read only by the synthesis; a run does not use these keys. The CLI
/// options --ratio, --valve-end-angle, --lash, --lash-ramp override them.
struct SynthesisSpec {
  double ratio = 1.0;                ///< translating follower: lever ratio dV/ds, > 0 [1]
  double valve_end_angle_deg = 0.0;  ///< oscillating finger: ψ₀ of the pivot–valve-end line, |ψ₀| < 90 [deg]
  double lash = 0.0;                 ///< valve lash, measured at the valve, ≥ 0 [length]
  double ramp_deg = 0.0;             ///< with lash > 0: the lash ramp's cam angle, in (0, 180) [deg]
};

/// [camshaft] (optional; inertias empty: no camshaft, the cam turns at the prescribed angle of
/// [cam]): the camshaft as a torsionally elastic body (issue 40). Stations 0 … N−1 are unknowns
/// of the mechanism whose coordinate is the shaft angle φ_i [rad] (history columns
/// u_shaft_<i>, v_shaft_<i>); segment i joins stations i and i + 1. Every cam has the profile of
/// [cam] and sits on a station with an angular offset α (its lift is X_C(φ_station − α): a cam
/// with a larger offset opens later). The drive: a torsional spring–damper (the chain, belt or
/// gear train as an equivalent) from the drive station to a crank whose angle is the cam angle
/// θ(t) that [cam] prescribes plus harmonic orders,
///   θ_crank(t) = θ(t) + Σ_k a_k sin(n_k θ(t) + p_k)   (orders n_k per camshaft revolution).
/// The cam contacts of the network ([[contacts]] of type cam, in their order) ride on the cams
/// contact_cams names. Needs follower.kind = "network".
struct CamshaftSpec {
  /// Polar inertia per station [mass·length²], each > 0; ≥ 1 station.
  std::vector<double> inertias;
  /// Torsional stiffness GJ/L of each segment [force·length/rad], N − 1 entries, each > 0.
  std::vector<double> stiffnesses;
  /// Rayleigh damping of the shaft C = αJ + βK_shaft (α acts on the stations' absolute speed:
  /// a viscous bearing drag; β on the segments' twist rates), α [1/time], β [time], ≥ 0.
  double rayleigh_alpha = 0.0;
  double rayleigh_beta = 0.0;
  /// The station of each cam (0-based integers, < N); one entry per cam, ≥ 1 cam.
  std::vector<double> cam_stations;
  /// Each cam's angular offset in camshaft degrees, or in crank degrees (2 × camshaft
  /// degrees, a four-stroke's firing interval), one form only, one entry per cam
  /// (neither: all 0).
  std::vector<double> cam_offsets_deg;
  std::vector<double> cam_offsets_crank_deg;
  /// For every cam contact of the network (in [[contacts]] order), the cam it rides on
  /// (0-based integers). Empty: the i-th cam contact rides on cam i (as many cam contacts as cams).
  std::vector<double> contact_cams;
  /// The drive station (0-based, < N) [0].
  long drive_station = 0;
  /// How the drive station turns: "compliant" (default) through the drive coupling below;
  /// "prescribed": the drive station's angle is the crank's law θ_crank(t) exactly (the
  /// station is no unknown: its neighbours' segments are driven by it, its cams are
  /// prescribed cams at θ_crank(t) − offset), without drive_stiffness or drive_damping.
  CamshaftDrive drive = CamshaftDrive::Compliant;
  /// The drive coupling's torsional stiffness [force·length/rad], > 0 (drive = "compliant"),
  /// and damping [force·length·time/rad], ≥ 0.
  double drive_stiffness = 0.0;
  double drive_damping = 0.0;
  /// The crank's speed fluctuation: orders n_k (per camshaft revolution, > 0), angle
  /// amplitudes a_k [camshaft degrees], phases p_k [degrees]; equal lengths (may be empty).
  std::vector<double> crank_orders;
  std::vector<double> crank_amplitudes_deg;
  std::vector<double> crank_phases_deg;
  /// true when the scene has a camshaft (inertias given).
  bool present() const { return !inertias.empty(); }
};

struct Scene {
  std::string title = "camdyn scene";
  CamSpec cam;
  FollowerSpec follower;
  SpringSpec spring;
  ContactSpec contact;
  SolverSpec solver;
  RunSpec run;
  JumpSpec jump;
  CriteriaSpec criteria;
  LubricantSpec lubricant;
  /// [camshaft]: the camshaft as a body (empty: the prescribed cam angle of [cam]).
  CamshaftSpec camshaft;
  /// [synthesis]: the train the cam is synthesised through (not used by a run).
  SynthesisSpec synthesis;
  /// follower.kind = "network": the nodes, elements and contacts ([[nodes]], [[elements]],
  /// [[contacts]]); empty for the other kinds (follower.* bar keys and [spring] are then
  /// unused, [contact] gives the method and the contacts' default restitution and penalty).
  NetworkSpec network;
  /// 60 (camshaft rpm) or 120 (engine rpm of a four-stroke) when the scene gave its speed as
  /// cam.speed_rpm with cam.rpm_of: the unit its jump map and sweeps also speak
  /// (`sweep --key cam.speed_rpm`); 0 when it gave rev/s. Not a key: set when cam.speed_rpm
  /// is read (a file or --set), kept by later overrides.
  double rpm_per_rev_s = 0;
  /// Where the scene came from (file path or "<built-in>"), for error messages.
  std::string source = "<built-in>";
};

/// The paper's case B2 (elastic follower, 5 rev/s), the built-in default scene.
Scene default_scene();
/// The paper's reference cases: "A", "B1", "B2" (docs/method.md §5).
/// @throws SceneError (file "--case", key "case") for any other name.
Scene paper_case(const std::string& name);

/// Parse TOML text. Keys missing from the text keep the defaults of Scene{}.
/// The result is resolved (resolve_defaults) and validated; its source is source_name.
/// Unknown keys/tables, wrong types and broken rules throw with the offending node's line.
/// @throws SceneError naming source, line, key, value and rule.
Scene parse_scene(std::string_view toml_text, const std::string& source_name);
/// Read and parse a file. @throws SceneError (also when the file cannot be read:
/// "PATH: cannot read scene file: <strerror>").
Scene load_scene_file(const std::string& path);
/// The scene a run works on: the file's keys (types checked), then every override
/// ("dotted.key=value", as apply_overrides) set in the file's table, then the rules checked
/// once on the result — so an override may repair a file that breaks a rule alone. A rule
/// broken by an overridden key names file "--set" and the key as written in the override;
/// other errors name the file and line. The CLI (`scene`, `run`, `jump`, `sweep`) and
/// Python load scenes this way. @throws SceneError on a file that cannot be read or a rule broken.
Scene load_scene_file(const std::string& path, const std::vector<std::string>& overrides);
/// parse_scene with overrides, as load_scene_file(path, overrides). @throws SceneError as load_scene_file.
Scene parse_scene(std::string_view toml_text, const std::string& source_name,
                  const std::vector<std::string>& overrides);
/// Apply "dotted.key=value" (value in TOML syntax; bare words are taken as strings, so
/// contact.model=penalty works). Network entries are addressed by name or index
/// (resolve_network_key): contacts.seat.restitution=0.3, elements[1].preload=300. The scene is converted to a TOML table, the key set and
/// the table parsed again with the same checks as a file (errors name file "--set", no
/// line). On success the scene is replaced by the resolved, validated result (its source
/// is kept); on error it is unchanged.
/// contact.tol_u: when it is "automatic" — 0, or equal to the paper default of the
/// scene's current follower kind (1e-8 rigid, 1e-7 elastic_bar) — and the override is not
/// contact.tol_u itself, it is re-derived afterwards, so follower.kind=elastic_bar on a
/// rigid scene gives 1e-7. (An explicit tol_u equal to that default is treated the same.)
/// @throws SceneError with file "--set".
void apply_override(Scene& scene, const std::string& assignment);
/// Apply several "dotted.key=value" overrides at once: each is set in the scene's TOML
/// table, then the table is parsed and validated once, so the result does not depend on
/// their order (run.t_end=5e-7 with run.output_dt=5e-7 works either way round). Keys are
/// checked as by apply_override; later assignments of the same key win.
/// @throws SceneError with file "--set"; on error the scene is unchanged.
void apply_overrides(Scene& scene, const std::vector<std::string>& assignments);
/// Fill "0 = automatic" defaults: contact.tol_u = 0 → 1e-8 (rigid) / 1e-7 (elastic_bar).
/// Nothing else is changed (tol_v/tol_a = 0 keep meaning "per step"). Idempotent.
void resolve_defaults(Scene& scene);
/// Check every rule (errors name scene.source, no line). contact.tol_u = 0 is accepted as
/// "not yet resolved". Cam convexity is left to Cam. @throws SceneError naming key, value and rule.
void validate(const Scene& scene);
/// A scene whose rules were checked after its last change, resolved (resolve_defaults) and
/// read-only: made only by validated() and the loaders below, so whoever holds one (the
/// Simulator, the CLI, Python) does not check it again — a run validates its scene exactly
/// once, after every --set.
class ValidatedScene {
 public:
  const Scene& scene() const& { return scene_; }
  /// The scene itself, moved out (the ValidatedScene is spent).
  Scene scene() && { return std::move(scene_); }
  const Scene& operator*() const { return scene_; }
  const Scene* operator->() const { return &scene_; }

 private:
  explicit ValidatedScene(Scene scene) : scene_(std::move(scene)) {}
  friend ValidatedScene validated(Scene scene, const std::vector<std::string>& overrides);
  friend ValidatedScene load_validated_scene(const std::string& path, const std::vector<std::string>& overrides);
  friend ValidatedScene parse_validated_scene(std::string_view toml_text, const std::string& source_name,
                                              const std::vector<std::string>& overrides);
  Scene scene_;
};
/// The one validation of a scene: `overrides` applied (apply_overrides, which checks the
/// rules once on the result) or, without overrides, resolve_defaults and validate.
/// @throws SceneError as apply_overrides / validate.
ValidatedScene validated(Scene scene, const std::vector<std::string>& overrides = {});
/// load_scene_file(path, overrides) as a ValidatedScene (the loader's own check is the one
/// validation). @throws SceneError as load_scene_file.
ValidatedScene load_validated_scene(const std::string& path, const std::vector<std::string>& overrides = {});
/// parse_scene(toml_text, source_name, overrides) as a ValidatedScene. @throws SceneError as parse_scene.
ValidatedScene parse_validated_scene(std::string_view toml_text, const std::string& source_name,
                                     const std::vector<std::string>& overrides = {});
/// The scene as TOML with every key written (the resolved scene; floats in shortest
/// round-trip form). parse_scene(to_toml(s), ...) == s after resolve_defaults(s).
std::string to_toml(const Scene& scene);

/// One key of a scene with its value, as the writers (to_toml, the summary's "options")
/// see it. Enumerations arrive as their spelling in `text`.
struct SceneEntry {
  enum class Kind { Real, Int, Bool, Str, Array, Names };
  std::string table;  ///< "" for a top-level key
  std::string key;
  Kind kind = Kind::Real;
  double real = 0;
  long long integer = 0;
  bool boolean = false;
  std::string text;
  std::vector<double> array;
  std::vector<std::string> names;  ///< Kind::Names: an array of strings (a network entry's nodes)
};
/// Visit every key of `scene` in file order (top-level keys first, each table contiguous):
/// the one list of scene keys behind the loader, to_toml and the summary JSON.
void for_each_scene_entry(const Scene& scene, const std::function<void(const SceneEntry&)>& visit);
/// Visit the network of `scene`: every [[nodes]], then [[elements]], then [[contacts]]
/// entry, as `visit(array, index, keys)` with array "nodes" | "elements" | "contacts" and
/// the entry's keys in file order (SceneEntry::table = array). Only the keys of the entry's
/// type are given; an element's name only when it is not empty, a contact's restitution,
/// penalty_stiffness and penalty_damping only when set. Nothing for a scene without network.
void for_each_network_entry(
    const Scene& scene,
    const std::function<void(const std::string& array, std::size_t index, const std::vector<SceneEntry>& keys)>& visit);

/// One key of one network entry, addressed on the command line, as a Python override or as
/// a sweep key by the entry's name — "contacts.seat.restitution", "elements.pushrod.elements",
/// "nodes.valve.mass" (ARRAY.NAME.KEY; a name may contain dots, the key is after the last)
/// — or by its 0-based index — "contacts[1].restitution" (ARRAY[INDEX].KEY).
struct NetworkKey {
  std::string array;       ///< "nodes" | "elements" | "contacts"
  std::size_t index = 0;   ///< the entry's position in its array
  std::string key;         ///< the entry's key, e.g. "restitution"
  SceneEntry::Kind kind = SceneEntry::Kind::Real;  ///< Real, Int (masses, elements), Str or Names (nodes)
  /// "ARRAY[INDEX].KEY", the spelling of the loader's own messages ("contacts[1].restitution").
  std::string canonical() const;
};
/// Whether `key` is spelled as a network key: "nodes", "elements" or "contacts" followed by
/// '.' or '['.
bool is_network_key(std::string_view key);
/// Resolve a network key against scene.network (the entry must exist and the key be one of
/// the keys its type takes).
/// @pre is_network_key(key)
/// @throws SceneError (naming the key, value and rule) when the key is not ARRAY.NAME.KEY or
///   ARRAY[INDEX].KEY, no entry has that name (the rule lists the names there are), the index
///   is out of range (the rule gives the count and the names), or the key is not one of the
///   entry's type (the rule lists that type's keys, as the file loader does).
NetworkKey resolve_network_key(const Scene& scene, const std::string& key, const std::string& file,
                               const std::string& value);

/// Content equality (every field except `source`); exact comparison of doubles.
bool operator==(const CamSpec& a, const CamSpec& b);
bool operator==(const FollowerSpec& a, const FollowerSpec& b);
bool operator==(const SpringSpec& a, const SpringSpec& b);
bool operator==(const ContactSpec& a, const ContactSpec& b);
bool operator==(const SolverSpec& a, const SolverSpec& b);
bool operator==(const RunSpec& a, const RunSpec& b);
bool operator==(const JumpSpec& a, const JumpSpec& b);
bool operator==(const CriteriaSpec& a, const CriteriaSpec& b);
bool operator==(const LubricantSpec& a, const LubricantSpec& b);
bool operator==(const SynthesisSpec& a, const SynthesisSpec& b);
bool operator==(const CamshaftSpec& a, const CamshaftSpec& b);
bool operator==(const Scene& a, const Scene& b);
bool operator!=(const Scene& a, const Scene& b);

}  // namespace camdyn
