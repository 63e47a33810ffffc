// camdyn (private) — the CLI's subcommands, their options and shared helpers (main.cpp
// parses the command line and dispatches to the cmd_* functions).
#pragma once

#include <atomic>
#include <csignal>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

#ifndef CAMDYN_PLOT_SCRIPT_BUILD
#define CAMDYN_PLOT_SCRIPT_BUILD ""
#endif
#ifndef CAMDYN_PLOT_SCRIPT_INSTALL
#define CAMDYN_PLOT_SCRIPT_INSTALL ""
#endif

namespace camdyn_cli {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitBadInput = 2;
/// The run reached t_end but its contract (Summary::contract) does not hold.
constexpr int kExitContract = 3;

// ---- Ctrl-C -------------------------------------------------------------------------------

extern std::atomic<bool> g_stop;
extern std::atomic<int> g_signal;  // the signal that set g_stop (SIGINT, SIGTERM or SIGHUP)
extern "C" void on_sigint(int sig);

/// The signal that set g_stop: "SIGINT", "SIGTERM", "SIGHUP", or "" (none seen).
std::string signal_name();
/// What stopped the run, as the CLI reports it: "interrupted (SIGINT)" (Ctrl-C),
/// "interrupted (SIGTERM)" (kill), "interrupted" (no signal seen).
std::string stop_reason();

/// Installs on_sigint for SIGINT, SIGTERM and SIGHUP while it lives (resets g_stop). Each
/// handler is reset after its first signal: a second one acts as usual (ends the program).
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
    sigaction(SIGHUP, &sa, &old_hup_);    // and SIGHUP (the terminal closed)
  }
  ~SigintGuard() {
    if (installed_) sigaction(SIGINT, &old_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
    sigaction(SIGHUP, &old_hup_, nullptr);
  }
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;

 private:
  struct sigaction old_ {};
  struct sigaction old_term_ {};
  struct sigaction old_hup_ {};
  bool installed_ = false;
};

// ---- helpers ------------------------------------------------------------------------------

std::string fmt_g(double x, int digits = 6);

/// The scene a subcommand works on: file or paper case or a fallback, then overrides,
/// validated once (after the overrides) and resolved.
/// @throws SceneError.
camdyn::ValidatedScene build_scene(const std::string& file, const std::string& case_name,
                                   const std::vector<std::string>& sets, camdyn::Scene fallback);

/// The Simulator of a validated scene: every check a run makes before its first step
/// (the start state, the tolerance floors, the method on the follower). `scene` and `run`
/// both call it, so they accept the same scenes. Model-building failures become SceneError.
/// @throws SceneError.
std::unique_ptr<camdyn::Simulator> checked_simulator(const camdyn::ValidatedScene& scene);

/// Print `text` (and a newline if it has none) on stdout and flush; false on a write
/// error (e.g. stdout is /dev/full).
bool write_stdout(const std::string& text);

std::string plot_script_path();
/// A plotting script that ships next to scripts/camdyn_plot.py: $ENV_VAR if set, else the
/// installed copy, else the source tree's. Empty if none is found.
std::string companion_script_path(const char* env_var, const char* file_name);
/// scripts/camdyn_bench_plot.py ($CAMDYN_BENCH_PLOT_SCRIPT overrides).
std::string bench_plot_script_path();
/// scripts/camdyn_report.py ($CAMDYN_REPORT_SCRIPT overrides).
std::string report_script_path();
/// scripts/camdyn_sweep_plot.py ($CAMDYN_SWEEP_PLOT_SCRIPT overrides).
std::string sweep_plot_script_path();

/// Run the plot script (`script_override`, or camdyn_plot.py) with `args`. Returns its
/// exit status, or −1 if it could not start.
int run_plot_script(const std::vector<std::string>& args, std::string* why,
                    const std::string& script_override = std::string());

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
  // --synthesise-from-valve-lift: cam.law (or cam.profile = "table") is the VALVE lift
  bool synthesise = false;
  // the train's [synthesis] keys given on the command line (NaN: the scene's value)
  double ratio = NAN, valve_end_angle_deg = NAN, lash = NAN, ramp_deg = NAN;
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
  /// Directory of cached bench references ("" with --no-cache: none).
  std::string reference_cache;
  bool no_cache = false;
};

struct JumpOpts {
  CommonOpts c;
  std::string out = "camdyn-out";
  bool simulate = false;
  double rel_tol = 1e-3;
  double lo = 0, hi = 0;
  int points = 40;
  int jobs = 0;
  bool quiet = false;
};

struct SpectrumOpts {
  std::string dir;
  std::string column = "contact_force";
  int revolutions = 0;
  int samples = 1024;
  double max_order = 40;
};

struct CampbellOpts {
  CommonOpts c;
  std::string column = "contact_force";
  double from = NAN, to = NAN;
  long points = 0;
  int settle = 2, revolutions = 2, samples = 512, jobs = 0;
  double max_order = 32;
  std::string out = "camdyn-campbell";
  bool plot = false, quiet = false;
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

/// DIR/report.html by scripts/camdyn_report.py (`reuse`: keep the figures already drawn).
/// Returns the script's exit status (−1: not found or not started); `why` says what failed.
int write_report(const std::string& dir, bool reuse, std::string* why);

// jump and sweep need a scene of the user's (no built-in default): the resolved, validated
// scene from the file or --case with the --set overrides.
camdyn::Scene required_scene(const char* cmd, const CommonOpts& c);

// ---- subcommands (each returns the exit status) -------------------------------------------

int cmd_run(const RunOpts& o);
int cmd_cam(const CamOpts& o);
int cmd_scene(const SceneOpts& o);
int cmd_plot(const PlotOpts& o);
int cmd_report(const std::string& dir);
int cmd_bench(const BenchOpts& o);
int cmd_jump(const JumpOpts& o);
int cmd_spectrum(const SpectrumOpts& o);
int cmd_campbell(const CampbellOpts& o);
int cmd_sweep(const SweepOpts& o);

}  // namespace camdyn_cli
