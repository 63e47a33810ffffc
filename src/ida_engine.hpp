// camdyn (private) — the held (holonomic) contact as a DAE in SUNDIALS IDA.
// Formulation and index reduction: see the banner of ida_engine.cpp.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>

#include "camdyn/cam.hpp"
#include "camdyn/model.hpp"
#include "camdyn/scene.hpp"
#include "engine.hpp"

namespace camdyn {

/// Node 0 of a linear follower held on the cam, u₀ = X_C(t), integrated by IDA (variable-
/// order BDF) as a stabilised index-2 (GGL) DAE in y = [q; v; λ; μ; W]. λ is the contact
/// force (compressive > 0), μ the GGL multiplier (0 on the exact solution), W = ∫ λ Ẋ_C dt
/// the cam's work. Native stepping with IDA's own error control on q, v, W (λ, μ are
/// excluded from the error test). Every SUNDIALS flag is checked (SundialsError).
class IdaHeldContact {
 public:
  /// The cam's contact-point motion at time t.
  using CamFn = std::function<CamMotion(double t)>;

  /// @param model the full follower model (node 0 is the constrained contact node).
  /// @param scene solver.rtol/atol/max_step/initial_step/linear_solver are used.
  /// @throws SundialsError on a SUNDIALS failure.
  IdaHeldContact(std::shared_ptr<const FollowerModel> model, const Scene& scene, CamFn cam);
  ~IdaHeldContact();
  IdaHeldContact(const IdaHeldContact&) = delete;
  IdaHeldContact& operator=(const IdaHeldContact&) = delete;

  /// Start at t0 from the displacements q (node 0 is put on the cam, q₀ = X_C(t0)) and the
  /// velocities v (v₀ = Ẋ_C(t0)); λ(t0) = (Ẍ_C − ü₀,free)/M*, μ = 0, W = 0, with the
  /// consistent derivatives q̇ = v, v̇ = M⁻¹(f₀ − Kq − Cv + e₀λ), Ẇ = λẊ_C.
  /// @param tstop IDA never steps past it (the run's end time).
  void init(double t0, const Eigen::VectorXd& qv, double tstop);
  /// Rootfinding on λ (decreasing through 0: the constraint force turns tensile).
  void set_tensile_root(bool on);
  /// Toward tout, never past it (IDASetStopTime(tout): the values returned are IDA's step
  /// values, not its interpolant). IDA_NORMAL: up to tout; one_step: one internal step
  /// (IDA_ONE_STEP, for one row per step). Returns the time reached (tout, a root of λ, or
  /// the end of the step).
  double advance(double tout, bool one_step = false);
  bool hit_root() const { return hit_root_; }

  /// [q; v] at the time reached.
  const Eigen::VectorXd& state() const { return qv_; }
  double lambda() const { return lambda_; }
  double mu() const { return mu_; }
  double work() const { return work_; }
  /// Steps, residual evaluations (rhs_evals), linear-solver setups; rejected steps in
  /// `rejected` (error-test plus convergence failures).
  EngineStats stats() const;
  long rejected_steps() const;
  LinearSolverKind linear_solver() const { return lsk_; }
  int unknowns() const { return N_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  LinearSolverKind lsk_;
  int N_ = 0;
  Eigen::VectorXd qv_;
  double lambda_ = 0, mu_ = 0, work_ = 0;
  bool hit_root_ = false;
};

}  // namespace camdyn
