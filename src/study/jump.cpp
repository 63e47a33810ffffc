// camdyn — required contact force and jump speed (designer.hpp; the simulation route's
// speed-range map: speed_map.cpp; batch runs: batch.cpp).
#include "camdyn/designer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "camdyn/cam.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/output.hpp"
#include "results/designer_stats.hpp"
#include "results/verdict.hpp"
#include "study/speed_map.hpp"
#include "scene/shared_cam.hpp"

namespace camdyn {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;

std::string num(double x) { return format_double(x); }

void require_rigid(const Scene& s, const char* what) {
  if (s.follower.kind != FollowerKind::Rigid)
    throw SceneError(s.source, 0, "follower.kind", to_string(s.follower.kind),
                     std::string(what) + " needs follower.kind = \"rigid\"");
}
void require_constant_speed(const Scene& s) {
  if (!s.cam.speed_table_t.empty() || !s.cam.speed_table_rev_s.empty())
    throw SceneError(s.source, 0, "cam.speed_table_rev_s", "[...]",
                     "the jump speed is defined for a constant cam speed: remove the speed table");
}

// The terms of F_req at one cam angle: F_req = A ω² + B ω + C ω̇ + S.
struct ReqTerms {
  double A, B, C, S;
};
ReqTerms req_terms(const Scene& s, const Cam& cam, double x0, double theta) {
  const CamPoint p = cam.evaluate(theta);
  const double m = s.follower.mass, c = s.follower.damping, k = s.spring.stiffness;
  return {m * p.d2X_dtheta2, c * p.dX_dtheta, m * p.dX_dtheta,
          k * s.spring.precompression + k * (p.X_C - x0)};
}
double spring_origin(const Scene& s, const Cam& cam) {
  const CamDrive drive(s.cam);
  return cam.evaluate(drive.theta(0.0)).X_C + s.contact.initial_gap;
}

// Smallest w > 0 with A w² + B w + S = 0 (B already signed with the direction); +inf if
// none; 0 if S ≤ 0 (the spring does not hold the follower even at rest).
double contact_loss_speed(const ReqTerms& r) {
  const double A = r.A, B = r.B, S = r.S;
  if (!(S > 0)) return 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  if (A < 0) {
    const double D = std::sqrt(B * B - 4 * A * S);
    return B >= 0 ? (B + D) / (-2 * A) : 2 * S / (D - B);
  }
  if (B >= 0) return inf;
  if (A == 0) return S / (-B);
  const double disc = B * B - 4 * A * S;
  if (disc < 0) return inf;
  return 2 * S / (std::sqrt(disc) - B);
}

JumpResult jump_closed_form(const Scene& s, const JumpOptions& o, double dir) {
  const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(s.cam);
  const Cam& cam = *cam_owner;
  const double x0 = spring_origin(s, cam);
  auto w = [&](double th) {
    ReqTerms r = req_terms(s, cam, x0, th);
    r.B *= dir;
    return contact_loss_speed(r);
  };
  const int N = o.scan_points;
  const double dth = kTwoPi / N;
  std::vector<double> v(static_cast<std::size_t>(N));
  for (int i = 0; i < N; ++i) v[static_cast<std::size_t>(i)] = w(dth * i);
  const double best_scan = *std::min_element(v.begin(), v.end());
  JumpResult res;
  res.method = "closed-form";
  if (!std::isfinite(best_scan)) {
    res.jump_speed_rev_s = dir * std::numeric_limits<double>::infinity();
    res.theta_deg = NAN;
    return res;
  }
  double best = best_scan;
  double best_th = dth * double(std::min_element(v.begin(), v.end()) - v.begin());
  // Refine every scan minimum within 1 % of the best (golden section on [θ−Δ, θ+Δ]).
  for (int i = 0; i < N; ++i) {
    const double vi = v[static_cast<std::size_t>(i)];
    const double vl = v[static_cast<std::size_t>((i + N - 1) % N)];
    const double vr = v[static_cast<std::size_t>((i + 1) % N)];
    if (!(vi <= vl && vi <= vr) || vi > best_scan * 1.01 + 1e-300) continue;
    double a = dth * (i - 1), b = dth * (i + 1);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = w(c), fd = w(d);
    for (int it = 0; it < 200 && b - a > 1e-12; ++it) {
      if (fc <= fd) {
        b = d; d = c; fd = fc; c = b - g * (b - a); fc = w(c);
      } else {
        a = c; c = d; fc = fd; d = a + g * (b - a); fd = w(d);
      }
    }
    const double th = 0.5 * (a + b);
    double f = w(th);
    double th_best = th;
    if (vi < f) { f = vi; th_best = dth * i; }
    if (f < best) {
      best = f;
      best_th = th_best;
    }
  }
  // The one-sided values at the cam's joints: F_req jumps there (an arc corner, a law
  // joint), and a minimum on a joint is not a minimum of either smooth piece's interior.
  for (double b : cam.breakpoints())
    for (double th : {b - 1e-12, b + 1e-12}) {
      const double f = w(th);
      if (f < best) {
        best = f;
        best_th = th;
      }
    }
  res.jump_speed_rev_s = dir * best / kTwoPi;
  res.theta_deg = detail::angle_deg_mod360(best_th);
  return res;
}

}  // namespace

double required_contact_force(const Scene& scene, double theta, double omega, double omega_dot) {
  require_rigid(scene, "required_contact_force");
  const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(scene.cam);
  const Cam& cam = *cam_owner;
  const ReqTerms r = req_terms(scene, cam, spring_origin(scene, cam), theta);
  return r.A * omega * omega + r.B * omega + r.C * omega_dot + r.S;
}

double required_contact_force(const Scene& scene, double theta) {
  require_constant_speed(scene);
  return required_contact_force(scene, theta, kTwoPi * scene.cam.speed_rev_s, 0.0);
}

void JumpOptions::validate() const {
  if (scan_points < 16)
    throw SceneError("JumpOptions", 0, "scan_points", std::to_string(scan_points), "must be >= 16");
  if (!(rel_tol >= 1e-12 && rel_tol <= 0.5))
    throw SceneError("JumpOptions", 0, "rel_tol", num(rel_tol), "must be between 1e-12 and 0.5");
  if (!(lo_rev_s >= 0) || !std::isfinite(lo_rev_s))
    throw SceneError("JumpOptions", 0, "lo_rev_s", num(lo_rev_s), "must be >= 0 (0: automatic)");
  if (!(hi_rev_s >= 0) || !std::isfinite(hi_rev_s))
    throw SceneError("JumpOptions", 0, "hi_rev_s", num(hi_rev_s), "must be >= 0 (0: automatic)");
  if (grid_points < 2 || grid_points > 100000)
    throw SceneError("JumpOptions", 0, "grid_points", std::to_string(grid_points), "must be between 2 and 100000");
  if (lo_rev_s > 0 && hi_rev_s > 0 && !(lo_rev_s < hi_rev_s))
    throw SceneError("JumpOptions", 0, "lo_rev_s", num(lo_rev_s),
                     "must be < hi_rev_s = " + num(hi_rev_s));
}

namespace {
// The scene of a jump-speed search, resolved and checked (options too).
Scene jump_scene(const Scene& scene_in, const JumpOptions& o) {
  o.validate();
  Scene scene = scene_in;
  resolve_defaults(scene);
  validate(scene);
  require_constant_speed(scene);
  return scene;
}
}  // namespace

JumpResult jump_speed(const Scene& scene_in, const JumpOptions& o) {
  const Scene scene = jump_scene(scene_in, o);
  const double dir = scene.cam.speed_rev_s < 0 ? -1.0 : 1.0;
  if (scene.follower.kind == FollowerKind::Rigid && !o.force_simulation) {
    JumpResult r = jump_closed_form(scene, o, dir);
    if (std::isfinite(r.theta_deg)) {
      const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(scene.cam);
      const Cam& cam = *cam_owner;
      const detail::CamRegions reg(cam, scene.cam);
      r.phenomenon = detail::region_kind(reg.at(r.theta_deg * (kTwoPi / 360.0)));
      char b[64];
      std::snprintf(b, sizeof b, "%.1f", r.theta_deg);
      r.phenomenon_text = std::string(detail::kind_words(r.phenomenon)) + " at " + b + " deg";
    } else {
      r.phenomenon = "no_separation";
      r.phenomenon_text = detail::kind_words(r.phenomenon);
    }
    return r;
  }

  // Simulation: the speed-range map, its automatic range around the rigid-body estimate.
  Scene rigid = scene;
  rigid.follower.kind = FollowerKind::Rigid;
  rigid.follower.damping = 0.0;
  // (a network has no rigid-body estimate: the range starts around the scene's speed)
  const double est = scene.follower.kind == FollowerKind::Network
                         ? std::abs(scene.cam.speed_rev_s)
                         : std::abs(jump_closed_form(rigid, o, dir).jump_speed_rev_s);
  return detail::speed_map(scene, o, dir, est, nullptr);
}

JumpResult jump_speed(const Scene& scene_in, std::shared_ptr<const FollowerSystem> follower,
                      const JumpOptions& o) {
  if (!follower)
    throw SceneError("jump_speed", 0, "follower", "null",
                     "no follower given (for the scene's own follower call jump_speed(scene, options))");
  const Scene scene = jump_scene(scene_in, o);
  const double dir = scene.cam.speed_rev_s < 0 ? -1.0 : 1.0;
  // A user follower has no rigid-body estimate: the range starts around the scene's speed.
  return detail::speed_map(scene, o, dir, std::abs(scene.cam.speed_rev_s), follower);
}

}  // namespace camdyn
