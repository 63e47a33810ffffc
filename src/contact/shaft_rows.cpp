// camdyn — the contact rows at the state of a mechanism with a camshaft (contact_run.hpp:
// rows_at, cam_acc at a state; src/mechanism/camshaft.hpp has the model): a cam contact on the
// shaft gains the column −X_L′ on its station, T̃ = T − X_L′ e_sᵀ, M⁻¹T̃ᵀ = M⁻¹Tᵀ − X_L′ M⁻¹e_s,
// W̃ = T̃ M⁻¹T̃ᵀ, and its gap acceleration the part X_L″ φ̇_s² besides T̃ q̈.
#include <algorithm>
#include <string>

#include "contact/contact_run.hpp"
#include "contact/run_failure.hpp"  // fmt

namespace camdyn {
namespace detail {

double ContactRun::cam_acc(int j, const Eigen::VectorXd& y, const CamMotion& cm) const {
  const CamShaft* cs = mk_.camshaft();
  if (!cs || cs->contact_cam(j) < 0) return cam_acc(j, cm);
  return cs->contact_cam_motion(j, shaft_time(j, cm), y.data(), y.data() + n_).Xddot;
}

ContactRun::Rows ContactRun::rows_at(const double* q) const {
  const CamShaft* cs = mk_.camshaft();
  if (!cs) return {mk_.T(), mk_.MinvTt(), mk_.W()};
  const Eigen::Map<const Eigen::VectorXd> Q(q, n_);
  if (rows_q_.size() == n_ && rows_q_ == Q) return {rows_T_, rows_MT_, rows_W_};
  rows_T_ = mk_.T();
  rows_MT_ = mk_.MinvTt();
  const Eigen::MatrixXd& Z = cs->station_response();
  for (int j = 0; j < m_; ++j) {
    if (!cs->on_free_station(j)) continue;  // a prescribed station's cam: the row T_j
    const double dX = cs->lift(j, q).dX;
    const int s = cs->contact_dof(j);
    rows_T_(j, s) -= dX;
    rows_MT_.col(j) -= dX * Z.col(cs->cam_station(cs->contact_cam(j)));
  }
  rows_W_ = rows_T_ * rows_MT_;
  rows_q_ = Q;
  return {rows_T_, rows_MT_, rows_W_};
}

void ContactRun::note_shaft_frequencies() {
  const auto* mech = dynamic_cast<const Mechanism*>(&mk_);
  if (!mech || !mech->camshaft()) return;
  const std::vector<double> f = held_frequencies_hz(*mech, y_.data(), active_list(), F_.data());
  std::string line = "natural frequencies with the trains attached (the start's closed contacts held, crank held):";
  for (std::size_t i = 0; i < std::min<std::size_t>(f.size(), 6); ++i) line += (i ? ", " : " ") + fmt(f[i]) + " Hz";
  if (f.empty()) line += " none (the held contacts fix every unknown)";
  rec_.model.network.push_back(line);
}

// K̃ −= ∂(T̃ᵀF)/∂q at fixed F: the row's station entry −X_L′(φ_s) gives κF_j on (s, s),
// κ = X_L″(φ_s); and a law with ∂F/∂ġ ≠ 0 sees ġ_j = T_j v − X_L′ φ̇_s move with φ_s:
// ∂ġ_j/∂φ_s = −κφ̇_s, so K̃(i, s) += T̃_ji (∂F_j/∂ġ) κ φ̇_s.
void ContactRun::shaft_newton(SparseNewton& sn, ShaftForceFn forces) {
  const CamShaft* cs = mk_.camshaft();
  if (!cs) return;
  std::vector<Eigen::Triplet<double, long>> pat;
  for (int j = 0; j < m_; ++j) {
    if (!cs->on_free_station(j)) continue;
    const long s = cs->contact_dof(j);
    sn.row_entries.emplace_back(j, s);
    pat.emplace_back(s, s, 0.0);
    for (int i = 0; i < n_; ++i)
      if (mk_.T()(j, i) != 0.0) pat.emplace_back(i, s, 0.0);
  }
  shaft_kr_pattern_.resize(n_, n_);
  shaft_kr_pattern_.setFromTriplets(pat.begin(), pat.end());
  shaft_kr_pattern_.makeCompressed();
  sn.Kr_pattern = &shaft_kr_pattern_;
  sn.rows = [this, cs, forces = std::move(forces)](double t, const double* y, Eigen::MatrixXd& T, SparseMatrix& Kr) {
    T = rows_at(y).T;
    shaft_y_ = Eigen::Map<const Eigen::VectorXd>(y, ny_);
    shaft_F_.setZero(m_);
    shaft_dF_.setZero(m_);
    forces(t, shaft_y_, shaft_F_, shaft_dF_);
    std::fill(Kr.valuePtr(), Kr.valuePtr() + Kr.nonZeros(), 0.0);
    for (int j = 0; j < m_; ++j) {
      if (!cs->on_free_station(j)) continue;
      const long s = cs->contact_dof(j);
      const double kappa = cs->lift(j, y).ddX;
      Kr.coeffRef(s, s) += kappa * shaft_F_[j];
      if (shaft_dF_[j] == 0.0) continue;
      const double c = shaft_dF_[j] * kappa * y[n_ + s];
      for (int i = 0; i < n_; ++i)
        if (T(j, i) != 0.0) Kr.coeffRef(i, s) += c * T(j, i);
    }
  };
}

}  // namespace detail
}  // namespace camdyn
