// camdyn — cam profiles: construction and validation of the points, circle and lift
// profiles, and the contact-point search of the points profile (docs/method.md §2).
// Split from cam.cpp; the profile data is Cam::Impl (cam_impl.hpp).
//
// Profiles
//   points — periodic cubic splines x(α), y(α) (period 2π) through the knots
//            (r_i cos α_i, r_i sin α_i). The contact point at cam angle θ is the global
//            maximum over α of X(α, θ) = x cos θ − y sin θ: the profile point whose
//            cam-frame outward normal points at angle −θ. The normal angle φ(α) is
//            tabulated densely at construction (monotone for a convex profile); a call
//            inverts the table (hint from the previous call, else binary search) and
//            polishes α by safeguarded Newton on X_α(α) = 0.
//   circle — closed form.
//   lift   — support function h(θ) = r_b + L(θ), L a periodic cubic spline in θ.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cam/format.hpp"
#include "cam/impl.hpp"
#include "cam/spline.hpp"

namespace camdyn {

using namespace cam_detail;  // cam_impl.hpp

namespace {

std::string fmt_deg1(double deg) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f°", deg);
  return buf;
}

/// Angle in degrees wrapped into [0, 360).
double wrap360(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w < 0) w += 360.0;
  if (!(w < 360.0)) w = 0.0;
  // Avoid printing "360.0°" or "-0.0°" after rounding to one decimal.
  if (w >= 359.95) w = 0.0;
  return w;
}

/// The angle a − 2πk closest to the reference ref.
double unwrap_near(double a, double ref) {
  return a - kTwoPi * std::round((a - ref) / kTwoPi);
}

/// Checks shared by the two knot tables (points: angles_deg/radii; lift: lift_angles_deg/lift).
void check_knot_angles(const std::vector<double>& ang, const std::string& key) {
  if (!all_finite(ang)) fail(key, fmt_list(ang), "every angle must be finite (no nan/inf)");
  if (ang.size() < 4)
    fail(key, fmt_list(ang),
         "a periodic cubic spline needs at least 4 knots (got " + std::to_string(ang.size()) +
             ")");
  for (std::size_t i = 1; i < ang.size(); ++i)
    if (!(ang[i] > ang[i - 1]))
      fail(key, fmt_list(ang),
           "angles must be strictly increasing (entry " + std::to_string(i) + " = " +
               fmt_num(ang[i]) + " does not exceed entry " + std::to_string(i - 1) + " = " +
               fmt_num(ang[i - 1]) + ")");
  if (!(ang.back() - ang.front() < 360.0))
    fail(key, fmt_list(ang),
         "angles must span less than 360° (last − first = " +
             fmt_num(ang.back() - ang.front()) + "°)");
}

/// Golden-section minimum of f on [a, b].
template <class F>
std::pair<double, double> golden_min(F&& f, double a, double b, int iters = 80) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < iters && (b - a) > 1e-15 * (1.0 + std::fabs(a)); ++i) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    }
  }
  return fc < fd ? std::make_pair(c, fc) : std::make_pair(d, fd);
}

/// Minimum of f over a periodic grid of n samples on [t0, t0 + period), refined by golden
/// section around the best sample.
template <class F>
double periodic_min(F&& f, double t0, double period, std::size_t n) {
  std::size_t best = 0;
  double fbest = std::numeric_limits<double>::infinity();
  const double dt = period / static_cast<double>(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double v = f(t0 + dt * static_cast<double>(k));
    if (v < fbest) {
      fbest = v;
      best = k;
    }
  }
  const double tb = t0 + dt * static_cast<double>(best);
  const auto r = golden_min(f, tb - dt, tb + dt);
  return std::min(fbest, r.second);
}

}  // namespace

// ---- points ---------------------------------------------------------------------------
void Cam::Impl::build_points(const CamSpec& spec) {
  const auto& ang = spec.angles_deg;
  const auto& rad = spec.radii;
  check_knot_angles(ang, "cam.angles_deg");
  if (!all_finite(rad)) fail("cam.radii", fmt_list(rad), "every radius must be finite (no nan/inf)");
  if (rad.size() != ang.size())
    fail("cam.radii", fmt_list(rad),
         "must have as many entries as cam.angles_deg (" + std::to_string(ang.size()) +
             "), got " + std::to_string(rad.size()));
  for (std::size_t i = 0; i < rad.size(); ++i)
    if (!(rad[i] > 0))
      fail("cam.radii", fmt_list(rad),
           "every radius must be > 0 (entry " + std::to_string(i) + " = " + fmt_num(rad[i]) +
               ")");

  const std::size_t n = ang.size();
  std::vector<double> a(n), x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) {
    a[i] = ang[i] * kDeg;
    x[i] = rad[i] * std::cos(a[i]);
    y[i] = rad[i] * std::sin(a[i]);
  }
  sx = detail::PeriodicSpline(a, x, kTwoPi);
  sy = detail::PeriodicSpline(a, y, kTwoPi);

  const std::size_t N = std::max<std::size_t>(4096, 64 * n);
  const double da = kTwoPi / static_cast<double>(N);
  std::vector<Derivs> D(N + 1);
  tab_alpha.resize(N + 1);
  for (std::size_t k = 0; k <= N; ++k) {
    tab_alpha[k] = a[0] + da * static_cast<double>(k);
    D[k] = derivs(k == N ? a[0] : tab_alpha[k]);
  }
  const std::string radii_s = fmt_list(rad);

  // (1) Regular curve: no zero tangent.
  for (std::size_t k = 0; k < N; ++k)
    if (!(std::hypot(D[k].x1, D[k].y1) > 0))
      fail("cam.radii", radii_s,
           "profile has a cusp (zero tangent) at polar angle " +
               fmt_deg1(wrap360(std::atan2(D[k].y, D[k].x) / kDeg)));

  // (2) Star-shaped about O: polar angle strictly increasing, one turn in total.
  {
    double total = 0;
    for (std::size_t k = 0; k < N; ++k) {
      const auto& d = D[k];
      const double rate = d.x * d.y1 - d.y * d.x1;  // r² dψ/dα
      if (!(rate > 0))
        fail("cam.radii", radii_s,
             "profile is self-intersecting or does not enclose the cam centre: its polar "
             "angle is not monotone (it turns back near polar angle " +
                 fmt_deg1(wrap360(std::atan2(d.y, d.x) / kDeg)) + ")");
      const double p0 = std::atan2(D[k].y, D[k].x), p1 = std::atan2(D[k + 1].y, D[k + 1].x);
      total += unwrap_near(p1 - p0, 0.0);
    }
    if (std::fabs(total - kTwoPi) > 1e-6)
      fail("cam.radii", radii_s,
           "profile is self-intersecting: its polar angle turns by " +
               fmt_num(total / kDeg) + "° (must be 360°)");
  }

  // (3) Convex: x′y″ − y′x″ > 0 everywhere (ρ > 0). Report each run where it fails, as
  //     cam angles θ (the cam angle at which that profile point would face the follower,
  //     i.e. its outward normal points along +X: θ = −φ) and as polar angles α.
  auto phi_of = [](const Derivs& d) { return std::atan2(-d.x1, d.y1); };
  {
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (std::size_t k = 0; k < N; ++k) {
      const bool bad = !(D[k].x1 * D[k].y2 - D[k].y1 * D[k].x2 > 0);
      if (!bad) continue;
      if (!runs.empty() && runs.back().second + 1 == k)
        runs.back().second = k;
      else
        runs.emplace_back(k, k);
    }
    // Merge a run that wraps around α = α_0.
    if (runs.size() > 1 && runs.front().first == 0 && runs.back().second == N - 1) {
      runs.front().first = runs.back().first;
      runs.pop_back();
    }
    if (!runs.empty()) {
      std::string th, al;
      for (std::size_t j = 0; j < runs.size(); ++j) {
        const auto [k0, k1] = runs[j];
        const std::size_t len = (k1 >= k0 ? k1 - k0 : k1 + N - k0) + 1;
        // cam angle θ = −φ along the run, unwrapped
        double ref = -phi_of(D[k0]), tmin = ref, tmax = ref;
        double pref = std::atan2(D[k0].y, D[k0].x), pmin = pref, pmax = pref;
        for (std::size_t i = 0; i < len; ++i) {
          const auto& d = D[(k0 + i) % N];
          const double t = unwrap_near(-phi_of(d), ref);
          ref = t;
          tmin = std::min(tmin, t);
          tmax = std::max(tmax, t);
          const double p = unwrap_near(std::atan2(d.y, d.x), pref);
          pref = p;
          pmin = std::min(pmin, p);
          pmax = std::max(pmax, p);
        }
        if (j) {
          th += ", ";
          al += ", ";
        }
        const double t0 = wrap360(tmin / kDeg), p0 = wrap360(pmin / kDeg);
        th += fmt_deg1(t0) + ".." + fmt_deg1(wrap360(t0 + (tmax - tmin) / kDeg));
        al += fmt_deg1(p0) + ".." + fmt_deg1(wrap360(p0 + (pmax - pmin) / kDeg));
      }
      fail("cam.radii", radii_s,
           "profile is not convex: radius of curvature ρ ≤ 0 at cam angles " + th +
               " (the cam angle θ at which that profile point would face the follower; "
               "profile polar angles " +
               al + ") — a flat-faced follower cannot follow a concave flank");
    }
  }

  // (4) Normal-angle table; total turning of the tangent must be exactly one turn.
  tab_phi.resize(N + 1);
  tab_phi[0] = phi_of(D[0]);
  for (std::size_t k = 1; k <= N; ++k) tab_phi[k] = unwrap_near(phi_of(D[k]), tab_phi[k - 1]);
  for (std::size_t k = 1; k <= N; ++k)
    if (!(tab_phi[k] > tab_phi[k - 1]))
      fail("cam.radii", radii_s,
           "profile is not convex: its tangent turns back near polar angle " +
               fmt_deg1(wrap360(std::atan2(D[k].y, D[k].x) / kDeg)));
  if (std::fabs(tab_phi[N] - tab_phi[0] - kTwoPi) > 1e-6)
    fail("cam.radii", radii_s,
         "profile is self-intersecting: the tangent turns by " +
             fmt_num((tab_phi[N] - tab_phi[0]) / kDeg) + "° in one loop (must be 360°)");
  tab_phi[N] = tab_phi[0] + kTwoPi;

  // (5) Derived quantities.
  auto rho_at = [this](double al) {
    const Derivs d = derivs(al);
    const double s2 = d.x1 * d.x1 + d.y1 * d.y1;
    return s2 * std::sqrt(s2) / (d.x1 * d.y2 - d.y1 * d.x2);
  };
  min_rho = periodic_min(rho_at, a[0], kTwoPi, N);
  // max_θ h = max_α r(α); min_θ h by sampling the support function.
  auto neg_r = [this](double al) {
    const Derivs d = derivs(al);
    return -std::hypot(d.x, d.y);
  };
  const double hmax = -periodic_min(neg_r, a[0], kTwoPi, N);
  auto h_at = [this](double th) { return evaluate(th).X_C; };
  const double hmin = periodic_min(h_at, 0.0, kTwoPi, N);
  lift = hmax - hmin;
  hint.set(0);
}

double Cam::Impl::contact_alpha(double theta, double ct, double st, Derivs* out) const {
  const std::size_t N = tab_phi.size() - 1;
  // Target normal angle −θ, reduced into [φ_0, φ_0 + 2π).
  double u = std::fmod(-theta - tab_phi[0], kTwoPi);
  if (u < 0) u += kTwoPi;
  if (!(u < kTwoPi)) u = 0.0;
  const double target = tab_phi[0] + u;

  std::size_t k = hint.get();
  if (!(k < N && tab_phi[k] <= target && target < tab_phi[k + 1])) {
    if (k + 1 < N && tab_phi[k + 1] <= target && target < tab_phi[k + 2]) {
      k = k + 1;
    } else if (k > 0 && k <= N && tab_phi[k - 1] <= target && target < tab_phi[k]) {
      k = k - 1;
    } else {
      k = static_cast<std::size_t>(std::upper_bound(tab_phi.begin(), tab_phi.end(), target) -
                                   tab_phi.begin());
      k = (k == 0) ? 0 : std::min(k - 1, N - 1);
    }
  }
  hint.set(k);

  double lo = tab_alpha[k], hi = tab_alpha[k + 1];
  double al = lo + (target - tab_phi[k]) / (tab_phi[k + 1] - tab_phi[k]) * (hi - lo);
  Derivs d = derivs(al);
  for (int it = 0; it < 12; ++it) {
    const double g = d.x1 * ct - d.y1 * st;   // X_α
    const double gp = d.x2 * ct - d.y2 * st;  // X_αα < 0
    if (g > 0)
      lo = al;
    else
      hi = al;
    const double step = -g / gp;
    if (!(std::fabs(step) > 1e-15)) break;
    double an = al + step;
    if (!(an > lo && an < hi)) {
      an = 0.5 * (lo + hi);
      if (!(hi - lo > 1e-15)) break;
    }
    al = an;
    d = derivs(al);
    if (std::fabs(step) < 1e-13) break;  // quadratic convergence: next step < 1e-20
  }
  *out = d;
  return al;
}

// ---- circle ---------------------------------------------------------------------------
void Cam::Impl::build_circle(const CamSpec& spec) {
  R = spec.radius;
  e = spec.eccentricity;
  if (!std::isfinite(R)) fail("cam.radius", fmt_num(R), "must be finite (no nan/inf)");
  if (!(R > 0)) fail("cam.radius", fmt_num(R), "must be > 0");
  if (!std::isfinite(e)) fail("cam.eccentricity", fmt_num(e), "must be finite (no nan/inf)");
  if (!(e >= 0)) fail("cam.eccentricity", fmt_num(e), "must be ≥ 0");
  if (!(e < R))
    fail("cam.eccentricity", fmt_num(e),
         "must be < cam.radius (" + fmt_num(R) + ") so that the cam encloses its centre");
  lift = 2.0 * e;
  min_rho = R;
}

// ---- lift -----------------------------------------------------------------------------
void Cam::Impl::build_lift(const CamSpec& spec) {
  rb = spec.base_radius;
  if (!std::isfinite(rb)) fail("cam.base_radius", fmt_num(rb), "must be finite (no nan/inf)");
  if (!(rb > 0)) fail("cam.base_radius", fmt_num(rb), "must be > 0");
  const auto& ang = spec.lift_angles_deg;
  const auto& L = spec.lift;
  check_knot_angles(ang, "cam.lift_angles_deg");
  if (!all_finite(L)) fail("cam.lift", fmt_list(L), "every lift must be finite (no nan/inf)");
  if (L.size() != ang.size())
    fail("cam.lift", fmt_list(L),
         "must have as many entries as cam.lift_angles_deg (" + std::to_string(ang.size()) +
             "), got " + std::to_string(L.size()));
  for (std::size_t i = 0; i < L.size(); ++i)
    if (!(rb + L[i] > 0))
      fail("cam.lift", fmt_list(L),
           "r_b + L must be > 0 (entry " + std::to_string(i) + ": " + fmt_num(rb) + " + " +
               fmt_num(L[i]) + ")");
  std::vector<double> a(ang.size());
  for (std::size_t i = 0; i < ang.size(); ++i) a[i] = ang[i] * kDeg;
  Ls = detail::PeriodicSpline(a, L, kTwoPi);

  const std::size_t N = std::max<std::size_t>(4096, 64 * ang.size());
  const double dt = kTwoPi / static_cast<double>(N);
  std::vector<std::pair<double, double>> runs;  // θ ranges [rad] where ρ ≤ 0
  bool in_run = false;
  for (std::size_t k = 0; k <= N; ++k) {
    const double th = dt * static_cast<double>(k);
    double h, h1, h2;
    Ls.eval(th, &h, &h1, &h2);
    h += rb;
    if (k < N && !(h > 0))
      fail("cam.lift", fmt_list(L),
           "r_b + L(θ) must be > 0 everywhere; the spline reaches " + fmt_num(h) +
               " at cam angle " + fmt_deg1(th / kDeg));
    const bool bad = !(h + h2 > 0) && k < N;
    if (bad && !in_run) runs.emplace_back(th, th);
    if (bad) runs.back().second = th;
    in_run = bad;
  }
  if (runs.size() > 1 && runs.front().first == 0.0 && runs.back().second >= kTwoPi - 1.5 * dt) {
    runs.front().first = runs.back().first - kTwoPi;
    runs.pop_back();
  }
  if (!runs.empty()) {
    std::string th;
    for (std::size_t j = 0; j < runs.size(); ++j) {
      if (j) th += ", ";
      const double t0 = wrap360(runs[j].first / kDeg);
      th += fmt_deg1(t0) + ".." + fmt_deg1(wrap360(t0 + (runs[j].second - runs[j].first) / kDeg));
    }
    // A hint about units: the usual cause of a non-convex lift table is angles in radians
    // (the table then spans a few degrees and L″ is huge) or lifts in another length unit.
    std::string hint;
    const double span = ang.back() - ang.front();
    double lmax = 0;
    for (double x : L) lmax = std::max(lmax, std::fabs(x));
    if (span <= kTwoPi + 1e-9)
    {
      char b[32];
      std::snprintf(b, sizeof b, "%.3g", span);
      hint = std::string("; cam.lift_angles_deg spans only ") + b +
             "°: are the angles in radians? They must be degrees";
    }
    else if (lmax > 10 * rb)
      hint = "; the lift reaches " + fmt_num(lmax) + ", more than 10× cam.base_radius = " +
             fmt_num(rb) + ": are lift and base radius in the same length unit?";
    else
      hint = "; the lift changes too fast for the base circle: a larger cam.base_radius or "
             "a smoother lift table";
    fail("cam.lift", fmt_list(L),
         "profile is not convex: radius of curvature ρ = r_b + L + L″ ≤ 0 at cam angles " + th +
             " — a flat-faced follower cannot follow a concave flank" + hint);
  }
  auto rho_at = [this](double th) {
    double h, h1, h2;
    Ls.eval(th, &h, &h1, &h2);
    return rb + h + h2;
  };
  min_rho = periodic_min(rho_at, 0.0, kTwoPi, N);
  const double Lmin = periodic_min([this](double th) { return Ls.value(th); }, 0.0, kTwoPi, N);
  const double Lmax = -periodic_min([this](double th) { return -Ls.value(th); }, 0.0, kTwoPi, N);
  lift = Lmax - Lmin;
}

}  // namespace camdyn
