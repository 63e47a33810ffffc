// camdyn — the cam from the valve lift (include/camdyn/synthesis.hpp; docs/cam_laws.md
// "From the valve lift to the cam").
//
//   Valve side of the train, q the follower coordinate:
//     translating: G(s) = r s;  oscillating: G(ψ) = ℓ_v (sin(ψ₀ + ψ) − sin ψ₀).
//   On the lobe G(q) = V + lash, so q = G⁻¹(V + lash) (Newton, bisection-safeguarded on
//   the monotone branch), q′ = V′/G′, q″ = (V″ − G″ q′²)/G′. Off the lobe, with lash, the
//   cam rises from the base circle (q = 0) to q_l = G⁻¹(lash) by q_l f(x), f = 10x³ − 15x⁴
//   + 6x⁵, over ramp_deg before the opening angle θ_o, and back after the closing θ_c.
#include "camdyn/synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "cam/format.hpp"

namespace camdyn {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kDeg = kPi / 180.0;

[[noreturn]] void fail(const std::string& key, const std::string& value, const std::string& rule) {
  throw SceneError("<synthesis>", 0, key, value, rule);
}

bool oscillating(const CamSpec& c) { return c.follower_motion == FollowerMotion::Oscillating; }

/// G, G′, G″ at q.
void valve_map(const CamSpec& c, const ValveTrainOptions& t, double q, double* g, double* g1, double* g2) {
  if (!oscillating(c)) {
    *g = t.ratio * q;
    *g1 = t.ratio;
    *g2 = 0.0;
    return;
  }
  const double p0 = t.valve_end_angle_deg * kDeg, lv = c.valve_arm;
  *g = lv * (std::sin(p0 + q) - std::sin(p0));
  *g1 = lv * std::cos(p0 + q);
  *g2 = -lv * std::sin(p0 + q);
}

void check_train(const CamSpec& c, const ValveTrainOptions& t) {
  if (!oscillating(c)) {
    if (!(std::isfinite(t.ratio) && t.ratio > 0))
      fail("synthesis.ratio", fmt_num(t.ratio), "the lever ratio dV/ds must be finite and > 0");
  } else {
    if (!(std::isfinite(c.valve_arm) && c.valve_arm > 0))
      fail("cam.valve_arm", fmt_num(c.valve_arm), "must be finite and > 0 (the finger's valve end)");
    if (!(std::isfinite(t.valve_end_angle_deg) && std::fabs(t.valve_end_angle_deg) < 90))
      fail("synthesis.valve_end_angle_deg", fmt_num(t.valve_end_angle_deg),
           "must be in (−90, 90) (at ±90° the finger's ratio dV/dψ is 0)");
  }
  if (!(std::isfinite(t.lash) && t.lash >= 0)) fail("synthesis.lash", fmt_num(t.lash), "must be finite and ≥ 0");
  if (t.lash > 0 && !(std::isfinite(t.ramp_deg) && t.ramp_deg > 0 && t.ramp_deg < 180))
    fail("synthesis.ramp_deg", fmt_num(t.ramp_deg), "with lash > 0 the lash ramp must be in (0, 180) degrees");
  if (t.points < 16) fail("points", std::to_string(t.points), "must be ≥ 16");
}

double poly345(double x, double* d1, double* d2) {
  x = std::min(1.0, std::max(0.0, x));
  *d1 = x * x * (30 - x * (60 - 30 * x));
  *d2 = x * (60 - x * (180 - 120 * x));
  return x * x * x * (10 - x * (15 - 6 * x));
}
}  // namespace

double follower_coordinate_for_valve(const CamSpec& c, const ValveTrainOptions& t, double y) {
  check_train(c, t);
  if (!(std::isfinite(y) && y >= 0)) fail("cam.law", fmt_num(y), "the valve lift + lash must be ≥ 0");
  if (!oscillating(c)) return y / t.ratio;
  const double p0 = t.valve_end_angle_deg * kDeg, reach = c.valve_arm * (1.0 - std::sin(p0));
  if (!(y < reach))
    fail("cam.law", fmt_num(y),
         "the valve lift + lash exceeds the finger's reach ℓ_v (1 − sin ψ₀) = " + fmt_num(reach) +
             " (cam.valve_arm = " + fmt_num(c.valve_arm) + ", valve_end_angle_deg = " +
             fmt_num(t.valve_end_angle_deg) + ")");
  // G is increasing on [0, π/2 − ψ₀]; Newton from the linearised root, kept in the bracket.
  double lo = 0.0, hi = 0.5 * kPi - p0;
  double q = y / (c.valve_arm * std::cos(p0));
  for (int it = 0; it < 100; ++it) {
    if (!(q > lo && q < hi)) q = 0.5 * (lo + hi);
    double g, g1, g2;
    valve_map(c, t, q, &g, &g1, &g2);
    const double r = g - y;
    if (r > 0) hi = q; else lo = q;
    const double dq = r / g1;
    q -= dq;
    if (std::fabs(dq) <= 1e-16 * std::max(1.0, std::fabs(q))) break;
  }
  return q;
}

CamSynthesis synthesise_cam_from_valve_lift(const CamSpec& cam, const MotionLaw& law, const ValveTrainOptions& t,
                                            const std::string& table_path) {
  check_train(cam, t);
  const int N = t.points;
  // The valve lift on the grid: its scale, its sign, and where it opens.
  std::vector<double> V(std::size_t(N) + 1);
  double vmax = 0, vmin = 0;
  for (int i = 0; i <= N; ++i) {
    V[std::size_t(i)] = law.eval(kTwoPi * i / N).L;
    vmax = std::max(vmax, V[std::size_t(i)]);
    vmin = std::min(vmin, V[std::size_t(i)]);
  }
  if (!(vmax > 0)) fail("cam.law", fmt_num(vmax), "the valve lift must rise above 0");
  const double ztol = 1e-12 * vmax;
  if (vmin < -ztol)
    fail("cam.law", fmt_num(vmin), "the valve lift must be ≥ 0 (0 on the base circle: the valve closed)");
  // Opening and closing angles: the grid brackets, refined by bisection on V > ztol.
  auto open_at = [&](double a, double b, bool rising) {
    for (int k = 0; k < 200 && b - a > 1e-15; ++k) {
      const double m = 0.5 * (a + b);
      ((law.eval(m).L > ztol) == rising ? b : a) = m;
    }
    return rising ? a : b;
  };
  std::vector<double> opens, closes;
  for (int i = 0; i < N; ++i) {
    const bool a = V[std::size_t(i)] > ztol, b = V[std::size_t(i) + 1] > ztol;
    const double ta = kTwoPi * i / N, tb = kTwoPi * (i + 1) / N;
    if (!a && b) opens.push_back(open_at(ta, tb, true));
    if (a && !b) closes.push_back(open_at(ta, tb, false));
  }
  double th_o = 0, th_c = 0, ql = 0;
  if (t.lash > 0) {
    if (opens.size() != 1 || closes.size() != 1)
      fail("cam.law", std::to_string(opens.size()) + " openings",
           "a valve lift with lash needs exactly one lobe (one opening, one closing)");
    th_o = opens[0];
    th_c = closes[0];
    // A law's joint within 1e-3 rad of the bisected angle is where the valve opens/closes.
    for (const Breakpoint& b : law.breakpoints()) {
      if (!(std::fabs(law.eval(b.theta).L) <= ztol)) continue;
      auto near = [&](double a) { return std::fabs(std::remainder(b.theta - a, kTwoPi)) < 1e-3; };
      if (near(th_o)) th_o = b.theta;
      if (near(th_c)) th_c = b.theta;
    }
    ql = follower_coordinate_for_valve(cam, t, t.lash);
    // Both ramps on the closed valve: the dwell from θ_c to θ_o must hold them.
    double dwell = th_o - th_c;
    if (dwell <= 0) dwell += kTwoPi;
    if (!(2.0 * t.ramp_deg * kDeg <= dwell))
      fail("synthesis.ramp_deg", fmt_num(t.ramp_deg),
           "the two lash ramps do not fit on the closed valve (" + fmt_num(dwell / kDeg) + "° from closing at " +
               fmt_num(th_c / kDeg) + "° to opening at " + fmt_num(th_o / kDeg) + "°)");
  }
  const double scale = oscillating(cam) ? cam.valve_arm : 1.0;  // table lift: s, or ℓ_v ψ
  const double ramp = t.ramp_deg * kDeg;
  CamSynthesis out;
  LiftTable& tab = out.table;
  for (int i = 0; i < N; ++i) {
    const double th = kTwoPi * i / N;
    double q = 0, q1 = 0, q2 = 0;
    auto rel = [&](double a) {  // θ − a in [0, 2π)
      double d = std::fmod(th - a, kTwoPi);
      return d < 0 ? d + kTwoPi : d;
    };
    const bool on_lobe = t.lash > 0 ? rel(th_o) <= rel(th_c) : true;
    if (on_lobe) {
      const LiftDerivs v = law.eval(th);
      const double y = std::max(0.0, v.L) + t.lash;
      q = follower_coordinate_for_valve(cam, t, y);
      double g, g1, g2;
      valve_map(cam, t, q, &g, &g1, &g2);
      q1 = v.L1 / g1;
      q2 = (v.L2 - g2 * q1 * q1) / g1;
    } else if (rel(th_c) < ramp) {  // closing ramp: q_l → 0
      double f1, f2;
      q = ql * poly345(1.0 - rel(th_c) / ramp, &f1, &f2);
      q1 = -ql * f1 / ramp;
      q2 = ql * f2 / (ramp * ramp);
    } else if (kTwoPi - rel(th_o) <= ramp) {  // opening ramp: 0 → q_l
      double f1, f2;
      q = ql * poly345(1.0 - (kTwoPi - rel(th_o)) / ramp, &f1, &f2);
      q1 = ql * f1 / ramp;
      q2 = ql * f2 / (ramp * ramp);
    }
    tab.angle_deg.push_back(360.0 * i / N);
    tab.lift.push_back(scale * q);
    tab.dlift_ddeg.push_back(scale * q1 * kDeg);
    tab.d2lift_ddeg2.push_back(scale * q2 * kDeg * kDeg);
  }
  {
    std::ofstream f(table_path, std::ios::binary | std::ios::trunc);
    f << "# the cam's follower lift synthesised from the valve lift (camdyn; docs/cam_laws.md)\n"
      << lift_table_csv(tab);
    if (!f) fail("table_path", "\"" + table_path + "\"", "cannot write the lift-table file");
  }
  out.spec = cam;
  out.spec.profile = CamProfileKind::Table;
  out.spec.lift_table = table_path;
  out.spec.law.clear();
  const Cam c(out.spec);  // the profile by the follower's kinematics, with its checks
  out.lift = c.lift();
  const CamExtremum pa =
      cam_extremum(c, [](const CamPoint& p) { return std::fabs(p.pressure_angle); }, true);
  out.max_pressure_angle_deg = pa.value / kDeg;
  out.max_pressure_angle_at_deg = pa.theta / kDeg;
  const CamExtremum rho = cam_extremum(
      c, [](const CamPoint& p) { return p.rho > 0 ? p.rho : std::nan(""); }, false);
  out.min_radius_of_curvature = rho.value;
  out.min_radius_of_curvature_at_deg = rho.theta / kDeg;
  return out;
}

}  // namespace camdyn
