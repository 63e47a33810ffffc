// camdyn — the scene validator's rules of [camshaft] (scene/validator.hpp; the camshaft as a
// body, include/camdyn/scene.hpp CamshaftSpec): stations, segments, cams, the drive, the
// crank's orders, and which contacts ride on which cam.
#include <cmath>
#include <string>
#include <vector>
#include <utility>

#include "scene/validator.hpp"

namespace camdyn {
namespace scene_detail {

namespace {
std::string array_text(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt_num(v[i]);
  return s + "]";
}
}  // namespace

void Validator::camshaft() const {
  const CamshaftSpec& c = s_.camshaft;
  const std::string no_shaft = "needs camshaft.inertias (a [camshaft] is a shaft of stations with polar inertia)";
  if (!c.present()) {
    const std::pair<const char*, bool> set[] = {
        {"camshaft.stiffnesses", !c.stiffnesses.empty()},
        {"camshaft.cam_stations", !c.cam_stations.empty()},
        {"camshaft.cam_offsets_deg", !c.cam_offsets_deg.empty()},
        {"camshaft.cam_offsets_crank_deg", !c.cam_offsets_crank_deg.empty()},
        {"camshaft.contact_cams", !c.contact_cams.empty()},
        {"camshaft.crank_orders", !c.crank_orders.empty()},
        {"camshaft.crank_amplitudes_deg", !c.crank_amplitudes_deg.empty()},
        {"camshaft.crank_phases_deg", !c.crank_phases_deg.empty()},
        {"camshaft.drive_stiffness", c.drive_stiffness != 0.0},
        {"camshaft.drive_damping", c.drive_damping != 0.0},
        {"camshaft.rayleigh_alpha", c.rayleigh_alpha != 0.0},
        {"camshaft.rayleigh_beta", c.rayleigh_beta != 0.0},
        {"camshaft.drive_station", c.drive_station != 0},
        {"camshaft.drive", c.drive != CamshaftDrive::Compliant},
    };
    for (const auto& [key, given] : set)
      if (given) fail_at("camshaft.inertias", "[]", std::string(no_shaft) + "; " + key + " is given", key);
    return;
  }
  const std::size_t N = c.inertias.size();
  for (std::size_t i = 0; i < N; ++i) {
    const std::string k = elem("camshaft.inertias", i);
    gt(k, c.inertias[i], 0.0);
    if (c.inertias[i] < 1.0 / kMaxMagnitude)
      fail_at(k, fmt_num(c.inertias[i]), "is not a physical magnitude: must be >= " + fmt_num(1.0 / kMaxMagnitude));
  }
  if (s_.follower.kind != FollowerKind::Network)
    fail_at("camshaft.inertias", array_text(c.inertias),
            std::string("a camshaft needs follower.kind = \"network\" (follower.kind is \"") +
                to_string(s_.follower.kind) + "\"): its cam contacts are the network's",
            "follower.kind");
  if (c.stiffnesses.size() != N - 1)
    fail_at("camshaft.stiffnesses", array_text(c.stiffnesses),
            "must have " + std::to_string(N - 1) + " entries (one per segment between the " + std::to_string(N) +
                " stations of camshaft.inertias)",
            "camshaft.inertias");
  for (std::size_t i = 0; i < c.stiffnesses.size(); ++i) gt(elem("camshaft.stiffnesses", i), c.stiffnesses[i], 0.0);
  auto index = [&](const std::string& key, double v, std::size_t count, const std::string& what) {
    finite(key, v);
    if (!(v >= 0 && v < double(count) && v == std::floor(v)))
      fail_at(key, fmt_num(v),
              "must be an integer >= 0 and < " + std::to_string(count) + " (" + what + ")");
  };
  if (c.cam_stations.empty())
    fail_at("camshaft.cam_stations", "[]", "must name the station of at least one cam");
  const std::size_t ncam = c.cam_stations.size();
  for (std::size_t i = 0; i < ncam; ++i)
    index(elem("camshaft.cam_stations", i), c.cam_stations[i], N,
          "a station of camshaft.inertias, which has " + std::to_string(N));
  if (!c.cam_offsets_deg.empty() && !c.cam_offsets_crank_deg.empty())
    fail_at("camshaft.cam_offsets_crank_deg", array_text(c.cam_offsets_crank_deg),
            "not with camshaft.cam_offsets_deg (give the offsets in one form)", "camshaft.cam_offsets_deg");
  for (const char* key : {"camshaft.cam_offsets_deg", "camshaft.cam_offsets_crank_deg"}) {
    const std::vector<double>& v =
        std::string(key) == "camshaft.cam_offsets_deg" ? c.cam_offsets_deg : c.cam_offsets_crank_deg;
    if (!v.empty() && v.size() != ncam)
      fail_at(key, array_text(v), "must have one entry per cam (" + std::to_string(ncam) + ", camshaft.cam_stations)");
    finite(key, v);
  }
  if (c.drive_station < 0 || std::size_t(c.drive_station) >= N)
    fail_at("camshaft.drive_station", std::to_string(c.drive_station),
            "must be a station of camshaft.inertias (>= 0 and < " + std::to_string(N) + ")");
  if (c.drive == CamshaftDrive::Compliant) {
    gt("camshaft.drive_stiffness", c.drive_stiffness, 0.0);
  } else {
    for (const auto& [key, v] : {std::pair<const char*, double>{"camshaft.drive_stiffness", c.drive_stiffness},
                                 {"camshaft.drive_damping", c.drive_damping}})
      if (v != 0.0)
        fail_at(key, fmt_num(v),
                "not with camshaft.drive = \"prescribed\" (the drive station follows the crank's law exactly: no "
                "coupling)",
                "camshaft.drive");
  }
  if (c.crank_amplitudes_deg.size() != c.crank_orders.size())
    fail_at("camshaft.crank_amplitudes_deg", array_text(c.crank_amplitudes_deg),
            "must have one entry per order of camshaft.crank_orders (" + std::to_string(c.crank_orders.size()) + ")");
  if (c.crank_phases_deg.size() != c.crank_orders.size())
    fail_at("camshaft.crank_phases_deg", array_text(c.crank_phases_deg),
            "must have one entry per order of camshaft.crank_orders (" + std::to_string(c.crank_orders.size()) + ")");
  for (std::size_t i = 0; i < c.crank_orders.size(); ++i) {
    gt(elem("camshaft.crank_orders", i), c.crank_orders[i], 0.0);
    finite(elem("camshaft.crank_amplitudes_deg", i), c.crank_amplitudes_deg[i]);
    finite(elem("camshaft.crank_phases_deg", i), c.crank_phases_deg[i]);
  }
  // the cam contacts and the cams they ride on
  std::size_t cam_contacts = 0;
  for (const ContactPointSpec& k : s_.network.contacts) cam_contacts += k.kind == ContactPointKind::Cam;
  if (c.contact_cams.empty()) {
    if (cam_contacts != ncam)
      fail_at("camshaft.cam_stations", array_text(c.cam_stations),
              "has " + std::to_string(ncam) + " cams but the network has " + std::to_string(cam_contacts) +
                  " cam contacts: give camshaft.contact_cams (the cam of each cam contact) or one cam per cam contact");
  } else {
    if (c.contact_cams.size() != cam_contacts)
      fail_at("camshaft.contact_cams", array_text(c.contact_cams),
              "must have one entry per cam contact of the network (" + std::to_string(cam_contacts) + ")");
    for (std::size_t i = 0; i < c.contact_cams.size(); ++i)
      index(elem("camshaft.contact_cams", i), c.contact_cams[i], ncam,
            "a cam of camshaft.cam_stations, which has " + std::to_string(ncam));
  }
  for (std::size_t i = 0; i < s_.network.nodes.size(); ++i)
    if (s_.network.nodes[i].name.rfind("shaft_", 0) == 0)
      fail_at(elem("nodes", i) + ".name", quote(s_.network.nodes[i].name),
              "\"shaft_<i>\" names the camshaft's stations (a [camshaft] is given): rename the node");
}

}  // namespace scene_detail
}  // namespace camdyn
