// Network scenes (issue 16): [[nodes]], [[elements]], [[contacts]] with follower.kind =
// "network" — parsing, validation messages, round trips, equality, the summary's options.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"

#ifndef CAMDYN_SOURCE_DIR
#define CAMDYN_SOURCE_DIR "."
#endif

using namespace camdyn;

namespace {

std::string error_of(const std::string& text, const std::string& file = "net.toml") {
  try {
    parse_scene(text, file);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}

// A valve train with every kind of element and contact: cam → tappet → pushrod (bar) →
// rocker (lever) → lash → valve, valve spring with surge masses, a dashpot and the seat.
const std::string kValveTrain = R"(title = "pushrod valve train"
[follower]
kind = "network"

[contact]
model = "penalty"
penalty_stiffness = 1e8

[[nodes]]
name = "tappet"
mass = 0.02
[[nodes]]
name = "rocker_in"
[[nodes]]
name = "rocker_out"
[[nodes]]
name = "valve"
mass = 0.04
initial_displacement = -1e-5
initial_velocity = 0.25

[[elements]]
name = "tappet_spring"
type = "spring"
nodes = ["tappet", "ground"]
stiffness = 2000
preload = 20
[[elements]]
name = "pushrod"
type = "bar"
nodes = ["tappet", "rocker_in"]
mass = 0.03
youngs_modulus = 2.1e11
area = 3e-5
length = 0.2
elements = 4
mass_matrix = "consistent"
rayleigh_beta = 1e-6
[[elements]]
name = "rocker"
type = "lever"
nodes = ["rocker_in", "rocker_out"]
ratio = 1.5
[[elements]]
name = "valve_spring"
type = "spring"
nodes = ["valve", "ground"]
stiffness = 35000
preload = 250
damping = 2
mass = 0.03
masses = 4
[[elements]]
type = "dashpot"
nodes = ["valve", "ground"]
damping = 5

[[contacts]]
name = "cam"
type = "cam"
nodes = ["tappet"]
clearance = 0
[[contacts]]
name = "lash"
type = "lash"
nodes = ["rocker_out", "valve"]
clearance = 1e-4
restitution = 0.2
[[contacts]]
name = "seat"
type = "stop"
nodes = ["valve"]
side = "below"
penalty_stiffness = 5e8
penalty_damping = 100
)";

/// The "Networks" example of docs/interface.md: the ```toml block after the line
/// "<!-- network example -->".
std::string docs_example() {
  std::ifstream in(std::string(CAMDYN_SOURCE_DIR) + "/docs/interface.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const auto marker = doc.find("<!-- network example -->");
  if (marker == std::string::npos) return "";
  const auto b = doc.find("```toml\n", marker);
  const auto e = doc.find("```\n", b + 8);
  if (b == std::string::npos || e == std::string::npos) return "";
  return doc.substr(b + 8, e - b - 8);
}

}  // namespace

TEST(NetworkScene, EnumSpellings) {
  for (const char* s : {"spring", "dashpot", "bar", "lever"}) {
    ElementKind v;
    ASSERT_TRUE(parse_enum(s, &v)) << s;
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"cam", "lash", "stop"}) {
    ContactPointKind v;
    ASSERT_TRUE(parse_enum(s, &v)) << s;
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"below", "above"}) {
    StopSide v;
    ASSERT_TRUE(parse_enum(s, &v)) << s;
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"lumped", "consistent"}) {
    BarMass v;
    ASSERT_TRUE(parse_enum(s, &v)) << s;
    EXPECT_STREQ(to_string(v), s);
  }
  FollowerKind f;
  ASSERT_TRUE(parse_enum("network", &f));
  EXPECT_EQ(f, FollowerKind::Network);
  EXPECT_STREQ(to_string(FollowerKind::Network), "network");
  ElementKind e;
  EXPECT_FALSE(parse_enum("Spring", &e));
  EXPECT_FALSE(parse_enum("rod", &e));
}

TEST(NetworkScene, DocsExampleParsesAndRoundTrips) {
  const std::string text = docs_example();
  ASSERT_FALSE(text.empty()) << "docs/interface.md lacks the network example";
  const Scene s = parse_scene(text, "interface.md");
  EXPECT_EQ(s.follower.kind, FollowerKind::Network);
  ASSERT_EQ(s.network.nodes.size(), 2u);
  EXPECT_EQ(s.network.nodes[0].name, "tappet");
  EXPECT_EQ(s.network.nodes[1].name, "valve");
  ASSERT_EQ(s.network.contacts.size(), 2u);
  EXPECT_EQ(s.network.contacts[0].kind, ContactPointKind::Cam);
  EXPECT_EQ(s.network.contacts[0].nodes, std::vector<std::string>{"tappet"});
  EXPECT_DOUBLE_EQ(s.network.contacts[0].clearance, 0.2e-3);
  EXPECT_EQ(s.network.contacts[1].kind, ContactPointKind::Stop);
  EXPECT_EQ(s.network.contacts[1].side, StopSide::Below);
  EXPECT_EQ(parse_scene(to_toml(s), "again.toml"), s);
  // Its cam is a valid (convex) lift cam.
  EXPECT_NO_THROW(Cam cam(s.cam));
}

TEST(NetworkScene, ParsesRoundTripsAndCompares) {
  const Scene s = parse_scene(kValveTrain, "vt.toml");
  ASSERT_EQ(s.follower.kind, FollowerKind::Network);
  const NetworkSpec& n = s.network;
  ASSERT_EQ(n.nodes.size(), 4u);
  EXPECT_EQ(n.nodes[1].name, "rocker_in");
  EXPECT_EQ(n.nodes[1].mass, 0.0);
  EXPECT_EQ(n.nodes[3].mass, 0.04);
  EXPECT_EQ(n.nodes[3].initial_displacement, -1e-5);
  EXPECT_EQ(n.nodes[3].initial_velocity, 0.25);
  ASSERT_EQ(n.elements.size(), 5u);
  EXPECT_EQ(n.elements[0].kind, ElementKind::Spring);
  EXPECT_EQ(n.elements[0].nodes, (std::vector<std::string>{"tappet", "ground"}));
  EXPECT_EQ(n.elements[0].stiffness, 2000.0);
  EXPECT_EQ(n.elements[0].preload, 20.0);
  EXPECT_EQ(n.elements[1].kind, ElementKind::Bar);
  EXPECT_EQ(n.elements[1].elements, 4);
  EXPECT_EQ(n.elements[1].mass_matrix, BarMass::Consistent);
  EXPECT_EQ(n.elements[1].rayleigh_beta, 1e-6);
  EXPECT_EQ(n.elements[2].kind, ElementKind::Lever);
  EXPECT_EQ(n.elements[2].ratio, 1.5);
  EXPECT_EQ(n.elements[3].masses, 4);
  EXPECT_EQ(n.elements[4].kind, ElementKind::Dashpot);
  EXPECT_EQ(n.elements[4].name, "");
  ASSERT_EQ(n.contacts.size(), 3u);
  EXPECT_EQ(n.contacts[0].restitution, std::nullopt);
  EXPECT_EQ(n.contacts[1].kind, ContactPointKind::Lash);
  EXPECT_EQ(n.contacts[1].restitution, 0.2);
  EXPECT_EQ(n.contacts[1].penalty_stiffness, std::nullopt);
  EXPECT_EQ(n.contacts[2].penalty_stiffness, 5e8);
  EXPECT_EQ(n.contacts[2].penalty_damping, 100.0);

  // Round trip through to_toml; optional values only when set, names only when given.
  const std::string toml = to_toml(s);
  const Scene back = parse_scene(toml, "back.toml");
  EXPECT_EQ(back, s);
  EXPECT_EQ(to_toml(back), toml);
  EXPECT_NE(toml.find("[[nodes]]\nname = \"tappet\"\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("[[elements]]\ntype = \"dashpot\"\nnodes = [\"valve\", \"ground\"]\ndamping = 5.0\n"),
            std::string::npos)
      << toml;
  EXPECT_NE(toml.find("[[contacts]]\nname = \"cam\"\ntype = \"cam\"\nnodes = [\"tappet\"]\nclearance = 0.0\n\n"),
            std::string::npos)
      << toml;
  // (the [synthesis] table has a ratio of its own: look only at the elements)
  const std::string elements = toml.substr(toml.find("[[elements]]"));
  EXPECT_EQ(elements.find("ratio = 1.0"), std::string::npos) << "a spring has no ratio:\n" << toml;

  // Equality sees every network field.
  auto differs = [&](auto&& change) {
    Scene t = s;
    change(t.network);
    return !(t == s) && t != s;
  };
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.nodes[2].mass = 1e-3; }));
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.nodes[0].name = "bucket"; }));
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.elements[2].ratio = -1.5; }));
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.elements[1].mass_matrix = BarMass::Lumped; }));
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.elements[3].nodes[0] = "tappet"; }));
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.contacts[2].side = StopSide::Above; }));
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.contacts[0].restitution = 0.0; }));
  EXPECT_TRUE(differs([](NetworkSpec& m) { m.contacts.pop_back(); }));
  Scene same = s;
  same.source = "elsewhere";
  EXPECT_EQ(same, s);
}

TEST(NetworkScene, OverridesKeepTheNetwork) {
  Scene s = parse_scene(kValveTrain, "vt.toml");
  const NetworkSpec before = s.network;
  apply_overrides(s, {"contact.penalty_stiffness=2e8", "run.t_end=0.05"});
  EXPECT_EQ(s.network, before);
  EXPECT_EQ(s.contact.penalty_stiffness, 2e8);
  EXPECT_EQ(s.source, "vt.toml");
  // The network is checked again: leaving "network" with the arrays present is an error.
  try {
    apply_override(s, "follower.kind=rigid");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(),
                 "--set: key 'nodes' = (4 entries): [[nodes]] needs follower.kind = \"network\" "
                 "(follower.kind is \"rigid\")");
  }
  EXPECT_EQ(s.follower.kind, FollowerKind::Network);
}

TEST(NetworkScene, OptionsJsonHasTheNetwork) {
  const Scene s = parse_scene(kValveTrain, "vt.toml");
  const std::string j = scene_json(s);
  EXPECT_NE(j.find("\"nodes\": [\n    {\n      \"name\": \"tappet\",\n      \"mass\": 0.02,"), std::string::npos) << j;
  EXPECT_NE(j.find("\"type\": \"lever\",\n      \"nodes\": [\"rocker_in\", \"rocker_out\"],\n      \"ratio\": 1.5\n"),
            std::string::npos)
      << j;
  EXPECT_NE(j.find("\"contacts\": [\n"), std::string::npos) << j;
  EXPECT_NE(j.find("\"penalty_damping\": 100\n    }\n  ],\n  \"source\": \"vt.toml\"\n}"), std::string::npos) << j;
  // Scenes of the other kinds: no network keys.
  const std::string r = scene_json(paper_case("A"));
  EXPECT_EQ(r.find("\"nodes\""), std::string::npos) << r;
  EXPECT_EQ(r.find("\"contacts\""), std::string::npos) << r;
}

// ---------------------------------------------------------------- malformed network scenes

namespace {

// Lines 1–2; the minimal valid network below is lines 3–13.
const std::string kHead = "[follower]\nkind = \"network\"\n";
const std::string kNode = "[[nodes]]\nname = \"a\"\nmass = 1\n";                                 // 3–5
const std::string kSpring = "[[elements]]\ntype = \"spring\"\nnodes = [\"a\", \"ground\"]\nstiffness = 100\n";  // 6–9
const std::string kCam = "[[contacts]]\nname = \"cam\"\ntype = \"cam\"\nnodes = [\"a\"]\n";       // 10–13

struct BadNet {
  const char* what;
  std::string toml;
  std::string message;
};

}  // namespace

TEST(NetworkScene, MinimalNetworkIsValid) {
  const Scene s = parse_scene(kHead + kNode + kSpring + kCam, "min.toml");
  EXPECT_EQ(s.network.nodes.size(), 1u);
  EXPECT_EQ(parse_scene(to_toml(s), "again.toml"), s);
}

TEST(NetworkScene, ExactMessages) {
  const std::string good = kHead + kNode + kSpring + kCam;
  const std::vector<BadNet> cases = {
      // ---- structure and types
      {"nodes as a table", kHead + "[nodes]\nname = \"a\"\n",
       "net.toml:3: key 'nodes' = {...}: must be an array of tables ([[nodes]]); allowed keys in [[nodes]]: "
       "name, mass, initial_displacement, initial_velocity"},
      {"unknown node key", kHead + "[[nodes]]\nname = \"a\"\nmas = 1\n" + kSpring + kCam,
       "net.toml:5: key 'nodes[0].mas' = 1: unknown key; allowed keys in [[nodes]]: "
       "name, mass, initial_displacement, initial_velocity"},
      {"string for a number", kHead + "[[nodes]]\nname = \"a\"\nmass = \"1 kg\"\n" + kSpring + kCam,
       "net.toml:5: key 'nodes[0].mass' = \"1 kg\": must be a number"},
      {"element without type", good + "[[elements]]\nnodes = [\"a\", \"ground\"]\n",
       "net.toml:14: key 'elements[1]' = {...}: must have a key 'type' (\"spring\" | \"dashpot\" | \"bar\" | "
       "\"lever\" | \"progressive_spring\" | \"guide_friction\" | \"gas_load\" | \"hydraulic_lash_adjuster\")"},
      {"bad element type", good + "[[elements]]\ntype = \"rod\"\n",
       "net.toml:15: key 'elements[1].type' = \"rod\": must be one of \"spring\", \"dashpot\", \"bar\", \"lever\", "
       "\"progressive_spring\", \"guide_friction\", \"gas_load\", \"hydraulic_lash_adjuster\""},
      {"key of another type", kHead + kNode + "[[elements]]\ntype = \"spring\"\nnodes = [\"a\", \"ground\"]\n"
                                              "stiffness = 100\nratio = 2\n" + kCam,
       "net.toml:10: key 'elements[0].ratio' = 2: not a key of a spring element; allowed keys of a spring "
       "element: name, type, nodes, stiffness, preload, damping, mass, masses, free_length, solid_length, coil_gaps, coil_restitution"},
      {"unknown element key", kHead + kNode + "[[elements]]\ntype = \"dashpot\"\nnodes = [\"a\", \"ground\"]\n"
                                               "damping = 1\nstifness = 2\n" + kCam,
       "net.toml:10: key 'elements[0].stifness' = 2: unknown key; allowed keys of a dashpot element: "
       "name, type, nodes, damping"},
      {"side on a cam contact", good + "side = \"below\"\n",
       "net.toml:14: key 'contacts[0].side' = \"below\": not a key of a cam contact; allowed keys of a cam "
       "contact: name, type, nodes, clearance, restitution, penalty_stiffness, penalty_damping"},
      {"number in nodes", kHead + kNode + "[[elements]]\ntype = \"spring\"\nnodes = [\"a\", 0]\n" + kCam,
       "net.toml:8: key 'elements[0].nodes[1]' = 0: must be a string (a node name)"},
      {"masses not an integer", kHead + kNode + kSpring + "mass = 0.01\nmasses = 2.5\n" + kCam,
       "net.toml:11: key 'elements[0].masses' = 2.5: must be an integer"},
      {"bar elements too many", kHead + kNode + "[[elements]]\ntype = \"bar\"\nnodes = [\"a\", \"ground\"]\n"
                                                 "mass = 1\nyoungs_modulus = 1\narea = 1\nlength = 1\n"
                                                 "elements = 200000\n" + kCam,
       "net.toml:13: key 'elements[0].elements' = 200000: must be >= 1 and <= 100000"},
      {"bad mass_matrix", kHead + kNode + "[[elements]]\ntype = \"bar\"\nnodes = [\"a\", \"ground\"]\n"
                                           "mass = 1\nyoungs_modulus = 1\narea = 1\nlength = 1\n"
                                           "mass_matrix = \"diagonal\"\n" + kCam,
       "net.toml:13: key 'elements[0].mass_matrix' = \"diagonal\": must be one of \"lumped\", \"consistent\""},
      {"bad stop side", good + "[[contacts]]\nname = \"seat\"\ntype = \"stop\"\nnodes = [\"a\"]\nside = \"under\"\n",
       "net.toml:18: key 'contacts[1].side' = \"under\": must be one of \"below\", \"above\""},
      // ---- follower kind
      {"arrays with a rigid follower", kNode + kSpring + kCam,
       "net.toml:1: key 'nodes' = (1 entry): [[nodes]] needs follower.kind = \"network\" "
       "(follower.kind is \"rigid\")"},
      {"network without nodes", kHead,
       "net.toml:2: key 'follower.kind' = \"network\": needs at least one [[nodes]] entry"},
      {"network without contacts", kHead + kNode + kSpring,
       "net.toml:2: key 'follower.kind' = \"network\": needs at least one [[contacts]] entry"},
      // ---- nodes
      {"empty node name", kHead + "[[nodes]]\nname = \"\"\nmass = 1\n" + kSpring + kCam,
       "net.toml:4: key 'nodes[0].name' = \"\": must not be empty (node names are required)"},
      {"node named ground", kHead + "[[nodes]]\nname = \"ground\"\nmass = 1\n" + kSpring + kCam,
       "net.toml:4: key 'nodes[0].name' = \"ground\": is reserved (\"ground\" is the fixed end of a spring, "
       "dashpot or bar)"},
      {"bad node name", kHead + "[[nodes]]\nname = \"a b\"\nmass = 1\n" + kSpring + kCam,
       "net.toml:4: key 'nodes[0].name' = \"a b\": must contain only letters, digits, '_' and '-'"},
      {"duplicate node", kHead + kNode + kNode + kSpring + kCam,
       "net.toml:7: key 'nodes[1].name' = \"a\": must be unique (nodes[0] has the same name)"},
      {"negative node mass", kHead + "[[nodes]]\nname = \"a\"\nmass = -1\n" + kSpring + kCam,
       "net.toml:5: key 'nodes[0].mass' = -1: must be >= 0 (node 'a')"},
      {"NaN initial velocity", kHead + kNode + "initial_velocity = nan\n" + kSpring + kCam,
       "net.toml:6: key 'nodes[0].initial_velocity' = nan: must be a finite number (node 'a')"},
      // ---- references
      {"unknown node", kHead + kNode + "[[elements]]\ntype = \"spring\"\nnodes = [\"a\", \"b\"]\n" + kCam,
       "net.toml:8: key 'elements[0].nodes[1]' = \"b\": names no node of [[nodes]] (spring #0)"},
      {"one node", kHead + kNode + "[[elements]]\nname = \"k\"\ntype = \"spring\"\nnodes = [\"a\"]\n" + kCam,
       "net.toml:9: key 'elements[0].nodes' = [\"a\"]: must name exactly 2 nodes, has 1 (spring 'k')"},
      {"same node twice", kHead + kNode + kSpring + "[[elements]]\ntype = \"dashpot\"\nnodes = [\"a\", \"a\"]\n"
                                                      "damping = 1\n" + kCam,
       "net.toml:12: key 'elements[1].nodes' = [\"a\", \"a\"]: must name two different nodes (dashpot #1)"},
      {"ground on a lever", kHead + kNode + kSpring + "[[elements]]\ntype = \"lever\"\nnodes = [\"a\", \"ground\"]\n" + kCam,
       "net.toml:12: key 'elements[1].nodes[1]' = \"ground\": \"ground\" cannot be a node of a lever (lever #1)"},
      {"ground in a contact", kHead + kNode + kSpring + "[[contacts]]\nname = \"c\"\ntype = \"stop\"\n"
                                                        "nodes = [\"ground\"]\n",
       "net.toml:13: key 'contacts[0].nodes[0]' = \"ground\": \"ground\" cannot be a node of a contact "
       "(stop contact 'c')"},
      {"lash with one node", good + "[[contacts]]\nname = \"l\"\ntype = \"lash\"\nnodes = [\"a\"]\n",
       "net.toml:17: key 'contacts[1].nodes' = [\"a\"]: must name exactly 2 nodes, has 1 (lash contact 'l')"},
      {"empty contact name", kHead + kNode + kSpring + "[[contacts]]\ntype = \"cam\"\nnodes = [\"a\"]\n",
       "net.toml:10: key 'contacts[0].name' = \"\": must not be empty (contact names are required)"},
      {"duplicate contact", good + kCam,
       "net.toml:15: key 'contacts[1].name' = \"cam\": must be unique (contacts[0] has the same name)"},
      // ---- element values
      {"negative stiffness", kHead + kNode + "[[elements]]\nname = \"vs\"\ntype = \"spring\"\n"
                                             "nodes = [\"a\", \"ground\"]\nstiffness = -5\n" + kCam,
       "net.toml:10: key 'elements[0].stiffness' = -5: must be >= 0 (spring 'vs')"},
      {"infinite preload", kHead + kNode + kSpring + "preload = inf\n" + kCam,
       "net.toml:10: key 'elements[0].preload' = inf: must be a finite number (spring #0)"},
      {"spring mass without masses", kHead + kNode + kSpring + "mass = 0.01\n" + kCam,
       "net.toml:6: key 'elements[0].masses' = 0: must be >= 1 for a spring with mass "
       "(elements[0].mass = 0.01) (spring #0)"},
      {"masses without mass", kHead + kNode + kSpring + "masses = 3\n" + kCam,
       "net.toml:10: key 'elements[0].masses' = 3: needs elements[0].mass > 0 (spring #0)"},
      {"dashpot without damping", kHead + kNode + kSpring + "[[elements]]\ntype = \"dashpot\"\n"
                                                            "nodes = [\"a\", \"ground\"]\n" + kCam,
       "net.toml:10: key 'elements[1].damping' = 0: must be > 0 (dashpot #1)"},
      {"bar without mass", kHead + kNode + "[[elements]]\nname = \"rod\"\ntype = \"bar\"\n"
                                           "nodes = [\"a\", \"ground\"]\nyoungs_modulus = 1\narea = 1\nlength = 1\n" + kCam,
       "net.toml:6: key 'elements[0].mass' = 0: must be > 0 (bar 'rod')"},
      {"bar zero length", kHead + kNode + "[[elements]]\ntype = \"bar\"\nnodes = [\"a\", \"ground\"]\n"
                                          "mass = 1\nyoungs_modulus = 1\narea = 1\nlength = 0\n" + kCam,
       "net.toml:12: key 'elements[0].length' = 0: must be > 0 (bar #0)"},
      {"negative Rayleigh", kHead + kNode + "[[elements]]\ntype = \"bar\"\nnodes = [\"a\", \"ground\"]\n"
                                            "mass = 1\nyoungs_modulus = 1\narea = 1\nlength = 1\n"
                                            "rayleigh_alpha = -1\n" + kCam,
       "net.toml:13: key 'elements[0].rayleigh_alpha' = -1: must be >= 0 (bar #0)"},
      // ---- levers
      {"lever ratio 0", kHead + kNode + "[[nodes]]\nname = \"b\"\n" + kSpring +
                            "[[elements]]\nname = \"rocker\"\ntype = \"lever\"\nnodes = [\"a\", \"b\"]\nratio = 0\n" + kCam,
       "net.toml:16: key 'elements[1].ratio' = 0: must be finite and > 0 (the output moves ratio times the input, "
       "in the same direction) (lever 'rocker')"},
      {"two levers drive one node",
       kHead + kNode + "[[nodes]]\nname = \"b\"\n[[nodes]]\nname = \"c\"\nmass = 1\n" + kSpring +
           "[[elements]]\ntype = \"lever\"\nnodes = [\"a\", \"b\"]\n"
           "[[elements]]\ntype = \"lever\"\nnodes = [\"c\", \"b\"]\n" + kCam,
       "net.toml:20: key 'elements[2].nodes[1]' = \"b\": is already the output of lever #1 (elements[1]); "
       "a node is the output of at most one lever (lever #2)"},
      {"lever cycle",
       kHead + kNode + "[[nodes]]\nname = \"b\"\n" + kSpring +
           "[[elements]]\ntype = \"lever\"\nnodes = [\"a\", \"b\"]\nratio = 2\n"
           "[[elements]]\ntype = \"lever\"\nnodes = [\"b\", \"a\"]\nratio = 0.5\n" + kCam,
       "net.toml:14: key 'elements[1].nodes' = [\"a\", \"b\"]: levers form a cycle through node 'b' (lever #1)"},
      // ---- contacts
      {"negative clearance", good + "clearance = -1e-4\n",
       "net.toml:14: key 'contacts[0].clearance' = -0.0001: must be >= 0 (cam contact 'cam')"},
      {"restitution above 1", good + "restitution = 1.5\n",
       "net.toml:14: key 'contacts[0].restitution' = 1.5: must be >= 0 and <= 1 (cam contact 'cam')"},
      {"zero penalty stiffness", good + "penalty_stiffness = 0\n",
       "net.toml:14: key 'contacts[0].penalty_stiffness' = 0: must be > 0 (cam contact 'cam')"},
      {"negative penalty damping", good + "penalty_damping = -2\n",
       "net.toml:14: key 'contacts[0].penalty_damping' = -2: must be >= 0 (cam contact 'cam')"},
      // ---- the network as a whole
      {"dangling node", kHead + kNode + "[[nodes]]\nname = \"spare\"\nmass = 1\n" + kSpring + kCam,
       "net.toml:7: key 'nodes[1].name' = \"spare\": node 'spare' is dangling: no element or contact uses it"},
      {"floating node (dashpot only)", kHead + kNode + "[[elements]]\ntype = \"dashpot\"\n"
                                                       "nodes = [\"a\", \"ground\"]\ndamping = 1\n" + kCam,
       "net.toml:4: key 'nodes[0].name' = \"a\": node 'a' floats: no spring or bar connects it to ground"},
      {"floating pair (spring between them only)",
       kHead + kNode + "[[nodes]]\nname = \"b\"\nmass = 1\n" + kSpring +
           "[[elements]]\ntype = \"spring\"\nnodes = [\"b\", \"c\"]\nstiffness = 1\n"
           "[[nodes]]\nname = \"c\"\nmass = 1\n" + kCam,
       "net.toml:7: key 'nodes[1].name' = \"b\": node 'b' floats: no spring or bar connects it to ground"},
      {"massless node", kHead + "[[nodes]]\nname = \"a\"\n" +
                            "[[elements]]\ntype = \"spring\"\nnodes = [\"a\", \"ground\"]\nstiffness = 100\n" + kCam,
       "net.toml:3: key 'nodes[0].mass' = 0: node 'a' has no mass (give it mass, or connect a bar or a spring "
       "with mass to it or to a node tied to it by a lever)"},
  };
  ASSERT_GE(cases.size(), 15u);
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    EXPECT_EQ(error_of(c.toml), c.message) << c.toml;
  }
}

TEST(NetworkScene, LeverTransfersMassAndGrounding) {
  // b has no mass and no spring of its own, but is tied by a lever to a: valid.
  const std::string text = kHead + kNode + "[[nodes]]\nname = \"b\"\n" + kSpring +
                           "[[elements]]\ntype = \"lever\"\nnodes = [\"a\", \"b\"]\nratio = 2\n" +
                           "[[contacts]]\nname = \"cam\"\ntype = \"cam\"\nnodes = [\"b\"]\n";
  EXPECT_EQ(error_of(text), "<no error>");
  // A bar to ground grounds and gives mass; a spring with mass gives mass to a massless node.
  const std::string bar = kHead + "[[nodes]]\nname = \"a\"\n[[elements]]\ntype = \"bar\"\nnodes = [\"ground\", \"a\"]\n"
                          "mass = 1\nyoungs_modulus = 1\narea = 1\nlength = 1\n" + kCam;
  EXPECT_EQ(error_of(bar), "<no error>");
  const std::string surge = kHead + "[[nodes]]\nname = \"a\"\n" + kSpring + "mass = 0.1\nmasses = 1\n" + kCam;
  EXPECT_EQ(error_of(surge), "<no error>");
}
