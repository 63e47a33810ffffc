// camdyn (private) — the speed-range map behind jump_speed()'s simulation route
// (designer.hpp; docs/guide/sweeps.md "The speed-range map").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "camdyn/designer.hpp"

namespace camdyn {
class FollowerSystem;
namespace detail {

/// The verdict kinds the map follows, in their reporting order.
const std::vector<std::string>& map_kinds();
/// true for the kinds that are a departure of the cam chain (not "seat_bounce").
bool is_departure_kind(const std::string& kind);

/// One trial: the scene at `speed_rev_s` (signed) for jump.settle_revolutions +
/// jump.judge_revolutions revolutions; the verdict of the events in the judged ones.
/// Never throws for a failing run (finished = false, text = its message).
SpeedTrial run_speed_trial(const Scene& scene, double speed_rev_s,
                           const std::shared_ptr<const FollowerSystem>& follower,
                           std::string* contact_of_first = nullptr, double* theta_of_first = nullptr);

/// The map over |speed| (dir: the sign of the speeds run); `est` [rev/s] > 0 centres an
/// automatic range. @pre options validated, scene resolved and validated.
JumpResult speed_map(const Scene& scene, const JumpOptions& options, double dir, double est,
                     const std::shared_ptr<const FollowerSystem>& follower);

}  // namespace detail
}  // namespace camdyn
