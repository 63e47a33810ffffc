// camdyn — a C0 joint of the cam under closed contacts, for any number of contacts
// (ContactRun::cam_joint_impact). At a joint the cam's velocity Ẋ_C jumps (a constant-velocity ramp next to a
// dwell); the steps land there (cam_stops.hpp), the step that ends on it sees the cam
// before it, every step after it the cam after it (cam_joints.hpp). A closed cam contact
// the cam now approaches (ġ⁺ < 0) is struck: a plastic impact on every contact taking part
// (resolve_impact: the cam's impulse work and the loss booked, the struck contacts held);
// one the cam now leaves (ġ⁺ > 0) separates; holonomic contacts take the jump both ways.
#include <cmath>

#include "contact/contact_run.hpp"

namespace camdyn {
namespace detail {

bool ContactRun::cam_joint_impact() {
  CamMotion r;
  if (joints_.empty() || t_ == joint_t_ || !joints_.at(cam_, t_, 1, &r)) return false;
  joint_t_ = t_;
  for (CamCache& c : cam_cache_)  // the joint's time was cached with the motion before it
    if (c.t == t_) c.t = NAN;
  const CamMotion cm = cam_at(t_);
  std::vector<int> struck, leaving;
  for (int j = 0; j < m_; ++j) {
    if (!active_[j] || !mk_.contacts()[j].cam) continue;
    const double v = mk_.contacts()[j].t.dot(y_.segment(n_, n_)), gd = v - cm.Xdot;
    if (!(std::abs(gd) > 1e-12 * (std::abs(cm.Xdot) + std::abs(v)))) continue;
    (gd < 0.0 || !unilateral_ ? struck : leaving).push_back(j);
  }
  if (struck.empty() && leaving.empty()) return false;
  for (int j : leaving) {
    active_[j] = 0;
    ++rec_.separations;
    record_event(EventKind::Separation, j, 0.0);
  }
  if (struck.empty()) {
    settle_active(cm);
    return true;
  }
  for (int j : struck) active_[j] = 0;  // they take part as closing contacts
  resolve_impact(struck, cm, /*plastic=*/true);
  return true;
}

}  // namespace detail
}  // namespace camdyn
