// camdyn — arc cams as a list (cam.profile = "arcs", docs/cam_laws.md "Arc cams as a list"):
// the arcs of cam.arc_*, checked to form one closed chain, as the Arc records the
// translating and oscillating geometries evaluate in closed form.
//
//   Arc i: centre c_i, signed radius R_i, its points c_i + |R_i| (cos ψ, sin ψ) for ψ from
//   arc_from_deg to arc_to_deg (ψ increasing on a convex arc, decreasing on a concave one,
//   so that the chain runs counter-clockwise round the cam). Outward normal angle n = ψ on
//   a convex arc, ψ + π on a concave one; an Arc stores [n0, n1] increasing.
//   Joint i → i+1: the end of arc i must be the start of arc i+1 (gap ≤ 1e-9 of the cam's
//   size); the normal's turn there δ = n_start(i+1) − n_end(i) (mod 2π, in (−π, π]) is 0 at a
//   tangent joint, > 0 at a convex corner (a corner arc R = 0 over [n_end, n_end + δ] is
//   inserted: a flat face pivots on the corner, a roller rolls round it), < 0 at a concave
//   corner. The normal turns once round in total: Σ ±(arc spans) + Σ δ = 2π.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cam/follower_geometry.hpp"
#include "cam/format.hpp"

namespace camdyn {
namespace detail {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kDeg = kPi / 180.0;

[[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& rule) {
  throw SceneError("<cam>", 0, key, value, rule);
}

std::string deg(double rad) { return fmt_num(std::round(rad / kDeg * 1e9) / 1e9) + "°"; }

std::string elem(const char* key, std::size_t i) { return std::string(key) + "[" + std::to_string(i) + "]"; }

}  // namespace

std::vector<Arc> make_arc_list(const CamSpec& c) {
  const std::size_t n = c.arc_radius.size();
  if (n == 0) fail("cam.arc_radius", fmt_list(c.arc_radius), "cam.profile = \"arcs\" needs at least one arc");
  const bool cart = !c.arc_centre_x.empty() || !c.arc_centre_y.empty();
  const bool polar = !c.arc_centre_r.empty() || !c.arc_centre_deg.empty();
  if (cart == polar)
    fail("cam.arc_centre_x", fmt_list(c.arc_centre_x),
         "give the arc centres either as cam.arc_centre_x/cam.arc_centre_y or as cam.arc_centre_r/cam.arc_centre_deg "
         "(exactly one of the two pairs)");
  auto same = [&](const char* key, const std::vector<double>& v) {
    if (v.size() != n)
      fail(key, fmt_list(v),
           "must have one entry per arc, as many as cam.arc_radius (" + std::to_string(n) + "), got " +
               std::to_string(v.size()));
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(v[i])) fail(elem(key, i), fmt_num(v[i]), "must be finite");
  };
  same("cam.arc_radius", c.arc_radius);
  same("cam.arc_from_deg", c.arc_from_deg);
  same("cam.arc_to_deg", c.arc_to_deg);
  std::vector<double> cx(n), cy(n);
  if (cart) {
    same("cam.arc_centre_x", c.arc_centre_x);
    same("cam.arc_centre_y", c.arc_centre_y);
    cx = c.arc_centre_x;
    cy = c.arc_centre_y;
  } else {
    same("cam.arc_centre_r", c.arc_centre_r);
    same("cam.arc_centre_deg", c.arc_centre_deg);
    for (std::size_t i = 0; i < n; ++i) {
      if (!(c.arc_centre_r[i] >= 0)) fail(elem("cam.arc_centre_r", i), fmt_num(c.arc_centre_r[i]), "must be >= 0");
      cx[i] = c.arc_centre_r[i] * std::cos(c.arc_centre_deg[i] * kDeg);
      cy[i] = c.arc_centre_r[i] * std::sin(c.arc_centre_deg[i] * kDeg);
    }
  }
  const FollowerFace face = c.follower_face;
  const double rr = face == FollowerFace::Roller ? c.roller_radius : 0.0;
  double scale = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double R = c.arc_radius[i], span = c.arc_to_deg[i] - c.arc_from_deg[i];
    if (R == 0) fail(elem("cam.arc_radius", i), "0", "must be > 0 (convex) or < 0 (concave); a corner needs no arc");
    if (R > 0 && !(span > 0 && span <= 360))
      fail(elem("cam.arc_to_deg", i), fmt_num(c.arc_to_deg[i]),
           "arc " + std::to_string(i) + " is convex (radius > 0): must exceed cam.arc_from_deg[" + std::to_string(i) +
               "] = " + fmt_num(c.arc_from_deg[i]) + " by at most 360 (the chain runs counter-clockwise)");
    if (R < 0 && !(span < 0 && span >= -360))
      fail(elem("cam.arc_to_deg", i), fmt_num(c.arc_to_deg[i]),
           "arc " + std::to_string(i) + " is concave (radius < 0): must be below cam.arc_from_deg[" +
               std::to_string(i) + "] = " + fmt_num(c.arc_from_deg[i]) + " by at most 360");
    if (R < 0 && face == FollowerFace::Flat)
      fail(elem("cam.arc_radius", i), fmt_num(R),
           "arc " + std::to_string(i) + " is concave (cam angles " + deg(-(c.arc_from_deg[i] * kDeg + kPi)) + ".." +
               deg(-(c.arc_to_deg[i] * kDeg + kPi)) +
               ") — a flat-faced follower cannot follow a concave stretch; cam.follower_face = \"knife_edge\" or "
               "\"roller\"");
    if (R < 0 && face == FollowerFace::Roller && !(-R > rr))
      fail("cam.roller_radius", fmt_num(rr),
           "the roller does not fit the concave arc " + std::to_string(i) + " (radius " + fmt_num(-R) +
               "): the roller radius must be smaller");
    scale = std::max(scale, std::hypot(cx[i], cy[i]) + std::fabs(R));
  }
  auto point = [&](std::size_t i, double psi_deg) {
    const double R = std::fabs(c.arc_radius[i]), a = psi_deg * kDeg;
    return std::array<double, 2>{cx[i] + R * std::cos(a), cy[i] + R * std::sin(a)};
  };
  auto normal = [&](std::size_t i, double psi_deg) { return psi_deg * kDeg + (c.arc_radius[i] < 0 ? kPi : 0.0); };
  std::vector<Arc> out;
  double turn = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double R = c.arc_radius[i];
    const double na = normal(i, c.arc_from_deg[i]), nb = normal(i, c.arc_to_deg[i]);
    Arc a{cx[i], cy[i], R, std::min(na, nb), std::max(na, nb)};
    a.drawn = int(i);
    out.push_back(a);
    turn += nb - na;
    const std::size_t j = (i + 1) % n;
    const auto E = point(i, c.arc_to_deg[i]), S = point(j, c.arc_from_deg[j]);
    const double gap = std::hypot(S[0] - E[0], S[1] - E[1]);
    const std::string joint = "joint " + std::to_string(i) + "→" + std::to_string(j);
    if (!(gap <= 1e-9 * scale))
      fail(elem("cam.arc_from_deg", j), fmt_num(c.arc_from_deg[j]),
           "the arcs do not meet at " + joint + ": arc " + std::to_string(i) + " ends at (" + fmt_num(E[0]) + ", " +
               fmt_num(E[1]) + "), arc " + std::to_string(j) + " starts at (" + fmt_num(S[0]) + ", " + fmt_num(S[1]) +
               "), " + fmt_num(gap) + " apart (allowed 1e-9 of the cam's size " + fmt_num(scale) +
               "; give the angles to full precision)");
    const double d = std::remainder(normal(j, c.arc_from_deg[j]) - nb, kTwoPi);
    if (std::fabs(d) <= 1e-9) {
      turn += d;
      continue;
    }
    turn += d;
    if (d < 0 && face != FollowerFace::KnifeEdge)
      fail(elem("cam.arc_from_deg", j), fmt_num(c.arc_from_deg[j]),
           joint + " is a concave corner (the tangent turns back by " + deg(-d) + ", at cam angle " + deg(-nb) +
               ") — only a knife edge can follow it (a " + to_string(face) +
               " face cannot enter it); make the arcs tangent there");
    if (d > 0) {
      Arc k{E[0], E[1], 0.0, nb, nb + d};
      out.push_back(k);
    }
  }
  if (!(std::fabs(turn - kTwoPi) <= 1e-9))
    fail("cam.arc_to_deg", fmt_list(c.arc_to_deg),
         "the arcs' tangent turns by " + deg(turn) +
             " in total; one closed chain run counter-clockwise round the cam turns by 360°");
  // Normal ranges reduced to start in [0, 2π); plot parameter by arc length (a corner gets
  // a share as if its radius were 1e-3 of the cam's size).
  double total = 0;
  for (Arc& a : out) {
    const double sh = std::floor(a.n0 / kTwoPi) * kTwoPi;
    a.n0 -= sh;
    a.n1 -= sh;
    total += (a.R == 0 ? 1e-3 * scale : std::fabs(a.R)) * (a.n1 - a.n0);
  }
  double u = 0;
  for (Arc& a : out) {
    a.u0 = u;
    u += (a.R == 0 ? 1e-3 * scale : std::fabs(a.R)) * (a.n1 - a.n0) / total;
    a.u1 = u;
  }
  return out;
}

std::array<double, 2> arc_chain_point(const std::vector<Arc>& arcs, double a) {
  double u = std::fmod(a / kTwoPi, 1.0);
  if (u < 0) u += 1.0;
  for (const Arc& arc : arcs) {
    if (u > arc.u1 && &arc != &arcs.back()) continue;
    const double f = arc.u1 > arc.u0 ? std::clamp((u - arc.u0) / (arc.u1 - arc.u0), 0.0, 1.0) : 0.0;
    // Along the chain: a convex arc's normal increases, a concave arc's decreases.
    const double n = arc.R >= 0 ? arc.n0 + f * (arc.n1 - arc.n0) : arc.n1 - f * (arc.n1 - arc.n0);
    return {arc.cx + arc.R * std::cos(n), arc.cy + arc.R * std::sin(n)};
  }
  return {arcs.front().cx, arcs.front().cy};
}

}  // namespace detail
}  // namespace camdyn
