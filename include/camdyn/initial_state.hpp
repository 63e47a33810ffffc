// camdyn — the start of a run: what X_C means for each contact, the check of the initial
// state, and a helper that puts a user-defined follower on the cam at t = 0
// (docs/initial_state.md).
//
//   Two follower families measure the cam differently:
//     rigid, elastic_bar   gap = q₀ − X_C(θ)              X_C absolute: the face position
//                                                          from the cam's centre O
//     network, user        gap = T q + clearance − X_L(t)  X_L = X_C − X_base: the cam's lift
//                                                          above its base circle
//   X_base (cam_lift_base): profile "lift" — cam.base_radius (the table's L = 0; the
//   spline through the table may ring a little below it between knots); "points" and
//   "circle" — the smallest X_C over a revolution (points: the smallest support-function
//   value of the spline, e.g. 1.9807 for the paper's cam whose knots sit at r = 2.0;
//   circle: R − e).
//
//   A run starts only from an initial state that penetrates no contact by more than
//   contact.tol_u (the penalty method: by more than its own equilibrium penetration +
//   tol_u). Simulator's constructors check it and throw SceneError naming the contact, its
//   gap and the keys that set it.
#pragma once

#include <memory>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {

/// X_base: the X_C from which a network's or a user follower's cam contact measures the
/// cam's lift (cam.base_radius for profile "lift"; min over θ of X_C for "points" and
/// "circle", by a scan of 3600 angles refined by golden section).
/// @pre `cam` was built from `spec`.
double cam_lift_base(const Cam& cam, const CamSpec& spec);

/// The cam's lift X_C − X_base, Ẋ_C, Ẍ_C at time t (the drive θ(t), ω(t), ω̇(t)): what the
/// gap of a network's or user follower's cam contact subtracts.
/// @throws SceneError on an invalid cam.
CamMotion cam_lift_motion(const CamSpec& spec, double t);

/// A follower's state at t = 0.
struct FollowerStart {
  std::vector<double> q, v;
};

/// Puts a user follower on the cam at t = 0: the state of follower.initial_state() moved by
/// the smallest M-weighted correction (δq = M⁻¹Tᵀ W⁺ r, W = T M⁻¹ Tᵀ) that closes every cam
/// contact (gap 0 and gap rate 0 at t = 0, against cam_lift_motion(scene.cam, 0)) and
/// leaves the gaps and gap rates of the other contacts (stops, lashes) as they were.
/// Return it from the follower's initial_state() to start held on the cam.
/// @throws SceneError (file "<follower>") on an invalid follower or a follower without a
/// cam contact; SceneError on an invalid cam.
FollowerStart initial_state_on_cam(const Scene& scene, const FollowerSystem& follower);

}  // namespace camdyn
