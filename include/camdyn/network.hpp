// camdyn — follower networks (valve trains): nodes, elements and several unilateral
// contacts (docs/interface.md "Networks").
//
//   A network scene (follower.kind = "network") describes the follower as a chain or tree
//   of nodes on one axis each (displacement q ≥ 0 in the node's own lift direction,
//   measured from the installed position: q = 0 at rest with the cam on its base circle):
//
//     [[nodes]]     name, mass [mass], initial_displacement, initial_velocity
//     [[elements]]  spring   nodes = [lower, upper], stiffness k, preload P, damping c,
//                            mass m_s with `masses` internal masses (a surging coil spring)
//                   dashpot  nodes = [lower, upper], damping c
//                   bar      nodes = [lower, upper], an elastic bar of `elements` elements
//                            (mass, youngs_modulus, area, length, mass_matrix, Rayleigh)
//                   lever    nodes = [input, output], q_output = ratio · q_input (a rocker);
//                            [input, output, pivot]: q_output = ratio · q_input
//                            + (1 − ratio) · q_pivot (a finger on a moving pivot)
//                   progressive_spring  nodes = [lower, upper], a force–deflection table
//                            (deflections, forces; monotone cubic), installed_deflection,
//                            damping c: a nonlinear element
//                   guide_friction  nodes = [node, guide]: Coulomb friction μN, regularised
//                            −μN tanh(v_rel / v_s) (friction_coefficient, normal_load,
//                            velocity_scale)
//                   gas_load  nodes = [valve, body]: −p(crank angle)·A on the valve
//                            (crank_angles_deg, pressures, area, crank_ratio, crank_offset_deg)
//   A spring with coil_gaps / free_length + solid_length gets one unilateral coil contact per
//   segment of its coil chain (its coils close at their solid heights: coil clash).
//     [[contacts]]  cam      nodes = [node]          gap g = q + clearance − X_C(t)
//                   lash     nodes = [lower, upper]  gap g = q_upper − q_lower + clearance
//                   stop     nodes = [node], side = "below": g = q + clearance (a valve seat)
//                                        side = "above": g = clearance − q
//
//   "ground" (q ≡ 0) may end a spring, dashpot, bar or progressive_spring. A spring, dashpot or bar between
//   [lower, upper] is compressed by δ = q_lower − q_upper and pushes lower by −(P + kδ + cδ̇)
//   and upper by +(P + kδ + cδ̇). A contact force F ≥ 0 acts along ∂g/∂q: the contact matrix
//   T has one row per contact (g = T q + g₀ − X_C(t)·[cam]), the generalised force is TᵀF.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace camdyn {

enum class ElementKind { Spring, Dashpot, Bar, Lever, ProgressiveSpring, GuideFriction, GasLoad, HydraulicLashAdjuster };
enum class ContactPointKind { Cam, Lash, Stop };
enum class StopSide { Below, Above };
enum class BarMass { Consistent, Lumped };

const char* to_string(ElementKind v);       // "spring" | "dashpot" | "bar" | "lever" | "progressive_spring"
                                            // | "guide_friction" | "gas_load" | "hydraulic_lash_adjuster"
const char* to_string(ContactPointKind v);  // "cam" | "lash" | "stop"
const char* to_string(StopSide v);          // "below" | "above"
const char* to_string(BarMass v);           // "lumped" | "consistent"
bool parse_enum(std::string_view s, ElementKind* out);
bool parse_enum(std::string_view s, ContactPointKind* out);
bool parse_enum(std::string_view s, StopSide* out);
bool parse_enum(std::string_view s, BarMass* out);

/// A node of the network: one displacement (after levers are eliminated, a node tied as a
/// lever's output is not an unknown of its own).
struct NodeSpec {
  /// Unique name, not "ground" [letters, digits, '_', '-'].
  std::string name;
  /// Lumped mass at the node [mass], ≥ 0 (a massless node needs mass from a bar, a spring
  /// with mass, or a lever tying it to one).
  double mass = 0.0;
  /// q(0) [length] and q̇(0) [length/time], finite.
  double initial_displacement = 0.0;
  double initial_velocity = 0.0;
};

/// An element between two nodes ("ground" allowed at one end of a spring, dashpot or bar).
struct ElementSpec {
  /// Optional name for reports and errors (default: "<kind> #<index>").
  std::string name;
  ElementKind kind = ElementKind::Spring;
  /// [lower, upper] (lever: [input, output] or [input, output, pivot]); two (a lever: two
  /// or three), distinct.
  std::vector<std::string> nodes;
  /// spring: stiffness k [force/length], ≥ 0.
  double stiffness = 0.0;
  /// spring: preload P [force], finite: the compressive force at q = 0 (> 0 pushes apart).
  double preload = 0.0;
  /// spring, dashpot: viscous damping c [force·time/length], ≥ 0 (dashpot: > 0).
  double damping = 0.0;
  /// spring: its own mass m_s [mass], ≥ 0; bar: total mass [mass], > 0.
  double mass = 0.0;
  /// spring with mass: internal masses N ≥ 1 (the spring becomes N + 1 springs of stiffness
  /// (N + 1)k with masses m_s/(N + 1) inside and m_s/(2(N + 1)) on each end node: a lumped
  /// bar, whose first surge frequency tends to ½√(k/m_s) like N⁻²). 0 with mass = 0.
  int masses = 0;
  /// bar: E [force/length²] > 0, A [length²] > 0, L [length] > 0, N elements ≥ 1,
  /// mass matrix, Rayleigh C = αM + βK (α, β ≥ 0).
  double youngs_modulus = 0.0;
  double area = 0.0;
  double length = 0.0;
  int elements = 1;
  BarMass mass_matrix = BarMass::Lumped;
  double rayleigh_alpha = 0.0;
  double rayleigh_beta = 0.0;
  /// lever: q_output = ratio · q_input, ratio finite and ≠ 0; with a pivot node
  /// q_output = ratio · q_input + (1 − ratio) · q_pivot (ratio = output arm / input arm, ≠ 1).
  double ratio = 1.0;
  /// progressive_spring: the force–deflection curve as a table, deflections [length]
  /// strictly increasing, forces [force] non-decreasing (a monotone curve), ≥ 2 points of
  /// the same count; F(δ) between them is the monotone cubic (PCHIP) through the points,
  /// beyond them the straight line of the end slope.
  std::vector<double> deflections;
  std::vector<double> forces;
  /// progressive_spring: the deflection at q = 0 [length], finite; the preload is F there.
  double installed_deflection = 0.0;
  /// spring, coil clash (on when solid_length > 0): the spring's free length and solid
  /// length [length] (solid_length > 0, free_length > solid_length + preload/stiffness), the
  /// installed gaps between neighbouring coil masses [length] (masses + 1 entries, one per
  /// segment of the coil chain lower → upper, each ≥ 0, adding up to the travel to solid
  /// free_length − preload/stiffness − solid_length; empty: equal gaps, uniform pitch), and
  /// the restitution of the coil-to-coil impacts (unset: [contact] restitution).
  std::vector<double> coil_gaps;
  double free_length = 0.0;
  double solid_length = 0.0;
  std::optional<double> coil_restitution;
  /// guide_friction: Coulomb coefficient μ (≥ 0), constant normal load N [force] (≥ 0),
  /// regularisation speed v_s [length/time] (> 0): f = −μN tanh(v_rel/v_s).
  double friction_coefficient = 0.0;
  double normal_load = 0.0;
  double velocity_scale = 1e-3;
  /// gas_load: cylinder pressure table p(φ) over the crank angle φ [deg] (strictly
  /// increasing, within one cycle [0, 360·crank_ratio)) and pressures [force/length²]
  /// (finite), linear between the points and periodic over the cycle; the valve-head area
  /// is `area`; φ = crank_ratio·θ + crank_offset_deg (θ the cam angle in degrees;
  /// crank_ratio 2 for a four-stroke engine).
  std::vector<double> crank_angles_deg;
  std::vector<double> pressures;
  double crank_ratio = 2.0;
  double crank_offset_deg = 0.0;
  /// hydraulic_lash_adjuster (nodes [lower, upper], compressed by δ = q_lower − q_upper;
  /// docs/interface.md): plunger area `area`
  /// [length²] > 0, the plunger spring `stiffness` ≥ 0 and `preload`, and (pressures gauge
  /// [force/length²]): chamber volume at q = 0 [length³] > 0; oil bulk modulus > 0;
  /// entrained-air volume fraction at air_reference_pressure, in [0, 1); the absolute
  /// pressure of that fraction (the atmosphere) > 0; the leak-down path: plunger diameter
  /// [length] > 0, radial clearance [length] ≥ 0 (0: no leak), leak length [length] > 0,
  /// dynamic viscosity [force·time/length²] > 0; the gallery (supply) pressure ≥ 0; the check
  /// valve: opening pressure difference ≥ 0, flow area [length²] ≥ 0 (0: no valve),
  /// discharge coefficient in (0, 1], laminar-turbulent transition pressure > 0, oil density
  /// [mass/length³] > 0; the chamber pressure at t = 0, > −air_reference_pressure.
  double chamber_volume = 0.0;
  double bulk_modulus = 1.5e9;
  double air_fraction = 0.0;
  double air_reference_pressure = 101325.0;
  double plunger_diameter = 0.0;
  double leak_clearance = 0.0;
  double leak_length = 0.0;
  double viscosity = 0.0;
  double supply_pressure = 0.0;
  double check_opening_pressure = 0.0;
  double check_area = 0.0;
  double check_discharge_coefficient = 0.7;
  double check_transition_pressure = 1000.0;
  double oil_density = 850.0;
  double initial_pressure = 0.0;
  /// hydraulic_lash_adjuster, the check valve as a ball (check_ball_mass [mass] > 0; 0: the
  /// orifice law above): its spring's stiffness [force/length] > 0, whose preload holds the
  /// ball on its seat up to check_opening_pressure (preload = check_opening_pressure · A_s);
  /// its viscous damping [force·time/length] ≥ 0; the seat bore's diameter [length] > 0
  /// (seat area A_s = π d_s²/4, curtain area π d_s x up to the full-open area check_area, or
  /// A_s when check_area is 0); the seat's contact stiffness [force/length] > 0 (a
  /// regularised elastic stop). Without a ball these keys must be 0.
  double check_ball_mass = 0.0;
  double check_ball_stiffness = 0.0;
  double check_ball_damping = 0.0;
  double check_seat_diameter = 0.0;
  double check_seat_stiffness = 0.0;
};

/// A unilateral contact (any number per network).
struct ContactPointSpec {
  /// Unique name (history columns F_<name>, gap_<name>, in_<name>; events' contact).
  std::string name;
  ContactPointKind kind = ContactPointKind::Cam;
  /// cam, stop: [node]; lash: [lower, upper].
  std::vector<std::string> nodes;
  /// Gap at q = 0 (cam: on the base circle, X_C = 0) [length], ≥ 0.
  double clearance = 0.0;
  /// stop only: which side of the node the stop is on.
  StopSide side = StopSide::Below;
  /// Per-contact values; unset = the [contact] table's restitution, penalty_stiffness,
  /// penalty_damping.
  std::optional<double> restitution;
  std::optional<double> penalty_stiffness;
  std::optional<double> penalty_damping;
};

/// The network of a scene with follower.kind = "network" (empty otherwise).
struct NetworkSpec {
  std::vector<NodeSpec> nodes;
  std::vector<ElementSpec> elements;
  std::vector<ContactPointSpec> contacts;
};

bool operator==(const NodeSpec& a, const NodeSpec& b);
bool operator==(const ElementSpec& a, const ElementSpec& b);
bool operator==(const ContactPointSpec& a, const ContactPointSpec& b);
bool operator==(const NetworkSpec& a, const NetworkSpec& b);

}  // namespace camdyn
