// camdyn — the speed-range map (speed_map.hpp; docs/guide/sweeps.md "The speed-range map").
//
//   1. grid      trial speeds equally spaced over [lo, hi], run in parallel (the sweep's
//                worker pool); an automatic range is widened while nothing departs (up)
//                or the lowest speed already departs (down).
//   2. refine    between every two neighbouring trials whose verdict kinds differ, the
//                midpoint is run; repeated (each round's midpoints in parallel) until
//                every such pair is closer than rel_tol·|speed|.
//   3. bands     per kind, the runs of neighbouring trials that show it, bracketed by the
//                trials around them; the lowest departure = the lowest separation speed.
#include "study/speed_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>
#include <set>

#include "camdyn/follower_system.hpp"
#include "camdyn/output.hpp"
#include "mechanism/mechanism.hpp"
#include "results/verdict.hpp"
#include "study/thread_pool.hpp"

namespace camdyn {
namespace detail {

namespace {

std::string num(double x) { return format_double(x); }

struct Trial {
  SpeedTrial t;
  std::map<std::string, std::pair<std::string, double>> first;  // kind → (contact, θ [deg])
  bool has(const std::string& k) const { return std::find(t.kinds.begin(), t.kinds.end(), k) != t.kinds.end(); }
  bool departs() const {
    for (const auto& k : t.kinds)
      if (is_departure_kind(k)) return true;
    return false;
  }
};

Trial trial(const Scene& scene, double v, const std::shared_ptr<const FollowerSystem>& follower,
            const MechanicalSystem* mech) {
  Trial out;
  out.t.speed_rev_s = v;
  try {
    Scene s = scene;
    s.cam.speed_rev_s = v;
    const double revs = double(scene.jump.settle_revolutions + scene.jump.judge_revolutions);
    s.run.t_end = revs / std::abs(v);
    const double t_judge = double(scene.jump.settle_revolutions) / std::abs(v);
    const Summary r = follower ? Simulator(s, follower).run() : Simulator(s).run();
    out.t.finished = r.finished;
    if (r.finished) out.t.criteria = r.criteria;
    if (!r.finished) {
      out.t.text = r.message;
      return out;
    }
    std::vector<ContactEvent> judged;
    for (const ContactEvent& e : r.events)
      if (e.t >= t_judge) judged.push_back(e);
    const std::vector<VerdictItem> v_items = make_verdict(s, mech, judged);
    out.t.text = verdict_one_line(v_items);
    for (const std::string& k : map_kinds())
      for (const VerdictItem& it : v_items)
        if (it.kind == k) {
          if (!out.has(k)) out.t.kinds.push_back(k);
          if (!out.first.count(k)) out.first[k] = {it.contact, it.theta_deg};
        }
  } catch (const std::exception& e) {
    out.t.finished = false;
    out.t.text = e.what();
  }
  return out;
}

// The verdict's view of the follower: the mechanism when its contacts are named (their
// names, roles and clearances), else null (summary_builder.cpp passes the same).
std::shared_ptr<const MechanicalSystem> verdict_system(const Scene& scene,
                                                       const std::shared_ptr<const FollowerSystem>& follower) {
  std::shared_ptr<const MechanicalSystem> m;
  if (follower) m = make_user_system(scene, follower);
  else m = std::make_shared<const Mechanism>(scene);
  return m->traits().named_contacts ? m : nullptr;
}

}  // namespace

const std::vector<std::string>& map_kinds() {
  static const std::vector<std::string> k{"opening_liftoff", "nose_float", "closing_bounce", "seat_bounce"};
  return k;
}

bool is_departure_kind(const std::string& kind) {
  return kind == "opening_liftoff" || kind == "nose_float" || kind == "closing_bounce";
}

SpeedTrial run_speed_trial(const Scene& scene, double speed_rev_s,
                           const std::shared_ptr<const FollowerSystem>& follower, std::string* contact,
                           double* theta) {
  const auto mech = verdict_system(scene, follower);
  Trial t = trial(scene, speed_rev_s, follower, mech.get());
  for (const std::string& k : t.t.kinds)
    if (is_departure_kind(k)) {
      if (contact) *contact = t.first[k].first;
      if (theta) *theta = t.first[k].second;
      break;
    }
  return t.t;
}

JumpResult speed_map(const Scene& scene, const JumpOptions& o, double dir, double est,
                     const std::shared_ptr<const FollowerSystem>& follower) {
  if (!std::isfinite(est) || est <= 0) est = 1.0;
  const bool auto_lo = !(o.lo_rev_s > 0), auto_hi = !(o.hi_rev_s > 0);
  double lo = auto_lo ? 0.5 * est : o.lo_rev_s;
  double hi = auto_hi ? 1.5 * est : o.hi_rev_s;
  if (auto_lo && !(lo < hi)) lo = 0.5 * hi;
  if (auto_hi && !(lo < hi)) hi = 2.0 * lo;
  const auto mech = verdict_system(scene, follower);

  JumpResult res;
  res.method = "simulation";
  std::map<double, Trial> trials;  // by |speed|
  std::mutex mu;
  auto run_all = [&](const std::vector<double>& speeds) {
    std::vector<double> todo;
    for (double v : speeds)
      if (!trials.count(v) && std::find(todo.begin(), todo.end(), v) == todo.end()) todo.push_back(v);
    std::vector<Trial> out(todo.size());
    parallel_for(todo.size(), o.jobs, nullptr, [&](std::size_t i) {
      out[i] = trial(scene, dir * todo[i], follower, mech.get());
      std::lock_guard<std::mutex> lock(mu);
      if (o.log) o.log(dir * todo[i], out[i].departs());
      return true;
    });
    for (std::size_t i = 0; i < todo.size(); ++i) trials[todo[i]] = std::move(out[i]);
    res.simulations += int(todo.size());
  };
  auto grid = [&](double a, double b) {
    std::vector<double> g;
    const int n = o.grid_points;
    for (int i = 0; i < n; ++i) g.push_back(i == n - 1 ? b : (a * double(n - 1 - i) + b * double(i)) / double(n - 1));
    return g;
  };
  auto any_departs = [&] {
    for (const auto& kv : trials)
      if (kv.second.t.finished && kv.second.departs()) return true;
    return false;
  };
  auto lowest_departs = [&] {
    for (const auto& kv : trials)
      if (kv.second.t.finished) return kv.second.departs();
    return false;
  };

  // 1. grid (widened while automatic and nothing / everything departs)
  double spacing = 0;
  auto scan = [&](double a, double b) {
    run_all(grid(a, b));
    spacing = std::max(spacing, (b - a) / double(o.grid_points - 1));
  };
  scan(lo, hi);
  for (int i = 0; i < 6 && auto_hi && !any_departs(); ++i) {
    const double a = hi;
    hi *= 2.0;
    scan(a, hi);
  }
  for (int i = 0; i < 6 && auto_lo && lowest_departs(); ++i) {
    const double b = lo;
    lo *= 0.5;
    scan(lo, b);
  }
  res.grid_spacing_rev_s = spacing;
  res.grid_simulations = res.simulations;
  res.range_lo_rev_s = dir * lo;
  res.range_hi_rev_s = dir * hi;

  // 2. refine every boundary between finished neighbours
  auto finished_list = [&] {
    std::vector<const Trial*> f;
    for (const auto& kv : trials)
      if (kv.second.t.finished) f.push_back(&kv.second);
    return f;
  };
  for (int round = 0; round < 200; ++round) {
    const std::vector<const Trial*> f = finished_list();
    std::vector<double> mids;
    for (std::size_t i = 0; i + 1 < f.size(); ++i) {
      const double a = std::abs(f[i]->t.speed_rev_s), b = std::abs(f[i + 1]->t.speed_rev_s);
      if (f[i]->t.kinds == f[i + 1]->t.kinds || b - a <= o.rel_tol * b) continue;
      const double m = 0.5 * (a + b);
      if (m > a && m < b) mids.push_back(m);
    }
    if (mids.empty()) break;
    run_all(mids);
  }

  // 3. bands, the lowest departure, monotonicity
  const std::vector<const Trial*> f = finished_list();
  for (const auto& kv : trials) {
    res.trials.push_back(kv.second.t);
    if (!kv.second.t.finished) ++res.failed_simulations;
  }
  for (const std::string& k : map_kinds()) {
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (!f[i]->has(k) || (i > 0 && f[i - 1]->has(k))) continue;
      SpeedBand b;
      b.kind = k;
      b.from_in = f[i]->t.speed_rev_s;
      if (i > 0) b.from_out = f[i - 1]->t.speed_rev_s;
      const auto& first = f[i]->first.at(k);
      b.contact = first.first;
      b.theta_deg = first.second;
      std::size_t j = i;
      while (j + 1 < f.size() && f[j + 1]->has(k)) ++j;
      b.to_in = f[j]->t.speed_rev_s;
      if (j + 1 < f.size()) b.to_out = f[j + 1]->t.speed_rev_s;
      res.bands.push_back(b);
    }
  }
  std::size_t first_dep = f.size();
  for (std::size_t i = 0; i < f.size() && first_dep == f.size(); ++i)
    if (f[i]->departs()) first_dep = i;
  if (first_dep == f.size()) {
    res.jump_speed_rev_s = dir * std::numeric_limits<double>::infinity();
    res.lo_rev_s = res.hi_rev_s = dir * hi;
    res.theta_deg = NAN;
    res.phenomenon = "no_separation";
    res.phenomenon_text = "no departure of the cam chain between " + num(lo) + " and " + num(hi) + " rev/s";
  } else {
    const Trial& t = *f[first_dep];
    res.hi_rev_s = t.t.speed_rev_s;
    res.lo_rev_s = first_dep > 0 ? f[first_dep - 1]->t.speed_rev_s : t.t.speed_rev_s;
    res.jump_speed_rev_s = 0.5 * (res.lo_rev_s + res.hi_rev_s);
    res.phenomenon_text = t.t.text;
    for (const std::string& k : t.t.kinds)
      if (is_departure_kind(k)) {
        res.phenomenon = k;
        res.theta_deg = t.first.at(k).second;
        break;
      }
    if (first_dep == 0)
      res.phenomenon_text += " (already at the lowest trial speed: the lowest separation speed may be lower)";
    for (std::size_t i = first_dep + 1; i < f.size(); ++i)
      if (!f[i]->departs()) {
        std::size_t j = i;
        while (j > 0 && !f[j - 1]->departs()) --j;
        res.monotone = false;
        res.monotone_text = "not monotone in speed: the cam chain departs at " + num(f[first_dep]->t.speed_rev_s) +
                            " rev/s but keeps contact again at " + num(f[i]->t.speed_rev_s) + " rev/s";
        break;
      }
  }
  return res;
}

}  // namespace detail

namespace {
std::string speed_text(double v, double rpm) {
  char b[96];
  if (rpm > 0) std::snprintf(b, sizeof b, "%.6g rev/s (%.6g rpm)", v, v * rpm);
  else std::snprintf(b, sizeof b, "%.6g rev/s", v);
  return b;
}
std::string bracket_text(double a, double b) {
  char t[96];
  std::snprintf(t, sizeof t, "[%.7g, %.7g]", std::min(a, b), std::max(a, b));
  return t;
}
}  // namespace

std::string speed_map_text(const JumpResult& r, double rpm) {
  std::string s;
  if (std::isfinite(r.jump_speed_rev_s))
    s += "lowest separation speed: " + speed_text(r.jump_speed_rev_s, rpm) + ", bracket " +
         bracket_text(r.lo_rev_s, r.hi_rev_s) + " rev/s (" + detail::kind_words(r.phenomenon) + ")\n";
  else
    s += "lowest separation speed: none in " + bracket_text(r.range_lo_rev_s, r.range_hi_rev_s) + " rev/s\n";
  for (const SpeedBand& b : r.bands) {
    char th[32];
    std::snprintf(th, sizeof th, "%.1f", b.theta_deg);
    s += std::string("  ") + detail::kind_words(b.kind) + " ('" + b.contact + "' at " + th + " deg): from ";
    s += std::isnan(b.from_out) ? "below " + speed_text(b.from_in, rpm) + " (the lowest trial)"
                                : speed_text(0.5 * (b.from_out + b.from_in), rpm) + " " + bracket_text(b.from_out, b.from_in);
    s += " to ";
    s += std::isnan(b.to_out) ? "above " + speed_text(b.to_in, rpm) + " (the highest trial)"
                              : speed_text(0.5 * (b.to_in + b.to_out), rpm) + " " + bracket_text(b.to_in, b.to_out);
    s += "\n";
  }
  if (r.bands.empty()) s += "  no phenomenon in the range\n";
  // the acceptance criteria over the trials: the lowest failing speed of each
  std::vector<std::string> names;
  for (const SpeedTrial& t : r.trials)
    for (const CriterionResult& c : t.criteria)
      if (std::find(names.begin(), names.end(), c.name) == names.end()) names.push_back(c.name);
  for (const std::string& n : names) {
    long judged = 0, failed = 0;
    double first = NAN;
    for (const SpeedTrial& t : r.trials)
      for (const CriterionResult& c : t.criteria)
        if (c.name == n && !std::isnan(c.value)) {
          ++judged;
          if (!c.pass) {
            ++failed;
            if (std::isnan(first) || std::abs(t.speed_rev_s) < std::abs(first)) first = t.speed_rev_s;
          }
        }
    s += "  criterion " + n + ": " + std::to_string(failed) + " of " + std::to_string(judged) + " judged trials fail" +
         (std::isnan(first) ? std::string() : ", first at " + speed_text(first, rpm)) + "\n";
  }
  if (!r.monotone) s += "WARNING: " + r.monotone_text + "\n";
  if (r.failed_simulations > 0) s += "WARNING: " + std::to_string(r.failed_simulations) + " trial(s) failed (left out)\n";
  return s;
}

std::string jump_speed_text(const JumpResult& r) {
  char b[160];
  if (!std::isfinite(r.jump_speed_rev_s)) return r.jump_speed_rev_s > 0 ? "+inf" : "-inf";
  if (r.method != "simulation") {
    std::snprintf(b, sizeof b, "%.10g rev/s (closed form)", r.jump_speed_rev_s);
    return b;
  }
  const double lo = std::min(r.lo_rev_s, r.hi_rev_s), hi = std::max(r.lo_rev_s, r.hi_rev_s);
  const double w = hi - lo, mid = 0.5 * (lo + hi);
  if (!(w > 0)) {
    std::snprintf(b, sizeof b, "%.17g rev/s, bracket [%.17g, %.17g] rev/s, width 0 rev/s", mid, lo, hi);
    return b;
  }
  const int p = int(std::floor(std::log10(w)));  // the decimal place of the width
  const double q0 = std::pow(10.0, p), q = q0 / 10.0;
  const double mid_r = std::round(mid / q0) * q0;                            // to the width's place
  const double lo_r = std::floor(lo / q + 1e-9) * q, hi_r = std::ceil(hi / q - 1e-9) * q;  // outwards, one place
  std::snprintf(b, sizeof b, "%.*f rev/s, bracket [%.*f, %.*f] rev/s, width %.2g rev/s", std::max(0, -p), mid_r,
                std::max(0, 1 - p), lo_r, std::max(0, 1 - p), hi_r, w);
  return b;
}

}  // namespace camdyn
