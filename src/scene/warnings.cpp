// camdyn — the plausibility warnings that need only the scene (scene/warnings.hpp).
#include "scene/warnings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace camdyn {
namespace scene_detail {

std::string warning_number(double x) {
  char b[32];
  if (x == std::floor(x) && std::abs(x) < 1e9)
    std::snprintf(b, sizeof b, "%.0f", x);
  else
    std::snprintf(b, sizeof b, "%.4g", x);
  return b;
}

void append_speed_warning(const Scene& scene, const PlausibleRanges& r, std::vector<std::string>& w) {
  const auto num = warning_number;
  double speed = scene.cam.speed_table_rev_s.empty() ? std::abs(scene.cam.speed_rev_s) : 0.0;
  for (double s : scene.cam.speed_table_rev_s) speed = std::max(speed, std::abs(s));
  if (speed > r.max_speed_rev_s)
    w.push_back("cam: speed " + num(speed) + " rev/s (" + num(60.0 * speed) + " camshaft rpm, " +
                num(120.0 * speed) + " engine rpm) is above " + num(r.max_speed_rev_s) +
                " rev/s, beyond any valve train (cam.speed_rev_s is in camshaft revolutions per second)");
}

void append_network_part_warnings(const NetworkSpec& network, const PlausibleRanges& r,
                                  std::vector<std::string>& w) {
  const auto num = warning_number;
  for (const NodeSpec& n : network.nodes)
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
  for (std::size_t i = 0; i < network.elements.size(); ++i) {
    const ElementSpec& e = network.elements[i];
    const std::string name =
        "element '" + (e.name.empty() ? std::string(to_string(e.kind)) + " #" + std::to_string(i) : e.name) + "'";
    if (e.kind == ElementKind::Spring) stiffness(name + ": stiffness", e.stiffness);
    if (e.kind == ElementKind::Spring && e.preload < 0)
      w.push_back(name + ": preload " + num(e.preload) + " N is negative: the spring pulls its nodes together at rest " +
                  "(a valve spring is installed compressed: preload > 0)");
    if (e.kind == ElementKind::Bar) stiffness(name + ": E*A/L", e.youngs_modulus * e.area / e.length);
  }
}

}  // namespace scene_detail
}  // namespace camdyn
