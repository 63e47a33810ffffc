// camdyn — the resolved scene as JSON (summary.json's "options"; output.hpp scene_json).
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/output.hpp"
#include "output/json_writer.hpp"

namespace camdyn {

using detail::JsonObject;

namespace {

// One scene key as a JSON member, by its kind (the tables and the network's objects).
void put_entry(JsonObject& w, const SceneEntry& e) {
  switch (e.kind) {
    case SceneEntry::Kind::Real: w.num(e.key, e.real); break;
    case SceneEntry::Kind::Int: w.integer(e.key, e.integer); break;
    case SceneEntry::Kind::Bool: w.boolean(e.key, e.boolean); break;
    case SceneEntry::Kind::Str: w.str(e.key, e.text); break;
    case SceneEntry::Kind::Array: w.nums(e.key, e.array); break;
    case SceneEntry::Kind::Names: w.strs(e.key, e.names); break;
  }
}

}  // namespace

std::string scene_json(const Scene& s, int indent) {
  std::string out;
  JsonObject o(out, indent);
  // One nested object per table, filled from the scene's own key list (the one the loader
  // and to_toml use), so no key can be missing here.
  std::string table, body;
  std::unique_ptr<JsonObject> child;
  auto close_table = [&] {
    if (!child) return;
    child->close();
    o.raw(table, body);
    child.reset();
    body.clear();
  };
  for_each_scene_entry(s, [&](const SceneEntry& e) {
    if (e.table != table) {
      close_table();
      table = e.table;
      if (!table.empty()) child = std::make_unique<JsonObject>(body, o.child_indent());
    }
    JsonObject& w = child ? *child : o;
    put_entry(w, e);
  });
  close_table();
  // The network (follower.kind = "network"): "nodes", "elements", "contacts" as arrays of
  // objects with the keys of the scene file. Absent for the other follower kinds.
  if (s.follower.kind == FollowerKind::Network || !s.network.nodes.empty() || !s.network.elements.empty() ||
      !s.network.contacts.empty()) {
    std::map<std::string, std::vector<std::string>> objects;
    for_each_network_entry(s, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& keys) {
      std::string body;
      JsonObject w(body, o.child_indent() + 2);
      for (const auto& e : keys) {
        put_entry(w, e);
      }
      w.close();
      objects[array].push_back(std::move(body));
    });
    for (const char* array : {"nodes", "elements", "contacts"}) {
      const auto& list = objects[array];
      std::string a = "[";
      for (std::size_t i = 0; i < list.size(); ++i) {
        a += i ? ",\n" : "\n";
        a.append(static_cast<std::size_t>(o.child_indent() + 2), ' ');
        a += list[i];
      }
      if (!list.empty()) {
        a += '\n';
        a.append(static_cast<std::size_t>(o.child_indent()), ' ');
      }
      a += ']';
      o.raw(array, a);
    }
  }
  o.str("source", s.source);
  o.close();
  return out;
}

}  // namespace camdyn
