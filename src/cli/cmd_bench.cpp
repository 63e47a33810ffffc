// camdyn — command-line tool: `camdyn bench` (and its --tolerance-sweep).
#include "commands.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "study/bench.hpp"
#include "study/bench_tolerance.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"

namespace camdyn_cli {

using namespace camdyn;
namespace fs = std::filesystem;

namespace {

// The progress lines of the bench and the tolerance sweep: stderr, flushed per line.
void log_line(const std::string& line) {
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

/// The example trains the bench knows by name (found in ./examples or the source tree).
const std::map<std::string, std::string>& train_files() {
  static const std::map<std::string, std::string> t{{"ohc", "ohc_bucket_tappet.toml"},
                                                    {"ohv", "ohv_pushrod_train.toml"}};
  return t;
}

/// A scene named on the command line: a file, a bench case (bench_case()) or an example
/// train (ohc, ohv); its label.
/// @throws SceneError for a name that is none of them or a scene that does not load.
std::pair<Scene, std::string> named_scene(const std::string& name) {
  std::error_code ec;
  const auto& trains = train_files();
  if (fs::exists(name, ec) || (!is_bench_case(name) && !trains.count(name))) {
    Scene sc = load_scene_file(name);
    Cam cam(sc.cam);  // a bad profile is bad input
    return {std::move(sc), fs::path(name).stem().string()};
  }
  if (trains.count(name)) {
    fs::path f = fs::path("examples") / trains.at(name);
    if (!fs::exists(f, ec)) f = fs::path(CAMDYN_PLOT_SCRIPT_BUILD).parent_path().parent_path() / "examples" / trains.at(name);
    if (!fs::exists(f, ec))
      throw SceneError("bench", 0, "scene", name, "examples/" + trains.at(name) + " not found");
    return {load_scene_file(f.string()), name};
  }
  return {bench_case(name), name};
}

/// `camdyn bench --tolerance-sweep`: scene names A, A7, B1, B2 (t_end 0.1 unless --t-end),
/// stiff, ohc and ohv (examples/ohc_bucket_tappet.toml, examples/ohv_pushrod_train.toml:
/// one revolution), or scene files; none: all of them.
int cmd_tolerance_sweep(const BenchOpts& o) {
  ToleranceSweepOptions to;
  std::vector<std::string> names = o.scenes;
  if (names.empty()) names = {"A", "A7", "B1", "B2", "stiff", "ohc", "ohv"};
  for (const auto& name : names) {
    auto [sc, label] = named_scene(name);
    std::error_code ec;
    if (is_bench_case(name) && name != "stiff" && !fs::exists(name, ec)) sc.run.t_end = 0.1;
    to.scenes.push_back(std::move(sc));
    to.labels.push_back(label);
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
    to.log = log_line;
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

}  // namespace

int cmd_bench(const BenchOpts& o) {
  if (o.tolerance_sweep) return cmd_tolerance_sweep(o);
  // Input stage: every error here is bad input (exit 2, raised to main()).
  BenchOptions bo;
  for (const auto& name : o.scenes) {
    auto [sc, label] = named_scene(name);
    resolve_defaults(sc);
    validate(sc);
    bo.scenes.push_back(std::move(sc));
    bo.labels.push_back(std::move(label));
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
  if (!o.no_cache) {
    bo.reference_cache_dir = o.reference_cache;
    if (bo.reference_cache_dir.empty()) {
      const char* xdg = std::getenv("XDG_CACHE_HOME");
      const char* home = std::getenv("HOME");
      if (xdg && *xdg)
        bo.reference_cache_dir = (fs::path(xdg) / "camdyn" / "bench").string();
      else if (home && *home)
        bo.reference_cache_dir = (fs::path(home) / ".cache" / "camdyn" / "bench").string();
    }
  }
  ensure_output_dir(o.out);
  if (!o.quiet)
    bo.log = log_line;

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

}  // namespace camdyn_cli
