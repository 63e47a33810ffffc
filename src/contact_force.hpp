// camdyn (private) — the contact force a method hands its engine (src/engine.hpp).
//
//   M q̈ + C q̇ + K q = f₀ + e₀ F:   the engine integrates the follower and asks the running
//   method's ContactForce for F; with none set, F = 0 (free flight).
//
// The engine knows nothing of contact models: each method owns its force and sets it
// (Engine::set_contact). The forces of the methods:
//   StepRamp      Lee's force shape over one step (lee_classic, lee_located, replay);
//   ForceTable    a given force history (replay of a run: bench/bench_overhead);
//   PenaltyForce  the spring–damper laws (src/contact/penalty.cpp, laws in penalty_law.hpp);
//   the held bar's coupling to the cam (src/contact/event.cpp);
//   HeldContact   node 0 held on the cam, the force from the acceleration level
//                 (src/contact/lee_multistep.cpp; the engine evaluates it).
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
  /// F at time t for the contact node's displacement q₀ and velocity v₀.
  virtual double force(double t, double q0, double v0) const = 0;
  /// ∂F/∂q₀ and ∂F/∂v₀ (the implicit engines' Newton matrix); zero unless the force
  /// depends on the state.
  virtual void derivatives(double /*t*/, double /*q0*/, double /*v0*/, double* dFdq, double* dFdv) const {
    *dFdq = 0.0;
    *dFdv = 0.0;
  }
};

/// The held contact: node 0 moves on a prescribed path P(t) (the cam's contact point).
/// Its force is a function of the whole state, F = (P̈ − ü₀,free(q, v)) / M* (the
/// acceleration level), which the engine's right-hand side evaluates itself, so force()
/// is 0; the displacement and velocity levels are the engine's projection
/// (Engine::set_held_projection). The Newton matrix is bordered for it (engines.cpp).
class HeldContact : public ContactForce {
 public:
  double force(double, double, double) const final { return 0.0; }
  /// P(t), Ṗ(t), P̈(t).
  virtual CamMotion path(double t) const = 0;
};

/// The cam's contact-point motion at t with the last value kept: the right-hand side,
/// the projection and the root function of one step ask for the same t.
class CamPath {
 public:
  CamPath(const Cam& cam, const CamDrive& drive) : cam_(&cam), drive_(&drive) {}
  CamMotion at(double t) const {
    if (t == cached_t_) return cached_;
    cached_ = cam_->motion(drive_->theta(t), drive_->omega(t), drive_->omega_dot(t));
    cached_t_ = t;
    return cached_;
  }

 private:
  const Cam* cam_;
  const CamDrive* drive_;
  mutable double cached_t_ = std::numeric_limits<double>::quiet_NaN();
  mutable CamMotion cached_{};
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

/// A force history: piecewise linear through (t[i], F[i]) (increasing times; the end
/// values outside). The vectors are borrowed and must outlive the force.
struct ForceTable final : ContactForce {
  const std::vector<double>* t = nullptr;
  const std::vector<double>* F = nullptr;
  double force(double time, double, double) const override {
    const std::vector<double>& T = *t;
    const std::vector<double>& V = *F;
    if (time <= T.front()) return V.front();
    if (time >= T.back()) return V.back();
    const size_t i = size_t(std::upper_bound(T.begin(), T.end(), time) - T.begin());  // T[i-1] ≤ t < T[i]
    const double x = (time - T[i - 1]) / (T[i] - T[i - 1]);
    return V[i - 1] + x * (V[i] - V[i - 1]);
  }
};

}  // namespace camdyn
