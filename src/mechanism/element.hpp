// camdyn (private) — an element of a mechanism as a part: its generalised force on its nodes,
// its Jacobian blocks, optional internal states, its energy and its named forces
// (docs/guide/architecture.md "Adding an element").
//
//   An element sees its nodes' displacements x and velocities ẋ (one entry per node, in the
//   order of the scene's `nodes`; "ground" reads 0), the time t and its internal states s:
//
//     f = f(t, x, ẋ, s)          generalised force on its nodes (added to r in M q̈ = r + TᵀF)
//     ∂f/∂x, ∂f/∂ẋ                dense nodes() × nodes() blocks (the mechanism scatters them
//                                 into one sparse tangent whose pattern is fixed at build time)
//     ṡ = g(t, x, ẋ, s)          its internal states' equations, with ∂g/∂x, ∂g/∂ẋ, ∂g/∂s, ∂f/∂s
//     V(x, s), P(t, x, ẋ, s)     stored energy (up to a constant) and dissipated power, for the
//                                 run's energy ledger: f·ẋ = −dV/dt − P for a passive element
//     force_names(), forces()     what history.csv shows as force_<name> (run.element_forces)
//
// Linear elements (spring, dashpot, bar, lever, node mass) are not Elements: they assemble
// into the mechanism's sparse M, C, K, f₀ (src/mechanism/mechanism.cpp), so a linear train
// keeps its linear-algebra path. An Element is a nonlinear part; a mechanism with one is not
// linear() and its implicit engines add the element tangent K_e = −∂r_e/∂q, C_e = −∂r_e/∂q̇
// to their Newton matrix (SparseNewton::element_tangent, IDA's residual Jacobian). Internal
// states s are carried by the ODE engines after q and v (y = [q; v; s], element_set.hpp);
// IDA carries them after its multipliers and the cam's work (y = [q; v; λ; μ; W; s]).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace camdyn {

struct ElementSpec;
struct Scene;

/// What an element's functions receive.
struct ElementState {
  double t = 0.0;
  const double* x = nullptr;   ///< nodes() displacements
  const double* xd = nullptr;  ///< nodes() velocities
  const double* s = nullptr;   ///< states() internal states (null when states() = 0)
};

/// A nonlinear element of a mechanism (see the file comment).
class Element {
 public:
  /// @param name the element's name (history column force_<name>).
  /// @param nodes number of nodes it acts on (≥ 1).
  /// @param states number of internal states (≥ 0).
  Element(std::string name, int nodes, int states = 0) : name_(std::move(name)), nodes_(nodes), states_(states) {}
  virtual ~Element() = default;

  const std::string& name() const { return name_; }
  int nodes() const { return nodes_; }
  int states() const { return states_; }
  /// The kind as in the scene ("progressive_spring").
  virtual const char* kind() const = 0;
  /// One line for the model description ("progressive_spring 'x' [a → b] …").
  virtual std::string describe() const = 0;

  /// f (nodes() entries, overwritten).
  virtual void force(const ElementState& e, double* f) const = 0;
  /// ∂f/∂x and ∂f/∂ẋ, nodes() × nodes() column-major (entry (i, j) at [i + j·nodes()]),
  /// overwritten. dfdxd may be null when damps() is false.
  virtual void force_jacobian(const ElementState& e, double* dfdx, double* dfdxd) const = 0;
  /// false: f does not depend on ẋ (its ∂f/∂ẋ block is left out of the pattern).
  virtual bool damps() const = 0;

  /// Internal states (states() > 0 only): ṡ = g (states() entries) and the blocks ∂g/∂x,
  /// ∂g/∂ẋ (states() × nodes()), ∂g/∂s (states() × states()), ∂f/∂s (nodes() × states()),
  /// column-major. The initial states s(0).
  virtual void state_rate(const ElementState&, double* /*sdot*/) const {}
  virtual void state_jacobian(const ElementState&, double* /*dgdx*/, double* /*dgdxd*/, double* /*dgds*/,
                              double* /*dfds*/) const {}
  virtual void initial_states(double* /*s0*/) const {}

  /// Stored energy V(x, s), zero at the installed position x = 0.
  virtual double stored_energy(const ElementState& e) const = 0;
  /// Dissipated power P ≥ 0 (signed for an element that is an external force, e.g. a gas
  /// load: minus the power it puts in, so that the energy ledger closes).
  virtual double dissipated_power(const ElementState& e) const = 0;

  /// The element's reported forces: names (history columns force_<name>) and values.
  /// Default: one force, named name(): the compressive force along its first two nodes.
  virtual std::vector<std::string> force_names() const { return {name_}; }
  virtual void forces(const ElementState& e, double* out) const = 0;

 private:
  std::string name_;
  int nodes_, states_;
};

/// The Element of a nonlinear scene element, null for a linear kind (spring, dashpot, bar,
/// lever), which assembles into M, C, K, f₀. The one place an element kind is registered
/// (src/mechanism/elements/registry.cpp).
/// @param name the element's report name (its scene name, or "<kind>_<index>").
/// @param scene the element's scene (a gas_load reads its cam drive θ(t); may be null for
/// the other kinds).
/// @pre validate(scene) passed.
std::unique_ptr<Element> make_element(const ElementSpec& spec, const std::string& name,
                                      const Scene* scene = nullptr);

}  // namespace camdyn
