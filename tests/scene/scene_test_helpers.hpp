// Helpers of the scene tests (test_scene.cpp, test_scene_override.cpp): the error message of a
// scene text or of one override, an example's path, the key lists the messages name.
#pragma once

#include <string>

#include "camdyn/scene.hpp"

#ifndef CAMDYN_SOURCE_DIR
#define CAMDYN_SOURCE_DIR "."
#endif

namespace scene_test {

using namespace camdyn;


inline std::string example(const std::string& name) { return std::string(CAMDYN_SOURCE_DIR) + "/examples/" + name; }

inline std::string error_of(const std::string& text, const std::string& file = "bad.toml") {
  try {
    parse_scene(text, file);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}

inline std::string override_error(Scene s, const std::string& assignment) {
  try {
    apply_override(s, assignment);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}

inline const std::string kCamKeys =
    "profile, angles_deg, radii, base_radius, lift_angles_deg, lift, radius, eccentricity, speed_rev_s, speed_rpm, rpm_of, "
    "speed_table_t, speed_table_rev_s, theta0_deg, law, lift_table, nose_radius, nose_distance, flank_radius, "
    "arc_centre_x, arc_centre_y, arc_centre_r, arc_centre_deg, arc_radius, arc_from_deg, arc_to_deg, "
    "follower_face, follower_offset, roller_radius, follower_motion, pivot_x, pivot_y, arm_length, pad_offset, "
    "valve_arm, land_on_breaks, width, youngs_modulus, poisson_ratio, "
    "follower_youngs_modulus, follower_poisson_ratio, friction_coefficient, friction_static_coefficient, "
    "friction_stribeck_speed, roller_slip";
inline const std::string kTopKeys = "title, cam, follower, spring, contact, solver, run, jump, criteria, lubricant, camshaft, synthesis, nodes, elements, contacts";


}  // namespace scene_test
