// A camshaft whose drive station turns at the crank's law exactly (camshaft.drive =
// "prescribed", issue 40 item 1; src/mechanism/camshaft.hpp): the station is no unknown, its
// cams are prescribed cams at θ_crank(t) − offset, its segments drive their other stations.
// Checked against independent truth:
//   * a rigid shaft (one station, prescribed) is today's prescribed cam: the same follower
//     motion as the scene without a [camshaft], to round-off;
//   * two stations, the drive station prescribed and the cam on the other: the segment is the
//     drive coupling of the two-degree-of-freedom model (k = GJ/L, c = βGJ/L), integrated here
//     by RK4 (camshaft_test_support.hpp), through an impact, a lift-off and the landing;
//   * energy: the drive's work (the segment's power and the prescribed cams' F Ẋ) =
//     dissipated + stored;
//   * bad input: the coupling's keys with a prescribed drive name the key.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "../network_run_support.hpp"
#include "camshaft_test_support.hpp"

namespace camdyn {
namespace {

using camshaft_test::Model;
using camshaft_test::num;
using camshaft_test::TwoDof;
using camshaft_test::two_dof_toml;

double largest_difference(const camdyn_test::NetRun& a, const camdyn_test::NetRun& b, const std::string& col) {
  EXPECT_EQ(a.rows.size(), b.rows.size());
  double err = 0.0;
  for (std::size_t i = 0; i < std::min(a.rows.size(), b.rows.size()); ++i)
    err = std::max(err, std::abs(a.col(a.rows[i], col) - b.col(b.rows[i], col)));
  return err;
}

void expect_rigid_shaft_is_the_prescribed_cam(const std::string& model) {
  TwoDof p;
  p.model = model;
  p.speed = model == "penalty" ? 42.0 : 25.0;
  const double t_end = 0.03;
  const std::string base = two_dof_toml(p, false, t_end);
  const camdyn_test::NetRun fixed = camdyn_test::run_keeping_rows(parse_scene(base, "<test>"));
  const camdyn_test::NetRun shaft = camdyn_test::run_keeping_rows(
      parse_scene(base + "[camshaft]\ninertias = [1e-4]\ncam_stations = [0]\ndrive = \"prescribed\"\n", "<test>"));
  ASSERT_EQ(shaft.sum.termination, Termination::Finished) << shaft.sum.message;
  EXPECT_EQ(shaft.sum.contacts[0].impacts, fixed.sum.contacts[0].impacts);
  EXPECT_EQ(shaft.sum.contacts[0].separations, fixed.sum.contacts[0].separations);
  // measured: bitwise equal (0) on penalty, event and Lee (the crank's law without orders is θ(t))
  EXPECT_LT(largest_difference(shaft, fixed, "u_f"), 1e-15);
  EXPECT_LT(largest_difference(shaft, fixed, "F_cam"), 1e-9);
}
TEST(CamshaftPrescribed, RigidShaftIsThePrescribedCamPenalty) { expect_rigid_shaft_is_the_prescribed_cam("penalty"); }
TEST(CamshaftPrescribed, RigidShaftIsThePrescribedCamEvent) { expect_rigid_shaft_is_the_prescribed_cam("event"); }
TEST(CamshaftPrescribed, RigidShaftIsThePrescribedCamLee) { expect_rigid_shaft_is_the_prescribed_cam("lee"); }

// The two-station shaft: station 0 prescribed, the cam on station 1 of inertia J, the segment
// k_d with β = c_d/k_d: station 1 moves as the one-station shaft of the compliant model.
std::string two_station_toml(const TwoDof& p, double t_end) {
  return two_dof_toml(p, false, t_end) + "[camshaft]\ninertias = [3e-4, " + num(p.J) + "]\nstiffnesses = [" +
         num(p.kd) + "]\nrayleigh_beta = " + num(p.cd / p.kd) + "\ncam_stations = [1]\ndrive = \"prescribed\"\n";
}

TEST(CamshaftPrescribed, TwoStationsAgainstTheTwoDofModel) {
  const TwoDof p;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(parse_scene(two_station_toml(p, 0.03), "<test>"));
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  EXPECT_GE(r.sum.contacts[0].impacts, 3);
  EXPECT_GE(r.sum.contacts[0].separations, 2);
  const Model model{p};
  Eigen::Vector4d y(0.0, 0.0, p.theta0, model.omega());
  double t = 0.0, err_x = 0.0, err_phi = 0.0;
  for (const HistoryRow& row : r.rows) {
    if (row.t > t) {
      y = model.advance(t, y, row.t, 2e-7);
      t = row.t;
    }
    err_x = std::max(err_x, std::abs(r.col(row, "u_f") - y[0]));
    err_phi = std::max(err_phi, std::abs(r.col(row, "u_shaft_1") - y[2]));
    // the prescribed station is on the crank: no twist of the drive, the wind-up is the segment's
    EXPECT_EQ(r.col(row, "drive_twist"), 0.0);
    EXPECT_NEAR(r.col(row, "windup_cam0"), p.theta0 + model.omega() * row.t - y[2], 1e-9);
  }
  // measured: 5.7e-12 m, 2.1e-11 rad (rtol 1e-10)
  EXPECT_LT(err_x, 1e-10);
  EXPECT_LT(err_phi, 2e-10);
}

TEST(CamshaftPrescribed, DriveWorkIsDissipatedPlusStored) {
  TwoDof p;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(parse_scene(two_station_toml(p, 0.02), "<test>"));
  ASSERT_EQ(r.sum.termination, Termination::Finished);
  const HistoryRow& last = r.rows.back();
  const double W = last.work_cam, D = last.dissipated;
  EXPECT_GT(D, 0.0);
  const double residual = std::abs(W - D - last.kinetic + r.rows.front().kinetic - last.potential);
  // measured: 3.3e-10 J of W = 0.073 J
  EXPECT_LT(residual, 1e-7 * std::max(std::abs(W), D));
}

TEST(CamshaftPrescribed, CouplingKeysAreRefused) {
  TwoDof p;
  const std::string s = two_dof_toml(p, false, 0.01) + "[camshaft]\ninertias = [1e-4]\ncam_stations = [0]\n"
                                                        "drive = \"prescribed\"\n";
  for (const char* key : {"drive_stiffness", "drive_damping"}) {
    try {
      parse_scene(s + key + " = 10.0\n", "<test>");
      ADD_FAILURE() << "no SceneError for " << key;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), std::string("camshaft.") + key) << e.what();
    }
  }
}

}  // namespace
}  // namespace camdyn
