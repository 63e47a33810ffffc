// One Cam per cam spec (src/scene/shared_cam.hpp): a run's parts share the cam its checks
// built. The cache must never hand out a cam of another spec: specs equal key by key share
// one object, any key that differs gives another (checked against a Cam built directly), a
// lift-table file rewritten on disk is read again, and a spec that fails is not kept.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <camdyn/cam.hpp>
#include <camdyn/lift_table.hpp>
#include <camdyn/scene.hpp>

#include "scene/shared_cam.hpp"

namespace camdyn {
namespace {

CamSpec law_cam(double lift) {
  CamSpec c;
  c.profile = CamProfileKind::Law;
  c.law = "dwell 150; poly345 100 " + std::to_string(lift) + "; poly345 110 -" + std::to_string(lift);
  c.base_radius = 2.0;
  return c;
}

TEST(SharedCam, EqualSpecsShareOneCamAndADifferentKeyGetsItsOwn) {
  const CamSpec a = law_cam(0.4);
  const auto c1 = detail::shared_cam(a);
  const auto c2 = detail::shared_cam(CamSpec(a));
  EXPECT_EQ(c1.get(), c2.get());
  CamSpec b = a;
  b.base_radius = 2.5;  // one key differs
  const auto c3 = detail::shared_cam(b);
  EXPECT_NE(c1.get(), c3.get());
  const Cam direct(b);
  for (double th : {0.0, 2.7, 4.4}) EXPECT_EQ(c3->evaluate(th).X_C, direct.evaluate(th).X_C);
  CamSpec s = a;
  s.speed_rev_s = 9.0;  // a drive key: also part of the spec compared
  EXPECT_NE(detail::shared_cam(s).get(), c1.get());
}

TEST(SharedCam, ARewrittenLiftTableIsReadAgain) {
  const std::string dir = (std::filesystem::temp_directory_path() / "camdyn_shared_cam").string();
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/t.csv";
  CamSpec t;
  t.profile = CamProfileKind::Table;
  t.lift_table = path;
  t.base_radius = 2.0;
  { std::ofstream(path) << lift_table_csv(lift_table_of(Cam(law_cam(0.4)), 360)); }
  const auto first = detail::shared_cam(t);
  EXPECT_NEAR(first->lift(), 0.4, 1e-9);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // a later modification time
  { std::ofstream(path) << lift_table_csv(lift_table_of(Cam(law_cam(0.3)), 360)); }
  const auto second = detail::shared_cam(t);
  EXPECT_NE(first.get(), second.get());
  EXPECT_NEAR(second->lift(), 0.3, 1e-9);
  EXPECT_NEAR(first->lift(), 0.4, 1e-9);  // a holder's cam is untouched
}

TEST(SharedCam, AFailingSpecThrowsEveryTime) {
  CamSpec bad;
  bad.profile = CamProfileKind::Table;
  bad.lift_table = "/nonexistent/camdyn_table.csv";
  for (int i = 0; i < 2; ++i) {
    try {
      detail::shared_cam(bad);
      FAIL() << "no error";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), "cam.lift_table");
    }
  }
}

}  // namespace
}  // namespace camdyn
