// A run validates its scene exactly once, after every --set (issue 34 item 4, issue 35 items
// 4 and 5): the one validation function counts its calls (scene/validation_count.hpp), and
// each way a run is started — the CLI's and Python's path (a ValidatedScene from the loader
// with the overrides, then the Simulator), a Scene given to the Simulator, a batch of
// validated scenes — adds exactly one per scene.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "camdyn/batch.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "scene/validation_count.hpp"
#include "test_support.hpp"

namespace {

using camdyn::scene_detail::validation_count;

const std::string kScene = std::string(CAMDYN_SOURCE_DIR) + "/examples/ohv_pushrod_train.toml";
const std::vector<std::string> kShort{"run.t_end=2e-4", "run.output_dt=1e-4"};

TEST(ValidatedScene, TheLoaderWithOverridesThenTheSimulatorValidatesOnce) {
  const auto before = validation_count();
  const camdyn::ValidatedScene v = camdyn::load_validated_scene(kScene, kShort);
  EXPECT_EQ(validation_count() - before, 1u);
  camdyn::Simulator sim(v);
  const camdyn::Summary s = sim.run();
  EXPECT_TRUE(s.finished) << s.message;
  EXPECT_EQ(validation_count() - before, 1u);  // the Simulator did not check it again
  EXPECT_EQ(v->run.t_end, 2e-4);               // the overrides are in the validated scene
}

TEST(ValidatedScene, ASceneGivenToTheSimulatorIsValidatedOnce) {
  const camdyn::Scene sc = camdyn::load_validated_scene(kScene, kShort).scene();
  const auto before = validation_count();
  camdyn::Simulator sim(sc);
  EXPECT_EQ(validation_count() - before, 1u);
  // validated() with overrides: the overrides' one check, not a second one.
  const auto mid = validation_count();
  const camdyn::ValidatedScene v = camdyn::validated(sc, {"cam.speed_rev_s=20"});
  EXPECT_EQ(validation_count() - mid, 1u);
  EXPECT_EQ(v->cam.speed_rev_s, 20.0);
}

TEST(ValidatedScene, ABatchOfValidatedScenesIsNotCheckedAgain) {
  std::vector<camdyn::ValidatedScene> scenes;
  for (const char* speed : {"cam.speed_rev_s=15", "cam.speed_rev_s=20"}) {
    std::vector<std::string> sets = kShort;
    sets.emplace_back(speed);
    scenes.push_back(camdyn::load_validated_scene(kScene, sets));
  }
  const auto before = validation_count();
  const std::vector<camdyn::Summary> sums = camdyn::run_batch(scenes, 1);
  EXPECT_EQ(validation_count() - before, 0u);
  ASSERT_EQ(sums.size(), 2u);
  for (const auto& s : sums) EXPECT_TRUE(s.finished) << s.message;
}

// The validation is the same one: what the loader refuses, validated() refuses with the same
// message, and the Simulator of a Scene too.
TEST(ValidatedScene, TheSameRulesOnEveryPath) {
  camdyn::Scene sc = camdyn::load_validated_scene(kScene, kShort).scene();
  sc.run.t_end = -1.0;
  std::string a, b;
  try {
    camdyn::validated(sc);
  } catch (const camdyn::SceneError& e) {
    a = e.what();
  }
  try {
    camdyn::Simulator sim(sc);
  } catch (const camdyn::SceneError& e) {
    b = e.what();
  }
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_NE(a.find("run.t_end"), std::string::npos) << a;
}

}  // namespace
