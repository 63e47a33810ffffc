// camdyn — required contact force and jump speed (designer.hpp; batch runs: batch.cpp).
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
  const Cam cam(s.cam);
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

bool separates(const Scene& base, double speed, double* theta_deg,
               const std::shared_ptr<const FollowerSystem>& follower, std::vector<VerdictItem>* verdict) {
  Scene s = base;
  s.cam.speed_rev_s = speed;
  // run.output_dt is kept: Lee lands its steps on output times, so it shapes the run.
  const Summary r = follower ? Simulator(s, follower).run() : Simulator(s).run();
  if (!r.finished)
    throw SceneError(base.source, 0, "cam.speed_rev_s", num(speed),
                     "jump speed: the simulation failed there (" + r.message + ")");
  if (theta_deg) *theta_deg = r.first_separation_theta_deg;
  if (verdict) *verdict = r.verdict;
  // A network separates every cycle somewhere (the valve leaves its seat, a lash opens):
  // it jumps when its cam contact separates on the lift (the designer's first separation).
  // So does a user follower (issue 28): its first cam contact's first separation.
  if (follower || s.follower.kind == FollowerKind::Network) return !std::isnan(r.first_separation_theta_deg);
  return r.separations > 0;
}

JumpResult jump_by_simulation(const Scene& scene, const JumpOptions& o, double dir, double est,
                              const std::shared_ptr<const FollowerSystem>& follower);

}  // namespace

double required_contact_force(const Scene& scene, double theta, double omega, double omega_dot) {
  require_rigid(scene, "required_contact_force");
  const Cam cam(scene.cam);
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
      const Cam cam(scene.cam);
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

  // Simulation: bisection on "the run separates", bracket from the rigid-body estimate.
  Scene rigid = scene;
  rigid.follower.kind = FollowerKind::Rigid;
  rigid.follower.damping = 0.0;
  // (a network has no rigid-body estimate: the bracket starts around the scene's speed)
  const double est = scene.follower.kind == FollowerKind::Network
                         ? std::abs(scene.cam.speed_rev_s)
                         : std::abs(jump_closed_form(rigid, o, dir).jump_speed_rev_s);
  return jump_by_simulation(scene, o, dir, est, nullptr);
}

JumpResult jump_speed(const Scene& scene_in, std::shared_ptr<const FollowerSystem> follower,
                      const JumpOptions& o) {
  if (!follower)
    throw SceneError("jump_speed", 0, "follower", "null",
                     "no follower given (for the scene's own follower call jump_speed(scene, options))");
  const Scene scene = jump_scene(scene_in, o);
  const double dir = scene.cam.speed_rev_s < 0 ? -1.0 : 1.0;
  // A user follower has no rigid-body estimate: the bracket starts around the scene's speed.
  return jump_by_simulation(scene, o, dir, std::abs(scene.cam.speed_rev_s), follower);
}

namespace {

JumpResult jump_by_simulation(const Scene& scene, const JumpOptions& o, double dir, double est,
                              const std::shared_ptr<const FollowerSystem>& follower) {
  if (!std::isfinite(est) || est <= 0) est = 1.0;
  double lo = o.lo_rev_s > 0 ? o.lo_rev_s : 0.5 * est;
  double hi = o.hi_rev_s > 0 ? o.hi_rev_s : 1.5 * est;
  JumpResult res;
  res.method = "simulation";
  std::vector<VerdictItem> v_hi, v_dummy, v_mid;
  auto test = [&](double sp, double* th, std::vector<VerdictItem>* v) {
    const bool sep = separates(scene, dir * sp, th, follower, v);
    ++res.simulations;
    if (o.log) o.log(dir * sp, sep);
    return sep;
  };
  double th_hi = NAN, th_dummy = NAN;
  for (int i = 0; test(lo, &th_dummy, &v_dummy); ++i) {
    if (o.lo_rev_s > 0 || i >= 12)
      throw SceneError(scene.source, 0, "cam.speed_rev_s", num(dir * lo),
                       "jump speed: the follower already separates at the lower bracket speed");
    hi = lo;
    lo *= 0.5;
  }
  for (int i = 0; !test(hi, &th_hi, &v_hi); ++i) {
    if (o.hi_rev_s > 0 || i >= 12)
      throw SceneError(scene.source, 0, "cam.speed_rev_s", num(dir * hi),
                       "jump speed: no separation up to the upper bracket speed within run.t_end");
    lo = hi;
    hi *= 2.0;
  }
  while (hi - lo > o.rel_tol * hi) {
    const double mid = 0.5 * (lo + hi);
    double th = NAN;
    if (test(mid, &th, &v_mid)) {
      hi = mid;
      th_hi = th;
      v_hi = v_mid;
    } else {
      lo = mid;
    }
  }
  res.lo_rev_s = dir * lo;
  res.hi_rev_s = dir * hi;
  res.jump_speed_rev_s = dir * 0.5 * (lo + hi);
  res.theta_deg = th_hi;
  res.phenomenon_text = detail::verdict_one_line(v_hi);
  for (const VerdictItem& v : v_hi)
    if (res.phenomenon.empty() && v.kind != "seat_bounce") res.phenomenon = v.kind;
  if (res.phenomenon.empty() && !v_hi.empty()) res.phenomenon = v_hi.front().kind;
  return res;
}

}  // namespace

}  // namespace camdyn
