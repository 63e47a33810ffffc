// Issue 25: the tolerance is a contract. Tight tolerances finish, and the answer agrees
// with an independent, tighter solution (the event-driven method at rtol 1e-12).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "engine/sundials_error.hpp"

namespace camdyn {
namespace {

// Largest |u_c − u_c,ref| over the output rows the two runs share.
double max_uc_difference(const RunResult& a, const RunResult& ref) {
  std::map<long long, double> r;
  for (const HistoryRow& row : ref.rows) r[std::llround(row.t * 1e9)] = row.u_c;
  double e = 0;
  long shared = 0;
  for (const HistoryRow& row : a.rows) {
    const auto it = r.find(std::llround(row.t * 1e9));
    if (it == r.end()) continue;
    ++shared;
    e = std::max(e, std::abs(row.u_c - it->second));
  }
  EXPECT_GT(shared, 100);
  return e;
}

// B2 over 0.1 s at tol_u = rtol = 1e-10 ended in a step size underflow at t = 0.0767 s: a
// step landed on the force's zero ended at F = 8e-6 (its interpolant's accuracy), above
// the separation threshold 1e-10·F_max = 2e-6, found the zero again 7.5e-14 s later, and
// the held step of that size needed round-off forces of 1e10.
TEST(ToleranceContract, B2AtTightTolerancesFinishesAndAgreesWithTheEventMethod) {
  Scene ref_scene = paper_case("B2");
  ref_scene.run.t_end = 0.1;
  ref_scene.run.output_dt = 1e-4;
  ref_scene.contact.model = ContactModel::Event;
  ref_scene.solver.rtol = 1e-12;
  const RunResult ref = simulate(ref_scene);
  ASSERT_TRUE(ref.summary.finished) << ref.summary.message;
  for (double tol : {1e-10, 1e-11}) {
    Scene s = paper_case("B2");
    s.run.t_end = 0.1;
    s.run.output_dt = 1e-4;
    s.contact.tol_u = tol;
    s.solver.rtol = tol;
    const RunResult r = simulate(s);
    ASSERT_TRUE(r.summary.finished) << "tol " << tol << ": " << r.summary.message;
    EXPECT_EQ(r.summary.separations, ref.summary.separations) << tol;
    EXPECT_EQ(r.summary.impacts, ref.summary.impacts) << tol;
    EXPECT_LT(max_uc_difference(r, ref), 1e-8) << tol;
  }
}

// A SUNDIALS flag reads as words naming what failed, never as its number.
TEST(ToleranceContract, SundialsFlagsAreTranslatedIntoWords) {
  const std::regex number("flag|-[0-9]");
  struct Case {
    const char* call;
    int flag;
    const char* words;
  } cases[] = {{"ERKStepEvolve", -3, "error test failed repeatedly"},
               {"CVode", -3, "error test failed repeatedly"},
               {"ARKStepEvolve", -4, "Newton iteration failed to converge"},
               {"CVode", -1, "maximum number of internal steps"},
               {"IDASolve", -9, "residual function failed repeatedly"},
               {"IDASolve", -3, "error test failed repeatedly"},
               {"klu_l_factor", -1, "klu_l_factor: failed"},
               {"ERKStepEvolve (trial step ended short of t + h)", -1, "ended short of t + h): failed"}};
  for (const Case& c : cases) {
    const std::string what = SundialsError(c.call, c.flag).what();
    EXPECT_NE(what.find(c.words), std::string::npos) << what;
    EXPECT_FALSE(std::regex_search(what, number)) << what;
    EXPECT_EQ(SundialsError(c.call, c.flag).flag(), c.flag);
  }
}

// Magnitudes no unit system needs are refused at validation, naming the key (they passed
// and the run failed with "ERKStepEvolve failed with flag -3").
TEST(ToleranceContract, MeaninglessMagnitudesAreRefusedNamingTheKey) {
  for (const char* set : {"follower.youngs_modulus=1e308", "follower.area=1e308", "spring.precompression=1e308",
                          "spring.precompression=-1e308", "follower.mass=1e-300", "spring.stiffness=1e60"}) {
    Scene s = paper_case("B2");
    const std::string key = std::string(set).substr(0, std::string(set).find('='));
    try {
      apply_override(s, set);
      Simulator sim(s);
      ADD_FAILURE() << set << " accepted";
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(key), std::string::npos) << what;
      EXPECT_NE(what.find("not a physical magnitude"), std::string::npos) << what;
    }
  }
  // The largest accepted values are taken at face value.
  Scene s = paper_case("B2");
  apply_override(s, "spring.precompression=1e50");
  EXPECT_NO_THROW(validate(s));
}

// A displacement tolerance below the round-off of the gap (1000 ulps of the cam's largest
// radius, 3 on case B2: 6.7e-13) is refused at the start, naming contact.tol_u.
TEST(ToleranceContract, ToleranceBelowDoublePrecisionIsRefusedAtTheStart) {
  Scene s = paper_case("B2");
  s.contact.tol_u = 1e-13;
  try {
    Simulator sim(s);
    ADD_FAILURE() << "tol_u 1e-13 accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("contact.tol_u"), std::string::npos) << what;
    EXPECT_NE(what.find("double precision"), std::string::npos) << what;
  }
  s.contact.tol_u = 1e-12;
  EXPECT_NO_THROW(Simulator{s});
}

// FullReport says what rtol means on the engine, and warns on cvode-bdf with an elastic
// follower at a loose rtol (BDF2 damps the resolved modes).
TEST(ToleranceContract, FullReportSaysWhatTheToleranceMeans) {
  for (Integrator e : {Integrator::ArkodeErk, Integrator::CvodeBdf}) {
    Scene s = paper_case("B1");
    s.run.t_end = 2e-3;
    s.solver.integrator = e;
    const RunResult r = simulate(s);
    ASSERT_TRUE(r.summary.finished) << r.summary.message;
    const std::string rep = r.summary.FullReport();
    EXPECT_NE(rep.find("tolerance:"), std::string::npos) << rep;
    const bool warned = rep.find("warning:") != std::string::npos;
    EXPECT_EQ(warned, e == Integrator::CvodeBdf) << rep;
    EXPECT_EQ(r.summary.tolerance_warning.empty(), e != Integrator::CvodeBdf);
  }
}

// Fuzzed --set assignments on the paper cases, each run for a few steps: the scene is
// refused with a SceneError, or the run ends (finished or not) with a message that has no
// SUNDIALS flag number in it. No crash, no hang (t_end and max_steps are small).
TEST(ToleranceContract, FuzzedOverridesRunAFewStepsWithoutFlagNumbers) {
  const std::vector<std::string> keys = {
      "follower.youngs_modulus", "follower.area",     "follower.length",   "follower.mass",
      "spring.stiffness",        "spring.precompression", "cam.speed_rev_s", "contact.tol_u",
      "solver.rtol",             "solver.atol",       "contact.restitution", "contact.initial_gap",
      "follower.rayleigh_beta",  "contact.penalty_stiffness", "solver.max_step"};
  const std::vector<std::string> models = {"lee", "event", "penalty"};
  const std::vector<std::string> engines = {"arkode-erk", "arkode-dirk", "cvode-bdf"};
  std::mt19937 rng(25);
  std::uniform_int_distribution<int> pick_key(0, int(keys.size()) - 1), expo(-60, 60), sign(0, 3);
  const std::regex flag_number("flag -?[0-9]");
  int runs = 0, refused = 0;
  for (int i = 0; i < 60; ++i) {
    Scene s = paper_case(i % 2 ? "B2" : "A");
    s.run.t_end = 2e-3;
    s.run.max_steps = 2000;
    s.follower.elements = 8;
    std::vector<std::string> sets = {"contact.model=" + models[std::size_t(i) % 3],
                                     "solver.integrator=" + engines[std::size_t(i / 3) % 3]};
    for (int k = 0; k < 2; ++k) {
      char v[64];
      std::snprintf(v, sizeof v, "%s1e%d", sign(rng) == 0 ? "-" : "", expo(rng));
      sets.push_back(keys[std::size_t(pick_key(rng))] + "=" + v);
    }
    std::string line;
    for (const std::string& a : sets) line += a + " ";
    std::printf("fuzz %d: %s\n", i, line.c_str());
    std::fflush(stdout);
    try {
      apply_overrides(s, sets);
      Simulator sim(s);
      const Summary sum = sim.run();
      ++runs;
      EXPECT_FALSE(std::regex_search(sum.message, flag_number)) << sum.message;
    } catch (const SceneError& e) {
      ++refused;
      EXPECT_FALSE(std::regex_search(std::string(e.what()), flag_number)) << e.what();
    }
  }
  EXPECT_GT(runs, 5);
  EXPECT_GT(refused, 5);
}

// Case A per method × engine at rtol 1e-4/1e-7/1e-10 against the closed-form force: in
// tests/contact/test_tolerance_matrix.cpp (ToleranceMatrix, A_*).

}  // namespace
}  // namespace camdyn
