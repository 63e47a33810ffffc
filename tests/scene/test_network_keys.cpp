// Network entries addressed by name or index ("contacts.seat.restitution",
// "elements[1].preload") as --set overrides and sweep keys (issue 26). The truth each
// override is checked against is the same change written into the scene file.
#include <gtest/gtest.h>
#include "../test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "camdyn/designer.hpp"
#include "camdyn/scene.hpp"

namespace fs = std::filesystem;
using camdyn_test::slurp;
using camdyn_test::split;

namespace {

const std::string kSource = CAMDYN_SOURCE_DIR;
const std::string kCli = CAMDYN_CLI_PATH;

std::string example_path(const std::string& name) { return kSource + "/examples/" + name; }
std::string example_text(const std::string& name) { return slurp(example_path(name)); }

/// `text` with the first occurrence of `what` replaced by `with` (the test fails if absent).
std::string edit(std::string text, const std::string& what, const std::string& with) {
  const auto at = text.find(what);
  EXPECT_NE(at, std::string::npos) << "'" << what << "' not in the example";
  if (at != std::string::npos) text.replace(at, what.size(), with);
  return text;
}

/// The message of the SceneError apply_overrides throws ("" if none).
std::string override_error(camdyn::Scene sc, const std::vector<std::string>& sets) {
  try {
    camdyn::apply_overrides(sc, sets);
  } catch (const camdyn::SceneError& e) {
    return e.what();
  }
  return "";
}

// ---- overrides by name give the scene of the edited file --------------------------------

TEST(NetworkKeys, OverrideEqualsTheSameChangeInTheFile) {
  struct Case {
    const char* example;
    std::string set;
    std::string what, with;  // the same change made in the file's text
  };
  const std::vector<Case> cases{
      {"ohc_bucket_tappet.toml", "contacts.seat.restitution=0.3", "side = \"below\"",
       "side = \"below\"\nrestitution = 0.3"},
      {"ohc_bucket_tappet.toml", "contacts[1].restitution=0.3", "side = \"below\"",
       "side = \"below\"\nrestitution = 0.3"},
      {"ohc_bucket_tappet.toml", "nodes.valve.mass=0.06", "mass = 0.050 ", "mass = 0.06 "},
      {"ohc_bucket_tappet.toml", "elements.valve_spring.preload=300", "preload = 250.0",
       "preload = 300.0"},
      {"ohc_bucket_tappet.toml", "elements.stem.stiffness=4e7", "stiffness = 5e7", "stiffness = 4e7"},
      {"ohc_bucket_tappet.toml", "contacts.cam.clearance=1e-4", "clearance = 0.2e-3", "clearance = 1e-4"},
      {"ohv_pushrod_train.toml", "elements.pushrod.elements=100", "elements = 4\n", "elements = 100\n"},
      {"ohv_pushrod_train.toml", "elements.valve_spring.masses=3", "masses = 6", "masses = 3"},
      {"ohv_pushrod_train.toml", "elements.pushrod.mass_matrix=consistent", "mass_matrix = \"lumped\"",
       "mass_matrix = \"consistent\""},
      {"ohv_pushrod_train.toml", "elements.rocker.ratio=1.6", "ratio = 1.5", "ratio = 1.6"},
      {"ohv_pushrod_train.toml", "contacts.lash.clearance=0.3e-3", "clearance = 0.25e-3", "clearance = 0.3e-3"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.set);
    camdyn::Scene by_set = camdyn::load_scene_file(example_path(c.example));
    const camdyn::Scene original = by_set;
    camdyn::apply_override(by_set, c.set);
    const camdyn::Scene by_file = camdyn::parse_scene(edit(example_text(c.example), c.what, c.with), "edited");
    EXPECT_TRUE(by_set == by_file);
    EXPECT_FALSE(by_set == original);  // the change took effect
  }
}

// ---- errors: exact messages (apply_overrides, and the CLI's exit 2) -----------------------

struct BadKey {
  const char* example;
  std::string set;
  std::string message;  // SceneError::what()
};

const std::vector<BadKey>& bad_keys() {
  static const std::vector<BadKey> v{
      {"ohc_bucket_tappet.toml", "contacts.sat.restitution=0.3",
       "--set: key 'contacts.sat.restitution' = 0.3: no [[contacts]] entry named 'sat'; [[contacts]] has 2 "
       "entries: cam, seat"},
      {"ohc_bucket_tappet.toml", "nodes.pushrod.mass=0.1",
       "--set: key 'nodes.pushrod.mass' = 0.1: no [[nodes]] entry named 'pushrod'; [[nodes]] has 2 entries: "
       "tappet, valve"},
      {"ohv_pushrod_train.toml", "elements.valvespring.preload=300",
       "--set: key 'elements.valvespring.preload' = 300: no [[elements]] entry named 'valvespring'; [[elements]] "
       "has 4 entries: pushrod, rocker, lifter_spring, valve_spring"},
      {"case_A.toml", "contacts.seat.restitution=0.3",
       "--set: key 'contacts.seat.restitution' = 0.3: no [[contacts]] entry named 'seat'; the scene has no "
       "[[contacts]] entries"},
      {"ohc_bucket_tappet.toml", "contacts[2].restitution=0.3",
       "--set: key 'contacts[2].restitution' = 0.3: index 2 out of range; [[contacts]] has 2 entries: cam, seat"},
      {"ohv_pushrod_train.toml", "nodes[17].mass=0.1",
       "--set: key 'nodes[17].mass' = 0.1: index 17 out of range; [[nodes]] has 4 entries: lifter, rocker_in, "
       "rocker_tip, valve"},
      {"ohc_bucket_tappet.toml", "elements.valve_spring.elements=100",
       "--set: key 'elements.valve_spring.elements' = 100: not a key of a spring element; allowed keys of a "
       "spring element: name, type, nodes, stiffness, preload, damping, mass, masses, free_length, solid_length, coil_gaps, coil_restitution"},
      {"ohv_pushrod_train.toml", "elements.pushrod.preload=10",
       "--set: key 'elements.pushrod.preload' = 10: not a key of a bar element; allowed keys of a bar element: "
       "name, type, nodes, mass, youngs_modulus, area, length, elements, mass_matrix, rayleigh_alpha, "
       "rayleigh_beta"},
      {"ohc_bucket_tappet.toml", "contacts.cam.side=above",
       "--set: key 'contacts.cam.side' = \"above\": not a key of a cam contact; allowed keys of a cam contact: "
       "name, type, nodes, clearance, restitution, penalty_stiffness, penalty_damping"},
      {"ohc_bucket_tappet.toml", "nodes.valve.stiffness=1",
       "--set: key 'nodes.valve.stiffness' = 1: unknown key; allowed keys of a node: name, mass, "
       "initial_displacement, initial_velocity"},
      {"ohc_bucket_tappet.toml", "contacts.seat=0.3",
       "--set: key 'contacts.seat' = 0.3: expected contacts.NAME.KEY or contacts[INDEX].KEY (e.g. "
       "contacts.seat.restitution)"},
      {"ohc_bucket_tappet.toml", "elements[x].preload=1",
       "--set: key 'elements[x].preload' = 1: expected elements.NAME.KEY or elements[INDEX].KEY (e.g. "
       "elements.valve_spring.preload)"},
      // a bad value is reported under the key as written (not as elements[1].masses)
      {"ohc_bucket_tappet.toml", "elements.valve_spring.masses=1.5",
       "--set: key 'elements.valve_spring.masses' = 1.5: must be an integer"},
  };
  return v;
}

TEST(NetworkKeys, BadKeysGiveExactMessages) {
  for (const auto& c : bad_keys()) {
    SCOPED_TRACE(c.set);
    const camdyn::Scene sc = camdyn::load_scene_file(example_path(c.example));
    EXPECT_EQ(override_error(sc, {c.set}), c.message);
  }
}

struct Cli {
  int status = -1;
  std::string out, err;
};

class NetworkKeysCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(kCli.empty()) << "the camdyn CLI was not built";
    dir_ = fs::temp_directory_path() /
           ("camdyn_netkeys_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  /// "camdyn ARGS" in the test directory (ARGS: shell text, single-quoted by the caller).
  Cli camdyn(const std::string& args) {
    const std::string cmd = "cd '" + dir_.string() + "' && '" + kCli + "' " + args + " >out.txt 2>err.txt </dev/null";
    const int raw = std::system(cmd.c_str());
    Cli r;
    r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(dir_ / "out.txt");
    r.err = slurp(dir_ / "err.txt");
    return r;
  }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  fs::path dir_;
};

TEST_F(NetworkKeysCli, BadKeysExitTwoWithTheExactMessage) {
  for (const auto& c : bad_keys()) {
    SCOPED_TRACE(c.set);
    const Cli r = camdyn("run '" + example_path(c.example) + "' --set '" + c.set + "' --out D --quiet");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "camdyn: " + c.message + "\n");
    EXPECT_FALSE(fs::exists(dir_ / "D" / "history.csv"));
  }
}

// --set contacts.seat.restitution=0.3 on the OHC example: the same history and events, byte
// for byte, as the edited file; and not those of the unedited file (the seat bounces).
TEST_F(NetworkKeysCli, SetByNameGivesTheEditedFilesHistory) {
  const std::string ohc = example_path("ohc_bucket_tappet.toml");
  write("edited.toml", edit(example_text("ohc_bucket_tappet.toml"), "side = \"below\"",
                            "side = \"below\"\nrestitution = 0.3"));
  ASSERT_EQ(camdyn("run '" + ohc + "' --set contacts.seat.restitution=0.3 --out S --quiet").status, 0);
  ASSERT_EQ(camdyn("run edited.toml --out F --quiet").status, 0);
  ASSERT_EQ(camdyn("run '" + ohc + "' --out O --quiet").status, 0);
  const std::string hs = slurp(dir_ / "S" / "history.csv"), hf = slurp(dir_ / "F" / "history.csv");
  const std::string es = slurp(dir_ / "S" / "events.csv"), ef = slurp(dir_ / "F" / "events.csv");
  ASSERT_GT(hs.size(), 1000u);
  EXPECT_TRUE(hs == hf) << "history.csv differs";
  EXPECT_EQ(es, ef);
  // restitution 0 → 0.3 makes the valve bounce on its seat: more seat impacts than the original
  auto seat_impacts = [](const std::string& events) {
    int n = 0;
    for (const auto& line : split(events, '\n'))
      if (line.find(",impact,") != std::string::npos && line.size() > 5 && line.substr(line.size() - 5) == ",seat")
        ++n;
    return n;
  };
  EXPECT_GT(seat_impacts(es), seat_impacts(slurp(dir_ / "O" / "events.csv")));
}

/// The number after "\"KEY\": " in a summary.json.
std::string json_field(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return "(missing " + key + ")";
  const auto from = at + key.size() + 4;
  return json.substr(from, json.find_first_of(",\n}", from) - from);
}

// A sweep over elements.valve_spring.preload with --jobs 2: every row is the run of the
// scene file with that preload written in.
TEST_F(NetworkKeysCli, SweepOverAValveSpringPreload) {
  const Cli r = camdyn("sweep '" + example_path("ohc_bucket_tappet.toml") +
                       "' --key elements.valve_spring.preload --from 100 --to 300 --points 3 --jobs 2 "
                       "--no-timing --quiet --out W");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = split(slurp(dir_ / "W" / "sweep.csv"), '\n');
  ASSERT_GE(lines.size(), 4u);
  const auto header = split(lines[0], ',');
  EXPECT_EQ(header[0], "elements.valve_spring.preload");
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  const char* preloads[] = {"100", "200", "300"};
  std::vector<std::string> max_forces;
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(preloads[i]);
    const auto row = split(lines[1 + i], ',');
    ASSERT_EQ(row[0], preloads[i]);
    const std::string name = std::string("p") + preloads[i];
    write(name + ".toml", edit(example_text("ohc_bucket_tappet.toml"), "preload = 250.0",
                               std::string("preload = ") + preloads[i] + ".0"));
    ASSERT_EQ(camdyn("run " + name + ".toml --out " + name + " --quiet").status, 0);
    const std::string js = slurp(dir_ / name / "summary.json");
    for (const char* k : {"separations", "impacts", "max_contact_force", "min_contact_force", "max_gap", "steps"})
      EXPECT_EQ(row[col.at(k)], json_field(js, k)) << k;
    max_forces.push_back(row[col.at("max_contact_force")]);
  }
  EXPECT_NE(max_forces[0], max_forces[2]);  // the key reached the model
}

TEST_F(NetworkKeysCli, SweepKeyErrors) {
  const std::string ohc = "sweep '" + example_path("ohc_bucket_tappet.toml") + "' --from 1 --to 2 --points 2 --out W ";
  struct Case {
    std::string key, message;
  };
  const std::vector<Case> cases{
      {"elements.spring.preload",
       "camdyn: --key: key 'key' = elements.spring.preload: no [[elements]] entry named 'spring'; [[elements]] has 2 "
       "entries: stem, valve_spring\n"},
      {"elements[2].preload",
       "camdyn: --key: key 'key' = elements[2].preload: index 2 out of range; [[elements]] has 2 entries: stem, "
       "valve_spring\n"},
      {"elements.stem.elements",
       "camdyn: --key: key 'key' = elements.stem.elements: not a key of a spring element; allowed keys of a spring "
       "element: name, type, nodes, stiffness, preload, damping, mass, masses, free_length, solid_length, coil_gaps, coil_restitution\n"},
      {"contacts.seat.side",
       "camdyn: --key: key 'key' = contacts.seat.side: is a string, not a number: only numeric keys can be swept\n"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.key);
    const Cli r = camdyn(ohc + "--key '" + c.key + "'");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, c.message);
  }
}

// Integer keys are swept as integers (elements.valve_spring.masses: 2, 4 — not 2.0000001).
TEST(NetworkKeys, SweepAxisOfAnIntegerKeyTakesWholeNumbersOnly) {
  // Issue 35: 1, 1.59, 2.52, 4 (geometric) were rounded to 1, 2, 3, 4 without a word; now
  // refused, and whole-number grids accepted.
  const camdyn::Scene sc = camdyn::load_scene_file(example_path("ohc_bucket_tappet.toml"));
  EXPECT_THROW(camdyn::make_sweep_axis(sc, "elements.valve_spring.masses", 1, 4, NAN, 4, true), camdyn::SceneError);
  const camdyn::SweepAxis ax = camdyn::make_sweep_axis(sc, "elements.valve_spring.masses", 1, 4, NAN, 4, false);
  EXPECT_EQ(ax.values, (std::vector<double>{1, 2, 3, 4}));
}

}  // namespace
