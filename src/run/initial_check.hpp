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
class MechanicalSystem;
namespace detail {

/// Where the start of a mechanism comes from (the keys a message names).
enum class StartKeys {
  Scene,  ///< the scene's follower: rigid and elastic_bar (gap = q₀(0) − X_C(θ₀), X_C
          ///< absolute; key contact.initial_gap) or a network (keys
          ///< nodes[i].initial_displacement, contacts[j].clearance)
  User,   ///< a user FollowerSystem (file "<follower>", keys initial_state(), contacts()[j])
};
/// @throws SceneError naming the first contact the start penetrates.
void check_start(const Scene& scene, const MechanicalSystem& mech, StartKeys keys);

}  // namespace detail
}  // namespace camdyn
