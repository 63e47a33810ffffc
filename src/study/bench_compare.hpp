// camdyn — internal: what `camdyn bench` and its tolerance sweep share (runs under a CPU
// budget, the common output grid, the comparison with a reference run). Not installed.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "camdyn/output.hpp"
#include "camdyn/simulator.hpp"
#include "study/bench.hpp"

namespace camdyn {
namespace bench_detail {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline std::string g3(double x) {
  if (!std::isfinite(x)) return "–";
  char b[48];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}

inline std::string csv_num(double x) { return std::isnan(x) ? std::string() : format_double(x); }

inline std::string csv_text(std::string s) {
  for (char& c : s)
    if (c == ',' || c == '\n' || c == '\r' || c == '"') c = ';';
  return s;
}

/// Rows of a run on the common grid (index k = round(t/dt)), with a CPU budget.
class GridObserver : public Observer {
 public:
  GridObserver(double budget, std::atomic<bool>* stop, bool keep)
      : budget_(budget), stop_(stop), keep_(keep) {}
  void on_row(const HistoryRow& r) override {
    if (keep_) rows.push_back(r);
    check();
  }
  void on_event(const ContactEvent& e) override {
    if (keep_) events.push_back(e);
  }
  void on_progress(double, double, long) override { check(); }
  std::vector<HistoryRow> rows;
  std::vector<ContactEvent> events;
  bool over_budget = false;

 private:
  void check() {
    if (budget_ <= 0) return;
    if (double(std::clock() - c0_) / CLOCKS_PER_SEC > budget_) {
      over_budget = true;
      stop_->store(true);
    }
  }
  double budget_;
  std::atomic<bool>* stop_;
  bool keep_;
  std::clock_t c0_ = std::clock();
};

/// The headlines' equal accuracy: err_force ≤ this (bench_tables.cpp).
constexpr double kHeadlineTarget = 1e-3;

struct Run {
  Summary sum;
  std::vector<HistoryRow> rows;
  std::vector<ContactEvent> events;
  bool over_budget = false;
};

/// One run under a CPU budget (0: none). Besides the observer's checks (rows, progress), a
/// watchdog thread polls the process CPU clock every 20 ms and raises the stop flag, which
/// every engine's run loop reads after each step or chunk of steps (an IDA run stuck at
/// t = 1.5e-16 reported neither rows nor progress).
inline Run run_once(const Scene& sc, double budget, bool keep_rows) {
  std::atomic<bool> stop{false}, done{false}, watchdog_fired{false};
  GridObserver obs(budget, &stop, keep_rows);
  std::thread watchdog;
  if (budget > 0)
    watchdog = std::thread([&] {
      const std::clock_t c0 = std::clock();
      while (!done.load()) {
        if (double(std::clock() - c0) / CLOCKS_PER_SEC > budget) {
          watchdog_fired.store(true);
          stop.store(true);
          return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
  Run r;
  try {
    Simulator sim(sc);
    r.sum = sim.run(&obs, &stop);
  } catch (const std::exception& e) {
    r.sum.finished = false;
    r.sum.message = std::string("error: ") + e.what();
  }
  done.store(true);
  if (watchdog.joinable()) watchdog.join();
  r.rows = std::move(obs.rows);
  r.events = std::move(obs.events);
  r.over_budget = obs.over_budget || watchdog_fired.load();
  return r;
}

/// Series on the grid: values at k = 0..n-1 (NaN where a row is missing).
struct Grid {
  std::vector<double> u, v, f;
  std::vector<int> c;
  std::vector<double> kick;  // impact impulses applied at an instant, by grid interval
  size_t n = 0;
};

/// Impacts resolved as an instantaneous impulse (event-driven, Lee "located") are not in
/// the sampled force: book each in the grid interval (t_k, t_k+1] that holds it.
inline void add_kicks(Grid& g, const std::vector<ContactEvent>& ev, double dt) {
  g.kick.assign(g.n, 0.0);
  for (const ContactEvent& e : ev) {
    if (e.impulse == 0.0) continue;
    const double x = e.t / dt;
    size_t k = size_t(std::max(0.0, std::ceil(x - 1e-9) - 1.0));
    if (k < g.n) g.kick[k] += e.impulse;
  }
}

inline Grid to_grid(const std::vector<HistoryRow>& rows, double dt, size_t n) {
  Grid g;
  g.n = n;
  g.u.assign(n, kNaN);
  g.f.assign(n, kNaN);
  g.v.assign(n, kNaN);
  g.c.assign(n, 0);
  for (const auto& r : rows) {
    const double kd = r.t / dt;
    const long k = std::lround(kd);
    if (k < 0 || size_t(k) >= n || std::fabs(kd - double(k)) > 1e-6) continue;
    g.u[size_t(k)] = r.u_c;
    g.f[size_t(k)] = r.contact_force;
    g.v[size_t(k)] = r.v_c;
    g.c[size_t(k)] = r.in_contact;
  }
  return g;
}

inline bool complete(const Grid& g) {
  for (size_t k = 0; k < g.n; ++k)
    if (!std::isfinite(g.u[k]) || !std::isfinite(g.f[k])) return false;
  return true;
}

inline double total_variation(const std::vector<double>& f, size_t k1) {
  double tv = 0;
  for (size_t k = 1; k < k1 && k < f.size(); ++k) tv += std::fabs(f[k] - f[k - 1]);
  return tv;
}

/// Impulse of F over [k0, k1] grid intervals (trapezoid).
inline double impulse(const std::vector<double>& f, size_t k0, size_t k1, double dt) {
  double s = 0;
  for (size_t k = k0; k < k1 && k + 1 < f.size(); ++k) s += 0.5 * (f[k] + f[k + 1]) * dt;
  return s;
}

struct Comparison {
  double err_u = kNaN, err_force = kNaN, osc = kNaN, impulse_err = kNaN;
  double contact_frac = kNaN;
  double event_err = kNaN;
  /// max |F − F_ref| / max |F_ref| pointwise on the grid up to the pointwise horizon,
  /// whatever the follower (an impact's jump shifted in time counts in full).
  double err_force_pointwise = kNaN;
  /// Impact speeds: max over the reference's impacts (within the pointwise horizon) of |v − v_ref| / |v_ref| at the run's nearest impact; NaN: the reference has
  /// none; 1 when the run has no impact.
  double impact_speed_err = kNaN;
  long events = 0;  // separations and impacts within the pointwise horizon
};

struct SceneInfo {
  std::string label;
  Scene scene;
  bool rigid = true;
  bool chaotic = false;  // elastic and the reference separates: pointwise only early
  bool jumps = false;    // the reference separates: the force jumps at impacts
  double dt = 1e-4;
  size_t n = 0;        // grid points 0..n-1
  size_t k_point = 0;  // pointwise comparison up to this grid index (inclusive)
  size_t k_window = 10;  // grid intervals per impulse window (1 ms)
  size_t k_rev = 0;      // grid intervals per revolution (0: unknown)
  Grid ref;
  double ref_contact_frac = kNaN;
  double ref_mean_force = kNaN;  // mean of the reference's contact force where it is > 0
  std::vector<ContactEvent> ref_events;  // separations and impacts up to k_point
  // Rigid follower: m ü = f0 − k u − c u̇ + F (for the momentum-balance impulse).
  double m = 0, k = 0, c = 0, f0 = 0;

  /// Contact impulse over grid intervals [k0, k1]. Elastic follower: trapezoid on the
  /// sampled force. Rigid follower: from the momentum balance, m Δu̇ − ∫(f0 − k u − c u̇)dt,
  /// so impacts (the reference's Newton impulse, a penalty spike between grid points)
  /// count in full; the trapezoid on the smooth u is the same quadrature for every run.
  double impulse_of(const Grid& g, size_t k0, size_t k1) const {
    if (!rigid) {
      double kicks = 0;
      for (size_t k = k0; k < k1 && k < g.kick.size(); ++k) kicks += g.kick[k];
      return impulse(g.f, k0, k1, dt) + kicks;
    }
    double s = 0;
    for (size_t j = k0; j < k1; ++j)
      s += 0.5 * dt * (2 * f0 - k * (g.u[j] + g.u[j + 1]) - c * (g.v[j] + g.v[j + 1]));
    return m * (g.v[k1] - g.v[k0]) - s;
  }
};

/// Separations and impacts up to time t_max; impacts slower than 1e-6 of the fastest
/// (grazing re-contacts at round-off speed) are dropped.
inline std::vector<ContactEvent> switch_events(const std::vector<ContactEvent>& ev, double t_max) {
  double vmax = 0;
  for (const auto& e : ev)
    if (e.type == EventKind::Impact) vmax = std::max(vmax, std::fabs(e.impact_velocity));
  std::vector<ContactEvent> out;
  for (const auto& e : ev) {
    if (e.t > t_max * (1 + 1e-12)) continue;
    if (e.type == EventKind::Separation ||
        (e.type == EventKind::Impact && std::fabs(e.impact_velocity) > 1e-6 * vmax))
      out.push_back(e);
  }
  return out;
}

inline Comparison compare(const SceneInfo& si, const Grid& g, const std::vector<ContactEvent>& ev) {
  Comparison c;
  const Grid& r = si.ref;
  const size_t kp = std::min(si.k_point, si.n - 1);
  double eu = 0;
  for (size_t k = 0; k <= kp; ++k) eu = std::max(eu, std::fabs(g.u[k] - r.u[k]));
  c.err_u = eu;
  if (si.rigid && !si.jumps) {
    // A rigid follower that never separates: a continuous contact force: pointwise, relative to the peak.
    double fmax = 0, ef = 0;
    for (size_t k = 0; k <= kp; ++k) {
      fmax = std::max(fmax, std::fabs(r.f[k]));
      ef = std::max(ef, std::fabs(g.f[k] - r.f[k]));
    }
    c.err_force = fmax > 0 ? ef / fmax : ef;
  } else {
    // An elastic follower's force (elastic ringing), or one that jumps where the contact
    // closes (an impact), is compared by its impulse over 1 ms windows (a jump shifted by
    // δ would otherwise count as an O(1) error).
    double imax = 0, ei = 0;
    for (size_t k0 = 0; k0 + si.k_window <= kp; k0 += si.k_window) {
      const double ir = si.impulse_of(si.ref, k0, k0 + si.k_window);
      const double ig = si.impulse_of(g, k0, k0 + si.k_window);
      imax = std::max(imax, std::fabs(ir));
      ei = std::max(ei, std::fabs(ig - ir));
    }
    c.err_force = imax > 0 ? ei / imax : ei;
  }
  {
    double fmax = 0, ef = 0;
    for (size_t k = 0; k <= kp; ++k) {
      fmax = std::max(fmax, std::fabs(r.f[k]));
      ef = std::max(ef, std::fabs(g.f[k] - r.f[k]));
    }
    c.err_force_pointwise = fmax > 0 ? ef / fmax : ef;
  }
  const double tvr = total_variation(r.f, si.n);
  c.osc = tvr > 0 ? total_variation(g.f, si.n) / tvr : kNaN;
  // Impulse per revolution (or over the whole run when shorter than one revolution).
  if (si.k_rev > 0 && si.k_rev < si.n) {
    double e = 0;
    for (size_t k0 = 0; k0 + si.k_rev <= si.n - 1; k0 += si.k_rev) {
      const double ir = si.impulse_of(si.ref, k0, k0 + si.k_rev);
      const double ig = si.impulse_of(g, k0, k0 + si.k_rev);
      e = std::max(e, ir != 0 ? std::fabs(ig - ir) / std::fabs(ir) : std::fabs(ig - ir));
    }
    c.impulse_err = e;
  } else {
    const double ir = si.impulse_of(si.ref, 0, si.n - 1);
    const double ig = si.impulse_of(g, 0, si.n - 1);
    c.impulse_err = ir != 0 ? std::fabs(ig - ir) / std::fabs(ir) : std::fabs(ig - ir);
  }
  long in = 0;
  for (size_t k = 0; k < si.n; ++k) in += g.c[k] ? 1 : 0;
  c.contact_frac = double(in) / double(si.n);
  // Separation and impact times against the reference's.
  const double t_max = si.dt * double(kp);
  const std::vector<ContactEvent> mine = switch_events(ev, t_max);
  c.events = long(mine.size());
  if (!si.ref_events.empty()) {
    double e = 0;
    for (const auto& re : si.ref_events) {
      double best = si.dt * double(si.n - 1);  // none of this kind: the whole run
      for (const auto& me : mine)
        if (me.type == re.type) best = std::min(best, std::fabs(me.t - re.t));
      e = std::max(e, best);
    }
    c.event_err = e;
    double es = kNaN;
    for (const auto& re : si.ref_events) {
      if (re.type != EventKind::Impact || re.impact_velocity == 0.0) continue;
      double best = kNaN, dt_best = 0;
      for (const auto& me : mine)
        if (me.type == EventKind::Impact && (std::isnan(best) || std::fabs(me.t - re.t) < dt_best)) {
          dt_best = std::fabs(me.t - re.t);
          best = std::fabs(std::fabs(me.impact_velocity) - std::fabs(re.impact_velocity)) /
                 std::fabs(re.impact_velocity);
        }
      if (std::isnan(best)) best = 1.0;
      es = std::isnan(es) ? best : std::max(es, best);
    }
    c.impact_speed_err = es;
  }
  return c;
}

inline double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}
/// The reference run of `ref` (no budget, rows kept), from the cache directory `dir` when it
/// holds one for the same scene and build, else run and (when `dir` is not empty) stored
/// there. The key: the scene's TOML (to_toml) with the library version and the size and
/// modification time of the running executable (any rebuild invalidates it). A cached run
/// keeps what the comparison reads: rows (t, u_c, v_c, F, in_contact), events, finished,
/// separations, cpu_seconds, steps, rhs_evals and message. `cached` (if given) says which it was.
Run reference_run(const Scene& ref, const std::string& dir, bool* cached = nullptr);

/// An elastic bar whose element crossing time h_e / c (c = √(E/ρ), ρ = m / (A L)) is below
/// 2 µs (bench_compare.cpp): the full sweep's fine-mesh bars.
bool fine_mesh_bar(const FollowerSpec& f);

/// The rule of the reference (bench_tables.cpp): each finished row of `label` whose
/// err_force, err_force_pointwise or impulse_err is not 10× above the reference-check row's
/// gets a note naming the column and the factor.
void flag_unresolved(std::vector<BenchRow>& rows, const std::string& label);

/// Fill `si` (grid, reference series, events, the rigid follower's constants) from the
/// scene `base` (defaults resolved, run.t_end set) and its reference run `rr`, on the
/// common grid `dt`. Returns false when the reference does not cover the grid.
bool setup_scene_info(SceneInfo& si, const Scene& base, const Run& rr, double dt);

}  // namespace bench_detail
}  // namespace camdyn
