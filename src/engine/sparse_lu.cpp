// camdyn — SparseLu and CustomLinearSolver (sparse_lu.hpp).
#include "engine/sparse_lu.hpp"

#include <klu.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace camdyn {
namespace detail {

struct SparseLu::Klu {
  klu_l_common common{};
  klu_l_symbolic* symbolic = nullptr;
  klu_l_numeric* numeric = nullptr;
  Klu() { klu_l_defaults(&common); }
  ~Klu() {
    if (numeric) klu_l_free_numeric(&numeric, &common);
    if (symbolic) klu_l_free_symbolic(&symbolic, &common);
  }
};

SparseLu::SparseLu(bool dense, EngineStats& stats) : dense_(dense), stats_(stats) {
  if (!dense_) klu_ = new Klu();
}
SparseLu::~SparseLu() { delete klu_; }

void SparseLu::factor(SparseMatrix& A) {
  n_ = A.rows();
  if (dense_) {
    lu_.compute(Eigen::MatrixXd(A));
    return;
  }
  long* Ap = A.outerIndexPtr();
  long* Ai = A.innerIndexPtr();
  double* x = A.valuePtr();
  if (!klu_->symbolic) {
    klu_->symbolic = klu_l_analyze(n_, Ap, Ai, &klu_->common);
    if (!klu_->symbolic) throw SundialsError("klu_l_analyze", -1);
    ++stats_.lin_analyses;
  }
  if (!klu_->numeric) {
    klu_->numeric = klu_l_factor(Ap, Ai, x, klu_->symbolic, &klu_->common);
    if (!klu_->numeric) throw SundialsError("klu_l_factor", -1);
  } else if (!klu_l_refactor(Ap, Ai, x, klu_->symbolic, klu_->numeric, &klu_->common)) {
    throw SundialsError("klu_l_refactor", -1);
  }
}

void SparseLu::solve(double* x) {
  if (dense_) {
    Eigen::Map<Eigen::VectorXd> X(x, n_);
    X = lu_.solve(Eigen::VectorXd(X));
  } else if (!klu_l_solve(klu_->symbolic, klu_->numeric, n_, 1, x, &klu_->common)) {
    throw SundialsError("klu_l_solve", -1);
  }
}

CustomLinearSolver::CustomLinearSolver(SUNContext ctx, std::function<void()> setup,
                                       std::function<void(double* x)> solve)
    : setup_(std::move(setup)), solve_(std::move(solve)) {
  ls_.reset(SUNLinSolNewEmpty(ctx));
  if (!ls_) throw SundialsError("SUNLinSolNewEmpty", -1);
  ls_->content = this;
  ls_->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  ls_->ops->setup = &CustomLinearSolver::ls_setup;
  ls_->ops->solve = &CustomLinearSolver::ls_solve;
  ls_->ops->free = [](SUNLinearSolver S) {
    SUNLinSolFreeEmpty(S);
    return 0;
  };
  placeholder_.reset(SUNDenseMatrix(1, 1, ctx));
  if (!placeholder_) throw SundialsError("SUNDenseMatrix", -1);
}

int CustomLinearSolver::ls_setup(SUNLinearSolver S, SUNMatrix) {
  try {
    static_cast<CustomLinearSolver*>(S->content)->setup_();
    return 0;
  } catch (...) {
    return -1;
  }
}
int CustomLinearSolver::ls_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, double) {
  try {
    N_VScale(1.0, b, x);
    static_cast<CustomLinearSolver*>(S->content)->solve_(N_VGetArrayPointer(x));
    return 0;
  } catch (...) {
    return -1;
  }
}

}  // namespace detail
}  // namespace camdyn
