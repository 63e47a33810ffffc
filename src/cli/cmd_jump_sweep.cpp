// camdyn — command-line tool: `camdyn jump` and `camdyn sweep`.
#include "commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "camdyn/designer.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "sweep_mpi.hpp"

namespace camdyn_cli {

using namespace camdyn;
namespace fs = std::filesystem;

namespace {

std::string band_json(const SpeedBand& b) {
  return "{\"kind\": " + json_string(b.kind) + ", \"contact\": " + json_string(b.contact) +
         ", \"theta_deg\": " + json_number(b.theta_deg) + ", \"from_out_rev_s\": " + json_number(b.from_out) +
         ", \"from_in_rev_s\": " + json_number(b.from_in) + ", \"to_in_rev_s\": " + json_number(b.to_in) +
         ", \"to_out_rev_s\": " + json_number(b.to_out) + "}";
}

std::string trial_json(const SpeedTrial& t) {
  std::string k;
  for (const std::string& x : t.kinds) k += (k.empty() ? "" : ", ") + json_string(x);
  std::string c;
  for (const CriterionResult& x : t.criteria)
    c += (c.empty() ? "" : ", ") + std::string("{\"name\": ") + json_string(x.name) + ", \"value\": " +
         json_number(x.value) + ", \"limit\": " + json_number(x.limit) + ", \"theta_deg\": " +
         json_number(x.theta_deg) + ", \"pass\": " + (x.pass ? "true" : "false") + "}";
  return "{\"speed_rev_s\": " + json_number(t.speed_rev_s) + ", \"finished\": " + (t.finished ? "true" : "false") +
         ", \"kinds\": [" + k + "], \"text\": " + json_string(t.text) + ", \"criteria\": [" + c + "]}";
}

}  // namespace

int cmd_jump(const JumpOpts& o) {
  Scene sc = required_scene("jump", o.c);
  if (o.jobs < 0) throw SceneError("--jobs", 0, "jobs", std::to_string(o.jobs), "must be >= 0 (0: all cores)");
  JumpOptions jo;
  jo.rel_tol = o.rel_tol;
  jo.lo_rev_s = o.lo;
  jo.hi_rev_s = o.hi;
  jo.grid_points = o.points;
  jo.jobs = o.jobs;
  jo.force_simulation = o.simulate;
  if (!o.quiet)
    jo.log = [](double sp, bool sep) {
      std::fprintf(stderr, "  %.10g rev/s: %s\n", sp, sep ? "departs" : "keeps contact");
      std::fflush(stderr);
    };
  ensure_output_dir(o.out);
  JumpResult r;
  {
    SigintGuard guard;
    r = jump_speed(sc, jo);  // SceneError → exit 2; a failing trial is reported as such
  }
  const bool sim = r.method == "simulation";
  const std::string path = join_path(o.out, "jump.json");
  std::string j = "{\n  \"scene\": " + json_string(sc.title) +
                  ",\n  \"jump_speed_rev_s\": " + json_number(r.jump_speed_rev_s) +
                  ",\n  \"method\": " + json_string(r.method) +
                  ",\n  \"theta_deg\": " + json_number(r.theta_deg) +
                  ",\n  \"phenomenon\": " + json_string(r.phenomenon) +
                  ",\n  \"phenomenon_text\": " + json_string(r.phenomenon_text) +
                  ",\n  \"jump_speed_text\": " + json_string(jump_speed_text(r));
  if (sc.rpm_per_rev_s > 0)  // the scene speaks rpm (cam.speed_rpm, cam.rpm_of)
    j += ",\n  \"rpm_per_rev_s\": " + json_number(sc.rpm_per_rev_s) + ",\n  \"jump_speed_rpm\": " +
         json_number(r.jump_speed_rev_s * sc.rpm_per_rev_s);
  if (sim) {
    j += ",\n  \"lo_rev_s\": " + json_number(r.lo_rev_s) + ",\n  \"hi_rev_s\": " +
         json_number(r.hi_rev_s) + ",\n  \"bracket_width_rev_s\": " +
         json_number(std::abs(r.hi_rev_s - r.lo_rev_s)) + ",\n  \"rel_tol\": " + json_number(o.rel_tol) +
         ",\n  \"simulations\": " + std::to_string(r.simulations) +
         ",\n  \"grid_simulations\": " + std::to_string(r.grid_simulations) +
         ",\n  \"failed_simulations\": " + std::to_string(r.failed_simulations) +
         ",\n  \"settle_revolutions\": " + std::to_string(sc.jump.settle_revolutions) +
         ",\n  \"judge_revolutions\": " + std::to_string(sc.jump.judge_revolutions) +
         ",\n  \"range_lo_rev_s\": " + json_number(r.range_lo_rev_s) +
         ",\n  \"range_hi_rev_s\": " + json_number(r.range_hi_rev_s) +
         ",\n  \"grid_spacing_rev_s\": " + json_number(r.grid_spacing_rev_s) +
         ",\n  \"monotone\": " + (r.monotone ? "true" : "false") +
         ",\n  \"monotone_text\": " + json_string(r.monotone_text) + ",\n  \"bands\": [";
    for (std::size_t i = 0; i < r.bands.size(); ++i) j += (i ? ",\n    " : "\n    ") + band_json(r.bands[i]);
    j += r.bands.empty() ? "]" : "\n  ]";
    j += ",\n  \"trials\": [";
    for (std::size_t i = 0; i < r.trials.size(); ++i) j += (i ? ",\n    " : "\n    ") + trial_json(r.trials[i]);
    j += r.trials.empty() ? "]" : "\n  ]";
  }
  j += "\n}\n";
  int rc = kExitOk;
  try {
    write_file_atomic(path, j);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: cannot write '%s': %s\n", path.c_str(), e.what());
    rc = kExitFailed;
  }
  const std::string rpm_text =
      sc.rpm_per_rev_s > 0 && std::isfinite(r.jump_speed_rev_s)
          ? " = " + fmt_g(r.jump_speed_rev_s * sc.rpm_per_rev_s, 6) +
                (sc.rpm_per_rev_s == 120 ? " engine rpm" : " camshaft rpm")
          : std::string();
  if (!o.quiet) {
    if (sim) {
      std::printf("%s: speed-range map over [%s, %s] rev/s: %d trials (%d on the grid, spacing %s rev/s), "
                  "%ld + %ld revolutions each\n",
                  sc.title.c_str(), fmt_g(r.range_lo_rev_s, 7).c_str(), fmt_g(r.range_hi_rev_s, 7).c_str(),
                  r.simulations, r.grid_simulations, fmt_g(r.grid_spacing_rev_s, 4).c_str(),
                  sc.jump.settle_revolutions, sc.jump.judge_revolutions);
      std::printf("%s", speed_map_text(r, sc.rpm_per_rev_s).c_str());
      std::printf("jump speed: %s%s\nphenomenon: %s (%s)", jump_speed_text(r).c_str(), rpm_text.c_str(),
                  r.phenomenon.c_str(), r.phenomenon_text.c_str());
    } else {
      std::printf("%s: %s, margin reaches zero at cam angle %s deg", sc.title.c_str(), r.method.c_str(),
                  fmt_g(r.theta_deg, 10).c_str());
      std::printf("\njump speed: %s%s\nphenomenon: %s (%s)", jump_speed_text(r).c_str(), rpm_text.c_str(),
                  r.phenomenon.c_str(), r.phenomenon_text.c_str());
    }
    std::printf("\noutput: %s\n", path.c_str());
  }
  std::printf("jump_speed_rev_s = %.17g\n", r.jump_speed_rev_s);
  std::fflush(stdout);
  return rc;
}

namespace {

class SweepProgress {
 public:
  explicit SweepProgress(bool on) : on_(on), tty_(::isatty(STDERR_FILENO) != 0) {}
  void operator()(long done, long total, long failed, double elapsed) {
    if (!on_) return;
    if (first_ < 0) first_ = done - 1;
    const long computed = done - first_;
    const double now = elapsed;
    if (tty_ && now - last_ < 0.2 && done < total) return;
    if (!tty_ && done * 10 / total == last_decile_ && done < total) return;
    last_ = now;
    last_decile_ = done * 10 / total;
    char eta[48] = "?";
    if (computed > 0 && done < total) {
      const double rest = now / double(computed) * double(total - done);
      if (rest < 120) std::snprintf(eta, sizeof eta, "%.0f s", rest);
      else if (rest < 7200) std::snprintf(eta, sizeof eta, "%.0f min", rest / 60);
      else std::snprintf(eta, sizeof eta, "%.1f h", rest / 3600);
    } else if (done >= total) {
      std::snprintf(eta, sizeof eta, "done");
    }
    char line[200];
    const int n = std::snprintf(line, sizeof line, " sweep: %ld/%ld points, %ld failed, ETA %s",
                                done, total, failed, eta);
    if (tty_) {
      std::fprintf(stderr, "\r%s%*s", line, std::max(0, width_ - n), "");
      width_ = std::max(width_, n);
    } else {
      std::fprintf(stderr, "%s\n", line);
    }
    std::fflush(stderr);
  }
  void finish() {
    if (tty_ && width_ > 0) std::fprintf(stderr, "\r%*s\r", width_, "");
    std::fflush(stderr);
  }

 private:
  bool on_, tty_;
  long first_ = -1, last_decile_ = -1;
  double last_ = -1;
  int width_ = 0;
};

}  // namespace

int cmd_sweep(const SweepOpts& o) {
  Scene sc = required_scene("sweep", o.c);
  if (o.jobs < 0) throw SceneError("--jobs", 0, "jobs", std::to_string(o.jobs), "must be >= 1 (0: all cores)");
  SweepOptions so;
  so.axes.push_back(make_sweep_axis(sc, o.a1.key, o.a1.from, o.a1.to, o.a1.step, o.a1.points, o.a1.log));
  if (!o.a2.key.empty()) {
    try {
      so.axes.push_back(make_sweep_axis(sc, o.a2.key, o.a2.from, o.a2.to, o.a2.step, o.a2.points, o.a2.log));
    } catch (const SceneError& e) {  // name the second axis' options: --from2, key 'to2', ...
      throw SceneError(e.file() + "2", 0, e.key() + "2", e.value(), e.rule());
    }
  } else if (!std::isnan(o.a2.from) || !std::isnan(o.a2.to) || !std::isnan(o.a2.step) || o.a2.points != 0 ||
             o.a2.log) {
    throw SceneError("--key2", 0, "key2", "", "--from2/--to2/--step2/--points2/--log2 need --key2 KEY");
  }
  so.jobs = o.jobs;
  so.out_dir = o.out;
  so.resume = o.resume;
  so.timing = !o.no_timing;
  so.point_timeout_seconds = o.timeout;
  so.stop = &g_stop;
  SweepProgress progress(!o.quiet);
  so.progress = [&progress](long d, long t, long f, double e) { progress(d, t, f, e); };
  so.validate();
  SweepResult res;
  bool master = true;
  {
    SigintGuard guard;
    if (camdyn_cli::launched_under_mpi())
      res = camdyn_cli::run_sweep_mpi(sc, so, &master);
    else
      res = run_sweep(sc, so);
  }
  progress.finish();
  if (!master) return kExitOk;
  if (!o.quiet) {
    const std::string by = signal_name().empty() ? "" : " by " + signal_name();
    const std::string tail = res.interrupted ? " — INTERRUPTED" + by + " (run again with --resume)" : "";
    std::printf("sweep: %ld points (%ld computed, %ld from the journal), %ld failed%s\n", res.total,
                res.computed, res.skipped, res.failed, tail.c_str());
    std::printf("output: %s, %s\n", res.csv_path.c_str(), res.poincare_path.c_str());
    try {
      for (const SweepCriterion& c : sweep_criteria_table(res.csv_path))
        std::printf("criterion %s: %ld of %ld judged points fail%s\n", c.name.c_str(), c.failed, c.judged,
                    std::isnan(c.first_failure)
                        ? ""
                        : (", first at " + o.a1.key + " = " + fmt_g(c.first_failure, 10)).c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "camdyn: warning: %s\n", e.what());
    }
    std::fflush(stdout);
  }
  if (o.plot) {
    std::string why;
    const std::string script = sweep_plot_script_path();
    if (script.empty()) {
      std::fprintf(stderr, "camdyn: warning: no figures drawn: camdyn_sweep_plot.py not found\n");
    } else if (run_plot_script({o.out, "--quiet"}, &why, script) != 0) {
      std::fprintf(stderr, "camdyn: warning: no figures drawn: %s\n", why.c_str());
    } else {
      if (!o.quiet) std::printf("figures: %s\n", join_path(o.out, "sweep_*.png").c_str());
      if (write_report(o.out, true, &why) != 0)
        std::fprintf(stderr, "camdyn: warning: no report written: %s\n", why.c_str());
      else if (!o.quiet)
        std::printf("report: %s\n", join_path(o.out, "report.html").c_str());
    }
  }
  return res.interrupted ? kExitFailed : kExitOk;
}

}  // namespace camdyn_cli
