// camdyn (private) — replay of a Lee run's step sequence with the contact force given.
//
// Lee's method wraps every step in an iteration (several integrations per step). Its
// overhead is measured against the same engine integrating the same accepted steps with
// the contact force ramps the run found, once each, no iteration: Observer::on_lee_step
// records the sequence, replay_lee_steps integrates it (bench/bench_overhead.cpp).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "camdyn/simulator.hpp"

namespace camdyn {

/// One accepted Lee step: the contact force ramp F0 → F1 over [t0, t0 + h].
struct LeeStep {
  double t0, h, F0, F1;
};

/// Records the accepted steps of a Lee run (and the last output row).
struct LeeStepRecorder : Observer {
  std::vector<LeeStep> steps;
  HistoryRow last_row;
  void on_row(const HistoryRow& r) override { last_row = r; }
  void on_lee_step(double t0, double h, double F0, double F1) override {
    steps.push_back({t0, h, F0, F1});
  }
};

struct ReplayResult {
  Eigen::VectorXd y;         ///< state [q; v] after the last step
  double cpu_seconds = 0.0;  ///< std::clock: engine construction + the steps
  long engine_steps = 0;     ///< engine steps (internal steps for CVODE)
};

/// Integrates `steps` from the run's initial state with the scene's engine (trial-step
/// mode, ContactLaw::Ramp). @pre scene resolved and validated (Simulator::scene()).
ReplayResult replay_lee_steps(const Scene& scene, const std::vector<LeeStep>& steps);

}  // namespace camdyn
