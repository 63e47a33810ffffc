// Friction at the cam contact (cam.friction_coefficient, Stribeck keys, roller_slip;
// src/results/designer_columns.hpp CamFriction) against independent truth:
//   * a flat-faced follower held on an eccentric circle cam (radius R, eccentricity e) by a
//     spring k with preload P, no damping: in contact, X_C = R + e cos ψ (the face's distance
//     from the cam centre) and F = P + k(X_C − X_base) + m Ẍ_C, so the mean friction torque
//     over a revolution is the closed form
//       T̄_f = μ·mean(F·X_C) = μ[(P + k e)R + k e²/2 − m ω² e²/2]
//     and the mean friction power T̄_f·ω, the friction energy 2π T̄_f;
//   * with a Stribeck curve μ(v) = μ + (μ_s − μ)exp(−(v/v_st)²) of the sliding speed ω X_C:
//     the mean against Gauss–Legendre quadrature of μ(ωX_C)·F·X_C over ψ written here;
//   * the energy ledger over a revolution: the drive's energy (cam torque + friction torque)
//     equals the change of stored energy plus everything dissipated (friction included);
//   * a rolling roller (roller_slip 0) has no sliding friction; bad keys: SceneError.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

constexpr double kR = 0.02, kE = 0.004, kK = 20e3, kP = 100.0, kM = 0.05, kSpeed = 5.0, kMu = 0.08;

Scene friction_scene(ContactModel model, Integrator integ) {
  Scene s = default_scene();
  s.title = "cam friction";
  s.cam.profile = CamProfileKind::Circle;
  s.cam.radius = kR;
  s.cam.eccentricity = kE;
  s.cam.speed_rev_s = kSpeed;
  s.cam.theta0_deg = 180.0;  // on the base circle
  s.cam.friction_coefficient = kMu;
  s.follower.kind = FollowerKind::Network;
  NodeSpec f;
  f.name = "follower";
  f.mass = kM;
  s.network.nodes = {f};
  ElementSpec sp;
  sp.name = "spring";
  sp.kind = ElementKind::Spring;
  sp.nodes = {"follower", "ground"};
  sp.stiffness = kK;
  sp.preload = kP;
  s.network.elements = {sp};
  ContactPointSpec c;
  c.name = "cam";
  c.kind = ContactPointKind::Cam;
  c.nodes = {"follower"};
  s.network.contacts = {c};
  s.contact.model = model;
  s.contact.penalty_stiffness = 1e9;  // N/m (penalty): stiff against the spring's 2e4
  s.contact.penalty_damping = 2e3;
  s.solver.integrator = integ;
  s.solver.rtol = 1e-9;
  s.solver.atol = 1e-13;
  s.run.t_end = 1.0 / kSpeed;  // one revolution
  s.run.output_dt = 1e-4;
  return s;
}

TEST(CamFriction, FlatFaceMeanTorqueIsTheClosedForm) {
  const double w = 2 * M_PI * kSpeed;
  const double T = kMu * ((kP + kK * kE) * kR + kK * kE * kE / 2 - kM * w * w * kE * kE / 2);
  const std::pair<ContactModel, Integrator> cases[] = {{ContactModel::Lee, Integrator::ArkodeErk},
                                                       {ContactModel::Event, Integrator::ArkodeDirk},
                                                       {ContactModel::Penalty, Integrator::CvodeBdf}};
  for (const auto& [model, integ] : cases) {
    SCOPED_TRACE(std::string(to_string(integ)) + " " + to_string(model));
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(friction_scene(model, integ));
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    // the follower starts at rest on the base circle: the run is the steady motion up to the
    // free vibration the start leaves (the spring's, undamped; measured |ΔT̄|/T̄: Lee/ERK
    // 4.6e-5, event/DIRK 3.5e-8, penalty/BDF 2.0e-5)
    EXPECT_NEAR(r.sum.cam_friction_torque_mean, T, 2e-4 * T);
    EXPECT_NEAR(r.sum.cam_friction_power_mean, T * w, 2e-4 * T * w);
    EXPECT_NEAR(r.sum.cam_friction_work, 2 * M_PI * T, 2e-4 * 2 * M_PI * T);
    // columns: flat face: sliding speed ω X_C, force μF, torque μF X_C, power μF ω X_C
    const Cam cam(friction_scene(model, integ).cam);
    for (const HistoryRow& row : r.rows) {
      const double F = r.col(row, "F_cam"), v = r.col(row, "sliding_speed");
      const double XC = cam.evaluate(row.theta).X_C;  // R + e cos(θ − θ_e): the face's distance
      EXPECT_NEAR(XC, kR + kE * std::cos(row.theta), 1e-12);
      EXPECT_NEAR(v, w * XC, 1e-9);
      EXPECT_NEAR(r.col(row, "cam_friction_force"), kMu * F, 1e-9);
      EXPECT_NEAR(r.col(row, "cam_friction_torque"), kMu * F * XC, 1e-9);
      EXPECT_NEAR(r.col(row, "cam_friction_power"), kMu * F * XC * w, 1e-8);
    }
    // the energy ledger with friction: drive energy = ΔE + dissipated (friction included);
    // the cam's own ledger (work on the follower = ΔE + D) is the run's energy residual;
    // measured relative misfit ≤ 4e-7 of the friction energy (1.89 J)
    const HistoryRow& end = r.rows.back();
    const double drive = (r.sum.cam_torque_mean + r.sum.cam_friction_torque_mean) * 2 * M_PI;
    const double stored = end.kinetic + end.potential - (r.rows.front().kinetic + r.rows.front().potential);
    EXPECT_NEAR(drive, stored + end.dissipated + r.sum.cam_friction_work, 1e-4 * r.sum.cam_friction_work);
  }
}

TEST(CamFriction, StribeckMeanAgainstQuadrature) {
  Scene s = friction_scene(ContactModel::Event, Integrator::ArkodeDirk);
  const double mus = 0.15, vst = 0.6;
  s.cam.friction_static_coefficient = mus;
  s.cam.friction_stribeck_speed = vst;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  const double w = 2 * M_PI * kSpeed;
  // composite midpoint rule over ψ, 20 000 panels (a smooth periodic integrand: spectrally
  // accurate); F = P + k(X − (R − e)) + m Ẍ. Measured relative difference 3.2e-8
  const int n = 20000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double psi = 2 * M_PI * (i + 0.5) / n, X = kR + kE * std::cos(psi);
    const double F = kP + kK * (X - (kR - kE)) - kM * w * w * kE * std::cos(psi);
    const double v = w * X, mu = kMu + (mus - kMu) * std::exp(-(v / vst) * (v / vst));
    sum += mu * F * X;
  }
  const double T = sum / n;
  EXPECT_NEAR(r.sum.cam_friction_torque_mean, T, 2e-4 * T);
}

TEST(CamFriction, RollingRollerHasNoSlidingFrictionAndBadKeys) {
  Scene s = friction_scene(ContactModel::Event, Integrator::ArkodeDirk);
  s.cam.follower_face = FollowerFace::Roller;
  s.cam.roller_radius = 0.008;
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  EXPECT_EQ(r.sum.cam_friction_work, 0.0);
  EXPECT_EQ(r.sum.cam_friction_force_max, 0.0);
  auto expect_error = [](Scene bad, const std::string& key, const std::string& rule_part) {
    try {
      validate(bad);
      ADD_FAILURE() << "no error for " << key;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), key);
      EXPECT_NE(e.rule().find(rule_part), std::string::npos) << e.rule();
    }
  };
  Scene b = s;
  b.cam.roller_slip = 1.5;
  expect_error(b, "cam.roller_slip", "");
  b = friction_scene(ContactModel::Event, Integrator::ArkodeDirk);
  b.cam.roller_slip = 0.1;
  expect_error(b, "cam.roller_slip", "applies to cam.follower_face = \"roller\" only");
  b = friction_scene(ContactModel::Event, Integrator::ArkodeDirk);
  b.cam.friction_static_coefficient = 0.05;
  b.cam.friction_stribeck_speed = 0.5;
  expect_error(b, "cam.friction_static_coefficient", "must be >= cam.friction_coefficient");
  b = friction_scene(ContactModel::Event, Integrator::ArkodeDirk);
  b.cam.friction_coefficient = -0.1;
  expect_error(b, "cam.friction_coefficient", ">= 0");
}

}  // namespace
}  // namespace camdyn
