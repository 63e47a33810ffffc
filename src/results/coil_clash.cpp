// camdyn — the coil-clash results of a run (coil_clash.hpp).
#include "results/coil_clash.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "results/designer_stats.hpp"  // angle_deg_mod360

namespace camdyn {
namespace detail {

void collect_coil_clash(Summary& s) {
  std::vector<CoilClashResult>& out = s.coil_clash;
  out.clear();
  for (const ContactResult& c : s.contacts) {
    if (c.coil_spring.empty()) continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const CoilClashResult& r) { return r.spring == c.coil_spring; });
    if (it == out.end()) {
      out.emplace_back();
      it = out.end() - 1;
      it->spring = c.coil_spring;
    }
    it->impacts += c.impacts;
    it->coils_closed += c.impacts > 0;
    it->max_impact_velocity = std::max(it->max_impact_velocity, c.max_impact_velocity);
  }
  std::map<std::string, std::string> spring_of;  // coil contact → its spring
  for (const ContactResult& c : s.contacts)
    if (!c.coil_spring.empty()) spring_of[c.name] = c.coil_spring;
  for (const ContactEvent& e : s.events) {  // the first impact in time (angles wrap)
    if (e.type != EventKind::Impact) continue;
    const auto k = spring_of.find(e.contact);
    if (k == spring_of.end()) continue;
    for (CoilClashResult& r : out)
      if (r.spring == k->second && std::isnan(r.first_impact_theta_deg))
        r.first_impact_theta_deg = angle_deg_mod360(e.theta);
  }
}

}  // namespace detail
}  // namespace camdyn
