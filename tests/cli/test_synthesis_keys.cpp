// The synthesis train as scene keys ([synthesis]; src/scene/scene.cpp, src/cli/cmd_misc.cpp):
// parsed, validated naming the key, written back by to_toml; `camdyn cam
// --synthesise-from-valve-lift` takes the train from the scene and each CLI option
// overrides its key (the same lift table either way).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../test_support.hpp"
#include "camdyn/scene.hpp"

using namespace camdyn;
namespace fs = std::filesystem;

namespace {

const std::string kCli = CAMDYN_CLI_PATH;
const std::string kSource = CAMDYN_SOURCE_DIR;

std::string key_of(const std::string& text) {
  try {
    parse_scene(text, "<test>");
  } catch (const SceneError& e) {
    return e.key();
  }
  return "<no error>";
}

struct Cli {
  int status;
  std::string err;
};
Cli cam(const fs::path& dir, const std::string& args) {
  const std::string err = (dir / "stderr.txt").string();
  const std::string cmd = kCli + " cam " + kSource + "/examples/synth_finger.toml --synthesise-from-valve-lift " +
                          "--no-plot -q " + args + " 2>" + err;
  const int rc = std::system(cmd.c_str());
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, camdyn_test::slurp(err)};
}

}  // namespace

TEST(SynthesisKeys, ParsedValidatedAndWrittenBack) {
  const Scene a = parse_scene("[synthesis]\nratio = 1.6\nlash = 0.25\nramp_deg = 40\nvalve_end_angle_deg = -7.5\n", "<test>");
  EXPECT_EQ(a.synthesis.ratio, 1.6);
  EXPECT_EQ(a.synthesis.lash, 0.25);
  EXPECT_EQ(a.synthesis.ramp_deg, 40.0);
  EXPECT_EQ(a.synthesis.valve_end_angle_deg, -7.5);
  const Scene b = parse_scene(to_toml(a), "<round trip>");
  EXPECT_TRUE(b.synthesis == a.synthesis);
  EXPECT_TRUE(b == a);
  // defaults: a bucket (ratio 1), no lash
  const Scene d = parse_scene("", "<test>");
  EXPECT_EQ(d.synthesis.ratio, 1.0);
  EXPECT_EQ(d.synthesis.lash, 0.0);
  EXPECT_EQ(key_of("[synthesis]\nratio = 0\n"), "synthesis.ratio");
  EXPECT_EQ(key_of("[synthesis]\nvalve_end_angle_deg = 95\n"), "synthesis.valve_end_angle_deg");
  EXPECT_EQ(key_of("[synthesis]\nlash = -1\n"), "synthesis.lash");
  EXPECT_EQ(key_of("[synthesis]\nlash = 0.1\n"), "synthesis.ramp_deg");  // lash needs a ramp
  EXPECT_EQ(key_of("[synthesis]\nwhatever = 1\n"), "synthesis.whatever");
}

TEST(SynthesisKeys, CliTakesTheSceneAndItsOptionsOverride) {
  const fs::path dir = fs::temp_directory_path() / ("camdyn_synth_keys_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // the scene's [synthesis] valve_end_angle_deg = 5
  const Cli a = cam(dir, "-o " + (dir / "A").string());
  ASSERT_EQ(a.status, 0) << a.err;
  // the key set to 0 and the option giving 5 back: the same table, to the byte
  const Cli b = cam(dir, "--set synthesis.valve_end_angle_deg=0 --valve-end-angle 5 -o " + (dir / "B").string());
  ASSERT_EQ(b.status, 0) << b.err;
  // the key at 0 alone: another finger, another cam
  const Cli c = cam(dir, "--set synthesis.valve_end_angle_deg=0 -o " + (dir / "C").string());
  ASSERT_EQ(c.status, 0) << c.err;
  const std::string ta = camdyn_test::slurp(dir / "A" / "cam_lift_table.csv");
  ASSERT_FALSE(ta.empty());
  EXPECT_EQ(ta, camdyn_test::slurp(dir / "B" / "cam_lift_table.csv"));
  EXPECT_NE(ta, camdyn_test::slurp(dir / "C" / "cam_lift_table.csv"));
  // synthesised.toml keeps the train it was made with
  const Scene s = load_scene_file((dir / "B" / "synthesised.toml").string());
  EXPECT_EQ(s.synthesis.valve_end_angle_deg, 5.0);
  EXPECT_EQ(s.cam.profile, CamProfileKind::Table);
  // a bad option: exit 2 naming the key
  const Cli bad = cam(dir, "--valve-end-angle 95 -o " + (dir / "D").string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("synthesis.valve_end_angle_deg"), std::string::npos) << bad.err;
  fs::remove_all(dir);
}
