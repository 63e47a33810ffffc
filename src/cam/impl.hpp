// camdyn — internal to cam.cpp and cam_profiles.cpp: Cam::Impl (the profile data of a
// Cam) and the helpers both files use. Not a public header.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "cam/follower_geometry.hpp"
#include "cam/follower_oscillating.hpp"
#include "cam/spline.hpp"

namespace camdyn {

namespace cam_detail {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kDeg = kPi / 180.0;

[[noreturn]] inline void fail(const std::string& key, const std::string& value,
                       const std::string& rule) {
  throw SceneError("<cam>", 0, key, value, rule);
}

inline bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

struct Derivs {
  double x, x1, x2, y, y1, y2;
};

}  // namespace cam_detail

// =====================================================================================
struct Cam::Impl {
  CamProfileKind kind = CamProfileKind::Points;
  // circle
  double R = 0, e = 0;
  // points
  detail::PeriodicSpline sx, sy;
  std::vector<double> tab_alpha, tab_phi;  // N + 1 entries; tab_phi unwrapped, increasing
  // lift
  detail::PeriodicSpline Ls;
  double rb = 0;
  // law, arc, and non-flat followers (follower_geometry.hpp)
  std::shared_ptr<const detail::TranslatingGeometry> geo;
  std::shared_ptr<const detail::OscillatingGeometry> osc;  // follower_oscillating.hpp
  std::vector<double> breaks;
  // derived
  double lift = 0, min_rho = 0;
  // Segment of the last contact point: where the next search starts. The segment found
  // is the unique k with tab_phi[k] ≤ target < tab_phi[k+1] whatever the hint, so
  // concurrent const calls on one Cam (threads) only race on speed, not on results; a
  // relaxed atomic makes that race defined behaviour.
  struct Hint {
    mutable std::atomic<std::size_t> k{0};
    Hint() = default;
    Hint(const Hint& o) : k(o.k.load(std::memory_order_relaxed)) {}
    Hint& operator=(const Hint& o) {
      k.store(o.k.load(std::memory_order_relaxed), std::memory_order_relaxed);
      return *this;
    }
    std::size_t get() const { return k.load(std::memory_order_relaxed); }
    void set(std::size_t v) const { k.store(v, std::memory_order_relaxed); }
  } hint;

  void build_points(const CamSpec& spec);
  void build_circle(const CamSpec& spec);
  void build_lift(const CamSpec& spec);

  cam_detail::Derivs derivs(double a) const {
    std::size_t seg;
    double s;
    sx.locate(a, &seg, &s);  // sx and sy share the knots
    cam_detail::Derivs d;
    sx.eval_local(seg, s, &d.x, &d.x1, &d.x2);
    sy.eval_local(seg, s, &d.y, &d.y1, &d.y2);
    return d;
  }

  /// points: α* of the contact point at cam angle θ (cos θ = ct, sin θ = st), with the
  /// profile derivatives there.
  double contact_alpha(double theta, double ct, double st, cam_detail::Derivs* out) const;
  CamPoint evaluate(double theta) const;
};

}  // namespace camdyn
