// camdyn (private) — a generic engine on SUNDIALS for y' = f(t, y) with dense linear
// algebra: the integrator of the network (several-contact) methods.
//
//   arkode-erk   ERKStep, Dormand–Prince 5(4)
//   arkode-dirk  ARKStep, SDIRK 5-stage 4(3), SUNDIALS dense matrix + dense LU, the
//                Jacobian from OdeSystem::jacobian (exact) or SUNDIALS' difference quotients
//   cvode-bdf    CVODE BDF, same linear algebra
//
// It knows nothing of scenes, followers or contacts: the contact method owns the right-hand
// side (the force law is inside f) and the root functions. Two ways to drive it, as the
// single-contact Engine (engine.hpp):
//   * trial steps: step(t, y, h) takes exactly one step of size h from (t, y), returns the
//     end state and the WRMS norm of the local error estimate (one-step engines; CVODE
//     integrates [t, t+h] under its own error control and returns 0);
//   * native stepping: reinit(t, y), then advance(tout) takes one internal,
//     error-controlled step, never past tout, stopping at a root of the root functions.
// Every SUNDIALS flag is checked (negative → SundialsError naming the call); the callbacks
// catch every exception and return −1, so none crosses SUNDIALS. SUNDIALS treats −1 as an
// unrecoverable failure: the step fails and step()/advance() throw SundialsError, whose
// message carries the exception's what(); the engine is usable again after reinit()/step()
// from a saved state. ERK/DIRK trial steps ignore SolverSpec::max_step (h is the caller's).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "camdyn/scene.hpp"
#include "engine.hpp"  // SundialsError, check_flag, EngineStats

namespace camdyn {

/// The system an OdeEngine integrates.
struct OdeSystem {
  /// Number of unknowns, ≥ 1.
  int size = 0;
  /// ydot = f(t, y). May throw (the engine's callback turns it into a failed step:
  /// SundialsError from step()/advance()).
  std::function<void(double t, const double* y, double* ydot)> rhs;
  /// Optional dense Jacobian J = ∂f/∂y (size × size, column-major Eigen matrix, already
  /// sized). Empty: SUNDIALS' difference-quotient Jacobian (implicit engines only).
  std::function<void(double t, const double* y, Eigen::MatrixXd& J)> jacobian;
  /// true: f is linear in y (ARKStepSetLinear / one Newton iteration per stage with the
  /// exact Jacobian; trial steps are then exactly affine in anything f depends on
  /// linearly). Needs `jacobian`.
  bool linear = false;
  /// cvode-bdf only: the largest BDF order (0: CVODE's default 5). Orders ≥ 3 are not
  /// A-stable: an undamped stiff system (a chain of stiff springs and bars) wants ≤ 2.
  int max_order = 0;
};

class OdeEngine {
 public:
  virtual ~OdeEngine() = default;
  /// "arkode-erk" | "arkode-dirk" | "cvode-bdf".
  virtual const char* name() const = 0;
  /// Order of the embedded error estimate + 1 (the exponent of a step controller).
  virtual int error_order() const = 0;
  /// True if step() returns a meaningful local error estimate (ERK, DIRK); false for CVODE.
  virtual bool estimates_error() const = 0;

  /// One step of exactly h from (t, y); y_out = state at t + h. Returns the WRMS norm of
  /// the local error estimate (≤ 1 acceptable), 0 if !estimates_error().
  /// @throws SundialsError (e.g. the right-hand side threw).
  virtual double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) = 0;
  /// The unweighted local error estimate of the last step() (size() entries).
  const Eigen::VectorXd& local_error() const { return local_error_; }
  /// WRMS norm of err with the engine's tolerances, weights rtol·|y_i| + atol.
  double wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const;

  /// Native mode: restart from (t, y) with the solver's own error control.
  virtual void reinit(double t, const Eigen::VectorXd& y) = 0;
  /// One internal step toward tout (never past it). Returns the time reached; y_out holds
  /// the state there. After a root: hit_root() and root_info().
  virtual double advance(double tout, Eigen::VectorXd& y_out) = 0;
  /// Native mode: the solution at t inside the last internal step (SUNDIALS' own
  /// interpolant, GetDky with k = 0). @pre t within the last step.
  virtual void dense(double t, Eigen::VectorXd& y_out) = 0;

  /// Root functions g(t, y) (count n ≥ 0; 0 switches rootfinding off); all directions.
  using RootFn = std::function<void(double t, const double* y, double* g)>;
  virtual void set_roots(int n, RootFn fn) = 0;
  /// After advance(): true if it stopped at a root; root_info()[i] ≠ 0 for the functions
  /// that have a root there (sign: direction of the crossing, as SUNDIALS reports it).
  bool hit_root() const { return hit_root_; }
  const std::vector<int>& root_info() const { return root_info_; }

  const EngineStats& stats() const { return stats_; }
  int size() const { return n_; }

  /// The engine for `integrator` ("ida" is not an OdeEngine: @throws std::invalid_argument).
  /// trial: made for step() (own error test; ERK/DIRK tolerances huge inside SUNDIALS);
  /// otherwise for native stepping with spec.rtol, spec.atol.
  static std::unique_ptr<OdeEngine> make(Integrator integrator, const SolverSpec& spec,
                                         OdeSystem system, bool trial);

 protected:
  OdeEngine(const SolverSpec& spec, OdeSystem sys) : spec_(spec), sys_(std::move(sys)), n_(sys_.size) {}
  SolverSpec spec_;
  OdeSystem sys_;
  int n_;
  EngineStats stats_;
  Eigen::VectorXd local_error_;
  bool hit_root_ = false;
  std::vector<int> root_info_;
  RootFn root_fn_;
};

}  // namespace camdyn
