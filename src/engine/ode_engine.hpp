// camdyn (private) — a generic engine on SUNDIALS for y' = f(t, y): the integrator of
// the mechanism's methods (every follower; src/contact/contact_run.hpp). A Mechanism's
// Newton systems go through the sparse Schur complement (OdeSystem::newton, below); the
// dense matrix and dense LU named here are the fallback (a user FollowerSystem).
//
//   arkode-erk   ERKStep, Dormand–Prince 5(4)
//   arkode-dirk  ARKStep, SDIRK 5-stage 4(3), SUNDIALS dense matrix + dense LU, the
//                Jacobian from OdeSystem::jacobian (exact) or SUNDIALS' difference quotients
//   cvode-bdf    CVODE BDF, same linear algebra
//
// It knows nothing of scenes, followers or contacts: the contact method owns the right-hand
// side (the force law is inside f) and the root functions. Two ways to drive it:
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
#include <limits>
#include <vector>
#include <utility>

#include "mechanism/sparse_matrix.hpp"
#include "camdyn/scene.hpp"
#include "engine/engine_stats.hpp"
#include "engine/sundials_error.hpp"

namespace camdyn {

/// The Newton matrix of a mechanism, y = [q; v] (and its elements' states s, below), q̇ = v,
/// M v̇ = f₀ − K q − C v + Tᵀ F(t, y):
/// the implicit engines solve (I − γJ)x = b through the n × n Schur complement
///   S x_v = M b_v − γ K̃ b_u (+ T_Aᵀ μ),   x_u = b_u + γ x_v,   S = M + γC̃ + γ²K̃,
/// K̃ = K − Tᵀ diag(∂F/∂g) T, C̃ = C − Tᵀ diag(∂F/∂ġ) T, sparse (KLU, one symbolic analysis
/// per run; dense LU for ≤ 16 unknowns as solver.linear_solver = "auto" says) instead of a
/// dense 2n × 2n matrix: O(nnz) per factorisation and solve.
struct SparseNewton {
  const SparseMatrix* M = nullptr;  ///< required
  const SparseMatrix* K = nullptr;  ///< required
  const SparseMatrix* C = nullptr;  ///< null: undamped
  Eigen::MatrixXd T;                ///< contact rows (m × n)
  /// F's derivatives at (t, y) along the contacts (a penalty law): dFdg, dFdgd (m entries).
  /// Empty: F does not depend on y (a prescribed force, or none).
  std::function<void(double t, const double* y, Eigen::VectorXd& dFdg, Eigen::VectorXd& dFdgd)> contact_derivatives;
  /// The contacts (indices into T) held at the acceleration level inside f — F_A =
  /// W_AA⁻¹(Ẍ_C,A − T_A M⁻¹(f₀ − Kq − Cv)), so J's velocity rows are P M⁻¹[−K, −C] with
  /// T_A P = 0 — read at every solve: the system is bordered with T_A (x_v,A = b_v,A).
  /// Null: none.
  const std::vector<int>* held = nullptr;
  /// Nonlinear elements (src/mechanism/element_set.hpp): their tangent K_e = −∂r_e/∂q and
  /// C_e = −∂r_e/∂q̇ enter K̃ = K + K_e − …, C̃ = C + C_e − …. Ke_pattern (and Ce_pattern,
  /// null if no element damps) fix the pattern; element_tangent(t, y, Ke, Ce) writes the
  /// values at (t, y) on copies of them. Empty: none (a linear mechanism).
  const SparseMatrix* Ke_pattern = nullptr;
  const SparseMatrix* Ce_pattern = nullptr;
  std::function<void(double t, const double* y, SparseMatrix& Ke, SparseMatrix& Ce)> element_tangent;
  /// Optional, with element_tangent: the elements' generalised force r_e(t, y) (n entries,
  /// added to r, which the caller zeroes), when it is the only part of f that the Newton
  /// matrix does not hold exactly (f = [v; M⁻¹(f₀(t) − Kq − Cv + r_e + Tᵀ F)] with F a
  /// function of t alone or held at the acceleration level; no contact_derivatives, rows or
  /// states). An implicit trial engine then predicts a Newton iteration's next correction
  /// from it (SparseNewtonSolver::next_correction) instead of taking that iteration to
  /// measure the contraction rate.
  std::function<void(double t, const double* y, double* r)> element_force;
  /// The elements' internal states (0: none): y = [q; v; s], ṡ = g(t, q, v, s), and r depends
  /// on s. J gains the blocks R_s = ∂r/∂s (in the velocity rows, through M⁻¹), G_q = ∂g/∂q,
  /// G_v = ∂g/∂q̇, G_s = ∂g/∂s; s is eliminated with H = (I − γG_s)⁻¹ (states × states):
  ///   S = M + γC̃ + γ²K̃ − γ² R_s H (γG_q + G_v),
  ///   S x_v = M b_v − γK̃ b_u + γ R_s H (b_s + γ G_q b_u),   x_s = H (b_s + γ(G_q x_u + G_v x_v)).
  /// Rs_pattern (n × states) and Gq_pattern (states × n, also G_v's) fix the patterns;
  /// state_blocks(t, y, Rs, Gq, Gv, Gs) writes the values at (t, y) (Gs dense).
  int states = 0;
  const SparseMatrix* Rs_pattern = nullptr;
  const SparseMatrix* Gq_pattern = nullptr;
  std::function<void(double t, const double* y, SparseMatrix& Rs, SparseMatrix& Gq, SparseMatrix& Gv,
                     Eigen::MatrixXd& Gs)>
      state_blocks;
  /// State-dependent contact rows (a camshaft's cam contacts, src/mechanism/camshaft.hpp:
  /// T̃ = T − X_L′ e_sᵀ). rows(t, y, T, Kr) writes the rows at (t, y) into T (m × n, non-zero
  /// only on T's pattern and row_entries) and into Kr (on Kr_pattern) the part of K̃ the rows'
  /// dependence on q gives: −∂(T(q)ᵀF)/∂q at the method's forces F, and −T(q)ᵀ ∂F/∂ġ ∂ġ/∂q
  /// beyond ġ = T v (a penalty law's damping through the row's moving column). K̃ gains Kr;
  /// the contact derivatives' outer products and the held set's border use the rows at (t, y).
  /// Called before contact_derivatives. Empty: T is constant.
  std::vector<std::pair<int, long>> row_entries;  ///< (contact, unknown) entries beyond T's
  const SparseMatrix* Kr_pattern = nullptr;        ///< required with rows
  std::function<void(double t, const double* y, Eigen::MatrixXd& T, SparseMatrix& Kr)> rows;
};

/// The system an OdeEngine integrates.
struct OdeSystem {
  /// Number of unknowns, ≥ 1.
  int size = 0;
  /// Optional absolute tolerance per unknown (size entries, each > 0); empty: the
  /// SolverSpec's scalar atol for every unknown. Used by SUNDIALS' error test and by wrms().
  Eigen::VectorXd atol;
  /// ydot = f(t, y). May throw (the engine's callback turns it into a failed step:
  /// SundialsError from step()/advance()).
  std::function<void(double t, const double* y, double* ydot)> rhs;
  /// Optional dense Jacobian J = ∂f/∂y (size × size, column-major Eigen matrix, already
  /// sized). Empty: SUNDIALS' difference-quotient Jacobian (implicit engines only).
  std::function<void(double t, const double* y, Eigen::MatrixXd& J)> jacobian;
  /// Optional, preferred to `jacobian` by the implicit engines: the sparse structure of the
  /// Newton matrix (a Mechanism).
  std::shared_ptr<const SparseNewton> newton;
  /// true: f is linear in y (ARKStepSetLinear / one Newton iteration per stage with the
  /// exact Jacobian; trial steps are then exactly affine in anything f depends on
  /// linearly). Needs `jacobian` or `newton`.
  bool linear = false;
  /// cvode-bdf only: the largest BDF order (0: CVODE's default 5). Orders ≥ 3 are not
  /// A-stable: an undamped stiff system (a chain of stiff springs and bars) wants ≤ 2.
  int max_order = 0;
  /// cvode-bdf only: CVODE's BDF stability-limit detection (CVodeSetStabLimDet), which
  /// lowers the order where orders ≥ 3 go unstable on lightly damped stiff modes.
  bool stability_limit_detection = false;
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
  /// WRMS norm of err with the engine's tolerances, weights rtol·|y_i| + atol_i.
  double wrms(const Eigen::VectorXd& err, const Eigen::VectorXd& y) const;

  /// Native mode: restart from (t, y) with the solver's own error control.
  virtual void reinit(double t, const Eigen::VectorXd& y) = 0;
  /// One internal step toward tout (never past it). Returns the time reached; y_out holds
  /// the state there. After a root: hit_root() and root_info().
  virtual double advance(double tout, Eigen::VectorXd& y_out) = 0;
  /// Native mode: the solution at t inside the last internal step (SUNDIALS' own
  /// interpolant, GetDky with k = 0). @pre t within the last step. At the time advance()
  /// returned it gives advance()'s state bit for bit (ARKODE's Hermite and CVODE's Nordsieck
  /// interpolants weigh y_n by 1 and the rest by 0 there; tests/engine/test_dense_reuse.cpp).
  virtual void dense(double t, Eigen::VectorXd& y_out) = 0;

  /// Keep dense()'s right-hand-side evaluations while `on`. ARKODE's Hermite interpolant of
  /// degree 4 and 5 evaluates f at points inside the last step (h/3 and 2h/3 before its end)
  /// on every GetDky call: the same t and the same interpolated y for every call inside one
  /// step. While on, an evaluation that dense() asks for again at the same t and a bitwise
  /// equal y is copied from the first one (the last two are kept): dense() returns the same
  /// bits, and EngineStats::rhs_evals counts only the evaluations made. Switching clears
  /// what was kept. CVODE's GetDky evaluates no f (no effect there).
  /// @pre f (the caller's held set, cam window, …) does not change while on: switch it off
  /// before changing them.
  void keep_dense_rhs(bool on) {
    keep_dense_rhs_ = on;
    for (DenseRhs& d : dense_rhs_) d.t = std::numeric_limits<double>::quiet_NaN();
  }

  /// Projection onto a manifold the method keeps (e.g. its closed contacts' displacement and
  /// velocity levels), applied to every accepted step's end state (native mode):
  /// fn(t, y, corr) writes corr = P(y) − y (size() entries). cvode-bdf: CVODE's own
  /// projection (CVodeSetProjFn, every step; the correction enters its Nordsieck history;
  /// the error test keeps the unprojected estimate — projected, it vanishes where the
  /// constraints fix every unknown, a valve clamped between cam and seat, and CVODE's steps
  /// then grew until its interpolant put a separation 3e-7 s off). arkode-erk / arkode-dirk (ARKODE 6.4 has no
  /// projection): after each step the state is projected and the stepper reset there with
  /// its planned next step size, its growth limited to the normal factor (after a reset
  /// ARKODE allows 10⁴: a valve at rest stepped over a whole lift event). A state returned
  /// at a root (interpolated) is not projected. Empty fn: none.
  using ProjFn = std::function<void(double t, const double* y, double* corr)>;
  virtual void set_projection(ProjFn fn) { proj_ = std::move(fn); }

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
  ProjFn proj_;
  // keep_dense_rhs: the last two evaluations made inside dense() (t NaN: none)
  struct DenseRhs {
    double t = std::numeric_limits<double>::quiet_NaN();
    Eigen::VectorXd y, f;
  };
  DenseRhs dense_rhs_[2];
  int dense_rhs_next_ = 0;
  bool keep_dense_rhs_ = false;
  bool in_dense_ = false;  // inside dense(): its GetDky's right-hand sides
};

}  // namespace camdyn
