// A rigid or elastic_bar follower built as a one-contact Mechanism and run by the contact
// methods and engines, checked against independent truth: case A's and A7's closed forms,
// the event-driven method at tight tolerance (a second formulation), the bar's mass and
// stiffness assembled densely in the test, and the history's columns; the retired keys of
// the single-follower stack.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include <Eigen/Dense>
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

TEST_P(MechanismStackCaseA, LeeMatchesTheClosedForm) {
  // The bounds of LeeCaseA.MatchesClosedFormWithDefaultTolerances (test_lee.cpp).
  Scene s = paper_case("A");
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

// The one-contact mechanism's algebra against the follower's equations written out here:
// rigid, m a = −kδ₀ − k(q − q(0)) − c v; the bar, M and K of 2-node elements assembled
// densely (M consistent: mₑ/6 [2 1; 1 2]), the spring on the far node, the preloaded shape
// q_i(0) = x₀ − i kδ₀ h/(EA); W = e₀ᵀM⁻¹e₀ and a = M⁻¹(f₀ − Kq) by a dense LU.
TEST(MechanismStack, OneContactMechanismHasTheFollowersMassAndForces) {
  for (const char* c : {"A", "B1"}) {
    Scene s = paper_case(c);
    s.follower.mass_matrix = MassMatrixKind::Consistent;
    resolve_defaults(s);
    const Mechanism mech(s);
    ASSERT_FALSE(mech.traits().named_contacts);  // the one-contact mechanism of a follower
    ASSERT_EQ(mech.m(), 1);
    const Cam cam(s.cam);
    const CamDrive drive(s.cam);
    const double x0 = cam.evaluate(drive.theta(0.0)).X_C + s.contact.initial_gap;
    const double k = s.spring.stiffness, P = k * s.spring.precompression;
    const bool rigid = s.follower.kind == FollowerKind::Rigid;
    const int n = rigid ? 1 : int(s.follower.elements) + 1;
    ASSERT_EQ(mech.n(), n) << c;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), K = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd q0(n), f0 = Eigen::VectorXd::Zero(n);
    if (rigid) {
      M(0, 0) = s.follower.mass;
      K(0, 0) = k;
      q0[0] = x0;
    } else {
      const int N = n - 1;
      const double h = s.follower.length / N, EA = s.follower.youngs_modulus * s.follower.area;
      const double me = s.follower.mass / N;
      for (int e = 0; e < N; ++e) {
        M.block(e, e, 2, 2) += me / 6.0 * (Eigen::Matrix2d() << 2, 1, 1, 2).finished();
        K.block(e, e, 2, 2) += EA / h * (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
      }
      K(N, N) += k;
      for (int i = 0; i < n; ++i) q0[i] = x0 - i * P * h / EA;
    }
    f0[n - 1] = -P + k * q0[n - 1];
    EXPECT_LE((mech.q0() - q0).cwiseAbs().maxCoeff(), 1e-14 * std::abs(x0)) << c;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    const Eigen::VectorXd z = lu.solve(Eigen::VectorXd::Unit(n, 0));
    EXPECT_NEAR(mech.W()(0, 0), z[0], 1e-12 * z[0]) << c;
    if (rigid) EXPECT_NEAR(mech.W()(0, 0), 1.0 / s.follower.mass, 1e-15) << c;
    // Free acceleration at a displaced, moving state (undamped: C = 0).
    Eigen::VectorXd q = q0, v(n), a(n);
    for (int i = 0; i < n; ++i) {
      q[i] += 1e-3 * std::sin(1.0 + i);
      v[i] = 0.1 * std::cos(2.0 + i);
    }
    mech.acceleration(0.0, q.data(), v.data(), Eigen::VectorXd(), a.data());
    const Eigen::VectorXd a_ref = lu.solve(f0 - K * q);
    EXPECT_LE((a - a_ref).cwiseAbs().maxCoeff(), 1e-9 * a_ref.cwiseAbs().maxCoeff()) << c;
    EXPECT_NEAR(mech.kinetic_energy(v.data()), 0.5 * v.dot(M * v), 1e-12 * v.dot(M * v)) << c;
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

// The keys of the retired single-follower stack: Lee's classic step is refused on every
// follower kind naming the key, the value and what to use; solver.stack and
// contact.error_variant are ignored with a warning (the run is the same as without them).
TEST(MechanismStack, RetiredKeysAreRefusedOrWarnedAbout) {
  for (const char* file : {"case_A.toml", "ohc_bucket_tappet.toml"}) {
    Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/" + file);
    s.contact.lee_step = LeeStepKind::Classic;
    try {
      Simulator sim(s);
      ADD_FAILURE() << file << ": no error";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), "contact.lee_step") << file;
      EXPECT_EQ(e.value(), "classic") << file;
      EXPECT_EQ(e.rule(),
                "Lee's classic step was retired (docs/background/changelog.md): use contact.lee_step = "
                "\"located\" (the default), or remove the key")
          << file;
    }
  }
  Scene s = paper_case("A");
  s.run.t_end = 0.02;
  const Summary plain = Simulator(s).run();
  s.solver.stack = StackKind::Follower;
  s.contact.error_variant = ErrorVariant::Eq17;
  const Simulator sim(s);
  ASSERT_EQ(sim.warnings().size(), 2u);
  EXPECT_EQ(sim.warnings()[0],
            "solver.stack = \"follower\" is deprecated and ignored: every follower runs on the mechanism (remove the key)");
  EXPECT_EQ(sim.warnings()[1],
            "contact.error_variant = \"eq17\" is deprecated and ignored: it chose the classic step's equations; the "
            "located step has one form (remove the key)");
  const Summary r = Simulator(s).run();
  ASSERT_TRUE(r.finished) << r.message;
  EXPECT_EQ(r.steps, plain.steps);
  EXPECT_EQ(r.warnings, sim.warnings());
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
