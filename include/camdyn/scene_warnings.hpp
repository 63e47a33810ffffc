// camdyn — warnings for a valid but implausible valve train: not errors, the run
// goes on; the CLI prints each as "camdyn: warning: …" on stderr, Summary::warnings and
// summary.json "warnings" keep them (docs/guide/valve_trains.md, "Plausibility warnings").
#pragma once

#include <string>
#include <vector>

#include "camdyn/follower_system.hpp"
#include "camdyn/scene.hpp"

namespace camdyn {

/// The plausibility ranges of a valve train in SI units (kg, m, N, s). Documented with
/// their reasons in docs/guide/valve_trains.md.
struct PlausibleRanges {
  double min_node_mass = 1e-3;      ///< kg: a keeper pair is a few grams
  double max_node_mass = 10.0;      ///< kg: a heavy rocker or a large-bore valve is < 1 kg
  double min_stiffness = 1e3;       ///< N/m: a hydraulic lifter's plunger spring is 1–5 N/mm
  double max_stiffness = 1e10;      ///< N/m: a steel stem or pushrod is 1e7–1e8, a Hertz contact ~1e9
  double max_lift = 0.05;           ///< m: valve lifts are 5–20 mm
  double max_speed_rev_s = 200.0;   ///< camshaft rev/s: 12 000 camshaft rpm = 24 000 engine rpm
};

/// Warnings for `scene` as a valve train: only for follower.kind = "network" (the valve-train
/// scenes, in SI units), or for a user follower when `follower` is given (its cam contacts'
/// clearances; the scene's own follower tables are then unused). Checks, in order: a cam
/// lift above max_lift (lengths given in mm?), a camshaft speed above max_speed_rev_s,
/// every cam or lash contact whose clearance is not smaller than the cam's lift (the valve
/// never opens), node masses (> 0) outside [min_node_mass, max_node_mass], spring
/// stiffnesses (> 0) and bars' E·A/L outside [min_stiffness, max_stiffness]. Other scenes
/// (the paper's rigid and elastic_bar cases, in any consistent units): none.
/// @pre the scene is valid (validate()). Never throws for a valid scene.
std::vector<std::string> scene_warnings(const Scene& scene, const FollowerSystem* follower = nullptr,
                                        const PlausibleRanges& ranges = PlausibleRanges{});

}  // namespace camdyn
