// camdyn — command-line tool: `camdyn run`.
#include "commands.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <unistd.h>

#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn_cli {

using namespace camdyn;
namespace fs = std::filesystem;

namespace {

// ---- progress line ------------------------------------------------------------------------

class CliObserver : public HistoryWriter {
 public:
  explicit CliObserver(bool show_progress) : enabled_(show_progress) {}

  void on_progress(double t, double t_end, long steps) override {
    if (!enabled_) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (elapsed < 1.0) return;
    char eta[48];
    if (t > 0 && t_end > t && std::isfinite(t)) {
      const double rest = elapsed * (t_end - t) / t;
      if (rest < 120)
        std::snprintf(eta, sizeof eta, "%.0f s", rest);
      else if (rest < 7200)
        std::snprintf(eta, sizeof eta, "%.0f min", rest / 60);
      else
        std::snprintf(eta, sizeof eta, "%.1f h", rest / 3600);
    } else {
      std::snprintf(eta, sizeof eta, "?");
    }
    char line[200];
    int n = std::snprintf(line, sizeof line, "\r t = %.4g / %g s  steps %ld  ETA %s", t, t_end,
                          steps, eta);
    if (n < 0) return;
    int len = n - 1;  // without '\r'
    std::string out(line);
    if (len < width_) out.append(static_cast<size_t>(width_ - len), ' ');
    width_ = std::max(width_, len);
    std::fputs(out.c_str(), stderr);
    std::fflush(stderr);
  }

  /// Erase the progress line, if one was drawn.
  void finish() {
    if (width_ > 0) {
      std::fprintf(stderr, "\r%*s\r", width_, "");
      std::fflush(stderr);
      width_ = 0;
    }
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  Clock::time_point start_ = Clock::now();
  int width_ = 0;
};

constexpr const char* kStopPlaceholder = "interrupted (signal)";

}  // namespace

int cmd_run(const RunOpts& o) {
  // Input stage: every error here is bad input (exit 2, raised to main()).
  Scene sc = build_scene(o.c.scene_file, o.c.case_name, o.c.sets, default_scene());
  resolve_defaults(sc);
  validate(sc);
  ensure_output_dir(o.out);
  std::optional<Simulator> sim;
  try {
    sim.emplace(sc);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(sc.source, 0, "scene", sc.title, std::string("cannot build the model: ") +
                                                          e.what());
  }
  // Implausible as a valve train (issue 28): said, not refused (also in summary.json).
  for (const std::string& w : sim->warnings()) std::fprintf(stderr, "camdyn: warning: %s\n", w.c_str());

  // Run stage.
  const bool progress = !o.quiet && ::isatty(STDERR_FILENO);
  CliObserver obs(progress);
  obs.set_extra_columns(sim->extra_columns());
  Summary summary;
  bool interrupted = false;
  {
    SigintGuard guard;
    try {
      // The signal is known only once it came: the run's message ends with this
      // placeholder, replaced below by stop_reason().
      summary = sim->run(&obs, &g_stop, kStopPlaceholder);
    } catch (const std::exception& e) {
      summary = Summary{};
      summary.scene = sc.title;
      summary.finished = false;
      summary.message = std::string("internal error: ") + e.what();
      summary.t_end = obs.rows().empty() ? 0.0 : obs.rows().back().t;
      summary.events = obs.events();
    } catch (...) {
      summary = Summary{};
      summary.scene = sc.title;
      summary.finished = false;
      summary.message = "internal error (unknown exception)";
      summary.t_end = obs.rows().empty() ? 0.0 : obs.rows().back().t;
      summary.events = obs.events();
    }
    interrupted = g_stop.load();
  }
  obs.finish();
  if (summary.scene.empty()) summary.scene = sc.title;
  if (!summary.finished && summary.message.empty())
    summary.message = interrupted ? stop_reason() : "did not finish";
  {
    std::string& m = summary.message;
    const std::string ph = kStopPlaceholder;
    if (m.size() >= ph.size() && m.compare(m.size() - ph.size(), ph.size(), ph) == 0)
      m.replace(m.size() - ph.size(), ph.size(), stop_reason());
  }

  // Output stage: always write what was computed.
  int rc = summary.finished ? kExitOk : kExitFailed;
  try {
    obs.write(o.out);
    write_summary(o.out, summary, sc);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: cannot write the output in '%s': %s\n", o.out.c_str(),
                 e.what());
    rc = kExitFailed;
  }

  if (!o.quiet) {
    std::string report;
    try {
      report = summary.BriefReport();
    } catch (const std::exception&) {
      report.clear();
    }
    if (!report.empty()) {
      std::fputs(report.c_str(), stdout);
      if (report.back() != '\n') std::fputc('\n', stdout);
    }
    std::printf("output: %s, %s, %s\n", join_path(o.out, "history.csv").c_str(),
                join_path(o.out, "events.csv").c_str(),
                join_path(o.out, "summary.json").c_str());
    std::fflush(stdout);
  }
  if (!summary.finished) {
    // The simulator's message may already start with "at t = ...": do not repeat it.
    const std::string& m = summary.message;
    const std::string where = m.rfind("at t =", 0) == 0 || m.rfind("at t=", 0) == 0
                                  ? m
                                  : "at t = " + fmt_g(summary.t_end, 8) + ": " + m;
    std::fprintf(stderr, "camdyn: %s %s\n",
                 interrupted ? "simulation interrupted" : "simulation failed", where.c_str());
  }

  if (o.plot) {
    std::string why;
    std::vector<std::string> args{"run", o.out, "--quiet"};  // listed below, once
    const int prc = run_plot_script(args, &why);
    if (prc != 0) {
      std::fprintf(stderr, "camdyn: warning: no figures drawn: %s\n", why.c_str());
    } else if (!o.quiet) {
      std::printf("figures: %s, %s, %s\n", join_path(o.out, "displacement.png").c_str(),
                  join_path(o.out, "contact_force.png").c_str(),
                  join_path(o.out, "contact_force_zoom.png").c_str());
    }
    if (prc == 0 && write_report(o.out, true, &why) != 0)
      std::fprintf(stderr, "camdyn: warning: no report written: %s\n", why.c_str());
    else if (prc == 0 && !o.quiet)
      std::printf("report: %s\n", join_path(o.out, "report.html").c_str());
  }
  return rc;
}

}  // namespace camdyn_cli
