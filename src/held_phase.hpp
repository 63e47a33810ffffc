// camdyn (private) — the held phase of a single follower (event-driven and holonomic
// baselines, src/contact/event.cpp) by coordinate partitioning of its contact row.
//
//   The contact row T = e₀ᵀ (node 0, the contact face) held on the cam: q₀ = X_C(t) is a
//   holonomic constraint, and its multiplier is the contact force F. With r the other
//   coordinates, M q̈ + C q̇ + K q = f₀ + e₀F splits into
//     M_rr q̈_r + C_rr q̇_r + K_rr q_r = f_r − (K_r0 X_C + C_r0 Ẋ_C + M_r0 Ẍ_C)     (motion)
//     F = M_00 Ẍ_C + M_0r q̈_r − (f₀,₀ − K_00 X_C − K_0r q_r − C_00 Ẋ_C − C_0r q̇_r)  (force)
//   The free part is a follower model over r (the engines integrate it); the row 0 and
//   column 0 couplings are read from the model's sparse matrices, whatever their pattern.
//   The engines take a load on one node of a model, so the column couplings must reach
//   only the free part's first node (true for every element that joins node 0 to one
//   neighbour, as the bar's do); the constructor checks it.
//   A rigid follower has no free part: F = m Ẍ_C − (f₀ − k X_C − c Ẋ_C).
#pragma once

#include <memory>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/model.hpp"

namespace camdyn {
namespace detail {

class HeldPhase {
 public:
  /// @throws std::logic_error if node 0 couples to a free node other than its neighbour.
  explicit HeldPhase(const FollowerModel& model);

  /// The free part (n − 1 nodes; its node 0 is the model's node 1), null for a rigid
  /// follower.
  const std::shared_ptr<const FollowerModel>& free_part() const { return free_; }
  /// The cam's load on the free part's node 0: −K_r0 X_C − C_r0 Ẋ_C − M_r0 Ẍ_C.
  double coupling_load(const CamMotion& c) const { return -k_r0_ * c.X - c_r0_ * c.Xdot - m_r0_ * c.Xddot; }
  /// The contact force at the free part's state (q_r, v_r) and acceleration a_r (null for
  /// a rigid follower).
  double reaction(const CamMotion& c, const double* qr, const double* vr, const double* ar) const;

 private:
  struct Entry {
    int j;     // free coordinate
    double v;  // row 0's coefficient there
  };
  std::shared_ptr<const FollowerModel> free_;
  double f0_ = 0, k00_ = 0, c00_ = 0, m00_ = 0;
  std::vector<Entry> k0r_, c0r_, m0r_;
  double k_r0_ = 0, c_r0_ = 0, m_r0_ = 0;
};

}  // namespace detail
}  // namespace camdyn
