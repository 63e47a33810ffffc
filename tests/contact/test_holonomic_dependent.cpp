// The holonomic method holds every closed contact for good. On the roller finger
// (examples/ohc_roller_finger.toml) cam and seat hold at the start; once the finger has
// taken up the lash, the lash contact closes on a chain the other two already fix (two
// unknowns, three rows): the multipliers are not unique and IDA's Newton matrix is
// singular. The run used to end with "the linear solver setup failed unrecoverably"; it
// now stops at the lash's impact naming the dependent contacts and the methods that
// handle them, and the lash's closing is where the kinematics put it: the finger's
// displacement at the impact equals the lash (0.1 mm) to the state's accuracy.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

TEST(HolonomicDependentContacts, StopsAtTheRedundantClosingNamingTheContacts) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_roller_finger.toml");
  s.contact.model = ContactModel::Holonomic;
  s.solver.integrator = Integrator::Ida;
  s.run.t_end = 0.02;
  const RunResult r = simulate(s);
  EXPECT_FALSE(r.summary.finished);
  EXPECT_EQ(r.summary.termination, Termination::StepFailure);
  EXPECT_NE(r.summary.message.find("the held contacts 'cam', 'lash', 'seat' are dependent"), std::string::npos)
      << r.summary.message;
  EXPECT_NE(r.summary.message.find("(rank 2 of 3)"), std::string::npos) << r.summary.message;
  EXPECT_NE(r.summary.message.find("use contact.model = \"lee\" or \"event\""), std::string::npos);
  ASSERT_EQ(r.summary.events.size(), 1u);
  EXPECT_EQ(r.summary.events[0].type, EventKind::Impact);
  EXPECT_EQ(r.summary.events[0].contact, "lash");
  EXPECT_NEAR(r.summary.t_end, r.summary.events[0].t, 1e-15);
  // the last row is the impact's state: the lash taken up
  ASSERT_FALSE(r.rows.empty());
  EXPECT_NEAR(r.rows.back().u_c, 1e-4, 1e-12);
}

TEST(HolonomicDependentContacts, LeeRunsTheSameSceneThrough) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_roller_finger.toml");
  s.run.t_end = 0.02;
  const RunResult r = simulate(s);
  EXPECT_TRUE(r.summary.finished) << r.summary.message;
}

}  // namespace
}  // namespace camdyn
