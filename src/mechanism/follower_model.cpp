// camdyn — follower model builder (docs/method.md §1, §5).
//
//   M q̈ + C q̇ + K q = f₀ + e₀ F(t)
//
//   rigid       n = 1:  M = m, C = c, K = k, f₀ = −k δ₀ + k q(0).
//   elastic_bar n = N+1 nodes, element length h = L/N, element mass mₑ = m/N:
//     Kₑ = EA/h [1 −1; −1 1],   Mₑ = mₑ/6 [2 1; 1 2] (consistent) or mₑ/2 I (lumped),
//     K += k e_N e_Nᵀ,  f₀ = (−k δ₀ + k q_N(0)) e_N,  C = αM + βK.
//   Initial shape: uniform compression by the preload F₀ = k δ₀:
//     q_i(0) = x₀ − i F₀ h / (EA),  x₀ = X_C(θ₀) + initial_gap.
//   M* = e₀ᵀ M⁻¹ e₀ from one sparse solve.
//
// Only what the scene asks for is built: a rigid follower is three scalars (no sparse
// matrix, no mesh, no factorisation); C exists only if damping was asked for.
#include <sstream>
#include <stdexcept>

#include "camdyn/cam.hpp"
#include "camdyn/model.hpp"
#include "legacy/engine.hpp"

namespace camdyn {

// LDLᵀ of the tridiagonal consistent mass matrix (2-node elements: M is tridiagonal and
// SPD, so no pivoting and no fill): M = L D Lᵀ, L unit lower bidiagonal with subdiagonal
// l_i. A solve is two passes of O(n) with no index arrays (it is called once per
// right-hand side of the explicit engine, so it matters: Eigen's general sparse LDLᵀ
// solve took ~19 % of an explicit Lee run at 10⁴ elements).
struct FollowerModel::Factor {
  std::vector<double> l, dinv;  // l[0] unused
  explicit Factor(const SparseMatrix& M) {
    const long n = M.rows();
    l.assign(n, 0.0);
    dinv.assign(n, 0.0);
    double d_prev = 0.0;
    for (long j = 0; j < n; ++j) {
      double a = 0.0, b = 0.0;  // M(j, j), M(j, j − 1)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
        if (it.row() == j) a = it.value();
        else if (it.row() < j - 1 || it.row() > j + 1) throw std::logic_error("mass matrix is not tridiagonal");
      }
      if (j > 0) b = M.coeff(j, j - 1);
      if (j > 0) l[j] = b / d_prev;
      const double d = a - l[j] * b;
      if (!(d > 0.0)) throw std::runtime_error("mass matrix factorisation failed (not positive definite)");
      dinv[j] = 1.0 / d;
      d_prev = d;
    }
  }
  void solve(const double* b, double* x) const {
    const long n = long(l.size());
    x[0] = b[0];
    for (long i = 1; i < n; ++i) x[i] = b[i] - l[i] * x[i - 1];
    x[n - 1] *= dinv[n - 1];
    for (long i = n - 2; i >= 0; --i) x[i] = x[i] * dinv[i] - l[i + 1] * x[i + 1];
  }
};

FollowerModel::~FollowerModel() = default;

std::string ModelDescription::ToString() const {
  std::ostringstream o;
  o << follower << ": " << nodes << " node(s), " << unknowns << " unknowns, mass " << mass
    << (sparse ? ", sparse" : ", dense/scalar") << ", linear solver " << linear_solver
    << ", contact " << contact << (damping ? ", damped" : ", undamped")
    << (preload ? ", preloaded spring" : "") << (varying_speed ? ", varying cam speed" : "")
    << "; rhs terms:";
  for (const auto& t : rhs_terms) o << ' ' << t;
  for (const auto& e : network) o << "\n    " << e;
  return o.str();
}

FollowerModel::FollowerModel(const Scene& scene) {
  const FollowerSpec& f = scene.follower;
  const double k = scene.spring.stiffness;
  preload_ = k * scene.spring.precompression;
  spring_k_ = k;
  const Cam cam(scene.cam);
  const CamDrive drive(scene.cam);
  const double x0 = cam.evaluate(drive.theta(0.0)).X_C + scene.contact.initial_gap;

  desc_.follower = to_string(f.kind);
  desc_.preload = preload_ != 0.0;
  desc_.varying_speed = !drive.constant_speed();
  desc_.contact = scene.contact.separation ? "unilateral" : "holonomic";
  desc_.rhs_terms = {"inertia"};

  if (f.kind == FollowerKind::Rigid) {
    rigid_ = true;
    lumped_ = true;
    n_ = 1;
    m_ = f.mass;
    k_ = k;
    c_ = f.damping;
    damped_ = c_ != 0.0;
    mstar_ = 1.0 / m_;
    q0_ = Eigen::VectorXd::Constant(1, x0);
    q_far0_ = x0;
    f0_ = Eigen::VectorXd::Constant(1, -preload_ + k * x0);
    Mdiag_inv_ = Eigen::VectorXd::Constant(1, 1.0 / m_);
    desc_.nodes = 1;
    desc_.mass = "scalar";
    desc_.sparse = false;
    if (k != 0.0) desc_.rhs_terms.push_back("spring");
    if (damped_) desc_.rhs_terms.push_back("viscous_damper");
  } else {
    rigid_ = false;
    const long N = f.elements;
    n_ = static_cast<int>(N + 1);
    lumped_ = f.mass_matrix == MassMatrixKind::Lumped;
    const double h = f.length / double(N);
    const double EA = f.youngs_modulus * f.area;
    const double ke = EA / h, me = f.mass / double(N);
    // One tridiagonal pattern shared by K, M and C (explicit zeros where needed), so the
    // engines can fill M + γC + γ²K or M − γJ entry by entry without a sparse add.
    std::vector<Eigen::Triplet<double, long>> tk, tm;
    tk.reserve(4 * N + 1);
    tm.reserve(4 * N);
    const double mo = lumped_ ? 0.0 : me / 6.0, md = lumped_ ? me / 2.0 : me / 3.0;
    for (long e = 0; e < N; ++e) {
      const long a = e, b = e + 1;
      tk.emplace_back(a, a, ke);
      tk.emplace_back(b, b, ke);
      tk.emplace_back(a, b, -ke);
      tk.emplace_back(b, a, -ke);
      tm.emplace_back(a, a, md);
      tm.emplace_back(b, b, md);
      tm.emplace_back(a, b, mo);
      tm.emplace_back(b, a, mo);
    }
    tk.emplace_back(N, N, k);
    K_.resize(n_, n_);
    M_.resize(n_, n_);
    K_.setFromTriplets(tk.begin(), tk.end());
    M_.setFromTriplets(tm.begin(), tm.end());
    K_.makeCompressed();
    M_.makeCompressed();
    const double ar = f.rayleigh_alpha, br = f.rayleigh_beta;
    damped_ = ar != 0.0 || br != 0.0;
    if (damped_) {
      C_ = ar * M_ + br * K_;  // same pattern (both tridiagonal)
      C_.makeCompressed();
    }
    // Initial shape: uniform compression under the preload.
    q0_.resize(n_);
    for (long i = 0; i < n_; ++i) q0_[i] = x0 - double(i) * preload_ / ke;
    q_far0_ = q0_[N];
    f0_ = Eigen::VectorXd::Zero(n_);
    f0_[N] = -preload_ + k * q_far0_;
    // Mass solve: diagonal for lumped, tridiagonal LDLᵀ for consistent.
    if (lumped_) Mdiag_inv_ = M_.diagonal().cwiseInverse();
    else factor_ = std::make_unique<Factor>(M_);
    desc_.nodes = n_;
    desc_.mass = lumped_ ? "lumped" : "consistent";
    desc_.sparse = true;
    desc_.rhs_terms.push_back("bar_stiffness");
    if (k != 0.0) desc_.rhs_terms.push_back("spring");
    if (damped_) desc_.rhs_terms.push_back("rayleigh_damping");
  }
  contact_coupling();
  if (preload_ != 0.0) desc_.rhs_terms.push_back("preload");
  desc_.rhs_terms.push_back("contact_force");
  desc_.damping = damped_;
  desc_.unknowns = 2 * n_ + (scene.solver.integrator == Integrator::Ida ? 3 : 0);  // IDA: + λ, μ, W
  desc_.linear_solver = to_string(resolve_linear_solver(scene.solver, n_));
  if (scene.solver.integrator == Integrator::ArkodeErk) desc_.linear_solver = "none";
}

void FollowerModel::internal_force(const double* q, const double* v, double* r) const {
  if (rigid_) {
    r[0] = f0_[0] - k_ * q[0] - c_ * v[0];
    return;
  }
  // r = r₀ − K(q − q(0)) − C v with r₀ = f₀ − K q(0): the same value as f₀ − Kq − Cv,
  // but its round-off scales with the motion since t = 0, not with |K||q| (a stiff bar
  // at rest otherwise shows force noise of ~1e-7 of the preload, which Lee's
  // acceleration level then feeds back as force jumps that ring the mesh).
  Eigen::Map<const Eigen::VectorXd> V(v, n_);
  Eigen::Map<Eigen::VectorXd> R(r, n_);
  R = r0_;
  const long* outer = K_.outerIndexPtr();
  const long* inner = K_.innerIndexPtr();
  const double* val = K_.valuePtr();
  for (long j = 0; j < n_; ++j) {
    const double dq = q[j] - q0_[j];
    for (long p = outer[j]; p < outer[j + 1]; ++p) r[inner[p]] -= val[p] * dq;
  }
  if (damped_) R.noalias() -= C_ * V;
}

void FollowerModel::solve_mass(const double* b, double* x) const {
  Eigen::Map<const Eigen::VectorXd> B(b, n_);
  Eigen::Map<Eigen::VectorXd> X(x, n_);
  if (lumped_)
    X = B.cwiseProduct(Mdiag_inv_);
  else
    factor_->solve(b, x);
}

// c = M⁻¹e₀, M* = c₀, and the node-0 acceleration as a linear form of the state:
// e₀ᵀM⁻¹(f₀ − Kq − Cv) = c·f₀ − (Kc)·q − (Cc)·v (K, C symmetric), so that
// contact_acceleration is three dot products, no solve, no temporary.
void FollowerModel::contact_coupling() {
  Eigen::VectorXd e0 = Eigen::VectorXd::Zero(n_);
  e0[0] = 1.0;
  mass_col0_.resize(n_);
  solve_mass(e0.data(), mass_col0_.data());
  mstar_ = mass_col0_[0];
  a_f0_ = mass_col0_.dot(f0_);
  if (rigid_) {
    a_q_ = Eigen::VectorXd::Constant(1, k_ * mass_col0_[0]);
    a_v_ = Eigen::VectorXd::Constant(1, c_ * mass_col0_[0]);
    return;
  }
  a_q_ = K_ * mass_col0_;
  a_v_ = damped_ ? Eigen::VectorXd(C_ * mass_col0_) : Eigen::VectorXd::Zero(n_);
  r0_ = f0_ - K_ * q0_;
  a_r0_ = a_f0_ - a_q_.dot(q0_);
}

double FollowerModel::contact_acceleration(const double* q, const double* v, double F) const {
  if (rigid_) return (f0_[0] - k_ * q[0] - c_ * v[0] + F) / m_;
  Eigen::Map<const Eigen::VectorXd> V(v, n_);
  double a = a_r0_ + mstar_ * F;  // shifted by q(0) as in internal_force
  for (long i = 0; i < n_; ++i) a -= a_q_[i] * (q[i] - q0_[i]);
  if (damped_) a -= a_v_.dot(V);
  return a;
}

double FollowerModel::kinetic_energy(const double* v) const {
  if (rigid_) return 0.5 * m_ * v[0] * v[0];
  Eigen::Map<const Eigen::VectorXd> V(v, n_);
  return 0.5 * V.dot(M_ * V);
}

double FollowerModel::potential_energy(const double* q) const {
  if (rigid_) return 0.5 * k_ * q[0] * q[0] - f0_[0] * q[0];
  Eigen::Map<const Eigen::VectorXd> Q(q, n_);
  return 0.5 * Q.dot(K_ * Q) - f0_.dot(Q);
}

double FollowerModel::damping_power(const double* v) const {
  if (!damped_) return 0.0;
  if (rigid_) return c_ * v[0] * v[0];
  Eigen::Map<const Eigen::VectorXd> V(v, n_);
  return V.dot(C_ * V);
}

std::shared_ptr<const FollowerModel> build_model(const Scene& scene) {
  return std::make_shared<const FollowerModel>(scene);
}

}  // namespace camdyn
