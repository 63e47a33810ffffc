// camdyn — the held phase by coordinate partitioning of the contact row (src/held_phase.hpp).
#include "held_phase.hpp"

#include <stdexcept>

namespace camdyn {
namespace detail {

HeldPhase::HeldPhase(const FollowerModel& m) {
  if (m.rigid()) {
    f0_ = m.f0()[0];
    k00_ = m.k_rigid();
    c00_ = m.c_rigid();
    m00_ = m.m_rigid();
    return;
  }
  free_ = m.free_part();
  f0_ = m.f0()[0];
  // Row 0 and column 0 of the symmetric M, K, C: column 0's entries give both.
  auto split = [](const SparseMatrix& A, double& a00, std::vector<Entry>& row, double& a_r0, const char* name) {
    for (SparseMatrix::InnerIterator it(A, 0); it; ++it) {
      if (it.row() == 0) {
        a00 = it.value();
        continue;
      }
      if (it.row() > 1 && it.value() != 0.0)
        throw std::logic_error(std::string("held phase: ") + name + " couples node 0 to node " +
                               std::to_string(it.row()) + "; the engines load one node of the free part");
      if (it.row() == 1) a_r0 = it.value();
      row.push_back({int(it.row()) - 1, it.value()});
    }
  };
  split(m.K(), k00_, k0r_, k_r0_, "K");
  split(m.M(), m00_, m0r_, m_r0_, "M");
  if (m.damped()) {
    split(m.C(), c00_, c0r_, c_r0_, "C");
  } else {
    for (const Entry& e : k0r_) c0r_.push_back({e.j, 0.0});  // undamped: zeros on K's pattern
  }
}

double HeldPhase::reaction(const CamMotion& c, const double* qr, const double* vr, const double* ar) const {
  double r0 = f0_ - k00_ * c.X;
  for (const Entry& e : k0r_) r0 -= e.v * qr[e.j];
  r0 -= c00_ * c.Xdot;
  for (const Entry& e : c0r_) r0 -= e.v * vr[e.j];
  double F = m00_ * c.Xddot;
  for (const Entry& e : m0r_) F += e.v * ar[e.j];
  return F - r0;
}

}  // namespace detail
}  // namespace camdyn
