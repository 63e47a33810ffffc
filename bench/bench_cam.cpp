// Cost of Cam::evaluate() — the contact-point search on the solver's hot path.
//   *_SmallSteps: θ advances by a small step per call (what an integrator does);
//   *_RandomJumps: θ jumps at random over ±10 turns (worst case for the tracking hint);
//   Motion*: Cam::motion() (X_C, Ẋ_C, Ẍ_C only: what the contact methods call);
//   LawRunSteps: a run on a motion law (cycloidal / 3-4-5 rise and fall, 3.5 revolutions,
//   Lee located on arkode-erk) with and without steps landing on the law's joints
//   (cam.land_on_breaks): counters steps and rejected (issue 24: the breakpoints cost no
//   extra rejected steps).
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>
#include <camdyn/simulator.hpp>

namespace {

camdyn::CamSpec spec_of(camdyn::CamProfileKind kind) {
  camdyn::CamSpec s;  // default: the paper cam (points)
  s.profile = kind;
  if (kind == camdyn::CamProfileKind::Lift) {
    s.base_radius = 2.0;
    s.lift_angles_deg = {0, 60, 120, 180, 240, 300};
    s.lift = {0.0, 0.1, 0.5, 0.8, 0.4, 0.05};
  }
  if (kind == camdyn::CamProfileKind::Law) {  // issue 24: an exhaust-valve-like law
    s.base_radius = 2.0;
    s.law = "ramp 15 0.01; cycloidal 100 0.79; dwell 20; modsine 100 -0.79; ramp 15 -0.01; dwell 110";
  }
  if (kind == camdyn::CamProfileKind::Arc) {
    s.base_radius = 2.0;
    s.nose_radius = 0.6;
    s.nose_distance = 1.8;
    s.flank_radius = 5.0;
  }
  return s;
}

void SmallSteps(benchmark::State& state, camdyn::CamProfileKind kind) {
  const camdyn::Cam cam(spec_of(kind));
  const double dtheta = 1e-4 * static_cast<double>(state.range(0));
  double theta = 0.0, sink = 0.0;
  for (auto _ : state) {
    const camdyn::CamPoint p = cam.evaluate(theta);
    sink += p.X_C;
    theta += dtheta;
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations());
}

void RandomJumps(benchmark::State& state, camdyn::CamProfileKind kind) {
  const camdyn::Cam cam(spec_of(kind));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-62.8, 62.8);
  std::vector<double> th(4096);
  for (double& t : th) t = U(rng);
  std::size_t i = 0;
  double sink = 0.0;
  for (auto _ : state) {
    sink += cam.evaluate(th[i]).X_C;
    i = (i + 1) & 4095;
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations());
}

void MotionSmallSteps(benchmark::State& state, camdyn::CamProfileKind kind) {
  const camdyn::Cam cam(spec_of(kind));
  double theta = 0.0, sink = 0.0;
  for (auto _ : state) {
    sink += cam.motion(theta, 11.0, 0.0).Xddot;
    theta += 1e-4;
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(state.iterations());
}

// Arg(0): 3-4-5, Arg(1): cycloidal; Arg(2): land on the joints (1) or not (0).
void LawRunSteps(benchmark::State& state) {
  const char* kind = state.range(0) ? "cycloidal" : "poly345";
  const std::string law = std::string("dwell 100; ") + kind + " 70 0.5; dwell 20; " + kind + " 70 -0.5; dwell 100";
  camdyn::Scene sc = camdyn::parse_scene("[cam]\nprofile = \"law\"\nlaw = \"" + law +
                                             "\"\nbase_radius = 4.0\nspeed_rev_s = 1.75\n"
                                             "[follower]\nkind = \"rigid\"\n[run]\nt_end = 2.0\noutput_dt = 0.0\n",
                                         "<bench>");
  sc.cam.land_on_breaks = state.range(1) != 0;
  camdyn::Summary s;
  for (auto _ : state) {
    camdyn::Simulator sim(sc);
    s = sim.run();
    benchmark::DoNotOptimize(s.steps);
  }
  if (!s.finished) state.SkipWithError(s.message.c_str());
  state.counters["steps"] = double(s.steps);
  state.counters["rejected"] = double(s.rejected_steps);
}

void PaperMotionForm(benchmark::State& state) {
  const camdyn::Cam cam{camdyn::CamSpec{}};
  double theta = 0.0, sink = 0.0;
  for (auto _ : state) {
    sink += cam.motion_paper(theta, 11.0, 0.0).Xddot;
    theta += 1e-4;
    benchmark::DoNotOptimize(sink);
  }
}

void PaperConstruct(benchmark::State& state) {
  const camdyn::CamSpec s;
  for (auto _ : state) {
    camdyn::Cam cam(s);
    benchmark::DoNotOptimize(cam);
  }
}

}  // namespace

// Argument: step in units of 1e-4 rad (1 ≈ a solver step at 1.75 rev/s and Δt ≈ 1e-5 s).
BENCHMARK_CAPTURE(SmallSteps, paper, camdyn::CamProfileKind::Points)->Arg(1)->Arg(100);
BENCHMARK_CAPTURE(RandomJumps, paper, camdyn::CamProfileKind::Points);
BENCHMARK_CAPTURE(SmallSteps, circle, camdyn::CamProfileKind::Circle)->Arg(1);
BENCHMARK_CAPTURE(RandomJumps, circle, camdyn::CamProfileKind::Circle);
BENCHMARK_CAPTURE(SmallSteps, lift, camdyn::CamProfileKind::Lift)->Arg(1);
BENCHMARK_CAPTURE(RandomJumps, lift, camdyn::CamProfileKind::Lift);
BENCHMARK_CAPTURE(SmallSteps, law, camdyn::CamProfileKind::Law)->Arg(1);
BENCHMARK_CAPTURE(RandomJumps, law, camdyn::CamProfileKind::Law);
BENCHMARK_CAPTURE(SmallSteps, arc, camdyn::CamProfileKind::Arc)->Arg(1);
BENCHMARK_CAPTURE(RandomJumps, arc, camdyn::CamProfileKind::Arc);
BENCHMARK_CAPTURE(MotionSmallSteps, lift, camdyn::CamProfileKind::Lift);
BENCHMARK_CAPTURE(MotionSmallSteps, law, camdyn::CamProfileKind::Law);
BENCHMARK(LawRunSteps)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(PaperMotionForm);
BENCHMARK(PaperConstruct)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
