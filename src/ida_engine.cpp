// camdyn — the held (holonomic) contact as a DAE in SUNDIALS IDA 6.4 (`solver.integrator =
// "ida"`, contact.model = "holonomic"): the classical constrained-multibody route (Haug),
// an independent second formulation of the held-contact force.
//
//   Linear follower, n nodes, node 0 held on the cam (e₀ = first unit vector):
//     M q̈ + C q̇ + K q = f₀ + e₀ λ,      g(q, t) = q₀ − X_C(t) = 0,
//   λ = the contact force (compressive > 0), the Lagrange multiplier of g.
//   As a first-order system in [q; v] the constraint is index 3 (λ appears only after
//   differentiating g twice). Stabilised index-2 formulation (Gear–Gupta–Leimkuhler):
//   keep the position constraint g = 0 and add its time derivative ġ = v₀ − Ẋ_C = 0, with
//   a second multiplier μ that projects q̇ back onto the position constraint,
//
//     F_q = q̇ − v + e₀ μ                        = 0   (n)
//     F_v = M v̇ − (f₀ − K q − C v + e₀ λ)       = 0   (n)
//     F_g = q₀ − X_C(t)                          = 0   (1, multiplier μ)
//     F_ġ = v₀ − Ẋ_C(t)                          = 0   (1, multiplier λ)
//     F_W = Ẇ − λ Ẋ_C(t)                         = 0   (1, the cam's work W = ∫ λ Ẋ_C dt)
//
//   y = [q; v; λ; μ; W], N = 2n + 3. On the exact solution μ = 0 and λ is the held-contact
//   force; λ and μ are index-2 algebraic unknowns: IDASetId gives them 0 and
//   IDASetSuppressAlg(SUNTRUE) leaves them out of the local error test, which then
//   controls q, v and W (W is an ordinary differential unknown; left out of the test it
//   drifted by 1e-5 of the work across case A's force peak).
//   Consistent initial values: q₀ = X_C(0), v₀ = Ẋ_C(0), the other nodes from the model,
//   λ(0) = (Ẍ_C − ü₀,free)/M* (the acceleration constraint), μ = 0, v̇ = M⁻¹(f₀ − Kq − Cv
//   + e₀λ), q̇ = v, Ẇ = λẊ_C; no IDACalcIC.
//   Newton matrix J = ∂F/∂y + c_j ∂F/∂ẏ, constant except c_j and ∂F_W/∂λ = −Ẋ_C(t):
//     [ c_j I      −I        0    e₀   0  ]
//     [ K        c_j M + C  −e₀   0    0  ]
//     [ e₀ᵀ        0         0    0    0  ]
//     [ 0          e₀ᵀ       0    0    0  ]
//     [ 0          0       −Ẋ_C   0   c_j ]
//   (nonsingular: e₀ᵀM⁻¹e₀ = M* > 0), in CSC form (int64 indices) factored by KLU when
//   N − 1 = 2n + 2 > 16 unknowns besides W (solver.linear_solver = "auto"), dense LU
//   otherwise; the pattern (union of ∂F/∂y and ∂F/∂ẏ) is fixed, so KLU's symbolic
//   analysis is done once. Bars run BDF orders ≤ 2 (A-stable: the undamped mesh modes sit
//   on the imaginary axis, see engines.cpp), a rigid follower orders ≤ 5.
//   Output: IDA_NORMAL with IDASetStopTime at every output time, so that rows are IDA's
//   step values (λ, an index-2 unknown, is not accurate through the interpolant).
//   Rootfinding on λ (decreasing) reports the first time the constraint force turns
//   tensile (the follower would separate there if the contact were unilateral).
//
// Every SUNDIALS flag is checked (negative → SundialsError naming the call); callbacks
// catch every exception and return −1 so none crosses SUNDIALS.
#include "ida_engine.hpp"
#include "sundials_raii.hpp"

#include <ida/ida.h>
#include <ida/ida_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace camdyn {

namespace {

/// IDA steps per IDASolve call (IdaHeldContact::advance returns short of tout after them).
constexpr long kStepsPerCall = 20000;

/// IDA's messages as its default handler prints them, except the end of a chunk of
/// kStepsPerCall steps (not an error here).
void ida_errors(int code, const char* module, const char* function, char* msg, void*) {
  if (code == IDA_TOO_MUCH_WORK) return;
  std::fprintf(stderr, "\n[%s ERROR]  %s\n  %s\n\n", module, function, msg);
}

struct IdaDel {
  void operator()(void* m) const { IDAFree(&m); }
};
using detail::ContextHolder;
using detail::LS;
using detail::Mat;
using detail::NVec;
using detail::not_null;

// M, K, C of the model as n × n sparse matrices (rigid: 1 × 1; undamped: C empty).
SparseMatrix scalar_matrix(double x) {
  SparseMatrix A(1, 1);
  A.insert(0, 0) = x;
  A.makeCompressed();
  return A;
}

}  // namespace

struct IdaHeldContact::Impl {
  std::shared_ptr<const FollowerModel> model;
  const FollowerModel& m;
  CamFn cam;
  int n, N;
  int iL, iU, iW;  // indices of λ, μ, W
  SolverSpec spec;
  bool dense;
  SparseMatrix M, K, C;  // n × n
  SparseMatrix J0, J1;   // ∂F/∂y, ∂F/∂ẏ on one common (union) pattern
  long p_wl = -1;        // position of ∂F_W/∂λ in the pattern
  Eigen::VectorXd r, Mvp;
  // Declaration order = construction order; destruction runs in reverse: IDA memory
  // first, then the linear solver, matrix and vectors it references, the context last.
  ContextHolder ctx_holder;
  SUNContext ctx = ctx_holder.ctx;
  NVec yy, yp, id, atol;
  Mat A;
  LS ls;
  std::unique_ptr<void, IdaDel> mem;
  bool root_on = false;

  Impl(std::shared_ptr<const FollowerModel> mdl, const Scene& scene, CamFn c, bool dense_ls)
      : model(std::move(mdl)), m(*model), cam(std::move(c)), n(m.n()), N(2 * m.n() + 3),
        iL(2 * m.n()), iU(2 * m.n() + 1), iW(2 * m.n() + 2), spec(scene.solver), dense(dense_ls),
        r(m.n()), Mvp(m.n()) {
    if (m.rigid()) {
      M = scalar_matrix(m.m_rigid());
      K = scalar_matrix(m.k_rigid());
      C = scalar_matrix(m.c_rigid());
    } else {
      M = m.M();
      K = m.K();
      C = m.damped() ? m.C() : SparseMatrix(n, n);
    }
    build_pattern();
    yy.reset(not_null(N_VNew_Serial(N, ctx), "N_VNew_Serial"));
    yp.reset(not_null(N_VNew_Serial(N, ctx), "N_VNew_Serial"));
    id.reset(not_null(N_VNew_Serial(N, ctx), "N_VNew_Serial"));
    atol.reset(not_null(N_VNew_Serial(N, ctx), "N_VNew_Serial"));
    N_VConst(0.0, yy.get());
    N_VConst(0.0, yp.get());
  }

  void build_pattern() {
    using T = Eigen::Triplet<double, long>;
    std::vector<T> t0, t1, tp;
    auto add0 = [&](long i, long j, double v) { t0.emplace_back(i, j, v); tp.emplace_back(i, j, 1.0); };
    auto add1 = [&](long i, long j, double v) { t1.emplace_back(i, j, v); tp.emplace_back(i, j, 1.0); };
    for (long i = 0; i < n; ++i) {
      add0(i, n + i, -1.0);  // F_q: −v
      add1(i, i, 1.0);       // F_q: q̇
    }
    add0(0, iU, 1.0);  // F_q0: + μ
    for (long j = 0; j < n; ++j) {
      for (SparseMatrix::InnerIterator it(K, j); it; ++it) add0(n + it.row(), j, it.value());
      for (SparseMatrix::InnerIterator it(C, j); it; ++it) add0(n + it.row(), n + j, it.value());
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) add1(n + it.row(), n + j, it.value());
    }
    add0(n, iL, -1.0);     // F_v0: − λ
    add0(iL, 0, 1.0);      // F_g = q₀ − X_C   (row 2n)
    add0(iU, n, 1.0);      // F_ġ = v₀ − Ẋ_C   (row 2n + 1)
    add0(iW, iL, 1.0);     // F_W: −Ẋ_C(t) λ (value set per Jacobian)
    add1(iW, iW, 1.0);     // F_W: Ẇ
    SparseMatrix P(N, N), A0(N, N), A1(N, N);
    P.setFromTriplets(tp.begin(), tp.end());
    A0.setFromTriplets(t0.begin(), t0.end());
    A1.setFromTriplets(t1.begin(), t1.end());
    J0 = A0 + 0.0 * P;  // both on P's pattern (Eigen's sparse sum keeps the union)
    J1 = A1 + 0.0 * P;
    J0.makeCompressed();
    J1.makeCompressed();
    if (J0.nonZeros() != P.nonZeros() || J1.nonZeros() != P.nonZeros())
      throw std::logic_error("IdaHeldContact: Jacobian patterns differ");
    for (long p = J0.outerIndexPtr()[iL]; p < J0.outerIndexPtr()[iL + 1]; ++p)
      if (J0.innerIndexPtr()[p] == iW) p_wl = p;
  }

  // F(t, y, ẏ).
  void residual(double t, const double* y, const double* dy, double* F) {
    const double* q = y;
    const double* v = y + n;
    const double lam = y[iL], mu = y[iU];
    const CamMotion c = cam(t);
    for (int i = 0; i < n; ++i) F[i] = dy[i] - v[i];
    F[0] += mu;
    m.internal_force(q, v, r.data());
    r[0] += lam;
    Mvp.noalias() = M * Eigen::Map<const Eigen::VectorXd>(dy + n, n);
    for (int i = 0; i < n; ++i) F[n + i] = Mvp[i] - r[i];
    F[iL] = q[0] - c.X;
    F[iU] = v[0] - c.Xdot;
    F[iW] = dy[iW] - lam * c.Xdot;
  }

  // J = J0 + c_j J1 (with ∂F_W/∂λ = −Ẋ_C(t)).
  void jacobian(double t, double cj, SUNMatrix Jac) {
    const long nnz = J0.nonZeros();
    const double* a0 = J0.valuePtr();
    const double* a1 = J1.valuePtr();
    const double wl = -cam(t).Xdot;
    auto value = [&](long p) { return p == p_wl ? wl : a0[p] + cj * a1[p]; };
    if (dense) {
      SUNMatZero(Jac);
      for (long j = 0; j < N; ++j) {
        double* col = SUNDenseMatrix_Column(Jac, j);
        for (long p = J0.outerIndexPtr()[j]; p < J0.outerIndexPtr()[j + 1]; ++p) col[J0.innerIndexPtr()[p]] = value(p);
      }
      return;
    }
    sunindextype* cp = SUNSparseMatrix_IndexPointers(Jac);
    sunindextype* ri = SUNSparseMatrix_IndexValues(Jac);
    double* x = SUNSparseMatrix_Data(Jac);
    for (long j = 0; j <= N; ++j) cp[j] = J0.outerIndexPtr()[j];
    for (long p = 0; p < nnz; ++p) {
      ri[p] = J0.innerIndexPtr()[p];
      x[p] = value(p);
    }
  }

  static int res_cb(double t, N_Vector y, N_Vector dy, N_Vector F, void* ud) {
    try {
      static_cast<Impl*>(ud)->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(dy), N_VGetArrayPointer(F));
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int jac_cb(double t, double cj, N_Vector, N_Vector, N_Vector, SUNMatrix Jac, void* ud, N_Vector,
                    N_Vector, N_Vector) {
    try {
      static_cast<Impl*>(ud)->jacobian(t, cj, Jac);
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int root_cb(double, N_Vector y, N_Vector, double* g, void* ud) {
    try {
      g[0] = N_VGetArrayPointer(y)[static_cast<Impl*>(ud)->iL];
      return 0;
    } catch (...) {
      return -1;
    }
  }
};

IdaHeldContact::IdaHeldContact(std::shared_ptr<const FollowerModel> model, const Scene& scene, CamFn cam) {
  const int n = model->n();
  N_ = 2 * n + 3;
  lsk_ = resolve_linear_solver(scene.solver, n);  // "auto": KLU when 2n + 2 > 16 (λ, μ counted)
  impl_ = std::make_unique<Impl>(std::move(model), scene, std::move(cam), lsk_ == LinearSolverKind::Dense);
  qv_.resize(2 * n);
}

IdaHeldContact::~IdaHeldContact() = default;

void IdaHeldContact::init(double t0, const Eigen::VectorXd& qv, double tstop) {
  Impl& d = *impl_;
  const FollowerModel& m = d.m;
  const int n = d.n;
  double* y = N_VGetArrayPointer(d.yy.get());
  double* dy = N_VGetArrayPointer(d.yp.get());
  std::copy(qv.data(), qv.data() + 2 * n, y);
  const CamMotion c = d.cam(t0);
  y[0] = c.X;
  y[n] = c.Xdot;
  const double a_free = m.contact_acceleration(y, y + n, 0.0);
  const double lam = (c.Xddot - a_free) / m.mstar();
  y[d.iL] = lam;
  y[d.iU] = 0.0;
  y[d.iW] = 0.0;
  std::copy(y + n, y + 2 * n, dy);  // q̇ = v
  m.internal_force(y, y + n, d.r.data());
  d.r[0] += lam;
  m.solve_mass(d.r.data(), dy + n);  // v̇ = M⁻¹(f₀ − Kq − Cv + e₀λ)
  dy[d.iL] = dy[d.iU] = 0.0;
  dy[d.iW] = lam * c.Xdot;

  // Differential (1): q, v, W. Algebraic (0): λ, μ (index 2: out of the error test).
  N_VConst(1.0, d.id.get());
  double* idv = N_VGetArrayPointer(d.id.get());
  idv[d.iL] = idv[d.iU] = 0.0;
  // Absolute tolerances: atol on q, v; λ and μ are weighted only in the Newton test, on
  // their own scales (a force and a velocity), so that round-off of order c_j·ε|q| in μ
  // does not fail it.
  const double rtol = d.spec.rtol, atol = d.spec.atol;
  N_VConst(atol, d.atol.get());
  double* av = N_VGetArrayPointer(d.atol.get());
  av[d.iL] = std::max(atol, rtol * std::abs(lam));
  av[d.iU] = std::max(atol, rtol * std::max(std::abs(c.Xdot), 1.0));
  av[d.iW] = std::max(atol, rtol * std::abs(lam * c.X));

  d.mem.reset(not_null(IDACreate(d.ctx), "IDACreate"));
  void* mem = d.mem.get();
  check_flag(IDAInit(mem, &Impl::res_cb, t0, d.yy.get(), d.yp.get()), "IDAInit");
  check_flag(IDASetUserData(mem, &d), "IDASetUserData");
  check_flag(IDASVtolerances(mem, rtol, d.atol.get()), "IDASVtolerances");
  check_flag(IDASetId(mem, d.id.get()), "IDASetId");
  check_flag(IDASetSuppressAlg(mem, SUNTRUE), "IDASetSuppressAlg");
  // At most kStepsPerCall steps per IDASolve: advance() then returns short of tout, so the
  // run loop checks the caller's stop flag, its CPU budget and run.max_steps between chunks
  // (the tolerance sweep found case A at rtol 1e-12 stepping for minutes inside one call).
  check_flag(IDASetMaxNumSteps(mem, kStepsPerCall), "IDASetMaxNumSteps");
  check_flag(IDASetErrHandlerFn(mem, &ida_errors, nullptr), "IDASetErrHandlerFn");
  check_flag(IDASetMaxOrd(mem, m.rigid() ? 5 : 2), "IDASetMaxOrd");
  check_flag(IDASetStopTime(mem, tstop), "IDASetStopTime");
  if (d.spec.max_step > 0) check_flag(IDASetMaxStep(mem, d.spec.max_step), "IDASetMaxStep");
  if (d.spec.initial_step > 0) check_flag(IDASetInitStep(mem, d.spec.initial_step), "IDASetInitStep");
  if (d.dense) {
    d.A.reset(not_null(SUNDenseMatrix(N_, N_, d.ctx), "SUNDenseMatrix"));
    d.ls.reset(not_null(SUNLinSol_Dense(d.yy.get(), d.A.get(), d.ctx), "SUNLinSol_Dense"));
  } else {
    d.A.reset(not_null(SUNSparseMatrix(N_, N_, d.J0.nonZeros(), CSC_MAT, d.ctx), "SUNSparseMatrix"));
    d.ls.reset(not_null(SUNLinSol_KLU(d.yy.get(), d.A.get(), d.ctx), "SUNLinSol_KLU"));
  }
  check_flag(IDASetLinearSolver(mem, d.ls.get(), d.A.get()), "IDASetLinearSolver");
  check_flag(IDASetJacFn(mem, &Impl::jac_cb), "IDASetJacFn");
  if (d.root_on) set_tensile_root(true);
  qv_ = Eigen::Map<const Eigen::VectorXd>(y, 2 * n);
  lambda_ = lam;
  mu_ = 0.0;
  work_ = 0.0;
}

void IdaHeldContact::set_tensile_root(bool on) {
  Impl& d = *impl_;
  d.root_on = on;
  if (!d.mem) return;
  check_flag(IDARootInit(d.mem.get(), on ? 1 : 0, on ? &Impl::root_cb : nullptr), "IDARootInit");
  if (on) {
    int dir = -1;
    check_flag(IDASetRootDirection(d.mem.get(), &dir), "IDASetRootDirection");
    check_flag(IDASetNoInactiveRootWarn(d.mem.get()), "IDASetNoInactiveRootWarn");
  }
}

double IdaHeldContact::advance(double tout, bool one_step) {
  Impl& d = *impl_;
  double tret = 0;
  // Rows land on IDA's own steps (tstop = tout): λ is an index-2 unknown, accurate at the
  // step points to O(local error / h) but not through IDA's interpolating polynomial
  // (case A, rtol 1e-10: interpolated rows 2.0e-8 of the peak force off, step points 4.9e-9).
  check_flag(IDASetStopTime(d.mem.get(), tout), "IDASetStopTime");
  int raw = IDASolve(d.mem.get(), tout, &tret, d.yy.get(), d.yp.get(), one_step ? IDA_ONE_STEP : IDA_NORMAL);
  if (raw == IDA_TOO_MUCH_WORK) raw = IDA_SUCCESS;  // kStepsPerCall steps taken: tret < tout
  const int flag = check_flag(raw, "IDASolve");
  hit_root_ = flag == IDA_ROOT_RETURN;
  const double* y = N_VGetArrayPointer(d.yy.get());
  qv_ = Eigen::Map<const Eigen::VectorXd>(y, 2 * d.n);
  lambda_ = y[d.iL];
  mu_ = y[d.iU];
  work_ = y[d.iW];
  return tret;
}

EngineStats IdaHeldContact::stats() const {
  EngineStats s;
  void* mem = impl_->mem.get();
  if (!mem) return s;
  check_flag(IDAGetNumSteps(mem, &s.steps), "IDAGetNumSteps");
  check_flag(IDAGetNumResEvals(mem, &s.rhs_evals), "IDAGetNumResEvals");
  check_flag(IDAGetNumLinSolvSetups(mem, &s.lin_setups), "IDAGetNumLinSolvSetups");
  s.lin_analyses = impl_->dense ? 0 : 1;  // SUNLinSol_KLU: one symbolic analysis (fixed pattern)
  return s;
}

long IdaHeldContact::rejected_steps() const {
  void* mem = impl_->mem.get();
  if (!mem) return 0;
  long netf = 0, ncf = 0;
  check_flag(IDAGetNumErrTestFails(mem, &netf), "IDAGetNumErrTestFails");
  check_flag(IDAGetNumNonlinSolvConvFails(mem, &ncf), "IDAGetNumNonlinSolvConvFails");
  return netf + ncf;
}

}  // namespace camdyn
