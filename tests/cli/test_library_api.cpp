// The library as a caller uses it (issue 17): overrides applied together and validated
// once, and the reason a caller's stop flag gives.
#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

TEST(LibraryApi, OverridesAreValidatedOnceInEitherOrder) {
  const Scene base = paper_case("A");  // t_end = 1, output_dt = 1e-4
  Scene a = base, b = base;
  apply_overrides(a, {"run.t_end=5e-7", "run.output_dt=5e-7"});
  apply_overrides(b, {"run.output_dt=5e-7", "run.t_end=5e-7"});
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.run.t_end, 5e-7);
  EXPECT_EQ(a.run.output_dt, 5e-7);
  // one at a time, the first order breaks output_dt <= t_end in between
  Scene c = base;
  EXPECT_THROW(apply_override(c, "run.t_end=5e-7"), SceneError);
  EXPECT_EQ(c, base);  // unchanged on error
}

TEST(LibraryApi, OverridesErrorLeavesSceneUnchangedAndNamesSet) {
  Scene s = paper_case("A");
  const Scene before = s;
  try {
    apply_overrides(s, {"cam.speed_rev_s=3", "spring.stiffness=-1"});
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "--set");
    EXPECT_EQ(e.key(), "spring.stiffness");
  }
  EXPECT_EQ(s, before);
  EXPECT_THROW(apply_overrides(s, {"cam.nope=1"}), SceneError);
  EXPECT_THROW(apply_overrides(s, {"no_equals"}), SceneError);
}

TEST(LibraryApi, OverridesRederiveAutomaticTolerance) {
  Scene s = paper_case("A");  // rigid: tol_u = 1e-8 (the paper default, "automatic")
  apply_overrides(s, {"follower.kind=elastic_bar", "cam.speed_rev_s=2"});
  EXPECT_EQ(s.contact.tol_u, 1e-7);
  Scene t = paper_case("A");
  apply_overrides(t, {"follower.kind=elastic_bar", "contact.tol_u=3e-9"});
  EXPECT_EQ(t.contact.tol_u, 3e-9);
  Scene u = paper_case("A");  // empty list: nothing changes
  apply_overrides(u, {});
  EXPECT_EQ(u, paper_case("A"));
}

TEST(LibraryApi, StopFlagReasonIsTheCallers) {
  Scene s = paper_case("A");
  s.run.t_end = 0.01;
  Simulator sim(s);
  std::atomic<bool> stop{true};
  const Summary by_caller = sim.run(nullptr, &stop, "stopped by caller");
  EXPECT_FALSE(by_caller.finished);
  EXPECT_NE(by_caller.message.find("stopped by caller"), std::string::npos) << by_caller.message;
  const Summary by_default = sim.run(nullptr, &stop);
  // The default reason is the caller's stop, not a signal (issue 27: the CLI names its signal).
  EXPECT_NE(by_default.message.find("stopped by caller"), std::string::npos)
      << by_default.message;
  std::atomic<bool> go{false};
  EXPECT_TRUE(sim.run(nullptr, &go, "stopped by caller").finished);
}

}  // namespace
}  // namespace camdyn
