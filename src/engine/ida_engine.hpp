// camdyn (private) — held (holonomic) contacts of a mechanism as a DAE in SUNDIALS IDA.
// Formulation and index reduction: see the banner of ida_engine.cpp.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "engine/engine_stats.hpp"
#include "engine/sundials_error.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {

/// The held contacts S of a linear Mechanism (src/mechanism/mechanism.hpp: M q̈ + C q̇ + K q = f₀ +
/// TᵀF), g_S(q, t) = T_S q + g₀,S − X_C(t)·[cam] = 0 (a [camshaft]'s cam contact: its cam's
/// lift at its station's angle, the row T̃ = T − X_L′e_sᵀ at the state; ida_rows.hpp), integrated by IDA (variable-order
/// BDF) as a stabilised index-2 (GGL) DAE in y = [q; v; λ; μ; W]: λ the held contacts'
/// forces (compressive > 0), μ the GGL multipliers (0 on the exact solution), W = Σ over
/// held cam contacts ∫ λ_j Ẋ_C dt the cam's work; with the nonlinear elements' internal
/// states s (ṡ = g(t, q, v, s), element.hpp) y = [q; v; λ; μ; W; s]. Native stepping with IDA's own error
/// control on q, v, W (λ, μ are excluded from the error test). Rootfinding: λ_j
/// decreasing through 0 (a held contact turns tensile) and, for the contacts not held,
/// their gaps decreasing through 0 (an open contact closes). Every SUNDIALS flag is
/// checked (SundialsError).
class IdaHeldSet {
 public:
  /// The cam's lift at time t (the gaps' X_C).
  using CamFn = std::function<CamMotion(double t)>;

  /// @param mech the mechanism (kept by reference: it must outlive this object).
  /// @param held the held contacts S (W_SS nonsingular); the others are watched for closing.
  /// @param scene solver.rtol/atol/max_step/initial_step/linear_solver are used.
  /// @throws SundialsError on a SUNDIALS failure.
  IdaHeldSet(const Mechanism& mech, std::vector<int> held, const Scene& scene, CamFn cam);
  ~IdaHeldSet();
  IdaHeldSet(const IdaHeldSet&) = delete;
  IdaHeldSet& operator=(const IdaHeldSet&) = delete;

  /// Start at t0 from y = [q; v; s] (s: the mechanism's states() entries) on g_S = ġ_S = 0 and the held forces `lambda` (k entries,
  /// the acceleration level's), μ = 0, W = 0, with the consistent derivatives q̇ = v,
  /// v̇ = M⁻¹(f₀ − Kq − Cv + T_Sᵀλ), Ẇ = Σ λ_j Ẋ_C. @param tstop IDA never steps past it.
  void init(double t0, const Eigen::VectorXd& y, const Eigen::VectorXd& lambda, double tstop);
  /// Toward tout, never past it (IDASetStopTime(tout): the values returned are IDA's step
  /// values, not its interpolant). IDA_NORMAL: up to tout; one_step: one internal step.
  /// Returns the time reached (tout, a root, or the end of the step).
  double advance(double tout, bool one_step = false);
  /// After advance(): the held contact that turned tensile (index into the mechanism's
  /// contacts) or −1; the open contact that closed or −1.
  int tensile_contact() const { return tensile_; }
  int closing_contact() const { return closing_; }
  /// Stop watching for tensile held forces (after the first tensile time).
  void stop_tensile_roots();

  /// [q; v; s] at the time reached.
  const Eigen::VectorXd& state() const { return y_; }
  /// λ over the held contacts (in the order of `held`).
  const Eigen::VectorXd& lambda() const { return lambda_; }
  const std::vector<int>& held() const { return held_; }
  double work() const { return work_; }
  /// The energy the mechanism dissipated (its damping and elements) since init().
  double dissipated() const { return dissipated_; }
  /// Steps, residual evaluations (rhs_evals), linear-solver setups, symbolic analyses.
  EngineStats stats() const;
  /// Error-test plus convergence failures.
  long rejected_steps() const;
  LinearSolverKind linear_solver() const { return lsk_; }
  int unknowns() const { return N_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> held_;
  LinearSolverKind lsk_;
  int N_ = 0;
  Eigen::VectorXd y_, lambda_;
  double work_ = 0, dissipated_ = 0;
  int tensile_ = -1, closing_ = -1;
};

}  // namespace camdyn
