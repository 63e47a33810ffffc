// camdyn (private) — the check of a run's initial state, for every follower kind and
// contact method (called once, by Simulator's constructors; src/run/initial_state.cpp).
//
//   A contact whose gap at t = 0 is below −contact.tol_u is bad input (SceneError naming
//   the contact, the gap and the keys that set it). The penalty method, which starts in its
//   own equilibrium (each held contact penetrated by the s at which its law carries the
//   contact's force at t = 0), accepts a start down to −(s + tol_u).
#pragma once

#include "camdyn/scene.hpp"

namespace camdyn {
class FollowerModel;
class MechanicalSystem;
namespace detail {

/// Rigid and elastic_bar followers: gap = q₀(0) − X_C(θ₀) (X_C absolute).
/// @throws SceneError (key contact.initial_gap).
void check_start(const Scene& scene, const FollowerModel& model);
/// Networks (user = false: keys nodes[i].initial_displacement, contacts[j].clearance) and
/// user followers (user = true: file "<follower>", keys initial_state(), contacts()[j]).
/// @throws SceneError.
void check_start(const Scene& scene, const MechanicalSystem& mech, bool user);

}  // namespace detail
}  // namespace camdyn
