// camdyn (private) — integrator engines on SUNDIALS behind one interface.
//
//   First-order form, y = [q; v] (2n unknowns):
//     q̇ = v,   M v̇ = f₀ − K q − C v + e₀ F(t, q₀, v₀)
//   F is the contact force law of the running method: a ramp F(t) linear over the step
//   (Lee), a penalty law F(s, ŝ) (penalty), or zero (free flight).
//
// Two ways to drive an engine:
//   * trial steps (Lee): step(t, y, h) takes exactly one step of size h from a saved
//     state and returns the end state and the WRMS norm of the local error estimate;
//     the same step can be retaken with another force ramp.
//   * native stepping (penalty, event): reinit(t, y) then advance(tout) takes one
//     internal, error-controlled step, never past tout (optionally stopping at a root).
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

namespace camdyn {

/// A negative SUNDIALS return flag, turned into an exception naming the call.
class SundialsError : public std::runtime_error {
 public:
  SundialsError(const std::string& call, int flag)
      : std::runtime_error(call + " failed with flag " + std::to_string(flag)), flag_(flag) {}
  int flag() const { return flag_; }

 private:
  int flag_;
};

/// Throws SundialsError if flag < 0. Returns flag otherwise.
int check_flag(int flag, const char* call);

/// "auto" → dense for a handful of unknowns, KLU beyond.
LinearSolverKind resolve_linear_solver(const Scene& scene, int nodes);

/// The contact force on node 0 (F = −p ≥ 0 pushes the follower away from the cam).
struct ContactLaw {
  enum class Kind { None, Ramp, Penalty, Prescribed, Held, Table };
  Kind kind = Kind::None;
  // Ramp: F(t) = F0 + (F1 − F0)x + Fc·4x(1 − x), x = (t − t0)/h on the step [t0, t0 + h]
  // (Fc = 0: the classic linear ramp; Fc ≠ 0: the located step's two-parameter shape).
  double t0 = 0, h = 1, F0 = 0, F1 = 0, Fc = 0;
  // Penalty: s = X_C − q₀ (penetration > 0), ŝ = Ẋ_C − v₀.
  //   linear:        F = max(0, k_p s + c_p ŝ)               while s > 0
  //   hunt_crossley: F = max(0, k_p sⁿ (1 + c_p ŝ))          while s > 0
  const Cam* cam = nullptr;
  const CamDrive* drive = nullptr;
  PenaltyLaw law = PenaltyLaw::Linear;
  double kp = 0, cp = 0, exponent = 1.5;
  // Prescribed (held bar, node 0 moving with the cam; this model's node 0 is the bar's
  // node 1): F = −K₁₀ X_C(t) − C₁₀ Ẋ_C(t) − M₁₀ Ẍ_C(t), independent of the state.
  double k10 = 0, c10 = 0, m10 = 0;
  // Table: F(t) piecewise linear through (table_t[i], table_F[i]) (increasing times; the
  // end values outside) — a given force history (bench/bench_overhead's replay).
  const std::vector<double>* table_t = nullptr;
  const std::vector<double>* table_F = nullptr;
  // Held (node 0 on the cam, the full follower; cvode-bdf only): the acceleration level's
  // force F = (Ẍ_C − ü₀,free(q, v)) / M*, a function of the whole state that the engine's
  // right-hand side evaluates itself (force() returns 0 for it), so that node 0 moves with
  // the cam's acceleration; the displacement and velocity levels are the engine's
  // projection (Engine::set_held_projection).

  double force(double t, double q0, double v0) const;
  /// The cam's contact-point motion at t (needs cam and drive). The last value is kept:
  /// the right-hand side, the projection and the root function of one step ask for the
  /// same t.
  CamMotion cam_motion(double t) const;
  mutable double cached_t_ = std::numeric_limits<double>::quiet_NaN();
  mutable CamMotion cached_motion_{};
  /// Penalty only (else 0): the elastic part of the law, F_el(s) = k_p s (linear) or
  /// k_p sⁿ (Hunt–Crossley) for s > 0, and its stored energy V_p(s) = ∫₀ˢ F_el = ½k_p s²
  /// or k_p sⁿ⁺¹/(n+1). The rest of the force, F − F_el, is the damper's: its power
  /// (F − F_el)·ŝ ≥ 0 is dissipated (also where the clipping F = 0 releases V_p).
  double elastic_force(double t, double q0) const;
  double stored_energy(double t, double q0) const;
  /// dF/dq₀ and dF/dv₀ (for the Jacobian); zero except for an active penalty.
  void derivatives(double t, double q0, double v0, double* dFdq, double* dFdv) const;
};

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
  /// True if step() maps the contact force's shape parameters affinely to the end state
  /// and to the local error estimate, exactly up to round-off, for a fixed h (one-step
  /// engines with a fixed stage structure: ERK, and DIRK with its linear stage solves).
  /// CVODE chooses its internal steps from the solution: not exactly affine.
  virtual bool affine_steps() const { return estimates_error(); }
  /// true: the right-hand side drops f₀ (the preload), so that a step from y = 0 gives the
  /// follower's response to the contact force alone (Lee's shape responses, exact also
  /// for steps whose response is far below the round-off of the state).
  void set_homogeneous(bool on) { homogeneous_ = on; }
  /// The unweighted local error estimate of the last step() (empty if none).
  const Eigen::VectorXd& local_error() const { return local_error_; }
  /// WRMS norm with the engine's tolerances, weights from y.
  double wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const;

  /// Engine's own proposal for the next step after step() (0 = no opinion).
  virtual double suggested_step() const { return 0.0; }

  /// Native mode: restart from (t, y) with the solver's own error control.
  virtual void reinit(double t, const Eigen::VectorXd& y) = 0;
  /// One internal step toward tout (never past it). Returns the time reached; y_out holds
  /// the state there.
  virtual double advance(double tout, Eigen::VectorXd& y_out) = 0;

  /// Native mode, multistep engines (CVODE): allow BDF orders up to q, with CVODE's BDF
  /// stability-limit detection on (it lowers the order where orders ≥ 3, not A-stable,
  /// would amplify an undamped stiff mode). No-op for the one-step engines.
  virtual void set_max_order(int /*q*/) {}

  /// Native mode, held contact (ContactLaw::Kind::Held): on, every internal step's
  /// corrected state is projected onto u₀ = X_C(t), u̇₀ = Ẋ_C(t) by a rigid translation
  /// of the follower (no strain changes), and the projection enters the engine's history (CVODE's projection interface: no restart). Only the
  /// multistep engine supports it. @throws std::logic_error on the other engines.
  virtual void set_held_projection(bool /*on*/) {
    throw std::logic_error(std::string("held projection: not supported by ") + name());
  }
  /// The held contact's force at state y with node 0 on the cam (u₀ = X_C, u̇₀ = Ẋ_C):
  /// F = (Ẍ_C(t) − e₀ᵀM⁻¹(f₀ − Kq − Cv)) / M*. Not thread-safe (a buffer per engine).
  double held_force(double t, const double* y) const;

  /// Rootfinding (native mode): one function g(t, y); direction −1, 0 or +1.
  using RootFn = std::function<double(double t, const double* y)>;
  virtual void set_root(RootFn fn, int direction) = 0;
  /// After advance(): true if it stopped at a root of g.
  bool hit_root() const { return hit_root_; }

  const EngineStats& stats() const { return stats_; }
  ContactLaw& law() { return law_; }

 protected:
  /// ydot = f(t, y) with the current contact law. Counts evaluations.
  void rhs(double t, const double* y, double* ydot);
  /// The mass-matrix form (DIRK): fi = [v; f₀ − Kq − Cv + e₀F].
  void rhs_unscaled(double t, const double* y, double* out);

  Engine(std::shared_ptr<const FollowerModel> model, const SolverSpec& spec)
      : model_(std::move(model)), spec_(spec), n_(model_->n()), work_(model_->n()) {}

  std::shared_ptr<const FollowerModel> model_;
  SolverSpec spec_;
  int n_;
  ContactLaw law_;
  EngineStats stats_;
  Eigen::VectorXd work_, local_error_;
  RootFn root_fn_;
  bool hit_root_ = false;
  Eigen::VectorXd mass_col0_;  // M⁻¹e₀ (held contact), computed on first use
  mutable Eigen::VectorXd held_y_;  // held_force's state with node 0 on the cam
  const Eigen::VectorXd& mass_col0();
  bool homogeneous_ = false;
  static int root_callback(double t, const double* y, double* g, void* ud) noexcept;
};

/// Make the engine a scene asks for. @throws SundialsError on a SUNDIALS failure.
std::unique_ptr<Engine> make_engine(std::shared_ptr<const FollowerModel> model,
                                    const Scene& scene);
/// The same, with the use stated: trial = true for Lee's trial steps (tighter CVODE
/// Newton and error tolerances), false for native stepping.
std::unique_ptr<Engine> make_engine(std::shared_ptr<const FollowerModel> model,
                                    const Scene& scene, bool trial);

}  // namespace camdyn
