// camdyn — exact contact kinematics of oscillating followers (see follower_oscillating.hpp).
#include "cam/follower_oscillating.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "cam/format.hpp"

namespace camdyn {
namespace detail {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kScan = 7200;

using V2 = OscVec;
V2 operator+(V2 a, V2 b) { return {a.x + b.x, a.y + b.y}; }
V2 operator-(V2 a, V2 b) { return {a.x - b.x, a.y - b.y}; }
V2 operator*(double s, V2 a) { return {s * a.x, s * a.y}; }
double dot(V2 a, V2 b) { return a.x * b.x + a.y * b.y; }
double cross(V2 a, V2 b) { return a.x * b.y - a.y * b.x; }
V2 J(V2 a) { return {-a.y, a.x}; }  // +90°
V2 unit(double a) { return {std::cos(a), std::sin(a)}; }
V2 rot(V2 a, double t) {
  const double c = std::cos(t), s = std::sin(t);
  return {a.x * c - a.y * s, a.x * s + a.y * c};
}
double norm(V2 a) { return std::hypot(a.x, a.y); }

[[noreturn]] void fail(const std::string& key, double value, const std::string& rule) {
  throw SceneError("<cam>", 0, key, fmt_num(value), rule);
}

/// "a..b, c..d" [deg] of the runs of true flags over the scan of [0, 2π).
std::string bad_angles(const std::vector<char>& bad) {
  std::string out;
  const int n = int(bad.size());
  char b[64];
  constexpr int kListed = 6;  // runs listed (the rest counted)
  int runs = 0;
  for (int k = 0; k < n;) {
    if (!bad[k]) {
      ++k;
      continue;
    }
    const int k0 = k;
    while (k < n && bad[k]) ++k;
    if (++runs > kListed) continue;
    std::snprintf(b, sizeof b, "%s%.1f°..%.1f°", out.empty() ? "" : ", ", 360.0 * k0 / n, 360.0 * (k - 1) / n);
    out += b;
  }
  if (runs > kListed) out += " and " + std::to_string(runs - kListed) + " more";
  return out;
}

double reduce(double a, double lo) {
  double u = std::fmod(a - lo, kTwoPi);
  if (u < 0) u += kTwoPi;
  return lo + u;
}

}  // namespace

OscillatingGeometry::OscillatingGeometry(const CamSpec& spec)
    : kind_(geometry_kind(spec.profile)), face_(spec.follower_face), px_(spec.pivot_x), py_(spec.pivot_y),
      arm_(spec.arm_length), pad_(spec.pad_offset), rr_(spec.roller_radius), lv_(spec.valve_arm),
      rb_(spec.base_radius) {
  const std::string why = " (cam.follower_motion = \"oscillating\")";
  if (face_ != FollowerFace::Flat && face_ != FollowerFace::Roller)
    throw SceneError("<cam>", 0, "cam.follower_face", std::string("\"") + to_string(face_) + "\"",
                     "an oscillating follower has a flat pad or a roller: \"flat\" or \"roller\"");
  if (kind_ != CamProfileKind::Law && kind_ != CamProfileKind::Circle && kind_ != CamProfileKind::Arc &&
      kind_ != CamProfileKind::Arcs)
    throw SceneError("<cam>", 0, "cam.profile", std::string("\"") + to_string(kind_) + "\"",
                     "an oscillating follower needs cam.profile \"law\", \"table\", \"circle\", \"arc\" or \"arcs\"");
  if (spec.follower_offset != 0.0)
    fail("cam.follower_offset", spec.follower_offset, "applies to translating followers only; must be 0" + why);
  if (!std::isfinite(px_)) fail("cam.pivot_x", px_, "must be finite");
  if (!std::isfinite(py_)) fail("cam.pivot_y", py_, "must be finite");
  if (!(std::isfinite(lv_) && lv_ > 0)) fail("cam.valve_arm", lv_, "must be finite and > 0" + why);
  if (face_ == FollowerFace::Roller) {
    if (!(std::isfinite(arm_) && arm_ > 0)) fail("cam.arm_length", arm_, "must be finite and > 0" + why);
    if (!(std::isfinite(rr_) && rr_ > 0))
      fail("cam.roller_radius", rr_, "must be > 0 for cam.follower_face = \"roller\"");
  } else {
    if (!std::isfinite(pad_)) fail("cam.pad_offset", pad_, "must be finite");
    rr_ = 0.0;
  }
  const V2 P{px_, py_};
  if (!(norm(P) > 0)) fail("cam.pivot_x", px_, "the pivot must not sit on the cam centre");
  // The radius the base position touches: law — the base circle; circle/arc — the
  // profile's smallest distance from O (R − e, base_radius).
  double r0 = rb_;
  if (kind_ == CamProfileKind::Law) {
    if (!(std::isfinite(rb_) && rb_ > 0)) fail("cam.base_radius", rb_, "must be > 0");
    law_ = law_of(spec);
    for (const Breakpoint& b : law_->breakpoints()) breaks_.push_back(b.theta);
  } else {
    arcs_ = kind_ == CamProfileKind::Arcs ? make_arc_list(spec) : make_arcs(spec);
    for (const Arc& a : arcs_)
      if (a.R < 0)
        throw SceneError("<cam>", 0, "cam.arc_radius", fmt_num(a.R),
                         "an oscillating follower needs a convex cam (every arc radius > 0)");
    r0 = INFINITY;
    for (int k = 0; k < kScan; ++k) {
      const auto p = profile_point(kTwoPi * k / kScan);
      r0 = std::min(r0, std::hypot(p[0], p[1]));
    }
  }
  // Base position and the sense σ: of the two assemblies touching the circle (O, r0), the
  // one whose contact lies nearer the +X axis (largest X).
  const double d = norm(P), beta = std::atan2(-P.y, -P.x);
  double bestX = -INFINITY;
  for (int sg : {1, -1}) {
    double a, qx;
    if (face_ == FollowerFace::Roller) {
      const double A = r0 + rr_, cg = (arm_ * arm_ + d * d - A * A) / (2 * arm_ * d);
      if (!(std::fabs(cg) < 1))
        fail("cam.arm_length", arm_,
             "the roller cannot reach the cam: |pivot| = " + fmt_num(d) + ", the roller centre's circle about the cam centre has radius " +
                 fmt_num(A) + " (need |arm_length − " + fmt_num(A) + "| < |pivot| < arm_length + " + fmt_num(A) + ")");
      a = beta + sg * std::acos(cg);
      qx = P.x + arm_ * std::cos(a);
    } else {
      const double q = (pad_ - sg * r0) / d;
      if (!(std::fabs(q) < 1))
        fail("cam.pad_offset", pad_,
             "the pad line cannot touch the cam: |pad_offset ∓ " + fmt_num(r0) + "| must be < |pivot| = " + fmt_num(d));
      a = beta - std::asin(q);
      qx = sg * r0 * (-std::sin(a));
    }
    if (qx > bestX) {
      bestX = qx;
      sigma_ = sg;
      alpha_b_ = a;
    }
  }
  alpha_ref_ = alpha_b_;
  if (kind_ == CamProfileKind::Law) {
    check_law_profile(spec);
  } else {
    check_arcs(spec);
  }
  check_friction_lock(spec);
  xmin_ = INFINITY;
  xmax_ = -INFINITY;
  min_rho_ = INFINITY;
  for (int k = 0; k < kScan; ++k) {
    const OscillatingState s = eval(kTwoPi * k / kScan);
    xmin_ = std::min(xmin_, s.f.s);
    xmax_ = std::max(xmax_, s.f.s);
    if (s.f.rho > 0) min_rho_ = std::min(min_rho_, s.f.rho);
  }
  if (kind_ != CamProfileKind::Law) {  // X measured from the lowest position
    alpha_ref_ += sigma_ * xmin_ / lv_;
    xmax_ -= xmin_;
    xmin_ = 0.0;
  }
  if (!std::isfinite(min_rho_)) min_rho_ = kNaN;
}

// ---- profile cams -----------------------------------------------------------------------
double OscillatingGeometry::arc_alpha(const Arc& arc, double theta, double* nu) const {
  const V2 P{px_, py_}, K = rot({arc.cx, arc.cy}, theta), D = K - P;
  const double d = norm(D), beta = std::atan2(D.y, D.x);
  double a;
  V2 nh;
  if (face_ == FollowerFace::Roller) {
    const double A = arc.R + rr_, cg = (arm_ * arm_ + d * d - A * A) / (2 * arm_ * d);
    if (!(std::fabs(cg) <= 1)) return kNaN;
    a = beta + sigma_ * std::acos(cg);
    nh = (1.0 / A) * (P + arm_ * unit(a) - K);
  } else {
    const double q = (pad_ - sigma_ * arc.R) / d;
    if (!(std::fabs(q) <= 1)) return kNaN;
    a = beta - std::asin(q);
    nh = double(sigma_) * J(unit(a));
  }
  *nu = std::atan2(nh.y, nh.x) - theta;
  return a;
}

int OscillatingGeometry::select_arc(double theta) const {
  if (arcs_.size() == 1) return 0;
  int best = -1, near = 0;
  double bestLift = -INFINITY, bestMiss = INFINITY;
  for (std::size_t i = 0; i < arcs_.size(); ++i) {
    const Arc& arc = arcs_[i];
    double nu = 0;
    const double a = arc_alpha(arc, theta, &nu);
    if (std::isnan(a)) continue;
    const double t = reduce(nu, arc.n0);
    const double miss = t <= arc.n1 ? 0.0 : std::min(t - arc.n1, arc.n0 + kTwoPi - t);
    const double lift = sigma_ * reduce(a - alpha_b_, -kPi);
    if (miss == 0.0 && lift > bestLift) {
      bestLift = lift;
      best = int(i);
    }
    if (miss < bestMiss) {
      bestMiss = miss;
      near = int(i);
    }
  }
  return best >= 0 ? best : near;
}

OscillatingState OscillatingGeometry::eval_arc(double theta) const {
  const int i = select_arc(theta);
  const Arc& arc = arcs_[i];
  double nu = 0;
  const double a = arc_alpha(arc, theta, &nu);
  const V2 P{px_, py_}, K = rot({arc.cx, arc.cy}, theta);
  // g(α, θ) = c + a_v·K(θ) + w(α)·b + λ w(α)·K(θ); K^(i) = J^i K, w^(j) = J^j w.
  // (G00 = 0 by construction; only the partial derivatives are needed.)
  double lam;
  V2 av, b, w;
  const V2 u = unit(a);
  if (face_ == FollowerFace::Roller) {
    av = -2.0 * P;
    w = u;
    b = 2.0 * arm_ * P;
    lam = -2.0 * arm_;
  } else {
    av = {0, 0};
    w = J(u);
    b = -1.0 * P;
    lam = 1.0;
  }
  V2 Ki[4], Wj[4];
  Ki[0] = K;
  Wj[0] = w;
  for (int k = 1; k < 4; ++k) {
    Ki[k] = J(Ki[k - 1]);
    Wj[k] = J(Wj[k - 1]);
  }
  auto G = [&](int i_, int j_) {
    if (j_ == 0) return dot(av, Ki[i_]) + lam * dot(Wj[0], Ki[i_]);
    if (i_ == 0) return dot(Wj[j_], b) + lam * dot(Wj[j_], Ki[0]);
    return lam * dot(Wj[j_], Ki[i_]);
  };
  const double G01 = G(0, 1), G10 = G(1, 0), G20 = G(2, 0), G11 = G(1, 1), G02 = G(0, 2);
  const double G30 = G(3, 0), G21 = G(2, 1), G12 = G(1, 2), G03 = G(0, 3);
  const double a1 = -G10 / G01;
  const double a2 = -(G20 + 2 * G11 * a1 + G02 * a1 * a1) / G01;
  const double a3 = -(G30 + 3 * G21 * a1 + 3 * G12 * a1 * a1 + G03 * a1 * a1 * a1 + 3 * G11 * a2 +
                      3 * G02 * a1 * a2) / G01;
  OscillatingState s;
  s.alpha = a;
  s.psi1 = sigma_ * a1;
  s.psi2 = sigma_ * a2;
  s.psi3 = sigma_ * a3;
  V2 nh;
  if (face_ == FollowerFace::Roller) {
    nh = (1.0 / (arc.R + rr_)) * (P + arm_ * u - K);
  } else {
    nh = double(sigma_) * J(u);
  }
  s.f.rho = arc.R;
  s.f.arc = i;
  finish(s, K + arc.R * nh, nh);
  return s;
}

// ---- law cams ------------------------------------------------------------------------------
OscillatingState OscillatingGeometry::eval_law(double theta) const {
  const LiftDerivs L = law_->eval(theta);
  OscillatingState s;
  s.alpha = alpha_b_ + sigma_ * L.L / lv_;
  s.psi1 = L.L1 / lv_;
  s.psi2 = L.L2 / lv_;
  s.psi3 = L.L3 / lv_;
  const double a1 = sigma_ * s.psi1, a2 = sigma_ * s.psi2;
  const V2 P{px_, py_}, u = unit(s.alpha), n = J(u);
  V2 nh, Q;
  if (face_ == FollowerFace::Roller) {
    const V2 C = P + arm_ * u, C1 = (arm_ * a1) * n, C2 = arm_ * a2 * n - (arm_ * a1 * a1) * u;
    const V2 T = C1 - J(C), U = C2 - 2.0 * J(C1) - C;  // pitch curve c′, c″ (cam frame, turned by θ)
    const double nt = norm(T);
    nh = (1.0 / nt) * J(T);
    Q = C - rr_ * nh;
    s.f.rho = -nt * nt * nt / cross(T, U) - rr_;
  } else {
    // Envelope of the pad lines; support function h(ν) in direction m = σ n.
    const double h = sigma_ * (dot(n, P) + pad_);
    const double h1 = -sigma_ * dot(u, P) * a1;
    const double h2 = -sigma_ * (dot(n, P) * a1 * a1 + dot(u, P) * a2);
    const double nu1 = a1 - 1.0, nu2 = a2;
    const double hn = h1 / nu1, hnn = (h2 * nu1 - h1 * nu2) / (nu1 * nu1 * nu1);
    nh = double(sigma_) * n;
    Q = h * nh - (sigma_ * hn) * u;
    s.f.rho = h + hnn;
  }
  finish(s, Q, nh);
  return s;
}

void OscillatingGeometry::finish(OscillatingState& s, V2 Q, V2 nh) const {
  s.f.cx = Q.x;
  s.f.cy = Q.y;
  s.nx = nh.x;
  s.ny = nh.y;
  s.psi = sigma_ * (s.alpha - alpha_ref_);
  if (kind_ != CamProfileKind::Law) s.psi = reduce(s.psi, -kPi);
  s.f.s = lv_ * s.psi;
  s.f.s1 = lv_ * s.psi1;
  s.f.s2 = lv_ * s.psi2;
  s.f.s3 = lv_ * s.psi3;
  const V2 P{px_, py_}, QP = Q - P;
  s.moment_arm = sigma_ * cross(QP, nh);
  s.tangent_arm = sigma_ * dot(QP, nh);
  s.normal_distance = dot(Q, nh);
  // Direction of motion (lifting) of the follower's point on the line of action: the
  // roller centre C = Q + r_r n̂ (the roller's pressure angle), the pad's point at Q.
  const V2 CP = QP + rr_ * nh;
  const V2 t = (sigma_ / norm(CP)) * J(CP);
  s.f.phi = std::atan2(cross(t, nh), dot(t, nh));
}

void OscillatingGeometry::check_friction_lock(const CamSpec& spec) {
  // Friction at the pad (docs/contacts.md): the generalised contact force on X is
  // N (a + μ s b)/ℓ_v, s = ±1 the sliding sense; it must stay positive for either sense.
  const double mu_max = std::max(spec.friction_coefficient, spec.friction_static_coefficient);
  if (face_ != FollowerFace::Flat || !(mu_max > 0)) return;
  std::vector<char> locked(kScan);
  for (int k = 0; k < kScan; ++k) {
    const OscillatingState s = eval(kTwoPi * k / kScan);
    locked[k] = !(s.moment_arm - mu_max * std::abs(s.tangent_arm) > 0);
  }
  const std::string bad = bad_angles(locked);
  if (!bad.empty())
    fail("cam.friction_coefficient", spec.friction_coefficient,
         "friction at the pad locks the arm (moment arm a <= mu |b|, b the friction force's arm about the pivot, "
         "mu = max(friction_coefficient, friction_static_coefficient)) at cam angles " +
             bad + " — lower the friction or move the pivot");
}

void OscillatingGeometry::check_law_profile(const CamSpec& spec) {
  std::vector<char> undercut(kScan), concave(kScan), back(kScan), toggle(kScan);
  for (int k = 0; k < kScan; ++k) {
    const OscillatingState s = eval_law(kTwoPi * k / kScan);
    toggle[k] = !(s.moment_arm > 0);
    if (face_ == FollowerFace::Roller) {
      const double rp = s.f.rho + rr_;
      undercut[k] = rp > 0 && !(rp > rr_);
    } else {
      concave[k] = !(s.f.rho > 0);
      back[k] = !(sigma_ * s.psi1 < 1.0);
    }
  }
  std::string bad = bad_angles(toggle);
  if (!bad.empty())
    fail("cam.pivot_x", px_,
         "the contact force cannot turn the arm (moment arm ≤ 0: the contact passes the pivot or toggles) at cam angles " +
             bad + " — move the pivot or lower the lift");
  bad = bad_angles(undercut);
  if (!bad.empty())
    fail("cam.roller_radius", rr_,
         "the cam is undercut: the pitch curve's radius of curvature is below the roller radius at cam angles " + bad +
             " — a smaller roller or a larger cam.base_radius");
  bad = bad_angles(back);
  if (!bad.empty())
    fail("cam.valve_arm", lv_,
         "the pad turns faster than the cam (ψ′ ≥ 1: the profile folds back) at cam angles " + bad);
  bad = bad_angles(concave);
  if (!bad.empty())
    fail("cam.base_radius", spec.base_radius,
         "profile is not convex: the flat pad's envelope has radius of curvature ≤ 0 at cam angles " + bad +
             " — a flat pad cannot follow a concave flank; a larger cam.base_radius, or cam.follower_face = \"roller\"");
}

void OscillatingGeometry::check_arcs(const CamSpec&) {
  std::vector<char> reach(kScan), toggle(kScan);
  for (int k = 0; k < kScan; ++k) {
    const double th = kTwoPi * k / kScan;
    const int i = select_arc(th);
    double nu = 0;
    reach[k] = std::isnan(arc_alpha(arcs_[i], th, &nu));
    if (!reach[k]) toggle[k] = !(eval_arc(th).moment_arm > 1e-9 * (std::fabs(arm_) + std::fabs(lv_) + rb_));
  }
  std::string bad = bad_angles(reach);
  if (!bad.empty())
    fail(face_ == FollowerFace::Roller ? "cam.arm_length" : "cam.pad_offset",
         face_ == FollowerFace::Roller ? arm_ : pad_, "the follower cannot reach the cam at cam angles " + bad);
  bad = bad_angles(toggle);
  if (!bad.empty())
    fail("cam.pivot_x", px_,
         "the contact force cannot turn the arm (moment arm ≤ 0: toggle position) at cam angles " + bad +
             " — move the pivot");
  if (arcs_.size() > 1) breaks_ = arc_switches([this](double th) { return select_arc(th); }, kScan);
}

void fill_cam_point(CamPoint& p, const FollowerState& f) {
  p.X_C = f.s;
  p.dX_dtheta = f.s1;
  p.d2X_dtheta2 = f.s2;
  p.d3X_dtheta3 = f.s3;
  p.rho = f.rho;
  p.pressure_angle = f.phi;
  p.beta = std::atan2(f.cy, f.cx);
  p.r = std::hypot(f.cx, f.cy);
}

void OscillatingGeometry::fill(CamPoint& p, double theta) const {
  const OscillatingState o = eval(theta);
  fill_cam_point(p, o.f);
  p.psi = o.psi;
  p.dpsi_dtheta = o.psi1;
  p.d2psi_dtheta2 = o.psi2;
  p.moment_arm = o.moment_arm;
  p.normal_force_ratio = lv_ / o.moment_arm;
}

OscillatingState OscillatingGeometry::eval(double theta) const {
  return kind_ == CamProfileKind::Law ? eval_law(theta) : eval_arc(theta);
}

std::array<double, 2> OscillatingGeometry::profile_point(double a) const {
  if (kind_ == CamProfileKind::Law) {
    const OscillatingState s = eval_law(a);
    const V2 q = rot({s.f.cx, s.f.cy}, -a);
    return {q.x, q.y};
  }
  return arc_profile_point(arcs_, a);
}

}  // namespace detail
}  // namespace camdyn
