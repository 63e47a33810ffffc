// camdyn — the contact rows at the state of a mechanism with a camshaft (contact_run.hpp:
// rows_at, cam_acc at a state; src/mechanism/camshaft.hpp has the model): a cam contact on the
// shaft gains the column −X_L′ on its station, T̃ = T − X_L′ e_sᵀ, M⁻¹T̃ᵀ = M⁻¹Tᵀ − X_L′ M⁻¹e_s,
// W̃ = T̃ M⁻¹T̃ᵀ, and its gap acceleration the part X_L″ φ̇_s² besides T̃ q̈.
#include "contact/contact_run.hpp"

namespace camdyn {
namespace detail {

double ContactRun::cam_acc(int j, const Eigen::VectorXd& y, const CamMotion& cm) const {
  const CamShaft* cs = mk_.camshaft();
  if (!cs || cs->contact_cam(j) < 0) return cam_acc(j, cm);
  const double w = y[n_ + cs->contact_dof(j)];
  return cs->lift(j, y.data()).ddX * w * w;
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
    if (cs->contact_cam(j) < 0) continue;
    const double dX = cs->lift(j, q).dX;
    const int s = cs->contact_dof(j);
    rows_T_(j, s) -= dX;
    rows_MT_.col(j) -= dX * Z.col(cs->cam_station(cs->contact_cam(j)));
  }
  rows_W_ = rows_T_ * rows_MT_;
  rows_q_ = Q;
  return {rows_T_, rows_MT_, rows_W_};
}

}  // namespace detail
}  // namespace camdyn
