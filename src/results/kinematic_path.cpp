// camdyn — the kinematic lift of a network's nodes (kinematic_path.hpp).
#include "results/kinematic_path.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace camdyn {
namespace detail {

KinematicPath::KinematicPath(const Scene& scene) {
  const NetworkSpec& net = scene.network;  // empty without [[nodes]]/[[contacts]]: no path
  for (const NodeSpec& n : net.nodes) names_.push_back(n.name);
  nodes_.assign(names_.size(), KinematicNode{});
  auto index = [&](const std::string& s) -> int {
    for (std::size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == s) return int(i);
    return -1;  // ground
  };
  std::deque<int> queue;
  for (std::size_t j = 0; j < net.contacts.size(); ++j) {
    const ContactPointSpec& c = net.contacts[j];
    if (c.kind != ContactPointKind::Cam || c.nodes.empty()) continue;
    levels_.push_back(c.clearance);
    const int i = index(c.nodes[0]);
    if (i < 0 || nodes_[std::size_t(i)].reached) continue;
    nodes_[std::size_t(i)] = {true, 1.0, c.clearance, int(j)};
    queue.push_back(i);
  }
  // breadth first: the first path found to a node is its path (and its source's cam)
  int from = -1;  // the source of the node being expanded
  auto reach = [&](int to, double gain, double take_up) {
    if (to < 0 || nodes_[std::size_t(to)].reached || !(gain != 0.0) || !std::isfinite(gain)) return;
    nodes_[std::size_t(to)] = {true, gain, take_up, from};
    queue.push_back(to);
  };
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    const KinematicNode k = nodes_[std::size_t(i)];
    from = k.source;
    const std::string& me = names_[std::size_t(i)];
    for (const ContactPointSpec& c : net.contacts) {
      if (c.kind != ContactPointKind::Lash || c.nodes.size() != 2 || c.nodes[0] != me) continue;
      // q_upper = max(0, a·max(0, X − b) − c) = a·max(0, X − b − c/a) for a > 0
      if (k.gain > 0) reach(index(c.nodes[1]), k.gain, k.take_up + c.clearance / k.gain);
    }
    for (const ElementSpec& e : net.elements) {
      if (e.nodes.size() < 2) continue;
      const int a = index(e.nodes[0]), b = index(e.nodes[1]);
      if (a < 0 || b < 0) continue;  // an element to ground is not on a path
      if (e.kind == ElementKind::Lever) {
        if (a == i) reach(b, k.gain * e.ratio, k.take_up);
        if (b == i && e.ratio != 0.0) reach(a, k.gain / e.ratio, k.take_up);
      } else {
        if (a == i) reach(b, k.gain, k.take_up);
        if (b == i) reach(a, k.gain, k.take_up);
      }
    }
  }
  for (const ContactPointSpec& c : net.contacts) {
    if (c.kind != ContactPointKind::Lash || c.nodes.size() != 2) continue;
    const int lo = index(c.nodes[0]);
    if (lo < 0) continue;
    const KinematicNode& k = nodes_[std::size_t(lo)];
    if (k.reached && k.gain > 0) levels_.push_back(k.take_up + c.clearance / k.gain);
  }
  std::sort(levels_.begin(), levels_.end());
}

KinematicNode KinematicPath::node(const std::string& name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return nodes_[i];
  return {};
}

}  // namespace detail
}  // namespace camdyn
