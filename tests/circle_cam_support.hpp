// The eccentric circle cam of examples/circle_cam.toml with a rigid follower, whose
// required force and jump speed are known in closed form (tests/study/test_jump_speed.cpp,
// tests/study/test_sweep.cpp, tests/results/test_designer_stats.cpp).
//
// Truths used here:
//  * Eccentric circle cam (centre (e, 0), radius R), θ₀ = 0: X_C = R + e cos θ,
//    h″ = −e cos θ, so with the spring convention of docs/method.md §1 (spring force on the
//    follower −(kδ₀ + k(u − X_C(θ₀)))) a rigid follower needs
//      F_req(θ, ω) = −m e ω² cos θ + kδ₀ + k e (cos θ − 1),
//    smallest at θ = 0 when δ₀ > e, and the jump speed is √(kδ₀/(m e))/(2π) rev/s.
//  * Same cam started at θ₀ = 180° (x₀ = R − e): F_req = −m e ω² cos θ + kδ₀ + k e(cos θ + 1)
//    turns zero first (θ > 180°) at cos θ* = (kδ₀ + k e)/(m e ω² − k e), θ* = 360° − acos(·).
//  * While the follower rides the cam its contact face is at X_C(θ) with velocity
//    −e ω sin θ: the Poincaré samples at the section angle are known exactly.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>

#include "camdyn/scene.hpp"

namespace camdyn_test {

constexpr double kPi = 3.14159265358979323846;

/// examples/NAME in the source tree.
inline std::string example(const std::string& name) {
  return (std::filesystem::path(CAMDYN_SOURCE_DIR) / "examples" / name).string();
}

/// examples/circle_cam.toml with spring stiffness k, precompression δ₀, mass m, eccentricity e
/// and radius R.
inline camdyn::Scene circle_scene(double k = 500, double d0 = 7, double m = 1, double e = 0.5, double R = 2) {
  camdyn::Scene s = camdyn::load_scene_file(example("circle_cam.toml"));
  s.spring.stiffness = k;
  s.spring.precompression = d0;
  s.follower.mass = m;
  s.cam.eccentricity = e;
  s.cam.radius = R;
  return s;
}

/// The closed-form jump speed √(kδ₀/(m e))/(2π) [rev/s] of circle_scene(k, δ₀, m, e).
inline double analytic_jump(double k, double d0, double m, double e) {
  return std::sqrt(k * d0 / (m * e)) / (2 * kPi);
}

}  // namespace camdyn_test
