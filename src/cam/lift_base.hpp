// camdyn (private) — the cam's base X for the parts below the run (contact, mechanism,
// results); the same function is public in camdyn/initial_state.hpp.
#pragma once

#include "camdyn/cam.hpp"

namespace camdyn {

/// X_base: the X_C from which a network's or a user follower's cam contact measures the
/// cam's lift (cam.base_radius for profile "lift"; min over θ of X_C for "points" and
/// "circle", by a scan of 3600 angles refined by golden section). Defined in
/// src/cam/extremes.cpp.
/// @pre `cam` was built from `spec`.
double cam_lift_base(const Cam& cam, const CamSpec& spec);

}  // namespace camdyn
