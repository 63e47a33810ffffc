// Lee's method on a network on cvode-bdf, the three levels inside CVODE's own step
// (src/contact/methods/lee_cvode.cpp): one camshaft revolution of the OHC and OHV trains
// against the event-driven method on arkode-erk at rtol 1e-12 (a second formulation on
// another engine, converged): the same events, times to 1e-8 s (issue 23), and the rows —
// which come from CVODE's interpolant between the step ends, put on the held contacts —
// against the reference's rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "camdyn/scene.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

using camdyn_test::NetRun;
using camdyn_test::run_keeping_rows;

struct RevCase {
  const char* name;
  const char* scene;
  const char* u1;  // two nodes whose displacements are compared row by row
  const char* u2;
  double dP;  // impulses, relative
};
class NetworkLeeCvodeRevolution : public ::testing::TestWithParam<RevCase> {};

TEST_P(NetworkLeeCvodeRevolution, EventsAndRowsMatchTheEventMethodOnErkAtTightTolerance) {
  const RevCase& c = GetParam();
  Scene lee = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/" + c.scene + ".toml");
  lee.run.t_end = 1.0 / lee.cam.speed_rev_s;  // one revolution
  lee.run.output_dt = 2e-6;  // the examples' rows: more rows than steps
  lee.contact.model = ContactModel::Lee;
  lee.solver.integrator = Integrator::CvodeBdf;
  Scene ref = lee;
  ref.contact.model = ContactModel::Event;
  ref.solver.integrator = Integrator::ArkodeErk;
  ref.solver.rtol = 1e-12;
  ref.solver.atol = 1e-16;
  const NetRun a = run_keeping_rows(lee), b = run_keeping_rows(ref);
  ASSERT_TRUE(a.sum.finished) << a.sum.message;
  ASSERT_TRUE(b.sum.finished) << b.sum.message;
  // events: the same impacts on the same contacts, times to 1e-8 s. The tail of a rattle
  // (lash and seat taking turns, impact speeds falling geometrically) ends where an approach
  // becomes a touch; that sticking speed follows each run's gap tolerance (rtol·X for the
  // event method, docs/tolerances.md), so the reference at rtol 1e-12 resolves more of the
  // tail than Lee at the scene's rtol. The impacts faster than 1 mm/s are compared.
  auto fast_impacts = [](const Summary& s) {
    std::vector<ContactEvent> v;
    for (const ContactEvent& e : s.events)
      if (e.type == EventKind::Impact && std::abs(e.impact_velocity) >= 1e-3) v.push_back(e);
    return v;
  };
  const std::vector<ContactEvent> ea = fast_impacts(a.sum), eb = fast_impacts(b.sum);
  ASSERT_EQ(ea.size(), eb.size());
  ASSERT_GE(ea.size(), 2u);
  // impulses: relative to the impact's own, at least a tenth of the largest (a rattle's slow
  // impacts near the sticking speed carry small impulses whose relative error grows)
  double P_max = 0;
  for (const ContactEvent& e : eb) P_max = std::max(P_max, std::abs(e.impulse));
  double dt_max = 0, dP_max = 0;
  for (size_t i = 0; i < ea.size(); ++i) {
    const ContactEvent &x = ea[i], &y = eb[i];
    EXPECT_EQ(x.contact, y.contact) << i;
    EXPECT_NEAR(x.t, y.t, 1e-8) << i << ' ' << x.contact;
    const double P_ref = std::max(std::abs(y.impulse), 0.1 * P_max);
    EXPECT_NEAR(x.impulse, y.impulse, c.dP * P_ref) << i;
    dt_max = std::max(dt_max, std::abs(x.t - y.t));
    dP_max = std::max(dP_max, std::abs(x.impulse - y.impulse) / P_ref);
  }
  // rows: on the same output times; the held contacts' gaps are zero to round-off (the
  // interpolated state is projected), the displacements within the step error
  ASSERT_EQ(a.rows.size(), b.rows.size());
  ASSERT_GT(a.rows.size(), size_t(a.sum.steps)) << "rows between the step ends";
  double g_held = 0, du = 0, u_scale = 0, dF = 0, F_scale = 0;
  std::vector<std::string> contacts;
  for (const std::string& n : a.cols)
    if (n.rfind("in_", 0) == 0) contacts.push_back(n.substr(3));
  for (size_t i = 0; i < a.rows.size(); ++i) {
    const HistoryRow &x = a.rows[i], &y = b.rows[i];
    ASSERT_NEAR(x.t, y.t, 1e-15) << i;
    for (const std::string& k : contacts)
      if (a.col(x, "in_" + k) != 0) g_held = std::max(g_held, std::abs(a.col(x, "gap_" + k)));
    for (const char* u : {c.u1, c.u2}) {
      du = std::max(du, std::abs(a.col(x, std::string("u_") + u) - b.col(y, std::string("u_") + u)));
      u_scale = std::max(u_scale, std::abs(b.col(y, std::string("u_") + u)));
    }
    // away from the events (a row within 1 µs of one may sit on either side of it)
    bool near_event = false;
    for (const ContactEvent& e : b.sum.events) near_event = near_event || std::abs(e.t - y.t) < 1e-6;
    if (!near_event) dF = std::max(dF, std::abs(x.contact_force - y.contact_force));
    F_scale = std::max(F_scale, std::abs(y.contact_force));
  }
  std::printf("%s: %zu events, max |dt| %.3g s, max dP/P %.3g; %ld steps, %zu rows; held |g| %.3g m, "
              "max |du| %.3g m (of %.3g), max |dF| %.3g N (of %.3g)\n",
              c.name, a.sum.events.size(), dt_max, dP_max, a.sum.steps, a.rows.size(), g_held, du, u_scale, dF,
              F_scale);
  EXPECT_LE(g_held, 1e-12);
  // 100 rtol of the lift; the force: the stiff stem (5e7 N/m on the OHC train) turns a
  // displacement error δ into k δ (measured 6.9e-10 m, 0.035 N on OHC)
  EXPECT_LE(du, 1e-6 * u_scale);
  EXPECT_LE(dF, 2e-4 * F_scale);
}

INSTANTIATE_TEST_SUITE_P(Trains, NetworkLeeCvodeRevolution,
                         ::testing::Values(RevCase{"ohc", "ohc_bucket_tappet", "tappet", "valve", 1e-4},
                                           RevCase{"ohv", "ohv_pushrod_train", "lifter", "valve", 1e-3}),
                         [](const ::testing::TestParamInfo<RevCase>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace camdyn

namespace camdyn {
namespace {

// The OHV train with its pushrod as 1000 bar elements on cvode-bdf, at rest on the cam's
// base circle for 4 ms (the lash closes at 9 ms): a train at rest in its equilibrium stays
// there (the truth). The held contacts' projection in the kinetic-energy metric M moved
// the lifter node alone; behind it the first pushrod element (period ≈ 0.3 µs, steps of
// 0.1 ms) was strained at every step and CVODE's error test failed for good at 1.7 ms
// (Lee) / 2.5 ms (event). The metric S = M + γC + γ²K (methods/event.hpp) moves the
// stiff chain with the node.
class FinePushrodAtRest : public ::testing::TestWithParam<ContactModel> {};

TEST_P(FinePushrodAtRest, StaysInItsEquilibriumOnCvode) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohv_pushrod_train.toml");
  for (ElementSpec& e : s.network.elements)
    if (e.name == "pushrod") e.elements = 1000;
  s.contact.model = GetParam();
  s.solver.integrator = Integrator::CvodeBdf;
  s.run.t_end = 0.004;
  s.run.output_dt = 1e-4;
  const NetRun r = run_keeping_rows(s);
  ASSERT_TRUE(r.sum.finished) << r.sum.message;
  EXPECT_EQ(r.sum.events.size(), 0u);
  ASSERT_GE(r.rows.size(), 41u);
  double g_held = 0, du = 0;  // the named nodes' displacements from their start (0 at t = 0)
  for (const HistoryRow& x : r.rows) {
    for (size_t i = 0; i < r.cols.size(); ++i) {
      const std::string& n = r.cols[i];
      if (n.rfind("in_", 0) == 0 && x.extra[i] != 0) g_held = std::max(g_held, std::abs(r.col(x, "gap_" + n.substr(3))));
      if (n.rfind("u_", 0) == 0) du = std::max(du, std::abs(x.extra[i] - r.rows[0].extra[i]));
    }
  }
  std::printf("%s: %ld steps, held |g| %.3g m, drift %.3g m\n", to_string(GetParam()), r.sum.steps, g_held, du);
  EXPECT_LE(g_held, 1e-12);
  EXPECT_LE(du, 10 * s.solver.atol);  // measured 4.2e-13 m
}

INSTANTIATE_TEST_SUITE_P(Methods, FinePushrodAtRest, ::testing::Values(ContactModel::Lee, ContactModel::Event),
                         [](const ::testing::TestParamInfo<ContactModel>& i) { return std::string(to_string(i.param)); });

}  // namespace
}  // namespace camdyn
