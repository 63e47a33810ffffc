// camdyn — bring your own follower: a user-defined follower through the public API.
//
//   M q̈ = r(t, q, q̇) + Tᵀ F,   F ≥ 0 (one entry per contact),
//   gap of contact j:  g_j = T_j q + clearance_j − X_C(t)·[cam]   (X_C: the cam's lift above
//   its base circle, as for network scenes — cam_lift_motion(), not the absolute
//   Cam::motion(); camdyn/initial_state.hpp). A start with g_j < −contact.tol_u is refused
//   (SceneError); initial_state_on_cam() gives a state on the cam.
//
// r may be nonlinear (a progressive valve spring, a hydraulic element, …); M is constant
// (its action M⁻¹ is what the methods need). The scene gives the cam, the contact method,
// the engine and the run (Simulator(scene, follower)); the follower replaces the scene's
// follower.* / [spring] / network tables. Lee's method needs r, M⁻¹ and the contact rows
// only — no linear held model — and iterates with Lee's constants (W = T M⁻¹ Tᵀ) where the
// step map is not affine; penalty and event-driven run as well. An implicit engine uses
// force_jacobian() when given, SUNDIALS' difference quotients otherwise.
//
// Example (C++): tests/mechanism/test_follower_system.cpp and README "Bring your own follower".
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace camdyn {

/// One contact point of a user-defined follower.
struct FollowerContact {
  /// Unique, non-empty [A-Za-z0-9_-]: history columns F_<name>, gap_<name>, in_<name>.
  std::string name;
  /// T_j over the follower's unknowns (size() entries, not all zero).
  std::vector<double> row;
  /// Gap at q = 0 (cam: on the base circle) [length], ≥ 0.
  double clearance = 0.0;
  /// true: the cam's lift enters the gap (a cam contact); false: a stop or lash.
  bool cam = true;
  /// Unset: the scene's [contact] restitution / penalty_stiffness / penalty_damping.
  std::optional<double> restitution, penalty_stiffness, penalty_damping;
};

/// A user-defined follower. Implementations must be thread-compatible: one Simulator calls
/// it from one thread; const methods may be called many times per step.
class FollowerSystem {
 public:
  virtual ~FollowerSystem() = default;
  /// Number of unknowns n ≥ 1 (displacements; the state is [q; q̇]).
  virtual int size() const = 0;
  /// The contacts (≥ 1), in order.
  virtual std::vector<FollowerContact> contacts() const = 0;
  /// r(t, q, q̇): every force on the follower but the contacts' (n entries).
  virtual void force(double t, const double* q, const double* v, double* r) const = 0;
  /// x = M⁻¹ b (M constant, symmetric positive definite).
  virtual void solve_mass(const double* b, double* x) const = 0;
  /// Optional Jacobians ∂r/∂q and ∂r/∂q̇ (n × n, column-major); return false if not given
  /// (the default: implicit engines then use difference quotients).
  virtual bool force_jacobian(double /*t*/, const double* /*q*/, const double* /*v*/, double* /*dr_dq*/,
                              double* /*dr_dv*/) const {
    return false;
  }
  /// true if r is affine in (q, q̇) with constant coefficients and no explicit t: Lee's step
  /// map is then affine and the located step solves its force shape exactly (default false:
  /// Lee iterates with its constants).
  virtual bool linear() const { return false; }
  /// Initial state (default: at rest at q = 0). Every gap must be ≥ −contact.tol_u at t = 0
  /// (Simulator throws SceneError otherwise); initial_state_on_cam() closes the cam contacts.
  virtual void initial_state(double* q, double* v) const {
    for (int i = 0; i < size(); ++i) q[i] = v[i] = 0.0;
  }
  /// Energies for the history's energy columns (NaN: not provided; the balance is then not
  /// checked). potential_energy: of r's conservative part, up to a constant; dissipated
  /// power: −q̇ᵀ r_dissipative.
  virtual double kinetic_energy(const double* /*v*/) const { return NAN; }
  virtual double potential_energy(const double* /*q*/) const { return NAN; }
  virtual double damping_power(const double* /*v*/) const { return 0.0; }
  /// For reports.
  virtual std::string name() const { return "user-defined follower"; }
};

}  // namespace camdyn
