// Springs whose coils clash (a spring with coil masses and coil_gaps / free_length /
// solid_length: one unilateral coil-to-coil contact per segment of its coil chain) against
// independent truth:
//   * the static force–deflection curve of a variable-pitch spring: the piecewise-linear
//     closed form x(L) = Σ_s min((L − P)/k_s, g_s) (k_s = (N + 1)k per segment, each
//     segment closing at its gap g_s), for one spring and for a nested pair (inner and
//     outer spring in parallel), on the event, Lee and penalty methods and on ARKODE ERK,
//     DIRK and CVODE BDF;
//   * a valve train whose spring surges into its coils: coil-clash events in summary.json's
//     coil_clash (count, first angle, speed) and none when the coils never close;
//   * bad coil keys: SceneError naming key, value and rule (gaps that do not add up to the
//     travel to solid, a wrong count, a negative gap, solid_length missing).
// The first surge frequency of an open spring of N coil masses against ½√(k/m_s) as N grows
// is tests/mechanism/test_network.cpp SurgeSpring.FirstSurgeFrequencyConvergesLikeNMinus2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

// Spring data: k, preload, free and solid length, coil masses, gap weights (variable pitch).
struct CoilSpring {
  std::string name;
  double k, P, free, solid, mass;
  int masses;
  std::vector<double> weights;  // gap of segment s ∝ weights[s]
  double travel() const { return free - P / k - solid; }
  std::vector<double> gaps() const {
    double w = 0;
    for (double x : weights) w += x;
    std::vector<double> g;
    for (double x : weights) g.push_back(travel() * x / w);
    return g;
  }
  double ks() const { return k * (masses + 1); }
  // The closed form: the static deflection x at a compressive force L (all segments carry L;
  // an open one is compressed (L − P)/k_s, a closed one by its gap; with a penalty contact
  // of stiffness k_pen, by g + (L − P − k_s g)/(k_s + k_pen): the segment and the penalty
  // spring in parallel beyond the gap).
  double deflection(double L, double kpen = INFINITY) const {
    double x = 0;
    for (double g : gaps()) {
      const double d = (L - P) / ks();
      x += d <= g ? d : g + (std::isinf(kpen) ? 0.0 : (L - P - ks() * g) / (ks() + kpen));
    }
    return x;
  }
  // Its inverse: the force at deflection x (bisection on the monotone x(L) below solid).
  double force(double x, double kpen = INFINITY) const {
    double lo = P, hi = P + ks() * travel() * 2;
    for (int i = 0; i < 200; ++i) {
      const double m = 0.5 * (lo + hi);
      (deflection(m, kpen) < x ? lo : hi) = m;
    }
    return 0.5 * (lo + hi);
  }
  ElementSpec spec() const {
    ElementSpec e;
    e.name = name;
    e.kind = ElementKind::Spring;
    e.nodes = {"valve", "ground"};
    e.stiffness = k;
    e.preload = P;
    e.mass = mass;
    e.masses = masses;
    e.damping = 5.0;
    e.free_length = free;
    e.solid_length = solid;
    e.coil_gaps = gaps();
    e.coil_restitution = 0.0;
    return e;
  }
};

const CoilSpring kOuter{"outer", 30e3, 200.0, 0.045, 0.025, 0.02, 3, {1, 2, 3, 4}};
const CoilSpring kInner{"inner", 12e3, 90.0, 0.040, 0.022, 0.01, 2, {3, 1, 2}};

// A valve of 50 g on the springs [valve, ground] (its lift q compresses them), lifted by a
// constant force L (a spring [ground, valve] of stiffness 0 and preload L pushes the valve by
// +L), a dashpot to ground, a stop far above.
Scene loaded_valve(const std::vector<CoilSpring>& springs, double L, ContactModel model, Integrator integ) {
  Scene s = default_scene();
  s.title = "coil clash static";
  s.follower.kind = FollowerKind::Network;
  NodeSpec v;
  v.name = "valve";
  v.mass = 0.05;
  s.network.nodes = {v};
  for (const CoilSpring& c : springs) s.network.elements.push_back(c.spec());
  ElementSpec load;
  load.name = "load";
  load.kind = ElementKind::Spring;
  load.nodes = {"ground", "valve"};
  load.preload = L;  // its upper end, the valve, pushed by +L: the springs compressed
  ElementSpec d;
  d.kind = ElementKind::Dashpot;
  d.nodes = {"valve", "ground"};
  d.damping = 60.0;
  s.network.elements.push_back(load);
  s.network.elements.push_back(d);
  ContactPointSpec stop;
  stop.name = "stop";
  stop.kind = ContactPointKind::Stop;
  stop.nodes = {"valve"};
  stop.side = StopSide::Above;  // g = clearance − q: never reached (q ≤ 13.3 mm, the travel)
  stop.clearance = 0.05;
  s.network.contacts = {stop};
  s.contact.model = model;
  s.solver.integrator = integ;
  s.solver.rtol = 1e-8;
  s.solver.atol = 1e-12;
  s.run.t_end = 0.15;
  s.run.output_dt = 0.005;
  return s;
}

// The valve's static position under L: x from the closed form (nested: the sum of the
// springs' forces at x is L).
double closed_form_position(const std::vector<CoilSpring>& springs, double L, double kpen = INFINITY) {
  double lo = 0, hi = 0.05;
  for (int i = 0; i < 200; ++i) {
    const double x = 0.5 * (lo + hi);
    double F = 0;
    for (const CoilSpring& c : springs) F += c.force(x, kpen);
    (F < L ? lo : hi) = x;
  }
  return 0.5 * (lo + hi);
}

TEST(CoilClash, StaticCurveIsThePiecewiseLinearClosedForm) {
  // kOuter's segments close at L = 360, 520, 680, 840 N: loads with 0, 1, 2 and 3 coils closed
  for (double L : {300.0, 450.0, 600.0, 800.0}) {
    SCOPED_TRACE(L);
    const camdyn_test::NetRun r =
        camdyn_test::run_keeping_rows(loaded_valve({kOuter}, L, ContactModel::Event, Integrator::ArkodeDirk));
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    const double want = kOuter.deflection(L);
    // measured |Δx| ≤ 4e-17 m (x up to 1.3e-2 m): the transient has decayed
    EXPECT_NEAR(r.col(r.rows.back(), "u_valve"), want, 1e-9);
    int closed = 0;
    for (int s = 0; s < 4; ++s) closed += r.col(r.rows.back(), "in_outer_coil" + std::to_string(s)) > 0.5;
    EXPECT_EQ(closed, L < 360 ? 0 : L < 520 ? 1 : L < 680 ? 2 : 3);
  }
}

struct Case {
  ContactModel model;
  Integrator integ;
  double tol;  // on the static position [m]
};

TEST(CoilClash, NestedSpringsStaticOnEveryMethodAndEngine) {
  const std::vector<CoilSpring> both{kOuter, kInner};
  const double L = 850.0;
  const double kpen = 1e8;  // N/m, the penalty runs' coil contacts
  // nested: x = 10.30 mm, outer 578 N (2 coils closed), inner 272 N (2 closed); the penalty
  // closed form (closed coils give way by their force excess over k_s + k_pen) lies 2.4e-6 m
  // beyond. Measured |Δx| against each: event, Lee ≤ 7e-17 m, penalty 2e-17 m
  const double want = closed_form_position(both, L), want_pen = closed_form_position(both, L, kpen);
  const Case cases[] = {{ContactModel::Event, Integrator::ArkodeDirk, 1e-9},
                        {ContactModel::Lee, Integrator::ArkodeErk, 1e-9},
                        {ContactModel::Lee, Integrator::CvodeBdf, 1e-9},
                        {ContactModel::Event, Integrator::CvodeBdf, 1e-9},
                        {ContactModel::Penalty, Integrator::ArkodeErk, 1e-9}};
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(to_string(c.integ)) + " " + to_string(c.model));
    Scene s = loaded_valve(both, L, c.model, c.integ);
    s.contact.penalty_stiffness = kpen;
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    EXPECT_NEAR(r.col(r.rows.back(), "u_valve"), c.model == ContactModel::Penalty ? want_pen : want, c.tol);
    ASSERT_EQ(r.sum.coil_clash.size(), 2u);
    EXPECT_EQ(r.sum.coil_clash[0].spring, "outer");
    EXPECT_EQ(r.sum.coil_clash[1].spring, "inner");
  }
}

// A direct-acting valve train on an eccentric circle cam (lift e(1 + cos θ), 9 mm, started on
// its base circle at θ = 180°) whose spring (k 30 N/mm, preload 250 N, 5 coil segments) has
// 11 mm of travel to solid: with variable pitch (gaps 1.1, 2.2, 2.2, 2.2, 3.3 mm) the first
// segment closes when its share of the lift, lift/5, reaches 1.1 mm, at 5.5 mm lift
// (quasi-static closed form); with equal gaps (2.2 mm, 1.8 mm taken at full lift) none closes.
Scene clashing_train(std::vector<double> gaps) {
  Scene s = default_scene();
  s.title = "coil clash train";
  s.cam.profile = CamProfileKind::Circle;
  s.cam.radius = 0.02;
  s.cam.eccentricity = 0.0045;
  s.cam.speed_rev_s = 40.0;
  s.cam.theta0_deg = 180.0;
  s.follower.kind = FollowerKind::Network;
  s.network = camdyn_test::one_node_valve_network(0.06, 30e3, 250.0, 0.0);
  ElementSpec& sp = s.network.elements[0];
  sp.mass = 0.025;
  sp.masses = 4;
  sp.damping = 1.0;
  sp.free_length = 0.045;
  sp.solid_length = 0.045 - 250.0 / 30e3 - 0.011;
  sp.coil_gaps = std::move(gaps);
  s.network.contacts.erase(s.network.contacts.begin() + 1);  // the cam only: no seat (a circle cam)
  s.contact.model = ContactModel::Event;
  s.solver.integrator = Integrator::ArkodeDirk;
  s.run.t_end = 1.0 / 40.0;
  s.run.output_dt = 1e-4;
  return s;
}

TEST(CoilClash, ValveTrainReportsCoilClashEvents) {
  const Scene sc = clashing_train({0.0011, 0.0022, 0.0022, 0.0022, 0.0033});
  const camdyn_test::NetRun clash = camdyn_test::run_keeping_rows(sc);
  ASSERT_EQ(clash.sum.termination, Termination::Finished) << clash.sum.message;
  ASSERT_EQ(clash.sum.coil_clash.size(), 1u);
  const CoilClashResult& c = clash.sum.coil_clash[0];
  EXPECT_EQ(c.spring, "valve_spring");
  EXPECT_GT(c.impacts, 0);
  EXPECT_GE(c.coils_closed, 1);
  EXPECT_GT(c.max_impact_velocity, 0.0);
  // the lift at the first clash against the quasi-static 5.5 mm (the coil masses' inertia
  // and the start's surge move it; measured 5.519 mm at 283.1 deg, one impact at 0.21 m/s)
  const Cam cam(sc.cam);
  const double lift = cam.evaluate(c.first_impact_theta_deg * M_PI / 180).X_C - (0.02 - 0.0045);
  EXPECT_NEAR(lift, 0.0055, 0.0008) << "first clash at " << c.first_impact_theta_deg << " deg";
  // the first coil to close is the one with the smallest gap
  for (const ContactResult& k : clash.sum.contacts)
    if (k.name == "valve_spring_coil0") EXPECT_GT(k.impacts, 0);
  long n = 0;
  for (const ContactResult& k : clash.sum.contacts) n += k.coil_spring == "valve_spring" ? k.impacts : 0;
  EXPECT_EQ(n, c.impacts);

  const camdyn_test::NetRun open = camdyn_test::run_keeping_rows(clashing_train({}));
  ASSERT_EQ(open.sum.termination, Termination::Finished) << open.sum.message;
  ASSERT_EQ(open.sum.coil_clash.size(), 1u);
  EXPECT_EQ(open.sum.coil_clash[0].impacts, 0);
  EXPECT_TRUE(std::isnan(open.sum.coil_clash[0].first_impact_theta_deg));
}

TEST(CoilClash, KeysRoundTripAndBadInputNamesKeyValueRule) {
  Scene s = loaded_valve({kOuter}, 300.0, ContactModel::Event, Integrator::ArkodeDirk);
  resolve_defaults(s);
  const Scene back = parse_scene(to_toml(s), "roundtrip");
  EXPECT_EQ(back.network.elements[0].coil_gaps, s.network.elements[0].coil_gaps);
  EXPECT_EQ(back.network.elements[0].solid_length, kOuter.solid);
  EXPECT_EQ(back.network.elements[0].coil_restitution, std::optional<double>(0.0));
  auto expect_error = [&](Scene bad, const std::string& key, const std::string& rule_part) {
    try {
      validate(bad);
      ADD_FAILURE() << "no error for " << key;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), key);
      EXPECT_NE(e.rule().find(rule_part), std::string::npos) << e.rule();
    }
  };
  {
    Scene b = s;
    b.network.elements[0].coil_gaps[1] += 1e-4;
    expect_error(b, "elements[0].coil_gaps", "must add up to the travel to solid");
  }
  {
    Scene b = s;
    b.network.elements[0].coil_gaps.pop_back();
    expect_error(b, "elements[0].coil_gaps", "masses + 1 = 4");
  }
  {
    Scene b = s;
    b.network.elements[0].coil_gaps[0] = -1e-4;
    b.network.elements[0].coil_gaps[1] += 2e-4;
    expect_error(b, "elements[0].coil_gaps[0]", ">= 0");
  }
  {
    Scene b = s;
    b.network.elements[0].solid_length = 0.0;
    expect_error(b, "elements[0].solid_length", "must be > 0");
  }
  {
    Scene b = s;
    b.network.elements[0].free_length = 0.03;
    expect_error(b, "elements[0].free_length", "must exceed solid_length");
  }
}

}  // namespace
}  // namespace camdyn
