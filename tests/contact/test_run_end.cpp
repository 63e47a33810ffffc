// How a run ends (issue 12): Summary::termination at every end of a run, and an observer
// that stops a run by returning ObserverAction::Stop.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Keeps every row; returns Stop at the first row with t ≥ t_stop.
struct StopAt : Observer {
  double t_stop;
  std::vector<HistoryRow> rows;
  int on_row_calls = 0;
  explicit StopAt(double t) : t_stop(t) {}
  void on_row(const HistoryRow&) override { ++on_row_calls; }  // not called: on_output is
  ObserverAction on_output(const HistoryRow& r) override {
    rows.push_back(r);
    return r.t >= t_stop ? ObserverAction::Stop : ObserverAction::Continue;
  }
};

// An observer written before on_output existed: overrides on_row only.
struct OldStyle : Observer {
  std::vector<HistoryRow> rows;
  void on_row(const HistoryRow& r) override { rows.push_back(r); }
};

Scene short_case(const char* name, double t_end) {
  Scene s = paper_case(name);
  s.run.t_end = t_end;
  return s;
}

TEST(RunEnd, FinishedRunSaysFinished) {
  const RunResult r = simulate(short_case("A", 0.01));
  EXPECT_TRUE(r.summary.finished);
  EXPECT_EQ(r.summary.termination, Termination::Finished);
  EXPECT_STREQ(to_string(r.summary.termination), "finished");
  EXPECT_TRUE(contains(r.summary.BriefReport(), "finished"));
  EXPECT_TRUE(contains(r.summary.FullReport(), "termination:        finished"));
}

// One test per contact method: Stop at the row t ≥ 0.004 of case A (output_dt 1e-4)
// ends the run there, keeping the rows so far (the stopping row last) and identical to
// the same rows of a full run.
class ObserverStop : public ::testing::TestWithParam<std::string> {};

TEST_P(ObserverStop, EndsTheRunAtThatRow) {
  Scene s = short_case("A", 0.01);
  apply_overrides(s, {"contact.model=" + GetParam()});
  const RunResult full = simulate(s);
  ASSERT_TRUE(full.summary.finished) << full.summary.message;
  StopAt obs(0.004);
  Simulator sim(s);
  const Summary sum = sim.run(&obs);
  EXPECT_FALSE(sum.finished);
  EXPECT_EQ(sum.termination, Termination::StoppedByObserver);
  EXPECT_TRUE(contains(sum.message, "stopped by observer")) << sum.message;
  EXPECT_EQ(obs.on_row_calls, 0);
  ASSERT_FALSE(obs.rows.empty());
  EXPECT_GE(obs.rows.back().t, 0.004);
  EXPECT_LT(obs.rows.back().t, 0.004 + 1.5e-4);
  // the run ended at the accepted step that produced the stopping row
  EXPECT_GE(sum.t_end, obs.rows.back().t);
  EXPECT_LT(sum.t_end, 0.009);
  // every row but the stopping one continued; all equal the full run's rows
  ASSERT_LE(obs.rows.size(), full.rows.size());
  for (std::size_t i = 0; i < obs.rows.size(); ++i) {
    EXPECT_EQ(obs.rows[i].t, full.rows[i].t) << i;
    EXPECT_EQ(obs.rows[i].u_c, full.rows[i].u_c) << i;
    EXPECT_EQ(obs.rows[i].contact_force, full.rows[i].contact_force) << i;
  }
  EXPECT_TRUE(contains(summary_json(sum, sim.scene()), "\"termination\": \"stopped_by_observer\""));
}

INSTANTIATE_TEST_SUITE_P(Methods, ObserverStop,
                         ::testing::Values("lee", "penalty", "event", "holonomic"),
                         [](const auto& info) { return info.param; });

TEST(RunEnd, ObserverStopOnTheInitialRowTakesNoStep) {
  StopAt obs(0.0);
  Simulator sim(short_case("A", 0.01));
  const Summary sum = sim.run(&obs);
  EXPECT_EQ(sum.termination, Termination::StoppedByObserver);
  EXPECT_EQ(sum.steps, 0);
  EXPECT_EQ(sum.t_end, 0.0);
  ASSERT_EQ(obs.rows.size(), 1u);
  EXPECT_EQ(obs.rows[0].t, 0.0);
}

TEST(RunEnd, OnRowOnlyObserverStillGetsEveryRow) {
  const Scene s = short_case("A", 0.01);
  OldStyle obs;
  Simulator sim(s);
  const Summary sum = sim.run(&obs);
  EXPECT_EQ(sum.termination, Termination::Finished);
  EXPECT_EQ(obs.rows.size(), simulate(s).rows.size());
}

TEST(RunEnd, StopFlagIsStoppedByCaller) {
  Simulator sim(short_case("A", 0.01));
  std::atomic<bool> stop{true};
  const Summary sum = sim.run(nullptr, &stop, "stopped by caller");
  EXPECT_EQ(sum.termination, Termination::StoppedByCaller);
  EXPECT_TRUE(contains(sum.BriefReport(), "[stopped_by_caller]")) << sum.BriefReport();
}

TEST(RunEnd, MaxStepsIsMaxSteps) {
  Scene s = short_case("A", 0.01);
  s.run.max_steps = 5;
  const RunResult r = simulate(s);
  EXPECT_EQ(r.summary.termination, Termination::MaxSteps);
  EXPECT_TRUE(contains(r.summary.message, "run.max_steps = 5 reached")) << r.summary.message;
  EXPECT_FALSE(r.rows.empty());
}

TEST(RunEnd, EveryTerminationHasADistinctName) {
  const Termination all[] = {
      Termination::Finished,          Termination::StoppedByObserver, Termination::StoppedByCaller,
      Termination::MaxSteps,          Termination::StepSizeUnderflow, Termination::IterationFailure,
      Termination::NonFinite,         Termination::StepFailure,       Termination::SolverError,
      Termination::InvalidScene,      Termination::Error};
  std::vector<std::string> names;
  for (Termination t : all) {
    const std::string n = to_string(t);
    EXPECT_FALSE(n.empty());
    for (const auto& m : names) EXPECT_NE(n, m);
    names.push_back(n);
  }
}

TEST(RunEnd, SummaryJsonHasTerminationAndLinearSolverCounts) {
  const RunResult r = simulate(short_case("A", 0.01));
  const std::string j = summary_json(r.summary, short_case("A", 0.01));
  for (const char* key : {"\"termination\": \"finished\"", "\"lin_setups\":", "\"lin_analyses\":",
                          "\"relocated_steps\":", "\"iteration_failures\":", "\"period_kind\":",
                          "\"poincare\":", "\"max_gap\":"})
    EXPECT_TRUE(contains(j, key)) << key;
}

}  // namespace
}  // namespace camdyn
