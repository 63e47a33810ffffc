// camdyn (private) — the shared base of the OdeEngine implementations (ode_engine.cpp: ERK,
// DIRK and the factory; cvode_ode.cpp: CVODE): SUNDIALS handles, the callbacks that catch
// every exception and the counters. Included by those two files only.
#pragma once

#include "engine/ode_engine.hpp"

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <cvode/cvode_proj.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include "engine/sparse_newton.hpp"
#include "engine/sundials_raii.hpp"

namespace camdyn {
namespace ode_impl {


using detail::ContextHolder;
using detail::LS;
using detail::NLS;
using detail::Mat;
using detail::not_null;
using detail::kTrialMaxSteps;
using detail::trial_min_step;
using detail::NVec;

using detail::ArkDel;
using detail::CvDel;
using detail::ErkDel;
using detail::make_nvec;
inline Eigen::Map<Eigen::VectorXd> map(N_Vector v) {
  return Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(v), N_VGetLength(v));
}

// Trial steps: SUNDIALS' error test must never reject (our own test acts). The tolerances
// are the spec's scaled by kTrialScale/rtol, so that every weighted norm inside SUNDIALS
// is the native one divided by a constant: the Newton test (coefficient scaled alike) and
// the difference-quotient increments behave as in native mode, the error test never fails.
constexpr double kHugeTol = 1e30;
// With a projection, ERK/DIRK are reset after every step: the first step after a reset may
// grow by ARKODE's normal factor only (its default for a first step is 10⁴).
constexpr double kGrowthAfterReset = 20.0;

// Counter of a SUNDIALS integrator read as a running delta (robust to resets that zero it).
struct Counter {
  long base = 0;
  long delta(long now) {
    const long d = now >= base ? now - base : now;
    base = now;
    return d;
  }
};

// Shared state and callbacks of the three engines.
class EngineBase : public OdeEngine {
 protected:
  EngineBase(const SolverSpec& spec, OdeSystem sys, bool trial)
      : OdeEngine(spec, std::move(sys)), trial_(trial) {
    if (n_ < 1) throw std::invalid_argument("OdeEngine: system size must be ≥ 1");
    if (!sys_.rhs) throw std::invalid_argument("OdeEngine: no right-hand side");
    if (sys_.linear && !sys_.jacobian && !sys_.newton)
      throw std::invalid_argument("OdeEngine: linear = true needs a jacobian or the sparse Newton structure");
    if (sys_.newton && 2 * sys_.newton->M->rows() + sys_.newton->states != n_)
      throw std::invalid_argument("OdeEngine: the sparse Newton structure's size (2n + states) is not the system's");
    y_ = make_nvec(n_, ctx_.ctx);
    tmp_ = make_nvec(n_, ctx_.ctx);
    local_error_ = Eigen::VectorXd::Zero(n_);
  }

  /// check_flag, with the message of an exception a callback caught (if any) appended.
  int check(int flag, const char* call) {
    if (flag < 0 && !callback_error_.empty()) {
      std::string msg = std::string(call) + " [callback threw: " + callback_error_ + "]";
      callback_error_.clear();
      sundials_message_.clear();
      throw SundialsError(msg, flag);
    }
    callback_error_.clear();
    if (flag < 0 && !sundials_message_.empty()) {
      const std::string msg = std::string(call) + " [" + sundials_message_ + "]";
      sundials_message_.clear();
      return check_flag(flag, msg.c_str());
    }
    return check_flag(flag, call);
  }
  void caught(const char* what) {
    if (callback_error_.empty()) callback_error_ = what;
  }
  // A callback's body: 0, or −1 with the exception's message kept for check().
  template <class Body>
  static int guarded(void* ud, Body body) {
    auto* self = static_cast<EngineBase*>(ud);
    try {
      body(self);
      return 0;
    } catch (const std::exception& e) {
      self->caught(e.what());
    } catch (...) {
      self->caught("unknown exception");
    }
    return -1;
  }
  void set_root_count(int n, RootFn fn) {
    if (n < 0) throw std::invalid_argument("OdeEngine::set_roots: n < 0");
    if (n > 0 && !fn) throw std::invalid_argument("OdeEngine::set_roots: no function");
    root_fn_ = n > 0 ? std::move(fn) : RootFn();
    root_info_.assign(std::size_t(n), 0);
    hit_root_ = false;
  }
  void fetch_root_info(int flag, int root_return, int (*get)(void*, int*), void* mem, const char* call) {
    hit_root_ = flag == root_return;
    std::fill(root_info_.begin(), root_info_.end(), 0);
    if (hit_root_ && !root_info_.empty()) check(get(mem, root_info_.data()), call);
  }

  // ERK/DIRK native mode, after a step that ended at tret with state y_: the projected
  // state in y_; true if it moved (the stepper must restart there).
  bool project_step_end(double tret) {
    if (!proj_) return false;
    corr_.setZero(n_);
    proj_(tret, N_VGetArrayPointer(y_.get()), corr_.data());
    if (!(corr_.cwiseAbs().maxCoeff() > 0.0)) return false;
    map(y_.get()) += corr_;
    return true;
  }

  // The sparse Schur path (OdeSystem::newton): our own linear solver; the integrator's
  // linear-system function hands over γ and the state.
  void make_sparse_solver() {
    const bool dense = resolve_linear_solver(spec_, int(sys_.newton->M->rows())) == LinearSolverKind::Dense;
    newton_ = std::make_unique<detail::SparseNewtonSolver>(*sys_.newton, dense, stats_);
    cls_ = std::make_unique<detail::CustomLinearSolver>(
        ctx_.ctx, [this] { newton_->setup(); }, [this](double* x) { newton_->solve(x); });
  }
  // ARKLsLinSysFn / CVLsLinSysFn (ARKODE's has the mass matrix M in addition).
  static int ark_linsys(double t, N_Vector y, N_Vector, SUNMatrix, SUNMatrix, sunbooleantype, sunbooleantype* jcur,
                        double gamma, void* ud, N_Vector, N_Vector, N_Vector) {
    return linsys(t, y, jcur, gamma, ud);
  }
  static int cv_linsys(double t, N_Vector y, N_Vector, SUNMatrix, sunbooleantype, sunbooleantype* jcur, double gamma,
                       void* ud, N_Vector, N_Vector, N_Vector) {
    return linsys(t, y, jcur, gamma, ud);
  }
  static int linsys(double t, N_Vector y, sunbooleantype* jcur, double gamma, void* ud) {
    return guarded(ud, [&](EngineBase* self) {
      self->newton_->prepare(t, N_VGetArrayPointer(y), gamma);
      self->rate_unknown_ = true;
      *jcur = SUNTRUE;
    });
  }

  static int rhs_cb(double t, N_Vector y, N_Vector ydot, void* ud) {
    return guarded(ud, [&](EngineBase* self) {
      if (self->in_dense_ && self->keep_dense_rhs_) {
        self->dense_rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
        return;
      }
      ++self->stats_.rhs_evals;
      self->sys_.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    });
  }
  // f(t, y) inside dense() with keep_dense_rhs on: a kept evaluation at the same t and a
  // bitwise equal y, or a new one (kept in place of the older of the two)
  void dense_rhs(double t, const double* y, double* yd) {
    const std::size_t bytes = sizeof(double) * std::size_t(n_);
    for (const DenseRhs& d : dense_rhs_)
      if (d.t == t && std::memcmp(d.y.data(), y, bytes) == 0) {
        std::memcpy(yd, d.f.data(), bytes);
        return;
      }
    ++stats_.rhs_evals;
    sys_.rhs(t, y, yd);
    DenseRhs& d = dense_rhs_[dense_rhs_next_];
    dense_rhs_next_ ^= 1;
    d.t = t;
    d.y = Eigen::Map<const Eigen::VectorXd>(y, n_);
    d.f = Eigen::Map<const Eigen::VectorXd>(yd, n_);
  }
  // dense()'s GetDky call: its right-hand sides go through dense_rhs when kept
  struct InDense {
    explicit InDense(EngineBase& e) : e_(e) { e_.in_dense_ = true; }
    ~InDense() { e_.in_dense_ = false; }
    EngineBase& e_;
  };
  static int root_cb(double t, N_Vector y, double* g, void* ud) {
    return guarded(ud, [&](EngineBase* self) { self->root_fn_(t, N_VGetArrayPointer(y), g); });
  }
  // ARKLsJacFn and CVLsJacFn have the same signature.
  static int jac_cb(double t, N_Vector y, N_Vector, SUNMatrix Jac, void* ud, N_Vector, N_Vector, N_Vector) {
    return guarded(ud, [&](EngineBase* self) {
      Eigen::MatrixXd& J = self->J_;
      J.setZero(self->n_, self->n_);
      self->sys_.jacobian(t, N_VGetArrayPointer(y), J);
      if (J.rows() != self->n_ || J.cols() != self->n_)
        throw std::runtime_error("OdeSystem::jacobian resized its matrix");
      // Both column-major with leading dimension n.
      std::memcpy(SUNDenseMatrix_Data(Jac), J.data(), sizeof(double) * std::size_t(self->n_) * std::size_t(self->n_));
    });
  }

  // The integrator's linear-solver setups up to now (nls): the factorisations of its own
  // dense solver. The sparse Schur path counts its own factorisations (SparseNewtonSolver::
  // setup refactors only when γ or the contact derivatives changed): the integrator calls
  // its setup at every step after a reset — every Lee trial step — mostly with the same γ.
  void count_setups(long nls) {
    const long d = setups_.delta(nls);
    if (!newton_) stats_.lin_setups += d;
  }
  // The integrator's Newton iterations, Newton convergence failures and error-test failures
  // up to now (running totals since its last reset): counted, or (count = false) the base.
  void count_newton(long nni, long ncf, long netf, bool count = true) {
    const long a = nni_.delta(nni), b = ncf_.delta(ncf), c = netf_.delta(netf);
    if (!count) return;
    stats_.nonlin_iters += a;
    stats_.nonlin_conv_fails += b;
    stats_.err_test_fails += c;
  }

  bool trial_;
  ContextHolder ctx_;
  NVec y_, tmp_;
  NVec atol_;  // the per-unknown absolute tolerances (OdeSystem::atol), when given

  /// The integrator's tolerances: `rtol` with the per-unknown sys_.atol × atol_scale when the
  /// system gives them (`sv`, its *SVtolerances; SUNDIALS copies the vector), else the
  /// scalar `atol` × atol_scale (`ss`, its *SStolerances). `sv_name`, `ss_name`: the calls'
  /// names for check(). @throws std::invalid_argument for an sys_.atol of the wrong size or
  /// with an entry ≤ 0; SundialsError for a failed call.
  template <class SetVector, class SetScalar>
  void set_tolerances(void* mem, SetVector sv, const char* sv_name, SetScalar ss, const char* ss_name,
                      double rtol, double atol, double atol_scale = 1.0) {
    if (!sys_.atol.size()) {
      check(ss(mem, rtol, atol * atol_scale), ss_name);
      return;
    }
    if (sys_.atol.size() != n_ || !(sys_.atol.array() > 0.0).all())
      throw std::invalid_argument("OdeEngine: OdeSystem::atol needs size() entries, each > 0");
    atol_ = make_nvec(n_, ctx_.ctx);
    map(atol_.get()) = atol_scale * sys_.atol;
    check(sv(mem, rtol, atol_.get()), sv_name);
  }
  Eigen::MatrixXd J_;
  Eigen::VectorXd corr_;
  std::unique_ptr<detail::SparseNewtonSolver> newton_;
  std::unique_ptr<detail::CustomLinearSolver> cls_;
  bool rate_unknown_ = true;  // no Newton contraction rate measured since the last linear-system setup
  std::string callback_error_;
  std::string sundials_message_;  ///< the last message of SUNDIALS' error handler
  Counter steps_, setups_, nni_, ncf_, netf_;
};

}  // namespace ode_impl
}  // namespace camdyn
