// camdyn — a scene as data and as text: the key table (detail::key_table),
// for_each_scene_entry and to_toml.
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

#include "scene/key_table.hpp"
#include "scene/detail.hpp"
#include "scene/element_kinds.hpp"
#include "scene/fields.hpp"

namespace camdyn {

using namespace scene_detail;  // scene_detail.hpp, scene_fields.hpp

// ---------------------------------------------------------------- the key table as data

namespace detail {

std::string format_number(double v) { return fmt_num(v); }

std::vector<KeyTableRow> key_table() {
  std::vector<KeyTableRow> rows;
  for (const Field& f : fields()) {
    KeyTableRow r;
    r.key = f.path();
    switch (f.kind) {
      case FK::Real:
        r.type = "real";
        r.rule = f.rule == Rule::Finite ? "must be finite"
                 : f.rule == Rule::Gt   ? "must be > " + fmt_num(f.lo)
                 : f.rule == Rule::Ge   ? "must be >= " + fmt_num(f.lo)
                 : f.rule == Rule::In   ? "must be >= " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
                 : f.rule == Rule::GtLe ? "must be > " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
                                        : std::string(f.note);
        break;
      case FK::Int: r.type = "integer"; r.rule = range_rule(f.imin, f.imax); break;
      case FK::Bool: r.type = "bool"; r.rule = "must be true or false"; break;
      case FK::Str: r.type = "string"; r.rule = "must be a string"; break;
      case FK::Arr: r.type = "array of reals"; r.rule = "must be an array of finite numbers"; break;
      case FK::Enum: r.type = "enum"; r.rule = one_of(f.allowed); r.allowed = f.allowed; break;
    }
    const std::string key = r.key;
    rows.push_back(std::move(r));
    // The input-only keys in a designer's units, after the key each one replaces.
    if (key == "cam.speed_rev_s") {
      rows.push_back({"cam.speed_rpm", "real", "must be finite; needs cam.rpm_of; not with cam.speed_rev_s", {}, {}});
      rows.push_back({"cam.rpm_of", "enum", one_of({"camshaft", "engine"}), {"camshaft", "engine"}, {}});
    }
    if (key == "run.t_end")
      rows.push_back({"run.revolutions", "real", "must be > 0; not with run.t_end", {}, {}});
  }
  for (const auto& k : node_keys()) rows.push_back({"nodes." + k, k == "name" ? "string" : "real", "", {}, {}});
  auto typed = [&](const char* array, const std::vector<std::string>& all, const std::vector<std::string>& types,
                   const std::function<std::vector<std::string>(std::size_t)>& keys_of) {
    for (const auto& k : all) {
      KeyTableRow r;
      r.key = std::string(array) + "." + k;
      for (std::size_t i = 0; i < types.size(); ++i)
        if (contains(keys_of(i), k)) r.applies_to.push_back(types[i]);
      rows.push_back(std::move(r));
    }
  };
  std::vector<std::string> element_types;
  for (const ElementKindInfo& k : element_kinds()) element_types.emplace_back(k.name);
  typed("elements", all_element_keys(), element_types,
        [](std::size_t i) { return element_keys(element_kinds()[i].kind); });
  typed("contacts", all_contact_keys(), enum_names(kContactPointNames),
        [](std::size_t i) { return contact_keys(kContactPointNames[i].value); });
  return rows;
}

}  // namespace detail

void for_each_scene_entry(const Scene& scene, const std::function<void(const SceneEntry&)>& visit) {
  Scene& s = const_cast<Scene&>(scene);  // the field accessors return references; only read
  SceneEntry e;
  for (const auto& f : fields()) {
    e.table = f.table;
    e.key = f.key;
    switch (f.kind) {
      case FK::Real: e.kind = SceneEntry::Kind::Real; e.real = f.real(s); break;
      case FK::Int: e.kind = SceneEntry::Kind::Int; e.integer = f.get_int(s); break;
      case FK::Bool: e.kind = SceneEntry::Kind::Bool; e.boolean = f.boolean(s); break;
      case FK::Str: e.kind = SceneEntry::Kind::Str; e.text = f.str(s); break;
      case FK::Enum: e.kind = SceneEntry::Kind::Str; e.text = f.get_enum(s); break;
      case FK::Arr: e.kind = SceneEntry::Kind::Array; e.array = f.arr(s); break;
    }
    visit(e);
  }
}


std::string to_toml(const Scene& scene_in) {
  Scene resolved = scene_in;
  resolve_defaults(resolved);
  std::ostringstream os;
  os << "# camdyn scene (every key written; see docs/interface.md)\n";
  std::string current;
  auto write_entry = [&](const SceneEntry& e) {
    os << e.key << " = ";
    switch (e.kind) {
      case SceneEntry::Kind::Real: os << toml_float(e.real); break;
      case SceneEntry::Kind::Int: os << e.integer; break;
      case SceneEntry::Kind::Bool: os << (e.boolean ? "true" : "false"); break;
      case SceneEntry::Kind::Str: os << quote(e.text); break;
      case SceneEntry::Kind::Array: {
        os << "[";
        for (std::size_t i = 0; i < e.array.size(); ++i) os << (i ? ", " : "") << toml_float(e.array[i]);
        os << "]";
        break;
      }
      case SceneEntry::Kind::Names: {
        os << "[";
        for (std::size_t i = 0; i < e.names.size(); ++i) os << (i ? ", " : "") << quote(e.names[i]);
        os << "]";
        break;
      }
    }
    os << "\n";
  };
  for_each_scene_entry(resolved, [&](const SceneEntry& e) {
    if (!e.table.empty() && e.table != current) {
      current = e.table;
      os << "\n[" << e.table << "]\n";
    }
    write_entry(e);
  });
  // The network (follower.kind = "network"): [[nodes]], [[elements]], [[contacts]].
  for_each_network_entry(resolved, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& keys) {
    os << "\n[[" << array << "]]\n";
    for (const auto& e : keys) write_entry(e);
  });
  return os.str();
}
}  // namespace camdyn
