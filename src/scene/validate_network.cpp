// camdyn — the scene validator's rules of the network tables ([[nodes]], [[elements]],
// [[contacts]]; scene/validator.hpp): names, nodes, values, levers (no cycles, O(levers)),
// dangling and floating nodes, mass after lever elimination.
#include "scene/validator.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "scene/element_kinds.hpp"

namespace camdyn {
namespace scene_detail {

void Validator::network() const {
  const Scene& s = s_;
  const NetworkSpec& n = s.network;
  if (s.follower.kind != FollowerKind::Network) {
    const std::pair<const char*, std::size_t> arrays[] = {
        {"nodes", n.nodes.size()}, {"elements", n.elements.size()}, {"contacts", n.contacts.size()}};
    for (const auto& [name, count] : arrays)
      if (count > 0)
        net_fail(name, "(" + std::to_string(count) + (count == 1 ? " entry)" : " entries)"),
                 std::string("[[") + name + "]] needs follower.kind = \"network\" (follower.kind is \"" +
                     to_string(s.follower.kind) + "\")");
    return;
  }
  if (n.nodes.empty()) net_fail("follower.kind", "\"network\"", "needs at least one [[nodes]] entry");
  if (n.contacts.empty()) net_fail("follower.kind", "\"network\"", "needs at least one [[contacts]] entry");

  // ---- nodes
  std::map<std::string, std::size_t> node_index;
  for (std::size_t i = 0; i < n.nodes.size(); ++i) {
    const NodeSpec& nd = n.nodes[i];
    const std::string p = elem("nodes", i);
    const std::string who = "node '" + nd.name + "'";
    if (nd.name.empty()) net_fail(p + ".name", "\"\"", "must not be empty (node names are required)");
    if (nd.name == "ground")
      net_fail(p + ".name", quote(nd.name), "is reserved (\"ground\" is the fixed end of a spring, dashpot or bar)");
    if (!valid_node_name(nd.name))
      net_fail(p + ".name", quote(nd.name), "must contain only letters, digits, '_' and '-'");
    const auto [it, fresh] = node_index.emplace(nd.name, i);
    if (!fresh)
      net_fail(p + ".name", quote(nd.name), "must be unique (" + elem("nodes", it->second) + " has the same name)");
    net_ge(p + ".mass", nd.mass, 0.0, who);
    net_finite(p + ".initial_displacement", nd.initial_displacement, who);
    net_finite(p + ".initial_velocity", nd.initial_velocity, who);
  }
  std::vector<bool> used(n.nodes.size(), false);
  auto node_ref = [&](const std::string& key, const std::string& name, bool ground_ok, const std::string& who,
                      const char* ground_rule) {
    if (name == "ground") {
      if (!ground_ok) net_fail(key, quote(name), std::string(ground_rule) + " (" + who + ")");
      return;
    }
    auto it = node_index.find(name);
    if (it == node_index.end()) net_fail(key, quote(name), "names no node of [[nodes]] (" + who + ")");
    used[it->second] = true;
  };

  // ---- elements
  std::map<std::string, std::size_t> element_index;
  for (std::size_t i = 0; i < n.elements.size(); ++i) {
    const ElementSpec& e = n.elements[i];
    const std::string p = elem("elements", i);
    const std::string who = element_label(e, i);
    if (!e.name.empty()) {
      const auto [it, fresh] = element_index.emplace(e.name, i);
      if (!fresh)
        net_fail(p + ".name", quote(e.name),
                 "must be unique (" + elem("elements", it->second) + " has the same name; --set elements." + e.name +
                     ".KEY would not know which one)");
    }
    const bool lever = e.kind == ElementKind::Lever;
    if (e.nodes.size() != 2 && !(lever && e.nodes.size() == 3))
      net_fail(p + ".nodes", quoted_names(e.nodes),
               std::string(lever ? "must name 2 nodes [input, output] or 3 [input, output, pivot]"
                                 : "must name exactly 2 nodes") +
                   ", has " + std::to_string(e.nodes.size()) + " (" + who + ")");
    for (std::size_t k = 0; k < e.nodes.size(); ++k)
      node_ref(elem(p + ".nodes", k), e.nodes[k], !lever, who, "\"ground\" cannot be a node of a lever");
    for (std::size_t k = 1; k < e.nodes.size(); ++k)
      for (std::size_t l = 0; l < k; ++l)
        if (e.nodes[k] == e.nodes[l])
          net_fail(p + ".nodes", quoted_names(e.nodes),
                   std::string(e.nodes.size() == 3 ? "must name three" : "must name two") + " different nodes (" +
                       who + ")");
    // Each key's own rule (the kind's table, src/scene/element_kinds.cpp), then the rules
    // between its keys.
    for (const ElementField& f : element_kind(e.kind).fields) {
      const std::string key = p + "." + f.key;
      if (f.type == ElementField::Type::Int) {
        const int v = e.*f.integer;
        if (f.rule == ElementField::Rule::IntRange && (v < f.imin || v > f.imax))
          net_fail(key, std::to_string(v), range_rule(f.imin, f.imax) + " (" + who + ")");
        continue;
      }
      if (f.type != ElementField::Type::Real) continue;
      const double v = e.*f.real;
      switch (f.rule) {
        case ElementField::Rule::Finite: net_finite(key, v, who); break;
        case ElementField::Rule::Ge: net_ge(key, v, f.lo, who); break;
        case ElementField::Rule::Gt: net_gt(key, v, f.lo, who); break;
        case ElementField::Rule::IntRange:
        case ElementField::Rule::Custom: break;
      }
    }
    switch (e.kind) {
      case ElementKind::Spring:
        if (e.mass > 0 && e.masses < 1)
          net_fail(p + ".masses", std::to_string(e.masses),
                   "must be >= 1 for a spring with mass (" + p + ".mass = " + fmt_num(e.mass) + ") (" + who + ")");
        if (e.masses >= 1 && !(e.mass > 0))
          net_fail(p + ".masses", std::to_string(e.masses), "needs " + p + ".mass > 0 (" + who + ")");
        coil_clash(e, p, who);
        break;
      case ElementKind::Dashpot:
      case ElementKind::Bar:
      case ElementKind::GuideFriction: break;
      case ElementKind::Lever:
        if (e.nodes.size() == 2) {
          // A two-node lever's output moves ratio times its input, the same way: a ratio
          // <= 0 would turn the train's motion round (the valve pushed away from its lift),
          // which no rocker or finger does.
          if (!(std::isfinite(e.ratio) && e.ratio > 0.0))
            net_fail(p + ".ratio", fmt_num(e.ratio),
                     "must be finite and > 0 (the output moves ratio times the input, in the same direction) (" +
                         who + ")");
        } else {
          // With a pivot node the ratio is the signed arm ratio (negative: the pivot lies
          // between input and output).
          if (!(std::isfinite(e.ratio) && e.ratio != 0.0))
            net_fail(p + ".ratio", fmt_num(e.ratio), "must be finite and != 0 on a lever with a pivot node (" + who + ")");
          if (e.ratio == 1.0)
            net_fail(p + ".ratio", fmt_num(e.ratio),
                     "must be != 1 on a lever with a pivot node (ratio 1 ties the output to the input alone; "
                     "drop the pivot) (" + who + ")");
        }
        break;
      case ElementKind::ProgressiveSpring: {
        const std::vector<double>& x = e.deflections;
        const std::vector<double>& y = e.forces;
        if (x.size() < 2)
          net_fail(p + ".deflections", std::to_string(x.size()) + " points",
                   "must have at least 2 points (" + who + ")");
        if (y.size() != x.size())
          net_fail(p + ".forces", std::to_string(y.size()) + " points",
                   "must have as many points as " + p + ".deflections (" + std::to_string(x.size()) + ") (" +
                       who + ")");
        for (std::size_t k = 0; k < x.size(); ++k) {
          net_finite(elem(p + ".deflections", k), x[k], who);
          net_finite(elem(p + ".forces", k), y[k], who);
        }
        for (std::size_t k = 1; k < x.size(); ++k) {
          if (!(x[k] > x[k - 1]))
            net_fail(elem(p + ".deflections", k), fmt_num(x[k]),
                     "must be strictly increasing (> " + elem(p + ".deflections", k - 1) + " = " +
                         fmt_num(x[k - 1]) + ") (" + who + ")");
          if (!(y[k] >= y[k - 1]))
            net_fail(elem(p + ".forces", k), fmt_num(y[k]),
                     "must be non-decreasing, a monotone force-deflection curve (>= " +
                         elem(p + ".forces", k - 1) + " = " + fmt_num(y[k - 1]) + ") (" + who + ")");
        }
        if (!(y.back() > y.front()))
          net_fail(p + ".forces", fmt_num(y.back()),
                   "must rise somewhere: the last force must be > the first (" + who + ")");
        break;
      }
      case ElementKind::GasLoad: gas_load(e, p, who); break;
      case ElementKind::HydraulicLashAdjuster: {
        if (!(e.air_fraction < 1.0))
          net_fail(p + ".air_fraction", fmt_num(e.air_fraction), "must be < 1 (a volume fraction in [0, 1)) (" + who + ")");
        if (!(e.check_discharge_coefficient <= 1.0))
          net_fail(p + ".check_discharge_coefficient", fmt_num(e.check_discharge_coefficient),
                   "must be <= 1 (" + who + ")");
        if (!(e.initial_pressure > -e.air_reference_pressure))
          net_fail(p + ".initial_pressure", fmt_num(e.initial_pressure),
                   "must be > -air_reference_pressure (" + fmt_num(-e.air_reference_pressure) +
                       "): a gauge pressure above vacuum (" + who + ")");
        // The check ball: its keys need a ball (check_ball_mass > 0), a ball needs its spring,
        // its seat bore and its seat's stiffness.
        const std::pair<const char*, double> ball_keys[] = {{"check_ball_stiffness", e.check_ball_stiffness},
                                                            {"check_seat_diameter", e.check_seat_diameter},
                                                            {"check_seat_stiffness", e.check_seat_stiffness},
                                                            {"check_ball_damping", e.check_ball_damping}};
        for (const auto& [key, v] : ball_keys) {
          const bool needed = std::string(key) != "check_ball_damping";
          if (e.check_ball_mass > 0.0 && needed && !(v > 0.0))
            net_fail(p + "." + key, fmt_num(v),
                     "must be > 0 with a check ball (" + p + ".check_ball_mass = " + fmt_num(e.check_ball_mass) +
                         ") (" + who + ")");
          if (!(e.check_ball_mass > 0.0) && v != 0.0)
            net_fail(p + "." + key, fmt_num(v),
                     "needs a check ball: " + p + ".check_ball_mass > 0 (it is 0: the check valve is the orifice "
                     "law, which reads no check ball key) (" + who + ")");
        }
        break;
      }
    }
  }

  // ---- contacts
  std::map<std::string, std::size_t> contact_index;
  for (std::size_t i = 0; i < n.contacts.size(); ++i) {
    const ContactPointSpec& c = n.contacts[i];
    const std::string p = elem("contacts", i);
    const std::string who = contact_label(c, i);
    if (c.name.empty()) net_fail(p + ".name", "\"\"", "must not be empty (contact names are required)");
    const auto [it, fresh] = contact_index.emplace(c.name, i);
    if (!fresh)
      net_fail(p + ".name", quote(c.name), "must be unique (" + elem("contacts", it->second) + " has the same name)");
    const std::size_t want = c.kind == ContactPointKind::Lash ? 2 : 1;
    if (c.nodes.size() != want)
      net_fail(p + ".nodes", quoted_names(c.nodes),
               "must name exactly " + std::to_string(want) + (want == 1 ? " node" : " nodes") + ", has " +
                   std::to_string(c.nodes.size()) + " (" + who + ")");
    for (std::size_t k = 0; k < want; ++k)
      node_ref(elem(p + ".nodes", k), c.nodes[k], false, who, "\"ground\" cannot be a node of a contact");
    if (want == 2 && c.nodes[0] == c.nodes[1])
      net_fail(p + ".nodes", quoted_names(c.nodes), "must name two different nodes (" + who + ")");
    // A cam contact acts on the scene's cam ([cam], always present).
    net_ge(p + ".clearance", c.clearance, 0.0, who);
    if (c.restitution) {
      net_finite(p + ".restitution", *c.restitution, who);
      if (!(*c.restitution >= 0.0 && *c.restitution <= 1.0))
        net_fail(p + ".restitution", fmt_num(*c.restitution), "must be >= 0 and <= 1 (" + who + ")");
    }
    if (c.penalty_stiffness) net_gt(p + ".penalty_stiffness", *c.penalty_stiffness, 0.0, who);
    if (c.penalty_damping) net_ge(p + ".penalty_damping", *c.penalty_damping, 0.0, who);
  }

  // ---- levers: each node the output of at most one lever, no cycles
  std::map<std::string, std::size_t> lever_of_output;  // output node -> element index
  for (std::size_t i = 0; i < n.elements.size(); ++i) {
    const ElementSpec& e = n.elements[i];
    if (e.kind != ElementKind::Lever) continue;
    const auto [it, fresh] = lever_of_output.emplace(e.nodes[1], i);
    if (!fresh)
      net_fail(elem(elem("elements", i) + ".nodes", 1), quote(e.nodes[1]),
               "is already the output of " + element_label(n.elements[it->second], it->second) + " (" +
                   elem("elements", it->second) + "); a node is the output of at most one lever (" +
                   element_label(e, i) + ")");
  }
  // A lever's output depends on its input and its pivot: no lever may depend on itself.
  // One depth-first walk over output → {input, pivot}, each node entered once: O(levers);
  // a node met again while on the walk's path closes a cycle (named at its first lever).
  {
    auto deps = [&](const std::string& node) {
      std::vector<std::string> d;
      const auto it = lever_of_output.find(node);
      if (it != lever_of_output.end()) {
        const ElementSpec& e = n.elements[it->second];
        d.push_back(e.nodes[0]);
        if (e.nodes.size() == 3) d.push_back(e.nodes[2]);
      }
      return d;
    };
    std::map<std::string, int> state;  // 1 on the current path, 2 done
    for (const auto& [out, lever] : lever_of_output) {
      (void)lever;
      if (state[out] != 0) continue;
      std::vector<std::pair<std::string, std::size_t>> path{{out, 0}};  // node, next dependency
      state[out] = 1;
      while (!path.empty()) {
        const std::string cur = path.back().first;
        const std::vector<std::string> d = deps(cur);
        if (path.back().second >= d.size()) {
          state[cur] = 2;
          path.pop_back();
          continue;
        }
        const std::string next = d[path.back().second++];
        int& st = state[next];
        if (st == 1) {  // the path from next on is a cycle: name its first lever
          std::size_t first = lever_of_output.at(next);
          for (auto q = path.rbegin(); q != path.rend() && q->first != next; ++q)
            first = std::min(first, lever_of_output.at(q->first));
          const ElementSpec& e = n.elements[first];
          net_fail(elem("elements", first) + ".nodes", quoted_names(e.nodes),
                   "levers form a cycle through node '" + e.nodes[1] + "' (" + element_label(e, first) + ")");
        }
        if (st == 0) {
          st = 1;
          path.push_back({next, 0});
        }
      }
    }
  }

  // ---- dangling nodes
  for (std::size_t i = 0; i < n.nodes.size(); ++i)
    if (!used[i])
      net_fail(elem("nodes", i) + ".name", quote(n.nodes[i].name),
               "node '" + n.nodes[i].name + "' is dangling: no element or contact uses it");

  // ---- floating subsystems: components joined by springs (k > 0 or with mass), bars and
  // levers must be held to ground by a spring with k > 0 or a bar.
  const std::size_t nn = n.nodes.size();
  std::vector<std::size_t> parent(nn);
  for (std::size_t i = 0; i < nn; ++i) parent[i] = i;
  auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<bool> anchored(nn, false);
  for (const auto& e : n.elements) {
    // a guide with Coulomb friction holds its node too (against forces below μN)
    const bool stiff = (e.kind == ElementKind::Spring && e.stiffness > 0) || e.kind == ElementKind::Bar ||
                       e.kind == ElementKind::ProgressiveSpring ||
                       (e.kind == ElementKind::GuideFriction && e.friction_coefficient * e.normal_load > 0) ||
                       e.kind == ElementKind::HydraulicLashAdjuster;
    const bool joins = stiff || e.kind == ElementKind::Lever || (e.kind == ElementKind::Spring && e.mass > 0);
    if (!joins) continue;
    const bool g0 = e.nodes[0] == "ground", g1 = e.nodes[1] == "ground";
    if (g0 || g1) {
      if (stiff) anchored[node_index.at(g0 ? e.nodes[1] : e.nodes[0])] = true;
      continue;
    }
    parent[root(node_index.at(e.nodes[0]))] = root(node_index.at(e.nodes[1]));
    if (e.nodes.size() == 3) parent[root(node_index.at(e.nodes[2]))] = root(node_index.at(e.nodes[1]));
  }
  std::vector<bool> comp_anchored(nn, false);
  for (std::size_t i = 0; i < nn; ++i)
    if (anchored[i]) comp_anchored[root(i)] = true;
  for (std::size_t i = 0; i < nn; ++i)
    if (!comp_anchored[root(i)])
      net_fail(elem("nodes", i) + ".name", quote(n.nodes[i].name),
               "node '" + n.nodes[i].name + "' floats: no spring or bar connects it to ground");

  // ---- mass: after lever elimination (a lever's output is tied to its input), every
  // remaining unknown needs positive mass from node masses, bars or springs with mass.
  // (the unknowns a node moves with: itself, or its lever's input and pivot, recursively;
  // each node handed on once, so a chain of n levers costs O(n))
  std::vector<bool> has_mass(nn, false);
  std::set<std::string> handed_on;  // nodes whose mass already reached their unknowns
  auto give_mass = [&](const std::string& node) {
    std::vector<std::string> todo{node};
    while (!todo.empty()) {
      const std::string cur = todo.back();
      todo.pop_back();
      if (!handed_on.insert(cur).second) continue;
      auto it = lever_of_output.find(cur);
      if (it == lever_of_output.end()) {
        has_mass[node_index.at(cur)] = true;
        continue;
      }
      const ElementSpec& lv = n.elements[it->second];
      todo.push_back(lv.nodes[0]);
      if (lv.nodes.size() == 3) todo.push_back(lv.nodes[2]);
    }
  };
  for (std::size_t i = 0; i < nn; ++i)
    if (n.nodes[i].mass > 0) give_mass(n.nodes[i].name);
  for (const auto& e : n.elements) {
    const bool massive = e.kind == ElementKind::Bar || (e.kind == ElementKind::Spring && e.mass > 0);
    if (!massive) continue;
    for (const auto& name : e.nodes)
      if (name != "ground") give_mass(name);
  }
  for (std::size_t i = 0; i < nn; ++i)
    if (!lever_of_output.count(n.nodes[i].name) && !has_mass[i])
      net_fail(elem("nodes", i) + ".mass", fmt_num(n.nodes[i].mass),
               "node '" + n.nodes[i].name +
                   "' has no mass (give it mass, or connect a bar or a spring with mass to it or to a node "
                   "tied to it by a lever)");
}

void Validator::coil_clash(const ElementSpec& e, const std::string& p, const std::string& who) const {
  const bool any = e.solid_length != 0.0 || e.free_length != 0.0 || !e.coil_gaps.empty() || e.coil_restitution;
  if (!any) return;
  if (!(e.solid_length > 0))
    net_fail(p + ".solid_length", fmt_num(e.solid_length),
             "must be > 0 for coil clash (free_length, coil_gaps or coil_restitution is set) (" + who + ")");
  net_gt(p + ".stiffness", e.stiffness, 0.0, who + ", a spring whose coils clash");
  net_finite(p + ".free_length", e.free_length, who);
  const double installed = e.free_length - e.preload / e.stiffness, travel = installed - e.solid_length;
  if (!(travel > 0))
    net_fail(p + ".free_length", fmt_num(e.free_length),
             "must exceed solid_length + preload/stiffness = " + fmt_num(e.solid_length + e.preload / e.stiffness) +
                 " (the installed length free_length − preload/stiffness must be above solid) (" + who + ")");
  if (e.coil_restitution) {
    net_finite(p + ".coil_restitution", *e.coil_restitution, who);
    if (!(*e.coil_restitution >= 0.0 && *e.coil_restitution <= 1.0))
      net_fail(p + ".coil_restitution", fmt_num(*e.coil_restitution), "must be >= 0 and <= 1 (" + who + ")");
  }
  if (e.coil_gaps.empty()) return;
  const std::size_t want = std::size_t(e.masses) + 1;
  if (e.coil_gaps.size() != want)
    net_fail(p + ".coil_gaps", std::to_string(e.coil_gaps.size()) + " gaps",
             "must have masses + 1 = " + std::to_string(want) + " entries, one per segment of the coil chain (" + who +
                 ")");
  double sum = 0;
  for (std::size_t k = 0; k < want; ++k) {
    net_ge(elem(p + ".coil_gaps", k), e.coil_gaps[k], 0.0, who);
    sum += e.coil_gaps[k];
  }
  if (!(std::abs(sum - travel) <= 1e-6 * travel))
    net_fail(p + ".coil_gaps", "sum " + fmt_num(sum),
             "must add up to the travel to solid free_length − preload/stiffness − solid_length = " + fmt_num(travel) +
                 " (to 1e-6 of it) (" + who + ")");
}

void Validator::gas_load(const ElementSpec& e, const std::string& p, const std::string& who) const {
  const std::vector<double>& x = e.crank_angles_deg;
  const std::vector<double>& y = e.pressures;
  if (x.empty()) net_fail(p + ".crank_angles_deg", "0 points", "must have at least 1 point (" + who + ")");
  if (y.size() != x.size())
    net_fail(p + ".pressures", std::to_string(y.size()) + " points",
             "must have as many points as " + p + ".crank_angles_deg (" + std::to_string(x.size()) + ") (" + who + ")");
  const double cycle = 360.0 * e.crank_ratio;
  for (std::size_t k = 0; k < x.size(); ++k) {
    net_finite(elem(p + ".pressures", k), y[k], who);
    net_finite(elem(p + ".crank_angles_deg", k), x[k], who);
    if (!(x[k] >= 0.0 && x[k] < cycle))
      net_fail(elem(p + ".crank_angles_deg", k), fmt_num(x[k]),
               "must be >= 0 and < 360·crank_ratio = " + fmt_num(cycle) + " (one engine cycle) (" + who + ")");
    if (k > 0 && !(x[k] > x[k - 1]))
      net_fail(elem(p + ".crank_angles_deg", k), fmt_num(x[k]),
               "must be strictly increasing (> " + elem(p + ".crank_angles_deg", k - 1) + " = " + fmt_num(x[k - 1]) +
                   ") (" + who + ")");
  }
}

}  // namespace scene_detail
}  // namespace camdyn
