// Contact overhead of Lee's method (issue #4): CPU of a Lee run divided by the CPU of
// the same engine integrating the same step sequence with the contact force given.
//
//   For each scene (paper cases A, B1, B2, shortened) and engine (arkode-erk,
//   arkode-dirk, cvode-bdf): run Lee with an Observer recording each accepted step's
//   velocity-level ramp (Observer::on_lee_step), then replay: a fresh engine of the same
//   kind takes exactly those steps with those ramps (StepRamp), once each, no
//   iteration (src/legacy/replay.cpp). Both timed with std::clock in this process (Lee: the
//   whole Simulator::run, engine construction and output rows included; replay: engine
//   construction and the steps); median of R repeats (a Lee run over 5 s CPU is timed
//   once, with its replay).
//
//   Lee's classic step only: it runs on the single-follower stack (solver.stack =
//   "follower"), whose engines replay a step sequence; the located step runs on the
//   mechanism since round 3 (issue 23) and reports no step ramps.
//
//   usage: bench_overhead [repeats=3] [t_end_elastic=0.05] [engines=arkode-erk,arkode-dirk,cvode-bdf]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "legacy/replay.hpp"

using namespace camdyn;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  const double t_elastic = argc > 2 ? std::atof(argv[2]) : 0.05;
  const std::string engines = argc > 3 ? argv[3] : "arkode-erk,arkode-dirk,cvode-bdf";
  std::printf("| scene | t_end | engine | step | Lee CPU s | replay CPU s | ratio | Lee steps | "
              "mean it. u / v / a | u_c(end) replay − Lee |\n|---|---|---|---|---:|---:|---:|---:|---|---:|\n");
  for (const char* name : {"A", "B1", "B2"}) {
    for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
     for (LeeStepKind kind : {LeeStepKind::Classic}) {
      if (engines.find(to_string(integ)) == std::string::npos) continue;
      Scene s = paper_case(name);
      s.contact.lee_step = kind;
      s.solver.stack = StackKind::Follower;  // the classic step's stack
      s.solver.integrator = integ;
      if (std::string(name) != "A") s.run.t_end = t_elastic;
      Simulator sim(s);
      std::vector<double> lee_cpu, rep_cpu;
      LeeStepRecorder first;
      Summary sum;
      ReplayResult rep;
      for (int k = 0; k < repeats; ++k) {
        LeeStepRecorder rec;
        const std::clock_t c0 = std::clock();
        sum = sim.run(&rec);
        lee_cpu.push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
        if (k == 0) first = std::move(rec);
        rep = replay_lee_steps(sim.scene(), first.steps);
        rep_cpu.push_back(rep.cpu_seconds);
        if (lee_cpu.back() > 5.0) break;
      }
      if (!sum.finished) std::fprintf(stderr, "%s %s: %s\n", name, to_string(integ), sum.message.c_str());
      const double L = median(lee_cpu), R = median(rep_cpu);
      const char* once = lee_cpu.size() < size_t(repeats) ? " (once)" : "";
      std::printf("| %s | %g | %s | %s | %.4g%s | %.4g | %.2f | %ld | %.2f / %.2f / %.2f | %.1e |\n", name,
                  s.run.t_end, to_string(integ), to_string(kind), L, once, R, L / R, sum.steps, sum.level_u.mean(),
                  sum.level_v.mean(), sum.level_a.mean(), rep.y[0] - first.last_row.u_c);
      std::fflush(stdout);
     }
    }
  }
  return 0;
}
