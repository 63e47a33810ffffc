// camdyn — SparseNewtonSolver (sparse_newton.hpp).
#include "engine/sparse_newton.hpp"

#include <algorithm>
#include <stdexcept>

namespace camdyn {
namespace detail {

namespace {
using Trip = Eigen::Triplet<double, long>;
// Position of (i, j) in compressed S (which holds it).
long position(const SparseMatrix& S, long i, long j) {
  const long* outer = S.outerIndexPtr();
  const long* inner = S.innerIndexPtr();
  const long* b = inner + outer[j];
  const long* e = inner + outer[j + 1];
  const long* p = std::lower_bound(b, e, i);
  if (p == e || *p != i) throw std::logic_error("SparseNewtonSolver: entry outside the pattern");
  return long(p - inner);
}
std::vector<long> positions(const SparseMatrix& S, const SparseMatrix& A) {
  std::vector<long> pos;
  pos.reserve(std::size_t(A.nonZeros()));
  for (long j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) pos.push_back(position(S, it.row(), j));
  return pos;
}
}  // namespace

SparseNewtonSolver::SparseNewtonSolver(const SparseNewton& sys, bool dense, EngineStats& stats)
    : sys_(sys), n_(sys.M->rows()), m_(int(sys.T.rows())), stats_(stats), lu_(dense, stats) {
  if (!sys.M || !sys.K) throw std::invalid_argument("SparseNewton: M and K are required");
  // the union pattern, values zero; the diagonal explicit
  std::vector<Trip> t;
  auto pattern = [&](const SparseMatrix& A) {
    for (long j = 0; j < A.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) t.emplace_back(it.row(), j, 0.0);
  };
  pattern(*sys.M);
  pattern(*sys.K);
  if (sys.C) pattern(*sys.C);
  if (sys.element_tangent) {
    pattern(*sys.Ke_pattern);
    if (sys.Ce_pattern) pattern(*sys.Ce_pattern);
  }
  for (long i = 0; i < n_; ++i) t.emplace_back(i, i, 0.0);
  if (sys.states > 0) {  // R_s H (γG_q + G_v): every row of R_s with every column of G_q (H may be full)
    ns_ = sys.states;
    std::vector<long> ri, cj;
    for (long j = 0; j < sys.Rs_pattern->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*sys.Rs_pattern, j); it; ++it) ri.push_back(it.row());
    for (long j = 0; j < sys.Gq_pattern->outerSize(); ++j)
      if (sys.Gq_pattern->outerIndexPtr()[j + 1] > sys.Gq_pattern->outerIndexPtr()[j]) cj.push_back(j);
    std::sort(ri.begin(), ri.end());
    ri.erase(std::unique(ri.begin(), ri.end()), ri.end());
    for (long i : ri)
      for (long j : cj) t.emplace_back(i, j, 0.0);
    Rs_ = Rs_f_ = *sys.Rs_pattern;
    Gq_ = Gq_f_ = Gv_ = Gv_f_ = *sys.Gq_pattern;
    Gs_ = Gs_f_ = Eigen::MatrixXd::Zero(ns_, ns_);
  }
  T_ = T_f_ = sys.T;
  if (sys.rows) {  // state-dependent rows: their stiffness's pattern
    if (!sys.Kr_pattern) throw std::invalid_argument("SparseNewton: rows needs Kr_pattern");
    pattern(*sys.Kr_pattern);
    Kr_ = Kr_f_ = *sys.Kr_pattern;
  }
  std::vector<std::vector<long>> rows(static_cast<std::size_t>(m_));  // each row's pattern
  if (sys.contact_derivatives) {
    for (int j = 0; j < m_; ++j)
      for (long i = 0; i < n_; ++i)
        if (sys.T(j, i) != 0.0) rows[std::size_t(j)].push_back(i);
    for (const auto& [j, i] : sys.row_entries) rows[std::size_t(j)].push_back(i);
    for (auto& r : rows) {
      std::sort(r.begin(), r.end());
      r.erase(std::unique(r.begin(), r.end()), r.end());
      for (long a : r)
        for (long b : r) t.emplace_back(a, b, 0.0);
    }
  }
  S_.resize(n_, n_);
  S_.setFromTriplets(t.begin(), t.end());
  S_.makeCompressed();
  pos_m_ = positions(S_, *sys.M);
  pos_k_ = positions(S_, *sys.K);
  if (sys.C) pos_c_ = positions(S_, *sys.C);
  if (sys.element_tangent) {
    Ke_ = Ke_f_ = *sys.Ke_pattern;
    pos_ke_ = positions(S_, Ke_);
    if (sys.Ce_pattern) {
      Ce_ = Ce_f_ = *sys.Ce_pattern;
      pos_ce_ = positions(S_, Ce_);
    }
  }
  if (sys.rows) pos_kr_ = positions(S_, Kr_);
  for (int j = 0; j < m_; ++j)
    for (long a : rows[std::size_t(j)])
      for (long b : rows[std::size_t(j)]) outer_.push_back({position(S_, a, b), j, a, b});
  dFdg_ = dFdgd_ = Eigen::VectorXd::Zero(m_);
}

void SparseNewtonSolver::prepare(double t, const double* y, double gamma) {
  gamma_ = gamma;
  if (sys_.rows) sys_.rows(t, y, T_, Kr_);
  if (sys_.contact_derivatives) sys_.contact_derivatives(t, y, dFdg_, dFdgd_);
  if (sys_.element_tangent) sys_.element_tangent(t, y, Ke_, Ce_);
  if (ns_) sys_.state_blocks(t, y, Rs_, Gq_, Gv_, Gs_);
}

namespace {
bool same_values(const SparseMatrix& a, const SparseMatrix& b) {
  return a.nonZeros() == b.nonZeros() && std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr());
}
}  // namespace

void SparseNewtonSolver::setup() {
  if (factored_ && gamma_ == gamma_f_ && dFdg_ == dFdg_f_ && dFdgd_ == dFdgd_f_ &&
      (!sys_.element_tangent || (same_values(Ke_, Ke_f_) && same_values(Ce_, Ce_f_))) &&
      (!ns_ || (same_values(Rs_, Rs_f_) && same_values(Gq_, Gq_f_) && same_values(Gv_, Gv_f_) && Gs_ == Gs_f_)) &&
      (!sys_.rows || (T_ == T_f_ && same_values(Kr_, Kr_f_))))
    return;  // S unchanged
  const double g = gamma_;
  double* x = S_.valuePtr();
  std::fill(x, x + S_.nonZeros(), 0.0);
  const double* v = sys_.M->valuePtr();
  for (std::size_t p = 0; p < pos_m_.size(); ++p) x[pos_m_[p]] += v[p];
  v = sys_.K->valuePtr();
  for (std::size_t p = 0; p < pos_k_.size(); ++p) x[pos_k_[p]] += g * g * v[p];
  if (sys_.C) {
    v = sys_.C->valuePtr();
    for (std::size_t p = 0; p < pos_c_.size(); ++p) x[pos_c_[p]] += g * v[p];
  }
  for (const Outer& o : outer_) x[o.pos] -= (g * dFdgd_[o.j] + g * g * dFdg_[o.j]) * T_(o.j, o.a) * T_(o.j, o.b);
  if (sys_.rows) {
    v = Kr_.valuePtr();
    for (std::size_t p = 0; p < pos_kr_.size(); ++p) x[pos_kr_[p]] += g * g * v[p];
    T_f_ = T_;
    Kr_f_ = Kr_;
  }
  if (sys_.element_tangent) {
    v = Ke_.valuePtr();
    for (std::size_t p = 0; p < pos_ke_.size(); ++p) x[pos_ke_[p]] += g * g * v[p];
    v = Ce_.valuePtr();
    for (std::size_t p = 0; p < pos_ce_.size(); ++p) x[pos_ce_[p]] += g * v[p];
    Ke_f_ = Ke_;
    Ce_f_ = Ce_;
  }
  if (ns_) {  // − γ² R_s H (γG_q + G_v), H = (I − γG_s)⁻¹
    H_ = (Eigen::MatrixXd::Identity(ns_, ns_) - g * Gs_).partialPivLu().inverse();
    const SparseMatrix Hs = H_.sparseView(0.0, 0.0);
    const SparseMatrix G = g * Gq_ + Gv_;
    D_ = Rs_ * (Hs * G);
    for (long j = 0; j < D_.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(D_, j); it; ++it) x[position(S_, it.row(), j)] -= g * g * it.value();
    Rs_f_ = Rs_;
    Gq_f_ = Gq_;
    Gv_f_ = Gv_;
    Gs_f_ = Gs_;
  }
  lu_.factor(S_);
  ++stats_.lin_setups;
  gamma_f_ = g;
  dFdg_f_ = dFdg_;
  dFdgd_f_ = dFdgd_;
  factored_ = true;
  held_f_.clear();
  Z_.resize(0, 0);
}

void SparseNewtonSolver::border_held(const double* bv) {
  const std::vector<int>* held = sys_.held;
  if (!held || held->empty()) return;
  const int k = int(held->size());
  if (Z_.cols() != k || held_f_ != *held) {  // Z = S⁻¹T_Aᵀ, G = T_A Z
    held_f_ = *held;
    Z_.resize(n_, k);
    Eigen::MatrixXd G(k, k);
    for (int i = 0; i < k; ++i) {
      Z_.col(i) = T_f_.row((*held)[std::size_t(i)]).transpose();
      lu_.solve(Z_.col(i).data());
    }
    for (int i = 0; i < k; ++i) G.row(i) = T_f_.row((*held)[std::size_t(i)]) * Z_;
    G_.compute(G);
  }
  Eigen::VectorXd& r = r_;
  r.resize(k);
  for (int i = 0; i < k; ++i) {
    const auto t = T_f_.row((*held)[std::size_t(i)]);
    r[i] = (bv ? t.dot(Eigen::Map<const Eigen::VectorXd>(bv, n_)) : 0.0) - t.dot(rhs_);
  }
  if (k == 1)  // G⁻¹r = r/G (what the 1 × 1 LU gives), without its temporaries
    rhs_.noalias() += Z_.col(0) * (r[0] / G_.matrixLU()(0, 0));
  else
    rhs_.noalias() += Z_ * G_.solve(r);
}

bool SparseNewtonSolver::predicts_next_correction() const {
  return sys_.element_force && sys_.element_tangent && !sys_.contact_derivatives && !sys_.rows && ns_ == 0;
}

void SparseNewtonSolver::next_correction(double t, const double* z0, const double* dz, double* x) {
  const double g = gamma_f_;
  z1_ = Eigen::Map<const Eigen::VectorXd>(z0, 2 * n_) + Eigen::Map<const Eigen::VectorXd>(dz, 2 * n_);
  Eigen::Map<const Eigen::VectorXd> dq(dz, n_), dv(dz + n_, n_);
  re_.setZero(n_);
  sys_.element_force(t, z1_.data(), re_.data());
  rhs_.setZero(n_);
  sys_.element_force(t, z0, rhs_.data());
  re_ -= rhs_;
  re_.noalias() += Ke_f_ * dq;
  if (Ce_f_.nonZeros()) re_.noalias() += Ce_f_ * dv;
  // S x_v = γ m + T_Aᵀμ with T_A x_v = 0 (the velocity rows of [0; γ P M⁻¹ m]), x_u = γ x_v
  rhs_ = g * re_;
  lu_.solve(rhs_.data());
  border_held(nullptr);
  Eigen::Map<Eigen::VectorXd>(x + n_, n_) = rhs_;
  Eigen::Map<Eigen::VectorXd>(x, n_) = g * rhs_;
}

void SparseNewtonSolver::solve(double* b) {
  const double g = gamma_f_;
  Eigen::Map<Eigen::VectorXd> U(b, n_), V(b + n_, n_);
  rhs_.noalias() = *sys_.M * V;
  rhs_.noalias() -= g * (*sys_.K * U);
  if (sys_.element_tangent) rhs_.noalias() -= g * (Ke_f_ * U);
  if (sys_.rows) rhs_.noalias() -= g * (Kr_f_ * U);
  Eigen::Map<Eigen::VectorXd> Bs(b + 2 * n_, ns_);
  if (ns_) {  // + γ R_s H (b_s + γ G_q b_u)
    w_ = Bs;
    w_.noalias() += g * (Gq_f_ * U);
    rhs_.noalias() += g * (Rs_f_ * (H_ * w_));
  }
  if (sys_.contact_derivatives)
    for (int j = 0; j < m_; ++j)
      if (dFdg_f_[j] != 0.0) rhs_.noalias() += (g * dFdg_f_[j] * T_f_.row(j).dot(U)) * T_f_.row(j).transpose();
  lu_.solve(rhs_.data());
  border_held(b + n_);
  V = rhs_;
  U += g * V;
  if (ns_) {  // x_s = H (b_s + γ(G_q x_u + G_v x_v))
    w_ = Bs;
    w_.noalias() += g * (Gq_f_ * U);
    w_.noalias() += g * (Gv_f_ * V);
    Bs = H_ * w_;
  }
}

}  // namespace detail
}  // namespace camdyn
