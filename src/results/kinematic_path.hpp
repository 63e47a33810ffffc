// camdyn (private) — the kinematic lift of a network's nodes (issue 38): the cam lift X carried
// through the load path with every part rigid and every clearance on the path taken up.
//
//   From a cam contact (gap g = q + c − X ≥ 0: q = max(0, X − c)) along lash contacts
//   (lower → upper: q_upper = max(0, q_lower − c)), levers (input ↔ output: × ratio or
//   ÷ ratio, the pivot held) and the bars, springs, dashpots and progressive springs between
//   two nodes (rigid: q_upper = q_lower). Every node reached gets q = a·max(0, X − b): a the
//   lever ratio of the path, b the cam lift at which the path's clearances are taken up, X the
//   lift of the cam under the cam contact the path starts from (its `source`: with a
//   [camshaft] each cam contact rides on its own cam, so every train has its own path and X).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"

namespace camdyn {
namespace detail {

/// q = gain·max(0, X − take_up) for a node reached from a cam contact.
struct KinematicNode {
  bool reached = false;
  double gain = 0.0;     ///< the path's lever ratio, dq/dX once the clearances are taken up
  double take_up = 0.0;  ///< the cam lift X at which the node starts to move
  /// The cam contact the node's path starts from: its index in the network's [[contacts]]
  /// (−1: not reached). X in lift() is that contact's cam lift.
  int source = -1;
  double lift(double X) const { return reached ? gain * std::max(0.0, X - take_up) : 0.0; }
};

class KinematicPath {
 public:
  /// The network of `scene` (its [[nodes]], [[elements]], [[contacts]]; without them nothing
  /// is reached).
  explicit KinematicPath(const Scene& scene);
  /// The node named `name` (reached = false if no path from a cam contact leads to it).
  KinematicNode node(const std::string& name) const;
  /// Every node of the network in [[nodes]] order, and their names.
  const std::vector<KinematicNode>& nodes() const { return nodes_; }
  const std::vector<std::string>& names() const { return names_; }
  /// The cam lifts X where a clearance on a path from a cam contact is taken up: each cam
  /// contact's clearance and, for every lash contact whose lower node is reached, the lift
  /// at which it closes (sorted, duplicates kept).
  const std::vector<double>& take_up_levels() const { return levels_; }

 private:
  std::vector<std::string> names_;
  std::vector<KinematicNode> nodes_;
  std::vector<double> levels_;
};

}  // namespace detail
}  // namespace camdyn
