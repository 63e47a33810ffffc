// Dependent contact sets (issue 28): two contacts on one node — the cam above a one-node
// valve and the valve's seat below it, rows T = [1; 1], W = T M⁻¹ Tᵀ singular whenever
// both are closed. Truths independent of the program:
//   * kinematics: while the cam drives the valve, u = X_C − clearance, so the largest
//     lift is the table's peak (8 mm) minus the clearance; the seat carries no force
//     while its gap is open; the valve never sinks into the seat or the cam by more than
//     the tolerance (penalty: by its law, F/k_p);
//   * a second formulation: the same valve as two nodes (a light tappet on a very stiff,
//     damped stem): the same events on the same contacts, at cam angles that differ by
//     the stem's compliance only (250 N / 10⁸ N/m at 0.12 m/s: < 0.25°);
//   * the LCP itself (src/contact/active_set.hpp) on hand-solved cases: the minimal-norm
//     split of redundant rows, the open-going contact dropped, a jam refused;
//   * a user FollowerSystem with the same two rows [1] gives the same lift.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "camdyn/cam.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/simulator.hpp"
#include "contact/active_set.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

// The OHC example's cam (8 mm lift table, 25 rev/s, contact and solver settings) with a
// one-node valve: 0.1 kg, valve spring 35 kN/m preloaded 250 N, cam and seat on it.
Scene one_node_valve(double clearance, ContactModel model, Integrator integ) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  s.contact.model = model;
  s.solver.integrator = integ;
  s.run.output_dt = 1e-5;
  s.network = camdyn_test::one_node_valve_network(0.1, 35000.0, 250.0, clearance);
  return s;
}

struct Rows : Observer {
  std::vector<HistoryRow> rows;
  void on_row(const HistoryRow& r) override { rows.push_back(r); }
};
double col(const std::vector<std::string>& cols, const HistoryRow& r, const std::string& name) {
  for (size_t i = 0; i < cols.size(); ++i)
    if (cols[i] == name) return r.extra[i];
  ADD_FAILURE() << "no column " << name;
  return NAN;
}

struct Case {
  ContactModel model;
  Integrator integ;
  double clearance;
  const char* name;
};
class OneNodeValve : public ::testing::TestWithParam<Case> {};

TEST_P(OneNodeValve, LiftIsTheCamsMinusTheClearanceAndTheSeatIsComplementary) {
  const Case c = GetParam();
  const Scene s = one_node_valve(c.clearance, c.model, c.integ);
  Simulator sim(s);
  Rows obs;
  const Summary sum = sim.run(&obs);
  ASSERT_TRUE(sum.finished) << sum.message;
  const std::vector<std::string> cols = sim.extra_columns();
  const bool penalty = c.model == ContactModel::Penalty;
  const double tol_u = s.contact.tol_u, kp = s.contact.penalty_stiffness;
  double umax = -1, Fcam_max = 0, Fseat_max = 0;
  for (const HistoryRow& r : obs.rows) {
    umax = std::max(umax, col(cols, r, "u_valve"));
    Fcam_max = std::max(Fcam_max, col(cols, r, "F_cam"));
    Fseat_max = std::max(Fseat_max, col(cols, r, "F_seat"));
  }
  // the valve follows the cam over the nose: the largest lift is 8 mm − clearance (the
  // rows every 10 µs, 0.09° of cam, sample the nose's flat top to < 1e-9 m); penalty: less
  // the cam's penetration under the nose load (< F_max/k_p)
  const double expect = 0.008 - c.clearance;
  if (penalty)
    EXPECT_NEAR(umax, expect - 0.5 * Fcam_max / kp, 0.5 * Fcam_max / kp + 1e-9) << c.name;
  else
    EXPECT_NEAR(umax, expect, 1e-9) << c.name;
  for (const HistoryRow& r : obs.rows) {
    const double gs = col(cols, r, "gap_seat"), Fs = col(cols, r, "F_seat");
    const double gc = col(cols, r, "gap_cam"), Fc = col(cols, r, "F_cam");
    if (gs > 10 * tol_u) ASSERT_EQ(Fs, 0.0) << c.name << " seat force on an open gap at t = " << r.t;
    if (gc > 10 * tol_u) ASSERT_EQ(Fc, 0.0) << c.name << " cam force on an open gap at t = " << r.t;
    // penalty: the law's static penetration F/k_p plus a landing's v√(m/k_p) at up to
    // 0.2 m/s (the lash is taken up on the ramps at 0.12 m/s)
    const double land = 0.2 * std::sqrt(0.1 / kp);
    const double pen_seat = penalty ? 1.01 * Fseat_max / kp + land : tol_u;
    const double pen_cam = penalty ? 1.01 * Fcam_max / kp + land : tol_u;
    ASSERT_GE(gs, -pen_seat) << c.name << " t = " << r.t;
    ASSERT_GE(gc, -pen_cam) << c.name << " t = " << r.t;
  }
  // the seat carries the preload on the base circle (the cam's lobe has not begun at 0°)
  EXPECT_NEAR(obs.rows.front().contact_force + col(cols, obs.rows.front(), "F_seat"), 250.0, 1e-6) << c.name;
}

const Case kCases[] = {
    {ContactModel::Lee, Integrator::ArkodeErk, 0.2e-3, "lee_erk_lash"},
    {ContactModel::Lee, Integrator::ArkodeDirk, 0.2e-3, "lee_dirk_lash"},
    {ContactModel::Lee, Integrator::CvodeBdf, 0.2e-3, "lee_cvode_lash"},
    {ContactModel::Event, Integrator::ArkodeErk, 0.2e-3, "event_erk_lash"},
    {ContactModel::Event, Integrator::ArkodeDirk, 0.2e-3, "event_dirk_lash"},
    {ContactModel::Event, Integrator::CvodeBdf, 0.2e-3, "event_cvode_lash"},
    {ContactModel::Penalty, Integrator::ArkodeErk, 0.2e-3, "penalty_erk_lash"},
    {ContactModel::Penalty, Integrator::ArkodeDirk, 0.2e-3, "penalty_dirk_lash"},
    {ContactModel::Penalty, Integrator::CvodeBdf, 0.2e-3, "penalty_cvode_lash"},
    {ContactModel::Lee, Integrator::ArkodeErk, 0.0, "lee_erk_no_lash"},
    {ContactModel::Event, Integrator::CvodeBdf, 0.0, "event_cvode_no_lash"},
    {ContactModel::Penalty, Integrator::ArkodeErk, 0.0, "penalty_erk_no_lash"},
};
INSTANTIATE_TEST_SUITE_P(Methods, OneNodeValve, ::testing::ValuesIn(kCases),
                         [](const auto& i) { return std::string(i.param.name); });

// ---- the second formulation: a light tappet on a very stiff, damped stem -------------
TEST(OneNodeValve, EventsAgreeWithATwoNodeValveOnAStiffStem) {
  const Scene one = one_node_valve(0.2e-3, ContactModel::Event, Integrator::ArkodeErk);
  Scene two = one;
  NodeSpec tappet;
  tappet.name = "tappet";
  tappet.mass = 0.005;
  two.network.nodes = {tappet, one.network.nodes[0]};
  two.network.nodes[1].mass = 0.095;
  ElementSpec stem;
  stem.name = "stem";
  stem.kind = ElementKind::Spring;
  stem.nodes = {"tappet", "valve"};
  stem.stiffness = 1e8;
  stem.damping = 1400.0;  // ≈ critical for the tappet–valve pair: no chatter on the cam
  two.network.elements.push_back(stem);
  two.network.contacts[0].nodes = {"tappet"};
  const Summary a = Simulator(one).run(), b = Simulator(two).run();
  ASSERT_TRUE(a.finished) << a.message;
  ASSERT_TRUE(b.finished) << b.message;
  ASSERT_EQ(a.events.size(), 4u);  // cam impact, seat separation; seat impact, cam separation
  ASSERT_EQ(b.events.size(), a.events.size());
  for (size_t i = 0; i < a.events.size(); ++i) {
    EXPECT_EQ(to_string(a.events[i].type), std::string(to_string(b.events[i].type))) << i;
    EXPECT_EQ(a.events[i].contact, b.events[i].contact) << i;
    EXPECT_NEAR(a.events[i].theta * 180 / M_PI, b.events[i].theta * 180 / M_PI, 0.25) << i;
  }
  // the cam impact: before it the stem is unloaded, so the two models meet the cam together
  EXPECT_NEAR(a.events[0].theta, b.events[0].theta, 1e-9);
  EXPECT_NEAR(a.events[0].impact_velocity, b.events[0].impact_velocity, 1e-6);
}

// ---- the LCP on hand-solved cases ------------------------------------------------------
TEST(ContactLcp, RedundantRowsShareByTheMinimalNorm) {
  // two equal rows on m = 0.1: W = 10 [1 1; 1 1]; both held at equal demand b = −2500:
  // F₁ + F₂ = 250, minimal norm 125 each
  Eigen::MatrixXd W = 10.0 * Eigen::MatrixXd::Ones(2, 2);
  const detail::ContactLcpResult r = detail::solve_contact_lcp(W, Eigen::Vector2d(-2500.0, -2500.0));
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.F[0], 125.0, 1e-9);
  EXPECT_NEAR(r.F[1], 125.0, 1e-9);
  EXPECT_NEAR(r.w.cwiseAbs().maxCoeff(), 0.0, 1e-9);
}

TEST(ContactLcp, TheOpenGoingContactCarriesNothing) {
  // the cam accelerates up by 300 m/s² more than the seat asks: the seat opens
  // (w = 300), the cam carries m (2500 + 300) = 280 N
  Eigen::MatrixXd W = 10.0 * Eigen::MatrixXd::Ones(2, 2);
  const detail::ContactLcpResult r = detail::solve_contact_lcp(W, Eigen::Vector2d(-2800.0, -2500.0));
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.F[0], 280.0, 1e-9);
  EXPECT_EQ(r.F[1], 0.0);
  EXPECT_NEAR(r.w[1], 300.0, 1e-9);
}

TEST(ContactLcp, ANodeDrivenIntoAStopJams) {
  // rows +1 (cam below) and −1 (a stop above): W = 10 [1 −1; −1 1], the cam drives the
  // node up into the stop: b = (−100, +50) has no bounded solution
  Eigen::MatrixXd W(2, 2);
  W << 10, -10, -10, 10;
  EXPECT_FALSE(detail::solve_contact_lcp(W, Eigen::Vector2d(-100.0, 50.0)).ok);
  // the node accelerating away from the stop (b₂ = 100 > 0) while the cam pushes it
  // (b₁ = −50): the cam carries 5 N (10 F₁ = 50), the stop nothing and opens at 50 m/s²
  const detail::ContactLcpResult r = detail::solve_contact_lcp(W, Eigen::Vector2d(-50.0, 100.0));
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.F[0], 5.0, 1e-12);
  EXPECT_EQ(r.F[1], 0.0);
  EXPECT_NEAR(r.w[1], 50.0, 1e-12);
}

// ---- a user FollowerSystem with the two rows [1] ---------------------------------------
struct OneNodeUser : FollowerSystem {
  double m = 0.1, k = 35000.0, P = 250.0, clearance = 0.2e-3;
  int size() const override { return 1; }
  std::vector<FollowerContact> contacts() const override {
    FollowerContact cam, seat;
    cam.name = "cam";
    cam.row = {1.0};
    cam.clearance = clearance;
    seat.name = "seat";
    seat.row = {1.0};
    seat.cam = false;
    return {cam, seat};
  }
  void force(double, const double* q, const double*, double* r) const override { r[0] = -(P + k * q[0]); }
  void solve_mass(const double* b, double* x) const override { x[0] = b[0] / m; }
  bool force_jacobian(double, const double*, const double*, double* dq, double* dv) const override {
    dq[0] = -k;
    dv[0] = 0.0;
    return true;
  }
  bool linear() const override { return true; }
};

class UserTwoRows : public ::testing::TestWithParam<Case> {};
TEST_P(UserTwoRows, SameLiftAndEventsAsTheNetwork) {
  const Case c = GetParam();
  const Scene s = one_node_valve(c.clearance, c.model, c.integ);
  auto f = std::make_shared<OneNodeUser>();
  f->clearance = c.clearance;
  Simulator sim(s, f);
  Rows obs;
  const Summary sum = sim.run(&obs);
  ASSERT_TRUE(sum.finished) << sum.message;
  const std::vector<std::string> cols = sim.extra_columns();
  double umax = -1;
  for (const HistoryRow& r : obs.rows) {
    umax = std::max(umax, col(cols, r, "u_q0"));
    if (col(cols, r, "gap_seat") > 10 * s.contact.tol_u) ASSERT_EQ(col(cols, r, "F_seat"), 0.0) << r.t;
    ASSERT_GE(col(cols, r, "gap_seat"), -s.contact.tol_u) << r.t;
  }
  EXPECT_NEAR(umax, 0.008 - c.clearance, 1e-9);
  const Summary net = Simulator(s).run();
  ASSERT_EQ(sum.events.size(), net.events.size());
  for (size_t i = 0; i < net.events.size(); ++i) {
    EXPECT_EQ(to_string(sum.events[i].type), std::string(to_string(net.events[i].type))) << i;
    EXPECT_EQ(sum.events[i].contact, net.events[i].contact) << i;
    EXPECT_NEAR(sum.events[i].t, net.events[i].t, 1e-9) << i;
  }
}
INSTANTIATE_TEST_SUITE_P(Methods, UserTwoRows,
                         ::testing::Values(Case{ContactModel::Lee, Integrator::ArkodeErk, 0.2e-3, "lee_erk"},
                                           Case{ContactModel::Event, Integrator::ArkodeErk, 0.2e-3, "event_erk"},
                                           Case{ContactModel::Lee, Integrator::ArkodeErk, 0.0, "lee_erk_no_lash"}),
                         [](const auto& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace camdyn

namespace camdyn {
namespace {

// ---- results per contact (issue 28) against a second path: the rows and events --------
// On the OHC example, ContactResult is recomputed here from what history.csv and
// events.csv hold (the rows' F_/in_ columns, the events' kind/contact/θ/speed) and the
// take-up window from the Cam API: rows with |X(θ) − clearance| ≤ 1 % of the lift.
TEST(ContactResults, OhcMatchTheRowsAndEvents) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  s.run.output_dt = 1e-5;
  Simulator sim(s);
  Rows obs;
  const Summary sum = sim.run(&obs);
  ASSERT_TRUE(sum.finished) << sum.message;
  const std::vector<std::string> cols = sim.extra_columns();
  const Cam cam(s.cam);
  const double lift = cam.lift();
  ASSERT_EQ(sum.contacts.size(), s.network.contacts.size());
  auto deg = [](double th) {
    double d = std::fmod(th * 180.0 / M_PI, 360.0);
    return d < 0 ? d + 360.0 : d;
  };
  auto in_window = [&](double theta) {
    const double X = cam.motion(theta, 1.0, 0.0).X - s.cam.base_radius;
    for (const ContactPointSpec& c : s.network.contacts)
      if (c.kind == ContactPointKind::Cam && std::abs(X - c.clearance) <= 0.01 * lift) return true;
    return false;
  };
  for (size_t j = 0; j < s.network.contacts.size(); ++j) {
    const std::string name = s.network.contacts[j].name;
    const ContactResult& cr = sum.contacts[j];
    EXPECT_EQ(cr.name, name);
    double minF = NAN, vmax = 0, first_imp = NAN, first_sep = NAN;
    long imp = 0, sep = 0;
    std::vector<double> Fr;  // the rows' forces while closed outside the window (NaN: not)
    for (const HistoryRow& r : obs.rows) {
      const bool closed = col(cols, r, "in_" + name) == 1.0 && !in_window(r.theta);
      Fr.push_back(closed ? col(cols, r, "F_" + name) : NAN);
      if (closed && (std::isnan(minF) || Fr.back() < minF)) minF = Fr.back();
    }
    // the change from the least row to its neighbours (closed ones)
    double dF = 0;
    for (std::size_t i = 0; i < Fr.size(); ++i)
      if (Fr[i] == minF) {
        if (i > 0 && !std::isnan(Fr[i - 1])) dF = std::max(dF, Fr[i - 1] - minF);
        if (i + 1 < Fr.size() && !std::isnan(Fr[i + 1])) dF = std::max(dF, Fr[i + 1] - minF);
      }
    for (const ContactEvent& e : sum.events) {
      if (e.contact != name) continue;
      if (e.type == EventKind::Impact) {
        ++imp;
        vmax = std::max(vmax, e.impact_velocity);
        if (std::isnan(first_imp)) first_imp = deg(e.theta);
      } else if (e.type == EventKind::Separation) {
        ++sep;
        if (std::isnan(first_sep)) first_sep = deg(e.theta);
        if (!in_window(e.theta)) minF = 0.0;
      }
    }
    EXPECT_EQ(cr.impacts, imp) << name;
    EXPECT_EQ(cr.separations, sep) << name;
    EXPECT_DOUBLE_EQ(cr.max_impact_velocity, vmax) << name;
    EXPECT_NEAR(cr.first_impact_theta_deg, first_imp, 1e-9) << name;
    EXPECT_NEAR(cr.first_separation_theta_deg, first_sep, 1e-9) << name;
    // the least force is located inside the steps (not at the rows): at most every row's,
    // and within the change from the least row to its neighbours (measured: 0.85 N below it
    // on the cam, 0.83 N on the seat, at the take-up window's edge; the neighbours differ
    // from the least row by 10.2 N and 12.7 N, rows 10 µs apart)
    EXPECT_LE(cr.min_force, minF + 1e-9 * std::abs(minF)) << name;
    EXPECT_GE(cr.min_force, minF - dF) << name;
  }
  // the cam's margin on the lobe, not the lash take-up's 1.7 N: the valve spring's
  // preload less the inertia on the nose is hundreds of newtons here
  EXPECT_GT(sum.contacts[0].min_force, 100.0);
  // the seat is closed on the base circle with the preload (250 N), then let go and landed
  EXPECT_EQ(sum.contacts[1].impacts, 1);
  EXPECT_EQ(sum.contacts[1].separations, 1);
}

}  // namespace
}  // namespace camdyn
