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

#include <csignal>
#include <signal.h>
#include <unistd.h>

#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn_cli {

using namespace camdyn;
namespace fs = std::filesystem;

namespace {

// ---- progress line ------------------------------------------------------------------------

class CliObserver : public StreamingHistoryWriter {
 public:
  /// Streams DIR/history.csv and DIR/events.csv in place (a killed run keeps its rows).
  CliObserver(const std::string& dir, std::vector<std::string> extra, bool show_progress)
      : StreamingHistoryWriter(dir, std::move(extra), std::size_t(1) << 16, Placement::InPlace),
        enabled_(show_progress) {}

  void on_row(const HistoryRow& r) override {
    StreamingHistoryWriter::on_row(r);
    last_t_ = r.t;
  }
  double last_t() const { return last_t_; }

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
  void erase_progress() {
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
  double last_t_ = 0;
};

/// The files a run (and its --plot) writes in DIR, and the temporary names of earlier runs
/// that were killed while writing them: removed before a run starts, so DIR never holds a
/// file of an earlier run next to the new run's files.
void remove_earlier_outputs(const std::string& dir) {
  static const char* const kNames[] = {
      "history.csv", "events.csv", "summary.json", "report.html", "displacement.png",
      "contact_force.png", "contact_force_zoom.png", "network_motion.png", "network_forces.png",
      "lift_deviation.png", "camshaft.png"};
  std::error_code ec;
  for (const char* name : kNames) {
    const fs::path p = join_path(dir, name);
    if (fs::is_regular_file(fs::symlink_status(p, ec)) && !fs::remove(p, ec) && ec)
      throw std::runtime_error("cannot remove '" + p.string() + "' of an earlier run: " + ec.message());
  }
  for (const auto& e : fs::directory_iterator(dir.empty() ? "." : dir, ec)) {
    const std::string f = e.path().filename().string();
    for (const char* stem : {"history.csv.tmp.", "events.csv.tmp.", "summary.json.tmp."})
      if (f.rfind(stem, 0) == 0) fs::remove(e.path(), ec);
  }
}

/// Blocks SIGINT, SIGTERM and SIGHUP while it lives: the final write completes, and a
/// signal that came meanwhile acts (the default action: the handler was reset) afterwards.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t s;
    sigemptyset(&s);
    sigaddset(&s, SIGINT);
    sigaddset(&s, SIGTERM);
    sigaddset(&s, SIGHUP);
    ::sigprocmask(SIG_BLOCK, &s, &old_);
  }
  ~SignalsBlocked() { ::sigprocmask(SIG_SETMASK, &old_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t old_;
};

constexpr const char* kStopPlaceholder = "interrupted (signal)";

}  // namespace

int cmd_run(const RunOpts& o) {
  // Input stage: every error here is bad input (exit 2, raised to main()).
  const ValidatedScene validated_scene = build_scene(o.c.scene_file, o.c.case_name, o.c.sets, default_scene());
  const Scene& sc = validated_scene.scene();
  ensure_output_dir(o.out);
  std::unique_ptr<Simulator> sim = checked_simulator(validated_scene);  // the checks `camdyn scene` makes
  // Implausible as a valve train (issue 28): said, not refused (also in summary.json).
  for (const std::string& w : sim->warnings()) std::fprintf(stderr, "camdyn: warning: %s\n", w.c_str());

  // Output stage, first part: DIR holds only this run's files from here on, and a
  // summary.json saying "running" until the run ends (a killed run leaves it so).
  std::unique_ptr<CliObserver> obs;
  try {
    remove_earlier_outputs(o.out);
    write_running_summary(o.out, sc);
    obs = std::make_unique<CliObserver>(o.out, sim->extra_columns(), !o.quiet && ::isatty(STDERR_FILENO));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: cannot write the output in '%s': %s\n", o.out.c_str(), e.what());
    return kExitFailed;
  }

  // Run stage: rows and events go to disk as they come (bounded memory).
  Summary summary;
  bool interrupted = false;
  {
    SigintGuard guard;
    try {
      // The signal is known only once it came: the run's message ends with this
      // placeholder, replaced below by stop_reason().
      summary = sim->run(obs.get(), &g_stop, kStopPlaceholder);
    } catch (const std::exception& e) {
      summary = Summary{};
      summary.scene = sc.title;
      summary.finished = false;
      summary.message = std::string("internal error: ") + e.what();
      summary.t_end = obs->last_t();
    } catch (...) {
      summary = Summary{};
      summary.scene = sc.title;
      summary.finished = false;
      summary.message = "internal error (unknown exception)";
      summary.t_end = obs->last_t();
    }
    interrupted = g_stop.load();
  }
  obs->erase_progress();
  // The run's own warnings (after the scene's, printed above).
  for (std::size_t i = sim->warnings().size(); i < summary.warnings.size(); ++i)
    std::fprintf(stderr, "camdyn: warning: %s\n", summary.warnings[i].c_str());
  if (summary.scene.empty()) summary.scene = sc.title;
  if (!summary.finished && summary.message.empty())
    summary.message = interrupted ? stop_reason() : "did not finish";
  {
    std::string& m = summary.message;
    const std::string ph = kStopPlaceholder;
    if (m.size() >= ph.size() && m.compare(m.size() - ph.size(), ph.size(), ph) == 0)
      m.replace(m.size() - ph.size(), ph.size(), stop_reason());
  }

  // Output stage, last part: the rest of the rows, then summary.json replaced atomically.
  // SIGINT/SIGTERM/SIGHUP wait until both are done.
  int rc = !summary.finished ? kExitFailed : summary.contract.held ? kExitOk : kExitContract;
  {
    SignalsBlocked hold;
    std::string error;
    try {
      obs->finish();
    } catch (const std::exception& e) {
      error = e.what();
      if (summary.finished) {
        summary.finished = false;
        summary.termination = Termination::Error;
        summary.message = "the output could not be written: " + error;
      }
    }
    try {
      write_summary(o.out, summary, sc);
    } catch (const std::exception& e) {
      if (error.empty()) error = e.what();
    }
    if (!error.empty()) {
      std::fprintf(stderr,
                   "camdyn: cannot write the output in '%s': %s (summary.json says \"%s\" if "
                   "it could not be replaced: the files are those of this run, incomplete)\n",
                   o.out.c_str(), error.c_str(), "running");
      rc = kExitFailed;
    }
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
  if (summary.finished && !summary.contract.held) {
    for (const std::string& v : summary.contract.violations)
      std::fprintf(stderr, "camdyn: contract not held: %s\n", v.c_str());
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
