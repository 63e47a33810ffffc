// The scene-key reference (camdyn scene --keys, include/camdyn/scene_keys.hpp) against the
// scene's own writers and loader: every key the writers visit is in the reference, every
// network key is documented for exactly the entry types that take it, and every documented
// default is the value the loader gives a key left out of the file.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "camdyn/scene.hpp"
#include "camdyn/scene_keys.hpp"
#include "../test_support.hpp"

namespace {

using camdyn::SceneEntry;
using camdyn::SceneKeyInfo;

std::map<std::string, SceneKeyInfo> by_key() {
  std::map<std::string, SceneKeyInfo> m;
  for (const SceneKeyInfo& k : camdyn::scene_keys()) {
    EXPECT_TRUE(m.emplace(k.key, k).second) << "key listed twice: " << k.key;
    EXPECT_FALSE(k.type.empty()) << k.key;
    EXPECT_FALSE(k.unit.empty()) << k.key;
    EXPECT_FALSE(k.rule.empty()) << k.key;
    EXPECT_FALSE(k.description.empty()) << k.key;
    EXPECT_FALSE(k.default_value.empty()) << k.key;
  }
  return m;
}

std::string path_of(const SceneEntry& e) { return e.table.empty() ? e.key : e.table + "." + e.key; }

// Scenes whose writers visit every key: the built-in default, the paper cases, every example
// file (networks included) and a network with an entry of every type and every optional key.
std::vector<camdyn::Scene> scenes_with_every_key() {
  std::vector<camdyn::Scene> v{camdyn::Scene{}, camdyn::default_scene(), camdyn::paper_case("A")};
  for (const char* f : {"ohc_bucket_tappet.toml", "ohv_pushrod_train.toml", "lift_cam.toml", "circle_cam.toml"})
    v.push_back(camdyn::load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/" + f));
  camdyn::Scene s;
  s.follower.kind = camdyn::FollowerKind::Network;
  camdyn::NodeSpec a, b;
  a.name = "a";
  b.name = "b";
  s.network.nodes = {a, b};
  for (auto k : {camdyn::ElementKind::Spring, camdyn::ElementKind::Dashpot, camdyn::ElementKind::Bar,
                 camdyn::ElementKind::Lever, camdyn::ElementKind::ProgressiveSpring,
                 camdyn::ElementKind::GuideFriction, camdyn::ElementKind::GasLoad,
                 camdyn::ElementKind::HydraulicLashAdjuster}) {
    camdyn::ElementSpec e;
    e.kind = k;
    e.name = "e";
    e.nodes = {"a", "b"};
    s.network.elements.push_back(e);
  }
  {  // a spring whose coils clash: its optional keys are written only when on
    camdyn::ElementSpec e;
    e.name = "coils";
    e.nodes = {"a", "b"};
    e.stiffness = 1e4;
    e.free_length = 0.04;
    e.solid_length = 0.02;
    e.coil_gaps = {0.02};
    e.coil_restitution = 0.2;
    s.network.elements.push_back(e);
  }
  {  // a hydraulic lash adjuster whose check valve is a ball: its keys are written only then
    camdyn::ElementSpec e;
    e.kind = camdyn::ElementKind::HydraulicLashAdjuster;
    e.name = "hla";
    e.nodes = {"a", "b"};
    e.check_ball_mass = 3.3e-5;
    s.network.elements.push_back(e);
  }
  for (auto k : {camdyn::ContactPointKind::Cam, camdyn::ContactPointKind::Lash, camdyn::ContactPointKind::Stop}) {
    camdyn::ContactPointSpec c;
    c.kind = k;
    c.name = "c";
    c.restitution = 0.5;
    c.penalty_stiffness = 1e6;
    c.penalty_damping = 1.0;
    s.network.contacts.push_back(c);
  }
  v.push_back(s);
  return v;
}

TEST(SceneKeys, EveryKeyTheWritersVisitIsInTheReference) {
  const auto keys = by_key();
  const std::string md = camdyn::scene_keys_markdown();
  std::set<std::string> visited;
  for (const camdyn::Scene& s : scenes_with_every_key()) {
    camdyn::for_each_scene_entry(s, [&](const SceneEntry& e) { visited.insert(path_of(e)); });
    camdyn::for_each_network_entry(s, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& es) {
      for (const SceneEntry& e : es) visited.insert(array + "." + e.key);
    });
  }
  EXPECT_GT(visited.size(), 70u);
  for (const std::string& k : visited) {
    EXPECT_TRUE(keys.count(k)) << "scene key '" << k << "' is missing from camdyn::scene_keys()";
    EXPECT_NE(md.find("| `" + k + "` |"), std::string::npos) << "no row for '" << k << "' in the Markdown reference";
  }
  // ... and the reference lists no key the writers never write.
  // (input-only keys in a designer's units are converted at load: the writers never write them)
  for (const auto& [k, info] : keys)
    if (!info.input_only) EXPECT_TRUE(visited.count(k)) << "the reference lists '" << k << "'";
}

TEST(SceneKeys, NetworkKeysAreDocumentedForTheTypesThatTakeThem) {
  const auto keys = by_key();
  // Which types write which key (the writers give exactly the keys of the entry's type).
  std::map<std::string, std::set<std::string>> types_of;
  for (const camdyn::Scene& s : scenes_with_every_key()) {
    camdyn::for_each_network_entry(s, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& es) {
      std::string type;
      for (const SceneEntry& e : es)
        if (e.key == "type") type = e.text;
      if (array == "nodes") return;
      for (const SceneEntry& e : es) types_of[array + "." + e.key].insert(type);
    });
  }
  ASSERT_FALSE(types_of.empty());
  for (const auto& [k, types] : types_of) {
    const auto it = keys.find(k);
    ASSERT_NE(it, keys.end()) << k;
    const std::set<std::string> documented(it->second.applies_to.begin(), it->second.applies_to.end());
    EXPECT_EQ(documented, types) << "types of '" << k << "'";
  }
}

// The documented default of every [table] key, written into a file by itself, loads to the
// same scene as the empty file: it is the loader's default.
TEST(SceneKeys, DocumentedDefaultsAreTheLoadersDefaults) {
  const camdyn::Scene empty = camdyn::parse_scene("", "<empty>");
  int checked = 0;
  for (const SceneKeyInfo& k : camdyn::scene_keys()) {
    const auto dot = k.key.find('.');
    const std::string table = dot == std::string::npos ? "" : k.key.substr(0, dot);
    if (table == "nodes" || table == "elements" || table == "contacts") continue;
    if (k.input_only) continue;  // no default: converted at load (SceneUnits tests)
    const std::string text = table.empty() ? k.key + " = " + k.default_value
                                           : "[" + table + "]\n" + k.key.substr(dot + 1) + " = " + k.default_value;
    camdyn::Scene s;
    ASSERT_NO_THROW(s = camdyn::parse_scene(text, "<default>")) << text;
    EXPECT_TRUE(s == empty) << "documented default of '" << k.key << "' differs: " << text;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(SceneKeys, JsonAndMarkdownListTheSameKeys) {
  const std::string json = camdyn::scene_keys_json();
  const std::string md = camdyn::scene_keys_markdown();
  for (const SceneKeyInfo& k : camdyn::scene_keys()) {
    EXPECT_NE(json.find("{\"key\": \"" + k.key + "\""), std::string::npos) << k.key;
    EXPECT_NE(md.find("| `" + k.key + "` |"), std::string::npos) << k.key;
  }
}

#ifdef CAMDYN_CLI_PATH
// The page scripts/docs.sh writes is `camdyn scene --keys`: the same text as the library's.
TEST(SceneKeys, CliPrintsTheReference) {
  const std::string cli = CAMDYN_CLI_PATH;
  if (cli.empty()) GTEST_SKIP() << "CLI not built";
  const auto out = std::filesystem::temp_directory_path() / ("camdyn_keys_" + std::to_string(::getpid()) + ".md");
  ASSERT_EQ(std::system(("'" + cli + "' scene --keys > '" + out.string() + "'").c_str()), 0);
  EXPECT_EQ(camdyn_test::slurp(out), camdyn::scene_keys_markdown());
  ASSERT_EQ(std::system(("'" + cli + "' scene --keys --json > '" + out.string() + "'").c_str()), 0);
  EXPECT_EQ(camdyn_test::slurp(out), camdyn::scene_keys_json());
  // --json alone is bad input: exit 2.
  const int raw = std::system(("'" + cli + "' scene --json > /dev/null 2>&1").c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 2);
  std::filesystem::remove(out);
}
#endif

}  // namespace
