// camdyn — the network arrays of a scene ([[nodes]], [[elements]], [[contacts]],
// follower.kind = "network"): their keys by entry type, parsing them from TOML, listing them
// for the writers, and network keys addressed by name or index on the command line
// ("contacts.seat.restitution", "elements[1].preload"; issue 26).
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "scene/detail.hpp"
#include "scene/element_kinds.hpp"

namespace camdyn {

namespace scene_detail {

namespace {

// ---------------------------------------------------------------- network arrays

// [[nodes]], [[elements]], [[contacts]] (follower.kind = "network"): arrays of tables whose
// allowed keys depend on the entry's type. Keys of entry i are named "ARRAY[i].KEY" (0-based).

const char* const kNetworkArrays[] = {"nodes", "elements", "contacts"};

}  // namespace

bool is_network_array(std::string_view s) {
  for (const char* a : kNetworkArrays)
    if (s == a) return true;
  return false;
}

// The allowed keys of each network entry type (also read by the scene-key reference).
const std::vector<std::string>& node_keys() {
  static const std::vector<std::string> k{"name", "mass", "initial_displacement", "initial_velocity"};
  return k;
}

/// Every key an element may have (of some type): name, type, nodes, then the kinds' keys in
/// first-appearance order over the kinds (src/scene/element_kinds.cpp).
const std::vector<std::string>& all_element_keys() {
  static const std::vector<std::string> k = [] {
    std::vector<std::string> v{"name", "type", "nodes"};
    for (const ElementKindInfo& kind : element_kinds())
      for (const ElementField& f : kind.fields)
        if (!contains(v, f.key)) v.emplace_back(f.key);
    return v;
  }();
  return k;
}

std::vector<std::string> element_keys(ElementKind kind) {
  std::vector<std::string> k{"name", "type", "nodes"};
  for (const ElementField& f : element_kind(kind).fields) k.emplace_back(f.key);
  return k;
}

const std::vector<std::string>& all_contact_keys() {
  static const std::vector<std::string> k{"name",        "type",        "nodes",           "clearance",
                                          "side",        "restitution", "penalty_stiffness", "penalty_damping"};
  return k;
}

std::vector<std::string> contact_keys(ContactPointKind kind) {
  std::vector<std::string> k{"name", "type", "nodes", "clearance"};
  if (kind == ContactPointKind::Stop) k.emplace_back("side");
  k.insert(k.end(), {"restitution", "penalty_stiffness", "penalty_damping"});
  return k;
}

bool contains(const std::vector<std::string>& v, std::string_view s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

namespace {

std::string allowed_in_array(std::string_view array) {
  if (array == "nodes") return "allowed keys in [[nodes]]: " + join(node_keys(), ", ");
  if (array == "elements") return "allowed keys in [[elements]]: " + join(all_element_keys(), ", ") + " (by type)";
  return "allowed keys in [[contacts]]: " + join(all_contact_keys(), ", ") + " (by type)";
}

/// Builds SceneEntry lists for the writers (for_each_network_entry).
struct EntryList {
  std::string table;
  std::vector<SceneEntry> v;
  SceneEntry& add(const char* key, SceneEntry::Kind kind) {
    SceneEntry e;
    e.table = table;
    e.key = key;
    e.kind = kind;
    v.push_back(std::move(e));
    return v.back();
  }
  void real(const char* key, double x) { add(key, SceneEntry::Kind::Real).real = x; }
  void integer(const char* key, long long x) { add(key, SceneEntry::Kind::Int).integer = x; }
  void str(const char* key, const std::string& x) { add(key, SceneEntry::Kind::Str).text = x; }
  void names(const char* key, const std::vector<std::string>& x) { add(key, SceneEntry::Kind::Names).names = x; }
  void reals(const char* key, const std::vector<double>& x) { add(key, SceneEntry::Kind::Array).array = x; }
};

std::vector<SceneEntry> node_entries(const NodeSpec& n) {
  EntryList l{"nodes", {}};
  l.str("name", n.name);
  l.real("mass", n.mass);
  l.real("initial_displacement", n.initial_displacement);
  l.real("initial_velocity", n.initial_velocity);
  return std::move(l.v);
}

std::vector<SceneEntry> element_entries(const ElementSpec& e) {
  EntryList l{"elements", {}};
  if (!e.name.empty()) l.str("name", e.name);
  l.str("type", to_string(e.kind));
  l.names("nodes", e.nodes);
  for (const ElementField& f : element_kind(e.kind).fields) {
    if (f.written && !f.written(e)) continue;
    switch (f.type) {
      case ElementField::Type::Real: l.real(f.key, e.*f.real); break;
      case ElementField::Type::Int: l.integer(f.key, e.*f.integer); break;
      case ElementField::Type::Reals: l.reals(f.key, e.*f.reals); break;
      case ElementField::Type::OptionalReal:
        if (e.*f.optional) l.real(f.key, *(e.*f.optional));
        break;
      case ElementField::Type::MassMatrix: l.str(f.key, to_string(e.*f.mass_matrix)); break;
    }
  }
  return std::move(l.v);
}

std::vector<SceneEntry> contact_entries(const ContactPointSpec& c) {
  EntryList l{"contacts", {}};
  l.str("name", c.name);
  l.str("type", to_string(c.kind));
  l.names("nodes", c.nodes);
  l.real("clearance", c.clearance);
  if (c.kind == ContactPointKind::Stop) l.str("side", to_string(c.side));
  if (c.restitution) l.real("restitution", *c.restitution);
  if (c.penalty_stiffness) l.real("penalty_stiffness", *c.penalty_stiffness);
  if (c.penalty_damping) l.real("penalty_damping", *c.penalty_damping);
  return std::move(l.v);
}

/// Reads the values of one network entry (strict types, as read_field).
struct NetReader {
  const std::string& file;
  bool use_lines;
  LineMap& lines;

  int line(const toml::node& n) const { return use_lines ? line_of(n) : 0; }
  [[noreturn]] void fail_missing(const toml::table& t, const std::string& prefix, const std::string& rule) const {
    fail(file, line(t), prefix, "{...}", rule);
  }
  double real(const toml::node& n, const std::string& key) const {
    if (auto i = n.as_integer()) return static_cast<double>(i->get());
    if (auto d = n.as_floating_point()) return d->get();
    fail(file, line(n), key, fmt_node(n), "must be a number");
  }
  int integer(const toml::node& n, const std::string& key, long long lo, long long hi) const {
    const long long v = toml_integer(n, file, line(n), key);
    if (v < lo || v > hi) fail(file, line(n), key, fmt_node(n), range_rule(lo, hi));
    return static_cast<int>(v);
  }
  std::vector<double> reals(const toml::node& n, const std::string& key) {
    auto a = n.as_array();
    if (!a) fail(file, line(n), key, fmt_node(n), "must be an array of numbers");
    std::vector<double> v;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string ek = key + "[" + std::to_string(i) + "]";
      lines[ek] = line(*a->get(i));
      v.push_back(real(*a->get(i), ek));
    }
    return v;
  }
  std::string str(const toml::node& n, const std::string& key) const {
    if (auto s = n.as_string()) return s->get();
    fail(file, line(n), key, fmt_node(n), "must be a string");
  }
  std::vector<std::string> names(const toml::node& n, const std::string& key) {
    auto a = n.as_array();
    if (!a) fail(file, line(n), key, fmt_node(n), "must be an array of node names");
    std::vector<std::string> v;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::node& e = *a->get(i);
      const std::string ek = key + "[" + std::to_string(i) + "]";
      lines[ek] = line(e);
      auto s = e.as_string();
      if (!s) fail(file, line(e), ek, fmt_node(e), "must be a string (a node name)");
      v.push_back(s->get());
    }
    return v;
  }
  /// One key of an element, by its descriptor.
  void element_value(const ElementField& f, const toml::node& n, const std::string& key, ElementSpec& e) {
    switch (f.type) {
      case ElementField::Type::Real: e.*f.real = real(n, key); break;
      case ElementField::Type::Int: e.*f.integer = integer(n, key, f.imin, f.imax); break;
      case ElementField::Type::Reals: e.*f.reals = reals(n, key); break;
      case ElementField::Type::OptionalReal: e.*f.optional = real(n, key); break;
      case ElementField::Type::MassMatrix: e.*f.mass_matrix = enumeration(n, key, kBarMassNames); break;
    }
  }
  template <class E, std::size_t N>
  E enumeration(const toml::node& n, const std::string& key, const EnumName<E> (&names)[N]) const {
    E v{};
    auto s = n.as_string();
    if (!s || !enum_parse(names, s->get(), &v)) fail(file, line(n), key, fmt_node(n), one_of(enum_names(names)));
    return v;
  }
};

/// The value of the key 'type' of entry `prefix` (an element or contact), which decides the
/// other keys allowed; required.
template <class E, std::size_t N>
E entry_type(const toml::table& t, const std::string& prefix, const EnumName<E> (&names)[N], NetReader& r) {
  const toml::node* n = t.get("type");
  if (!n) {
    std::vector<std::string> q;
    for (const auto& a : enum_names(names)) q.push_back(quote(a));
    r.fail_missing(t, prefix, "must have a key 'type' (" + join(q, " | ") + ")");
  }
  r.lines[prefix + ".type"] = r.line(*n);
  return r.enumeration(*n, prefix + ".type", names);
}

/// The value of the key 'type' of element `prefix`, which decides the other keys allowed;
/// required. The kinds' names are those of element_kinds().
ElementKind element_type(const toml::table& t, const std::string& prefix, NetReader& r) {
  std::vector<std::string> names, quoted;
  for (const ElementKindInfo& k : element_kinds()) {
    names.emplace_back(k.name);
    quoted.push_back(quote(k.name));
  }
  const toml::node* n = t.get("type");
  if (!n) r.fail_missing(t, prefix, "must have a key 'type' (" + join(quoted, " | ") + ")");
  r.lines[prefix + ".type"] = r.line(*n);
  ElementKind kind{};
  auto s = n->as_string();
  if (!s || !parse_enum(s->get(), &kind)) fail(r.file, r.line(*n), prefix + ".type", fmt_node(*n), one_of(names));
  return kind;
}

}  // namespace

void read_network_array(const std::string& array, const toml::node& node, Scene& s, const std::string& file,
                        bool use_lines, LineMap& lines) {
  NetReader r{file, use_lines, lines};
  const int line = r.line(node);
  lines[array] = line;
  const toml::array* a = node.as_array();
  if (!a || (!a->empty() && !a->is_array_of_tables()))
    fail(file, line, array, fmt_node(node),
         "must be an array of tables ([[" + array + "]]); " + allowed_in_array(array));
  // A key an entry of this type does not take: name the type's keys (and say whether the
  // key belongs to another type).
  auto check_key = [&](const std::string& k, const toml::node& v, const std::string& key, const std::string& what,
                       const std::vector<std::string>& allowed, const std::vector<std::string>& all) {
    if (contains(allowed, k)) return;
    fail(file, r.line(v), key, fmt_node(v),
         (contains(all, k) ? "not a key of a" + what + "; " : std::string("unknown key; ")) +
             "allowed keys of a" + what + ": " + join(allowed, ", "));
  };
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table& t = *a->get(i)->as_table();
    const std::string prefix = array + "[" + std::to_string(i) + "]";
    lines[prefix] = r.line(t);
    if (array == "nodes") {
      NodeSpec n;
      for (const auto& [k, v] : sorted_entries(t)) {
        const std::string key = prefix + "." + k;
        lines[key] = r.line(*v);
        if (k == "name") n.name = r.str(*v, key);
        else if (k == "mass") n.mass = r.real(*v, key);
        else if (k == "initial_displacement") n.initial_displacement = r.real(*v, key);
        else if (k == "initial_velocity") n.initial_velocity = r.real(*v, key);
        else
          fail(file, r.line(*v), key, fmt_node(*v),
               std::string(v->is_table() ? "unknown table; " : "unknown key; ") + allowed_in_array(array));
      }
      s.network.nodes.push_back(std::move(n));
    } else if (array == "elements") {
      ElementSpec e;
      e.kind = element_type(t, prefix, r);
      const std::vector<std::string> allowed = element_keys(e.kind);
      for (const auto& [k, v] : sorted_entries(t)) {
        const std::string key = prefix + "." + k;
        lines[key] = r.line(*v);
        check_key(k, *v, key, std::string(" ") + to_string(e.kind) + " element", allowed, all_element_keys());
        if (k == "name") e.name = r.str(*v, key);
        else if (k == "nodes") e.nodes = r.names(*v, key);
        else if (const ElementField* f = element_field(e.kind, k)) r.element_value(*f, *v, key, e);
      }
      s.network.elements.push_back(std::move(e));
    } else {
      ContactPointSpec c;
      c.kind = entry_type(t, prefix, kContactPointNames, r);
      const std::vector<std::string> allowed = contact_keys(c.kind);
      for (const auto& [k, v] : sorted_entries(t)) {
        const std::string key = prefix + "." + k;
        lines[key] = r.line(*v);
        check_key(k, *v, key, std::string(" ") + to_string(c.kind) + " contact", allowed, all_contact_keys());
        if (k == "name") c.name = r.str(*v, key);
        else if (k == "nodes") c.nodes = r.names(*v, key);
        else if (k == "clearance") c.clearance = r.real(*v, key);
        else if (k == "side") c.side = r.enumeration(*v, key, kStopSideNames);
        else if (k == "restitution") c.restitution = r.real(*v, key);
        else if (k == "penalty_stiffness") c.penalty_stiffness = r.real(*v, key);
        else if (k == "penalty_damping") c.penalty_damping = r.real(*v, key);
      }
      s.network.contacts.push_back(std::move(c));
    }
  }
}

// ---------------------------------------------------------------- network keys by name

namespace {

/// How the entries of `array` are called in messages: "cam, seat" (an unnamed entry as
/// "[INDEX]").
std::string entry_names(const Scene& s, const std::string& array) {
  const NetworkSpec& n = s.network;
  std::vector<std::string> v;
  auto add = [&](const std::string& name, std::size_t i) {
    v.push_back(name.empty() ? "[" + std::to_string(i) + "]" : name);
  };
  if (array == "nodes")
    for (std::size_t i = 0; i < n.nodes.size(); ++i) add(n.nodes[i].name, i);
  else if (array == "elements")
    for (std::size_t i = 0; i < n.elements.size(); ++i) add(n.elements[i].name, i);
  else
    for (std::size_t i = 0; i < n.contacts.size(); ++i) add(n.contacts[i].name, i);
  return join(v, ", ");
}

std::size_t entry_count(const Scene& s, const std::string& array) {
  const NetworkSpec& n = s.network;
  return array == "nodes" ? n.nodes.size() : array == "elements" ? n.elements.size() : n.contacts.size();
}

const std::string& entry_name(const Scene& s, const std::string& array, std::size_t i) {
  const NetworkSpec& n = s.network;
  return array == "nodes" ? n.nodes[i].name : array == "elements" ? n.elements[i].name : n.contacts[i].name;
}

SceneEntry::Kind network_key_kind(const std::string& array, const std::string& key, const Scene& scene,
                                  std::size_t index) {
  if (key == "nodes") return SceneEntry::Kind::Names;
  if (key == "name" || key == "type" || key == "side") return SceneEntry::Kind::Str;
  if (array == "elements")
    if (const ElementField* f = element_field(scene.network.elements[index].kind, key)) {
      switch (f->type) {
        case ElementField::Type::Int: return SceneEntry::Kind::Int;
        case ElementField::Type::Reals: return SceneEntry::Kind::Array;
        case ElementField::Type::MassMatrix: return SceneEntry::Kind::Str;
        case ElementField::Type::Real:
        case ElementField::Type::OptionalReal: break;
      }
    }
  return SceneEntry::Kind::Real;
}

bool all_digits(const std::string& t) {
  return !t.empty() && t.size() < 10 && std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::string insert_network_override(toml::table& root, const Scene& scene, const std::string& key,
                                    const toml::node& value, const std::string& file) {
  const NetworkKey k = resolve_network_key(scene, key, file, fmt_node(value));
  toml::array* a = root.get_as<toml::array>(k.array);
  toml::table* t = a && k.index < a->size() ? a->get(k.index)->as_table() : nullptr;
  if (!t) fail(file, 0, key, fmt_node(value), "internal error: the scene's table has no " + k.canonical());
  value.visit([&](const auto& v) { t->insert_or_assign(k.key, v); });
  return k.canonical();
}

}  // namespace scene_detail

std::string NetworkKey::canonical() const { return array + "[" + std::to_string(index) + "]." + key; }

bool is_network_key(std::string_view key) {
  for (std::string_view a : {"nodes", "elements", "contacts"})
    if (key.size() > a.size() && key.substr(0, a.size()) == a && (key[a.size()] == '.' || key[a.size()] == '['))
      return true;
  return false;
}

NetworkKey resolve_network_key(const Scene& scene, const std::string& key, const std::string& file,
                               const std::string& value) {
  using namespace scene_detail;
  NetworkKey r;
  const std::size_t cut = key.find_first_of(".[");
  r.array = key.substr(0, cut);
  const std::string form = "expected " + r.array + ".NAME.KEY or " + r.array + "[INDEX].KEY (e.g. " +
                           (r.array == "nodes"      ? "nodes.valve.mass"
                            : r.array == "elements" ? "elements.valve_spring.preload"
                                                    : "contacts.seat.restitution") +
                           ")";
  const std::size_t count = entry_count(scene, r.array);
  const std::string there = count == 0 ? "the scene has no [[" + r.array + "]] entries"
                                       : "[[" + r.array + "]] has " + std::to_string(count) +
                                             (count == 1 ? " entry: " : " entries: ") + entry_names(scene, r.array);
  if (key[cut] == '[') {
    const std::size_t close = key.find(']', cut);
    if (close == std::string::npos || close + 1 >= key.size() || key[close + 1] != '.' || close + 2 >= key.size())
      fail(file, 0, key, value, form);
    const std::string idx = key.substr(cut + 1, close - cut - 1);
    if (!all_digits(idx)) fail(file, 0, key, value, form);
    r.index = static_cast<std::size_t>(std::stoul(idx));
    r.key = key.substr(close + 2);
    if (r.index >= count) fail(file, 0, key, value, "index " + idx + " out of range; " + there);
  } else {
    const std::size_t last = key.rfind('.');
    if (last == cut || last + 1 >= key.size()) fail(file, 0, key, value, form);
    const std::string name = key.substr(cut + 1, last - cut - 1);
    r.key = key.substr(last + 1);
    std::size_t i = 0;
    while (i < count && entry_name(scene, r.array, i) != name) ++i;
    if (name.empty() || i == count)
      fail(file, 0, key, value, "no [[" + r.array + "]] entry named '" + name + "'; " + there);
    r.index = i;
  }
  // The key must be one the entry's type takes (the file loader's rule and wording).
  std::vector<std::string> allowed;
  std::string what;
  bool known = false;
  if (r.array == "nodes") {
    allowed = node_keys();
    what = " node";
  } else if (r.array == "elements") {
    const ElementKind kind = scene.network.elements[r.index].kind;
    allowed = element_keys(kind);
    what = std::string(" ") + to_string(kind) + " element";
    known = contains(all_element_keys(), r.key);
  } else {
    const ContactPointKind kind = scene.network.contacts[r.index].kind;
    allowed = contact_keys(kind);
    what = std::string(" ") + to_string(kind) + " contact";
    known = contains(all_contact_keys(), r.key);
  }
  if (!contains(allowed, r.key))
    fail(file, 0, key, value,
         (known ? "not a key of a" + what + "; " : std::string("unknown key; ")) + "allowed keys of a" + what + ": " +
             join(allowed, ", "));
  r.kind = network_key_kind(r.array, r.key, scene, r.index);
  return r;
}

void for_each_network_entry(
    const Scene& scene,
    const std::function<void(const std::string& array, std::size_t index, const std::vector<SceneEntry>& keys)>& visit) {
  const NetworkSpec& n = scene.network;
  using namespace scene_detail;
  for (std::size_t i = 0; i < n.nodes.size(); ++i) visit("nodes", i, node_entries(n.nodes[i]));
  for (std::size_t i = 0; i < n.elements.size(); ++i) visit("elements", i, element_entries(n.elements[i]));
  for (std::size_t i = 0; i < n.contacts.size(); ++i) visit("contacts", i, contact_entries(n.contacts[i]));
}

}  // namespace camdyn
