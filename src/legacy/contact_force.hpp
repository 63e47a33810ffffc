// camdyn (private) — the contact force a method hands its engine (src/legacy/engine.hpp).
//
//   M q̈ + C q̇ + K q = f₀ + e₀ F:   the engine integrates the follower and asks the running
//   method's ContactForce for F; with none set, F = 0 (free flight).
//
// The engine knows nothing of contact models: each method owns its force and sets it
// (Engine::set_contact). The forces of the methods:
//   StepRamp      Lee's force shape over one step (lee_classic.cpp, replay.cpp).
// (The follower stack keeps Lee's classic step only; every other method runs on the
// mechanism, src/contact/contact_run.hpp.)
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "camdyn/cam.hpp"

namespace camdyn {

/// The force F on the contact node (node 0), F > 0 pushing the follower away from the cam.
class ContactForce {
 public:
  virtual ~ContactForce() = default;
  /// F at time t for the contact node's displacement q₀ and velocity v₀ (Lee's force
  /// shapes do not depend on the state: the Newton matrix has no contact term).
  virtual double force(double t, double q0, double v0) const = 0;
};

/// Lee's force over the step [t0, t0 + h]:
///   F(t) = F0 + (F1 − F0) x + Fc·4x(1 − x),   x = (t − t0)/h
/// (Fc = 0: the classic linear ramp; Fc ≠ 0: the located step's two-parameter shape).
struct StepRamp final : ContactForce {
  double t0 = 0, h = 1, F0 = 0, F1 = 0, Fc = 0;
  double force(double t, double, double) const override {
    const double x = (t - t0) / h;
    return F0 + (F1 - F0) * x + Fc * 4.0 * x * (1.0 - x);
  }
};

}  // namespace camdyn
