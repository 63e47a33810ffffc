// camdyn — plausibility warnings for valve trains (include/camdyn/scene_warnings.hpp): those
// that need the cam's lift (the shared cam of the run), with the scene's own
// (scene/warnings.hpp) in the documented order.
#include "camdyn/scene_warnings.hpp"

#include <cmath>
#include <exception>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/shared_cam.hpp"
#include "scene/warnings.hpp"

namespace camdyn {

namespace {

struct Gap {
  std::string name;
  double clearance;
};

// How each node moves per unit of cam lift when the cam drives the train rigidly (bars,
// springs between two nodes and closed lashes carry the motion, levers scale it): NaN for a node the cam does not drive.
// Breadth-first from the cam contacts' nodes, so linear in the network's size.
std::vector<double> lift_rates(const NetworkSpec& n) {
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < n.nodes.size(); ++i) index.emplace(n.nodes[i].name, i);
  std::vector<double> m(n.nodes.size(), NAN);
  // links[i]: (element or contact, is_contact) touching node i
  std::vector<std::vector<std::pair<std::size_t, bool>>> links(n.nodes.size());
  auto at = [&](const std::string& name) -> long {
    const auto it = index.find(name);
    return it == index.end() ? -1 : long(it->second);
  };
  for (std::size_t e = 0; e < n.elements.size(); ++e)
    for (const auto& name : n.elements[e].nodes)
      if (at(name) >= 0) links[std::size_t(at(name))].push_back({e, false});
  for (std::size_t c = 0; c < n.contacts.size(); ++c)
    for (const auto& name : n.contacts[c].nodes)
      if (at(name) >= 0) links[std::size_t(at(name))].push_back({c, true});
  std::vector<std::size_t> queue;
  for (const auto& c : n.contacts)
    if (c.kind == ContactPointKind::Cam && c.nodes.size() == 1 && at(c.nodes[0]) >= 0 &&
        std::isnan(m[std::size_t(at(c.nodes[0]))])) {
      m[std::size_t(at(c.nodes[0]))] = 1.0;
      queue.push_back(std::size_t(at(c.nodes[0])));
    }
  auto set = [&](long node, double v) {
    if (node < 0 || !std::isnan(m[std::size_t(node)]) || !std::isfinite(v)) return;
    m[std::size_t(node)] = v;
    queue.push_back(std::size_t(node));
  };
  for (std::size_t qi = 0; qi < queue.size(); ++qi) {
    const std::size_t i = queue[qi];
    const std::string& name = n.nodes[i].name;
    for (const auto& [k, contact] : links[i]) {
      if (!contact) {
        const ElementSpec& e = n.elements[k];
        if (e.nodes.size() != 2) continue;
        const long a = at(e.nodes[0]), b = at(e.nodes[1]);
        if (e.kind == ElementKind::Bar || (e.kind == ElementKind::Spring && e.stiffness > 0)) {
          set(a, m[i]);  // a bar, or a spring between two nodes (a valve stem), carries the motion
          set(b, m[i]);
        } else if (e.kind == ElementKind::Lever && e.ratio != 0) {
          if (e.nodes[0] == name) set(b, e.ratio * m[i]);
          else set(a, m[i] / e.ratio);
        }
      } else {
        const ContactPointSpec& c = n.contacts[k];
        if (c.kind != ContactPointKind::Lash || c.nodes.size() != 2) continue;
        // g = q_upper − q_lower + clearance: a contact only pushes, the lower node drives
        // the upper one up, the upper one drives the lower one down.
        if (c.nodes[0] == name && m[i] > 0) set(at(c.nodes[1]), m[i]);
        if (c.nodes[1] == name && m[i] < 0) set(at(c.nodes[0]), m[i]);
      }
    }
  }
  return m;
}

}  // namespace

std::vector<std::string> scene_warnings(const Scene& scene, const FollowerSystem* follower,
                                        const PlausibleRanges& r) {
  const auto num = scene_detail::warning_number;
  std::vector<std::string> w;
  // The valve-train scenes (SI units): a network ([[contacts]], @pre valid: only on
  // follower.kind = "network"), or a user follower's contacts.
  const bool network = !follower && !scene.network.contacts.empty();
  if (!network && !follower) return w;

  // ---- the cam: its lift (lengths in mm?) and its speed
  double lift = NAN;
  try {
    lift = detail::shared_cam(scene.cam)->lift();
  } catch (const std::exception&) {
    lift = NAN;  // a cam the run itself will refuse: nothing to say here
  }
  if (std::isfinite(lift) && lift > r.max_lift)
    w.push_back("cam: lift " + num(lift) + " m is larger than " + num(r.max_lift) +
                " m: lengths are in metres (" + num(lift) + " mm is " + num(lift / 1000.0) + " m)");
  scene_detail::append_speed_warning(scene, r, w);

  // ---- lash: a cam or lash contact whose clearance is not smaller than the lift
  std::vector<Gap> gaps;
  if (network) {
    for (const ContactPointSpec& c : scene.network.contacts)
      if (c.kind == ContactPointKind::Cam || c.kind == ContactPointKind::Lash) gaps.push_back({c.name, c.clearance});
  } else {
    for (const FollowerContact& c : follower->contacts())
      if (c.cam) gaps.push_back({c.name, c.clearance});
  }
  for (const Gap& g : gaps)
    if (std::isfinite(lift) && g.clearance > 0 && g.clearance >= lift)
      w.push_back("contact '" + g.name + "': clearance " + num(g.clearance) + " m is not smaller than the cam's lift " +
                  num(lift) + " m: the valve never opens (lengths are in metres: " + num(g.clearance) + " mm is " +
                  num(g.clearance / 1000.0) + " m)");
  if (!network) return w;

  // ---- contacts that the cam's lift can never open or never close
  if (std::isfinite(lift) && lift > 0) {
    const NetworkSpec& n = scene.network;
    const std::vector<double> m = lift_rates(n);
    std::map<std::string, std::size_t> index;
    for (std::size_t i = 0; i < n.nodes.size(); ++i) index.emplace(n.nodes[i].name, i);
    auto rate = [&](const std::string& node) {
      const auto it = index.find(node);
      return it == index.end() ? NAN : m[it->second];
    };
    for (const ContactPointSpec& c : n.contacts) {
      if (c.kind == ContactPointKind::Stop && c.nodes.size() == 1) {
        const double r = rate(c.nodes[0]);
        const double dg = (c.side == StopSide::Below ? r : -r) * lift;  // gap change over the full lift
        if (std::isfinite(dg) && dg < 0 && -dg > c.clearance)
          w.push_back("contact '" + c.name + "' (stop, side \"" + (c.side == StopSide::Below ? "below" : "above") +
                      "\"): the cam's lift " + num(lift) + " m would close it by " + num(-dg) +
                      " m, more than its clearance " + num(c.clearance) + " m: it blocks node '" + c.nodes[0] +
                      "' and never opens while the cam lifts (a valve seat is side = \"below\")");
      } else if (c.kind == ContactPointKind::Lash && c.nodes.size() == 2) {
        const double r0 = rate(c.nodes[0]), r1 = rate(c.nodes[1]);
        if (std::isfinite(r0) != std::isfinite(r1)) {
          // One side driven, the other not: the lift opens this lash instead of closing it.
          const std::string& driven = std::isfinite(r0) ? c.nodes[0] : c.nodes[1];
          const std::string& other = std::isfinite(r0) ? c.nodes[1] : c.nodes[0];
          const double dg = (std::isfinite(r1) ? r1 : -r0) * lift;
          w.push_back("contact '" + c.name + "' (lash, nodes [" + c.nodes[0] + ", " + c.nodes[1] +
                      "]): the cam's lift " + num(lift) + " m moves node '" + driven + "' away from node '" + other +
                      "' (the gap grows by " + num(std::abs(dg)) + " m): it never closes while the cam lifts and '" +
                      other + "' is never driven (a lash's nodes are [lower, upper]: the driving side first)");
        }
      }
    }
  }

  // ---- masses and stiffnesses of the network
  scene_detail::append_network_part_warnings(scene.network, r, w);
  return w;
}

}  // namespace camdyn
