// camdyn (private) — the plausibility warnings that need only the scene (no cam): the
// camshaft speed and the network's masses and stiffnesses. scene_warnings()
// (src/run/lift_warnings.cpp) adds those that need the cam's lift and keeps the documented
// order (include/camdyn/scene_warnings.hpp).
#pragma once

#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/scene_warnings.hpp"

namespace camdyn {
namespace scene_detail {

/// A value as a warning names it: four significant digits (0.008, 1e+10); whole numbers
/// below 1e9 in full (35000).
std::string warning_number(double x);

/// Appends the warning for a camshaft speed (cam.speed_rev_s, or the largest of
/// cam.speed_table_rev_s) above `ranges.max_speed_rev_s`, if there is one.
void append_speed_warning(const Scene& scene, const PlausibleRanges& ranges, std::vector<std::string>& warnings);

/// Appends, in this order, the warnings for node masses (> 0) outside [min_node_mass,
/// max_node_mass], then per element a spring's stiffness (> 0) outside [min_stiffness,
/// max_stiffness], a spring's negative preload and a bar's E·A/L outside that range.
void append_network_part_warnings(const NetworkSpec& network, const PlausibleRanges& ranges,
                                  std::vector<std::string>& warnings);

}  // namespace scene_detail
}  // namespace camdyn
