// camdyn (private) — the single-follower stack's integrator engines on SUNDIALS behind one
// interface (Lee's classic step only since issue 23; the mechanism's are src/engine/ode_engine.hpp).
//
//   First-order form, y = [q; v] (2n unknowns):
//     q̇ = v,   M v̇ = f₀ − K q − C v + e₀ F(t, q₀, v₀)
//   F is the running method's ContactForce (src/legacy/contact_force.hpp: Lee's force shape over
//   a step, StepRamp; none set: F = 0, free flight). The engine
//   knows nothing of contact models or scenes: it gets a follower model, the solver's
//   settings and, from the method, the force.
//
// How an engine is driven:
//   * trial steps (Lee's classic step): step(t, y, h) takes exactly one step of size h from a saved
//     state and returns the end state and the WRMS norm of the local error estimate;
//     the same step can be retaken with another force ramp.
//   (The native mode — reinit/advance, roots — was deleted with the follower stack's
//   penalty and event methods in issue 23: these engines serve Lee's classic step and
//   its replay only; every other method runs on src/engine/ode_engine.hpp.)
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/model.hpp"
#include "camdyn/scene.hpp"
#include "legacy/contact_force.hpp"

namespace camdyn {

/// What a SUNDIALS return flag of `call` means, in words ("the error test failed
/// repeatedly (…)"); "failed" where the flag carries no meaning (creation failures, and
/// calls whose name explains itself in parentheses). src/engine/sundials_flags.cpp.
std::string sundials_flag_words(const std::string& call, int flag);

/// A negative SUNDIALS return flag, turned into an exception naming the call and saying
/// what the flag means (never the bare number: issue 25).
class SundialsError : public std::runtime_error {
 public:
  SundialsError(const std::string& call, int flag)
      : std::runtime_error(call + ": " + sundials_flag_words(call, flag)), flag_(flag) {}
  int flag() const { return flag_; }

 private:
  int flag_;
};

/// Throws SundialsError if flag < 0. Returns flag otherwise.
int check_flag(int flag, const char* call);

/// "auto" → dense for a handful of unknowns, KLU beyond.
LinearSolverKind resolve_linear_solver(const SolverSpec& solver, int nodes);

struct EngineStats {
  long steps = 0;         ///< internal steps taken (accepted by the engine)
  long rhs_evals = 0;     ///< right-hand-side evaluations
  long lin_setups = 0;    ///< numeric factorisations of the Newton matrix (implicit engines)
  long lin_analyses = 0;  ///< symbolic analyses (KLU orderings) of its sparsity pattern
  long reinits = 0;       ///< restarts (CVODE history lost)
};

class Engine {
 public:
  virtual ~Engine() = default;
  virtual const char* name() const = 0;
  /// Order of the embedded error estimate + 1 (the exponent of the step controller).
  virtual int error_order() const = 0;
  /// True if step() returns a meaningful local error estimate; false if the engine
  /// controls its own error inside the step (CVODE) and step() never asks for rejection.
  virtual bool estimates_error() const { return true; }

  /// One step of exactly h from (t, y); y_out = state at t + h. Returns the WRMS norm of
  /// the local error estimate (≤ 1: acceptable), 0 if !estimates_error().
  virtual double step(double t, const Eigen::VectorXd& y, double h, Eigen::VectorXd& y_out) = 0;
  /// WRMS norm with the engine's tolerances, weights from y.
  double wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const;

  /// The force on node 0 from now on (borrowed: it must outlive its use; nullptr: F = 0).
  void set_contact(const ContactForce* force) { contact_ = force; }

  const EngineStats& stats() const { return stats_; }

 protected:
  /// ydot = f(t, y) with the current contact force. Counts evaluations.
  void rhs(double t, const double* y, double* ydot);
  /// The mass-matrix form (DIRK): fi = [v; f₀ − Kq − Cv + e₀F].
  void rhs_unscaled(double t, const double* y, double* out);

  Engine(std::shared_ptr<const FollowerModel> model, const SolverSpec& spec)
      : model_(std::move(model)), spec_(spec), n_(model_->n()), work_(model_->n()) {}

  std::shared_ptr<const FollowerModel> model_;
  SolverSpec spec_;
  int n_;
  const ContactForce* contact_ = nullptr;
  EngineStats stats_;
  Eigen::VectorXd work_, local_error_;
};

/// Make the engine `solver` asks for. trial = true for Lee's trial steps (tighter CVODE
/// Newton and error tolerances; tol_u > 0: CVODE's tolerances kept ≤ 10⁻² tol_u), false
/// for an engine without a contact method (tests). @throws SundialsError on a SUNDIALS failure.
std::unique_ptr<Engine> make_engine(std::shared_ptr<const FollowerModel> model, const SolverSpec& solver,
                                    bool trial, double tol_u = 0.0);

}  // namespace camdyn
