// camdyn — each valve's timing on a camshaft (valve_timing.hpp).
#include "results/valve_timing.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "camdyn/cam.hpp"
#include "cam/lift_base.hpp"  // cam_lift_base
#include "results/designer_stats.hpp"  // angle_deg_mod360

namespace camdyn {
namespace detail {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2 * kPi;
constexpr double kDeg = kPi / 180.0;
constexpr double kOpenFraction = 0.01;  // open above 1 % of the valve's kinematic lift
constexpr int kScan = 3600;             // the cam's lift scanned every 0.1°, crossings refined by bisection

// The cam's lift above its base circle over one revolution, scanned once for every valve.
struct LiftScan {
  Cam cam;
  double base = 0.0, max = 0.0;
  std::vector<double> X;
  explicit LiftScan(const CamSpec& spec) : cam(spec), base(cam_lift_base(cam, spec)), X(kScan) {
    for (int i = 0; i < kScan; ++i) {
      X[std::size_t(i)] = lift(kTwoPi * i / kScan);
      max = i == 0 ? X[0] : std::max(max, X[std::size_t(i)]);
    }
  }
  double lift(double psi) { return cam.motion(psi, 1.0, 0.0).X - base; }
};

struct KinematicAngles {
  bool found = false;
  double open = 0.0, close = 0.0, boundary = 0.0;  // boundary ≤ open < close < boundary + 2π
};

// Where X_L(ψ) crosses the level L: the opening after, and the closing before, the middle of
// the longest interval with X_L ≤ L.
KinematicAngles kinematic_angles(LiftScan& scan, double L) {
  struct Crossing {
    double psi;
    bool up;
  };
  std::vector<Crossing> cr;
  const double d = kTwoPi / kScan;
  for (int i = 0; i < kScan; ++i) {
    const bool a = scan.X[std::size_t(i)] > L, b = scan.X[std::size_t((i + 1) % kScan)] > L;
    if (a == b) continue;
    double lo = d * i, hi = d * (i + 1);  // lo on sample i's side
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      ((scan.lift(mid) > L) == a ? lo : hi) = mid;
    }
    cr.push_back({0.5 * (lo + hi), b});
  }
  KinematicAngles k;
  if (cr.size() < 2) return k;
  double longest = -1.0;
  for (std::size_t i = 0; i < cr.size(); ++i) {
    const Crossing& down = cr[i];
    const Crossing& up = cr[(i + 1) % cr.size()];
    if (down.up || !up.up) continue;
    const double len = std::fmod(up.psi - down.psi + 2 * kTwoPi, kTwoPi);
    if (len <= longest) continue;
    longest = len;
    k.boundary = std::fmod(down.psi + 0.5 * len, kTwoPi);
    k.open = up.psi;
    k.close = down.psi;
  }
  if (longest < 0) return k;
  auto after_boundary = [&](double psi) { return k.boundary + std::fmod(psi - k.boundary + 2 * kTwoPi, kTwoPi); };
  k.open = after_boundary(k.open);
  k.close = after_boundary(k.close);
  k.found = k.close > k.open;
  return k;
}

double wrap_deg(double rad) {  // to (−180°, 180°]
  double d = std::fmod(rad / kDeg, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}
}  // namespace

ValveTiming::ValveTiming(const Scene& sc, const KinematicPath& path, const std::vector<std::string>& nodes) {
  const CamshaftSpec& cs = sc.camshaft;
  if (!cs.present()) return;  // a camshaft drives a network's cam contacts (validate_camshaft.cpp)
  order_ = cs.crank_orders;
  for (double a : cs.crank_amplitudes_deg) amp_.push_back(a * kDeg);
  for (double p : cs.crank_phases_deg) phase_.push_back(p * kDeg);
  auto node_index = [&](const std::string& name) {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i] == name) return int(i);
    return -1;
  };
  LiftScan scan(sc.cam);
  const NetworkSpec& net = sc.network;
  int ordinal = 0;  // the cam contacts in order
  for (std::size_t j = 0; j < net.contacts.size(); ++j) {
    const ContactPointSpec& c = net.contacts[j];
    if (c.kind != ContactPointKind::Cam) continue;
    const int cam = cs.contact_cams.empty() ? ordinal : int(cs.contact_cams[std::size_t(ordinal)]);
    ++ordinal;
    std::vector<std::string> valves;  // the seats' nodes its path reaches, else its follower
    for (const ContactPointSpec& seat : net.contacts)
      if (seat.kind == ContactPointKind::Stop && seat.side == StopSide::Below && !seat.nodes.empty() &&
          path.node(seat.nodes[0]).source == int(j))
        valves.push_back(seat.nodes[0]);
    if (valves.empty() && !c.nodes.empty()) valves.push_back(c.nodes[0]);
    for (const std::string& name : valves) {
      const KinematicNode k = path.node(name);
      Valve v;
      v.node = node_index(name);
      if (v.node < 0 || !k.reached || !(k.gain > 0) || !(scan.max > k.take_up)) continue;
      v.res.valve = name;
      v.res.contact = c.name;
      v.res.cam = cam;
      v.res.threshold = kOpenFraction * k.gain * (scan.max - k.take_up);
      const KinematicAngles ka = kinematic_angles(scan, k.take_up + kOpenFraction * (scan.max - k.take_up));
      if (!ka.found) continue;
      v.open_kin = ka.open;
      v.close_kin = ka.close;
      v.boundary = ka.boundary;
      v.res.kinematic_opening_deg = angle_deg_mod360(ka.open);
      v.res.kinematic_closing_deg = angle_deg_mod360(ka.close);
      if (std::size_t(cam) < cs.cam_offsets_deg.size()) v.alpha = cs.cam_offsets_deg[std::size_t(cam)] * kDeg;
      if (std::size_t(cam) < cs.cam_offsets_crank_deg.size())
        v.alpha = 0.5 * cs.cam_offsets_crank_deg[std::size_t(cam)] * kDeg;
      v.up = v.down = NAN;
      valves_.push_back(std::move(v));
    }
  }
}

double ValveTiming::crank_angle(double theta) const {
  double a = theta;
  for (std::size_t k = 0; k < order_.size(); ++k) a += amp_[k] * std::sin(order_[k] * theta + phase_[k]);
  return a;
}

void ValveTiming::advance(Valve& v, double a) {
  const long c = long(std::floor((a - v.boundary) / kTwoPi));
  if (!v.started) {
    v.started = true;
    v.cycle = c;
    return;
  }
  if (c == v.cycle) return;
  close_cycle(v);
  v.cycle = c;
  v.up = v.down = NAN;
}

void ValveTiming::crossing(Valve& v, double a, bool upward) {
  advance(v, a);
  if (upward) {
    if (std::isnan(v.up)) v.up = a;
  } else {
    v.down = a;
  }
  v.above = upward;
}

// The cycle ends: a complete one (an opening, then a closing) replaces the result; a partial
// one (the run starts or ends with the valve open) stands only until a complete one is seen.
void ValveTiming::close_cycle(Valve& v) {
  const bool has_up = !std::isnan(v.up);
  const bool has_down = !std::isnan(v.down) && (!has_up || v.down > v.up) && !v.above;
  if (has_up) ++v.res.openings;
  const bool complete = has_up && has_down;
  if (!complete && (v.complete || (!has_up && !has_down))) return;
  v.complete = v.complete || complete;
  const double base = kTwoPi * double(v.cycle);
  ValveTimingResult& r = v.res;
  r.opening_deg = has_up ? angle_deg_mod360(v.up) : NAN;
  r.opening_error_deg = has_up ? wrap_deg(v.up - (v.open_kin + base)) : NAN;
  r.closing_deg = has_down ? angle_deg_mod360(v.down) : NAN;
  r.closing_error_deg = has_down ? wrap_deg(v.down - (v.close_kin + base)) : NAN;
}

void ValveTiming::row(double theta, const std::vector<double>& u) {
  if (traced_) return;
  const double th_c = crank_angle(theta);
  for (Valve& v : valves_) {
    const double a = th_c - v.alpha, x = u[std::size_t(v.node)];
    const double h = v.res.threshold;
    if (!v.started) {
      v.above = x > h;
    } else if ((v.prev_u > h) != (x > h)) {
      const double w = (v.prev_u - h) / (v.prev_u - x);
      crossing(v, v.prev_a + w * (a - v.prev_a), x > h);
    }
    advance(v, a);
    v.prev_a = a;
    v.prev_u = x;
  }
}

void ValveTiming::step(const std::vector<StepSample>& s, const StepProbe& probe) {
  traced_ = true;
  const int n = int(s.size());
  if (n < 2 || s[0].nodes.empty()) return;
  StepSample tmp;
  for (Valve& v : valves_) {
    const std::size_t i = std::size_t(v.node);
    const double h = v.res.threshold;
    if (!v.started) v.above = s[0].nodes[i] > h;
    advance(v, crank_angle(s[0].theta) - v.alpha);
    for (int k = 1; k < n; ++k) {
      const double d0 = s[std::size_t(k - 1)].nodes[i] - h, d1 = s[std::size_t(k)].nodes[i] - h;
      if ((d0 > 0) != (d1 > 0)) {
        const double sg = d0 > 0 ? 1.0 : -1.0;  // sg·(u − h) falls through zero
        const double xr = falling_root(
            [&](double x) {
              probe(x, tmp);
              return sg * (tmp.nodes[i] - h);
            },
            s[std::size_t(k - 1)].x, sg * d0, s[std::size_t(k)].x, sg * d1);
        probe(xr, tmp);
        crossing(v, crank_angle(tmp.theta) - v.alpha, d1 > 0);
      }
      advance(v, crank_angle(s[std::size_t(k)].theta) - v.alpha);
    }
  }
}

std::vector<ValveTimingResult> ValveTiming::results() const {
  std::vector<ValveTimingResult> out;
  for (Valve v : valves_) {  // a copy: the cycle under way is closed as the run ends
    if (v.started) close_cycle(v);
    out.push_back(v.res);
  }
  return out;
}

}  // namespace detail
}  // namespace camdyn
