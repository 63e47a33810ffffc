// camdyn — cam motion laws (see include/camdyn/motion_law.hpp).
//
// The modified trapezoid and the modified sine are built from their acceleration: pieces
// a(x) = c + A sin(w (x − x₀) + φ), integrated in closed form (velocity and displacement
// continuous, zero at x = 0), then scaled so that f(1) = 1. Everything else is a closed
// form or a polynomial.
#include "camdyn/motion_law.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "camdyn/cam_spec.hpp"
#include "camdyn/scene_error.hpp"
#include "cam/format.hpp"

namespace camdyn {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kDeg = kPi / 180.0;

// sin and cos of a phase a of a law (|a| ≤ 10; the laws' phases lie in [−π/2, 2π]), as
// one call: quadrant reduction r = a − k π/2 in two parts (k·pio2_1 exact for |k| < 2²⁰)
// and fdlibm's polynomial kernels on [−π/4, π/4] (k_sin.c, k_cos.c: error < 1 ulp there).
// std::sin and std::cos serve any argument (and the libm call cannot be inlined); this is
// the cost of a law's evaluation that a spline does not have (issue 24: bench_cam).
inline void sincos_phase(double a, double* s, double* c) {
  constexpr double invpio2 = 6.36619772367581382433e-01, pio2_1 = 1.57079632673412561417e+00,
                   pio2_1t = 6.07710050650619224932e-11;
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double k = std::floor(a * invpio2 + 0.5);
  const double r = (a - k * pio2_1) - k * pio2_1t;
  const double z = r * r;
  const double sr = r + z * r * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
  const double rc = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))), hz = 0.5 * z, w = 1.0 - hz;
  const double cr = w + (((1.0 - w) - hz) + z * rc);
  switch (static_cast<long>(k) & 3) {
    case 0: *s = sr; *c = cr; break;
    case 1: *s = cr; *c = -sr; break;
    case 2: *s = -sr; *c = -cr; break;
    default: *s = -cr; *c = sr; break;
  }
}

struct AccPiece {
  double x0, x1, c, A, w, ph;
  double v0 = 0, y0 = 0;  // velocity, displacement at x0 (filled by build)
  double sp = 0, cp = 1;  // sin φ, cos φ (precomputed: two fewer calls per evaluation)
};

struct AccLaw {
  std::vector<AccPiece> p;
  double scale = 1;
  AccLaw(std::vector<AccPiece> pieces) : p(std::move(pieces)) {
    double v = 0, y = 0;
    for (AccPiece& q : p) {
      q.sp = std::sin(q.ph);
      q.cp = std::cos(q.ph);
      q.v0 = v;
      q.y0 = y;
      const auto e = raw(q, q.x1);
      v = e[1];
      y = e[0];
    }
    scale = 1.0 / y;
  }
  // {y, v, a, j} of piece q at x (unscaled).
  static std::array<double, 4> raw(const AccPiece& q, double x) {
    const double u = x - q.x0;
    double y = q.y0 + q.v0 * u + 0.5 * q.c * u * u, v = q.v0 + q.c * u, a = q.c, j = 0;
    if (q.A != 0) {
      double s, c;
      sincos_phase(q.w * u + q.ph, &s, &c);
      const double sp = q.sp, cp = q.cp;
      const double iw = 1.0 / q.w;  // one division where there were three
      v += -(q.A * iw) * (c - cp);
      y += -(q.A * iw) * ((s - sp) * iw - u * cp);
      a += q.A * s;
      j = q.A * q.w * c;
    }
    return {y, v, a, j};
  }
  std::array<double, 4> eval(double x) const {
    std::size_t i = 0;
    while (i + 1 < p.size() && x > p[i].x1) ++i;
    auto r = raw(p[i], x);
    for (double& v : r) v *= scale;
    return r;
  }
};

const AccLaw& modtrap() {
  static const AccLaw law({{0.0, 0.125, 0, 1, 4 * kPi, 0},
                           {0.125, 0.375, 1, 0, 0, 0},
                           {0.375, 0.625, 0, 1, 4 * kPi, kPi / 2},
                           {0.625, 0.875, -1, 0, 0, 0},
                           {0.875, 1.0, 0, 1, 4 * kPi, -kPi / 2}});
  return law;
}
const AccLaw& modsine() {
  static const AccLaw law({{0.0, 0.125, 0, 1, 4 * kPi, 0},
                           {0.125, 0.875, 0, 1, 4 * kPi / 3, kPi / 2},
                           {0.875, 1.0, 0, 1, 4 * kPi, -kPi / 2}});
  return law;
}

/// Σ c_k x^k and its derivatives of orders 0 … N−1.
template <std::size_t N>
std::array<double, N> poly_eval(const std::vector<double>& c, double x) {
  std::array<double, N> r{};
  for (std::size_t d = 0; d < N; ++d) {
    double s = 0;
    for (std::size_t k = c.size(); k-- > d;) {
      double f = 1;  // k!/(k−d)!
      for (std::size_t m = 0; m < d; ++m) f *= double(k - m);
      s = s * x + c[k] * f;
    }
    r[d] = s;
  }
  return r;
}

const std::vector<double> kPoly345{0, 0, 0, 10, -15, 6};
const std::vector<double> kPoly4567{0, 0, 0, 0, 35, -84, 70, -20};
const std::vector<double> kPoly56789{0, 0, 0, 0, 0, 126, -420, 540, -315, 70};

[[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& rule) {
  throw SceneError("<cam>", 0, key, value, rule);
}

std::string seg_name(std::size_t i, const MotionSegment& s) {
  return "segment " + std::to_string(i + 1) + " (" + to_string(s.kind) + ")";
}

}  // namespace

const char* to_string(MotionSegmentKind k) {
  switch (k) {
    case MotionSegmentKind::Dwell: return "dwell";
    case MotionSegmentKind::Ramp: return "ramp";
    case MotionSegmentKind::Harmonic: return "harmonic";
    case MotionSegmentKind::Cycloidal: return "cycloidal";
    case MotionSegmentKind::Poly345: return "poly345";
    case MotionSegmentKind::Poly4567: return "poly4567";
    case MotionSegmentKind::Poly: return "poly";
    case MotionSegmentKind::ModTrap: return "modtrap";
    case MotionSegmentKind::ModSine: return "modsine";
    case MotionSegmentKind::Polydyne: return "polydyne";
  }
  return "?";
}

std::array<double, 4> MotionLaw::normalised(MotionSegmentKind kind, double x,
                                            const std::vector<double>& coefficients) {
  switch (kind) {
    case MotionSegmentKind::Dwell: return {0, 0, 0, 0};
    case MotionSegmentKind::Ramp: return {x, 1, 0, 0};
    case MotionSegmentKind::Harmonic: {
      double s, c;
      sincos_phase(kPi * x, &s, &c);
      return {0.5 * (1 - c), 0.5 * kPi * s, 0.5 * kPi * kPi * c, -0.5 * kPi * kPi * kPi * s};
    }
    case MotionSegmentKind::Cycloidal: {
      double s, c;
      sincos_phase(kTwoPi * x, &s, &c);
      return {x - s * (1.0 / kTwoPi), 1 - c, kTwoPi * s, kTwoPi * kTwoPi * c};
    }
    case MotionSegmentKind::Poly345: return poly_eval<4>(kPoly345, x);
    case MotionSegmentKind::Poly4567: return poly_eval<4>(kPoly4567, x);
    case MotionSegmentKind::Poly: return poly_eval<4>(coefficients, x);
    case MotionSegmentKind::ModTrap: return modtrap().eval(x);
    case MotionSegmentKind::ModSine: return modsine().eval(x);
    case MotionSegmentKind::Polydyne: return poly_eval<4>(kPoly56789, x);
  }
  return {0, 0, 0, 0};
}

LiftDerivs MotionLaw::eval_segment(std::size_t i, double u) const {
  const MotionSegment& s = segs_[i];
  const double b = beta_[i], ib = 1.0 / b;  // one division: x, L′, L″, L‴ multiply by it
  const double x = std::min(1.0, std::max(0.0, u * ib));
  LiftDerivs d;
  if (s.kind == MotionSegmentKind::Polydyne) {
    const auto p = poly_eval<6>(kPoly56789, x);
    const double w = kTwoPi * s.speed_rev_s, c = s.m * w * w / s.k, g = 1.0 + s.ks / s.k;
    const double H = s.rise, b2 = b * b;
    d.L = L0_[i] + H * (g * p[0] + c * p[2] / b2);
    d.L1 = H * (g * p[1] + c * p[3] / b2) / b;
    d.L2 = H * (g * p[2] + c * p[4] / b2) / b2;
    d.L3 = H * (g * p[3] + c * p[5] / b2) / (b2 * b);
    return d;
  }
  const auto f = normalised(s.kind, x, s.coefficients);
  const double H = s.rise;
  d.L = L0_[i] + H * f[0];
  d.L1 = H * f[1] * ib;
  d.L2 = H * f[2] * (ib * ib);
  d.L3 = H * f[3] * (ib * ib * ib);
  return d;
}

MotionLaw::MotionLaw(std::vector<MotionSegment> segments, const std::string& key)
    : segs_(std::move(segments)) {
  const std::size_t n = segs_.size();
  if (n == 0) fail(key, "\"\"", "needs at least one segment (e.g. \"dwell 180; cycloidal 90 1; cycloidal 90 -1\")");
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    MotionSegment& s = segs_[i];
    const std::string nm = seg_name(i, s);
    if (!(std::isfinite(s.duration_deg) && s.duration_deg > 0))
      fail(key, fmt_num(s.duration_deg), nm + ": the duration must be > 0 degrees");
    if (!std::isfinite(s.rise)) fail(key, fmt_num(s.rise), nm + ": the rise must be finite");
    if (s.kind == MotionSegmentKind::Dwell && s.rise != 0)
      fail(key, fmt_num(s.rise), nm + ": a dwell has no rise (give 'dwell DURATION')");
    if (s.kind == MotionSegmentKind::Poly) {
      if (s.coefficients.size() < 2)
        fail(key, fmt_list(s.coefficients), nm + ": give the coefficients c0 c1 … cn after the rise");
      double sum = 0;
      for (double c : s.coefficients) {
        if (!std::isfinite(c)) fail(key, fmt_list(s.coefficients), nm + ": coefficients must be finite");
        sum += c;
      }
      if (s.coefficients[0] != 0)
        fail(key, fmt_list(s.coefficients), nm + ": c0 must be 0 (the segment starts where the previous one ends)");
      if (std::fabs(sum - 1.0) > 1e-9)
        fail(key, fmt_list(s.coefficients),
             nm + ": the coefficients must sum to 1 (f(1) = 1; the rise scales it), got " + fmt_num(sum));
    }
    if (s.kind == MotionSegmentKind::Polydyne) {
      if (!(std::isfinite(s.k) && s.k > 0)) fail(key, fmt_num(s.k), nm + ": k (train stiffness) must be > 0");
      if (!(std::isfinite(s.m) && s.m > 0)) fail(key, fmt_num(s.m), nm + ": m (valve mass) must be > 0");
      if (!(std::isfinite(s.ks) && s.ks >= 0)) fail(key, fmt_num(s.ks), nm + ": ks (valve spring) must be ≥ 0");
      if (!(std::isfinite(s.speed_rev_s) && s.speed_rev_s != 0))
        fail(key, fmt_num(s.speed_rev_s), nm + ": speed_rev_s (design speed) must be finite and ≠ 0");
    }
    total += s.duration_deg;
  }
  if (std::fabs(total - 360.0) > 1e-9)
    fail(key, fmt_num(total), "the segment durations must sum to 360° (got " + fmt_num(total) + "°)");

  start_.assign(n + 1, 0.0);
  beta_.resize(n);
  L0_.assign(n + 1, 0.0);
  double acc = 0;
  for (std::size_t i = 0; i < n; ++i) {
    start_[i] = acc * kDeg;
    acc += segs_[i].duration_deg;
    beta_[i] = segs_[i].duration_deg * kDeg;
  }
  start_[n] = kTwoPi;
  beta_[n - 1] = kTwoPi - start_[n - 1];
  for (std::size_t i = 0; i < n; ++i) L0_[i + 1] = eval_segment(i, beta_[i]).L;

  // Sampled extremes (lift range, derivative scales for the continuity tolerance).
  std::array<double, 4> scale{0, 0, 0, 0};
  lmin_ = lmax_ = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k <= 256; ++k) {
      const LiftDerivs d = eval_segment(i, beta_[i] * k / 256.0);
      lmin_ = std::min(lmin_, d.L);
      lmax_ = std::max(lmax_, d.L);
      const double v[4] = {d.L, d.L1, d.L2, d.L3};
      for (int j = 0; j < 4; ++j) scale[j] = std::max(scale[j], std::fabs(v[j]));
    }
  // Closure: back to L = 0 after 360°.
  const double tol0 = 1e-9 * std::max(scale[0], 1e-300);
  if (std::fabs(L0_[n]) > tol0)
    fail(key, fmt_num(L0_[n]),
         "the lift does not close over the revolution: after 360° it is " + fmt_num(L0_[n]) +
             " (the rises and falls must cancel" +
             (std::any_of(segs_.begin(), segs_.end(),
                          [](const MotionSegment& s) { return s.kind == MotionSegmentKind::Polydyne; })
                  ? "; a polydyne segment changes the cam lift by (1 + ks/k)·H"
                  : "") +
             ")");
  L0_[n] = 0.0;

  // Continuity at each segment start (segment 0: against the end of the last one).
  breaks_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t p = (i + n - 1) % n;
    const LiftDerivs l = eval_segment(p, beta_[p]);
    LiftDerivs r = eval_segment(i, 0.0);
    if (i == 0) r.L = 0.0;
    const double lv[4] = {i == 0 ? L0_[n] : l.L, l.L1, l.L2, l.L3};
    const double rv[4] = {r.L, r.L1, r.L2, r.L3};
    Breakpoint& b = breaks_[i];
    b.theta = start_[i];
    b.order = 3;
    for (int k = 0; k < 4; ++k) {
      b.jump[k] = rv[k] - lv[k];
      if (std::fabs(b.jump[k]) > 1e-9 * std::max(scale[k], 1e-300)) {
        b.order = k - 1;
        break;
      }
    }
    if (b.order < 0)  // a lift jump: cannot happen with the lift carried over; kept as a guard
      fail(key, fmt_num(b.jump[0]), seg_name(i, segs_[i]) + ": the lift jumps at its start");
  }
}

LiftDerivs MotionLaw::eval(double theta) const {
  if (!tab_t_.empty()) return eval_table(theta);
  // θ mod 2π without fmod's exact division loop (a third of the evaluation's cost): the
  // reduced angle is within an ulp of θ of fmod's, far below the joints' 1e-9 rad windows.
  double u = theta - kTwoPi * std::floor(theta * (1.0 / kTwoPi));
  if (u < 0) u += kTwoPi;
  if (!(u < kTwoPi)) u = 0.0;
  // a law has a handful of segments: a forward scan beats the binary search's branches
  std::size_t i = 0;
  const std::size_t last = start_.size() - 2;
  while (i < last && start_[i + 1] <= u) ++i;
  return eval_segment(i, u - start_[i]);
}

std::string MotionLaw::continuity_report() const {
  std::string s;
  for (std::size_t i = 0; i < breaks_.size(); ++i) {
    if (i) s += ", ";
    s += "C" + std::to_string(breaks_[i].order) + " at " + fmt_num(std::round(breaks_[i].theta / kDeg * 1e6) / 1e6) + "°";
  }
  return s;
}

}  // namespace camdyn
