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

/// One accepted Lee step: the contact force F0 + (F1 − F0)x + Fc·4x(1 − x) over
/// [t0, t0 + h] (classic: Fc = 0), then an impulse on node 0 at t0 + h (located impacts).
struct LeeStep {
  double t0, h, F0, F1, Fc = 0.0, impulse = 0.0;
};

/// Records the accepted steps of a Lee run (and the last output row).
struct LeeStepRecorder : Observer {
  std::vector<LeeStep> steps;
  HistoryRow last_row;
  void on_row(const HistoryRow& r) override { last_row = r; }
  void on_lee_step(double t0, double h, double F0, double F1) override {
    steps.push_back({t0, h, F0, F1});
  }
  void on_lee_shape(double t0, double h, double F0, double F1, double Fc, double P) override {
    steps.push_back({t0, h, F0, F1, Fc, P});
  }
};

struct ReplayResult {
  Eigen::VectorXd y;         ///< state [q; v] after the last step
  double cpu_seconds = 0.0;  ///< std::clock: engine construction + the steps
  long engine_steps = 0;     ///< engine steps (internal steps for CVODE)
};

/// Integrates `steps` from the run's initial state with the scene's engine (trial-step
/// mode, StepRamp, src/legacy/contact_force.hpp). @pre scene resolved and validated (Simulator::scene()).
ReplayResult replay_lee_steps(const Scene& scene, const std::vector<LeeStep>& steps);

}  // namespace camdyn
