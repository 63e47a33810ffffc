// camdyn — scene validation: the Validator (every key's own rule from the key table, and
// the rules between keys).
#include "camdyn/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include <toml++/toml.h>

#include "camdyn/cam.hpp"
#include "scene/detail.hpp"
#include "scene/fields.hpp"

namespace camdyn {

using namespace scene_detail;  // scene_detail.hpp, scene_fields.hpp

namespace {

class Validator {
 public:
  Validator(const Scene& s, const std::string& file, const LineMap& lines) : s_(s), file_(file), lines_(lines) {}

  int line(const std::string& key, const std::string& fallback = "") const {
    auto it = lines_.find(key);
    if (it != lines_.end()) return it->second;
    if (!fallback.empty()) {
      it = lines_.find(fallback);
      if (it != lines_.end()) return it->second;
    }
    // An array element not recorded: use the array's line.
    auto br = key.find('[');
    if (br != std::string::npos) {
      it = lines_.find(key.substr(0, br));
      if (it != lines_.end()) return it->second;
    }
    return 0;
  }

  [[noreturn]] void fail_at(const std::string& key, const std::string& value, const std::string& rule,
                            const std::string& fallback = "") const {
    throw SceneError(file_, line(key, fallback), key, value, rule);
  }

  void finite(const std::string& key, double v) const {
    if (!std::isfinite(v)) fail_at(key, fmt_num(v), "must be a finite number");
    // Issue 25: E = 1e308 or a preload of 1e308 passed and the integrator then failed on
    // the overflowing products. No unit system needs magnitudes beyond 1e50, and products
    // of a few such quantities stay far inside double precision.
    if (std::abs(v) > kMaxMagnitude)
      fail_at(key, fmt_num(v),
              "is not a physical magnitude: must be <= " + fmt_num(kMaxMagnitude) +
                  " in absolute value (products with the scene's other quantities would overflow double precision)");
  }
  void finite(const std::string& key, const std::vector<double>& v) const {
    for (std::size_t i = 0; i < v.size(); ++i) finite(elem(key, i), v[i]);
  }
  void gt(const std::string& key, double v, double lo) const {
    finite(key, v);
    if (!(v > lo)) fail_at(key, fmt_num(v), "must be > " + fmt_num(lo));
  }
  void ge(const std::string& key, double v, double lo) const {
    finite(key, v);
    if (!(v >= lo)) fail_at(key, fmt_num(v), "must be >= " + fmt_num(lo));
  }
  void in(const std::string& key, double v, double lo, double hi) const {
    finite(key, v);
    if (!(v >= lo && v <= hi)) fail_at(key, fmt_num(v), "must be >= " + fmt_num(lo) + " and <= " + fmt_num(hi));
  }
  void int_in(const std::string& key, long long v, long long lo, long long hi) const {
    if (v < lo || v > hi) fail_at(key, std::to_string(v), range_rule(lo, hi));
  }
  static std::string elem(const std::string& key, std::size_t i) { return key + "[" + std::to_string(i) + "]"; }

  /// ≥ 4 values, strictly increasing, span < 360°.
  void angle_table(const std::string& key, const std::vector<double>& a, const std::string& context,
                   const std::string& fallback) const {
    if (a.size() < 4)
      fail_at(key, fmt_vec(a), "must have at least 4 values" + context + " (has " + std::to_string(a.size()) + ")",
              fallback);
    increasing(key, a);
    if (!(a.back() - a.front() < 360.0))
      fail_at(elem(key, a.size() - 1), fmt_num(a.back()),
              "must be < " + key + "[0] + 360 = " + fmt_num(a.front() + 360.0) + " (the table spans less than 360 deg)");
  }
  void increasing(const std::string& key, const std::vector<double>& a) const {
    for (std::size_t i = 1; i < a.size(); ++i)
      if (!(a[i] > a[i - 1]))
        fail_at(elem(key, i), fmt_num(a[i]),
                "must be > " + elem(key, i - 1) + " = " + fmt_num(a[i - 1]) + " (strictly increasing)");
  }
  void same_length(const std::string& key, const std::vector<double>& a, const std::string& ref_key,
                   const std::vector<double>& ref) const {
    if (a.size() != ref.size())
      fail_at(key, fmt_vec(a),
              "must have as many values as " + ref_key + " (" + std::to_string(ref.size()) + "), has " +
                  std::to_string(a.size()),
              ref_key);
  }

  /// Every key's own rule from the key table (fields()).
  void key_rules() const {
    Scene& s = const_cast<Scene&>(s_);  // the accessors are non-const; nothing is written
    for (const Field& f : fields()) {
      const std::string key = f.path();
      switch (f.kind) {
        case FK::Arr:
          finite(key, f.arr(s));
          break;
        case FK::Int:
          int_in(key, f.get_int(s), f.imin, f.imax);
          break;
        case FK::Real: {
          const double v = f.real(s);
          finite(key, v);
          if (f.rule == Rule::Gt && f.lo == 0.0 && v > 0.0 && v < 1.0 / kMaxMagnitude)
            fail_at(key, fmt_num(v),
                    "is not a physical magnitude: must be >= " + fmt_num(1.0 / kMaxMagnitude) +
                        " (its reciprocal would overflow double precision in the scene's products)");
          const bool ok = f.rule == Rule::Finite ? true
                          : f.rule == Rule::Gt   ? v > f.lo
                          : f.rule == Rule::Ge   ? v >= f.lo
                          : f.rule == Rule::In   ? (v >= f.lo && v <= f.hi)
                          : f.rule == Rule::GtLe ? (v > f.lo && v <= f.hi)
                                                 : (v == 0.0 || (v >= f.lo && v <= f.hi));
          if (ok) break;
          const std::string rule =
              f.rule == Rule::Gt   ? "must be > " + fmt_num(f.lo)
              : f.rule == Rule::Ge ? "must be >= " + fmt_num(f.lo)
              : f.rule == Rule::In ? "must be >= " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
              : f.rule == Rule::GtLe ? "must be > " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
                                     : std::string(f.note);
          fail_at(key, fmt_num(v), rule);
        }
        default:
          break;
      }
    }
  }

  void run() const {
    const Scene& s = s_;
    key_rules();
    // ---- cam (rules between keys)
    const CamSpec& c = s.cam;
    if (c.profile == CamProfileKind::Points) {
      angle_table("cam.angles_deg", c.angles_deg, "", "cam.profile");
      same_length("cam.radii", c.radii, "cam.angles_deg", c.angles_deg);
      for (std::size_t i = 0; i < c.radii.size(); ++i) gt(elem("cam.radii", i), c.radii[i], 0.0);
    }
    if (c.profile == CamProfileKind::Lift) {
      angle_table("cam.lift_angles_deg", c.lift_angles_deg, " for cam.profile = \"lift\"", "cam.profile");
      same_length("cam.lift", c.lift, "cam.lift_angles_deg", c.lift_angles_deg);
      for (std::size_t i = 0; i < c.lift.size(); ++i)
        if (!(c.base_radius + c.lift[i] > 0))
          fail_at(elem("cam.lift", i), fmt_num(c.lift[i]),
                  "must be > -cam.base_radius = " + fmt_num(-c.base_radius) + " (base_radius + lift > 0)");
    }
    // Motion laws, arc cams and the follower faces (issue 24): their rules live with the
    // geometry (cam.cpp, follower_geometry.cpp); reported here with the scene's file.
    if (c.profile == CamProfileKind::Table && c.lift_table.empty())
      fail_at("cam.lift_table", "\"\"", "cam.profile = \"table\" needs the lift-table CSV file", "cam.profile");
    if (c.profile == CamProfileKind::Law || c.profile == CamProfileKind::Table || c.profile == CamProfileKind::Arc || c.profile == CamProfileKind::Arcs ||
        c.follower_face != FollowerFace::Flat || c.follower_motion != FollowerMotion::Translating) {
      try {
        Cam check(c);
      } catch (const SceneError& e) {
        fail_at(e.key(), e.value(), e.rule());
      }
    }
    if (!(c.eccentricity < c.radius))
      fail_at("cam.eccentricity", fmt_num(c.eccentricity), "must be < cam.radius = " + fmt_num(c.radius));
    if (!c.speed_table_t.empty() || !c.speed_table_rev_s.empty()) {
      same_length("cam.speed_table_rev_s", c.speed_table_rev_s, "cam.speed_table_t", c.speed_table_t);
      if (c.speed_table_t.front() != 0.0)
        fail_at("cam.speed_table_t[0]", fmt_num(c.speed_table_t.front()), "must be 0 (the speed table starts at t = 0)");
      increasing("cam.speed_table_t", c.speed_table_t);
    }

    // ---- contact
    const ContactSpec& k = s.contact;
    if (!k.separation && k.model != ContactModel::Lee && k.model != ContactModel::Holonomic)
      fail_at("contact.separation", "false",
              std::string("requires contact.model \"lee\" or \"holonomic\" (contact.model is \"") + to_string(k.model) +
                  "\")",
              "contact.model");
    if (k.restitution > 0 && (k.model == ContactModel::Penalty || k.model == ContactModel::Holonomic))
      fail_at("contact.restitution", fmt_num(k.restitution),
              std::string("must be 0 with contact.model \"") + to_string(k.model) +
                  "\" (restitution needs contact.model \"lee\" or \"event\")",
              "contact.model");

    // ---- solver
    const SolverSpec& v = s.solver;
    // IDA integrates the held contact as a DAE (src/engine/ida_engine.cpp): the constraint
    // u₀ = X_C(t) holds at all times, i.e. the holonomic model only.
    if (v.integrator == Integrator::Ida && k.model != ContactModel::Holonomic)
      fail_at("solver.integrator", "\"ida\"",
              std::string("\"ida\" requires contact.model = \"holonomic\" (contact.model is \"") +
                  to_string(k.model) + "\")",
              "contact.model");

    // ---- run
    if (!(s.run.output_dt <= s.run.t_end))
      fail_at("run.output_dt", fmt_num(s.run.output_dt), "must be <= run.t_end = " + fmt_num(s.run.t_end));

    network();
  }

  // ---- network (follower.kind = "network")

  /// The line of `key`, else of the nearest enclosing key recorded ("elements[2].nodes[1]"
  /// → "elements[2].nodes" → "elements[2]" → "elements").
  int net_line(std::string key) const {
    for (;;) {
      auto it = lines_.find(key);
      if (it != lines_.end()) return it->second;
      const auto cut = key.find_last_of(".[");
      if (cut == std::string::npos || cut == 0) return 0;
      key.resize(cut);
    }
  }
  [[noreturn]] void net_fail(const std::string& key, const std::string& value, const std::string& rule) const {
    throw SceneError(file_, net_line(key), key, value, rule);
  }
  void net_finite(const std::string& key, double v, const std::string& who) const {
    if (!std::isfinite(v)) net_fail(key, fmt_num(v), "must be a finite number (" + who + ")");
  }
  void net_ge(const std::string& key, double v, double lo, const std::string& who) const {
    net_finite(key, v, who);
    if (!(v >= lo)) net_fail(key, fmt_num(v), "must be >= " + fmt_num(lo) + " (" + who + ")");
  }
  void net_gt(const std::string& key, double v, double lo, const std::string& who) const {
    net_finite(key, v, who);
    if (!(v > lo)) net_fail(key, fmt_num(v), "must be > " + fmt_num(lo) + " (" + who + ")");
  }
  static std::string quoted_names(const std::vector<std::string>& v) {
    std::vector<std::string> q;
    for (const auto& x : v) q.push_back(quote(x));
    return fmt_list(q);
  }
  static std::string element_label(const ElementSpec& e, std::size_t i) {
    return std::string(to_string(e.kind)) + (e.name.empty() ? " #" + std::to_string(i) : " '" + e.name + "'");
  }
  static std::string contact_label(const ContactPointSpec& c, std::size_t i) {
    return std::string(to_string(c.kind)) + " contact " + (c.name.empty() ? "#" + std::to_string(i) : "'" + c.name + "'");
  }
  static bool valid_node_name(const std::string& n) {
    for (char ch : n)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) return false;
    return true;
  }

  void network() const {
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
    for (std::size_t i = 0; i < n.elements.size(); ++i) {
      const ElementSpec& e = n.elements[i];
      const std::string p = elem("elements", i);
      const std::string who = element_label(e, i);
      if (e.nodes.size() != 2)
        net_fail(p + ".nodes", quoted_names(e.nodes),
                 "must name exactly 2 nodes, has " + std::to_string(e.nodes.size()) + " (" + who + ")");
      const bool lever = e.kind == ElementKind::Lever;
      for (std::size_t k = 0; k < 2; ++k)
        node_ref(elem(p + ".nodes", k), e.nodes[k], !lever, who, "\"ground\" cannot be a node of a lever");
      if (e.nodes[0] == e.nodes[1]) net_fail(p + ".nodes", quoted_names(e.nodes), "must name two different nodes (" + who + ")");
      switch (e.kind) {
        case ElementKind::Spring:
          net_ge(p + ".stiffness", e.stiffness, 0.0, who);
          net_finite(p + ".preload", e.preload, who);
          net_ge(p + ".damping", e.damping, 0.0, who);
          net_ge(p + ".mass", e.mass, 0.0, who);
          if (e.masses < 0 || e.masses > 100000)
            net_fail(p + ".masses", std::to_string(e.masses), range_rule(0, 100000) + " (" + who + ")");
          if (e.mass > 0 && e.masses < 1)
            net_fail(p + ".masses", std::to_string(e.masses),
                     "must be >= 1 for a spring with mass (" + p + ".mass = " + fmt_num(e.mass) + ") (" + who + ")");
          if (e.masses >= 1 && !(e.mass > 0))
            net_fail(p + ".masses", std::to_string(e.masses), "needs " + p + ".mass > 0 (" + who + ")");
          break;
        case ElementKind::Dashpot: net_gt(p + ".damping", e.damping, 0.0, who); break;
        case ElementKind::Bar:
          net_gt(p + ".mass", e.mass, 0.0, who);
          net_gt(p + ".youngs_modulus", e.youngs_modulus, 0.0, who);
          net_gt(p + ".area", e.area, 0.0, who);
          net_gt(p + ".length", e.length, 0.0, who);
          if (e.elements < 1 || e.elements > 100000)
            net_fail(p + ".elements", std::to_string(e.elements), range_rule(1, 100000) + " (" + who + ")");
          net_ge(p + ".rayleigh_alpha", e.rayleigh_alpha, 0.0, who);
          net_ge(p + ".rayleigh_beta", e.rayleigh_beta, 0.0, who);
          break;
        case ElementKind::Lever:
          if (!(std::isfinite(e.ratio) && e.ratio != 0.0))
            net_fail(p + ".ratio", fmt_num(e.ratio), "must be finite and != 0 (" + who + ")");
          break;
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
    for (std::size_t i = 0; i < n.elements.size(); ++i) {
      const ElementSpec& e = n.elements[i];
      if (e.kind != ElementKind::Lever) continue;
      std::string cur = e.nodes[0];
      for (std::size_t steps = 0; steps <= lever_of_output.size(); ++steps) {
        auto it = lever_of_output.find(cur);
        if (it == lever_of_output.end()) break;
        if (it->second == i)
          net_fail(elem("elements", i) + ".nodes", quoted_names(e.nodes),
                   "levers form a cycle through node '" + e.nodes[1] + "' (" + element_label(e, i) + ")");
        cur = n.elements[it->second].nodes[0];
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
      const bool stiff = (e.kind == ElementKind::Spring && e.stiffness > 0) || e.kind == ElementKind::Bar;
      const bool joins = stiff || e.kind == ElementKind::Lever || (e.kind == ElementKind::Spring && e.mass > 0);
      if (!joins) continue;
      const bool g0 = e.nodes[0] == "ground", g1 = e.nodes[1] == "ground";
      if (g0 || g1) {
        if (stiff) anchored[node_index.at(g0 ? e.nodes[1] : e.nodes[0])] = true;
        continue;
      }
      parent[root(node_index.at(e.nodes[0]))] = root(node_index.at(e.nodes[1]));
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
    auto unknown_of = [&](std::string name) {
      for (std::size_t steps = 0; steps <= lever_of_output.size(); ++steps) {
        auto it = lever_of_output.find(name);
        if (it == lever_of_output.end()) break;
        name = n.elements[it->second].nodes[0];
      }
      return node_index.at(name);
    };
    std::vector<bool> has_mass(nn, false);
    for (std::size_t i = 0; i < nn; ++i)
      if (n.nodes[i].mass > 0) has_mass[unknown_of(n.nodes[i].name)] = true;
    for (const auto& e : n.elements) {
      const bool massive = e.kind == ElementKind::Bar || (e.kind == ElementKind::Spring && e.mass > 0);
      if (!massive) continue;
      for (const auto& name : e.nodes)
        if (name != "ground") has_mass[unknown_of(name)] = true;
    }
    for (std::size_t i = 0; i < nn; ++i)
      if (unknown_of(n.nodes[i].name) == i && !has_mass[i])
        net_fail(elem("nodes", i) + ".mass", fmt_num(n.nodes[i].mass),
                 "node '" + n.nodes[i].name +
                     "' has no mass (give it mass, or connect a bar or a spring with mass to it or to a node "
                     "tied to it by a lever)");
  }

 private:
  const Scene& s_;
  const std::string& file_;
  const LineMap& lines_;
};

}  // namespace

namespace scene_detail {

void validate_impl(const Scene& s, const std::string& file, const LineMap& lines) {
  Validator(s, file, lines).run();
}

}  // namespace scene_detail

void validate(const Scene& scene) { validate_impl(scene, scene.source, LineMap{}); }

}  // namespace camdyn
