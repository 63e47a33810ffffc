// Large elastic followers (issue #8): whole Lee runs of case B1 with N elements.
//
//   For N = 10², 10³, …, 10⁶ and each engine (arkode-erk, arkode-dirk, cvode-bdf with
//   KLU), Lee's method over the first T seconds of case B1 with the bar cut into N
//   elements (everything else as the paper's case: consistent mass, tol_u 1e-7, rtol
//   1e-6). Reported: CPU per accepted step, accepted steps per simulated second, CPU per
//   simulated second, numeric factorisations and symbolic analyses (implicit engines),
//   and the peak resident memory of the process beyond its size before the model was
//   built, per element.
//
//   usage:
//     bench_scale run N ENGINE T [KEY=VALUE ...]
//         one run in this process (scene overrides as camdyn run --set, applied after
//         N, ENGINE and the window); prints one CSV row (no header)
//     bench_scale sweep [MAX_N=1000000] [CONFIGS=erk,dirk,cvode,dirk-loose] [BUDGET_S=600]
//         each (N, configuration) in its own process (a clean peak RSS per run), the
//         window T from window_for() below, at most kMaxSteps accepted + rejected steps
//         per run (a run stopped there reports the time it reached); CSV on stdout.
//         After a configuration's run at N took more than BUDGET_S/12 CPU seconds, its
//         larger N are skipped (noted in the CSV).
//   The CSV feeds scripts/bench_scale_plot.py (log–log figure, README table).
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"

using namespace camdyn;

namespace {

constexpr long kMaxSteps = 400;

const char* kHeader =
    "N,engine,settings,t_window,t_reached,finished,steps,rejected,lin_setups,lin_analyses,rhs_evals,"
    "cpu_s,ms_per_step,steps_per_sim_s,cpu_s_per_sim_s,mean_iter_u,mean_iter_v,u_c_end,"
    "rss_base_mb,rss_peak_mb,bytes_per_element";

long max_rss_kb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;  // kB on Linux
}

// The simulated window per engine and mesh: T = 0.08/N s. The explicit engine's step is
// bounded by the mesh (Δt ≈ 0.5 h_e/c, measured), so it takes ≈ 180 steps at every N and
// 10⁶ elements finish in minutes. The implicit engines at the paper's tolerances take
// smaller steps (runs are capped at kMaxSteps); cvode-bdf's Lee steps hold hundreds of
// internal steps, so its window is 1/20 of that (at least 1e-8 s).
double window_for(long N, const std::string& engine) {
  const double base = 2e-3 * 40.0 / double(N);  // 2 ms at the paper's 40 elements
  if (engine == "cvode-bdf") return std::max(1e-8, 0.05 * base);
  return std::max(1e-8, base);
}

int run_one(long N, const std::string& engine, double T, const std::vector<std::string>& sets) {
  const long rss0 = max_rss_kb();
  Scene s = paper_case("B1");
  s.follower.elements = int(N);
  s.solver.integrator = engine == "arkode-erk"    ? Integrator::ArkodeErk
                        : engine == "arkode-dirk" ? Integrator::ArkodeDirk
                                                  : Integrator::CvodeBdf;
  s.run.t_end = T;
  s.run.output_dt = T;  // rows at 0 and T only: no O(N) output work per step
  std::string settings;
  for (const std::string& kv : sets) {
    apply_override(s, kv);
    settings += (settings.empty() ? "" : " ") + kv;
  }
  struct LastRow : Observer {
    double u_c = NAN;
    void on_row(const HistoryRow& row) override { u_c = row.u_c; }
  } last;
  Simulator sim(s);
  const Summary r = sim.run(&last);
  const long rss1 = max_rss_kb();
  const double steps = double(std::max(1L, r.steps));
  std::printf("%ld,%s,%s,%.6g,%.6g,%d,%ld,%ld,%ld,%ld,%ld,%.6g,%.6g,%.6g,%.6g,%.4g,%.4g,%.12g,%.1f,%.1f,%.1f\n", N,
              engine.c_str(), settings.c_str(), T, r.t_end, r.finished ? 1 : 0, r.steps,
              r.rejected_steps, r.lin_setups, r.lin_analyses, r.rhs_evals, r.cpu_seconds,
              1e3 * r.cpu_seconds / steps, double(r.steps) / r.t_end, r.cpu_seconds / r.t_end,
              r.level_u.mean(), r.level_v.mean(), last.u_c, rss0 / 1024.0, rss1 / 1024.0,
              1024.0 * double(rss1 - rss0) / double(N));
  if (!r.finished) std::fprintf(stderr, "N = %ld %s %s: %s\n", N, engine.c_str(), settings.c_str(), r.message.c_str());
  return 0;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream in(s);
  for (std::string x; std::getline(in, x, ',');) v.push_back(x);
  return v;
}

struct Config {
  const char* name;
  const char* engine;
  const char* sets;  // extra overrides, space separated
};
const Config kConfigs[] = {
    {"erk", "arkode-erk", ""},
    {"dirk", "arkode-dirk", ""},
    {"cvode", "cvode-bdf", ""},
    {"dirk-loose", "arkode-dirk", "solver.rtol=1e-3 solver.atol=1e-6"},
};

int sweep(const char* self, long max_n, const std::vector<std::string>& names, double budget) {
  std::printf("%s,note\n", kHeader);
  std::fflush(stdout);
  for (const std::string& name : names) {
    const Config* c = nullptr;
    for (const Config& k : kConfigs)
      if (name == k.name) c = &k;
    if (!c) {
      std::fprintf(stderr, "unknown configuration '%s' (erk, dirk, cvode, dirk-loose)\n", name.c_str());
      return 2;
    }
    bool skip = false;
    for (long N = 100; N <= max_n; N *= 10) {
      const double T = window_for(N, c->engine);
      if (skip) {
        std::printf("%ld,%s,%s,%.6g,,,,,,,,,,,,,,,,,,skipped: the previous N took over budget/12\n", N,
                    c->engine, c->sets, T);
        continue;
      }
      char cmd[1024];
      std::snprintf(cmd, sizeof cmd, "'%s' run %ld %s %.17g run.max_steps=%ld %s", self, N, c->engine, T,
                    kMaxSteps, c->sets);
      FILE* p = popen(cmd, "r");
      if (!p) return 1;
      char line[2048] = {0};
      const bool got = std::fgets(line, sizeof line, p) != nullptr;
      pclose(p);
      if (!got) {
        std::printf("%ld,%s,%s,%.6g,,,,,,,,,,,,,,,,,,failed\n", N, c->engine, c->sets, T);
        skip = true;
        continue;
      }
      std::string row(line);
      while (!row.empty() && (row.back() == '\n' || row.back() == '\r')) row.pop_back();
      const std::vector<std::string> f = split(row);
      const bool stopped = f.size() > 5 && f[5] == "0";
      std::printf("%s,%s\n", row.c_str(), stopped ? "stopped at run.max_steps" : "");
      std::fflush(stdout);
      if (f.size() > 11 && std::atof(f[11].c_str()) > budget / 12.0) skip = true;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "run" && argc >= 5) {
    std::vector<std::string> sets(argv + 5, argv + argc);
    try {
      return run_one(std::atol(argv[2]), argv[3], std::atof(argv[4]), sets);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_scale: %s\n", e.what());
      return 2;
    }
  }
  if (mode == "sweep") {
    const long max_n = argc > 2 ? std::atol(argv[2]) : 1000000;
    const std::vector<std::string> names = split(argc > 3 ? argv[3] : "erk,dirk,cvode,dirk-loose");
    const double budget = argc > 4 ? std::atof(argv[4]) : 600.0;
    return sweep(argv[0], max_n, names, budget);
  }
  std::fprintf(stderr,
               "usage: bench_scale run N ENGINE T [KEY=VALUE ...]\n"
               "       bench_scale sweep [MAX_N] [CONFIGS] [BUDGET_S]\n");
  return 2;
}
