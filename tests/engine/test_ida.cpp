// The held contact as a DAE in SUNDIALS IDA (solver.integrator = "ida", src/engine/ida_engine.cpp)
// against independent truth:
//   case A (rigid follower, held on the cam): the closed form u = X_C(θ(t)),
//     F = m Ẍ_C + k δ₀ + k (X_C − X_C(0)), and the event-driven method's contact phase
//     (a second formulation: the reaction computed from the cam kinematics directly);
//   B1 (41-node bar → 85 DAE unknowns → KLU): the held-bar ODE integrated by arkode-erk
//     (the holonomic baseline: node 0 eliminated, reaction from the equation of motion);
//   the energy balance W = ΔT + ΔV + D (W a DAE component, T, V from the state);
//   the first tensile time (case A at 7 rev/s) against the closed-form root of F.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

// Closed-form held-contact force of case A (rigid follower).
double case_a_force(const Scene& s, double t, double* u = nullptr) {
  static thread_local std::unique_ptr<Cam> cam_p;
  static thread_local CamSpec spec;
  if (!cam_p || !(spec == s.cam)) {
    cam_p = std::make_unique<Cam>(s.cam);
    spec = s.cam;
  }
  const Cam& cam = *cam_p;
  CamDrive drive(s.cam);
  const CamMotion m = cam.motion(drive.theta(t), drive.omega(t), drive.omega_dot(t));
  const double X0 = cam.evaluate(drive.theta(0)).X_C;
  const double k = s.spring.stiffness;
  if (u) *u = m.X;
  return s.follower.mass * m.Xddot + k * s.spring.precompression + k * (m.X - X0);
}

Scene ida_case_a(double t_end) {
  Scene s = paper_case("A");
  s.contact.model = ContactModel::Holonomic;
  s.solver.integrator = Integrator::Ida;
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-12;
  s.run.t_end = t_end;
  return s;
}

TEST(Ida, CaseAEqualsClosedFormAndEventDriven) {
  Scene s = ida_case_a(1.0 / 1.75);  // one revolution
  s.solver.rtol = 1e-11;
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_EQ(r.summary.integrator, "ida");
  EXPECT_EQ(r.summary.model.linear_solver, "dense");  // 2n + 2 = 4 unknowns
  double du = 0, dF = 0, Fpeak = 0, t_worst = 0;
  for (const HistoryRow& row : r.rows) {
    double u;
    const double F = case_a_force(s, row.t, &u);
    du = std::max(du, std::abs(row.u_c - u));
    if (std::abs(row.contact_force - F) > dF) t_worst = row.t;
    dF = std::max(dF, std::abs(row.contact_force - F));
    Fpeak = std::max(Fpeak, std::abs(F));
  }
  std::printf("IDA case A: %ld steps, du %.2e, dF/Fpeak %.2e (worst at t = %.6g)\n", r.summary.steps, du,
              dF / Fpeak, t_worst);
  // The rows' force is the acceleration level on IDA's held state (methods/holonomic_ida.cpp): IDA's
  // λ, an index-2 unknown left out of the error test, is off by O(rtol·|v|/h) after the
  // short step that lands on a row (3.9e-9 of the peak at one row at rtol 1e-11). Measured
  // here 8e-16 (a rigid follower's held force is a function of the cam alone).
  EXPECT_LT(du, 1e-9 * Fpeak / s.spring.stiffness);  // u to 1e-9 of the peak (as a force k·u)
  EXPECT_LT(dF, 1e-9 * Fpeak);

  // The event-driven method's contact phase (no separation at 1.75 rev/s), same rows.
  Scene e = s;
  e.contact.model = ContactModel::Event;
  e.solver.integrator = Integrator::ArkodeErk;
  const RunResult re = simulate(e);
  ASSERT_TRUE(re.summary.finished) << re.summary.message;
  ASSERT_EQ(re.summary.separations, 0);
  ASSERT_EQ(re.rows.size(), r.rows.size());
  double dFe = 0, due = 0;
  for (size_t i = 0; i < r.rows.size(); ++i) {
    ASSERT_NEAR(r.rows[i].t, re.rows[i].t, 1e-12);
    due = std::max(due, std::abs(r.rows[i].u_c - re.rows[i].u_c));
    dFe = std::max(dFe, std::abs(r.rows[i].contact_force - re.rows[i].contact_force));
  }
  EXPECT_LT(due, 1e-9 * Fpeak / s.spring.stiffness);
  EXPECT_LT(dFe, 1e-9 * Fpeak);
}

// Impulses ∫F dt over consecutive windows of `window` (trapezoid on the rows).
std::vector<double> impulses(const std::vector<HistoryRow>& rows, double window) {
  std::vector<double> out;
  double acc = 0, t_next = window;
  for (size_t i = 1; i < rows.size(); ++i) {
    acc += 0.5 * (rows[i].t - rows[i - 1].t) * (rows[i].contact_force + rows[i - 1].contact_force);
    if (rows[i].t >= t_next * (1 - 1e-12)) {
      out.push_back(acc);
      acc = 0;
      t_next += window;
    }
  }
  return out;
}

TEST(Ida, B1HeldBarAgreesWithErkAndUsesKlu) {
  Scene s = paper_case("B1");
  s.contact.model = ContactModel::Holonomic;
  s.run.t_end = 0.02;
  s.run.output_dt = 1e-5;
  s.solver.rtol = 1e-8;
  s.solver.atol = 1e-12;
  Scene si = s;
  si.solver.integrator = Integrator::Ida;
  const RunResult ri = simulate(si);
  ASSERT_TRUE(ri.summary.finished) << ri.summary.message;
  EXPECT_EQ(ri.summary.model.linear_solver, "klu");  // 2·41 + 2 = 84 > 16
  EXPECT_EQ(ri.summary.model.unknowns, 2 * 41 + 4);  // [q; v; λ; μ; W; D]
  const RunResult re = simulate(s);  // holonomic on arkode-erk: the held bar as an ODE
  ASSERT_TRUE(re.summary.finished) << re.summary.message;
  ASSERT_EQ(ri.rows.size(), re.rows.size());
  double dF = 0, Fpeak = 0;
  for (size_t i = 0; i < ri.rows.size(); ++i) {
    dF = std::max(dF, std::abs(ri.rows[i].contact_force - re.rows[i].contact_force));
    Fpeak = std::max(Fpeak, std::abs(re.rows[i].contact_force));
  }
  const std::vector<double> Ii = impulses(ri.rows, 1e-3), Ie = impulses(re.rows, 1e-3);
  ASSERT_EQ(Ii.size(), Ie.size());
  ASSERT_GE(Ii.size(), 19u);
  double dI = 0, Ipeak = 0;
  for (size_t k = 0; k < Ii.size(); ++k) {
    dI = std::max(dI, std::abs(Ii[k] - Ie[k]));
    Ipeak = std::max(Ipeak, std::abs(Ie[k]));
  }
  std::printf("IDA B1: %ld steps (%ld rejected), %ld res evals, %ld lin setups; ERK %ld steps; "
              "pointwise dF/Fpeak %.2e, 1 ms impulses dI/Ipeak %.2e\n",
              ri.summary.steps, ri.summary.rejected_steps, ri.summary.rhs_evals, ri.summary.lin_setups,
              re.summary.steps, dF / Fpeak, dI / Ipeak);
  // Both runs control the local error of the state at rtol 1e-8; the force is the
  // state's second derivative at node 1 (ERK: through the held bar's equation of motion;
  // IDA: the multiplier, BDF-differentiated), and the bar's stiffest modes (element
  // crossing time 2.2e-5 s) are resolved only to the tolerance: 1e-5 of the peak
  // pointwise and 1e-6 for the 1 ms impulses (which average those modes out).
  EXPECT_LT(dF, 1e-5 * Fpeak);
  EXPECT_LT(dI, 1e-6 * Ipeak);
}

TEST(Ida, EnergyBalance) {
  for (const char* c : {"A", "B1"}) {
    Scene s = paper_case(c);
    s.contact.model = ContactModel::Holonomic;
    s.solver.integrator = Integrator::Ida;
    s.solver.rtol = 1e-10;
    s.solver.atol = 1e-12;
    s.run.t_end = c[0] == 'A' ? 0.3 : 0.02;
    const RunResult r = simulate(s);
    ASSERT_TRUE(r.summary.finished) << r.summary.message;
    double scale = 0;
    for (const HistoryRow& row : r.rows) scale = std::max({scale, std::abs(row.work_cam), row.kinetic});
    const HistoryRow& e = r.rows.back();
    const double resid = e.work_cam - e.kinetic - e.potential - e.dissipated + r.rows.front().kinetic;
    std::printf("IDA %s energy: W %.6g, residual %.2e (scale %.3g)\n", c, e.work_cam, resid, scale);
    EXPECT_LT(std::abs(resid), 1e-6 * scale) << c;
    EXPECT_LT(r.summary.energy_residual, 1e-6 * scale) << c;
  }
}

TEST(Ida, FirstTensileTimeIsTheRootOfTheClosedFormForce) {
  Scene s = ida_case_a(0.2);
  s.cam.speed_rev_s = 7.0;  // above the separation speed (≈ 6.4 rev/s)
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  // Closed-form root: scan, then bisect.
  double a = -1, b = -1;
  for (double t = 0; t < 0.2; t += 1e-5)
    if (case_a_force(s, t) < 0) {
      a = t - 1e-5;
      b = t;
      break;
    }
  ASSERT_GT(b, 0);
  for (int i = 0; i < 100; ++i) {
    const double m = 0.5 * (a + b);
    (case_a_force(s, m) >= 0 ? a : b) = m;
  }
  std::printf("IDA tensile at %.15g, closed form %.15g\n", r.summary.first_tensile_time, b);
  EXPECT_NEAR(r.summary.first_tensile_time, b, 1e-9);
  const auto it = std::find_if(r.summary.events.begin(), r.summary.events.end(),
                               [](const ContactEvent& e) { return e.type == EventKind::Tensile; });
  ASSERT_NE(it, r.summary.events.end());
  EXPECT_EQ(it->t, r.summary.first_tensile_time);
}

TEST(Ida, RequiresHolonomic) {
  Scene s = paper_case("A");
  s.solver.integrator = Integrator::Ida;
  for (ContactModel m : {ContactModel::Lee, ContactModel::Penalty, ContactModel::Event}) {
    s.contact.model = m;
    EXPECT_THROW(Simulator{s}, SceneError) << to_string(m);
  }
  s.contact.model = ContactModel::Holonomic;
  EXPECT_NO_THROW(Simulator{s});
}

}  // namespace
}  // namespace camdyn
