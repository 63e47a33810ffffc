// Networks with several contacts (issue 16), against closed forms:
//   * two masses, a spring and a lash between them, cam at rest: impact time, approach
//     velocity and impulse m₂(1 + e)v (the cam holds the lower mass);
//   * a valve dropped on its seat: impact times and velocities v, ev, e²v, … (a
//     conservative oscillator between impacts), and with e = 0 it stays; its fourth impact
//     time's error follows the tolerance;
//   * a rigid train (tappet, rocker lever, valve, springs): the float speed from the
//     required-force closed form, simulated at ±1e-4 around it;
//   * a multi-mass valve spring: first surge frequency → ½√(k/m_s) like N⁻²;
//   * a single-contact network against the same follower as a rigid / elastic_bar scene
//     (a second formulation).
// The methods against each other on two-contact trains: tests/contact/test_network_methods_agree.cpp.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>
#include <string>

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/output.hpp"
#include "camdyn/simulator.hpp"
#include "mechanism/mechanism.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

NodeSpec node(std::string name, double mass, double q0 = 0.0, double v0 = 0.0) {
  NodeSpec n;
  n.name = std::move(name);
  n.mass = mass;
  n.initial_displacement = q0;
  n.initial_velocity = v0;
  return n;
}
ElementSpec spring(std::string lower, std::string upper, double k, double preload = 0.0) {
  ElementSpec e;
  e.kind = ElementKind::Spring;
  e.nodes = {std::move(lower), std::move(upper)};
  e.stiffness = k;
  e.preload = preload;
  return e;
}
ElementSpec lever(std::string in, std::string out, double ratio) {
  ElementSpec e;
  e.kind = ElementKind::Lever;
  e.nodes = {std::move(in), std::move(out)};
  e.ratio = ratio;
  return e;
}
ContactPointSpec contact(std::string name, ContactPointKind kind, std::vector<std::string> nodes,
                         double clearance = 0.0) {
  ContactPointSpec c;
  c.name = std::move(name);
  c.kind = kind;
  c.nodes = std::move(nodes);
  c.clearance = clearance;
  return c;
}

// A network scene on a circle cam (R = 0.02, e = 0.004 m); `speed` rev/s.
Scene net_scene(double speed) {
  Scene s = default_scene();
  s.title = "network test";
  s.cam.profile = CamProfileKind::Circle;
  s.cam.radius = 0.02;
  s.cam.eccentricity = 0.004;
  s.cam.speed_rev_s = speed;
  s.cam.theta0_deg = 180.0;  // on the base circle (X_C minimal): q = 0 touches the cam
  s.follower.kind = FollowerKind::Network;
  s.contact.model = ContactModel::Lee;
  s.contact.tol_u = 1e-10;
  s.solver.integrator = Integrator::ArkodeErk;
  s.solver.rtol = 1e-9;
  s.solver.atol = 1e-13;
  s.run.output_dt = 0.0;
  return s;
}

using camdyn_test::NetRun;
NetRun run(const Scene& s) { return camdyn_test::run_keeping_rows(s); }
std::vector<ContactEvent> events_of(const Summary& s, const std::string& kind, const std::string& contact) {
  std::vector<ContactEvent> out;
  for (const ContactEvent& e : s.events)
    if (to_string(e.type) == kind && e.contact == contact) out.push_back(e);
  return out;
}

struct Method {
  ContactModel model;
  Integrator integrator;
  const char* name;
};
const Method kExactMethods[] = {{ContactModel::Lee, Integrator::ArkodeErk, "lee_erk"},
                                {ContactModel::Lee, Integrator::ArkodeDirk, "lee_dirk"},
                                {ContactModel::Event, Integrator::ArkodeErk, "event_erk"},
                                {ContactModel::Event, Integrator::CvodeBdf, "event_cvode"}};

// ---- two masses, spring and lash; the cam at rest holds the lower mass ----------------
// b (m₂) moves down from q = 0 with speed V; while the lash is open and the cam holds a,
// m₂ z̈ = −(k + k₂) z: z = −(V/ω) sin ωt, the lash (clearance c) closes at
// t* = asin(cω/V)/ω with approach √(V² − c²ω²); the lash impulse is m₂(1 + e)·approach.
class TwoMassLash : public ::testing::TestWithParam<std::tuple<Method, double>> {};

TEST_P(TwoMassLash, ImpactTimeVelocityAndImpulse) {
  const auto [method, e] = GetParam();
  const double m1 = 0.1, m2 = 0.05, k = 1e4, k2 = 5e3, c = 1e-3, V = 1.0;
  Scene s = net_scene(0.0);
  s.cam.theta0_deg = 180.0;  // base circle (X_C minimal), cam at rest
  s.contact.model = method.model;
  s.solver.integrator = method.integrator;
  s.contact.restitution = e;
  s.network.nodes = {node("a", m1), node("b", m2, 0.0, -V)};
  s.network.elements = {spring("a", "b", k), spring("b", "ground", k2)};
  s.network.contacts = {contact("cam", ContactPointKind::Cam, {"a"}),
                        contact("lash", ContactPointKind::Lash, {"a", "b"}, c)};
  const double w = std::sqrt((k + k2) / m2);
  const double t_imp = std::asin(c * w / V) / w, v_imp = std::sqrt(V * V - c * c * w * w);
  s.run.t_end = 1.05 * t_imp;
  const NetRun r = run(s);
  ASSERT_TRUE(r.sum.finished) << r.sum.message;
  const auto imp = events_of(r.sum, "impact", "lash");
  ASSERT_EQ(imp.size(), 1u);
  EXPECT_NEAR(imp[0].t, t_imp, 1e-8 * t_imp) << method.name;
  EXPECT_NEAR(imp[0].impact_velocity, v_imp, 1e-7 * v_imp) << method.name;
  EXPECT_NEAR(imp[0].impulse, m2 * (1 + e) * v_imp, 1e-7 * m2 * v_imp) << method.name;
  // after the impact: b moves away at e·approach (a held at rest by the cam)
  const HistoryRow& last = r.rows.back();
  const double zdot = r.col(last, "v_b") - r.col(last, "v_a");
  const double dt = last.t - t_imp;
  // z(t) after the impact: from z = −c with ż = e·v_imp (free oscillation about 0)
  const double z_exp = -c * std::cos(w * dt) + e * v_imp / w * std::sin(w * dt);
  const double zd_exp = c * w * std::sin(w * dt) + e * v_imp * std::cos(w * dt);
  EXPECT_NEAR(r.col(last, "u_b") - r.col(last, "u_a"), z_exp, 1e-8) << method.name;
  EXPECT_NEAR(zdot, zd_exp, 1e-6) << method.name;
  // no other event in this window, but for e = 0: the springs push b back at once, the
  // lash opens at the instant it closed (its force would pull)
  ASSERT_EQ(r.sum.events.size(), e == 0.0 ? 2u : 1u) << method.name;
  if (e == 0.0) {
    EXPECT_EQ(std::string(to_string(r.sum.events[1].type)), "separation");
    EXPECT_EQ(r.sum.events[1].contact, "lash");
    EXPECT_EQ(r.sum.events[1].t, imp[0].t);
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, TwoMassLash,
                         ::testing::Combine(::testing::ValuesIn(kExactMethods), ::testing::Values(0.0, 0.6)),
                         [](const auto& i) {
                           return std::string(std::get<0>(i.param).name) +
                                  (std::get<1>(i.param) == 0.0 ? "_plastic" : "_e06");
                         });

// ---- a valve dropped on its seat ------------------------------------------------------
// m ẍ = −P − k x from x₀ at rest: x = −d + (x₀ + d) cos ωt, d = P/k; the first impact at
// cos ωt₁ = d/(x₀ + d) with v₁ = (x₀ + d) ω sin ωt₁. Each bounce leaves with e·v and
// returns after Δt = 2 atan(e v/(ω d))/ω with the same speed: v, ev, e²v, …
class ValveSeat : public ::testing::TestWithParam<Method> {};

TEST_P(ValveSeat, BouncesWithTheRestitutionGiven) {
  const Method method = GetParam();
  const double m = 0.05, k = 3e4, P = 300.0, x0 = 2e-3, e = 0.7;
  Scene s = net_scene(0.0);
  s.contact.model = method.model;
  s.solver.integrator = method.integrator;
  s.network.nodes = {node("valve", m, x0)};
  s.network.elements = {spring("valve", "ground", k, P)};
  auto seat = contact("seat", ContactPointKind::Stop, {"valve"});
  seat.restitution = e;
  s.network.contacts = {seat};
  const double w = std::sqrt(k / m), d = P / k;
  double t = std::acos(d / (x0 + d)) / w, v = (x0 + d) * w * std::sin(w * t);
  std::vector<std::pair<double, double>> expect;
  for (int i = 0; i < 4; ++i) {
    expect.emplace_back(t, v);
    t += 2.0 * std::atan(e * v / (w * d)) / w;
    v *= e;
  }
  s.run.t_end = 0.5 * (expect[3].first + t);
  const NetRun r = run(s);
  ASSERT_TRUE(r.sum.finished) << r.sum.message;
  const auto imp = events_of(r.sum, "impact", "seat");
  ASSERT_EQ(imp.size(), 4u) << method.name;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(imp[i].t, expect[i].first, 1e-8 * expect[i].first) << method.name << " impact " << i;
    EXPECT_NEAR(imp[i].impact_velocity, expect[i].second, 1e-6 * expect[0].second) << method.name << " impact " << i;
  }
  // the ratio of successive approach velocities is e
  for (int i = 1; i < 4; ++i)
    EXPECT_NEAR(imp[i].impact_velocity / imp[i - 1].impact_velocity, e, 1e-6) << method.name;
}

TEST_P(ValveSeat, PlasticImpactStays) {
  const Method method = GetParam();
  const double m = 0.05, k = 3e4, P = 300.0, x0 = 2e-3;
  Scene s = net_scene(0.0);
  s.contact.model = method.model;
  s.solver.integrator = method.integrator;
  s.network.nodes = {node("valve", m, x0)};
  s.network.elements = {spring("valve", "ground", k, P)};
  s.network.contacts = {contact("seat", ContactPointKind::Stop, {"valve"})};
  s.run.t_end = 0.01;
  const NetRun r = run(s);
  ASSERT_TRUE(r.sum.finished) << r.sum.message;
  EXPECT_EQ(events_of(r.sum, "impact", "seat").size(), 1u) << method.name;
  EXPECT_EQ(events_of(r.sum, "separation", "seat").size(), 0u) << method.name;
  const HistoryRow& last = r.rows.back();
  EXPECT_EQ(last.in_contact, 1);
  EXPECT_NEAR(last.contact_force, P, 1e-9 * P) << method.name;  // the seat carries the preload
  EXPECT_NEAR(r.col(last, "u_valve"), 0.0, 1e-12) << method.name;
}

INSTANTIATE_TEST_SUITE_P(Methods, ValveSeat, ::testing::ValuesIn(kExactMethods),
                         [](const auto& i) { return std::string(i.param.name); });

// ---- rigid train: tappet → rocker (ratio r) → valve -------------------------------------
// One unknown q (the tappet); the valve moves r·q. The cam contact needs
//   F = m_eq Ẍ + k_eq X + P_eq ≥ 0,  m_eq = m_t + r² m_v, k_eq = k_t + r² k_v, P_eq = P_t + r P_v,
// at constant ω: Ẍ = h″ω², so the follower floats first at
//   ω_f² = min over h″ < 0 of (k_eq X + P_eq) / (−m_eq h″).
struct RigidTrain {
  double mt = 0.04, mv = 0.05, r = 1.5, kt = 2e3, kv = 3e4, Pt = 20.0, Pv = 250.0;
  Scene scene() const {
    Scene s = net_scene(10.0);
    s.network.nodes = {node("tappet", mt), node("valve", mv)};
    s.network.elements = {lever("tappet", "valve", r), spring("tappet", "ground", kt, Pt),
                          spring("valve", "ground", kv, Pv)};
    s.network.contacts = {contact("cam", ContactPointKind::Cam, {"tappet"})};
    return s;
  }
  // The float speed [rev/s] from the required force on the cam's own geometry (lift above
  // the base circle), scanned and refined by ternary search.
  double closed_form_rev_s() const {
    const Scene s = scene();
    const double meq = mt + r * r * mv, keq = kt + r * r * kv, Peq = Pt + r * Pv;
    const Cam cam(s.cam);
    double Xmin = INFINITY;
    for (int i = 0; i < 36000; ++i) Xmin = std::min(Xmin, cam.evaluate(i * 2 * M_PI / 36000).X_C);
    auto ratio = [&](double th) {
      const CamPoint p = cam.evaluate(th);
      return p.d2X_dtheta2 < 0 ? (keq * (p.X_C - Xmin) + Peq) / (-meq * p.d2X_dtheta2) : INFINITY;
    };
    double best = INFINITY, th_best = 0;
    for (int i = 0; i < 3600; ++i)
      if (ratio(i * 2 * M_PI / 3600) < best) best = ratio(th_best = i * 2 * M_PI / 3600);
    double a = th_best - 2 * M_PI / 3600, b = th_best + 2 * M_PI / 3600;
    for (int i = 0; i < 100; ++i) {
      const double c1 = a + (b - a) / 3, c2 = b - (b - a) / 3;
      (ratio(c1) < ratio(c2) ? b : a) = ratio(c1) < ratio(c2) ? c2 : c1;
    }
    return std::sqrt(ratio(0.5 * (a + b))) / (2 * M_PI);
  }
};

TEST(RigidTrain, FloatSpeedMatchesTheRequiredForceClosedForm) {
  const RigidTrain train;
  const Scene s = train.scene();
  const double n_f = train.closed_form_rev_s();
  for (double f : {1.0 - 1e-4, 1.0 + 1e-4}) {
    Scene sf = s;
    sf.cam.speed_rev_s = n_f * f;
    sf.run.t_end = 1.0 / sf.cam.speed_rev_s;  // one revolution
    const NetRun rr = run(sf);
    ASSERT_TRUE(rr.sum.finished) << rr.sum.message << " at " << sf.cam.speed_rev_s << " rev/s";
    if (f < 1.0)
      EXPECT_EQ(rr.sum.separations, 0) << "floats below the closed-form speed " << n_f;
    else
      EXPECT_GT(rr.sum.separations, 0) << "does not float above the closed-form speed " << n_f;
  }
}

// camdyn jump on a network: bisection on "the cam contact separates on the lift".
TEST(RigidTrain, JumpSpeedBySimulationMatchesTheClosedForm) {
  const RigidTrain train;
  Scene s = train.scene();
  s.run.t_end = 1.0 / 150.0;  // a revolution at the lowest speed tried
  JumpOptions o;
  o.rel_tol = 1e-6;
  o.lo_rev_s = 150.0;
  o.hi_rev_s = 250.0;
  const JumpResult r = jump_speed(s, o);
  EXPECT_EQ(r.method, "simulation");
  EXPECT_NEAR(r.jump_speed_rev_s, train.closed_form_rev_s(), 1e-5 * train.closed_form_rev_s());
}

// ---- multi-mass valve spring --------------------------------------------------------------
// The spring (k, m_s, N masses) with both ends held (the valve on its seat): its first
// surge frequency tends to ½√(k/m_s) Hz, the error falling like N⁻².
TEST(SurgeSpring, FirstSurgeFrequencyConvergesLikeNMinus2) {
  const double k = 4e4, ms = 0.03;
  const double f_exact = 0.5 * std::sqrt(k / ms);
  std::vector<double> err;
  const int Ns[] = {4, 8, 16, 32};
  for (int N : Ns) {
    Scene s = net_scene(0.0);
    ElementSpec sp = spring("valve", "ground", k, 250.0);
    sp.mass = ms;
    sp.masses = N;
    s.network.nodes = {node("valve", 0.05)};
    s.network.elements = {sp};
    s.network.contacts = {contact("seat", ContactPointKind::Stop, {"valve"})};
    validate(s);
    const Mechanism mech(s);
    ASSERT_EQ(mech.n(), N + 1);
    // valve held: unknown 0 (the named node) removed
    const Eigen::MatrixXd K = Eigen::MatrixXd(mech.K()).bottomRightCorner(N, N),
                          M = Eigen::MatrixXd(mech.M()).bottomRightCorner(N, N);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    const double f1 = std::sqrt(es.eigenvalues()[0]) / (2 * M_PI);
    err.push_back(std::abs(f1 - f_exact) / f_exact);
  }
  // observed order in N + 1 (the number of coil segments): 2
  for (size_t i = 1; i < err.size(); ++i)
    EXPECT_NEAR(std::log(err[i - 1] / err[i]) / std::log((Ns[i] + 1.0) / (Ns[i - 1] + 1.0)), 2.0, 0.01)
        << "N = " << Ns[i];
  EXPECT_LT(err.back(), 1e-3);
}

// ---- one contact: a network against the rigid / elastic_bar scene of the same follower ---
// The network's cam contact sees the lift (X_C − min X_C), the rigid scene X_C itself: the
// contact forces and gaps must agree, displacements differ by the base circle.
TEST(SingleContactNetwork, MatchesTheRigidFollowerScene) {
  Scene rigid = paper_case("A");
  rigid.run.t_end = 0.6;
  rigid.run.output_dt = 1e-3;
  rigid.solver.rtol = 1e-10;
  rigid.solver.atol = 1e-12;
  rigid.contact.tol_u = 1e-10;
  // The network measures q from the base circle (min X_C; this cam's spline dips to 1.98
  // below its knot radius 2.0): start at the lift x_l = X_C(θ₀) − min X_C with the preload
  // there equal to k δ₀.
  const Cam cam(rigid.cam);
  double Xmin = INFINITY;
  for (int i = 0; i < 3600; ++i) Xmin = std::min(Xmin, cam.evaluate(i * 2 * M_PI / 3600).X_C);
  {
    double a = 0, b = 2 * M_PI;
    for (int i = 0; i < 3600; ++i)
      if (cam.evaluate(i * 2 * M_PI / 3600).X_C == Xmin) a = (i - 1) * 2 * M_PI / 3600, b = a + 4 * M_PI / 3600;
    for (int i = 0; i < 200; ++i) {
      const double c1 = a + (b - a) / 3, c2 = b - (b - a) / 3;
      if (cam.evaluate(c1).X_C < cam.evaluate(c2).X_C) b = c2; else a = c1;
    }
    Xmin = std::min(Xmin, cam.evaluate(0.5 * (a + b)).X_C);
  }
  const double x_l = cam.evaluate(0.0).X_C - Xmin, k = rigid.spring.stiffness;
  Scene net = rigid;
  net.follower.kind = FollowerKind::Network;
  net.network.nodes = {node("f", rigid.follower.mass, x_l)};
  net.network.elements = {spring("f", "ground", k, k * rigid.spring.precompression - k * x_l)};
  net.network.contacts = {contact("cam", ContactPointKind::Cam, {"f"})};
  const NetRun a = run(rigid), b = run(net);
  ASSERT_TRUE(a.sum.finished) << a.sum.message;
  ASSERT_TRUE(b.sum.finished) << b.sum.message;
  ASSERT_EQ(a.rows.size(), b.rows.size());
  double Fmax = 0, dF = 0, dg = 0;
  for (size_t i = 0; i < a.rows.size(); ++i) {
    Fmax = std::max(Fmax, std::abs(a.rows[i].contact_force));
    dF = std::max(dF, std::abs(a.rows[i].contact_force - b.rows[i].contact_force));
    dg = std::max(dg, std::abs(a.rows[i].gap - b.rows[i].gap));
  }
  EXPECT_LT(dF, 1e-6 * Fmax);
  EXPECT_LT(dg, 1e-8);
  EXPECT_EQ(a.sum.separations, b.sum.separations);
  EXPECT_EQ(a.sum.impacts, b.sum.impacts);
}

// The tolerance controls the error at impacts on a network: the bouncing valve's fourth
// impact time (closed form) against rtol, for Lee and the event-driven method.
TEST(NetworkTolerance, ImpactTimeErrorFollowsTheTolerance) {
  const double m = 0.05, k = 3e4, P = 300.0, x0 = 2e-3, e = 0.7;
  const double w = std::sqrt(k / m), d = P / k;
  double t = std::acos(d / (x0 + d)) / w, v = (x0 + d) * w * std::sin(w * t);
  for (int i = 0; i < 3; ++i) {
    t += 2.0 * std::atan(e * v / (w * d)) / w;
    v *= e;
  }
  const double t4 = t;  // the fourth impact
  for (const Method& method : kExactMethods) {
    std::vector<double> err;
    for (double rtol : {1e-5, 1e-7, 1e-9}) {
      Scene s = net_scene(0.0);
      s.contact.model = method.model;
      s.solver.integrator = method.integrator;
      s.solver.rtol = rtol;
      s.solver.atol = 1e-3 * rtol * x0;
      s.contact.tol_u = rtol * x0;
      s.network.nodes = {node("valve", m, x0)};
      s.network.elements = {spring("valve", "ground", k, P)};
      auto seat = contact("seat", ContactPointKind::Stop, {"valve"});
      seat.restitution = e;
      s.network.contacts = {seat};
      s.run.t_end = 1.05 * t4;
      const NetRun r = run(s);
      ASSERT_TRUE(r.sum.finished) << r.sum.message;
      const auto imp = events_of(r.sum, "impact", "seat");
      ASSERT_GE(imp.size(), 4u) << method.name << " rtol " << rtol;
      err.push_back(std::abs(imp[3].t - t4) / t4);
      std::printf("%s rtol %g: 4th impact time error %.3g (relative), %ld steps, cpu %.3g s\n", method.name, rtol,
                  err.back(), r.sum.steps, r.sum.cpu_seconds);
      EXPECT_LT(err.back(), 100 * rtol) << method.name << " rtol " << rtol;
    }
    EXPECT_LT(err[2], err[0]) << method.name << ": the error does not fall with the tolerance";
  }
}

}  // namespace
}  // namespace camdyn
