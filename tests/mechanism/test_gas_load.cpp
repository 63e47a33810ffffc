// The cylinder's gas load on a valve head (scene type gas_load, −p(φ)·A on the valve;
// src/mechanism/elements/gas_load.hpp) against independent truth:
//   * the pressure table and the crank angle φ = crank_ratio·θ + offset against the test's
//     own periodic linear interpolation (wrap from the last point to the first one cycle on);
//   * a static offset under a constant pressure against p·A/k, on every method and engine;
//   * the opening force at lift-off: a two-mass valve train (tappet, stem, valve on its
//     seat) run slowly against a cylinder pressure falling over the opening; at the seat's
//     separation the stem force (the force that opens the valve) against P + p(φ_lo)·A with
//     p read from the table by the test at the lift-off angle;
//   * a table not monotone in angle, angles outside the cycle, a non-positive area:
//     SceneError naming key, value and rule.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/simulator.hpp"
#include "mechanism/elements/gas_load.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

ElementSpec gas(std::vector<double> phi, std::vector<double> p, double area) {
  ElementSpec e;
  e.name = "gas";
  e.kind = ElementKind::GasLoad;
  e.nodes = {"valve", "ground"};
  e.crank_angles_deg = std::move(phi);
  e.pressures = std::move(p);
  e.area = area;
  return e;
}

// The test's interpolation: periodic, linear, over a cycle of `cycle` degrees.
double table_pressure(const std::vector<double>& x, const std::vector<double>& y, double cycle, double phi) {
  phi = std::fmod(phi, cycle);
  if (phi < 0) phi += cycle;
  const std::size_t n = x.size();
  for (std::size_t k = 0; k + 1 < n; ++k)
    if (phi >= x[k] && phi <= x[k + 1]) return y[k] + (y[k + 1] - y[k]) * (phi - x[k]) / (x[k + 1] - x[k]);
  // the wrap segment from (x[n−1], y[n−1]) to (x[0] + cycle, y[0])
  const double xx = phi < x[0] ? phi + cycle : phi;
  return y[n - 1] + (y[0] - y[n - 1]) * (xx - x[n - 1]) / (x[0] + cycle - x[n - 1]);
}

TEST(GasLoad, TableAndCrankAngle) {
  CamSpec cam;
  cam.speed_rev_s = 25.0;
  cam.theta0_deg = 30.0;
  ElementSpec e = gas({10, 200, 370, 500}, {1e5, 4e6, 2e5, 5e5}, 1e-3);
  e.crank_offset_deg = 15.0;
  const GasLoad g(e, "gas", cam);
  const std::vector<double> x = e.crank_angles_deg, y = e.pressures;
  for (int i = 0; i < 400; ++i) {
    const double t = i * 1e-4;  // two cam revolutions: four engine cycles... of 720 crank deg each two
    const double theta_deg = 30.0 + 360.0 * 25.0 * t;
    const double phi = std::fmod(2.0 * theta_deg + 15.0, 720.0);
    EXPECT_NEAR(g.crank_angle_deg(t), phi, 1e-9);
    EXPECT_NEAR(g.pressure(phi), table_pressure(x, y, 720.0, phi), 1e-6) << phi;
    double f[2];
    const double xs[2] = {0, 0}, vs[2] = {0, 0};
    ElementState st;
    st.t = t;
    st.x = xs;
    st.xd = vs;
    g.force(st, f);
    EXPECT_NEAR(f[0], -table_pressure(x, y, 720.0, phi) * 1e-3, 1e-9);
    EXPECT_EQ(f[1], -f[0]);
  }
  // the wrap: between 500 and 730 deg, linear from 5e5 to 1e5
  EXPECT_NEAR(g.pressure(615.0), 3e5, 1e-6);
  EXPECT_NEAR(g.pressure(5.0), 5e5 + (1e5 - 5e5) * (725.0 - 500.0) / 230.0, 1e-6);
}

// A valve on a spring k (no preload), a dashpot, a constant pressure p on area A: it settles
// at x = −pA/k (pushed toward its seat side).
Scene constant_pressure(ContactModel model, Integrator integ) {
  Scene s = default_scene();
  s.title = "gas load static";
  s.follower.kind = FollowerKind::Network;
  NodeSpec v;
  v.name = "valve";
  v.mass = 0.05;
  s.network.nodes = {v};
  ElementSpec sp;
  sp.name = "spring";
  sp.kind = ElementKind::Spring;
  sp.nodes = {"valve", "ground"};
  sp.stiffness = 30e3;
  sp.damping = 40.0;
  s.network.elements = {sp, gas({0.0}, {2e5}, 1e-3)};
  ContactPointSpec stop;
  stop.name = "stop";
  stop.kind = ContactPointKind::Stop;
  stop.nodes = {"valve"};
  stop.side = StopSide::Below;  // g = q + 0.05: never reached at q = −6.7 mm
  stop.clearance = 0.05;
  s.network.contacts = {stop};
  s.contact.model = model;
  s.solver.integrator = integ;
  s.solver.rtol = 1e-9;
  s.solver.atol = 1e-13;
  s.run.t_end = 0.15;
  s.run.output_dt = 0.005;
  s.run.element_forces = true;
  return s;
}

TEST(GasLoad, StaticOffsetIsPAOverK) {
  const double want = -2e5 * 1e-3 / 30e3;  // −6.667 mm
  const std::pair<ContactModel, Integrator> cases[] = {{ContactModel::Lee, Integrator::ArkodeErk},
                                                       {ContactModel::Event, Integrator::ArkodeDirk},
                                                       {ContactModel::Penalty, Integrator::CvodeBdf},
                                                       {ContactModel::Lee, Integrator::CvodeBdf}};
  for (const auto& [model, integ] : cases) {
    SCOPED_TRACE(std::string(to_string(integ)) + " " + to_string(model));
    const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(constant_pressure(model, integ));
    ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
    // ζ = 0.52: after 0.15 s the transient has decayed (measured |Δx| ≤ 2e-18 m)
    EXPECT_NEAR(r.col(r.rows.back(), "u_valve"), want, 1e-10);
    EXPECT_EQ(r.col(r.rows.back(), "force_gas"), 200.0);
    // the gas's work is in the ledger (as signed dissipation): it closes
    EXPECT_LT(r.sum.energy_residual, 1e-6);  // measured ≤ 8.1e-8 J of the gas's 1.33 J
  }
}

// The two-mass OHC train (tappet on the cam, stem, valve on its seat, valve spring preload
// 250 N) at 2 rev/s, with a cylinder pressure falling linearly from 8 bar at crank angle 0 to
// 0.5 bar at 540 deg (and back over the wrap): the valve lifts off when the stem force
// reaches P + p(φ)·A.
TEST(GasLoad, OpeningForceAtLiftOffIsPreloadPlusPA) {
  Scene s = camdyn_test::two_mass_train();
  s.cam.speed_rev_s = 2.0;
  s.run.t_end = 0.5;
  s.run.output_dt = 2e-5;  // rows every 0.0144 deg of cam
  s.run.element_forces = true;
  const std::vector<double> phi{0.0, 540.0}, p{8e5, 0.5e5};
  const double A = 7e-4;
  s.network.elements.push_back(gas(phi, p, A));
  struct Keep : Observer {
    std::vector<HistoryRow> rows;
    std::vector<ContactEvent> events;
    void on_row(const HistoryRow& r) override { rows.push_back(r); }
    void on_event(const ContactEvent& e) override { events.push_back(e); }
  } keep;
  Simulator sim(s);
  camdyn_test::NetRun r;
  r.cols = sim.extra_columns();
  r.sum = sim.run(&keep);
  r.rows = keep.rows;
  ASSERT_EQ(r.sum.termination, Termination::Finished) << r.sum.message;
  const ContactEvent* lo = nullptr;
  for (const ContactEvent& e : keep.events)
    if (e.contact == "seat" && e.type == EventKind::Separation) {
      lo = &e;
      break;
    }
  ASSERT_NE(lo, nullptr);
  const double theta_deg = lo->theta * 180.0 / M_PI;
  const double p_lo = table_pressure(phi, p, 720.0, 2.0 * theta_deg);
  const double want = 250.0 + p_lo * A;
  // the stem force and the gas force at the lift-off: linear between the rows around it
  std::size_t k = 1;
  while (k + 1 < r.rows.size() && r.rows[k].t < lo->t) ++k;
  const HistoryRow &a = r.rows[k - 1], &b = r.rows[k];
  ASSERT_LE(a.t, lo->t);
  ASSERT_GE(b.t, lo->t);
  auto at = [&](const char* c) {
    const double x = (lo->t - a.t) / (b.t - a.t);
    return (1 - x) * r.col(a, c) + x * r.col(b, c);
  };
  EXPECT_NEAR(at("force_gas"), p_lo * A, 1e-6 * p_lo * A);
  // measured: lift-off at 84.64 deg, F_stem 645.391 N against P + p(φ)A = 645.429 N
  // (relative 5.9e-5: the valve's inertia at 2 rev/s and the rows' linear interpolation)
  EXPECT_NEAR(at("force_stem"), want, 2e-3 * want) << "lift-off at " << theta_deg << " deg";
}

TEST(GasLoad, BadTablesNameKeyValueAndRule) {
  auto expect_error = [](Scene bad, const std::string& key, const std::string& rule_part) {
    try {
      validate(bad);
      ADD_FAILURE() << "no error for " << key;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), key);
      EXPECT_NE(e.rule().find(rule_part), std::string::npos) << e.rule();
    }
  };
  const Scene s = constant_pressure(ContactModel::Event, Integrator::ArkodeDirk);
  Scene b = s;
  b.network.elements[1] = gas({0, 300, 200}, {1, 2, 3}, 1e-3);
  expect_error(b, "elements[1].crank_angles_deg[2]", "must be strictly increasing");
  b.network.elements[1] = gas({0, 300, 800}, {1, 2, 3}, 1e-3);
  expect_error(b, "elements[1].crank_angles_deg[2]", "< 360·crank_ratio = 720");
  b.network.elements[1] = gas({0, 300}, {1, 2, 3}, 1e-3);
  expect_error(b, "elements[1].pressures", "as many points");
  b.network.elements[1] = gas({0, 300}, {1, 2}, 0.0);
  expect_error(b, "elements[1].area", "must be > 0");
  b.network.elements[1] = gas({0, 300}, {1, 2}, 1e-3);
  b.network.elements[1].crank_ratio = 0;
  expect_error(b, "elements[1].crank_ratio", "must be > 0");
}

}  // namespace
}  // namespace camdyn
