// camdyn — tolerance sweep (bench_tolerance.hpp, issue 25).
#include "study/bench_tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "study/bench_compare.hpp"
#include "camdyn/output.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {

using namespace bench_detail;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

const std::vector<std::pair<std::string, ContactModel>>& method_names() {
  static const std::vector<std::pair<std::string, ContactModel>> m{
      {"lee", ContactModel::Lee},
      {"event", ContactModel::Event},
      {"holonomic", ContactModel::Holonomic},
      {"penalty", ContactModel::Penalty}};
  return m;
}
const std::vector<std::pair<std::string, Integrator>>& engine_names() {
  static const std::vector<std::pair<std::string, Integrator>> e{
      {"arkode-erk", Integrator::ArkodeErk},
      {"arkode-dirk", Integrator::ArkodeDirk},
      {"cvode-bdf", Integrator::CvodeBdf},
      {"ida", Integrator::Ida}};
  return e;
}

template <class T>
std::vector<std::pair<std::string, T>> pick(const std::vector<std::pair<std::string, T>>& all,
                                            const std::vector<std::string>& names,
                                            const char* what) {
  if (names.empty()) return all;
  std::vector<std::pair<std::string, T>> out;
  for (const auto& n : names) {
    auto it = std::find_if(all.begin(), all.end(), [&](const auto& p) { return p.first == n; });
    if (it == all.end()) {
      std::string allowed;
      for (const auto& p : all) allowed += (allowed.empty() ? "" : ", ") + p.first;
      throw SceneError("bench", 0, what, n, "must be one of " + allowed);
    }
    out.push_back(*it);
  }
  return out;
}

/// A reference of one contact model on one scene: the tight run, the comparison set-up on
/// the scene's grid, and the floors (its own error against the run one decade looser).
struct Reference {
  bool ok = false;
  std::string what;  // "event arkode-erk rtol 1e-12 atol 1e-14"
  SceneInfo si;
  double floor_u = kNaN, floor_f = kNaN;
};

/// The run of `base` with `model` on `eng` at `rtol` (tol_u = ratio·rtol, atol =
/// min(base atol, 1e-3·rtol)).
Scene configure(const Scene& base, ContactModel model, Integrator eng, double rtol,
                double tol_ratio) {
  Scene s = base;
  s.contact.model = model;
  s.solver.integrator = eng;
  s.solver.rtol = rtol;
  s.solver.atol = std::min(base.solver.atol, 1e-3 * rtol);
  if (model == ContactModel::Lee) {
    s.contact.tol_u = tol_ratio * rtol;
    s.contact.tol_v = 0;
    s.contact.tol_a = 0;
  }
  return s;
}

class Sweep {
 public:
  explicit Sweep(const ToleranceSweepOptions& o) : o_(o) {}

  void log(const std::string& s) const {
    if (o_.log) o_.log(s);
  }

  /// The reference of `model` on the scene (made once): event-driven (Lee's and the event
  /// method's), holonomic, or penalty, at options' reference_rtol (1e-12) and atol 1e-2 of
  /// it: arkode-erk on a rigid
  /// follower (contact phases closed form), cvode-bdf otherwise (the bar is stiff).
  Reference& reference(const std::string& label, const Scene& base, ContactModel model) {
    const ContactModel key = model == ContactModel::Lee ? ContactModel::Event : model;
    auto& slot = refs_[label + "/" + to_string(key)];
    if (!slot.what.empty()) return slot;
    const bool rigid = base.follower.kind == FollowerKind::Rigid;
    Scene ref = base;
    ref.contact.model = key;
    ref.solver.integrator = rigid ? Integrator::ArkodeErk : Integrator::CvodeBdf;
    ref.solver.rtol = o_.reference_rtol;
    ref.solver.atol = 1e-2 * o_.reference_rtol;
    slot.what = std::string(to_string(key)) + " " + to_string(ref.solver.integrator) +
                " rtol " + g3(ref.solver.rtol) + " atol " + g3(ref.solver.atol);
    // On the finest grid (1e-4); the scene's common grid is a multiple of it, chosen by
    // the first reference as `camdyn bench` does (1e-2 rigid, 1e-3 if it separates, 1e-4
    // elastic or network).
    ref.run.output_dt = 1e-4;
    Run rr = run_once(ref, 0.0, true);
    const double dt = dt_.count(label) ? dt_[label]
                                       : (!rigid ? 1e-4 : rr.sum.separations > 0 ? 1e-3 : 1e-2);
    dt_[label] = dt;
    ref.run.output_dt = dt;
    ToleranceRow row;
    row.scene = label;
    row.method = std::string("reference ") + to_string(key);
    row.engine = to_string(ref.solver.integrator);
    row.rtol = ref.solver.rtol;
    row.atol = ref.solver.atol;
    row.cpu_seconds = rr.sum.cpu_seconds;
    row.steps = rr.sum.steps;
    row.status = "reference";
    slot.ok = rr.sum.finished && setup_scene_info(slot.si, ref, rr, dt);
    if (!slot.ok) {
      row.message = "reference failed: " + rr.sum.message + "; its series are not compared";
      rows_.push_back(row);
      log("  " + row.message);
      return slot;
    }
    // Its own error: the same run one decade looser, compared with it.
    Scene chk = ref;
    chk.run.output_dt = 1e-4;
    chk.solver.rtol = 10 * ref.solver.rtol;
    chk.solver.atol = 10 * ref.solver.atol;
    Run rc = run_once(chk, 0.0, true);
    double umax = 0;
    for (double u : slot.si.ref.u) umax = std::max(umax, std::fabs(u));
    slot.floor_u = 4 * kEps * umax;
    slot.floor_f = 4 * kEps;
    if (rc.sum.finished) {
      Grid g = to_grid(rc.rows, dt, slot.si.n);
      add_kicks(g, rc.events, dt);
      if (complete(g)) {
        const Comparison c = compare(slot.si, g, rc.events);
        slot.floor_u = std::max(slot.floor_u, c.err_u);
        slot.floor_f = std::max(slot.floor_f, c.err_force);
      }
    }
    row.message = "output grid " + g3(dt) + "; floors (its distance to rtol " + g3(chk.solver.rtol) + ", at least 4 ulps): err_u " +
                  g3(slot.floor_u) + ", err_force " + g3(slot.floor_f);
    rows_.push_back(row);
    log("  reference " + slot.what + ": cpu " + g3(rr.sum.cpu_seconds) + " s; " + row.message);
    return slot;
  }

  void series(const std::string& label, const Scene& base, const std::string& mname,
              ContactModel model, const std::string& ename, Integrator eng,
              const std::vector<double>& rtols, double tol_ratio) {
    ToleranceRow proto;
    proto.scene = label;
    proto.method = mname;
    proto.engine = ename;
    // Does the scene allow this method on this engine at all (at a loose tolerance)?
    try {
      const Scene loose = configure(base, model, eng, 1e-4, tol_ratio);
      validate(loose);
      Simulator probe(loose);  // the checks made at the start (e.g. ida on a network)
    } catch (const SceneError& e) {
      ToleranceRow row = proto;
      row.status = "unsupported";
      row.message = e.what();
      rows_.push_back(row);
      return;
    }
    Reference& ref = reference(label, base, model);
    std::vector<double> eu, ef;
    std::string blown;
    for (double rtol : rtols) {
      ToleranceRow row = proto;
      Scene s = configure(base, model, eng, rtol, tol_ratio);
      s.run.output_dt = dt_[label];
      row.rtol = rtol;
      row.atol = s.solver.atol;
      if (model == ContactModel::Lee) row.tol_u = s.contact.tol_u;
      eu.push_back(kNaN);
      ef.push_back(kNaN);
      if (!blown.empty()) {
        row.status = "skipped";
        row.message = blown;
        rows_.push_back(row);
        continue;
      }
      try {
        validate(s);
        Simulator probe(s);  // the checks made at the start of a run
      } catch (const SceneError& e) {
        row.status = "refused";
        row.message = e.what();
        rows_.push_back(row);
        log("  " + label + " " + mname + " " + ename + " rtol " + g3(rtol) + ": refused: " + row.message);
        continue;
      }
      Run r = run_once(s, o_.time_budget_seconds, true);
      row.cpu_seconds = r.sum.cpu_seconds;
      row.steps = r.sum.steps;
      if (r.sum.contract.checked) row.contract_held = r.sum.contract.held ? 1 : 0;
      if (r.over_budget) {
        row.status = "over budget";
        row.message = "stopped at t = " + g3(r.sum.t_end) + " (budget " + g3(o_.time_budget_seconds) + " s CPU)";
        blown = "after rtol " + g3(rtol) + " took over the " + g3(o_.time_budget_seconds) + " s budget";
      } else if (!r.sum.finished) {
        row.status = "failed";
        row.message = r.sum.message;
      } else if (!ref.ok) {
        row.status = "finished";
        row.message = "no reference";
      } else {
        Grid g = to_grid(r.rows, ref.si.dt, ref.si.n);
        add_kicks(g, r.events, ref.si.dt);
        row.status = "finished";
        if (!complete(g)) {
          row.message = "rows do not land on the output grid";
        } else {
          const Comparison c = compare(ref.si, g, r.events);
          row.err_u = eu.back() = c.err_u;
          row.err_force = ef.back() = c.err_force;
          if (!ref.si.ref_events.empty() && c.events != long(ref.si.ref_events.size()))
            row.message = std::to_string(c.events) + " separations+impacts (reference " +
                          std::to_string(ref.si.ref_events.size()) + ")";
        }
      }
      log("  " + label + " " + mname + " " + ename + " rtol " + g3(rtol) + ": " + row.status +
          ", cpu " + g3(row.cpu_seconds) + " s, err_u " + g3(row.err_u) + ", err_F " +
          g3(row.err_force) + (row.message.empty() ? "" : "  [" + row.message + "]"));
      rows_.push_back(row);
    }
    for (int q = 0; q < 2; ++q) {
      SeriesCheck c = check_series(rtols, q == 0 ? eu : ef, q == 0 ? ref.floor_u : ref.floor_f);
      c.scene = label;
      c.method = mname;
      c.engine = ename;
      c.quantity = q == 0 ? "err_u" : "err_force";
      checks_.push_back(c);
    }
  }

  void scene(const std::string& label, Scene base) {
    resolve_defaults(base);
    if (o_.t_end > 0) base.run.t_end = o_.t_end;
    validate(base);
    const bool heavy = base.follower.kind != FollowerKind::Rigid;
    const std::vector<double>& rtols = heavy && !o_.heavy_rtols.empty() ? o_.heavy_rtols : o_.rtols;
    const double ratio = base.contact.tol_u / base.solver.rtol;
    log("scene " + label + ": " + base.title + ", t_end " + g3(base.run.t_end) + ", tol_u = " +
        g3(ratio) + " rtol");
    for (const auto& m : pick(method_names(), o_.methods, "method"))
      for (const auto& e : pick(engine_names(), o_.engines, "engine"))
        series(label, base, m.first, m.second, e.first, e.second, rtols, ratio);
  }

  ToleranceSweepOptions o_;
  std::vector<ToleranceRow> rows_;
  std::vector<SeriesCheck> checks_;
  std::map<std::string, Reference> refs_;
  std::map<std::string, double> dt_;
};

}  // namespace

SeriesCheck check_series(const std::vector<double>& rtols, const std::vector<double>& errs,
                         double floor) {
  SeriesCheck c;
  c.floor = floor;
  const double fl = std::isfinite(floor) ? floor : 0.0;
  std::string bad;
  double prev = kNaN, prev_rtol = kNaN;
  for (size_t i = 0; i < errs.size() && i < rtols.size(); ++i) {
    const double e = errs[i];
    if (!std::isfinite(e)) continue;
    ++c.finished;
    if (!(e >= c.err_min)) c.err_min = e;  // NaN-safe min
    if (std::isfinite(prev) && e > 2 * std::max(prev, fl)) {
      c.monotone = false;
      bad += (bad.empty() ? "" : "; ") + std::string("rises from ") + g3(prev) + " at rtol " +
             g3(prev_rtol) + " to " + g3(e) + " at rtol " + g3(rtols[i]);
    }
    prev = e;
    prev_rtol = rtols[i];
  }
  if (c.finished == 0) {
    c.verdict = "no finished run";
    return c;
  }
  for (size_t i = 0; i < errs.size() && i < rtols.size(); ++i)
    if (std::isfinite(errs[i]) && errs[i] <= 2 * c.err_min) {
      c.rtol_level = rtols[i];
      break;
    }
  c.reaches_floor = c.err_min <= 10 * fl;
  c.verdict = (c.monotone ? std::string("falls (within a factor 2)") : "NOT MONOTONE: " + bad) +
              "; levels off at " + g3(c.err_min) + " from rtol " + g3(c.rtol_level) + " (" +
              (c.reaches_floor ? "at the floor " : "above the floor ") + g3(floor) + ")";
  return c;
}

const std::vector<std::string>& tolerance_sweep_columns() {
  static const std::vector<std::string> c{"scene",   "method", "engine", "rtol",  "tol_u",
                                          "atol",    "cpu_s",  "steps",  "err_u", "err_force",
                                          "status", "message", "contract_held"};
  return c;
}

std::string tolerance_sweep_csv(const std::vector<ToleranceRow>& rows) {
  std::string s;
  for (const auto& c : tolerance_sweep_columns()) s += (s.empty() ? "" : ",") + c;
  s += "\n";
  for (const auto& r : rows)
    s += csv_text(r.scene) + "," + r.method + "," + r.engine + "," + csv_num(r.rtol) + "," +
         csv_num(r.tol_u) + "," + csv_num(r.atol) + "," + csv_num(r.cpu_seconds) + "," +
         std::to_string(r.steps) + "," + csv_num(r.err_u) + "," + csv_num(r.err_force) + "," +
         r.status + "," + csv_text(r.message) + "," + (r.contract_held < 0 ? "" : std::to_string(r.contract_held)) +
         "\n";
  return s;
}

ToleranceSweepResult run_tolerance_sweep(const ToleranceSweepOptions& options) {
  ToleranceSweepOptions o = options;
  if (o.labels.size() != o.scenes.size())
    throw SceneError("bench", 0, "labels", std::to_string(o.labels.size()),
                     "must be one per scene (" + std::to_string(o.scenes.size()) + ")");
  if (!(o.time_budget_seconds > 0))
    throw SceneError("bench", 0, "budget", g3(o.time_budget_seconds), "must be > 0 seconds");
  if (!(o.t_end >= 0) || !std::isfinite(o.t_end))
    throw SceneError("bench", 0, "t_end", g3(o.t_end), "must be >= 0 (0: the scene's)");
  for (const auto* grid : {&o.rtols, &o.heavy_rtols})
    for (double r : *grid)
      if (!(r >= 1e-14 && r <= 0.1))
        throw SceneError("bench", 0, "rtol", g3(r), "must be in [1e-14, 0.1]");
  if (!(o.reference_rtol >= 1e-14 && o.reference_rtol <= 1e-6))
    throw SceneError("bench", 0, "reference_rtol", g3(o.reference_rtol), "must be in [1e-14, 1e-6]");
  if (o.rtols.empty()) throw SceneError("bench", 0, "rtols", "(none)", "must not be empty");
  pick(method_names(), o.methods, "method");
  pick(engine_names(), o.engines, "engine");
  ensure_output_dir(o.out_dir);

  Sweep sw(o);
  for (size_t i = 0; i < o.scenes.size(); ++i) sw.scene(o.labels[i], o.scenes[i]);

  ToleranceSweepResult res;
  res.rows = std::move(sw.rows_);
  res.checks = std::move(sw.checks_);
  res.csv_path = join_path(o.out_dir, "tol_sweep.csv");
  res.series_path = join_path(o.out_dir, "tol_sweep_series.csv");
  res.md_path = join_path(o.out_dir, "tol_sweep.md");
  write_file_atomic(res.csv_path, tolerance_sweep_csv(res.rows));

  std::string sc = "scene,method,engine,quantity,floor,err_min,rtol_level,finished,monotone,reaches_floor,verdict\n";
  for (const auto& c : res.checks)
    sc += csv_text(c.scene) + "," + c.method + "," + c.engine + "," + c.quantity + "," +
          csv_num(c.floor) + "," + csv_num(c.err_min) + "," + csv_num(c.rtol_level) + "," +
          std::to_string(c.finished) + "," + (c.monotone ? "1" : "0") + "," +
          (c.reaches_floor ? "1" : "0") + "," + csv_text(c.verdict) + "\n";
  write_file_atomic(res.series_path, sc);

  std::ostringstream md;
  md << "# camdyn tolerance sweep\n\n"
     << "tol_u = (scene's tol_u/rtol) · rtol, atol = min(scene atol, 1e-3 rtol); CPU budget "
     << g3(o.time_budget_seconds) << " s per run (timed once). Errors against the reference "
        "of the same contact model (rows `reference …`: event-driven for lee and event; rtol "
     << g3(o.reference_rtol) << ") on the scene's output grid. A series is monotone when no finished run's error exceeds "
        "2 × max(the previous finished run's, the floor); the floor is the reference's own "
        "error (its distance to the same run at 10 × its rtol and atol), at least 4 ulps.\n\n";
  for (size_t i = 0; i < o.labels.size(); ++i) {
    md << "## " << o.labels[i] << "\n\n| method | engine | quantity | floor | levels off at | "
       << "from rtol | finished | verdict |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& c : res.checks)
      if (c.scene == o.labels[i])
        md << "| " << c.method << " | " << c.engine << " | " << c.quantity << " | "
           << g3(c.floor) << " | " << g3(c.err_min) << " | " << g3(c.rtol_level) << " | "
           << c.finished << " | " << (c.monotone ? "" : "**") << c.verdict
           << (c.monotone ? "" : "**") << " |\n";
    md << "\nNot finished:\n\n";
    for (const auto& r : res.rows)
      if (r.scene == o.labels[i] && r.status != "finished" && r.status != "reference")
        md << "- " << r.method << " " << r.engine << " rtol " << g3(r.rtol) << ": " << r.status
           << (r.message.empty() ? "" : " — " + r.message) << "\n";
    md << "\n";
  }
  write_file_atomic(res.md_path, md.str());
  return res;
}

}  // namespace camdyn
