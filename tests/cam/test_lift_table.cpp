// camdyn — lift tables in CSV (issue 37): a round trip (a law cam exported, read back and
// run as a cam.profile = "lift" spline) reproduces the cam, and bad tables are refused
// naming line and column.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <camdyn/cam.hpp>
#include <camdyn/lift_table.hpp>
#include <camdyn/scene.hpp>

using namespace camdyn;

TEST(LiftTable, RoundTripReproducesTheCam) {
  // A flat face on a poly4567 rise/return (C3 joints): the periodic cubic spline through
  // the 0.1° table read back is within its interpolation error h⁴ max|L⁗|·5/384 of the law.
  CamSpec law;
  law.profile = CamProfileKind::Law;
  law.law = "poly4567 100 0.8; dwell 20; poly4567 100 -0.8; dwell 140";
  law.base_radius = 2.0;
  const Cam cam(law);
  const LiftTable t = lift_table_of(cam, 3600);
  const std::string csv = lift_table_csv(t);
  const LiftTable back = parse_lift_table_csv("# exported by camdyn\n" + csv, "<csv>");
  ASSERT_EQ(back.angle_deg.size(), 3600u);
  for (std::size_t i = 0; i < t.lift.size(); ++i) {
    ASSERT_EQ(back.angle_deg[i], t.angle_deg[i]);  // shortest round-trip text: exact
    ASSERT_EQ(back.lift[i], t.lift[i]);
    ASSERT_EQ(back.dlift_ddeg[i], t.dlift_ddeg[i]);
  }
  // The derivative columns against the law's closed form at 40° (x = 0.4 of the rise):
  // poly4567 L = h(35x⁴ − 84x⁵ + 70x⁶ − 20x⁷), dL/dθ = L_x / β.
  const double x = 0.4, beta = 100.0;
  const double Lx = 0.8 * (140 * std::pow(x, 3) - 420 * std::pow(x, 4) + 420 * std::pow(x, 5) - 140 * std::pow(x, 6));
  EXPECT_NEAR(back.dlift_ddeg[400], Lx / beta, 1e-15);
  CamSpec lift;
  lift.profile = CamProfileKind::Lift;
  lift.base_radius = 2.0;
  lift.lift_angles_deg = back.angle_deg;
  lift.lift = back.lift;
  const Cam spline(lift);
  double err = 0;
  for (int i = 0; i < 7200; ++i) {
    const double th = 6.283185307179586 * (i + 0.5) / 7200;
    err = std::max(err, std::abs(spline.evaluate(th).X_C - cam.evaluate(th).X_C));
  }
  std::printf("lift table round trip (0.1° rows, spline): |X_C − law| ≤ %.3g\n", err);
  EXPECT_LT(err, 1e-9 * 0.8);
  EXPECT_NEAR(spline.lift(), cam.lift(), 1e-9);
}

TEST(LiftTable, BadTablesNameLineAndColumn) {
  auto error = [](const std::string& text) -> std::string {
    try {
      parse_lift_table_csv(text, "t.csv");
    } catch (const SceneError& e) {
      return e.what();
    }
    return "<no error>";
  };
  EXPECT_NE(error("angle,lift\n0,0\n").find("t.csv:1"), std::string::npos) << error("angle,lift\n0,0\n");
  const std::string rows = "angle_deg,lift\n0,0\n90,0.5\n180,1\n";
  EXPECT_NE(error(rows + "170,0\n").find("strictly increasing"), std::string::npos);
  EXPECT_NE(error(rows + "270,x\n").find("t.csv:5"), std::string::npos);
  EXPECT_NE(error(rows + "270,nan\n").find("finite"), std::string::npos);
  EXPECT_NE(error(rows + "270,0,1\n").find("2 numbers"), std::string::npos);
  EXPECT_NE(error(rows).find("at least 4 rows"), std::string::npos);
  EXPECT_NE(error(rows + "360,0\n").find("less than 360"), std::string::npos);
  EXPECT_EQ(parse_lift_table_csv(rows + "270,0.5\n", "t.csv").lift.size(), 4u);
}

TEST(LiftTable, CamCommandWritesTheTableOfTheArcExample) {
  // `camdyn cam` on examples/arc_cam_dwell.toml writes lift_table.csv; read back, its
  // largest lift is the dwell's R_d − R_b = 8 (roller centre: (28 + 6) − (20 + 6) on the axis
  // offset 1.5: √(34² − 1.5²) − √(26² − 1.5²)).
  const std::string dir = ::testing::TempDir() + "camdyn_lift_table_cli";
  const std::string cmd = std::string(CAMDYN_CLI_PATH) + " cam " + CAMDYN_SOURCE_DIR +
                          "/examples/arc_cam_dwell.toml --out " + dir + " --points 720 --no-plot --quiet";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(dir + "/lift_table.csv");
  std::stringstream ss;
  ss << in.rdbuf();
  const LiftTable t = parse_lift_table_csv(ss.str(), "lift_table.csv");
  ASSERT_EQ(t.angle_deg.size(), 720u);
  ASSERT_EQ(t.dlift_ddeg.size(), 720u);
  double top = 0;
  for (double L : t.lift) top = std::max(top, L);
  EXPECT_NEAR(top, std::sqrt(34.0 * 34.0 - 2.25) - std::sqrt(26.0 * 26.0 - 2.25), 1e-12);
}
