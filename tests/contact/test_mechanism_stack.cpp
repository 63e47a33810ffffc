// Issue 23 — a rigid or elastic_bar follower built as a one-contact Mechanism and run by
// the network methods and engines (solver.stack = "mechanism", the default), checked
// against independent truth: case A's and A7's closed forms, the event-driven method at
// tight tolerance (a second formulation), the follower model's M* and the history's
// columns.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/model.hpp"
#include "camdyn/simulator.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {
namespace {

// Case A (rigid, always in contact): u = X_C(θ(t)), F = m Ẍ_C + k δ₀ + k (X_C − X_C(0)).
struct CaseAErrors {
  double u = 0, F = 0, Fpeak = 0, min_gap = INFINITY;
};
CaseAErrors case_a_errors(const Scene& s, const RunResult& r) {
  const Cam cam(s.cam);
  const CamDrive drive(s.cam);
  const double X0 = cam.evaluate(drive.theta(0)).X_C, k = s.spring.stiffness;
  CaseAErrors e;
  for (const HistoryRow& row : r.rows) {
    const CamMotion m = cam.motion(drive.theta(row.t), drive.omega(row.t), drive.omega_dot(row.t));
    const double F = s.follower.mass * m.Xddot + k * s.spring.precompression + k * (m.X - X0);
    e.u = std::max(e.u, std::abs(row.u_c - m.X));
    e.F = std::max(e.F, std::abs(row.contact_force - F));
    e.Fpeak = std::max(e.Fpeak, std::abs(F));
    e.min_gap = std::min(e.min_gap, row.gap);
  }
  return e;
}

class MechanismStackCaseA : public ::testing::TestWithParam<Integrator> {};

TEST_P(MechanismStackCaseA, LeeMatchesTheClosedFormWithTheFollowerStacksBounds) {
  // The bounds of LeeCaseA.MatchesClosedFormWithDefaultTolerances (test_lee.cpp).
  Scene s = paper_case("A");
  s.solver.stack = StackKind::Mechanism;
  s.solver.integrator = GetParam();
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  const CaseAErrors e = case_a_errors(s, r);
  std::printf("%s: |u err| %.3e, |F err|/peak %.3e, min gap %.3e; %s\n", to_string(GetParam()), e.u, e.F / e.Fpeak,
              e.min_gap, r.summary.BriefReport().c_str());
  EXPECT_LE(e.u, 1e-7);
  EXPECT_LE(e.F / e.Fpeak, 1e-5);
  EXPECT_GE(e.min_gap, -(1e-8 + 1e-12));  // tol_u of a rigid follower
  EXPECT_EQ(r.summary.separations, 0);
  EXPECT_EQ(r.summary.impacts, 0);
  EXPECT_NE(r.summary.model.contact.find("one-contact mechanism"), std::string::npos) << r.summary.model.ToString();
}

INSTANTIATE_TEST_SUITE_P(Engines, MechanismStackCaseA,
                         ::testing::Values(Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf),
                         [](const auto& i) {
                           std::string n = to_string(i.param);
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

// A7 (case A at 7 rev/s): one separation and one impact per revolution, against the
// closed form — the follower leaves where the held force m Ẍ_C + k(δ₀ + X_C − X_C(0))
// reaches zero, flies on its spring (x − x_eq = (X_C(t_s) − x_eq) cos ω(t − t_s) +
// Ẋ_C(t_s)/ω sin ω(t − t_s), x_eq = X_C(0) − δ₀, ω² = k/m) and strikes the cam where
// x = X_C again (both roots by bisection to 1e-14 s on the exact cam).
struct A7Events {
  double t_sep = 0, t_imp = 0, v_imp = 0;
};
A7Events a7_closed_form(const Scene& s) {
  const Cam cam(s.cam);
  const CamDrive d(s.cam);
  const double k = s.spring.stiffness, m = s.follower.mass, w = std::sqrt(k / m);
  const double X0 = cam.evaluate(d.theta(0)).X_C, x_eq = X0 - s.spring.precompression;
  auto cm = [&](double t) { return cam.motion(d.theta(t), d.omega(t), d.omega_dot(t)); };
  auto force = [&](double t) { const CamMotion c = cm(t); return m * c.Xddot + k * (s.spring.precompression + c.X - X0); };
  auto root = [](auto f, double a, double b) {
    for (int i = 0; i < 200 && b - a > 1e-14; ++i) {
      const double c = 0.5 * (a + b);
      (f(a) * f(c) <= 0 ? b : a) = c;
    }
    return 0.5 * (a + b);
  };
  A7Events e;
  double t = 0;
  const double dt = 1e-5;
  while (force(t + dt) > 0) t += dt;
  e.t_sep = root(force, t, t + dt);
  const CamMotion c0 = cm(e.t_sep);
  auto x = [&](double tt) { return x_eq + (c0.X - x_eq) * std::cos(w * (tt - e.t_sep)) + c0.Xdot / w * std::sin(w * (tt - e.t_sep)); };
  auto gap = [&](double tt) { return x(tt) - cm(tt).X; };
  t = e.t_sep + dt;
  while (gap(t + dt) > 0) t += dt;
  e.t_imp = root(gap, t, t + dt);
  const double xd = -(c0.X - x_eq) * w * std::sin(w * (e.t_imp - e.t_sep)) + c0.Xdot * std::cos(w * (e.t_imp - e.t_sep));
  e.v_imp = std::abs(cm(e.t_imp).Xdot - xd);
  return e;
}

TEST(MechanismStack, A7EventsMatchTheClosedForm) {
  Scene ref = paper_case("A");  // examples/case_A7.toml: case A at 7 rev/s
  ref.cam.speed_rev_s = 7.0;
  ref.run.t_end = 0.1;
  const A7Events X = a7_closed_form(ref);
  for (ContactModel m : {ContactModel::Lee, ContactModel::Event})
    for (Integrator e : {Integrator::ArkodeErk, Integrator::ArkodeDirk}) {
      Scene s = ref;
      s.solver.stack = StackKind::Mechanism;
      s.contact.model = m;
      s.solver.integrator = e;
      s.solver.rtol = 1e-9;  // contact.tol_u stays 1e-8 (a rigid follower's default)
      const RunResult r = simulate(s);
      const std::string what = std::string(to_string(m)) + " on " + to_string(e);
      ASSERT_TRUE(r.summary.finished) << what << ": " << r.summary.message;
      ASSERT_EQ(r.summary.events.size(), 2u) << what;
      const ContactEvent &a = r.summary.events[0], &b = r.summary.events[1];
      std::printf("%s: separation at %.12f (closed form %.12f), impact at %.12f (%.12f), v %.9g (%.9g)\n",
                  what.c_str(), a.t, X.t_sep, b.t, X.t_imp, b.impact_velocity, X.v_imp);
      EXPECT_EQ(a.type, EventKind::Separation) << what;
      EXPECT_EQ(b.type, EventKind::Impact) << what;
      EXPECT_NEAR(a.t, X.t_sep, 1e-8) << what;
      EXPECT_NEAR(b.t, X.t_imp, 1e-8) << what;
      EXPECT_NEAR(b.impact_velocity, X.v_imp, 1e-6 * X.v_imp) << what;
    }
}

// The one-contact mechanism's algebra against the follower model's: W = T M⁻¹ Tᵀ = M*
// (a rigid follower: 1/m), the unknowns and the free acceleration.
TEST(MechanismStack, OneContactMechanismHasTheFollowerModelsMassAndForces) {
  for (const char* c : {"A", "B1"}) {
    Scene s = paper_case(c);
    s.follower.mass_matrix = MassMatrixKind::Consistent;
    resolve_defaults(s);
    const Mechanism mech(s);
    const auto fm = build_model(s);
    ASSERT_TRUE(mech.single_follower());
    ASSERT_EQ(mech.n(), fm->n()) << c;
    ASSERT_EQ(mech.m(), 1);
    EXPECT_NEAR(mech.W()(0, 0), fm->mstar(), 1e-12 * fm->mstar()) << c;
    if (fm->rigid()) EXPECT_NEAR(mech.W()(0, 0), 1.0 / s.follower.mass, 1e-15) << c;
    // Free acceleration at a displaced, moving state: a = M⁻¹(f₀ − Kq − Cv).
    Eigen::VectorXd q = fm->initial_displacement(), v(fm->n()), a(fm->n()), r(fm->n()), a_ref(fm->n());
    for (int i = 0; i < fm->n(); ++i) {
      q[i] += 1e-3 * std::sin(1.0 + i);
      v[i] = 0.1 * std::cos(2.0 + i);
    }
    mech.acceleration(0.0, q.data(), v.data(), Eigen::VectorXd(), a.data());
    fm->internal_force(q.data(), v.data(), r.data());
    fm->solve_mass(r.data(), a_ref.data());
    EXPECT_LE((a - a_ref).cwiseAbs().maxCoeff(), 1e-9 * a_ref.cwiseAbs().maxCoeff()) << c;
    EXPECT_NEAR(mech.kinetic_energy(v.data()), fm->kinetic_energy(v.data()), 1e-12 * fm->kinetic_energy(v.data()));
  }
}

// B1 (elastic bar, always in contact): Lee's contact force at every row within the
// tolerance's reach of the event-driven method at rtol 1e-10 (a second formulation), the
// single follower's history columns.
TEST(MechanismStack, B1ForceAgreesWithTheEventMethodAndKeepsItsColumns) {
  Scene ref = paper_case("B1");
  ref.run.t_end = 0.05;
  ref.solver.rtol = 1e-10;
  ref.contact.model = ContactModel::Event;
  const RunResult R = simulate(ref);
  ASSERT_TRUE(R.summary.finished) << R.summary.message;
  Scene s = ref;
  s.solver.rtol = 1e-7;
  s.contact.model = ContactModel::Lee;
  const Simulator sim(s);
  EXPECT_TRUE(sim.extra_columns().empty());
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  ASSERT_EQ(r.rows.size(), R.rows.size());
  double dF = 0, Fmax = 0, du = 0;
  for (size_t i = 0; i < r.rows.size(); ++i) {
    ASSERT_EQ(r.rows[i].t, R.rows[i].t);
    ASSERT_TRUE(r.rows[i].extra.empty());
    dF = std::max(dF, std::abs(r.rows[i].contact_force - R.rows[i].contact_force));
    du = std::max(du, std::abs(r.rows[i].u_c - R.rows[i].u_c));
    Fmax = std::max(Fmax, std::abs(R.rows[i].contact_force));
  }
  std::printf("B1 Lee vs event (rtol 1e-10): |dF|/Fmax %.3e, |du| %.3e\n", dF / Fmax, du);
  EXPECT_LE(dF / Fmax, 1e-4);
  EXPECT_LE(du, 1e-6);
}

TEST(MechanismStack, RefusesWhatItDoesNotRunWithExactMessages) {
  struct Case {
    StackKind stack;
    Integrator e;
    ContactModel m;
    LeeStepKind k;
    const char* value;
    const char* msg;
  };
  const Case cases[] = {
      {StackKind::Follower, Integrator::Ida, ContactModel::Holonomic, LeeStepKind::Located, "follower",
       "runs Lee's classic step only (contact.model = \"lee\", contact.lee_step = \"classic\"); every other "
       "method runs on the mechanism (use solver.stack = \"mechanism\" or \"auto\")"},
      {StackKind::Follower, Integrator::ArkodeErk, ContactModel::Lee, LeeStepKind::Located, "follower",
       "runs Lee's classic step only (contact.model = \"lee\", contact.lee_step = \"classic\"); every other "
       "method runs on the mechanism (use solver.stack = \"mechanism\" or \"auto\")"},
      {StackKind::Mechanism, Integrator::ArkodeErk, ContactModel::Lee, LeeStepKind::Classic, "mechanism",
       "runs Lee's located step (contact.lee_step = classic: use solver.stack = "
       "\"follower\" or \"auto\")"},
  };
  for (const Case& c : cases) {
    Scene s = paper_case("A");
    s.solver.stack = c.stack;
    s.solver.integrator = c.e;
    s.contact.model = c.m;
    s.contact.lee_step = c.k;
    try {
      Simulator sim(s);
      ADD_FAILURE() << "no error for " << c.msg;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), "solver.stack");
      EXPECT_EQ(e.value(), c.value);
      EXPECT_EQ(e.rule(), c.msg);
    }
  }
}

// The force margin between rows and step ends (Summary::min_contact_force): the lift-table
// cam below its jump speed, Lee on the mechanism stack, one revolution with no output rows
// (output_dt = 0: rows at the step ends only), against the closed form
// min_θ F_req(θ, ω) = m h″ω² + kδ₀ + k (h(θ) − h(0)) on a 0.01° grid — the bound of
// Designer.LiftCamMarginMatchesClosedForm (test_sweep.cpp), 1e-5 of the preload.
TEST(MechanismStack, ForceMarginInsideStepsMatchesTheClosedForm) {
  const Scene base = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/lift_cam.toml");
  for (double speed : {3.0, 6.0, 8.5}) {
    Scene s = base;
    s.solver.stack = StackKind::Mechanism;
    s.cam.speed_rev_s = speed;
    s.run.t_end = 1.0 / speed;
    s.run.output_dt = 0;
    s.solver.rtol = 1e-7;
    const Cam cam(s.cam);
    const double w = 2 * M_PI * speed, h0 = cam.evaluate(0).X_C;
    double closed = 1e300;
    for (int i = 0; i < 36000; ++i) {
      const CamPoint p = cam.evaluate(2 * M_PI * i / 36000);
      closed = std::min(closed, p.d2X_dtheta2 * w * w + 3500 + 500 * (p.X_C - h0));
    }
    const Summary r = Simulator(s).run();
    ASSERT_TRUE(r.finished) << r.message;
    std::printf("%g rev/s: min force %.9g, closed form %.9g (%.2e)\n", speed, r.min_contact_force, closed,
                r.min_contact_force - closed);
    EXPECT_EQ(r.separations, 0);
    EXPECT_NEAR(r.min_contact_force, closed, 1e-5 * 3500) << speed << " rev/s";
    EXPECT_NEAR(required_contact_force(s, r.min_force_theta_deg * M_PI / 180), closed, 1e-5 * 3500)
        << speed << " rev/s, at " << r.min_force_theta_deg << " deg";
  }
}

}  // namespace
}  // namespace camdyn

namespace camdyn {
namespace {
// Lee's classic step runs on the single-follower stack only: a network asking for it is
// bad input (it used to run the located step without a word).
TEST(MechanismStack, ANetworkRefusesTheClassicStep) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  s.contact.lee_step = LeeStepKind::Classic;
  try {
    Simulator sim(s);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "contact.lee_step");
    EXPECT_EQ(e.value(), "classic");
    EXPECT_EQ(e.rule(),
              "runs on a rigid or elastic_bar follower only (a network or a user follower runs Lee's located step: "
              "contact.lee_step = \"located\")");
  }
}
}  // namespace
}  // namespace camdyn
