// camdyn — held (holonomic) contacts of a mechanism as a DAE in SUNDIALS IDA 6.4
// (`solver.integrator = "ida"`, contact.model = "holonomic"): the classical
// constrained-multibody route (Haug), an independent second formulation of the held
// contacts' forces. One code for a single follower (a one-contact Mechanism,
// src/mechanism/follower_builder.cpp) and a network.
//
//   Linear mechanism, n unknowns, the held contacts S (k of them, rows T_S of T):
//     M q̈ + C q̇ + K q = f₀ + T_Sᵀ λ,      g_S(q, t) = T_S q + g₀,S − X_C(t)·[cam] = 0,
//   λ = the held contacts' forces (compressive > 0), the Lagrange multipliers of g_S.
//   As a first-order system in [q; v] the constraints are index 3 (λ appears only after
//   differentiating g twice). Stabilised index-2 formulation (Gear–Gupta–Leimkuhler):
//   keep the position constraints g_S = 0 and add their time derivatives ġ_S = 0, with
//   multipliers μ that project q̇ back onto the position constraints,
//
//     F_q = q̇ − v + T_Sᵀ μ                      = 0   (n)
//     F_v = M v̇ − (f₀ − K q − C v + T_Sᵀ λ)     = 0   (n)
//     F_g = T_S q + g₀,S − X_C(t)·[cam]          = 0   (k, multipliers μ)
//     F_ġ = T_S v − Ẋ_C(t)·[cam]                 = 0   (k, multipliers λ)
//     F_W = Ẇ − Σ_{j ∈ S, cam} λ_j Ẋ_C(t)        = 0   (1, the cam's work W)
//
//   A [camshaft] (ida_rows.hpp): a held cam contact on a free station s has the row
//   T̃_c = T_c − X_L′(φ_s)e_sᵀ in F_q, F_v and F_ġ, and F_g its lift X_L(φ_s − α); the
//   Newton matrix carries those −X_L′ entries and their derivatives in φ_s (X_L″μ, X_L″λ,
//   X_L″φ̇_s); r gains the crank's part of the drive couplings, and W their power (with the
//   prescribed station's cams' λẊ) instead of the free stations' cams' λẊ, which works inside.
//   With nonlinear elements r = f₀ − Kq − Cv + r_e(t, q, v, s) and their internal states s
//   (ns of them, element.hpp) add F_s = ṡ − g(t, q, v, s) = 0 (ns, differential, in the
//   error test), y = [q; v; λ; μ; W; s; D], N = 2n + 2k + 2 + ns; their blocks in the Newton
//   matrix: ∂F_v/∂q += K_e, ∂F_v/∂v += C_e, ∂F_v/∂s = −R_s, ∂F_s/∂q = −G_q, ∂F_s/∂v = −G_v,
//   ∂F_s/∂s = c_j I − G_s (ElementSet::state_tangent; G_s dense over the states). The
//   energy the mechanism dissipates, F_D = Ḋ − P(t, q, v, s) (its damping and elements'
//   power), is one more differential unknown D in the error test, so that the energy
//   ledger gets it to IDA's tolerance (the trapezoid on the rows missed the chamber's
//   throttling power between them); D feeds nothing back, its row of the Newton matrix is
//   c_j on the diagonal alone.
//   y = [q; v; λ; μ; W; D], N = 2n + 2k + 2 without states. On the exact solution μ = 0 and λ are the held
//   forces; λ and μ are index-2 algebraic unknowns: IDASetId gives them 0 and
//   IDASetSuppressAlg(SUNTRUE) leaves them out of the local error test, which then
//   controls q, v and W (W is an ordinary differential unknown; left out of the test it
//   drifted by 1e-5 of the work across case A's force peak). f₀ − Kq is evaluated as
//   r₀ − K(q − q(0)), r₀ = f₀ − Kq(0): its round-off scales with the motion, not with |K||q|
//   (a stiff bar at rest).
//   Consistent initial values: the caller's state on g_S = ġ_S = 0 and the acceleration
//   level's forces λ(0) (W_SS λ = Ẍ_C,S − T_S a_free), μ = 0, v̇ = M⁻¹(f₀ − Kq − Cv +
//   T_Sᵀλ), q̇ = v, Ẇ = Σ λ_j Ẋ_C; no IDACalcIC.
//   Newton matrix J = ∂F/∂y + c_j ∂F/∂ẏ, constant except c_j and ∂F_W/∂λ_j = −Ẋ_C(t):
//     [ c_j I      −I         0      T_Sᵀ   0  ]
//     [ K        c_j M + C   −T_Sᵀ    0     0  ]
//     [ T_S        0          0       0     0  ]
//     [ 0          T_S        0       0     0  ]
//     [ 0          0        −Ẋ_C·1ᵀ   0    c_j ]
//   (nonsingular for W_SS = T_S M⁻¹ T_Sᵀ nonsingular; a single follower: W = M*), in CSC
//   form (int64 indices) factored by KLU when N − 1 > 16 unknowns besides W
//   (solver.linear_solver = "auto"), dense LU otherwise; the pattern (union of ∂F/∂y and
//   ∂F/∂ẏ) is fixed, so KLU's symbolic analysis is done once. A single elastic bar runs
//   BDF orders ≤ 2 (A-stable: its undamped mesh modes sit on the imaginary axis), a rigid
//   follower orders ≤ 5, a network ≤ 4 (as Lee on cvode-bdf).
//   Output: IDA_NORMAL with IDASetStopTime at every output time, so that rows are IDA's
//   step values (λ, an index-2 unknown, is not accurate through the interpolant).
//   Rootfinding on λ_j (decreasing) reports the first time a held force turns tensile (a
//   unilateral contact would open there); on the gaps of the contacts not held
//   (decreasing), the time one closes.
//
// Every SUNDIALS flag is checked (negative → SundialsError naming the call); callbacks
// catch every exception and return −1 so none crosses SUNDIALS.
#include "engine/ida_engine.hpp"
#include "engine/ida_rows.hpp"
#include "engine/sundials_raii.hpp"

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
#include <stdexcept>
#include <utility>
#include <vector>

namespace camdyn {

namespace {

/// IDA steps per IDASolve call (IdaHeldSet::advance returns short of tout after them).
constexpr long kStepsPerCall = 20000;

/// IDA's messages, kept (never printed) for the failing call's SundialsError, except the
/// end of a chunk of kStepsPerCall steps (not an error here).
void ida_errors(int code, const char* module, const char* function, char* msg, void* data) {
  if (code == IDA_TOO_MUCH_WORK) return;
  detail::capture_sundials_message(code, module, function, msg, data);
}

struct IdaDel {
  void operator()(void* m) const { IDAFree(&m); }
};
using detail::ContextHolder;
using detail::LS;
using detail::Mat;
using detail::NVec;
using detail::not_null;

using ida_rows::Row;
using ida_rows::row_of;

}  // namespace

struct IdaHeldSet::Impl {
  const Mechanism& mech;
  const CamShaft* shaft;  // a [camshaft] (ida_rows.hpp), else nullptr
  IdaHeldSet::CamFn cam;
  int n, k, ns, N;
  int iL, iU, iW, iS, iD;  // first indices of λ, μ; index of W; first index of s; index of D
  std::vector<Row> held, open;
  std::vector<int> open_ids;
  SolverSpec spec;
  bool dense;
  Eigen::VectorXd q0, r0;
  SparseMatrix J0, J1;    // ∂F/∂y, ∂F/∂ẏ on one common (union) pattern
  std::vector<long> p_wl;  // positions of ∂F_W/∂λ_j (held cam contacts), −1 otherwise
  // a camshaft: per held contact on a free station s, the positions of its row's entries
  // (s, s), (s, μ), (n + s, s), (n + s, λ), (g, s), (ġ, n + s), (ġ, s)
  struct ShaftEntries {
    int c;
    long qq, qmu, vq, vlam, gq, gdv, gdq;
  };
  std::vector<ShaftEntries> p_shaft;
  // nonlinear elements: their tangent's values and positions in J0 (rows n + i)
  SparseMatrix Ke, Ce;
  std::vector<long> p_ke, p_ce;
  // the internal states' blocks: R_s, G_q, G_v (sparse) and G_s (dense), their positions in J0
  SparseMatrix Rs, Gq, Gv;
  Eigen::MatrixXd Gs;
  std::vector<long> p_rs, p_gq, p_gv, p_gs;
  Eigen::VectorXd sdot;
  Eigen::VectorXd r, Mvp, dq;
  std::vector<double> jx;  // the Jacobian's values on the pattern
  bool tensile_on = true;
  std::vector<int> roots_found;
  // Declaration order = construction order; destruction runs in reverse: IDA memory
  // first, then the linear solver, matrix and vectors it references, the context last.
  ContextHolder ctx_holder;
  std::string sundials_message;  ///< the last message of IDA's error handler (ida_errors)
  SUNContext ctx = ctx_holder.ctx;
  NVec yy, yp, id, atol;
  Mat A;
  LS ls;
  std::unique_ptr<void, IdaDel> mem;

  Impl(const Mechanism& mc, const std::vector<int>& held_ids, const Scene& scene, IdaHeldSet::CamFn c,
       bool dense_ls)
      : mech(mc), shaft(mc.camshaft()), cam(std::move(c)), n(mc.n()), k(int(held_ids.size())), ns(mc.states()),
        N(2 * mc.n() + 2 * k + 2 + ns), iL(2 * n), iU(2 * n + k), iW(2 * n + 2 * k), iS(2 * n + 2 * k + 1),
        iD(2 * n + 2 * k + 1 + ns),
        spec(scene.solver), dense(dense_ls), q0(mc.q0()), sdot(mc.states()), r(mc.n()), Mvp(mc.n()), dq(mc.n()) {
    std::vector<char> is_held(std::size_t(mech.m()), 0);
    for (int j : held_ids) {
      held.push_back(row_of(mech, j));
      is_held[std::size_t(j)] = 1;
    }
    for (int j = 0; j < mech.m(); ++j)
      if (!is_held[std::size_t(j)]) {
        open.push_back(row_of(mech, j));
        open_ids.push_back(j);
      }
    r0 = mech.f0() - mech.K() * q0;
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
    const SparseMatrix& M = mech.M();
    const SparseMatrix& K = mech.K();
    for (long j = 0; j < n; ++j) {
      for (SparseMatrix::InnerIterator it(K, j); it; ++it) add0(n + it.row(), j, it.value());
      if (mech.damped())
        for (SparseMatrix::InnerIterator it(mech.C(), j); it; ++it) add0(n + it.row(), n + j, it.value());
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) add1(n + it.row(), n + j, it.value());
    }
    const ElementSet& el = mech.elements();
    if (!el.empty()) {  // F_v = M v̇ − r: ∂/∂q of −r_e is K_e, ∂/∂v is C_e (values per Jacobian)
      Ke = el.stiffness_pattern();
      for (long j = 0; j < n; ++j)
        for (SparseMatrix::InnerIterator it(Ke, j); it; ++it) add0(n + it.row(), j, 0.0);
      if (el.damps()) {
        Ce = el.damping_pattern();
        for (long j = 0; j < n; ++j)
          for (SparseMatrix::InnerIterator it(Ce, j); it; ++it) add0(n + it.row(), n + j, 0.0);
      }
    }
    for (int c = 0; c < k; ++c) {
      for (const auto& e : held[std::size_t(c)].nz) {
        add0(e.first, iU + c, e.second);       // F_q: + T_cᵀ μ_c
        add0(n + e.first, iL + c, -e.second);  // F_v: − T_cᵀ λ_c
        add0(iL + c, e.first, e.second);       // F_g,c = T_c q + …   (row 2n + c)
        add0(iU + c, n + e.first, e.second);   // F_ġ,c = T_c v − …   (row 2n + k + c)
      }
      const Row& h = held[std::size_t(c)];
      if (h.cam && h.sdof < 0) add0(iW, iL + c, 1.0);  // F_W: −Ẋ_C λ_c (value per Jacobian)
      if (h.sdof >= 0) {  // a camshaft's free station s: T̃_c = T_c − X_L′e_sᵀ (values per Jacobian)
        const long st = h.sdof;
        add0(st, st, 0.0);            // F_q,s: −X_L′μ_c → −X_L″μ_c
        add0(st, iU + c, 0.0);        // F_q,s: −X_L′
        add0(n + st, st, 0.0);        // F_v,s: +X_L′λ_c → +X_L″λ_c
        add0(n + st, iL + c, 0.0);    // F_v,s: +X_L′
        add0(iL + c, st, 0.0);        // F_g,c: −X_L′
        add0(iU + c, n + st, 0.0);    // F_ġ,c: −X_L′ φ̇_s → −X_L′
        add0(iU + c, st, 0.0);        // F_ġ,c: −X_L″ φ̇_s
      }
    }
    add1(iW, iW, 1.0);  // F_W: Ẇ
    add1(iD, iD, 1.0);  // F_D: Ḋ
    if (ns > 0) {  // F_v: −R_s s; F_s = ṡ − g: −G_q, −G_v, c_j I − G_s (values per Jacobian)
      Rs = el.rs_pattern();
      Gq = el.gq_pattern();
      for (long j = 0; j < Rs.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(Rs, j); it; ++it) add0(n + it.row(), iS + j, 0.0);
      for (long j = 0; j < Gq.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(Gq, j); it; ++it) {
          add0(iS + it.row(), j, 0.0);
          add0(iS + it.row(), n + j, 0.0);
        }
      for (long l = 0; l < ns; ++l) {
        for (long c = 0; c < ns; ++c) add0(iS + l, iS + c, 0.0);
        add1(iS + l, iS + l, 1.0);
      }
    }
    SparseMatrix P(N, N), A0(N, N), A1(N, N);
    P.setFromTriplets(tp.begin(), tp.end());
    A0.setFromTriplets(t0.begin(), t0.end());
    A1.setFromTriplets(t1.begin(), t1.end());
    J0 = A0 + 0.0 * P;  // both on P's pattern (Eigen's sparse sum keeps the union)
    J1 = A1 + 0.0 * P;
    J0.makeCompressed();
    J1.makeCompressed();
    if (J0.nonZeros() != P.nonZeros() || J1.nonZeros() != P.nonZeros())
      throw std::logic_error("IdaHeldSet: Jacobian patterns differ");
    auto position = [&](long i, long j) {
      for (long p = J0.outerIndexPtr()[j]; p < J0.outerIndexPtr()[j + 1]; ++p)
        if (J0.innerIndexPtr()[p] == i) return p;
      throw std::logic_error("IdaHeldSet: element entry outside the pattern");
    };
    for (long j = 0; j < Ke.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Ke, j); it; ++it) p_ke.push_back(position(n + it.row(), j));
    for (long j = 0; j < Ce.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Ce, j); it; ++it) p_ce.push_back(position(n + it.row(), n + j));
    for (long j = 0; j < Rs.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Rs, j); it; ++it) p_rs.push_back(position(n + it.row(), iS + j));
    for (long j = 0; j < Gq.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Gq, j); it; ++it) {
        p_gq.push_back(position(iS + it.row(), j));
        p_gv.push_back(position(iS + it.row(), n + j));
      }
    for (long c = 0; c < ns; ++c)
      for (long l = 0; l < ns; ++l) p_gs.push_back(position(iS + l, iS + c));
    for (int c = 0; c < k; ++c) {
      const long st = held[std::size_t(c)].sdof;
      if (st < 0) continue;
      p_shaft.push_back({c, position(st, st), position(st, iU + c), position(n + st, st), position(n + st, iL + c),
                         position(iL + c, st), position(iU + c, n + st), position(iU + c, st)});
    }
    p_wl.assign(std::size_t(k), -1);
    for (int c = 0; c < k; ++c)
      for (long p = J0.outerIndexPtr()[iL + c]; p < J0.outerIndexPtr()[iL + c + 1]; ++p)
        if (J0.innerIndexPtr()[p] == iW) p_wl[std::size_t(c)] = p;
  }

  // F(t, y, ẏ).
  void residual(double t, const double* y, const double* dy, double* F) {
    const double* q = y;
    const double* v = y + n;
    const CamMotion c = cam(t);
    for (int i = 0; i < n; ++i) F[i] = dy[i] - v[i];
    dq = Eigen::Map<const Eigen::VectorXd>(q, n) - q0;
    r.noalias() = r0 - mech.K() * dq;
    if (mech.damped()) r.noalias() -= mech.C() * Eigen::Map<const Eigen::VectorXd>(v, n);
    const double* s = ns > 0 ? y + iS : nullptr;
    if (!mech.elements().empty()) mech.elements().add_force(t, q, v, r.data(), s);
    double Pw = 0.0;
    if (shaft) {  // the crank's part of the drive couplings, and their power: the run's input
      shaft->add_crank_forcing(t, r.data());
      Pw += shaft->coupling_power(t, q, v);
    }
    for (int j = 0; j < k; ++j) {
      const Row& h = held[std::size_t(j)];
      const double lam = y[iL + j], mu = y[iU + j];
      for (const auto& e : h.nz) {
        F[e.first] += e.second * mu;
        r[e.first] += e.second * lam;
      }
      const ida_rows::RowCam rc = ida_rows::row_cam(h, shaft, c, t, q, v);
      if (h.sdof >= 0) {  // T̃ᵀ: the contact's torque −X_L′λ on its station (its work stays inside)
        F[h.sdof] -= rc.dX * mu;
        r[h.sdof] -= rc.dX * lam;
      } else if (h.cam) {
        Pw += lam * rc.Xdot;
      }
      F[iL + j] = h.dot(q) + h.g0 - rc.X;
      F[iU + j] = h.dot(v) - rc.Xdot;
    }
    Mvp.noalias() = mech.M() * Eigen::Map<const Eigen::VectorXd>(dy + n, n);
    for (int i = 0; i < n; ++i) F[n + i] = Mvp[i] - r[i];
    F[iW] = dy[iW] - Pw;
    if (ns > 0) {
      mech.elements().state_rate(t, q, v, s, sdot.data());
      for (int l = 0; l < ns; ++l) F[iS + l] = dy[iS + l] - sdot[l];
    }
    F[iD] = dy[iD] - mech.damping_power(t, q, v, s);
  }

  // J = J0 + c_j J1 (with ∂F_W/∂λ_j = −Ẋ_C(t)).
  void jacobian(double t, double cj, const double* y, SUNMatrix Jac) {
    const long nnz = J0.nonZeros();
    const double* a0 = J0.valuePtr();
    const double* a1 = J1.valuePtr();
    const double wl = -cam(t).Xdot;
    std::vector<double>& x = jx;
    x.resize(std::size_t(nnz));
    for (long p = 0; p < nnz; ++p) x[std::size_t(p)] = a0[p] + cj * a1[p];
    for (int c = 0; c < k; ++c) {
      const long p = p_wl[std::size_t(c)];
      if (p < 0) continue;
      const Row& h = held[std::size_t(c)];
      x[std::size_t(p)] = h.shaft ? -ida_rows::row_cam(h, shaft, CamMotion{}, t, y, y + n).Xdot : wl;
    }
    for (const ShaftEntries& e : p_shaft) {
      const Row& h = held[std::size_t(e.c)];
      const ShaftCamLift L = shaft->lift(h.contact, y);
      const double lam = y[iL + e.c], mu = y[iU + e.c], ws = y[n + h.sdof];
      x[std::size_t(e.qq)] -= L.ddX * mu;
      x[std::size_t(e.qmu)] -= L.dX;
      x[std::size_t(e.vq)] += L.ddX * lam;
      x[std::size_t(e.vlam)] += L.dX;
      x[std::size_t(e.gq)] -= L.dX;
      x[std::size_t(e.gdv)] -= L.dX;
      x[std::size_t(e.gdq)] -= L.ddX * ws;
    }
    const double* s = ns > 0 ? y + iS : nullptr;
    if (!p_ke.empty()) {
      mech.elements().tangent(t, y, y + n, Ke, Ce, s);
      for (std::size_t p = 0; p < p_ke.size(); ++p) x[std::size_t(p_ke[p])] += Ke.valuePtr()[p];
      for (std::size_t p = 0; p < p_ce.size(); ++p) x[std::size_t(p_ce[p])] += Ce.valuePtr()[p];
    }
    if (ns > 0) {
      mech.elements().state_tangent(t, y, y + n, s, Rs, Gq, Gv, Gs);
      for (std::size_t p = 0; p < p_rs.size(); ++p) x[std::size_t(p_rs[p])] -= Rs.valuePtr()[p];
      for (std::size_t p = 0; p < p_gq.size(); ++p) x[std::size_t(p_gq[p])] -= Gq.valuePtr()[p];
      for (std::size_t p = 0; p < p_gv.size(); ++p) x[std::size_t(p_gv[p])] -= Gv.valuePtr()[p];
      for (long c = 0, p = 0; c < ns; ++c)
        for (long l = 0; l < ns; ++l, ++p) x[std::size_t(p_gs[std::size_t(p)])] -= Gs(l, c);
    }
    if (dense) {
      SUNMatZero(Jac);
      for (long j = 0; j < N; ++j) {
        double* col = SUNDenseMatrix_Column(Jac, j);
        for (long p = J0.outerIndexPtr()[j]; p < J0.outerIndexPtr()[j + 1]; ++p)
          col[J0.innerIndexPtr()[p]] = x[std::size_t(p)];
      }
      return;
    }
    sunindextype* cp = SUNSparseMatrix_IndexPointers(Jac);
    sunindextype* ri = SUNSparseMatrix_IndexValues(Jac);
    double* xv = SUNSparseMatrix_Data(Jac);
    for (long j = 0; j <= N; ++j) cp[j] = J0.outerIndexPtr()[j];
    for (long p = 0; p < nnz; ++p) {
      ri[p] = J0.innerIndexPtr()[p];
      xv[p] = x[std::size_t(p)];
    }
  }

  int root_count() const { return (tensile_on ? k : 0) + int(open.size()); }

  // λ_j of the held contacts (while watched), then the open contacts' gaps.
  void roots(double t, const double* y, double* g) {
    int i = 0;
    if (tensile_on)
      for (int j = 0; j < k; ++j) g[i++] = y[iL + j];
    if (open.empty()) return;
    const CamMotion c = cam(t);
    for (const Row& o : open) g[i++] = o.dot(y) + o.g0 - ida_rows::row_cam(o, shaft, c, t, y, y + n).X;
  }

  void set_roots() {
    const int nr = root_count();
    void* m = mem.get();
    check_flag(IDARootInit(m, nr, nr > 0 ? &Impl::root_cb : nullptr), "IDARootInit");
    if (nr == 0) return;
    std::vector<int> dir(std::size_t(nr), -1);
    check_flag(IDASetRootDirection(m, dir.data()), "IDASetRootDirection");
    check_flag(IDASetNoInactiveRootWarn(m), "IDASetNoInactiveRootWarn");
    roots_found.assign(std::size_t(nr), 0);
  }

  static int res_cb(double t, N_Vector y, N_Vector dy, N_Vector F, void* ud) {
    try {
      static_cast<Impl*>(ud)->residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(dy), N_VGetArrayPointer(F));
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int jac_cb(double t, double cj, N_Vector y, N_Vector, N_Vector, SUNMatrix Jac, void* ud, N_Vector,
                    N_Vector, N_Vector) {
    try {
      static_cast<Impl*>(ud)->jacobian(t, cj, N_VGetArrayPointer(y), Jac);
      return 0;
    } catch (...) {
      return -1;
    }
  }
  static int root_cb(double t, N_Vector y, N_Vector, double* g, void* ud) {
    try {
      static_cast<Impl*>(ud)->roots(t, N_VGetArrayPointer(y), g);
      return 0;
    } catch (...) {
      return -1;
    }
  }
};

IdaHeldSet::IdaHeldSet(const Mechanism& mech, std::vector<int> held, const Scene& scene, CamFn cam)
    : held_(std::move(held)) {
  const int n = mech.n(), k = int(held_.size()), ns = mech.states();
  N_ = 2 * n + 2 * k + 2 + ns;
  // "auto": KLU when the unknowns besides W exceed 16 (resolve_linear_solver counts 2·nodes + 2)
  lsk_ = resolve_linear_solver(scene.solver, n + k - 1 + (ns + 1) / 2);
  impl_ = std::make_unique<Impl>(mech, held_, scene, std::move(cam), lsk_ == LinearSolverKind::Dense);
  y_.resize(2 * n + ns);
  lambda_ = Eigen::VectorXd::Zero(k);
}

IdaHeldSet::~IdaHeldSet() = default;

void IdaHeldSet::init(double t0, const Eigen::VectorXd& y0, const Eigen::VectorXd& lam, double tstop) {
  Impl& d = *impl_;
  const Mechanism& mc = d.mech;
  const int n = d.n, k = d.k;
  double* y = N_VGetArrayPointer(d.yy.get());
  double* dy = N_VGetArrayPointer(d.yp.get());
  const int ns = d.ns;
  std::copy(y0.data(), y0.data() + 2 * n, y);
  if (ns > 0) std::copy(y0.data() + 2 * n, y0.data() + 2 * n + ns, y + d.iS);
  const double* s = ns > 0 ? y + d.iS : nullptr;
  const CamMotion c = d.cam(t0);
  Eigen::VectorXd F = Eigen::VectorXd::Zero(mc.m());
  double Pw = 0.0, Fmax = 0.0;
  for (int j = 0; j < k; ++j) {
    y[d.iL + j] = lam[j];
    y[d.iU + j] = 0.0;
    F[held_[std::size_t(j)]] = lam[j];
    const Row& h = d.held[std::size_t(j)];
    if (h.cam && h.sdof < 0) Pw += lam[j] * ida_rows::row_cam(h, d.shaft, c, t0, y, y + n).Xdot;
    Fmax = std::max(Fmax, std::abs(lam[j]));
  }
  if (d.shaft) Pw += d.shaft->coupling_power(t0, y, y + n);
  y[d.iW] = 0.0;
  std::copy(y + n, y + 2 * n, dy);  // q̇ = v
  mc.acceleration(t0, y, y + n, F, dy + n, false, s);  // v̇ = M⁻¹(r(t, q, v, s) + T_Sᵀλ)
  if (ns > 0) mc.state_rate(t0, y, y + n, s, dy + d.iS);  // ṡ = g
  for (int j = 0; j < 2 * k; ++j) dy[d.iL + j] = 0.0;
  dy[d.iW] = Pw;
  y[d.iD] = 0.0;
  dy[d.iD] = mc.damping_power(t0, y, y + n, s);

  // Differential (1): q, v, W. Algebraic (0): λ, μ (index 2: out of the error test).
  N_VConst(1.0, d.id.get());
  double* idv = N_VGetArrayPointer(d.id.get());
  for (int j = 0; j < 2 * k; ++j) idv[d.iL + j] = 0.0;
  // Absolute tolerances: atol on q, v; λ and μ are weighted only in the Newton test, on
  // their own scales (a force and a velocity), so that round-off of order c_j·ε|q| in μ
  // does not fail it.
  const double rtol = d.spec.rtol, atol = d.spec.atol;
  N_VConst(atol, d.atol.get());
  double* av = N_VGetArrayPointer(d.atol.get());
  for (int j = 0; j < k; ++j) {
    av[d.iL + j] = std::max(atol, rtol * std::abs(lam[j]));
    av[d.iU + j] = std::max(atol, rtol * std::max(std::abs(c.Xdot), 1.0));
  }
  av[d.iW] = std::max(atol, rtol * Fmax * std::abs(c.X));
  av[d.iD] = av[d.iW];

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
  check_flag(IDASetErrHandlerFn(mem, &ida_errors, &d.sundials_message), "IDASetErrHandlerFn");
  check_flag(IDASetMaxOrd(mem, mc.traits().ida_max_order), "IDASetMaxOrd");
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
  d.set_roots();
  y_.head(2 * n) = Eigen::Map<const Eigen::VectorXd>(y, 2 * n);
  y_.tail(ns) = Eigen::Map<const Eigen::VectorXd>(y + d.iS, ns);
  lambda_ = lam;
  work_ = dissipated_ = 0.0;
}

void IdaHeldSet::stop_tensile_roots() {
  Impl& d = *impl_;
  if (!d.tensile_on) return;
  d.tensile_on = false;
  if (d.mem) d.set_roots();
}

double IdaHeldSet::advance(double tout, bool one_step) {
  Impl& d = *impl_;
  double tret = 0;
  // Rows land on IDA's own steps (tstop = tout): λ is an index-2 unknown, accurate at the
  // step points to O(local error / h) but not through IDA's interpolating polynomial
  // (case A, rtol 1e-10: interpolated rows 2.0e-8 of the peak force off, step points 4.9e-9).
  check_flag(IDASetStopTime(d.mem.get(), tout), "IDASetStopTime");
  int raw = IDASolve(d.mem.get(), tout, &tret, d.yy.get(), d.yp.get(), one_step ? IDA_ONE_STEP : IDA_NORMAL);
  if (raw == IDA_TOO_MUCH_WORK) raw = IDA_SUCCESS;  // kStepsPerCall steps taken: tret < tout
  const std::string call = raw < 0 && !d.sundials_message.empty() ? "IDASolve [" + d.sundials_message + "]" : "IDASolve";
  d.sundials_message.clear();
  const int flag = check_flag(raw, call.c_str());
  tensile_ = closing_ = -1;
  if (flag == IDA_ROOT_RETURN) {
    check_flag(IDAGetRootInfo(d.mem.get(), d.roots_found.data()), "IDAGetRootInfo");
    int i = 0;
    if (d.tensile_on)
      for (int j = 0; j < d.k; ++j, ++i)
        if (d.roots_found[std::size_t(i)] != 0 && tensile_ < 0) tensile_ = held_[std::size_t(j)];
    for (std::size_t o = 0; o < d.open.size(); ++o, ++i)
      if (d.roots_found[std::size_t(i)] != 0 && closing_ < 0) closing_ = d.open_ids[o];
  }
  const double* y = N_VGetArrayPointer(d.yy.get());
  y_.head(2 * d.n) = Eigen::Map<const Eigen::VectorXd>(y, 2 * d.n);
  y_.tail(d.ns) = Eigen::Map<const Eigen::VectorXd>(y + d.iS, d.ns);
  for (int j = 0; j < d.k; ++j) lambda_[j] = y[d.iL + j];
  work_ = y[d.iW];
  dissipated_ = y[d.iD];
  return tret;
}

EngineStats IdaHeldSet::stats() const {
  EngineStats s;
  void* mem = impl_->mem.get();
  if (!mem) return s;
  check_flag(IDAGetNumSteps(mem, &s.steps), "IDAGetNumSteps");
  check_flag(IDAGetNumResEvals(mem, &s.rhs_evals), "IDAGetNumResEvals");
  check_flag(IDAGetNumLinSolvSetups(mem, &s.lin_setups), "IDAGetNumLinSolvSetups");
  check_flag(IDAGetNumNonlinSolvIters(mem, &s.nonlin_iters), "IDAGetNumNonlinSolvIters");
  check_flag(IDAGetNumNonlinSolvConvFails(mem, &s.nonlin_conv_fails), "IDAGetNumNonlinSolvConvFails");
  check_flag(IDAGetNumErrTestFails(mem, &s.err_test_fails), "IDAGetNumErrTestFails");
  s.lin_analyses = impl_->dense ? 0 : 1;  // SUNLinSol_KLU: one symbolic analysis (fixed pattern)
  return s;
}

long IdaHeldSet::rejected_steps() const {
  void* mem = impl_->mem.get();
  if (!mem) return 0;
  long netf = 0, ncf = 0;
  check_flag(IDAGetNumErrTestFails(mem, &netf), "IDAGetNumErrTestFails");
  check_flag(IDAGetNumNonlinSolvConvFails(mem, &ncf), "IDAGetNumNonlinSolvConvFails");
  return netf + ncf;
}

}  // namespace camdyn
