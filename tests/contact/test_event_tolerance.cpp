// camdyn — the event method's accuracy follows the documented tolerance (issue 37,
// docs/tolerances.md "The event method"). The four-arc cam under a knife edge at 245 rpm
// with restitution 0.6: the follower leaves the nose and lands on the flank in a train of
// bounces that decays until the sticking speed cuts it. Against a run at rtol 1e-13,
// tol_u 1e-12: at the default contact.tol_u (1e-8) the event times converge as rtol falls,
// and more of the bounce train is resolved. (Before, the gap roots and the sticking speed
// came from tol_u alone: 24 events and 1.39e-7 s off at rtol 1e-7, 1e-9 and 1e-11 alike.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

Scene bouncing_arc_cam() {
  Scene s = parse_scene(R"(
[cam]
profile = "arc"
base_radius = 2.0
nose_radius = 0.6
nose_distance = 1.8
flank_radius = 5.0
follower_face = "knife_edge"
theta0_deg = 180.0
speed_rev_s = 4.083333333333333
[follower]
kind = "rigid"
[contact]
model = "event"
restitution = 0.6
[run]
t_end = 0.3
output_dt = 1e-3
)",
                        "<test>");
  return s;
}

// The events of a run matching the reference's (same kind, within 0.1 ms) from the start,
// and the largest time error over them.
std::size_t matching(const Summary& r, const Summary& R, double* err) {
  std::size_t n = 0;
  *err = 0;
  while (n < std::min(r.events.size(), R.events.size()) && r.events[n].type == R.events[n].type &&
         std::abs(r.events[n].t - R.events[n].t) < 1e-4) {
    *err = std::max(*err, std::abs(r.events[n].t - R.events[n].t));
    ++n;
  }
  return n;
}

TEST(EventTolerance, EventTimesFallWithRtolAtTheDefaultTolU) {
  Scene ref = bouncing_arc_cam();
  ref.solver.rtol = 1e-13;
  ref.solver.atol = 1e-13;
  ref.contact.tol_u = 1e-12;
  const Summary R = Simulator(ref).run();
  ASSERT_TRUE(R.finished) << R.message;
  ASSERT_GE(R.events.size(), 20u);
  double errs[3];
  std::size_t counts[3];
  int i = 0;
  for (double rtol : {1e-7, 1e-9, 1e-11}) {
    Scene s = bouncing_arc_cam();
    s.solver.rtol = rtol;
    s.solver.atol = rtol;
    resolve_defaults(s);
    ASSERT_EQ(s.contact.tol_u, 1e-8);  // the default
    const Summary r = Simulator(s).run();
    ASSERT_TRUE(r.finished) << r.message;
    counts[i] = matching(r, R, &errs[i]);
    std::printf("event method, rtol %g, tol_u 1e-8: %zu events (reference %zu), the first %zu match, largest "
                "event-time error %.3g s\n",
                rtol, r.events.size(), R.events.size(), counts[i], errs[i]);
    EXPECT_EQ(counts[i], r.events.size()) << rtol;  // the bounces it resolves are the reference's
    ++i;
  }
  // Measured: 1.39e-7, 5.7e-8, 4.4e-9 s over 24, 25, 29 of the reference's 30 events.
  EXPECT_LT(errs[1], errs[0]);
  EXPECT_LT(errs[2], 0.1 * errs[0]);
  EXPECT_LE(counts[0], counts[1]);
  EXPECT_LT(counts[1], counts[2]);
}

TEST(EventTolerance, BelowRtolTheTolUNoLongerMatters) {
  // At rtol 1e-13 (rtol·X = 2.4e-13 for X = 2.4) tol_u 1e-8 and 1e-12 give the same run.
  Summary r[2];
  int i = 0;
  for (double tol_u : {1e-8, 1e-12}) {
    Scene s = bouncing_arc_cam();
    s.solver.rtol = 1e-13;
    s.solver.atol = 1e-13;
    s.contact.tol_u = tol_u;
    r[i] = Simulator(s).run();
    ASSERT_TRUE(r[i].finished) << r[i].message;
    ++i;
  }
  ASSERT_EQ(r[0].events.size(), r[1].events.size());
  for (std::size_t k = 0; k < r[0].events.size(); ++k) EXPECT_EQ(r[0].events[k].t, r[1].events[k].t);
}

TEST(EventTolerance, TolUFloorHoldsForEveryMethod) {
  for (ContactModel m : {ContactModel::Lee, ContactModel::Event, ContactModel::Penalty}) {
    Scene s = bouncing_arc_cam();
    s.contact.model = m;
    s.contact.restitution = 0.0;
    s.contact.tol_u = 1e-14;  // below 1000 ulps of the cam's radius 2.4: 5.3e-13
    try {
      Simulator(s).run();
      ADD_FAILURE() << to_string(m) << ": tol_u 1e-14 accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), "contact.tol_u") << to_string(m);
    }
  }
}

}  // namespace
}  // namespace camdyn
