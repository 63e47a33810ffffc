// camdyn — the scene-key reference: the key table (src/scene/scene.cpp, detail::key_table()) joined
// with the defaults of the default-constructed specs and one documentation table (units and
// meaning). scene_keys() refuses to run when the two tables disagree, so a new key without
// documentation fails `camdyn scene --keys`, the docs build and the test suite.
#include "camdyn/scene_keys.hpp"

#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "camdyn/scene.hpp"
#include "scene/element_kinds.hpp"
#include "scene/key_table.hpp"

namespace camdyn {

namespace {

struct KeyDoc {
  const char* key;
  const char* unit;
  const char* text;
  const char* type = nullptr;     // network keys: the value's type (the key table has the path only)
  const char* rule = nullptr;     // network keys: the validator's rule
  const char* fixed_default = nullptr;  // when the default is not a value ("(required)", "the [contact] value")
  bool input_only = false;  // a designer-unit key converted at load (cam.speed_rpm, …): never written
};

// Units: lengths, masses and times in any consistent units ("length", "mass", "time").
const KeyDoc kDocs[] = {
    {"title", "—", "Title of the scene, written to summary.json (`scene`)."},
    // [cam]
    {"cam.profile", "—", "Profile representation: `points` (polar spline through knots), `lift` (lift table over a "
                         "base circle, flat-faced follower), `circle` (eccentric circle; closed-form jump speed), "
                         "`law` (motion-law segments), `arc` (base, flanks and nose: four tangent arcs), `arcs` (any "
                         "closed chain of arcs, `cam.arc_*`), `table` (a lift-table CSV file, `cam.lift_table`, any "
                         "follower, as a law)."},
    {"cam.angles_deg", "deg", "points: polar angles of the spline knots; strictly increasing, span < 360, at least 4."},
    {"cam.radii", "length", "points: radii of the knots, > 0, as many as `cam.angles_deg`."},
    {"cam.base_radius", "length", "lift: base-circle radius r_b."},
    {"cam.lift_angles_deg", "deg", "lift: cam angles of the lift table; strictly increasing, span < 360, at least 4."},
    {"cam.lift", "length", "lift: follower lift L(θ) at `cam.lift_angles_deg` (periodic spline); r_b + L > 0."},
    {"cam.radius", "length", "circle: radius R."},
    {"cam.eccentricity", "length", "circle: eccentricity e, 0 ≤ e < R (centre at (e, 0) in the cam frame)."},
    {"cam.speed_rev_s", "rev/s", "Constant cam speed (any sign); ignored when a speed table is given."},
    {"cam.speed_rpm", "rpm", "Constant cam speed in revolutions per minute, instead of `cam.speed_rev_s` (giving both "
                             "is an error); needs `cam.rpm_of`. Converted when the scene is loaded (time in seconds): "
                             "camshaft rpm / 60 or engine rpm / 120 = `cam.speed_rev_s`, which `--resolved` writes. "
                             "Input only.", nullptr, nullptr, "(none)", true},
    {"cam.rpm_of", "—", "Whose rpm `cam.speed_rpm` is: `camshaft`, or `engine` — the crankshaft of a four-stroke "
                        "engine, which turns twice per camshaft revolution (camshaft rpm = engine rpm / 2). Required "
                        "with `cam.speed_rpm`, refused without it. Input only.", nullptr, nullptr, "(none)", true},
    {"cam.speed_table_t", "time", "Optional speed table: times, strictly increasing, first = 0; ω(t) piecewise "
                                  "linear between entries and constant after the last."},
    {"cam.speed_table_rev_s", "rev/s", "Speeds of the speed table, as many as `cam.speed_table_t`."},
    {"cam.theta0_deg", "deg", "Cam angle at t = 0."},
    {"cam.law", "—", "law: the motion-law segments, `KIND D H [...]` separated by `;` (dwell, ramp, harmonic, "
                     "cycloidal, poly345, poly4567, poly, modtrap, modsine, polydyne); spans sum to 360 deg and the "
                     "lift closes (docs/cam_laws.md)."},
    {"cam.lift_table", "—", "table: the lift-table CSV file (`angle_deg,lift[,dlift_ddeg,d2lift_ddeg2]`, as `camdyn cam` "
                            "writes; relative to the scene file); quintic Hermite through the derivatives if given, "
                            "else a periodic C² spline. The lift is what cam.law would give (docs/cam_laws.md)."},
    {"cam.nose_radius", "length", "arc: nose-circle radius r_n."},
    {"cam.nose_distance", "length", "arc: distance d of the nose-circle centre from the cam centre."},
    {"cam.flank_radius", "length", "arc: radius R_f of the two flank arcs, tangent to base and nose circles."},
    {"cam.arc_centre_x", "length", "arcs: x of each arc's centre in the cam frame (with `cam.arc_centre_y`; or polar `cam.arc_centre_r`/`cam.arc_centre_deg`)."},
    {"cam.arc_centre_y", "length", "arcs: y of each arc's centre in the cam frame."},
    {"cam.arc_centre_r", "length", "arcs: distance of each arc's centre from the cam centre (polar form, with `cam.arc_centre_deg`)."},
    {"cam.arc_centre_deg", "deg", "arcs: polar angle of each arc's centre in the cam frame."},
    {"cam.arc_radius", "length", "arcs: signed radius of each arc: > 0 convex, < 0 concave (centre outside the cam)."},
    {"cam.arc_from_deg", "deg", "arcs: direction from the arc's centre to its first point; the arcs run counter-clockwise round the cam."},
    {"cam.arc_to_deg", "deg", "arcs: direction from the arc's centre to its last point: > from (convex), < from (concave); consecutive arcs must meet (tangent, or a corner: a C0 joint)."},
    {"cam.follower_face", "—", "Follower face: `flat` (translating flat face), `knife_edge`, `roller` or `point` "
                               "(lift imposed, no base radius needed)."},
    {"cam.follower_offset", "length", "Offset ε of the translating follower's axis (knife edge, roller)."},
    {"cam.roller_radius", "length", "Roller radius r_r (follower_face = roller)."},
    {"cam.follower_motion", "—", "`translating` (default) or `oscillating`: a finger follower or rocker turning about "
                                 "a pivot, flat pad or roller; profile law, table, circle or arc (docs/cam_laws.md)."},
    {"cam.pivot_x", "length", "oscillating: X of the pivot relative to the cam centre (fixed frame)."},
    {"cam.pivot_y", "length", "oscillating: Y of the pivot relative to the cam centre (fixed frame)."},
    {"cam.arm_length", "length", "oscillating roller: distance from the pivot to the roller centre, > 0."},
    {"cam.pad_offset", "length", "oscillating flat: signed distance of the pad line from the pivot."},
    {"cam.valve_arm", "length", "oscillating: distance ℓ_v from the pivot to the valve end, > 0; the follower "
                                "coordinate is X = ℓ_v ψ and a law gives X (the valve-end lift)."},
    {"cam.land_on_breaks", "—", "Steps land on the law's joints and the arc cam's tangency points (stop times)."},
    {"cam.width", "length", "Cam width of the line contact; > 0 turns on the Hertz stress results."},
    {"cam.youngs_modulus", "force/length²", "Cam material's Young's modulus E₁ (Hertz stress)."},
    {"cam.poisson_ratio", "—", "Cam material's Poisson ratio ν₁ (Hertz stress)."},
    {"cam.follower_youngs_modulus", "force/length²", "Follower face's (or roller's) Young's modulus E₂ (Hertz stress)."},
    {"cam.follower_poisson_ratio", "—", "Follower face's (or roller's) Poisson ratio ν₂ (Hertz stress)."},
    {"cam.friction_coefficient", "—", "Friction coefficient μ at the cam contact (0: off); > 0 adds the history "
                                      "columns sliding_speed, cam_friction_force, cam_friction_torque, "
                                      "cam_friction_power and their summary results (docs/guide/elements.md)."},
    {"cam.friction_static_coefficient", "—", "Stribeck curve: the coefficient μ_s at zero sliding speed, "
                                             "μ(v) = μ + (μ_s − μ)·exp(−(v/v_st)²); used when "
                                             "friction_stribeck_speed > 0, then >= friction_coefficient."},
    {"cam.friction_stribeck_speed", "length/time", "Stribeck speed v_st of the cam friction (0: constant μ)."},
    {"cam.roller_slip", "—", "Roller follower: sliding speed as a fraction of the rolling speed (0: pure rolling)."},
    // [follower]
    {"follower.kind", "—", "`rigid` (one mass), `elastic_bar` (axial bar of N linear elements) or `network` "
                           "(nodes, elements and contacts of [[nodes]], [[elements]], [[contacts]])."},
    {"follower.mass", "mass", "Total mass of the rigid follower or the bar."},
    {"follower.damping", "force·time/length", "rigid: viscous damper to ground."},
    {"follower.youngs_modulus", "force/length²", "elastic_bar: Young's modulus E."},
    {"follower.area", "length²", "elastic_bar: cross-section area A."},
    {"follower.length", "length", "elastic_bar: bar length L."},
    {"follower.elements", "—", "elastic_bar: number of two-node linear elements N."},
    {"follower.mass_matrix", "—", "elastic_bar: consistent or lumped mass matrix."},
    {"follower.rayleigh_alpha", "1/time", "elastic_bar: Rayleigh damping C = αM + βK, the α."},
    {"follower.rayleigh_beta", "time", "elastic_bar: Rayleigh damping C = αM + βK, the β."},
    // [spring]
    {"spring.stiffness", "force/length", "Return-spring stiffness k on the follower's far end."},
    {"spring.precompression", "length", "Pre-compression δ₀ (k·δ₀ is the preload)."},
    // [contact]
    {"contact.model", "—", "Contact method: `lee` (Lee's augmented multipliers), `penalty`, `holonomic` "
                           "(held contact) or `event` (exact event-driven)."},
    {"contact.error_variant", "—", "Deprecated, ignored (a warning): chose the retired classic step's equations."},
    {"contact.lee_step", "—", "Lee's step: `located` (one consistent trajectory, switches located, dense output). "
                              "On cvode-bdf with an elastic follower or a network it runs inside CVODE's step. "
                              "`classic` (the retired round-1 step) is an error."},
    {"contact.tol_u", "length", "Displacement-level tolerance; 0 = the paper default, 1e-8 rigid, 1e-7 elastic_bar "
                                "and network (filled in by `camdyn scene --resolved`)."},
    {"contact.tol_v", "length/time", "Velocity-level tolerance; 0 = tol_u/Δt per step."},
    {"contact.tol_a", "length/time²", "Deprecated, ignored (a warning when not 0): the retired classic step's "
                                      "acceleration-level tolerance."},
    {"contact.max_iterations", "—", "Iterations per level before the step is retried with Δt/2."},
    {"contact.separation", "—", "false: the follower never leaves the cam (bilateral contact)."},
    {"contact.restitution", "—", "Newton restitution coefficient e at impact (0 = plastic, the paper); the default "
                                 "of every network contact."},
    {"contact.initial_gap", "length", "Clearance between cam and follower at t = 0 (valve lash); unused by networks."},
    {"contact.penalty_law", "—", "penalty only: `linear` (k_p s + c_p ṡ) or `hunt_crossley`."},
    {"contact.penalty_stiffness", "force/length", "penalty only: k_p (Hunt–Crossley: force/lengthⁿ); the default "
                                                  "of every network contact."},
    {"contact.penalty_damping", "force·time/length", "penalty only: c_p (Hunt–Crossley: α, time/length); the "
                                                     "default of every network contact."},
    {"contact.penalty_exponent", "—", "Hunt–Crossley exponent n."},
    // [solver]
    {"solver.integrator", "—", "`arkode-erk` (Dormand–Prince 5(4)), `arkode-dirk` (SDIRK, mass matrix), "
                               "`cvode-bdf` (BDF), `ida` (the held contacts as a DAE, any mechanism; needs contact.model = holonomic)."},
    {"solver.rtol", "—", "Relative local error tolerance."},
    {"solver.atol", "length", "Absolute local error tolerance."},
    {"solver.linear_solver", "—", "`auto` (dense for ≤ 16 unknowns, KLU beyond), `dense` or `klu`."},
    {"solver.max_step", "time", "Largest step; 0 = no limit beyond the output times."},
    {"solver.initial_step", "time", "First step; 0 = automatic."},
    {"solver.stack", "—", "Deprecated, ignored (a warning when not `auto`): every follower runs as a mechanism."},
    // [run]
    {"run.t_end", "time", "Final time."},
    {"run.revolutions", "rev", "Length of the run in camshaft revolutions, instead of `run.t_end` (giving both is an "
                               "error): run.t_end = revolutions / |cam speed|, set when the scene is loaded (a later "
                               "`--set cam.speed_rev_s` keeps that t_end unless run.revolutions is set again). Needs a "
                               "constant cam speed other than 0. Input only.", nullptr, nullptr, "(none)", true},
    {"run.output_dt", "time", "Output spacing of history.csv; 0 = one row per accepted step."},
    {"run.land_on_output", "—", "true: steps land on the output times instead of dense output (Lee located)."},
    {"run.max_steps", "—", "Safety bound on accepted + rejected steps."},
    {"run.poincare_angle_deg", "deg", "Cam angle of the once-per-revolution (Poincaré) samples of (u_c, v_c), "
                                      "relative to cam.theta0_deg."},
    {"run.settle_revolutions", "—", "Revolutions left out of the Poincaré samples and the period detector."},
    {"run.period_tol", "—", "Relative tolerance of the period detector (|Δu_c| ≤ tol·lift, |Δv_c| ≤ tol·lift·|ω|)."},
    {"run.designer_columns", "—", "true: history.csv gets pressure_angle_deg, radius_of_curvature, contact_stress, "
                                  "side_load, cam_torque, cam_power per row (docs/cam_laws.md)."},
    {"run.element_forces", "—", "true: history.csv gets `force_<element>` per spring (without mass), dashpot and "
                                "progressive_spring of a network: the element's compressive force (P + kδ + cδ̇, F(δ) + cδ̇); "
                                "guide_friction: the friction force on the node; gas_load: p·A toward the seat; "
                                "unnamed elements as `<type>_<index>`; then `surge_<spring>` per spring with coil masses "
                                "(its coils' largest departure from the linear quasi-static shape)."},
    {"run.valve_node", "—", "Network node that is the valve: history column `lift_deviation` (valve lift minus the "
                            "kinematic lift, the cam lift through the levers with the clearances on the path taken up) "
                            "and its extremes per revolution in summary.json; \"\" = none."},
    {"jump.settle_revolutions", "rev", "Speed-range map (`camdyn jump`): revolutions each trial speed runs before the "
                                      "judged ones (the start's transient)."},
    {"jump.judge_revolutions", "rev", "Speed-range map: revolutions whose events are judged at each trial speed "
                                     "(t_end = (settle + judge) / |speed|, run.t_end is not used)."},
    {"criteria.max_seating_velocity", "length/time", "Acceptance criterion: largest approach speed at a seat (stop "
                                                    "contact) impact, per landing. 0 = not judged."},
    {"criteria.max_bounce_height", "length", "Acceptance criterion: largest seat gap between a landing and its "
                                             "re-impact (a bounce: no cam lift past the take-up in between). 0 = not judged."},
    {"criteria.max_bounce_count", "—", "Acceptance criterion: most seat re-impacts after one landing (per cycle). "
                                       "-1 = not judged."},
    {"criteria.min_force_margin", "force", "Acceptance criterion: least force of each contact while closed, outside "
                                           "the lash take-up window (one criterion per contact). 0 = not judged."},
    {"criteria.max_hertz_stress", "force/length²", "Acceptance criterion: largest Hertz pressure at the cam (needs "
                                                   "cam.width > 0). 0 = not judged."},
    {"criteria.min_film_thickness", "length", "Acceptance criterion: least EHL film thickness at the cam (needs "
                                              "[lubricant]). 0 = not judged."},
    {"criteria.min_lambda", "—", "Acceptance criterion: least λ = film / lubricant.roughness at the cam. 0 = not judged."},
    {"criteria.max_ramp_velocity", "length/time", "Acceptance criterion: largest cam velocity |Ẋ| where the cam lift "
                                                  "crosses a lash take-up level (opening and closing ramps). 0 = not judged."},
    {"criteria.max_lift_deviation", "length", "Acceptance criterion: largest |valve lift − kinematic lift| (needs "
                                              "run.valve_node). 0 = not judged."},
    {"lubricant.viscosity", "force·time/length²", "Dynamic viscosity η₀ of the oil at the cam contact's inlet (Pa·s in "
                                                  "SI); > 0 adds the history columns film_thickness (and lambda); 0 = "
                                                  "no oil film."},
    {"lubricant.pressure_viscosity", "length²/force", "Pressure–viscosity coefficient ξ (1/Pa in SI; mineral oil ≈ 2e-8)."},
    {"lubricant.roughness", "length", "Composite surface roughness √(R_q,cam² + R_q,follower²): λ = film / roughness; "
                                      "0 = no λ."},
    {"camshaft.inertias", "mass·length²", "Camshaft as a body (optional; empty: the cam turns at [cam]'s prescribed angle): "
                                         "the polar inertia of each shaft station (each > 0). Station i is an unknown whose "
                                         "coordinate is its angle [rad] (history columns `u_shaft_<i>`, `v_shaft_<i>`). Needs "
                                         "follower.kind = \"network\"."},
    {"camshaft.stiffnesses", "force·length/rad", "Torsional stiffness GJ/L of each shaft segment (station i to i + 1), "
                                                "one fewer than stations, each > 0."},
    {"camshaft.rayleigh_alpha", "1/time", "Shaft damping C = αJ + βK: α on the stations' absolute speed (a viscous bearing drag)."},
    {"camshaft.rayleigh_beta", "time", "Shaft damping: β on the segments' twist rates."},
    {"camshaft.cam_stations", "—", "The station of each cam (0-based integers); one entry per cam, at least one cam. Every "
                                   "cam has [cam]'s profile."},
    {"camshaft.cam_offsets_deg", "deg", "Each cam's angular offset in camshaft degrees: its lift is X_C(φ_station − α) "
                                        "(a larger offset opens later). Not with camshaft.cam_offsets_crank_deg; neither: 0."},
    {"camshaft.cam_offsets_crank_deg", "deg", "Each cam's offset in crank degrees (2 × camshaft degrees: a four-stroke's "
                                              "firing intervals). Not with camshaft.cam_offsets_deg."},
    {"camshaft.contact_cams", "—", "For every cam contact of the network in [[contacts]] order, the cam it rides on "
                                   "(0-based integers); empty: the i-th cam contact rides on cam i."},
    {"camshaft.drive_station", "—", "The station the drive coupling acts on (0-based)."},
    {"camshaft.drive_stiffness", "force·length/rad", "The drive coupling's torsional stiffness (chain, belt or gear "
                                                    "train as an equivalent spring) to the crank; > 0 with a camshaft."},
    {"camshaft.drive_damping", "force·length·time/rad", "The drive coupling's torsional damping."},
    {"camshaft.crank_orders", "—", "The crank's speed fluctuation: θ_crank(t) = θ(t) + Σ a_k sin(n_k θ(t) + p_k), θ(t) the "
                                   "cam angle [cam] prescribes; orders n_k per camshaft revolution (an engine's 2nd order "
                                   "is the camshaft's 4th), each > 0."},
    {"camshaft.crank_amplitudes_deg", "deg", "Angle amplitude a_k of each order, camshaft degrees (as many as orders)."},
    {"camshaft.crank_phases_deg", "deg", "Phase p_k of each order (as many as orders)."},
    {"camshaft.drive", "—", "How the drive station turns: `compliant` (default) through the drive coupling "
                           "(camshaft.drive_stiffness, camshaft.drive_damping) from the crank; `prescribed`: the "
                           "drive station's angle is θ_crank(t) exactly (no unknown: its cams are prescribed cams at "
                           "θ_crank(t) − offset, its segments drive the neighbouring stations), without the coupling's keys."},
    {"synthesis.ratio", "—", "Cam synthesis from the valve lift (`camdyn cam --synthesise-from-valve-lift`; not used by a "
                            "run), translating follower: the lever ratio dV/ds of the valve to the follower (1: a bucket). "
                            "CLI --ratio overrides it."},
    {"synthesis.valve_end_angle_deg", "deg", "Cam synthesis, oscillating finger: the angle ψ₀ of the pivot–valve-end line "
                                            "from the normal to the valve axis at rest, |ψ₀| < 90 (valve lift "
                                            "cam.valve_arm·(sin(ψ₀ + ψ) − sin ψ₀)). CLI --valve-end-angle overrides it."},
    {"synthesis.lash", "length", "Cam synthesis: the valve lash, measured at the valve (≥ 0). CLI --lash overrides it."},
    {"synthesis.ramp_deg", "deg", "Cam synthesis: the cam angle over which the cam takes up the lash before the valve "
                                 "opens and after it closes; in (0, 180) when synthesis.lash > 0. CLI --lash-ramp "
                                 "overrides it."},
    // [[nodes]]
    {"nodes.name", "—", "Node name: history columns `u_<name>`, `v_<name>`.", "string",
     "non-empty, unique, not \"ground\", letters, digits, '_' and '-' only", "(required)"},
    {"nodes.mass", "mass", "Lumped mass of the node.", "real", "must be >= 0"},
    {"nodes.initial_displacement", "length", "q(0), from the installed position.", "real", "must be finite"},
    {"nodes.initial_velocity", "length/time", "q̇(0).", "real", "must be finite"},
    // [[elements]]
    {"elements.name", "—", "Element name, for messages.", "string", "any string", "\"<type> #<index>\""},
    {"elements.type", "—", "Element type; decides the other keys allowed.", "enum",
     nullptr /* the kinds' names: element_type_rule() */, "(required)"},
    {"elements.nodes", "—", "[lower, upper] (lever: [input, output], or [input, output, pivot] for a lever on a moving "
                            "pivot); \"ground\" may end a spring, dashpot, bar, progressive_spring, guide_friction "
                            "([node, guide]) or gas_load ([valve, body]).",
     "names", "two different node names (a lever: two or three)", "(required)"},
    // the other keys of [[elements]]: from the element kinds' tables (src/scene/element_kinds.cpp)
    // [[contacts]]
    {"contacts.name", "—", "Contact name: history columns `F_<name>`, `gap_<name>`, `in_<name>`; the `contact` column of events.csv.",
     "string", "non-empty, unique", "(required)"},
    {"contacts.type", "—", "`cam` (g = q + clearance − X_C), `lash` (g = q_upper − q_lower + clearance) or `stop` "
                           "(a seat or a stop).",
     "enum", "must be one of \"cam\", \"lash\", \"stop\"", "(required)"},
    {"contacts.nodes", "—", "cam, stop: [node]; lash: [lower, upper]; never \"ground\".", "names",
     "one node (cam, stop) or two different nodes (lash)", "(required)"},
    {"contacts.clearance", "length", "Gap at q = 0 (cam: on the base circle).", "real", "must be >= 0"},
    {"contacts.side", "—", "stop: `below` (g = q + clearance, a valve seat) or `above` (g = clearance − q).",
     "enum", "must be one of \"below\", \"above\""},
    {"contacts.restitution", "—", "Newton restitution coefficient of this contact.", "real",
     "must be >= 0 and <= 1", "contact.restitution"},
    {"contacts.penalty_stiffness", "force/length", "Penalty stiffness of this contact.", "real", "must be > 0",
     "contact.penalty_stiffness"},
    {"contacts.penalty_damping", "force·time/length", "Penalty damping of this contact.", "real", "must be >= 0",
     "contact.penalty_damping"},
};

std::string value_text(const SceneEntry& e) {
  switch (e.kind) {
    case SceneEntry::Kind::Real: return detail::format_number(e.real);
    case SceneEntry::Kind::Int: return std::to_string(e.integer);
    case SceneEntry::Kind::Bool: return e.boolean ? "true" : "false";
    case SceneEntry::Kind::Str: return "\"" + e.text + "\"";
    case SceneEntry::Kind::Array: {
      std::string s = "[";
      for (std::size_t i = 0; i < e.array.size(); ++i) s += (i ? ", " : "") + detail::format_number(e.array[i]);
      return s + "]";
    }
    case SceneEntry::Kind::Names: {
      std::string s = "[";
      for (std::size_t i = 0; i < e.names.size(); ++i) s += (i ? ", \"" : "\"") + e.names[i] + "\"";
      return s + "]";
    }
  }
  return "";
}

/// Defaults: the default-constructed Scene for the tables; one default-constructed entry of
/// every element and contact type for the network keys (the first type that has the key).
std::map<std::string, std::string> defaults() {
  std::map<std::string, std::string> d;
  for_each_scene_entry(Scene{}, [&](const SceneEntry& e) {
    d[e.table.empty() ? e.key : e.table + "." + e.key] = value_text(e);
  });
  Scene s;
  s.network.nodes.emplace_back();
  for (const scene_detail::ElementKindInfo& k : scene_detail::element_kinds()) {
    ElementSpec e;
    e.kind = k.kind;
    s.network.elements.push_back(e);
  }
  for (ContactPointKind k : {ContactPointKind::Cam, ContactPointKind::Lash, ContactPointKind::Stop}) {
    ContactPointSpec c;
    c.kind = k;
    s.network.contacts.push_back(c);
  }
  for_each_network_entry(s, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& keys) {
    for (const SceneEntry& e : keys) d.emplace(array + "." + e.key, value_text(e));
  });
  return d;
}

std::string json_str(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += c;
  }
  return o + "\"";
}

std::string md_cell(const std::string& s) {
  std::string o;
  for (char c : s) o += c == '|' ? std::string("\\|") : std::string(1, c);
  return o;
}

}  // namespace

std::vector<SceneKeyInfo> scene_keys() {
  std::map<std::string, KeyDoc> docs;
  for (const KeyDoc& d : kDocs) docs[d.key] = d;
  // The keys of the element kinds come with their documentation (src/scene/element_kinds.cpp).
  static const std::vector<scene_detail::ElementKeyDoc> element_docs = scene_detail::element_key_docs();
  for (const scene_detail::ElementKeyDoc& e : element_docs)
    docs[e.key] = KeyDoc{e.key.c_str(),  e.unit.c_str(), e.text.c_str(), e.type.c_str(),
                         e.rule.c_str(), e.fixed_default.empty() ? nullptr : e.fixed_default.c_str()};
  static const std::string element_type_rule = [] {
    std::string r;
    for (const scene_detail::ElementKindInfo& k : scene_detail::element_kinds())
      r += std::string(r.empty() ? "must be one of \"" : ", \"") + k.name + "\"";
    return r;
  }();
  docs["elements.type"].rule = element_type_rule.c_str();
  const std::map<std::string, std::string> dflt = defaults();
  std::vector<SceneKeyInfo> out;
  std::set<std::string> seen;
  for (const detail::KeyTableRow& row : detail::key_table()) {
    auto it = docs.find(row.key);
    if (it == docs.end())
      throw std::logic_error("scene key '" + row.key + "' has no documentation: add it to kDocs in src/scene/keys.cpp");
    const KeyDoc& d = it->second;
    SceneKeyInfo k;
    k.key = row.key;
    k.type = d.type ? d.type : row.type;
    k.unit = d.unit;
    k.rule = d.rule ? d.rule : row.rule;
    k.description = d.text;
    k.applies_to = row.applies_to;
    k.input_only = d.input_only;
    if (d.fixed_default) {
      k.default_value = d.fixed_default;
    } else {
      auto v = dflt.find(row.key);
      k.default_value = v != dflt.end() ? v->second : "(none)";
    }
    seen.insert(row.key);
    out.push_back(std::move(k));
  }
  for (const KeyDoc& d : kDocs)
    if (!seen.count(d.key))
      throw std::logic_error(std::string("src/scene/keys.cpp documents '") + d.key + "', which is no scene key");
  return out;
}

std::string scene_keys_markdown() {
  std::ostringstream o;
  o << "# Scene keys\n\n"
       "Every key a scene file takes, with its type, unit, default and rule. Lengths, masses and times are in "
       "any consistent units. *Rule* is the key's own check as the loader words it; rules between keys are in "
       "the description. *Default* is the value of a key left out of the file. The file format around the keys "
       "(tables, the arrays of a network, sign conventions) is in [the interface](../interface.md).\n\n"
       "This page is generated by `camdyn scene --keys` (JSON: `--keys --json`; C++: `camdyn::scene_keys()`) "
       "from the scene's key table in `src/scene/scene.cpp` — the table that parses, validates, applies `--set` and "
       "writes `to_toml` — with the defaults of the default-constructed scene and the units and descriptions "
       "of one table next to it (`src/scene/keys.cpp`); the program refuses to print it when that table misses "
       "a key or names one that does not exist, and the test `SceneKeys.*` checks that every key the scene "
       "writers visit is here.\n";
  std::string section = "\x01";
  for (const SceneKeyInfo& k : scene_keys()) {
    const auto dot = k.key.find('.');
    const std::string table = dot == std::string::npos ? "" : k.key.substr(0, dot);
    const bool network = table == "nodes" || table == "elements" || table == "contacts";
    if (table != section) {
      section = table;
      o << "\n## " << (table.empty() ? "Top level" : network ? "[[" + table + "]]" : "[" + table + "]") << "\n\n";
      o << (network ? "| key | for | type | unit | default | rule | description |\n|---|---|---|---|---|---|---|\n"
                    : "| key | type | unit | default | rule | description |\n|---|---|---|---|---|---|\n");
    }
    o << "| `" << k.key << "` | ";
    if (network) {
      std::string f;
      for (const auto& a : k.applies_to) f += (f.empty() ? "" : ", ") + a;
      o << (f.empty() ? "all" : f) << " | ";
    }
    o << k.type << " | " << k.unit << " | `" << md_cell(k.default_value) << "` | " << md_cell(k.rule) << " | "
      << md_cell(k.description) << " |\n";
  }
  return o.str();
}

std::string scene_keys_json() {
  std::ostringstream o;
  o << "[\n";
  const std::vector<SceneKeyInfo> keys = scene_keys();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const SceneKeyInfo& k = keys[i];
    o << "  {\"key\": " << json_str(k.key) << ", \"type\": " << json_str(k.type) << ", \"unit\": "
      << json_str(k.unit) << ", \"default\": " << json_str(k.default_value) << ", \"rule\": " << json_str(k.rule)
      << ", \"description\": " << json_str(k.description) << ", \"applies_to\": [";
    for (std::size_t j = 0; j < k.applies_to.size(); ++j) o << (j ? ", " : "") << json_str(k.applies_to[j]);
    o << "]}" << (i + 1 < keys.size() ? "," : "") << "\n";
  }
  o << "]\n";
  return o.str();
}

}  // namespace camdyn
