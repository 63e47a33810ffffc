// The Lee step hook (Observer::on_lee_step) reports the ramps that produced the run:
// integrating the recorded step sequence with those ramps and no iteration (the replay
// of bench/bench_overhead.cpp) must reproduce the Lee run.
//
// Lee's accepted state takes q from the displacement level and v from the velocity level
// (two integrations of the step with ramps ending at F₁ and F̂), and the hook reports the
// velocity level's ramp. So from any accepted state one step with the reported ramp gives
// the accepted velocity exactly (same engine, same inputs), while the displacement
// differs by the displacement level's share, (F₁ − F̂)h²/(6m) per step for a rigid
// follower: ~1e-12 per step on the lift of case A with its 1e-4 s steps (output_dt),
// which a chained replay accumulates (measured: 1e-11 at 0.1 s, 2e-8 at 1 s), and far
// more on the long steps of a run without output grid (8e-4 per step measured).
#include <gtest/gtest.h>

#include <cmath>

#include "camdyn/simulator.hpp"
#include "legacy/engine.hpp"
#include "legacy/replay.hpp"

namespace camdyn {
namespace {

struct RowsAndSteps : LeeStepRecorder {
  std::vector<HistoryRow> rows;
  void on_row(const HistoryRow& r) override {
    LeeStepRecorder::on_row(r);
    rows.push_back(r);
  }
};

TEST(LeeOverhead, HookReportsTheRampOfEachAcceptedVelocity) {  // classic step (the hook reports its ramps)
  Scene s = paper_case("A");
  s.contact.lee_step = LeeStepKind::Classic;  // the hook and the replay are the classic step's ramps
  s.solver.integrator = Integrator::ArkodeErk;
  s.run.output_dt = 0.0;  // a row per accepted step: the rigid follower's full state
  s.run.t_end = 0.3;
  Simulator sim(s);
  RowsAndSteps rec;
  const Summary sum = sim.run(&rec);
  ASSERT_TRUE(sum.finished) << sum.message;
  ASSERT_EQ(long(rec.steps.size()), sum.steps);
  ASSERT_EQ(rec.rows.size(), rec.steps.size() + 1);
  // The steps tile [0, t_end] without gaps or overlaps.
  EXPECT_EQ(rec.steps.front().t0, 0.0);
  for (size_t k = 0; k < rec.steps.size(); ++k) {
    ASSERT_GT(rec.steps[k].h, 0.0);
    ASSERT_EQ(rec.steps[k].t0, rec.rows[k].t);
    ASSERT_NEAR(rec.steps[k].t0 + rec.steps[k].h, rec.rows[k + 1].t, 1e-15);
  }
  // From each accepted state, one step with the reported ramp: the accepted velocity.
  auto model = build_model(sim.scene());
  auto engine = make_engine(model, sim.scene().solver, sim.scene().contact.model == ContactModel::Lee,
                            sim.scene().contact.tol_u);
  StepRamp law;
  engine->set_contact(&law);
  Eigen::VectorXd y(2), y1(2);
  double dv = 0, du = 0, vmax = 0;
  for (size_t k = 0; k < rec.steps.size(); ++k) {
    const LeeStep& st = rec.steps[k];
    law.t0 = st.t0;
    law.h = st.h;
    law.F0 = st.F0;
    law.F1 = st.F1;
    y << rec.rows[k].u_c, rec.rows[k].v_c;
    engine->step(st.t0, y, st.h, y1);
    dv = std::max(dv, std::abs(y1[1] - rec.rows[k + 1].v_c));
    du = std::max(du, std::abs(y1[0] - rec.rows[k + 1].u_c));
    vmax = std::max(vmax, std::abs(rec.rows[k + 1].v_c));
  }
  std::printf("one step from each accepted state: max |dv| %.3e (max |v| %.3g), max |du| %.3e\n", dv,
              vmax, du);
  EXPECT_LE(dv, 1e-13 * vmax);  // the same integration: equal to round-off
  // (du is the displacement level's share, see the header: not asserted.)
  // The first step's ramp starts at the initial contact force, each next one at the
  // force reported for the end of the previous step (the acceleration level's).
  for (size_t k = 0; k < rec.steps.size(); ++k) ASSERT_EQ(rec.steps[k].F0, rec.rows[k].contact_force);
}

TEST(LeeOverhead, ReplayOfCaseAReproducesTheLeeRun) {
  Scene s = paper_case("A");
  s.contact.lee_step = LeeStepKind::Classic;
  s.solver.integrator = Integrator::ArkodeErk;
  s.run.t_end = 0.1;  // before the lift: the chained replay drifts on it (see the header)
  Simulator sim(s);
  LeeStepRecorder rec;
  const Summary sum = sim.run(&rec);
  ASSERT_TRUE(sum.finished) << sum.message;
  const ReplayResult r = replay_lee_steps(sim.scene(), rec.steps);
  const double du = std::abs(r.y[0] - rec.last_row.u_c);
  std::printf("case A, %zu steps: Lee u_c(t_end) = %.15g, replay %.15g, |du| = %.3e\n",
              rec.steps.size(), rec.last_row.u_c, r.y[0], du);
  EXPECT_LE(du, 1e-9);
  // The check is sensitive to the ramps: the same steps with a constant force (F1 = F0,
  // the previous step's force held) land far away.
  std::vector<LeeStep> wrong = rec.steps;
  for (LeeStep& st : wrong) st.F1 = st.F0;
  const ReplayResult w = replay_lee_steps(sim.scene(), wrong);
  EXPECT_GT(std::abs(w.y[0] - rec.last_row.u_c), 1e3 * du + 1e-9);
}

}  // namespace
}  // namespace camdyn
