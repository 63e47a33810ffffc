// Scene keys in a designer's units (issue 28): cam.speed_rpm + cam.rpm_of and
// run.revolutions are converted at load; a scene given in them runs exactly as the scene
// in rev/s and seconds (history bitwise identical), and every misuse is a SceneError.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/scene_keys.hpp"
#include "camdyn/simulator.hpp"

#ifndef CAMDYN_SOURCE_DIR
#define CAMDYN_SOURCE_DIR "."
#endif

namespace {

using camdyn::Scene;
using camdyn::SceneError;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The OHC example (25 rev/s, t_end 0.04, a 0.2 mm lash) with its [cam] speed and [run]
// t_end lines replaced by `cam_line` and `run_line`.
std::string ohc_with(const std::string& cam_line, const std::string& run_line) {
  std::string t = slurp(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto p = t.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    if (p != std::string::npos) t.replace(p, t.find('\n', p) - p, to);
  };
  replace("speed_rev_s = 25.0", cam_line);
  replace("t_end = 0.04", run_line);
  return t;
}

void expect_same_history(const Scene& a, const Scene& b) {
  const camdyn::RunResult ra = camdyn::simulate(a), rb = camdyn::simulate(b);
  ASSERT_TRUE(ra.summary.finished) << ra.summary.message;
  ASSERT_TRUE(rb.summary.finished) << rb.summary.message;
  ASSERT_EQ(ra.rows.size(), rb.rows.size());
  ASSERT_GT(ra.rows.size(), 100u);
  for (std::size_t i = 0; i < ra.rows.size(); ++i) {
    const auto &x = ra.rows[i], &y = rb.rows[i];
    const double xs[] = {x.t, x.theta, x.u_c, x.v_c, x.a_c, x.contact_force, x.gap, x.kinetic, x.potential,
                         x.work_cam, x.dissipated};
    const double ys[] = {y.t, y.theta, y.u_c, y.v_c, y.a_c, y.contact_force, y.gap, y.kinetic, y.potential,
                         y.work_cam, y.dissipated};
    ASSERT_EQ(std::memcmp(xs, ys, sizeof xs), 0) << "row " << i;
    ASSERT_EQ(x.in_contact, y.in_contact) << "row " << i;
    ASSERT_EQ(x.extra, y.extra) << "row " << i;
  }
  EXPECT_EQ(ra.summary.events.size(), rb.summary.events.size());
}

// Half a camshaft revolution (the lash take-up, the lobe and the seat impact) at 25 rev/s:
// 1500 camshaft rpm and 3000 engine rpm are 25 rev/s; 0.5 revolutions are 0.02 s.
TEST(SceneUnits, RpmAndRevolutionsGiveTheHistoryOfRevPerSecondAndSeconds) {
  const Scene si = camdyn::parse_scene(ohc_with("speed_rev_s = 25.0", "t_end = 0.02"), "si.toml");
  const Scene cam = camdyn::parse_scene(
      ohc_with("speed_rpm = 1500\nrpm_of = \"camshaft\"", "revolutions = 0.5"), "cam.toml");
  const Scene engine = camdyn::parse_scene(
      ohc_with("speed_rpm = 3000.0\nrpm_of = \"engine\"", "revolutions = 0.5"), "engine.toml");
  // converted at load: the scene is in rev/s and seconds
  EXPECT_EQ(cam.cam.speed_rev_s, 25.0);
  EXPECT_EQ(engine.cam.speed_rev_s, 25.0);
  EXPECT_EQ(cam.run.t_end, 0.02);
  EXPECT_EQ(engine.run.t_end, 0.02);
  EXPECT_TRUE(cam == si);
  EXPECT_TRUE(engine == si);
  expect_same_history(si, cam);
  expect_same_history(si, engine);
}

// The paper's rigid case A at a non-round speed: 105 camshaft rpm = 1.75 rev/s, and 2
// revolutions = 2 / 1.75 s; a negative speed runs for |revolutions / speed|.
TEST(SceneUnits, RigidFollowerAndNegativeSpeed) {
  Scene a = camdyn::paper_case("A");
  a.run.t_end = 2.0 / 1.75;
  camdyn::validate(a);
  Scene b = camdyn::paper_case("A");
  camdyn::apply_overrides(b, {"cam.speed_rpm=105", "cam.rpm_of=camshaft", "run.revolutions=2"});
  EXPECT_EQ(b.cam.speed_rev_s, 1.75);
  EXPECT_EQ(b.run.t_end, a.run.t_end);
  expect_same_history(a, b);

  Scene c = camdyn::paper_case("A");
  camdyn::apply_overrides(c, {"run.revolutions=3", "cam.speed_rpm=-210", "cam.rpm_of=engine"});
  EXPECT_EQ(c.cam.speed_rev_s, -1.75);
  EXPECT_EQ(c.run.t_end, 3.0 / 1.75);
}

// --set cam.speed_rpm replaces the scene's cam.speed_rev_s (and run.revolutions its
// run.t_end); to_toml writes rev/s and seconds, which load back to the same scene.
TEST(SceneUnits, SetOverridesTheSceneSpeedAndReadsBack) {
  Scene s = camdyn::parse_scene(ohc_with("speed_rev_s = 25.0", "t_end = 0.04"), "ohc.toml");
  camdyn::apply_overrides(s, {"cam.speed_rpm=6000", "cam.rpm_of=engine"});
  EXPECT_EQ(s.cam.speed_rev_s, 50.0);
  EXPECT_EQ(s.run.t_end, 0.04);  // t_end stays in seconds
  camdyn::apply_override(s, "run.revolutions=4");
  EXPECT_EQ(s.run.t_end, 0.08);
  const std::string toml = camdyn::to_toml(s);
  EXPECT_EQ(toml.find("speed_rpm"), std::string::npos);
  EXPECT_EQ(toml.find("\nrevolutions ="), std::string::npos);
  EXPECT_TRUE(camdyn::parse_scene(toml, "back.toml") == s);
}

struct BadCase {
  std::string cam, run;  // lines of [cam] and [run]
  std::string message;
};

TEST(SceneUnits, ErrorsNameTheKeys) {
  const std::vector<BadCase> cases = {
      {"speed_rev_s = 25\nspeed_rpm = 1500\nrpm_of = \"camshaft\"", "t_end = 0.1",
       "bad.toml:3: key 'cam.speed_rpm' = 1500: cannot be given with cam.speed_rev_s (= 25): give the cam speed "
       "once, in rpm or in rev/s"},
      {"speed_rpm = 1500", "t_end = 0.1",
       "bad.toml:2: key 'cam.speed_rpm' = 1500: needs cam.rpm_of = \"camshaft\" (rpm of the camshaft) or "
       "\"engine\" (rpm of a four-stroke engine's crankshaft: the camshaft turns at half of it)"},
      {"speed_rpm = 1500\nrpm_of = \"crank\"", "t_end = 0.1",
       "bad.toml:3: key 'cam.rpm_of' = \"crank\": must be one of \"camshaft\", \"engine\""},
      {"rpm_of = \"engine\"", "t_end = 0.1", "bad.toml:2: key 'cam.rpm_of' = \"engine\": is only used with cam.speed_rpm"},
      {"speed_rpm = \"fast\"\nrpm_of = \"engine\"", "t_end = 0.1",
       "bad.toml:2: key 'cam.speed_rpm' = \"fast\": must be a number"},
      {"speed_rpm = inf\nrpm_of = \"engine\"", "t_end = 0.1",
       "bad.toml:2: key 'cam.speed_rpm' = inf: must be a finite number, at most 1e50 in absolute value"},
      {"speed_rev_s = 25", "t_end = 0.1\nrevolutions = 2",
       "bad.toml:5: key 'run.revolutions' = 2: cannot be given with run.t_end (= 0.1): give the run's length "
       "once, in revolutions or in time"},
      {"speed_rev_s = 25", "revolutions = 0", "bad.toml:4: key 'run.revolutions' = 0: must be > 0"},
      {"speed_rev_s = 0", "revolutions = 2",
       "bad.toml:4: key 'run.revolutions' = 2: needs a cam speed other than 0 (cam.speed_rev_s = 0)"},
      {"speed_table_t = [0, 1]\nspeed_table_rev_s = [1, 2]", "revolutions = 2",
       "bad.toml:5: key 'run.revolutions' = 2: needs a constant cam speed (a speed table is given): give "
       "run.t_end"},
  };
  for (const auto& c : cases) {
    const std::string text = "[cam]\n" + c.cam + "\n[run]\n" + c.run + "\n";
    try {
      camdyn::parse_scene(text, "bad.toml");
      ADD_FAILURE() << "no error for:\n" << text;
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()), c.message) << text;
    }
  }
}

TEST(SceneUnits, SetErrorsNameBothKeys) {
  Scene s = camdyn::default_scene();
  const Scene before = s;
  try {
    camdyn::apply_overrides(s, {"cam.speed_rev_s=3", "cam.speed_rpm=1500", "cam.rpm_of=camshaft"});
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--set: key 'cam.speed_rpm' = 1500: cannot be given with cam.speed_rev_s (= 3): give the cam speed "
              "once, in rpm or in rev/s");
  }
  try {
    camdyn::apply_overrides(s, {"run.t_end=1", "run.revolutions=2"});
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--set: key 'run.revolutions' = 2: cannot be given with run.t_end (= 1): give the run's length once, "
              "in revolutions or in time");
  }
  EXPECT_TRUE(s == before);
}

TEST(SceneUnits, UnknownKeyMessageListsThem) {
  try {
    camdyn::parse_scene("[run]\nrevs = 3\n", "bad.toml");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("allowed keys in [run]: t_end, revolutions, output_dt"), std::string::npos)
        << e.what();
  }
}

TEST(SceneUnits, DocumentedAsInputOnly) {
  int n = 0;
  for (const auto& k : camdyn::scene_keys())
    if (k.input_only) {
      ++n;
      EXPECT_TRUE(k.key == "cam.speed_rpm" || k.key == "cam.rpm_of" || k.key == "run.revolutions") << k.key;
    }
  EXPECT_EQ(n, 3);
}

}  // namespace
