// camdyn (private) — the direct solver behind the implicit engines' Newton systems
// (ode_engine.cpp, SparseNewton): (I − γJ)x = b of a second-order system through the n × n
// Schur complement S = M + γC̃ + γ²K̃, whose values change with γ but whose pattern does not.
//
//   SparseLu        KLU on a CSC matrix: one symbolic analysis per pattern (per run),
//                   klu_l_factor once, klu_l_refactor afterwards; dense partial-pivot LU
//                   instead when asked (a handful of unknowns).
//   CustomLinearSolver  a SUNDIALS "direct" linear solver whose system is ours: setup and
//                   solve callbacks and a 1 × 1 placeholder matrix that the integrator passes
//                   along but never reads (no SUNMatrix, no O(n²) SUNMatScaleAdd).
#pragma once

#include <sundials/sundials_linearsolver.h>

#include <Eigen/Dense>
#include <functional>

#include "mechanism/sparse_matrix.hpp"
#include "engine/engine_stats.hpp"
#include "engine/sundials_raii.hpp"


namespace camdyn {
namespace detail {

class SparseLu {
 public:
  /// dense: factorise with Eigen's PartialPivLU (small systems), else KLU.
  SparseLu(bool dense, EngineStats& stats);
  ~SparseLu();
  SparseLu(const SparseLu&) = delete;
  SparseLu& operator=(const SparseLu&) = delete;
  /// Factorise A (square, compressed). The first call analyses A's pattern (counted in
  /// stats.lin_analyses); later calls must pass the same pattern.
  /// @throws SundialsError naming the KLU call that failed (singular matrix).
  void factor(SparseMatrix& A);
  /// x = A⁻¹x in place (length n). @pre factor() called.
  void solve(double* x);

 private:
  struct Klu;
  bool dense_;
  long n_ = 0;
  EngineStats& stats_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  Klu* klu_ = nullptr;
};

class CustomLinearSolver {
 public:
  /// setup(): factorise the current system (throw on failure); solve(x): x = A⁻¹x in place
  /// (length of the integrator's vector).
  CustomLinearSolver(SUNContext ctx, std::function<void()> setup, std::function<void(double* x)> solve);
  SUNLinearSolver ls() { return ls_.get(); }
  SUNMatrix placeholder() { return placeholder_.get(); }

 private:
  static int ls_setup(SUNLinearSolver S, SUNMatrix);
  static int ls_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, double);
  std::function<void()> setup_;
  std::function<void(double*)> solve_;
  Mat placeholder_;
  LS ls_;
};

}  // namespace detail
}  // namespace camdyn
