// Bring your own follower (issue 17): a rigid follower on a progressive (cubic hardening)
// valve spring, given through the public FollowerSystem API, against independent solutions:
//   held on the cam:  F(t) = m Ẍ_C + P + k X_C + k₃ X_C³   (closed form, X_C from the Cam API)
//   separation:       the first root of that F (bisection on the closed form)
//   free flight:      m q̈ = −(P + k q + k₃ q³) by classical RK4 with 10⁻⁸ s steps from the
//                     separation state, up to the impact q = X_C.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "camdyn/cam.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

struct CubicSpringFollower : FollowerSystem {
  double m = 0.1, k = 2e4, k3 = 5e8, P = 150.0;  // kg, N/m, N/m³, N
  int size() const override { return 1; }
  std::vector<FollowerContact> contacts() const override {
    FollowerContact c;
    c.name = "cam";
    c.row = {1.0};
    return {c};
  }
  double spring(double q) const { return P + k * q + k3 * q * q * q; }
  void force(double, const double* q, const double*, double* r) const override { r[0] = -spring(q[0]); }
  void solve_mass(const double* b, double* x) const override { x[0] = b[0] / m; }
  mutable long jacobian_calls = 0;  // a run that uses the Jacobian calls it
  bool force_jacobian(double, const double* q, const double*, double* drdq, double* drdv) const override {
    ++jacobian_calls;
    drdq[0] = -(k + 3 * k3 * q[0] * q[0]);
    drdv[0] = 0.0;
    return true;
  }
  double kinetic_energy(const double* v) const override { return 0.5 * m * v[0] * v[0]; }
  double potential_energy(const double* q) const override {
    return P * q[0] + 0.5 * k * q[0] * q[0] + 0.25 * k3 * std::pow(q[0], 4);
  }
  std::string name() const override { return "cubic valve spring"; }
};

Scene cam_scene(double speed, ContactModel model, Integrator integ) {
  Scene s = default_scene();
  s.title = "user follower";
  s.cam.profile = CamProfileKind::Circle;
  s.cam.radius = 0.02;
  s.cam.eccentricity = 0.004;
  s.cam.theta0_deg = 180.0;  // base circle
  s.cam.speed_rev_s = speed;
  s.follower.kind = FollowerKind::Rigid;  // not used: the FollowerSystem replaces it
  s.contact.model = model;
  s.contact.tol_u = 1e-11;
  s.solver.integrator = integ;
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-14;
  s.run.output_dt = 0.0;
  return s;
}

// The cam's lift above its base circle (R − e for this circle cam) and its derivatives.
CamMotion lift(const Scene& s, double t) {
  static thread_local std::unique_ptr<Cam> cam;
  cam = std::make_unique<Cam>(s.cam);
  const CamDrive d(s.cam);
  CamMotion c = cam->motion(d.theta(t), d.omega(t), d.omega_dot(t));
  c.X -= s.cam.radius - s.cam.eccentricity;
  return c;
}

// The rows a run emits.
struct KeepRows : Observer {
  std::vector<HistoryRow> rows;
  void on_row(const HistoryRow& r) override { rows.push_back(r); }
};

struct Case {
  ContactModel model;
  Integrator integ;
  const char* name;
};
class UserFollower : public ::testing::TestWithParam<Case> {};

TEST_P(UserFollower, HeldForceIsTheClosedForm) {
  const Case c = GetParam();
  const auto f = std::make_shared<CubicSpringFollower>();
  Scene s = cam_scene(5.0, c.model, c.integ);
  s.run.t_end = 0.2;  // one revolution
  KeepRows keep;
  Simulator sim(s, f);
  const Summary sum = sim.run(&keep);
  ASSERT_TRUE(sum.finished) << sum.message;
  EXPECT_EQ(sum.separations, 0);
  double Fmax = 0, err = 0, gap = 0;
  for (const HistoryRow& r : keep.rows) {
    const CamMotion x = lift(s, r.t);
    const double F = f->m * x.Xddot + f->spring(x.X);
    Fmax = std::max(Fmax, F);
    err = std::max(err, std::abs(r.contact_force - F));
    gap = std::max(gap, std::abs(r.gap));
  }
  std::printf("%s: held force error %.3g of %.4g N, |gap| ≤ %.3g m, %ld steps\n", c.name, err / Fmax, Fmax, gap,
              sum.steps);
  EXPECT_LT(err, 1e-6 * Fmax) << c.name;
  EXPECT_LT(gap, 1e-10) << c.name;
  // energy balance with the user's energies, against the work scale F·lift
  std::printf("%s: energy residual %.3g of %.3g J\n", c.name, sum.energy_residual, Fmax * 0.008);
  EXPECT_LT(sum.energy_residual, 1e-8 * Fmax * 0.008) << c.name;
}

TEST_P(UserFollower, SeparationAndFreeFlightMatchTheIndependentSolution) {
  const Case c = GetParam();
  const auto f = std::make_shared<CubicSpringFollower>();
  Scene s = cam_scene(220.0, c.model, c.integ);
  // independent: the separation as the first root of the closed-form held force
  auto F_req = [&](double t) {
    const CamMotion x = lift(s, t);
    return f->m * x.Xddot + f->spring(x.X);
  };
  const double T = 1.0 / 220.0;
  double a = 0, b = -1;
  for (int i = 1; i <= 4000 && b < 0; ++i)
    if (F_req(i * T / 4000) < 0) a = (i - 1) * T / 4000, b = i * T / 4000;
  ASSERT_GT(b, 0) << "the closed form never separates";
  for (int i = 0; i < 200; ++i) (F_req(0.5 * (a + b)) >= 0 ? a : b) = 0.5 * (a + b);
  const double t_sep = 0.5 * (a + b);
  // free flight by RK4 from the cam's state there, until q meets the cam again
  double q = lift(s, t_sep).X, v = lift(s, t_sep).Xdot, t = t_sep;
  const double h = 1e-8;
  auto acc = [&](double qq) { return -f->spring(qq) / f->m; };
  double t_imp = -1, v_imp = 0;
  while (t < t_sep + T) {
    const double k1q = v, k1v = acc(q);
    const double k2q = v + 0.5 * h * k1v, k2v = acc(q + 0.5 * h * k1q);
    const double k3q = v + 0.5 * h * k2v, k3v = acc(q + 0.5 * h * k2q);
    const double k4q = v + h * k3v, k4v = acc(q + h * k3q);
    const double qn = q + h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q), vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    const double g0 = q - lift(s, t).X, g1 = qn - lift(s, t + h).X;
    if (t > t_sep + 1e-6 && g0 > 0 && g1 <= 0) {  // linear interpolation inside the tiny step
      const double x = g0 / (g0 - g1);
      t_imp = t + x * h;
      v_imp = lift(s, t_imp).Xdot - (v + x * (vn - v));
      break;
    }
    q = qn;
    v = vn;
    t += h;
  }
  ASSERT_GT(t_imp, 0) << "no impact within a revolution";
  s.run.t_end = t_imp + 0.1 * (t_imp - t_sep);
  Simulator sim(s, f);
  const Summary sum = sim.run();
  ASSERT_TRUE(sum.finished) << sum.message;
  ASSERT_GE(sum.events.size(), 2u) << c.name;
  EXPECT_EQ(std::string(to_string(sum.events[0].type)), "separation");
  EXPECT_EQ(std::string(to_string(sum.events[1].type)), "impact");
  std::printf("%s: separation %.3g s off, impact %.3g s off, approach %.6g vs %.6g m/s\n", c.name,
              sum.events[0].t - t_sep, sum.events[1].t - t_imp, sum.events[1].impact_velocity, v_imp);
  EXPECT_NEAR(sum.events[0].t, t_sep, 1e-9 * t_sep) << c.name;
  EXPECT_NEAR(sum.events[1].t, t_imp, 1e-8 * t_imp) << c.name;
  EXPECT_NEAR(sum.events[1].impact_velocity, v_imp, 1e-5 * v_imp) << c.name;
}

INSTANTIATE_TEST_SUITE_P(Methods, UserFollower,
                         ::testing::Values(Case{ContactModel::Lee, Integrator::ArkodeErk, "lee_erk"},
                                           Case{ContactModel::Lee, Integrator::ArkodeDirk, "lee_dirk"},
                                           Case{ContactModel::Event, Integrator::ArkodeErk, "event_erk"},
                                           Case{ContactModel::Event, Integrator::CvodeBdf, "event_cvode"}),
                         [](const auto& i) { return std::string(i.param.name); });

// Bad followers are named like bad scene keys.
// On cvode-bdf the event method and Lee inside CVODE's step use the follower's
// force_jacobian (projected on the held contact) for the Newton matrix, not difference
// quotients; the held force stays the closed form.
TEST(UserFollower, CvodeUsesTheFollowersJacobian) {
  for (ContactModel m : {ContactModel::Event, ContactModel::Lee}) {
    const auto f = std::make_shared<CubicSpringFollower>();
    Scene s = cam_scene(5.0, m, Integrator::CvodeBdf);
    s.run.t_end = 0.05;
    Simulator sim(s, f);
    const long calls_before = f->jacobian_calls;
    KeepRows rows;
    const Summary sum = sim.run(&rows);
    ASSERT_TRUE(sum.finished) << sum.message;
    EXPECT_GT(f->jacobian_calls, calls_before) << to_string(m);
    double dF = 0, Fmax = 0;
    for (const HistoryRow& r : rows.rows) {
      if (!r.in_contact) continue;
      const CamMotion c = lift(s, r.t);
      const double F = f->m * c.Xddot + f->spring(c.X);
      dF = std::max(dF, std::abs(r.contact_force - F));
      Fmax = std::max(Fmax, std::abs(F));
    }
    std::printf("%s on cvode-bdf: %ld Jacobian calls, held force |dF|/Fmax %.2e\n", to_string(m),
                f->jacobian_calls - calls_before, dF / Fmax);
    EXPECT_LT(dF, 1e-6 * Fmax) << to_string(m);
  }
}

TEST(UserFollowerInput, BadContactRowIsNamed) {
  struct Bad : CubicSpringFollower {
    std::vector<FollowerContact> contacts() const override {
      FollowerContact c;
      c.name = "cam";
      c.row = {1.0, 0.0};
      return {c};
    }
  };
  try {
    Simulator sim(cam_scene(5.0, ContactModel::Lee, Integrator::ArkodeErk), std::make_shared<Bad>());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "<follower>: key 'contacts()[0].row' = 2 entries: must have size() = 1 entries");
  }
}

}  // namespace
}  // namespace camdyn
