// The one builder of the Summary (src/run/summary_builder.cpp): its documented order holds.
// A short real run of case A gives a record and the parts; the record is then changed by
// hand and the builder's Summary is checked against expectations written here: the
// contract's energy bound from its formula in docs/tolerances.md ("The run's contract"),
// the warnings' order, the criteria judged on the record's contacts, an unfinished run's
// contract left unchecked.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "contact/contact_run.hpp"
#include "mechanism/mechanism.hpp"
#include "run/summary_builder.hpp"

using namespace camdyn;

namespace {

std::string example(const std::string& file) { return std::string(CAMDYN_SOURCE_DIR) + "/examples/" + file; }

// case A (a rigid follower on Lee's method) over 2 ms, with a force-margin criterion.
struct ShortRun {
  Scene scene = load_scene_file(example("case_A.toml"),
                                {"run.t_end=0.002", "solver.rtol=1e-6", "criteria.min_force_margin=10"});
  std::shared_ptr<const MechanicalSystem> mech = std::make_shared<const Mechanism>(scene);
  std::unique_ptr<detail::ContactRun> method = detail::make_contact_method(scene, mech, nullptr, nullptr);
  detail::RunRecord record = method->run();  // a copy, changed by the tests
};

}  // namespace

TEST(SummaryBuilder, TheContractSeesTheRecordsFinalEnergyNumbers) {
  ShortRun r;
  ASSERT_TRUE(r.record.finished) << r.record.message;
  // The bound at rtol 1e-6: min(max(100·1e-6, 1e-5), 1e-2) = 1e-4 of the energy scale
  // (the round-off floor 1000ε·magnitude is 2.2e-13 J here, far below).
  r.record.energy_scale = 1.0;
  r.record.energy_magnitude = 1.0;
  r.record.max_penetration = 0.0;
  r.record.energy_residual = 2e-4;
  Summary s = detail::build_summary(r.scene, *r.mech, {}, r.record, r.method->parts());
  EXPECT_TRUE(s.contract.checked);
  EXPECT_FALSE(s.contract.held);
  EXPECT_DOUBLE_EQ(s.contract.energy_bound, 1e-4);
  EXPECT_DOUBLE_EQ(s.energy_residual, 2e-4);
  ASSERT_EQ(s.contract.violations.size(), 1u);
  EXPECT_NE(s.contract.violations[0].find("energy residual"), std::string::npos) << s.contract.violations[0];

  r.record.energy_residual = 0.5e-4;
  s = detail::build_summary(r.scene, *r.mech, {}, r.record, r.method->parts());
  EXPECT_TRUE(s.contract.held);
  EXPECT_TRUE(s.contract.violations.empty());

  // An unfinished run: the contract is not checked, whatever its numbers.
  r.record.energy_residual = 1.0;
  r.record.finished = false;
  r.record.termination = Termination::MaxSteps;
  s = detail::build_summary(r.scene, *r.mech, {}, r.record, r.method->parts());
  EXPECT_FALSE(s.contract.checked);
  EXPECT_TRUE(s.contract.held);
  EXPECT_EQ(s.termination, Termination::MaxSteps);
}

TEST(SummaryBuilder, SceneWarningsComeBeforeTheRunsAndCriteriaReadTheRecordsContacts) {
  ShortRun r;
  r.record.warnings = {"run: c"};
  ASSERT_EQ(r.record.contacts.size(), 1u);
  r.record.contacts[0].min_force = 5.0;  // below the criterion's 10 N
  r.record.contacts[0].min_force_theta_deg = 42.0;
  r.record.min_gap = INFINITY;  // no step sampled a gap
  Summary s = detail::build_summary(r.scene, *r.mech, {"scene: a", "scene: b"}, r.record, r.method->parts());
  EXPECT_EQ(s.warnings, (std::vector<std::string>{"scene: a", "scene: b", "run: c"}));
  EXPECT_EQ(s.min_gap, 0.0);
  ASSERT_EQ(s.criteria.size(), 1u);
  EXPECT_EQ(s.criteria[0].name, "force_margin");
  EXPECT_EQ(s.criteria[0].value, 5.0);
  EXPECT_EQ(s.criteria[0].theta_deg, 42.0);
  EXPECT_FALSE(s.criteria[0].pass);
  EXPECT_FALSE(s.criteria_pass);

  r.record.contacts[0].min_force = 20.0;
  s = detail::build_summary(r.scene, *r.mech, {}, r.record, r.method->parts());
  EXPECT_TRUE(s.criteria_pass);
  EXPECT_EQ(s.warnings, (std::vector<std::string>{"run: c"}));
  // No events in the record: the verdict is the one "no_separation" item.
  r.record.events.clear();
  s = detail::build_summary(r.scene, *r.mech, {}, r.record, r.method->parts());
  ASSERT_EQ(s.verdict.size(), 1u);
  EXPECT_EQ(s.verdict[0].kind, "no_separation");
  EXPECT_EQ(s.verdict_text, s.verdict[0].text);
}

TEST(SummaryBuilder, CopiesTheRecordsCountersAndNamesWhatRan) {
  ShortRun r;
  r.record.steps = 123;
  r.record.rejected_steps = 4;
  r.record.impacts = 7;
  r.record.separations = 6;
  r.record.level_u.total = 9;
  const Summary s = detail::build_summary(r.scene, *r.mech, {}, r.record, r.method->parts());
  EXPECT_EQ(s.steps, 123);
  EXPECT_EQ(s.rejected_steps, 4);
  EXPECT_EQ(s.impacts, 7);
  EXPECT_EQ(s.separations, 6);
  EXPECT_EQ(s.level_u.total, 9);
  EXPECT_EQ(s.scene, r.scene.title);
  EXPECT_EQ(s.integrator, "arkode-erk");
  EXPECT_EQ(s.contact_model, "lee");
  EXPECT_FALSE(s.tolerance_meaning.empty());
}
