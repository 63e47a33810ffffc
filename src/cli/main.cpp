// camdyn — command-line tool (docs/interface.md "Command line").
//
//   camdyn run   [SCENE.toml] [--out DIR] [--set KEY=VALUE]... [--quiet] [--plot]
//   camdyn cam   [SCENE.toml] [--out DIR] [--points N] [--set KEY=VALUE]...
//   camdyn scene [SCENE.toml] [--resolved] [--set KEY=VALUE]...   camdyn scene --keys [--json]
//   camdyn plot  DIR [--zoom T0 T1]
//   camdyn report DIR
//   camdyn bench [SCENE ...] [--out DIR] [--quick] [--repeats N]
//   camdyn jump  SCENE [--set KEY=VALUE]... [--out DIR] [--simulate] [--rel-tol R]
//   camdyn sweep SCENE --key KEY --from A --to B (--step S | --points N [--log])
//                [--key2 ...] [--jobs N] [--resume] [--out DIR] [--plot] [--quiet]
//
// Exit status: 0 success; 1 the simulation (or a figure) failed; 2 bad input.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <map>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "camdyn/bench.hpp"
#include "camdyn/bench_tolerance.hpp"
#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/scene_keys.hpp"
#include "camdyn/simulator.hpp"
#include "sweep_mpi.hpp"

#ifndef CAMDYN_PLOT_SCRIPT_BUILD
#define CAMDYN_PLOT_SCRIPT_BUILD ""
#endif
#ifndef CAMDYN_PLOT_SCRIPT_INSTALL
#define CAMDYN_PLOT_SCRIPT_INSTALL ""
#endif

namespace {

using namespace camdyn;
namespace fs = std::filesystem;

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitBadInput = 2;

// ---- Ctrl-C -------------------------------------------------------------------------------

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};  // the signal that set g_stop (SIGINT or SIGTERM)
static_assert(std::atomic<bool>::is_always_lock_free, "signal handler needs a lock-free flag");
static_assert(std::atomic<int>::is_always_lock_free, "signal handler needs a lock-free int");

extern "C" void on_sigint(int sig) {
  g_signal.store(sig);
  g_stop.store(true);
}

/// The signal that set g_stop: "SIGINT", "SIGTERM", or "" (none seen).
std::string signal_name() {
  switch (g_signal.load()) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "";
  }
}
/// What stopped the run, as the CLI reports it: "interrupted (SIGINT)" (Ctrl-C),
/// "interrupted (SIGTERM)" (kill), "interrupted" (no signal seen).
std::string stop_reason() {
  const std::string s = signal_name();
  return s.empty() ? "interrupted" : "interrupted (" + s + ")";
}

class SigintGuard {
 public:
  SigintGuard() {
    g_stop.store(false);
    g_signal.store(0);
    struct sigaction sa {};
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;  // a second Ctrl-C kills the program the usual way
    installed_ = sigaction(SIGINT, &sa, &old_) == 0;
    sigaction(SIGTERM, &sa, &old_term_);  // SIGTERM too: keep what was computed
  }
  ~SigintGuard() {
    if (installed_) sigaction(SIGINT, &old_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;

 private:
  struct sigaction old_ {};
  struct sigaction old_term_ {};
  bool installed_ = false;
};

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

// ---- helpers ------------------------------------------------------------------------------

std::string fmt_g(double x, int digits = 6) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, x);
  return b;
}

/// The scene a subcommand works on: file or paper case or a fallback, then overrides.
Scene build_scene(const std::string& file, const std::string& case_name,
                  const std::vector<std::string>& sets, Scene fallback) {
  Scene sc;
  if (!file.empty() && !case_name.empty()) {
    throw SceneError("--case", 0, "case", case_name,
                     "give either a scene file or --case, not both");
  }
  if (!file.empty()) {
    sc = load_scene_file(file);
  } else if (!case_name.empty()) {
    sc = paper_case(case_name);  // SceneError names --case, the value and what is allowed
  } else {
    sc = std::move(fallback);
  }
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos) {
      throw SceneError("--set", 0, s, "",
                       "expected KEY=VALUE with a dotted key, e.g. --set cam.speed_rev_s=3");
    }
    if (eq == 0) {
      throw SceneError("--set", 0, "", s.substr(1),
                       "missing key before '=': expected KEY=VALUE, e.g. cam.speed_rev_s=3");
    }
  }
  apply_overrides(sc, sets);  // all at once, validated once: their order does not matter
  // Cam geometry (convexity, self-intersection) is checked by the Cam itself; name the
  // file or --set the offending key came from, not the Cam's own "<cam>".
  try {
    const Cam cam(sc.cam);
  } catch (const SceneError& e) {
    if (e.file() != "<cam>") throw;
    bool from_set = false;
    for (const auto& s : sets) {
      const std::string key = s.substr(0, s.find('='));
      if (key.rfind("cam.", 0) == 0) from_set = true;
    }
    throw SceneError(from_set ? "--set" : (file.empty() ? std::string("<built-in>") : file), 0,
                     e.key(), e.value(), e.rule());
  }
  return sc;
}

std::string plot_script_path() {
  if (const char* env = std::getenv("CAMDYN_PLOT_SCRIPT"); env && *env) return env;
  std::error_code ec;
  for (const char* p : {CAMDYN_PLOT_SCRIPT_INSTALL, CAMDYN_PLOT_SCRIPT_BUILD}) {
    if (p && *p && fs::is_regular_file(p, ec)) return p;
  }
  return {};
}

/// A plotting script that ships next to scripts/camdyn_plot.py: $ENV_VAR if set, else the
/// installed copy, else the source tree's. Empty if none is found.
std::string companion_script_path(const char* env_var, const char* file_name) {
  if (const char* env = std::getenv(env_var); env && *env) return env;
  std::error_code ec;
  for (const char* p : {CAMDYN_PLOT_SCRIPT_INSTALL, CAMDYN_PLOT_SCRIPT_BUILD}) {
    if (!p || !*p) continue;
    const fs::path cand = fs::path(p).parent_path() / file_name;
    if (fs::is_regular_file(cand, ec)) return cand.string();
  }
  return {};
}
/// scripts/camdyn_bench_plot.py ($CAMDYN_BENCH_PLOT_SCRIPT overrides).
std::string bench_plot_script_path() {
  return companion_script_path("CAMDYN_BENCH_PLOT_SCRIPT", "camdyn_bench_plot.py");
}
/// scripts/camdyn_report.py ($CAMDYN_REPORT_SCRIPT overrides).
std::string report_script_path() { return companion_script_path("CAMDYN_REPORT_SCRIPT", "camdyn_report.py"); }
/// scripts/camdyn_sweep_plot.py ($CAMDYN_SWEEP_PLOT_SCRIPT overrides).
std::string sweep_plot_script_path() {
  return companion_script_path("CAMDYN_SWEEP_PLOT_SCRIPT", "camdyn_sweep_plot.py");
}

/// Run the plot script (`script_override`, or camdyn_plot.py) with `args`. Returns its
/// exit status, or −1 if it could not start.
int run_plot_script(const std::vector<std::string>& args, std::string* why,
                    const std::string& script_override = std::string()) {
  const std::string script = script_override.empty() ? plot_script_path() : script_override;
  if (script.empty()) {
    *why = std::string("plot script not found (looked for ") + CAMDYN_PLOT_SCRIPT_INSTALL +
           " and " + CAMDYN_PLOT_SCRIPT_BUILD + ")";
    return -1;
  }
  const bool have_usr_python = ::access("/usr/bin/python3", X_OK) == 0;
  const std::string python = have_usr_python ? "/usr/bin/python3" : "python3";
  std::vector<std::string> argv_s{python, script};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    *why = std::string("fork failed: ") + std::strerror(errno);
    return -1;
  }
  if (pid == 0) {
    // The child keeps the default Ctrl-C behaviour.
    std::signal(SIGINT, SIG_DFL);
    if (have_usr_python)
      ::execv(argv[0], argv.data());
    else
      ::execvp(argv[0], argv.data());
    std::fprintf(stderr, "camdyn: cannot run %s: %s\n", python.c_str(), std::strerror(errno));
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      *why = std::string("waitpid failed: ") + std::strerror(errno);
      return -1;
    }
  }
  if (WIFEXITED(status)) {
    const int rc = WEXITSTATUS(status);
    if (rc == 127) *why = "python3 not found";
    else if (rc == 3) *why = "python3 has no numpy/matplotlib (apt-get install python3-matplotlib)";
    else if (rc != 0) *why = "plot script exited with status " + std::to_string(rc);
    return rc;
  }
  *why = "plot script was killed by signal " + std::to_string(WTERMSIG(status));
  return 128 + WTERMSIG(status);
}

// ---- subcommands --------------------------------------------------------------------------

struct CommonOpts {
  std::string scene_file;
  std::string case_name;
  std::vector<std::string> sets;
};

struct RunOpts {
  CommonOpts c;
  std::string out = "camdyn-out";
  bool quiet = false;
  bool plot = false;
};

struct CamOpts {
  CommonOpts c;
  std::string out = "camdyn-out";
  int points = 3600;
  bool quiet = false;
  bool no_plot = false;
};

struct SceneOpts {
  CommonOpts c;
  bool resolved = false;
  bool keys = false;  // print the key reference instead of a scene
  bool json = false;  // ... as JSON
};

struct PlotOpts {
  std::string dir;
  std::vector<double> zoom;
};

/// DIR/report.html by scripts/camdyn_report.py (`reuse`: keep the figures already drawn).
/// Returns the script's exit status (−1: not found or not started); `why` says what failed.
int write_report(const std::string& dir, bool reuse, std::string* why) {
  const std::string script = report_script_path();
  if (script.empty()) {
    *why = "camdyn_report.py not found";
    return -1;
  }
  std::vector<std::string> args{dir, "--quiet"};
  if (reuse) args.push_back("--reuse");
  return run_plot_script(args, why, script);
}

struct BenchOpts {
  std::vector<std::string> scenes;
  std::string out = "camdyn-bench";
  bool quick = false;
  int repeats = 3;
  double budget = 20.0;
  double t_end = 0.0;
  double output_dt = 0.0;
  bool quiet = false;
  bool no_plot = false;
  bool tolerance_sweep = false;
  std::vector<double> rtols, heavy_rtols;
  double reference_rtol = 1e-12;
  std::vector<std::string> methods, engines;
};

struct JumpOpts {
  CommonOpts c;
  std::string out = "camdyn-out";
  bool simulate = false;
  double rel_tol = 1e-4;
  double lo = 0, hi = 0;
  bool quiet = false;
};

struct SweepCliAxis {
  std::string key;
  double from = NAN, to = NAN, step = NAN;
  long points = 0;
  bool log = false;
};

struct SweepOpts {
  CommonOpts c;
  SweepCliAxis a1, a2;
  int jobs = 0;
  bool resume = false;
  std::string out = "camdyn-sweep";
  bool quiet = false;
  bool plot = false;
  bool no_timing = false;
  double timeout = 0;
};

// jump and sweep need a scene of the user's (no built-in default): the resolved, validated
// scene from the file or --case with the --set overrides.
Scene required_scene(const char* cmd, const CommonOpts& c) {
  if (c.scene_file.empty() && c.case_name.empty())
    throw SceneError(cmd, 0, "SCENE", "", "give a scene file (or --case A|B1|B2)");
  Scene sc = build_scene(c.scene_file, c.case_name, c.sets, default_scene());
  resolve_defaults(sc);
  validate(sc);
  return sc;
}

int cmd_jump(const JumpOpts& o) {
  Scene sc = required_scene("jump", o.c);
  JumpOptions jo;
  jo.rel_tol = o.rel_tol;
  jo.lo_rev_s = o.lo;
  jo.hi_rev_s = o.hi;
  jo.force_simulation = o.simulate;
  if (!o.quiet)
    jo.log = [](double sp, bool sep) {
      std::fprintf(stderr, "  %.10g rev/s: %s\n", sp, sep ? "separates" : "keeps contact");
      std::fflush(stderr);
    };
  ensure_output_dir(o.out);
  JumpResult r;
  {
    SigintGuard guard;
    r = jump_speed(sc, jo);  // SceneError → exit 2; a failing run is reported as such
  }
  const std::string path = join_path(o.out, "jump.json");
  std::string j = "{\n  \"scene\": " + json_string(sc.title) +
                  ",\n  \"jump_speed_rev_s\": " + json_number(r.jump_speed_rev_s) +
                  ",\n  \"method\": " + json_string(r.method) +
                  ",\n  \"theta_deg\": " + json_number(r.theta_deg) +
                  ",\n  \"phenomenon\": " + json_string(r.phenomenon) +
                  ",\n  \"phenomenon_text\": " + json_string(r.phenomenon_text) +
                  ",\n  \"jump_speed_text\": " + json_string(jump_speed_text(r));
  if (r.method == "simulation") {
    j += ",\n  \"lo_rev_s\": " + json_number(r.lo_rev_s) + ",\n  \"hi_rev_s\": " +
         json_number(r.hi_rev_s) + ",\n  \"bracket_width_rev_s\": " +
         json_number(std::abs(r.hi_rev_s - r.lo_rev_s)) + ",\n  \"rel_tol\": " + json_number(o.rel_tol) +
         ",\n  \"simulations\": " + std::to_string(r.simulations) + ",\n  \"t_end\": " +
         json_number(sc.run.t_end);
  }
  j += "\n}\n";
  int rc = kExitOk;
  try {
    write_file_atomic(path, j);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: cannot write '%s': %s\n", path.c_str(), e.what());
    rc = kExitFailed;
  }
  if (!o.quiet) {
    std::printf("%s: %s, margin reaches zero at cam angle %s deg", sc.title.c_str(),
                r.method.c_str(), fmt_g(r.theta_deg, 10).c_str());
    if (r.method == "simulation") std::printf(" (%d runs to t = %g)", r.simulations, sc.run.t_end);
    std::printf("\njump speed: %s\nphenomenon: %s", jump_speed_text(r).c_str(), r.phenomenon.c_str());
    if (r.method == "simulation") std::printf(" (the run at the upper bracket end: %s)", r.phenomenon_text.c_str());
    else std::printf(" (%s)", r.phenomenon_text.c_str());
    std::printf("\noutput: %s\n", path.c_str());
  }
  std::printf("jump_speed_rev_s = %.17g\n", r.jump_speed_rev_s);
  std::fflush(stdout);
  return rc;
}

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

constexpr const char* kStopPlaceholder = "interrupted (signal)";

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

int cmd_cam(const CamOpts& o) {
  // Without a scene: the paper cam (default CamSpec) at its default speed.
  Scene sc = build_scene(o.c.scene_file, o.c.case_name, o.c.sets, Scene{});
  resolve_defaults(sc);
  validate(sc);
  Cam cam(sc.cam);  // SceneError on a bad profile → exit 2
  ensure_output_dir(o.out);
  const std::string path = join_path(o.out, "cam.csv");
  try {
    write_file_atomic(path, cam_csv(cam, o.points));
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: cannot write '%s': %s\n", path.c_str(), e.what());
    return kExitFailed;
  }
  double speed = sc.cam.speed_rev_s;
  if (!sc.cam.speed_table_rev_s.empty()) speed = sc.cam.speed_table_rev_s.front();
  // Side file for the figures ('camdyn plot DIR' redraws them at the same speed).
  try {
    write_file_atomic(join_path(o.out, "cam_info.json"),
                      "{\n  \"title\": " + json_string(sc.title) +
                          ",\n  \"speed_rev_s\": " + json_number(speed) +
                          ",\n  \"points\": " + std::to_string(o.points) +
                          ",\n  \"lift\": " + json_number(cam.lift()) +
                          ",\n  \"min_radius_of_curvature\": " +
                          json_number(cam.min_radius_of_curvature()) +
                          ",\n  \"profile\": " + json_string(to_string(sc.cam.profile)) +
                          ",\n  \"follower_face\": " + json_string(to_string(sc.cam.follower_face)) +
                          ",\n  \"follower_offset\": " + json_number(sc.cam.follower_offset) +
                          ",\n  \"roller_radius\": " + json_number(sc.cam.roller_radius) +
                          ",\n  \"follower_motion\": " + json_string(to_string(sc.cam.follower_motion)) +
                          ",\n  \"pivot_x\": " + json_number(sc.cam.pivot_x) +
                          ",\n  \"pivot_y\": " + json_number(sc.cam.pivot_y) +
                          ",\n  \"continuity\": " + json_string(cam.law() ? cam.law()->continuity_report() : "") +
                          "\n}\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: warning: %s\n", e.what());
  }
  if (!o.quiet) {
    std::printf("wrote %s (%d points): lift %s, smallest radius of curvature %s\n",
                path.c_str(), o.points, fmt_g(cam.lift()).c_str(),
                fmt_g(cam.min_radius_of_curvature()).c_str());
    if (cam.law()) std::printf("motion law: continuity at the joints: %s\n", cam.law()->continuity_report().c_str());
    if (!cam.breakpoints().empty())
      std::printf("breakpoints: %zu (steps land on them: cam.land_on_breaks = %s)\n", cam.breakpoints().size(),
                  sc.cam.land_on_breaks ? "true" : "false");
    std::fflush(stdout);
  }
  if (!o.no_plot) {
    std::string why;
    // --quiet: the figures are listed below, once.
    std::vector<std::string> args{"cam", o.out, "--speed", fmt_g(speed, 17), "--quiet"};
    const int prc = run_plot_script(args, &why);
    if (prc != 0) {
      std::fprintf(stderr, "camdyn: warning: no cam figures drawn: %s\n", why.c_str());
    } else if (!o.quiet) {
      std::printf("figures: %s, %s, %s\n", join_path(o.out, "cam_profile.png").c_str(),
                  join_path(o.out, "cam_kinematics.png").c_str(),
                  join_path(o.out, "cam_geometry.png").c_str());
    }
  }
  return kExitOk;
}

int cmd_scene(const SceneOpts& o) {
  if (o.keys) {
    std::fputs((o.json ? scene_keys_json() : scene_keys_markdown()).c_str(), stdout);
    return kExitOk;
  }
  if (o.json) throw SceneError("scene", 0, "--json", "", "needs --keys (the scene itself is printed as TOML)");
  Scene sc = build_scene(o.c.scene_file, o.c.case_name, o.c.sets, default_scene());
  Scene resolved = sc;
  resolve_defaults(resolved);
  validate(resolved);
  const std::string text = to_toml(o.resolved ? resolved : sc);
  std::fputs(text.c_str(), stdout);
  if (!text.empty() && text.back() != '\n') std::fputc('\n', stdout);
  return kExitOk;
}

int cmd_plot(const PlotOpts& o) {
  std::error_code ec;
  if (!fs::is_directory(o.dir, ec)) {
    throw SceneError("plot", 0, "DIR", o.dir, "not a directory");
  }
  const bool have_history = fs::is_regular_file(join_path(o.dir, "history.csv"), ec);
  const bool have_cam = fs::is_regular_file(join_path(o.dir, "cam.csv"), ec);
  if (!have_history && !have_cam) {
    throw SceneError("plot", 0, "DIR", o.dir,
                     "holds neither history.csv (from 'camdyn run') nor cam.csv (from "
                     "'camdyn cam')");
  }
  int rc = kExitOk;
  if (have_history) {
    std::vector<std::string> args{"run", o.dir};
    if (o.zoom.size() == 2) {
      args.push_back("--zoom");
      args.push_back(fmt_g(o.zoom[0], 17));
      args.push_back(fmt_g(o.zoom[1], 17));
    }
    std::string why;
    if (run_plot_script(args, &why) != 0) {
      std::fprintf(stderr, "camdyn: cannot draw the figures: %s\n", why.c_str());
      rc = kExitFailed;
    }
  }
  if (have_cam) {
    std::string why;
    if (run_plot_script({"cam", o.dir}, &why) != 0) {
      std::fprintf(stderr, "camdyn: cannot draw the cam figures: %s\n", why.c_str());
      rc = kExitFailed;
    }
  }
  return rc;
}

int cmd_report(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw SceneError("report", 0, "DIR", dir, "not a directory");
  if (!fs::is_regular_file(join_path(dir, "summary.json"), ec) && !fs::is_regular_file(join_path(dir, "sweep.csv"), ec))
    throw SceneError("report", 0, "DIR", dir,
                     "holds neither summary.json (from 'camdyn run') nor sweep.csv (from 'camdyn sweep')");
  std::string why;
  const int rc = write_report(dir, false, &why);
  if (rc == 2) return kExitBadInput;  // the script printed what is wrong with DIR
  if (rc != 0) {
    std::fprintf(stderr, "camdyn: cannot write the report: %s\n", why.c_str());
    return kExitFailed;
  }
  std::printf("report: %s\n", join_path(dir, "report.html").c_str());
  return kExitOk;
}

/// `camdyn bench --tolerance-sweep`: scene names A, A7, B1, B2 (t_end 0.1 unless --t-end),
/// stiff, ohc and ohv (examples/ohc_bucket_tappet.toml, examples/ohv_pushrod_train.toml:
/// one revolution), or scene files; none: all of them.
int cmd_tolerance_sweep(const BenchOpts& o) {
  ToleranceSweepOptions to;
  std::vector<std::string> names = o.scenes;
  if (names.empty()) names = {"A", "A7", "B1", "B2", "stiff", "ohc", "ohv"};
  const std::map<std::string, std::string> trains{{"ohc", "ohc_bucket_tappet.toml"},
                                                  {"ohv", "ohv_pushrod_train.toml"}};
  std::error_code ec;
  for (const auto& name : names) {
    if (fs::exists(name, ec) || (!is_bench_case(name) && !trains.count(name))) {
      Scene sc = load_scene_file(name);
      Cam cam(sc.cam);  // a bad profile is bad input
      to.scenes.push_back(std::move(sc));
      to.labels.push_back(fs::path(name).stem().string());
    } else if (trains.count(name)) {
      fs::path f = fs::path("examples") / trains.at(name);
      if (!fs::exists(f, ec)) f = fs::path(CAMDYN_PLOT_SCRIPT_BUILD).parent_path().parent_path() / "examples" / trains.at(name);
      if (!fs::exists(f, ec))
        throw SceneError("bench", 0, "scene", name, "examples/" + trains.at(name) + " not found");
      to.scenes.push_back(load_scene_file(f.string()));
      to.labels.push_back(name);
    } else {
      Scene sc = bench_case(name);
      if (name != "stiff") sc.run.t_end = 0.1;
      to.scenes.push_back(std::move(sc));
      to.labels.push_back(name);
    }
  }
  if (!o.rtols.empty()) to.rtols = o.rtols;
  to.heavy_rtols = o.heavy_rtols;
  to.reference_rtol = o.reference_rtol;
  to.methods = o.methods;
  to.engines = o.engines;
  to.time_budget_seconds = o.budget;
  to.t_end = o.t_end;
  to.out_dir = o.out;
  if (!o.quiet)
    to.log = [](const std::string& line) {
      std::fprintf(stderr, "%s\n", line.c_str());
      std::fflush(stderr);
    };
  const ToleranceSweepResult res = run_tolerance_sweep(to);  // SceneError: exit 2
  int bad = 0;
  for (const auto& c : res.checks) bad += c.monotone ? 0 : 1;
  if (!o.quiet)
    std::printf("tolerance sweep: %zu runs, %zu series checks, %d not monotone; output: %s, %s, %s\n",
                res.rows.size(), res.checks.size(), bad, res.csv_path.c_str(),
                res.series_path.c_str(), res.md_path.c_str());
  if (!o.no_plot) {
    std::string why;
    const std::string script = companion_script_path("CAMDYN_TOL_SWEEP_PLOT_SCRIPT", "camdyn_tol_sweep_plot.py");
    if (script.empty() || run_plot_script({o.out}, &why, script) != 0)
      std::fprintf(stderr, "camdyn: warning: no figures drawn: %s\n",
                   script.empty() ? "camdyn_tol_sweep_plot.py not found" : why.c_str());
    else if (!o.quiet)
      std::printf("figures: %s\n", join_path(o.out, "tol_sweep_*.png").c_str());
  }
  return kExitOk;
}

int cmd_bench(const BenchOpts& o) {
  if (o.tolerance_sweep) return cmd_tolerance_sweep(o);
  // Input stage: every error here is bad input (exit 2, raised to main()).
  BenchOptions bo;
  for (const auto& name : o.scenes) {
    std::error_code ec;
    if (is_bench_case(name) && !fs::exists(name, ec)) {
      bo.scenes.push_back(bench_case(name));
      bo.labels.push_back(name);
      continue;
    }
    Scene sc = load_scene_file(name);
    resolve_defaults(sc);
    validate(sc);
    Cam cam(sc.cam);  // a bad profile is bad input
    bo.scenes.push_back(std::move(sc));
    bo.labels.push_back(fs::path(name).stem().string());
  }
  if (o.repeats < 1)
    throw SceneError("--repeats", 0, "repeats", std::to_string(o.repeats), "must be >= 1");
  if (!(o.budget > 0))
    throw SceneError("--budget", 0, "budget", fmt_g(o.budget), "must be > 0 seconds");
  if (!(o.t_end >= 0) || !std::isfinite(o.t_end))
    throw SceneError("--t-end", 0, "t_end", fmt_g(o.t_end), "must be > 0 (0: the scene's)");
  if (!(o.output_dt >= 0) || !std::isfinite(o.output_dt))
    throw SceneError("--output-dt", 0, "output_dt", fmt_g(o.output_dt),
                     "must be >= 0 (0: chosen per scene)");
  bo.quick = o.quick;
  bo.repeats = o.repeats;
  bo.time_budget_seconds = o.budget;
  bo.t_end = o.t_end;
  bo.output_dt = o.output_dt;
  bo.out_dir = o.out;
  ensure_output_dir(o.out);
  if (!o.quiet)
    bo.log = [](const std::string& line) {
      std::fprintf(stderr, "%s\n", line.c_str());
      std::fflush(stderr);
    };

  BenchResult res;
  try {
    res = run_bench(bo);
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: bench failed: %s\n", e.what());
    return kExitFailed;
  }
  if (!o.quiet) {
    for (size_t i = 0; i < res.headline_scene.size(); ++i)
      std::printf("scene %s: %s\n", res.headline_scene[i].c_str(),
                  res.headline_text[i].c_str());
    std::printf("output: %s, %s\n", res.csv_path.c_str(), res.md_path.c_str());
    std::fflush(stdout);
  }
  if (!o.no_plot) {
    std::string why;
    const std::string script = bench_plot_script_path();
    if (script.empty()) {
      std::fprintf(stderr, "camdyn: warning: no figures drawn: camdyn_bench_plot.py not found\n");
    } else if (run_plot_script(o.quiet ? std::vector<std::string>{o.out, "--quiet"}
                                       : std::vector<std::string>{o.out},
                               &why, script) != 0) {
      std::fprintf(stderr, "camdyn: warning: no figures drawn: %s\n", why.c_str());
    } else if (!o.quiet) {
      std::printf("figures: %s\n", join_path(o.out, "wp_*.png").c_str());
    }
  }
  return kExitOk;
}

void add_common(CLI::App* sub, CommonOpts& c, const char* scene_help) {
  sub->add_option("scene", c.scene_file, scene_help)->type_name("SCENE.toml");
  sub->add_option("--case", c.case_name,
                  "Use one of the paper's reference cases instead of a file: A, B1, B2")
      ->type_name("NAME");
  sub->add_option("--set", c.sets,
                  "Override a scene key, e.g. --set cam.speed_rev_s=3 --set "
                  "contact.model=penalty (repeatable; applied in order; value in TOML "
                  "syntax, bare words are strings)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
}

const std::vector<std::string> kCommands{"run", "cam", "scene", "plot", "report", "bench", "jump", "sweep"};

int real_main(int argc, char** argv) {
  CLI::App app{
      "camdyn — cam–follower dynamics with impact, separation and elastic deformation "
      "(Lee 1997).",
      "camdyn"};
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 the simulation failed, 2 bad input.\n"
      "Examples:\n"
      "  camdyn run                          # the built-in paper case B2\n"
      "  camdyn run scene.toml --out out --set cam.speed_rev_s=3 --plot\n"
      "  camdyn cam --out out                # cam.csv + cam figures\n"
      "  camdyn scene scene.toml --resolved  # the scene with every default filled in\n"
      "  camdyn bench --quick                # work–precision: Lee vs penalty vs baselines\n"
      "  camdyn jump examples/circle_cam.toml # jump (separation) speed\n"
      "  camdyn sweep examples/case_A7.toml --key cam.speed_rev_s --from 5 --to 8 --points 31\n"
      "  camdyn report out                   # out/report.html: figures and results in words\n"
      "Run 'camdyn COMMAND --help' for the options of a command.");

  RunOpts ro;
  auto* run = app.add_subcommand(
      "run",
      "Simulate a scene (default: the built-in paper case B2, elastic follower at 5 rev/s) "
      "and write DIR/history.csv, DIR/events.csv and DIR/summary.json (also when the run "
      "fails or is interrupted with Ctrl-C)");
  add_common(run, ro.c, "Scene file (TOML); without it the built-in default scene is run");
  run->add_option("-o,--out", ro.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  run->add_flag("-q,--quiet", ro.quiet, "Print nothing but errors");
  run->add_flag("--plot", ro.plot,
                "Draw displacement.png, contact_force.png and contact_force_zoom.png (networks "
                "also network_motion.png, network_forces.png) and the page report.html in DIR "
                "after the run (python3 + matplotlib)");
  run->footer(
      "history.csv columns: " +
      [] {
        std::string h;
        for (const auto& c : history_columns()) h += (h.empty() ? "" : ",") + c;
        return h;
      }() +
      "\nExit status: 0 finished, 1 the simulation failed (message names the time and the "
      "reason), 2 bad input.");

  CamOpts co;
  auto* cam = app.add_subcommand(
      "cam",
      "Cam kinematics over one revolution: DIR/cam.csv (theta,X_C,dX_dtheta,d2X_dtheta2,"
      "beta,r,rho) and the figures cam_profile.png and cam_kinematics.png");
  add_common(cam, co.c, "Scene file (TOML); without it the paper's cam is used");
  cam->add_option("-o,--out", co.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  cam->add_option("-n,--points", co.points, "Number of cam angles θ = 2π i/N, i = 0..N−1")
      ->type_name("N")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000000));
  cam->add_flag("-q,--quiet", co.quiet, "Print nothing but errors");
  cam->add_flag("--no-plot", co.no_plot, "Write cam.csv only, no figures");

  SceneOpts so;
  auto* scene = app.add_subcommand(
      "scene", "Check a scene and print it as TOML (with --resolved: every default filled in)");
  add_common(scene, so.c, "Scene file (TOML); without it the built-in default scene");
  scene->add_flag("-r,--resolved", so.resolved,
                  "Print the resolved scene (automatic values such as contact.tol_u filled "
                  "in)");
  scene->add_flag("--keys", so.keys,
                  "Print the reference of every scene key (key, type, unit, default, rule, "
                  "description) as Markdown, generated from the scene's key table");
  scene->add_flag("--json", so.json, "With --keys: print the reference as JSON");

  PlotOpts po;
  auto* plot = app.add_subcommand(
      "plot",
      "Draw the figures of an output directory: history.csv → displacement.png, "
      "contact_force.png, contact_force_zoom.png; cam.csv → cam_profile.png, "
      "cam_kinematics.png (python3 + matplotlib)");
  plot->add_option("dir", po.dir, "Output directory of 'camdyn run' or 'camdyn cam'")
      ->type_name("DIR")
      ->required();
  plot->add_option("--zoom", po.zoom,
                   "Time window of contact_force_zoom.png (default: 0.02 s around the "
                   "largest contact force)")
      ->type_name("T0 T1")
      ->expected(2);

  std::string report_dir;
  auto* report = app.add_subcommand(
      "report",
      "One self-contained HTML page of a run or a sweep, DIR/report.html: the figures "
      "(embedded) and the results in words, from summary.json, events.csv and history.csv "
      "(or sweep.csv) (python3 + matplotlib)");
  report->add_option("dir", report_dir, "Output directory of 'camdyn run' or 'camdyn sweep'")
      ->type_name("DIR")
      ->required();

  BenchOpts bo;
  auto* bench = app.add_subcommand(
      "bench",
      "Work–precision benchmark: Lee (engines × error variants × tolerances), penalty "
      "(k_p × c_p × rtol), holonomic and event runs against an event-driven reference; "
      "writes DIR/work_precision.csv, DIR/work_precision.md and wp_*.png figures");
  bench->add_option("scenes", bo.scenes,
                    "Scene files (TOML) or case names A, A7 (case A at 7 rev/s: separates), "
                    "B1, B2; default: A A7 B1 B2")
      ->type_name("SCENE");
  bench->add_option("-o,--out", bo.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  bench->add_flag("--quick", bo.quick,
                  "Reduced sweep: Lee on arkode-erk at two tolerances, penalty at three k_p, "
                  "elastic scenes cut to t_end = 0.02 (under a minute)");
  bench->add_option("--repeats", bo.repeats, "Timing repeats (median CPU time)")
      ->type_name("N")
      ->capture_default_str();
  bench->add_option("--budget", bo.budget,
                    "CPU seconds per run before it is stopped (a Lee series then skips its "
                    "tighter tolerances)")
      ->type_name("SECONDS")
      ->capture_default_str();
  bench->add_option("--t-end", bo.t_end, "Override every scene's run.t_end (0: keep)")
      ->type_name("T");
  bench->add_option("--output-dt", bo.output_dt,
                    "Common output grid every run lands on and is compared on (0: 1e-2 for "
                    "a rigid follower, 1e-3 if it separates, 1e-4 for an elastic one)")
      ->type_name("DT");
  bench->add_flag("-q,--quiet", bo.quiet, "Print nothing but errors");
  bench->add_flag("--no-plot", bo.no_plot, "Write the CSV and Markdown only, no figures");
  bench->add_flag("--tolerance-sweep", bo.tolerance_sweep,
                  "Tolerance sweep instead: every contact method x engine over rtol 1e-2..1e-12 "
                  "(tol_u alike) against a tight reference, per scene (names A A7 B1 B2 (0.1 s) "
                  "stiff ohc ohv, or files; default all); writes DIR/tol_sweep.csv, "
                  "tol_sweep_series.csv, tol_sweep.md, tol_sweep_*.png (docs/bench_tolerance_sweep.md)");
  bench->add_option("--rtols", bo.rtols, "Tolerance sweep: the rtol grid (default 1e-2 ... 1e-12, decades)")
      ->delimiter(',')
      ->type_name("R,R,...");
  bench->add_option("--heavy-rtols", bo.heavy_rtols,
                    "Tolerance sweep: the rtol grid of elastic and network scenes (default: --rtols)")
      ->delimiter(',')
      ->type_name("R,R,...");
  bench->add_option("--reference-rtol", bo.reference_rtol,
                    "Tolerance sweep: rtol of the references (atol 1e-2 of it)")
      ->type_name("R")
      ->capture_default_str();
  bench->add_option("--methods", bo.methods, "Tolerance sweep: lee,event,holonomic,penalty (default all)")
      ->delimiter(',')
      ->type_name("M,M,...");
  bench->add_option("--engines", bo.engines,
                    "Tolerance sweep: arkode-erk,arkode-dirk,cvode-bdf,ida (default all)")
      ->delimiter(',')
      ->type_name("E,E,...");

  JumpOpts jo;
  auto* jump = app.add_subcommand(
      "jump",
      "Jump (separation) speed at constant cam speed: closed form for a rigid follower "
      "(min over the cam angle of the required contact force reaches 0), bisection over "
      "cam.speed_rev_s on 'the run separates' otherwise; writes DIR/jump.json and prints "
      "'jump_speed_rev_s = <value>' as the last line");
  add_common(jump, jo.c, "Scene file (TOML)");
  jump->add_option("-o,--out", jo.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  jump->add_flag("--simulate", jo.simulate, "Bisection by simulation also for a rigid follower");
  jump->add_option("--rel-tol", jo.rel_tol, "Simulation: relative width of the final bracket")
      ->type_name("R")
      ->capture_default_str();
  jump->add_option("--lo", jo.lo, "Simulation: lower bracket speed [rev/s] (0: automatic)")->type_name("REV_S");
  jump->add_option("--hi", jo.hi, "Simulation: upper bracket speed [rev/s] (0: automatic)")->type_name("REV_S");
  jump->add_flag("-q,--quiet", jo.quiet, "Print only the last line");

  SweepOpts swo;
  auto* sweep = app.add_subcommand(
      "sweep",
      "Parameter sweep over one numeric scene key (or a grid of two): one run per point, "
      "in parallel (--jobs, or mpirun -np N camdyn sweep ...); DIR/sweep.csv (one row per "
      "point: the key values, then finished,separations,impacts,max_contact_force,"
      "min_contact_force,... cpu_seconds,message) and DIR/poincare.csv (per-revolution "
      "samples). Finished points are journalled (DIR/sweep.journal, fsync): a killed sweep "
      "loses nothing and --resume skips the points done");
  add_common(sweep, swo.c, "Scene file (TOML)");
  auto add_axis = [&](SweepCliAxis& a, const std::string& sfx) {
    sweep->add_option("--key" + sfx, a.key, "Scene key to sweep, e.g. cam.speed_rev_s")->type_name("KEY");
    sweep->add_option("--from" + sfx, a.from, "First value")->type_name("A");
    sweep->add_option("--to" + sfx, a.to, "Last value (> A)")->type_name("B");
    sweep->add_option("--step" + sfx, a.step, "Spacing (values A, A+S, ... <= B)")->type_name("S");
    sweep->add_option("--points" + sfx, a.points, "Number of values from A to B inclusive (>= 2)")->type_name("N");
    sweep->add_flag("--log" + sfx, a.log, "Geometric spacing with --points (A > 0)");
  };
  add_axis(swo.a1, "");
  add_axis(swo.a2, "2");
  sweep->get_option("--key")->required();
  sweep->add_option("-j,--jobs", swo.jobs, "Worker threads (0: all cores)")->type_name("N")->capture_default_str();
  sweep->add_flag("--resume", swo.resume, "Keep the points already in DIR/sweep.journal (same sweep only)");
  sweep->add_option("-o,--out", swo.out, "Output directory (created if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  sweep->add_flag("--no-timing", swo.no_timing, "Write cpu_seconds as 0 (byte-comparable files)");
  sweep->add_option("--timeout", swo.timeout, "CPU seconds per point before it is stopped and recorded as failed (0: none)")
      ->type_name("SECONDS");
  sweep->add_flag("-q,--quiet", swo.quiet, "No progress line or report");
  sweep->add_flag("--plot", swo.plot,
                  "Draw sweep_force.png, sweep_bifurcation.png and sweep_impacts.png and the "
                  "page report.html in DIR (python3 + matplotlib)");
  sweep->footer("Exit status: 0 every point done (failed points are rows with finished = 0), "
                "1 interrupted or I/O error, 2 bad input. Under mpirun rank 0 hands out the "
                "points and computes too; --jobs is ignored there (one thread per rank).");

  // A clear message for a mistyped command (CLI11 would only say "not expected").
  if (argc >= 2 && argv[1][0] != '-') {
    bool known = false;
    for (const auto& c : kCommands) known = known || c == argv[1];
    if (!known) {
      std::fprintf(stderr,
                   "camdyn: unknown command '%s' (allowed: run, cam, scene, plot, report, "
                   "bench, jump, sweep; see camdyn --help)\n",
                   argv[1]);
      return kExitBadInput;
    }
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::string what = e.what();
    if (argc < 2) what = "no command given (allowed: run, cam, scene, plot, report, bench, jump, sweep)";
    std::fprintf(stderr, "camdyn: %s\nRun 'camdyn --help' for the commands and options.\n",
                 what.c_str());
    return kExitBadInput;
  }
  if (po.zoom.size() == 2 && !(po.zoom[0] < po.zoom[1])) {
    throw SceneError("--zoom", 0, "zoom", fmt_g(po.zoom[0]) + " " + fmt_g(po.zoom[1]),
                     "expected T0 < T1");
  }

  if (run->parsed()) return cmd_run(ro);
  if (cam->parsed()) return cmd_cam(co);
  if (scene->parsed()) return cmd_scene(so);
  if (plot->parsed()) return cmd_plot(po);
  if (report->parsed()) return cmd_report(report_dir);
  if (bench->parsed()) return cmd_bench(bo);
  if (jump->parsed()) return cmd_jump(jo);
  if (sweep->parsed()) {
    // Under mpirun every rank parses the same command line: report bad input once (rank 0).
    if (camdyn_cli::launched_under_mpi() && camdyn_cli::mpi_rank_from_env() != 0) {
      try {
        return cmd_sweep(swo);
      } catch (const SceneError&) {
        return kExitBadInput;
      }
    }
    return cmd_sweep(swo);
  }
  std::fprintf(stderr, "camdyn: no command given (allowed: run, cam, scene, plot, report, bench, jump, sweep)\n");
  return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return real_main(argc, argv);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "camdyn: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "camdyn: out of memory\n");
    return kExitFailed;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "camdyn: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "camdyn: %s\n", e.what());
    return kExitFailed;
  } catch (...) {
    std::fprintf(stderr, "camdyn: unknown error\n");
    return kExitFailed;
  }
}
