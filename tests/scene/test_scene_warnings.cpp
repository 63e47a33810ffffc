// Plausibility warnings for valve trains (issue 28): a lash meant in mm, masses and
// stiffnesses outside valve-train ranges, a lift in mm, an absurd speed. Warnings, not
// errors: the run goes on and says them (stderr, Summary::warnings, summary.json).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/scene_warnings.hpp"
#include "camdyn/simulator.hpp"
#include "../test_support.hpp"

#ifndef CAMDYN_SOURCE_DIR
#define CAMDYN_SOURCE_DIR "."
#endif
#ifndef CAMDYN_CLI_PATH
#define CAMDYN_CLI_PATH ""
#endif

namespace {

namespace fs = std::filesystem;
using camdyn::Scene;

const std::string kOhc = std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml";

Scene ohc(const std::vector<std::string>& sets = {}) {
  Scene s = camdyn::load_scene_file(kOhc);
  camdyn::apply_overrides(s, sets);
  return s;
}

// The example's lift table peaks at 8 mm (values to four digits in the warnings).
std::string lash_warning(const Scene&) {
  return "contact 'cam': clearance 0.2 m is not smaller than the cam's lift 0.008 m: the valve never opens "
         "(lengths are in metres: 0.2 mm is 0.0002 m)";
}

TEST(SceneWarnings, LashMeantAsMillimetresWarnsAndRuns) {
  const Scene s = ohc({"contacts.cam.clearance=0.2", "run.t_end=0.01"});
  EXPECT_NEAR(camdyn::Cam(s.cam).lift(), 0.008, 1e-6);
  const std::vector<std::string> expected{lash_warning(s)};
  EXPECT_EQ(camdyn::scene_warnings(s), expected);
  camdyn::Simulator sim(s);
  EXPECT_EQ(sim.warnings(), expected);
  const camdyn::Summary sum = sim.run();
  EXPECT_TRUE(sum.finished) << sum.message;
  EXPECT_EQ(sum.warnings, expected);
  EXPECT_NE(sum.FullReport().find("  warning:            " + expected[0] + "\n"), std::string::npos);
}

TEST(SceneWarnings, ExampleAndPaperScenesHaveNone) {
  EXPECT_TRUE(camdyn::scene_warnings(ohc()).empty());
  EXPECT_TRUE(
      camdyn::scene_warnings(camdyn::load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohv_pushrod_train.toml"))
          .empty());
  // the paper's cases are in their own consistent units: no valve-train ranges apply
  for (const char* c : {"A", "B1", "B2"}) EXPECT_TRUE(camdyn::scene_warnings(camdyn::paper_case(c)).empty()) << c;
}

TEST(SceneWarnings, EachRuleWithItsText) {
  struct Case {
    std::vector<std::string> sets;
    std::string warning;
  };
  const std::vector<Case> cases = {
      {{"nodes.valve.mass=50"},
       "node 'valve': mass 50 kg is outside the valve-train range 0.001 to 10 kg (masses are in kg: 50 g is 0.05 kg)"},
      {{"nodes.tappet.mass=1e-4"}, "node 'tappet': mass 0.0001 kg is outside the valve-train range 0.001 to 10 kg"},
      {{"elements.valve_spring.stiffness=35"},
       "element 'valve_spring': stiffness 35 N/m is outside the valve-train range 1000 to 1e+10 N/m (stiffnesses "
       "are in N/m: 35 N/mm is 35000 N/m)"},
      {{"elements.stem.stiffness=5e11"},
       "element 'stem': stiffness 5e+11 N/m is outside the valve-train range 1000 to 1e+10 N/m"},
      {{"cam.speed_rev_s=500"},
       "cam: speed 500 rev/s (30000 camshaft rpm, 60000 engine rpm) is above 200 rev/s, beyond any valve train "
       "(cam.speed_rev_s is in camshaft revolutions per second)"},
  };
  for (const Case& c : cases) {
    const std::vector<std::string> expected{c.warning};
    EXPECT_EQ(camdyn::scene_warnings(ohc(c.sets)), expected) << c.sets[0];
  }
}

// A lift table in mm (× 1000) on a base radius in mm: the lift warns (8 > 0.05 m); the lash
// of 0.2 mm given in metres is then far below the lift and says nothing.
TEST(SceneWarnings, LiftInMillimetres) {
  Scene s = ohc();
  for (double& x : s.cam.lift) x *= 1000.0;
  s.cam.base_radius = 22.0;
  EXPECT_NEAR(camdyn::Cam(s.cam).lift(), 8.0, 1e-4);
  const std::vector<std::string> expected{"cam: lift 8 m is larger than 0.05 m: lengths are in metres (8 mm is 0.008 m)"};
  EXPECT_EQ(camdyn::scene_warnings(s), expected);
}

// The CLI: a warning line on stderr, "warnings" in summary.json, exit 0; none for the example.
TEST(SceneWarnings, CliPrintsThemAndKeepsThemInSummaryJson) {
  const std::string cli = CAMDYN_CLI_PATH;
  ASSERT_FALSE(cli.empty()) << "the camdyn CLI was not built";
  const fs::path dir = fs::temp_directory_path() / ("camdyn_warnings_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto run = [&](const std::string& sets, const std::string& out) {
    const std::string cmd = "'" + cli + "' run '" + kOhc + "' --quiet --set run.t_end=0.01 " + sets + " --out '" +
                            (dir / out).string() + "' 2>'" + (dir / (out + ".err")).string() + "' >/dev/null";
    const int raw = std::system(cmd.c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  };
  ASSERT_EQ(run("--set contacts.cam.clearance=0.2", "lash"), 0);
  const Scene s = ohc({"contacts.cam.clearance=0.2"});
  const std::string err = camdyn_test::slurp(dir / "lash.err");
  EXPECT_EQ(err, "camdyn: warning: " + lash_warning(s) + "\n");
  const std::string json = camdyn_test::slurp(dir / "lash" / "summary.json");
  EXPECT_NE(json.find("\"warnings\": [" + camdyn::json_string(lash_warning(s)) + "]"), std::string::npos) << json;

  ASSERT_EQ(run("", "plain"), 0);
  EXPECT_EQ(camdyn_test::slurp(dir / "plain.err"), "");
  EXPECT_NE(camdyn_test::slurp(dir / "plain" / "summary.json").find("\"warnings\": []"), std::string::npos);
  // designer units on the command line (tests/scene/test_scene_units.cpp): the speed in engine rpm
  // replaces the file's rev/s; both forms of one quantity is bad input (exit 2)
  ASSERT_EQ(run("--set cam.speed_rpm=3000 --set cam.rpm_of=engine", "rpm"), 0);
  const std::string hist = camdyn_test::slurp(dir / "plain" / "history.csv");
  EXPECT_GT(hist.size(), 1000u);
  EXPECT_EQ(camdyn_test::slurp(dir / "rpm" / "history.csv"), hist);  // 3000 engine rpm = 25 rev/s
  EXPECT_EQ(run("--set cam.speed_rev_s=25 --set cam.speed_rpm=1500 --set cam.rpm_of=camshaft", "both"), 2);
  EXPECT_EQ(camdyn_test::slurp(dir / "both.err"),
            "camdyn: --set: key 'cam.speed_rpm' = 1500: cannot be given with cam.speed_rev_s (= 25): give the cam "
            "speed once, in rpm or in rev/s\n");
  fs::remove_all(dir);
}

}  // namespace
