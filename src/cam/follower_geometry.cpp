// camdyn — exact contact kinematics of translating followers (see follower_geometry.hpp).
#include "cam/follower_geometry.hpp"

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
constexpr double kDeg = kPi / 180.0;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A value and its first three derivatives in θ.
struct Jet {
  double v = 0, d1 = 0, d2 = 0, d3 = 0;
};
Jet operator+(Jet a, Jet b) { return {a.v + b.v, a.d1 + b.d1, a.d2 + b.d2, a.d3 + b.d3}; }
Jet operator-(Jet a, Jet b) { return {a.v - b.v, a.d1 - b.d1, a.d2 - b.d2, a.d3 - b.d3}; }
Jet operator*(Jet a, Jet b) {
  return {a.v * b.v, a.d1 * b.v + a.v * b.d1, a.d2 * b.v + 2 * a.d1 * b.d1 + a.v * b.d2,
          a.d3 * b.v + 3 * a.d2 * b.d1 + 3 * a.d1 * b.d2 + a.v * b.d3};
}
Jet constant(double c) { return {c, 0, 0, 0}; }
void set_motion(FollowerState& f, const Jet& X) {
  f.s = X.v;
  f.s1 = X.d1;
  f.s2 = X.d2;
  f.s3 = X.d3;
}
/// f∘g with f, f′, f″, f‴ at g.v (Faà di Bruno to third order).
Jet compose(Jet g, double f0, double f1, double f2, double f3) {
  return {f0, f1 * g.d1, f2 * g.d1 * g.d1 + f1 * g.d2,
          f3 * g.d1 * g.d1 * g.d1 + 3 * f2 * g.d1 * g.d2 + f1 * g.d3};
}
Jet jsqrt(Jet g) {
  const double r = std::sqrt(g.v);
  return compose(g, r, 0.5 / r, -0.25 / (r * g.v), 0.375 / (r * g.v * g.v));
}

/// Angle a reduced into [lo, lo + 2π).
double reduce(double a, double lo) {
  double u = std::fmod(a - lo, kTwoPi);
  if (u < 0) u += kTwoPi;
  return lo + u;
}

std::string deg1(double rad) {
  char b[32];
  double d = std::fmod(rad / kDeg, 360.0);
  if (d < 0) d += 360.0;
  std::snprintf(b, sizeof b, "%.1f°", d >= 359.95 ? 0.0 : d);
  return b;
}

[[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& rule) {
  throw SceneError("<cam>", 0, key, value, rule);
}

/// The angle runs an error message lists (the rest counted: "… and 794 more").
constexpr int kListedRuns = 6;

/// "a..b, c..d" from a sampled predicate over [0, 2π).
template <class Bad>
std::string angle_runs(Bad bad, int n) {
  std::string out;
  int k = 0, runs = 0;
  while (k < n) {
    if (!bad(k)) {
      ++k;
      continue;
    }
    const int k0 = k;
    while (k < n && bad(k)) ++k;
    if (++runs > kListedRuns) continue;
    if (!out.empty()) out += ", ";
    out += deg1(kTwoPi * k0 / n) + ".." + deg1(kTwoPi * (k - 1) / n);
  }
  if (runs > kListedRuns) out += " and " + std::to_string(runs - kListedRuns) + " more";
  return out;
}

constexpr int kScan = 7200;

}  // namespace

std::vector<Arc> make_arcs(const CamSpec& c) {
  if (c.profile == CamProfileKind::Circle) return {{c.eccentricity, 0.0, c.radius, -kPi, kPi}};
  const double Rb = c.base_radius, rn = c.nose_radius, d = c.nose_distance, Rf = c.flank_radius;
  for (auto [k, v] : {std::pair<const char*, double>{"cam.base_radius", Rb}, {"cam.nose_radius", rn},
                      {"cam.nose_distance", d}, {"cam.flank_radius", Rf}})
    if (!(std::isfinite(v) && v > 0)) fail(k, fmt_num(v), "must be finite and > 0");
  if (!(rn < Rb)) fail("cam.nose_radius", fmt_num(rn), "must be < cam.base_radius = " + fmt_num(Rb));
  if (!(d + rn > Rb))
    fail("cam.nose_distance", fmt_num(d),
         "the nose must stand out of the base circle: nose_distance + nose_radius > base_radius = " + fmt_num(Rb));
  if (!(Rf > Rb)) fail("cam.flank_radius", fmt_num(Rf), "must be > cam.base_radius = " + fmt_num(Rb));
  // Flank centre F = (fx, ∓fy): |F| = R_f − R_b, |F − N| = R_f − r_n (internal tangency).
  const double a = Rf - Rb, b = Rf - rn;
  if (!(d < a + b))
    fail("cam.flank_radius", fmt_num(Rf),
         "too small to join the base and nose arcs: need 2·flank_radius > nose_distance + base_radius + nose_radius = " +
             fmt_num(d + Rb + rn));
  const double fx = (d * d - b * b + a * a) / (2 * d);
  const double fy2 = a * a - fx * fx;
  if (!(fy2 > 0)) fail("cam.flank_radius", fmt_num(Rf), "the flank arcs cannot be tangent to both circles");
  const double fy = std::sqrt(fy2);
  const double gn = std::atan2(fy, d - fx);  // nose/upper-flank tangency normal angle
  const double gb = std::atan2(fy, -fx);     // upper-flank/base tangency normal angle
  if (!(gn > 0 && gb > gn && gb < kPi))
    fail("cam.flank_radius", fmt_num(Rf), "the arcs do not form a convex cam (flank tangency out of order)");
  return {{d, 0.0, rn, -gn, gn},
          {fx, -fy, Rf, gn, gb},
          {0.0, 0.0, Rb, gb, kTwoPi - gb},
          {fx, fy, Rf, kTwoPi - gb, kTwoPi - gn}};
}

TranslatingGeometry::TranslatingGeometry(const CamSpec& spec)
    : kind_(geometry_kind(spec.profile)), face_(spec.follower_face), eps_(spec.follower_offset), rr_(spec.roller_radius),
      rb_(spec.base_radius) {
  if (!std::isfinite(eps_)) fail("cam.follower_offset", fmt_num(eps_), "must be finite");
  if (face_ == FollowerFace::Roller && !(std::isfinite(rr_) && rr_ > 0))
    fail("cam.roller_radius", fmt_num(rr_), "must be > 0 for cam.follower_face = \"roller\"");
  if (face_ != FollowerFace::Roller) rr_ = 0.0;
  if ((face_ == FollowerFace::Flat || face_ == FollowerFace::Point) && eps_ != 0.0)
    fail("cam.follower_offset", fmt_num(eps_),
         "applies to knife_edge and roller followers only (a flat face's offset does not change its motion)");
  if (kind_ == CamProfileKind::Law) {
    law_ = law_of(spec);
    for (const Breakpoint& b : law_->breakpoints()) breaks_.push_back(b.theta);
    if (face_ != FollowerFace::Point) {
      if (!(std::isfinite(rb_) && rb_ > 0)) fail("cam.base_radius", fmt_num(rb_), "must be > 0");
      if (!(rb_ + law_->min_lift() > 0))
        fail("cam.base_radius", fmt_num(rb_), "base_radius + L must stay > 0 (the law reaches " +
                                                  fmt_num(law_->min_lift()) + ")");
      const double Rp = rb_ + rr_;
      if (!(std::fabs(eps_) < Rp))
        fail("cam.follower_offset", fmt_num(eps_),
             "must be smaller in magnitude than the prime circle radius base_radius + roller_radius = " + fmt_num(Rp));
      d_ = std::sqrt(Rp * Rp - eps_ * eps_);
      if (!(d_ + law_->min_lift() > 0))
        fail("cam.follower_offset", fmt_num(eps_),
             "the follower's contact point would pass behind the cam centre: √((base_radius + roller_radius)² − offset²) + min L = " +
                 fmt_num(d_ + law_->min_lift()) + " must be > 0");
      check_law_profile(spec);
    }
  } else if (kind_ == CamProfileKind::Circle || kind_ == CamProfileKind::Arc || kind_ == CamProfileKind::Arcs) {
    if (face_ == FollowerFace::Point)
      fail("cam.follower_face", "\"point\"", "is for cam.profile = \"law\" only (a profile needs a follower face)");
    arcs_ = kind_ == CamProfileKind::Arcs ? make_arc_list(spec) : make_arcs(spec);
    if (face_ != FollowerFace::Flat) {
      // The axis must cut every pitch circle from the cam centre's side: |ε| below the
      // smallest distance of the pitch curve from O (base circle + roller, or R − e + R_r).
      double rmin = kTwoPi * 1e9;
      for (int k = 0; k < kScan; ++k) {
        const double a = kTwoPi * k / kScan;
        const auto p = profile_point(a);
        if (kind_ == CamProfileKind::Arcs) {  // the pitch curve: the offset arcs (corners: a circle R_r)
          rmin = std::min(rmin, std::hypot(p[0], p[1]) - rr_);  // a bound: |pitch| ≥ |profile| − R_r
          continue;
        }
        rmin = std::min(rmin, std::hypot(p[0], p[1]));
      }
      if (!(std::fabs(eps_) < rmin + rr_))
        fail("cam.follower_offset", fmt_num(eps_),
             "must be smaller in magnitude than the smallest pitch radius " + fmt_num(rmin + rr_));
    }
    if (arcs_.size() > 1) breaks_ = arc_switches([this](double th) { return select_arc(th); }, kScan);
    // Each switch's continuity from the two arcs' closed forms at the switch angle.
    for (double b : breaks_) {
      const int l = select_arc(b - 1e-9), r = select_arc(b + 1e-9);
      const FollowerState L = on_arc(arcs_[l], l, b), R = on_arc(arcs_[r], r, b);
      Breakpoint j;
      j.theta = b;
      j.jump = {R.s - L.s, R.s1 - L.s1, R.s2 - L.s2, R.s3 - L.s3};
      const double tol = 1e-9 * std::max(1.0, std::fabs(L.s));
      j.order = 3;
      for (int k = 3; k >= 1; --k)
        if (std::fabs(j.jump[k]) > tol) j.order = k - 1;
      joints_.push_back(j);
    }
  } else {
    fail("cam.follower_face", to_string(face_),
         std::string("cam.profile = \"") + to_string(kind_) +
             "\" takes a flat face only; knife_edge, roller and point need profile law, circle or arc");
  }
  smin_ = INFINITY;
  smax_ = -INFINITY;
  min_rho_ = INFINITY;
  for (int k = 0; k < kScan; ++k) {
    const FollowerState f = eval(kTwoPi * k / kScan);
    smin_ = std::min(smin_, f.s);
    smax_ = std::max(smax_, f.s);
    if (f.rho > 0) min_rho_ = std::min(min_rho_, f.rho);  // convex parts (concave: ρ < 0)
  }
  for (double b : breaks_) {
    for (double th : {b - 1e-9, b + 1e-9}) {
      const FollowerState f = eval(th);
      if (f.rho > 0) min_rho_ = std::min(min_rho_, f.rho);
    }
  }
  if (!std::isfinite(min_rho_)) min_rho_ = kNaN;
}

void TranslatingGeometry::check_law_profile(const CamSpec& spec) {
  std::vector<double> rho(kScan), rhop(kScan);
  for (int k = 0; k < kScan; ++k) {
    const FollowerState f = eval_law(kTwoPi * k / kScan);
    rho[k] = f.rho;
    rhop[k] = f.rho + rr_;
  }
  if (face_ == FollowerFace::Flat) {
    const std::string bad = angle_runs([&](int k) { return !(rho[k] > 0); }, kScan);
    if (!bad.empty())
      fail("cam.base_radius", fmt_num(spec.base_radius),
           "profile is not convex: radius of curvature ρ = r_b + L + L″ ≤ 0 at cam angles " + bad +
               " — a flat-faced follower cannot follow a concave flank; a larger cam.base_radius, "
               "or cam.follower_face = \"roller\" / \"point\"");
  } else if (face_ == FollowerFace::Roller) {
    const std::string bad = angle_runs([&](int k) { return rhop[k] > 0 && !(rhop[k] > rr_); }, kScan);
    if (!bad.empty())
      fail("cam.roller_radius", fmt_num(rr_),
           "the cam is undercut: the pitch curve's radius of curvature is below the roller radius at cam angles " +
               bad + " — a smaller roller or a larger cam.base_radius");
  }
}

FollowerState TranslatingGeometry::eval(double theta) const {
  return kind_ == CamProfileKind::Law ? eval_law(theta) : eval_arcs(theta);
}

FollowerState TranslatingGeometry::eval_law(double theta) const {
  const LiftDerivs L = law_->eval(theta);
  FollowerState f;
  if (face_ == FollowerFace::Point) {
    f.s = L.L;
    f.s1 = L.L1;
    f.s2 = L.L2;
    f.s3 = L.L3;
    f.rho = f.cx = f.cy = kNaN;
    return f;
  }
  if (face_ == FollowerFace::Flat) {
    f.s = rb_ + L.L;
    f.s1 = L.L1;
    f.s2 = L.L2;
    f.s3 = L.L3;
    f.rho = f.s + f.s2;
    f.cx = f.s;
    f.cy = -f.s1;
    return f;
  }
  const double x = d_ + L.L, x1 = L.L1, x2 = L.L2;
  f.s = x;
  f.s1 = x1;
  f.s2 = x2;
  f.s3 = L.L3;
  const double tx = x1 + eps_, ty = -x;          // c′ (pitch curve, fixed frame)
  const double ux = x2 - x, uy = -2 * x1 - eps_;  // c″
  const double nt = std::hypot(tx, ty);
  const double cross = tx * uy - ty * ux;
  const double rho_p = -nt * nt * nt / cross;
  f.rho = rho_p - rr_;
  f.phi = std::atan2(x1 + eps_, x);
  const double nx = x / nt, ny = (x1 + eps_) / nt;
  f.cx = x - rr_ * nx;
  f.cy = eps_ - rr_ * ny;
  return f;
}

FollowerState TranslatingGeometry::on_arc(const Arc& a, int i, double theta) const {
  const double c = std::cos(theta), s = std::sin(theta);
  // Arc centre in the fixed frame as a jet in θ.
  const Jet cX{a.cx * c - a.cy * s, -a.cx * s - a.cy * c, -a.cx * c + a.cy * s, a.cx * s + a.cy * c};
  const Jet cY{a.cx * s + a.cy * c, a.cx * c - a.cy * s, -a.cx * s - a.cy * c, -a.cx * c + a.cy * s};
  FollowerState f;
  f.arc = i;
  f.rho = a.R;
  if (face_ == FollowerFace::Flat) {
    const Jet X = cX + constant(a.R);
    set_motion(f, X);
    f.cx = X.v;
    f.cy = cY.v;
    return f;
  }
  // Pitch circle of signed radius A (< 0: a concave arc, whose contact faces +X with the
  // point on the far side of its centre): s = c_X + sgn(A) √(A² − q²).
  const double A = a.R + rr_, sg = A < 0 ? -1.0 : 1.0;
  const Jet q = constant(eps_) - cY;
  const Jet root = jsqrt(constant(A * A) - q * q);
  set_motion(f, cX + Jet{sg * root.v, sg * root.d1, sg * root.d2, sg * root.d3});
  f.phi = std::atan2(sg * q.v, root.v);
  f.cx = cX.v + a.R * std::cos(f.phi);
  f.cy = cY.v + a.R * std::sin(f.phi);
  return f;
}

int TranslatingGeometry::select_arc(double theta) const {
  if (arcs_.size() == 1) return 0;
  if (face_ == FollowerFace::Flat) {
    for (std::size_t i = 0; i < arcs_.size(); ++i) {
      const double t = reduce(-theta, arcs_[i].n0);
      if (t < arcs_[i].n1) return int(i);
    }
    return 0;
  }
  const double c = std::cos(theta), s = std::sin(theta);
  int best = -1;
  double bestX = -INFINITY, bestMiss = INFINITY;
  int near = 0;
  for (std::size_t i = 0; i < arcs_.size(); ++i) {
    const Arc& a = arcs_[i];
    const double cX = a.cx * c - a.cy * s, cY = a.cx * s + a.cy * c;
    const double A = a.R + rr_, q = eps_ - cY, disc = A * A - q * q;
    if (!(disc >= 0) || A == 0.0) continue;  // A = 0: a knife edge meets a corner at one instant only
    const double sg = A < 0 ? -1.0 : 1.0;
    const double X = cX + sg * std::sqrt(disc);
    const double n = std::atan2(sg * q, std::sqrt(disc)) - theta;  // cam-frame normal angle
    const double t = reduce(n, a.n0);
    const double miss = t <= a.n1 ? 0.0 : std::min(t - a.n1, a.n0 + kTwoPi - t);
    if (miss == 0.0 && X > bestX) {
      bestX = X;
      best = int(i);
    }
    if (miss < bestMiss) {
      bestMiss = miss;
      near = int(i);
    }
  }
  return best >= 0 ? best : near;
}

FollowerState TranslatingGeometry::eval_arcs(double theta) const {
  const int i = select_arc(theta);
  return on_arc(arcs_[i], i, theta);
}

std::array<double, 2> TranslatingGeometry::profile_point(double a) const {
  if (kind_ == CamProfileKind::Law) {
    const FollowerState f = eval_law(a);
    if (std::isnan(f.cx)) return {kNaN, kNaN};
    const double c = std::cos(a), s = std::sin(a);  // fixed → cam frame: rotate by −a
    return {f.cx * c + f.cy * s, -f.cx * s + f.cy * c};
  }
  if (kind_ == CamProfileKind::Arcs) return arc_chain_point(arcs_, a);
  return arc_profile_point(arcs_, a);
}

std::array<double, 2> arc_profile_point(const std::vector<Arc>& arcs, double a) {
  for (const Arc& arc : arcs) {
    const double t = reduce(a, arc.n0);
    if (t <= arc.n1) return {arc.cx + arc.R * std::cos(t), arc.cy + arc.R * std::sin(t)};
  }
  const Arc& arc = arcs.front();
  return {arc.cx + arc.R * std::cos(a), arc.cy + arc.R * std::sin(a)};
}

std::vector<double> arc_switches(const std::function<int(double)>& select, int n) {
  std::vector<double> out;
  int prev = select(0.0);
  for (int k = 1; k <= n; ++k) {
    const double th = kTwoPi * k / n;
    const int cur = select(th);
    if (cur != prev) {
      double lo = kTwoPi * (k - 1) / n, hi = th;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (select(mid) == prev ? lo : hi) = mid;
      }
      out.push_back(std::fmod(0.5 * (lo + hi), kTwoPi));
    }
    prev = cur;
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace detail
}  // namespace camdyn
