// camdyn — internal to engines.cpp and engine_cvode.cpp: the SUNDIALS helpers and the
// Schur-complement linear solver shared by the implicit engines (arkode-dirk in
// engines.cpp, cvode-bdf in engine_cvode.cpp). Not a public header.
#pragma once

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include <Eigen/Dense>
#include <memory>

#include "legacy/engine.hpp"
#include "engine/sparse_lu.hpp"
#include "engine/sundials_raii.hpp"

namespace camdyn {
namespace engine_detail {

// ---------------------------------------------------------------- RAII ----------
using detail::ContextHolder;
using detail::LS;
using detail::Mat;
using detail::NVec;
using detail::ArkDel;
using detail::CvDel;
using detail::ErkDel;
using detail::make_nvec;
using detail::not_null;
using detail::kTrialMaxSteps;
using detail::trial_min_step;
inline Eigen::Map<Eigen::VectorXd> map(N_Vector v) {
  return Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(v), N_VGetLength(v));
}

constexpr double kHugeTol = 1e30;  // trial steps: our own error test, never ARKODE's

// Values of K, M, C at pattern position p of column j (rigid: scalars).
struct ModelEntries {
  const FollowerModel& m;
  double K(long p) const { return m.rigid() ? m.k_rigid() : m.K().valuePtr()[p]; }
  double M(long p) const { return m.rigid() ? m.m_rigid() : m.M().valuePtr()[p]; }
  double C(long p) const {
    if (!m.damped()) return 0.0;
    return m.rigid() ? m.c_rigid() : m.C().valuePtr()[p];
  }
  long begin(long j) const { return m.rigid() ? 0 : m.K().outerIndexPtr()[j]; }
  long end(long j) const { return m.rigid() ? 1 : m.K().outerIndexPtr()[j + 1]; }
  long row(long p) const { return m.rigid() ? 0 : m.K().innerIndexPtr()[p]; }
};

// ---------------------------------------------------------------- Schur solver ---
// The Newton systems of both implicit engines, (I − γJ) x = b with
// J = [[0, I], [−M⁻¹K, −M⁻¹C]], through the n × n system
//   S x_v = M b_v − γ K b_u,   S = M + γC + γ²K,   x_u = b_u + γ x_v.
// S has the pattern of K (tridiagonal for a bar). KLU's symbolic analysis is done once
// for that pattern; the numeric factorisation is redone only when γ changed since the
// last one — Lee's trial steps retake the same step size several times, and ARKODE asks
// for a setup at the first stage after every reset. (The contact force is a prescribed
// shape over the step: it adds nothing to J.)
class SchurSolver {
 public:
  SchurSolver(const FollowerModel& m, bool dense, EngineStats& stats)
      : m_(m), n_(m.n()), stats_(stats), lu_(dense, stats) {
    if (!m.rigid()) S_ = m.K();  // copy of the shared pattern
  }

  void setup(double g) {
    if (factored_ && g == g_) return;  // S unchanged
    g_ = g;
    factored_ = true;
    ++stats_.lin_setups;
    if (m_.rigid()) {
      s_rigid_ = m_.m_rigid() + g * m_.c_rigid() + g * g * m_.k_rigid();
      return;
    }
    const ModelEntries e{m_};
    double* x = S_.valuePtr();
    for (long j = 0; j < n_; ++j)
      for (long p = e.begin(j); p < e.end(j); ++p) {
        x[p] = e.M(p) + g * e.C(p) + g * g * e.K(p);
      }
    lu_.factor(S_);
  }
  // x = (I − γJ)⁻¹ b, in place on b (length 2n).
  void solve(double* b) {
    const long n = n_;
    double* bu = b;
    double* bv = b + n;
    if (m_.rigid()) {
      const double rhs = m_.m_rigid() * bv[0] - g_ * m_.k_rigid() * bu[0];
      bv[0] = rhs / s_rigid_;
      bu[0] += g_ * bv[0];
      return;
    }
    Eigen::Map<Eigen::VectorXd> U(bu, n), V(bv, n);
    rhs_.noalias() = m_.M() * V;
    rhs_.noalias() -= g_ * (m_.K() * U);
    lu_.solve(rhs_.data());
    V = rhs_;
    U += g_ * V;
  }

 private:
  const FollowerModel& m_;
  long n_;
  EngineStats& stats_;
  bool factored_ = false;
  double g_ = 0, s_rigid_ = 1;
  SparseMatrix S_;
  Eigen::VectorXd rhs_;
  detail::SparseLu lu_;
};

// The SchurSolver as a SUNDIALS linear solver (detail::CustomLinearSolver). The engine's
// linear-system function hands over γ (prepare), the solver's setup factorises (if it
// changed), its solve applies (I − γJ)⁻¹.
class SchurLinearSolver {
 public:
  SchurLinearSolver(const FollowerModel& m, bool dense, EngineStats& stats, SUNContext ctx)
      : schur_(m, dense, stats),
        cls_(ctx, [this] { schur_.setup(gamma_); },
             [this](double* x) { schur_.solve(x); }) {}
  SUNLinearSolver ls() { return cls_.ls(); }
  SUNMatrix placeholder() { return cls_.placeholder(); }
  // From the linear-system function: the system I − γJ for this γ.
  void prepare(double gamma) { gamma_ = gamma; }

 private:
  SchurSolver schur_;
  double gamma_ = 0;
  detail::CustomLinearSolver cls_;
};

/// The cvode-bdf engine (engine_cvode.cpp), for make_engine.
std::unique_ptr<Engine> make_cvode_engine(std::shared_ptr<const FollowerModel> model,
                                          const SolverSpec& solver, LinearSolverKind lsk,
                                          bool trial, double tol_u);

}  // namespace engine_detail
}  // namespace camdyn
