// camdyn — --set overrides: "dotted.key=value" assignments put into the scene as a TOML
// table and parsed and validated again (the same path as a file).
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

#include "scene/detail.hpp"
#include "scene/fields.hpp"

namespace camdyn {

using namespace scene_detail;  // scene_detail.hpp, scene_fields.hpp

namespace {

std::string trim(std::string_view s) {
  const char* ws = " \t\r\n";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(ws);
  return std::string(s.substr(b, e - b + 1));
}

// Put one "dotted.key=value" into `root` (`scene` as a TOML table); returns the key (a
// network key as "ARRAY[INDEX].KEY", the loader's spelling). Only the key's place is checked
// here; the value is checked when the table is parsed.
std::string insert_override(toml::table& root, const Scene& scene, const std::string& assignment) {
  static const std::string kFile = "--set";
  const auto eq = assignment.find('=');
  if (eq == std::string::npos)
    throw SceneError(kFile, 0, "", "", "expected KEY=VALUE (e.g. cam.speed_rev_s=3), got '" + assignment + "'");
  const std::string key = trim(std::string_view(assignment).substr(0, eq));
  const std::string text = trim(std::string_view(assignment).substr(eq + 1));
  if (key.empty())
    throw SceneError(kFile, 0, "", "", "expected KEY=VALUE (e.g. cam.speed_rev_s=3), got '" + assignment + "'");

  // The value: a TOML value if it parses as one, else the bare text as a string.
  toml::table parsed;
  const toml::node* value = nullptr;
  try {
    const std::string doc = "x = " + text;
    parsed = toml::parse(std::string_view(doc), std::string_view("--set"));
    if (parsed.size() == 1) value = parsed.get("x");
  } catch (const toml::parse_error&) {
    value = nullptr;
  }
  if (!value) {
    parsed = toml::table{};
    parsed.insert_or_assign("x", text);
    value = parsed.get("x");
  }

  // A network entry's key, by name or index: "contacts.seat.restitution", "elements[1].preload".
  if (is_network_key(key)) return insert_network_override(root, scene, key, *value, kFile);
  // The key: "title" or "TABLE.KEY".
  std::string table, leaf;
  const auto dot = key.find('.');
  if (dot == std::string::npos) {
    leaf = key;
    if (leaf != "title" && !is_table_name(leaf))
      throw SceneError(kFile, 0, key, fmt_node(*value), "unknown key; " + allowed_top());
  } else {
    table = key.substr(0, dot);
    leaf = key.substr(dot + 1);
    if (!is_table_name(table))
      throw SceneError(kFile, 0, key, fmt_node(*value), "unknown key; " + allowed_top());
  }
  if (!table.empty() && !root.get_as<toml::table>(table)) root.insert_or_assign(table, toml::table{});
  toml::table* dst = table.empty() ? &root : root.get_as<toml::table>(table);
  value->visit([&](const auto& v) { dst->insert_or_assign(leaf, v); });
  return key;
}

}  // namespace

namespace {

// Set every override in `root` (a file's table, or a scene as a table) and read and validate
// the result once. `draft` resolves network names and the automatic tol_u. A rule broken by
// a key that an override set is reported under "--set" and the key as the user wrote it.
Scene read_with_overrides(toml::table& root, const Scene& draft, const std::vector<std::string>& assignments,
                          const std::string& file, bool use_lines) {
  static const std::string kFile = "--set";
  // tol_u that is "automatic" (0, or the paper default of the current follower kind) is
  // re-derived after the overrides, so follower.kind=elastic_bar gets 1e-7, not rigid's 1e-8.
  const double tol_u = draft.contact.tol_u;
  const bool tol_u_auto = tol_u == 0.0 || tol_u == paper_tol_u(draft.follower.kind);

  bool sets_tol_u = false;
  std::map<std::string, std::string> spelled;  // "contacts[1].restitution" → "contacts.seat.restitution"
  std::vector<std::string> keys_set;
  for (const auto& a : assignments) {
    const std::string key = insert_override(root, draft, a);
    keys_set.push_back(key);
    sets_tol_u |= key == "contact.tol_u";
    const std::string given = trim(std::string_view(a).substr(0, a.find('=')));
    spelled[key] = given;
  }
  if (tol_u_auto && !sets_tol_u) {
    if (!root.get_as<toml::table>("contact")) root.insert_or_assign("contact", toml::table{});
    root.get_as<toml::table>("contact")->insert_or_assign("tol_u", 0.0);
  }
  drop_replaced_by_designer_units(root, keys_set);  // cam.speed_rpm replaces cam.speed_rev_s, …

  // One parse and one validation of the result: the order of the overrides does not matter.
  try {
    return from_table(root, file, use_lines);
  } catch (const SceneError& e) {
    const auto it = spelled.find(e.key());
    if (it == spelled.end()) throw;
    throw SceneError(kFile, 0, it->second, e.value(), e.rule());
  }
}

}  // namespace

void apply_overrides(Scene& scene, const std::vector<std::string>& assignments) {
  if (assignments.empty()) return;
  toml::table root = to_table(scene);
  Scene out = read_with_overrides(root, scene, assignments, "--set", false);
  out.source = scene.source;
  if (out.rpm_per_rev_s == 0) out.rpm_per_rev_s = scene.rpm_per_rev_s;  // the scene's speed unit
  scene = std::move(out);
}

Scene parse_scene(std::string_view toml_text, const std::string& source_name,
                  const std::vector<std::string>& overrides) {
  if (overrides.empty()) return parse_scene(toml_text, source_name);
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw SceneError(source_name, static_cast<int>(e.source().begin.line), "", "", std::string(e.description()));
  }
  return scene_detail::scene_from_table(root, source_name, overrides);
}

namespace scene_detail {
Scene scene_from_table(toml::table& root, const std::string& source_name, const std::vector<std::string>& overrides) {
  if (overrides.empty()) return from_table(root, source_name, true);
  // The file's keys and types are read first (a wrong type is the file's error); its rules
  // are checked once, after the overrides: an override may repair the file.
  const Scene draft = from_table(root, source_name, true, false);
  return read_with_overrides(root, draft, overrides, source_name, true);
}
}  // namespace scene_detail

void apply_override(Scene& scene, const std::string& assignment) {
  apply_overrides(scene, {assignment});
}

}  // namespace camdyn
