// camdyn — plausibility warnings for valve trains (include/camdyn/scene_warnings.hpp).
#include "camdyn/scene_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "camdyn/cam.hpp"

namespace camdyn {

namespace {

// Four significant digits: a warning names a value, it is no record of it (0.008, 1e+10);
// whole numbers below 1e9 in full (35000).
std::string num(double x) {
  char b[32];
  if (x == std::floor(x) && std::abs(x) < 1e9)
    std::snprintf(b, sizeof b, "%.0f", x);
  else
    std::snprintf(b, sizeof b, "%.4g", x);
  return b;
}

struct Gap {
  std::string name;
  double clearance;
};

}  // namespace

std::vector<std::string> scene_warnings(const Scene& scene, const FollowerSystem* follower,
                                        const PlausibleRanges& r) {
  std::vector<std::string> w;
  const bool network = scene.follower.kind == FollowerKind::Network && !follower;
  if (!network && !follower) return w;

  // ---- the cam: its lift (lengths in mm?) and its speed
  double lift = NAN;
  try {
    lift = Cam(scene.cam).lift();
  } catch (const std::exception&) {
    lift = NAN;  // a cam the run itself will refuse: nothing to say here
  }
  if (std::isfinite(lift) && lift > r.max_lift)
    w.push_back("cam: lift " + num(lift) + " m is larger than " + num(r.max_lift) +
                " m: lengths are in metres (" + num(lift) + " mm is " + num(lift / 1000.0) + " m)");
  double speed = scene.cam.speed_table_rev_s.empty() ? std::abs(scene.cam.speed_rev_s) : 0.0;
  for (double s : scene.cam.speed_table_rev_s) speed = std::max(speed, std::abs(s));
  if (speed > r.max_speed_rev_s)
    w.push_back("cam: speed " + num(speed) + " rev/s (" + num(60.0 * speed) + " camshaft rpm, " +
                num(120.0 * speed) + " engine rpm) is above " + num(r.max_speed_rev_s) +
                " rev/s, beyond any valve train (cam.speed_rev_s is in camshaft revolutions per second)");

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

  // ---- masses and stiffnesses of the network
  for (const NodeSpec& n : scene.network.nodes)
    if (n.mass > 0 && (n.mass < r.min_node_mass || n.mass > r.max_node_mass))
      w.push_back("node '" + n.name + "': mass " + num(n.mass) + " kg is outside the valve-train range " +
                  num(r.min_node_mass) + " to " + num(r.max_node_mass) + " kg" +
                  (n.mass > r.max_node_mass ? " (masses are in kg: " + num(n.mass) + " g is " + num(n.mass / 1000.0) +
                                                  " kg)"
                                            : std::string()));
  auto stiffness = [&](const std::string& what, double k) {
    if (k > 0 && (k < r.min_stiffness || k > r.max_stiffness))
      w.push_back(what + " " + num(k) + " N/m is outside the valve-train range " + num(r.min_stiffness) + " to " +
                  num(r.max_stiffness) + " N/m" +
                  (k < r.min_stiffness ? " (stiffnesses are in N/m: " + num(k) + " N/mm is " + num(k * 1000.0) +
                                             " N/m)"
                                       : std::string()));
  };
  for (std::size_t i = 0; i < scene.network.elements.size(); ++i) {
    const ElementSpec& e = scene.network.elements[i];
    const std::string name =
        "element '" + (e.name.empty() ? std::string(to_string(e.kind)) + " #" + std::to_string(i) : e.name) + "'";
    if (e.kind == ElementKind::Spring) stiffness(name + ": stiffness", e.stiffness);
    if (e.kind == ElementKind::Bar) stiffness(name + ": E*A/L", e.youngs_modulus * e.area / e.length);
  }
  return w;
}

}  // namespace camdyn
