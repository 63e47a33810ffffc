// camdyn — command-line tool: signals, scene and plot-script helpers shared by the subcommands.
#include "commands.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "scene/shared_cam.hpp"

namespace camdyn_cli {

using namespace camdyn;
namespace fs = std::filesystem;

// ---- Ctrl-C -------------------------------------------------------------------------------

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};  // the signal that set g_stop (SIGINT, SIGTERM or SIGHUP)
static_assert(std::atomic<bool>::is_always_lock_free, "signal handler needs a lock-free flag");
static_assert(std::atomic<int>::is_always_lock_free, "signal handler needs a lock-free int");

extern "C" void on_sigint(int sig) {
  g_signal.store(sig);
  g_stop.store(true);
}

/// The signal that set g_stop: "SIGINT", "SIGTERM", "SIGHUP", or "" (none seen).
std::string signal_name() {
  switch (g_signal.load()) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "";
  }
}
/// What stopped the run, as the CLI reports it: "interrupted (SIGINT)" (Ctrl-C),
/// "interrupted (SIGTERM)" (kill), "interrupted" (no signal seen).
std::string stop_reason() {
  const std::string s = signal_name();
  return s.empty() ? "interrupted" : "interrupted (" + s + ")";
}

// ---- helpers ------------------------------------------------------------------------------

std::string fmt_g(double x, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, x);
  return b;
}

/// The scene a subcommand works on: file or paper case or a fallback, then overrides.
ValidatedScene build_scene(const std::string& file, const std::string& case_name,
                           const std::vector<std::string>& sets, Scene fallback) {
  if (!file.empty() && !case_name.empty()) {
    throw SceneError("--case", 0, "case", case_name,
                     "give either a scene file or --case, not both");
  }
  // The file with the overrides set in it, validated once: --set may repair the file.
  std::optional<ValidatedScene> loaded;
  Scene base;
  if (!file.empty()) {
    loaded = load_validated_scene(file, sets);
  } else if (!case_name.empty()) {
    base = paper_case(case_name);  // SceneError names --case, the value and what is allowed
  } else {
    base = std::move(fallback);
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
  // The overrides all at once, validated once: their order does not matter.
  ValidatedScene sc = loaded ? std::move(*loaded) : validated(std::move(base), sets);
  // Cam geometry (convexity, self-intersection) is checked by the Cam itself; name the
  // file or --set the offending key came from, not the Cam's own "<cam>".
  try {
    camdyn::detail::shared_cam(sc->cam);  // built once: the run shares it
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

std::unique_ptr<Simulator> checked_simulator(const ValidatedScene& sc) {
  try {
    return std::make_unique<Simulator>(sc);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(sc->source, 0, "scene", sc->title, std::string("cannot build the model: ") + e.what());
  }
}

bool write_stdout(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  if (!text.empty() && text.back() != '\n') std::fputc('\n', stdout);
  return std::fflush(stdout) == 0 && !std::ferror(stdout);
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
                    const std::string& script_override) {
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

// jump and sweep need a scene of the user's (no built-in default): the resolved, validated
// scene from the file or --case with the --set overrides.
Scene required_scene(const char* cmd, const CommonOpts& c) {
  if (c.scene_file.empty() && c.case_name.empty())
    throw SceneError(cmd, 0, "SCENE", "", "give a scene file (or --case A|B1|B2)");
  return build_scene(c.scene_file, c.case_name, c.sets, default_scene()).scene();  // resolved and validated
}

}  // namespace camdyn_cli
