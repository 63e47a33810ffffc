// The run's contract (issue 35, docs/tolerances.md "The run's contract"): a run that
// reaches t_end checks its own result before calling it good. The truth the contract uses
// is a conservation law the run does not enforce: the cam's work equals the change of the
// follower's energy plus what was dissipated (W − ΔE − D = 0). The reproducers are the
// issue's: case B2 on arkode-erk at rtol = atol = 1e-2, arkode-dirk at rtol 0.1 over 0.5 s,
// contact.tol_u = 1 on the OHC example.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include <cmath>
#include <memory>
#include <vector>

#include "camdyn/follower_system.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

using namespace camdyn;

namespace {

std::string example(const std::string& file) { return std::string(CAMDYN_SOURCE_DIR) + "/examples/" + file; }

bool mentions(const RunContract& c, const std::string& what) {
  for (const auto& v : c.violations)
    if (v.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(RunContract, LooseErkOnCaseB2FinishesButDoesNotHoldIt) {
  // The reproducer: finished with exit 0, peak force 40,099 N against 24,999 N at
  // rtol 1e-6 and 6,942 separations against 2,283. Measured here: the energy residual is
  // 4.07e3 J on a ledger whose largest entry is 3.96e3 J (the run's whole energy is off),
  // against 0.09 J (2.4e-5 of it) at rtol 1e-6.
  const Scene s = load_scene_file(example("case_B2.toml"),
                                  {"solver.integrator=arkode-erk", "solver.rtol=1e-2", "solver.atol=1e-2"});
  Simulator sim(s);
  const Summary sum = sim.run();
  ASSERT_TRUE(sum.finished) << sum.message;
  EXPECT_TRUE(sum.contract.checked);
  EXPECT_FALSE(sum.contract.held);
  EXPECT_TRUE(mentions(sum.contract, "energy residual")) << sum.contract.violations.size();
  EXPECT_TRUE(mentions(sum.contract, "solver.rtol"));
  // The bound: min(100 rtol, 0.01) of the ledger's scale.
  EXPECT_DOUBLE_EQ(sum.contract.energy_bound, 0.01 * sum.contract.energy_scale);
  EXPECT_GT(sum.energy_residual, 0.5 * sum.contract.energy_scale);
  EXPECT_NE(sum.BriefReport().find("CONTRACT NOT HELD"), std::string::npos);
}

TEST(RunContract, CaseB2AtItsOwnTolerancesHoldsIt) {
  // The same scene at the file's rtol 1e-6, first 0.05 s (a few hundred steps per
  // revolution): residual 2.4e-5 of the scale over the full run, inside 1e-4.
  const Scene s = load_scene_file(example("case_B2.toml"), {"solver.integrator=arkode-erk", "run.t_end=0.05"});
  Simulator sim(s);
  const Summary sum = sim.run();
  ASSERT_TRUE(sum.finished) << sum.message;
  EXPECT_TRUE(sum.contract.checked);
  EXPECT_TRUE(sum.contract.held) << (sum.contract.violations.empty() ? "" : sum.contract.violations[0]);
  EXPECT_GT(sum.contract.energy_scale, 0.0);
  EXPECT_LE(sum.energy_residual, sum.contract.energy_bound);
}

TEST(RunContract, DirkAtRtolPointOneIsNotAResult) {
  // The reproducer (7 separations against 1,082): the run now stops where a held
  // contact penetrates by more than 10 tol_u, so it never says "finished".
  const Scene s = load_scene_file(example("case_B2.toml"),
                                  {"solver.integrator=arkode-dirk", "solver.rtol=0.1", "run.t_end=0.5"});
  Simulator sim(s);
  const Summary sum = sim.run();
  EXPECT_FALSE(sum.finished && sum.contract.held) << sum.message;
  if (!sum.finished) {
    EXPECT_NE(sum.message.find("penetrates"), std::string::npos) << sum.message;
    EXPECT_FALSE(sum.contract.checked);
  }
}

TEST(RunContract, TolUOfOneOnTheOhcExampleIsRefusedAtTheStart) {
  // The reproducer gave 147 seat bounces and 385 kN. The cam lifts 8 mm: tol_u may
  // be at most 1 % of that, 8e-5 m.
  const Scene s = load_scene_file(example("ohc_bucket_tappet.toml"), {"contact.tol_u=1"});
  try {
    Simulator sim(s);
    FAIL() << "contact.tol_u = 1 accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "contact.tol_u");
    EXPECT_NE(e.rule().find("lift 0.008"), std::string::npos) << e.what();
    EXPECT_NE(e.rule().find("8e-05"), std::string::npos) << e.what();
  }
  // At the limit it is accepted.
  const Scene ok = load_scene_file(example("ohc_bucket_tappet.toml"), {"contact.tol_u=8e-5"});
  EXPECT_NO_THROW(Simulator{ok});
}

TEST(RunContract, ExamplesAtTheirOwnTolerancesHoldIt) {
  // No false alarm on the shipped scenes (short runs; the contract is checked at the end).
  const std::pair<const char*, const char*> cases[] = {
      {"case_A.toml", "run.t_end=0.4"},          {"case_A7.toml", "run.t_end=0.2"},
      {"ohc_bucket_tappet.toml", "run.t_end=0.04"}, {"ohv_pushrod_train.toml", "run.t_end=0.02"},
      {"case_B1.toml", "run.t_end=0.02"}};
  for (const auto& [file, set] : cases) {
    Simulator sim(load_scene_file(example(file), {set}));
    const Summary sum = sim.run();
    ASSERT_TRUE(sum.finished) << file << ": " << sum.message;
    EXPECT_TRUE(sum.contract.held) << file << ": " << sum.contract.violations[0];
  }
}

TEST(RunContract, ARunInWhichAlmostNothingMovesHoldsIt) {
  // The OHV train started on its base circle at 20° for 1.5 ms: the lifter rests on the cam
  // (15 N), the work is 8.6e-13 J and the residual 3.7e-15 J — round-off, not an error (the
  // relative bound alone, 1e-5 of the scale, is 8.6e-18 J and failed it). The floor
  // 1000ε·(largest force, the seat's 330 N, × the cam's 6 mm lift) = 4.4e-13 J holds it (the
  // residual is 1e-2 of it); in a run that moves the
  // relative bound is far above it (LooseErkOnCaseB2… above: exactly 0.01 of the scale).
  Simulator sim(load_scene_file(example("ohv_pushrod_train.toml"), {"cam.theta0_deg=20", "run.t_end=0.0015"}));
  const Summary sum = sim.run();
  ASSERT_TRUE(sum.finished) << sum.message;
  EXPECT_TRUE(sum.contract.held) << (sum.contract.violations.empty() ? "" : sum.contract.violations[0]);
  EXPECT_NEAR(sum.contract.energy_magnitude, sum.max_contact_force * 0.006, 1e-5 * sum.contract.energy_magnitude);
  EXPECT_LT(sum.contract.energy_bound, 1e-12);  // a floor at round-off, not a loose bound
  EXPECT_LE(sum.energy_residual, sum.contract.energy_bound);
}

TEST(RunContract, CliExitsThreeAndSaysWhichKeyToTighten) {
  // The same loose run over its first 0.1 s (residual 392 J against a bound of 37.6 J):
  // exit 3, summary.json "contract": {"held": false}, stderr names solver.rtol.
  const std::string dir = ::testing::TempDir() + "camdyn_contract_cli";
  const std::string cmd = std::string("'") + CAMDYN_CLI_PATH + "' run '" + example("case_B2.toml") +
                          "' --set solver.integrator=arkode-erk --set solver.rtol=1e-2 --set solver.atol=1e-2"
                          " --set run.t_end=0.1 --quiet --out '" + dir + "' 2>'" + dir + ".err'";
  const int raw = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 3);
  std::ifstream sj(dir + "/summary.json"), er(dir + ".err");
  const std::string summary((std::istreambuf_iterator<char>(sj)), {}), err((std::istreambuf_iterator<char>(er)), {});
  EXPECT_NE(summary.find("\"held\": false"), std::string::npos);
  EXPECT_NE(summary.find("\"status\": \"finished\""), std::string::npos);
  EXPECT_NE(err.find("camdyn: contract not held: energy residual"), std::string::npos) << err;
  EXPECT_NE(err.find("solver.rtol"), std::string::npos) << err;
}

namespace {
// A one-mass follower on a spring whose force becomes NaN after t = 2 ms.
struct NanAfter2ms : FollowerSystem {
  int size() const override { return 1; }
  std::vector<FollowerContact> contacts() const override {
    FollowerContact c;
    c.name = "cam";
    c.row = {1.0};
    return {c};
  }
  void force(double t, const double* q, const double*, double* r) const override {
    r[0] = t > 0.002 ? NAN : -(150.0 + 2e4 * q[0]);
  }
  void solve_mass(const double* b, double* x) const override { x[0] = b[0] / 0.1; }
};
}  // namespace

TEST(RunMessages, NonFiniteUserForceIsNamed) {
  // Issue 35: was "step size underflow at t = 0.002" without naming the force. Named on the
  // event and penalty methods (the engine's failed call carries it). Not yet on Lee's located
  // step, which still ends in "step size underflow" here.
  Scene s = paper_case("A");
  apply_overrides(s, {"cam.profile=circle", "cam.radius=0.02", "cam.eccentricity=0.004", "cam.theta0_deg=180",
                      "cam.speed_rev_s=5", "run.t_end=0.01", "run.output_dt=1e-3"});
  for (const char* model : {"event", "penalty"}) {
    Scene m = s;
    apply_override(m, std::string("contact.model=") + model);
    Simulator sim(m, std::make_shared<NanAfter2ms>());
    const Summary sum = sim.run();
    EXPECT_FALSE(sum.finished) << model;
    EXPECT_NE(sum.message.find("returned a non-finite value"), std::string::npos) << model << ": " << sum.message;
    EXPECT_EQ(sum.message.find("[ARKODE"), std::string::npos) << sum.message;
  }
}
