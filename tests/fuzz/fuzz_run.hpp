// The simulation half of the fuzz harness (issue 25), shared by the libFuzzer target
// (fuzz_scene.cpp) and the deterministic default-suite test (test_fuzz_runs.cpp): a scene
// that loads is run for a few steps, and every message it produces (the refusal's, the
// run's end, the full report) must be free of SUNDIALS flag numbers.
//
// The run is kept short whatever the scene says: t_end at most 2 ms, no history kept (no
// observer rows), at most 2000 steps, a 2 s wall budget (the run is stopped by the caller's
// flag, checked every 256 steps), at most 64 bar elements. A camdyn::SceneError from the
// Simulator is a refusal (fine); any other exception propagates (a finding).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <regex>
#include <string>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn_fuzz {

struct FewSteps {
  bool refused = false;   // SceneError when the Simulator was made or run
  bool finished = false;  // the run reached its (shortened) t_end
  std::string message;    // the refusal's or the run's message
  std::string report;     // Summary::FullReport() of a run
};

/// "flag -3", "flag 2": a SUNDIALS return code shown as a number.
inline bool has_flag_number(const std::string& text) {
  static const std::regex flag_number("flag -?[0-9]");
  return std::regex_search(text, flag_number);
}

/// The scene shortened to a few steps (see the file's comment).
inline camdyn::Scene shortened(camdyn::Scene s) {
  s.run.t_end = std::min(s.run.t_end, 2e-3);
  if (s.run.output_dt > s.run.t_end) s.run.output_dt = s.run.t_end;
  s.run.max_steps = std::min<long>(s.run.max_steps, 2000);
  s.follower.elements = std::min(s.follower.elements, 64);
  return s;
}

/// Run `scene` shortened for a few steps; SceneError → refused.
inline FewSteps run_few_steps(const camdyn::Scene& scene) {
  struct Budget : camdyn::Observer {
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    std::atomic<bool> stop{false};
    void check() {
      if (std::chrono::steady_clock::now() - start > std::chrono::seconds(2)) stop = true;
    }
    // progress comes every 256 accepted steps: rows and Lee's trial steps check as well
    // (a scene whose every step is slow under the sanitizers ran 13 s past the budget)
    void on_progress(double, double, long) override { check(); }
    void on_row(const camdyn::HistoryRow&) override { check(); }
    void on_step(const camdyn::StepInfo&) override { check(); }
  } budget;
  FewSteps out;
  try {
    camdyn::Simulator sim(shortened(scene));
    const camdyn::Summary sum = sim.run(&budget, &budget.stop);
    out.finished = sum.finished;
    out.message = sum.message;
    out.report = sum.FullReport();
  } catch (const camdyn::SceneError& e) {
    out.refused = true;
    out.message = e.what();
  }
  return out;
}

}  // namespace camdyn_fuzz
