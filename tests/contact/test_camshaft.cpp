// The camshaft as a body (issue 40, [camshaft]; src/mechanism/camshaft.hpp), against
// independent truth:
//   * the shaft alone: torsional natural frequencies of a two-inertia shaft (the quadratic's
//     closed form) and of a uniform shaft lumped in N stations (the chain's exact
//     2√(k/J) sin((2n − 1)π/(4N)), which tends to the continuous (2n − 1)π/2 √(GJ/(ρI_p L²)));
//   * a constant torque: the bearing drag αJω of a shaft turning at constant speed twists
//     every segment and the drive coupling by the static twist of the torque beyond it;
//   * one cam on a compliant shaft with a rigid follower (penalty contact) against the same
//     two-degree-of-freedom model integrated here by RK4, through an impact and a lift-off;
//     Lee's method against the event method on the same shaft;
//   * the stiff-shaft limit: as the drive and shaft stiffness grow, the follower's motion
//     converges to the run with the cam at its prescribed angle (no [camshaft]);
//   * energy: drive work = dissipated + change of stored energy over a revolution;
//   * bad input: SceneError naming the key.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "mechanism/mechanism.hpp"
#include "../network_run_support.hpp"
#include "camshaft_test_support.hpp"

namespace camdyn {
namespace {

using camshaft_test::kPi;
using camshaft_test::Model;
using camshaft_test::TwoDof;
using camshaft_test::two_dof_toml;

// The shaft's stations' block of M and K (the follower "f" is decoupled: its cam never
// touches in these scenes).
void shaft_blocks(const Mechanism& mech, Eigen::MatrixXd& M, Eigen::MatrixXd& K) {
  const CamShaft* cs = mech.camshaft();
  ASSERT_NE(cs, nullptr);
  const Eigen::MatrixXd Mf = Eigen::MatrixXd(mech.M()), Kf = Eigen::MatrixXd(mech.K());
  const int N = cs->stations();
  M.resize(N, N);
  K.resize(N, N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      M(i, j) = Mf(cs->station_dof(i), cs->station_dof(j));
      K(i, j) = Kf(cs->station_dof(i), cs->station_dof(j));
    }
}

Eigen::VectorXd frequencies(const Mechanism& mech) {
  Eigen::MatrixXd M, K;
  shaft_blocks(mech, M, K);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  return es.eigenvalues().cwiseSqrt();  // ascending
}

// A scene whose shaft is given by its [camshaft] lines; the follower's cam contact is 1 m
// away (never touches).
Scene shaft_scene(const std::string& camshaft_lines) {
  TwoDof p;
  p.g0 = 1.0;
  std::string s = two_dof_toml(p, false, 0.01);
  s += "[camshaft]\n" + camshaft_lines;
  return parse_scene(s, "<test>");
}

std::string list(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", v[i]);
    s += (i ? ", " : "") + std::string(b);
  }
  return s + "]";
}

TEST(CamshaftModel, TwoInertiaFrequencies) {
  // J₁ at the drive (k_d to the crank, held fixed for the vibration), k between J₁ and J₂:
  // J₁J₂ω⁴ − (J₁k + J₂(k_d + k))ω² + k_d k = 0. Measured: equal to round-off.
  const double J1 = 2e-4, J2 = 5e-4, k = 800.0, kd = 300.0;
  const Scene sc = shaft_scene("inertias = " + list({J1, J2}) + "\nstiffnesses = " + list({k}) +
                               "\ncam_stations = [1]\ndrive_stiffness = " + std::to_string(kd) + "\n");
  const Mechanism mech(sc);
  const Eigen::VectorXd w = frequencies(mech);
  const double a = J1 * J2, b = -(J1 * k + J2 * (kd + k)), c = kd * k;
  const double disc = std::sqrt(b * b - 4 * a * c);
  const double w1 = std::sqrt((-b - disc) / (2 * a)), w2 = std::sqrt((-b + disc) / (2 * a));
  EXPECT_NEAR(w[0], w1, 1e-12 * w1);
  EXPECT_NEAR(w[1], w2, 1e-12 * w2);
}

TEST(CamshaftModel, UniformShaftFrequencies) {
  // A uniform shaft of length L, torsional stiffness GJ, polar inertia per length ρI_p, clamped
  // at the crank (x = 0) and free at x = L, lumped in N stations at x = h … L (h = L/N): the
  // drive coupling is the first segment GJ/h, the stations carry ρI_p h (the last ρI_p h/2).
  // The chain's exact frequencies: ω_n = 2√(k/J) sin((2n − 1)π/(4N)), k = GJ/h, J = ρI_p h;
  // the continuous shaft's: (2n − 1)π/2 · √(GJ/(ρI_p L²)).
  const double L = 0.4, GJ = 2000.0, rho_ip = 2e-3;
  const double w_cont1 = kPi / 2 * std::sqrt(GJ / (rho_ip * L * L));
  double err_prev = NAN;
  for (int N : {8, 16, 32}) {
    const double h = L / N, k = GJ / h, J = rho_ip * h;
    std::vector<double> inertias(N, J), stiff(N - 1, k);
    inertias.back() = J / 2;
    const Scene sc = shaft_scene("inertias = " + list(inertias) + "\nstiffnesses = " + list(stiff) +
                                 "\ncam_stations = [0]\ndrive_stiffness = " + std::to_string(k) + "\n");
    const Mechanism mech(sc);
    const Eigen::VectorXd w = frequencies(mech);
    for (int n = 1; n <= 3; ++n) {
      const double exact = 2 * std::sqrt(k / J) * std::sin((2 * n - 1) * kPi / (4 * N));
      EXPECT_NEAR(w[n - 1], exact, 1e-10 * exact) << "N " << N << " mode " << n;
    }
    // the lumped shaft tends to the continuous one at second order: 3.2e-3, 8.0e-4, 2.0e-4
    const double err = std::abs(w[0] - w_cont1) / w_cont1;
    if (!std::isnan(err_prev)) EXPECT_NEAR(err_prev / err, 4.0, 0.05) << "N " << N;
    err_prev = err;
  }
  EXPECT_LT(err_prev, 3e-4);
}

TEST(CamshaftRun, BearingDragTwistsTheShaftStatically) {
  // Three stations turning at ω with bearing drag α: station i carries the torque αJ_iω; in
  // the steady state each segment twists by the drag of the stations beyond it over its
  // stiffness, the drive coupling by the whole drag over k_d (β damps the transient).
  const std::vector<double> J{2e-4, 3e-4, 4e-4}, k{900.0, 600.0};
  const double kd = 400.0, alpha = 20.0, beta = 1e-3;
  Scene sc = shaft_scene("inertias = " + list(J) + "\nstiffnesses = " + list(k) +
                         "\ncam_stations = [2]\ndrive_stiffness = " + std::to_string(kd) +
                         "\ndrive_damping = 0.6\nrayleigh_alpha = " + std::to_string(alpha) +
                         "\nrayleigh_beta = " + std::to_string(beta) + "\n");
  sc.run.t_end = 0.3;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(sc);
  ASSERT_EQ(r.sum.termination, Termination::Finished);
  const HistoryRow& last = r.rows.back();
  const double w = 2 * kPi * sc.cam.speed_rev_s;
  const double crank = sc.cam.theta0_deg * kPi / 180 + w * last.t;
  const double tau0 = alpha * w * (J[0] + J[1] + J[2]), tau1 = alpha * w * (J[1] + J[2]), tau2 = alpha * w * J[2];
  const double phi0 = r.col(last, "u_shaft_0"), phi1 = r.col(last, "u_shaft_1"), phi2 = r.col(last, "u_shaft_2");
  // measured: the three twists 3e-12, 4e-12, 4e-12 of their closed forms, the drive torque 8e-13
  EXPECT_NEAR(crank - phi0, tau0 / kd, 1e-9 * tau0 / kd);
  EXPECT_NEAR(phi0 - phi1, tau1 / k[0], 1e-9 * tau1 / k[0]);
  EXPECT_NEAR(phi1 - phi2, tau2 / k[1], 1e-9 * tau2 / k[1]);
  // the drive torque column: the whole drag
  EXPECT_NEAR(r.col(last, "drive_torque"), tau0, 1e-9 * tau0);
}

TEST(CamshaftRun, OneCamOnACompliantShaftAgainstTheTwoDofModel) {
  const TwoDof p;
  const double t_end = 0.03;  // 1.26 revolutions: the fall onto the cam, lift-off near the nose, re-impact
  const Scene sc = parse_scene(two_dof_toml(p, true, t_end), "<test>");
  {  // the closed form of the lift used by the model is the cam's
    const Cam cam(sc.cam);
    for (double th : {0.3, 1.7, 3.0}) {
      const double X = cam.motion(th, 1.0, 0.0).X - cam.motion(kPi, 1.0, 0.0).X;
      ASSERT_NEAR(X, p.e * (1 + std::cos(th)), 1e-12);
    }
  }
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(sc);
  ASSERT_EQ(r.sum.termination, Termination::Finished);
  EXPECT_GE(r.sum.contacts[0].impacts, 3);
  EXPECT_GE(r.sum.contacts[0].separations, 2);
  const Model model{p};
  Eigen::Vector4d y(0.0, 0.0, p.theta0, model.omega());
  double t = 0.0, err_x = 0.0, err_phi = 0.0, x_scale = 0.0;
  for (const HistoryRow& row : r.rows) {
    if (row.t > t) {
      y = model.advance(t, y, row.t, 2e-7);
      t = row.t;
    }
    err_x = std::max(err_x, std::abs(r.col(row, "u_f") - y[0]));
    err_phi = std::max(err_phi, std::abs(r.col(row, "u_shaft_0") - y[2]));
    x_scale = std::max(x_scale, std::abs(y[0]));
  }
  // measured: 5.7e-12 m of the follower's 8 mm travel, 2.1e-11 rad (camdyn at rtol 1e-10 and
  // 1e-12 agree to 4.5e-10 m; the reference at h = 1e-6 and 5e-7 to 1e-12 m)
  EXPECT_LT(err_x, 1e-10);
  EXPECT_LT(err_phi, 2e-10);
}

// The largest difference of the follower's displacement between a camshaft run and the run
// with the cam at its prescribed angle.
double stiff_limit_error(double kd, const std::string& model) {
  TwoDof p;
  p.model = model;
  p.speed = 25.0;  // below the lift-off speed: the follower stays on the cam after its landing
  p.kd = kd;
  p.cd = 2 * 0.05 * std::sqrt(kd * p.J);  // 5 % of critical: the start's twist transient decays
  const double t_end = 0.02;
  const Scene shaft = parse_scene(two_dof_toml(p, true, t_end), "<test>");
  const Scene fixed = parse_scene(two_dof_toml(p, false, t_end), "<test>");
  const camdyn_test::NetRun a = camdyn_test::run_keeping_rows(shaft), b = camdyn_test::run_keeping_rows(fixed);
  EXPECT_EQ(a.rows.size(), b.rows.size());
  double err = 0.0;
  for (std::size_t i = 0; i < std::min(a.rows.size(), b.rows.size()); ++i)
    err = std::max(err, std::abs(a.col(a.rows[i], "u_f") - b.col(b.rows[i], "u_f")));
  return err;
}

void expect_stiff_limit(const std::string& model) {
  // The follower's motion error against the prescribed cam falls like 1/k_d: the shaft's
  // twist under the contact torque is τ/k_d.
  const double e1 = stiff_limit_error(1e3, model), e2 = stiff_limit_error(1e4, model),
               e3 = stiff_limit_error(1e5, model);
  // measured (k_d = 1e3, 1e4, 1e5 N m/rad): penalty 2.9e-7, 3.6e-8, 2.9e-9 m; event and Lee
  // 2.9e-7, 2.9e-8, 2.9e-9 m
  EXPECT_LT(e2, 0.2 * e1);
  EXPECT_LT(e3, 0.2 * e2);
  EXPECT_LT(e3, 1e-8);
}
TEST(CamshaftRun, StiffShaftLimitIsThePrescribedCamPenalty) { expect_stiff_limit("penalty"); }
TEST(CamshaftRun, StiffShaftLimitIsThePrescribedCamEvent) { expect_stiff_limit("event"); }
TEST(CamshaftRun, StiffShaftLimitIsThePrescribedCamLee) { expect_stiff_limit("lee"); }

TEST(CamshaftRun, LeeAndEventAgreeOnACompliantShaft) {
  // Two formulations of the rigid contact (Lee's located step, the event method's held
  // constraint and roots) on the same compliant shaft: the fall onto the cam with restitution
  // 0.3, its bounces, then the follower held on the cam over the lift. Measured: 6.5e-14 m.
  TwoDof p;
  p.speed = 25.0;
  p.kd = 1e4;
  p.cd = 2 * 0.05 * std::sqrt(p.kd * p.J);
  p.model = "lee";
  const camdyn_test::NetRun a = camdyn_test::run_keeping_rows(parse_scene(two_dof_toml(p, true, 0.02), "<test>"));
  p.model = "event";
  const camdyn_test::NetRun b = camdyn_test::run_keeping_rows(parse_scene(two_dof_toml(p, true, 0.02), "<test>"));
  ASSERT_EQ(a.rows.size(), b.rows.size());
  double err = 0.0;
  for (std::size_t i = 0; i < a.rows.size(); ++i)
    err = std::max(err, std::abs(a.col(a.rows[i], "u_f") - b.col(b.rows[i], "u_f")));
  EXPECT_LT(err, 1e-10);
}

void expect_energy_balance(const std::string& model) {
  // One revolution with the drive damper and the contact's damping or impacts:
  // W_drive = ΔT + ΔV + D (the run's energy residual) to the run's tolerance.
  TwoDof p;
  p.model = model;
  const Scene sc = parse_scene(two_dof_toml(p, true, 0.02), "<test>");
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(sc);
  ASSERT_EQ(r.sum.termination, Termination::Finished);
  const HistoryRow& last = r.rows.back();
  const double W = last.work_cam, D = last.dissipated;
  EXPECT_GT(std::abs(W), 0.0);
  EXPECT_GT(D, 0.0);
  const double residual = std::abs(W - D - last.kinetic + r.rows.front().kinetic - last.potential);
  // measured: penalty 3.3e-10 J of W = 0.073 J, event 9.6e-10 J, Lee 7.9e-10 J (rtol 1e-10)
  EXPECT_LT(residual, 1e-7 * std::max(std::abs(W), D));
}
TEST(CamshaftRun, DriveWorkIsDissipatedPlusStoredPenalty) { expect_energy_balance("penalty"); }
TEST(CamshaftRun, DriveWorkIsDissipatedPlusStoredEvent) { expect_energy_balance("event"); }
TEST(CamshaftRun, DriveWorkIsDissipatedPlusStoredLee) { expect_energy_balance("lee"); }

void expect_scene_error(const std::string& lines, const std::string& key) {
  TwoDof p;
  const std::string s = two_dof_toml(p, false, 0.01) + "[camshaft]\n" + lines;
  try {
    parse_scene(s, "<test>");
    ADD_FAILURE() << "no SceneError for " << lines;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
  }
}

TEST(CamshaftScene, BadInputNamesTheKey) {
  const std::string ok = "inertias = [1e-4, 1e-4]\nstiffnesses = [500.0]\ndrive_stiffness = 400.0\n";
  expect_scene_error(ok + "cam_stations = [2]\n", "camshaft.cam_stations[0]");
  expect_scene_error(ok + "cam_stations = [0]\ncam_offsets_deg = [10]\ncam_offsets_crank_deg = [20]\n",
                     "camshaft.cam_offsets_crank_deg");
  expect_scene_error(ok + "cam_stations = [0]\ndrive_station = 2\n", "camshaft.drive_station");
  expect_scene_error("cam_stations = [0]\ndrive_stiffness = 400.0\n", "camshaft.inertias");
  expect_scene_error("inertias = [0.0]\ncam_stations = [0]\ndrive_stiffness = 400.0\n", "camshaft.inertias[0]");
  expect_scene_error(ok + "cam_stations = [0, 1]\n", "camshaft.cam_stations");  // two cams, one cam contact
  expect_scene_error("inertias = [1e-4]\ncam_stations = [0]\n", "camshaft.drive_stiffness");
}

}  // namespace
}  // namespace camdyn
