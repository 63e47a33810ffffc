// Issue 25: the fuzz harness's simulation half without clang. 300 deterministic mutations
// of the example scenes (a number replaced by an extreme value, a line deleted or
// duplicated, a --set override of a key with an extreme value), each loaded and, when it
// loads, run for a few steps by the same code as the libFuzzer target (fuzz/fuzz_run.hpp:
// t_end ≤ 2 ms, ≤ 2000 steps, 2 s wall budget). Passes when nothing but SceneError is
// thrown, no run crashes or hangs, and no message (refusal, run end, full report) shows a
// SUNDIALS flag number.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "../fuzz/fuzz_run.hpp"

namespace camdyn {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) lines.push_back(l);
  return lines;
}

const char* const kExtremes[] = {"0",    "-1",     "1e308", "-1e308", "1e-308", "nan",  "inf",   "-inf",
                                 "1e20", "-1e-20", "-0.0",  "3",      "1e-14",  "2e9",  "100000"};

// One mutation of the scene text (lines), chosen by rng: a number on a line replaced by an
// extreme value (1 in 5) or scaled by 0.1, 0.5, 1.5, 10 or −1 (2 in 5), a line deleted or
// duplicated (1 in 5 each).
void mutate(std::vector<std::string>& lines, std::mt19937& rng) {
  if (lines.empty()) return;
  std::uniform_int_distribution<size_t> line(0, lines.size() - 1);
  std::uniform_int_distribution<int> kind(0, 4), extreme(0, int(std::size(kExtremes)) - 1), factor(0, 4);
  static const double kFactors[] = {0.1, 0.5, 1.5, 10.0, -1.0};
  const size_t i = line(rng);
  const int k = kind(rng);
  if (k <= 2) {
    static const std::regex number("[-+]?[0-9]+(\\.[0-9]*)?([eE][-+]?[0-9]+)?");
    for (size_t j = 0; j < lines.size(); ++j) {
      std::string& l = lines[(i + j) % lines.size()];
      std::smatch m;
      if (l.rfind('#', 0) != 0 && l.find('=') != std::string::npos && std::regex_search(l, m, number)) {
        char v[32];
        std::snprintf(v, sizeof v, "%.17g", std::strtod(m.str().c_str(), nullptr) * kFactors[factor(rng)]);
        const std::string value = k == 0 ? std::string(kExtremes[extreme(rng)]) : std::string(v);
        l = m.prefix().str() + value + m.suffix().str();
        return;
      }
    }
  } else if (k == 3) {
    lines.erase(lines.begin() + long(i));
  } else {
    lines.insert(lines.begin() + long(i), lines[i]);
  }
}

TEST(FuzzRuns, MutatedExampleScenesRunAFewStepsWithoutCrashOrFlagNumbers) {
  const std::vector<std::string> seeds = {"case_A",          "case_A7",     "case_B1",  "case_B2",
                                          "circle_cam",      "lift_cam",    "law_roller", "stiff_bar",
                                          "ohc_bucket_tappet", "ohv_pushrod_train"};
  const std::vector<std::string> keys = {"follower.youngs_modulus", "follower.mass", "spring.stiffness",
                                         "cam.speed_rev_s",         "contact.tol_u", "solver.rtol",
                                         "solver.atol",             "contact.restitution", "contact.model",
                                         "solver.integrator",       "run.t_end",     "solver.max_step"};
  std::mt19937 rng(2025);
  std::uniform_int_distribution<size_t> pick_seed(0, seeds.size() - 1), pick_key(0, keys.size() - 1);
  std::uniform_int_distribution<int> count(1, 2), coin(0, 3), extreme(0, int(std::size(kExtremes)) - 1);
  int loaded = 0, ran = 0, finished = 0;
  for (int i = 0; i < 300; ++i) {
    const std::string seed = seeds[pick_seed(rng)];
    std::vector<std::string> lines = split_lines(read_text(std::string(CAMDYN_SOURCE_DIR) + "/examples/" + seed + ".toml"));
    ASSERT_GT(lines.size(), 5u) << seed;
    for (int k = count(rng); k > 0; --k) mutate(lines, rng);
    std::string text;
    for (const std::string& l : lines) text += l + "\n";
    std::string set;  // a --set override, one mutation in four
    if (coin(rng) == 0) set = keys[pick_key(rng)] + "=" + kExtremes[extreme(rng)];
    SCOPED_TRACE("mutation " + std::to_string(i) + " of " + seed + (set.empty() ? "" : ", --set " + set));
    Scene s;
    try {
      s = parse_scene(text, seed + ".toml");
      if (!set.empty()) apply_override(s, set);
    } catch (const SceneError& e) {
      EXPECT_FALSE(camdyn_fuzz::has_flag_number(e.what())) << e.what();
      continue;
    }
    ++loaded;
    std::printf("mutation %d of %s%s\n", i, seed.c_str(), set.empty() ? "" : (", --set " + set).c_str());
    std::fflush(stdout);
    const camdyn_fuzz::FewSteps r = camdyn_fuzz::run_few_steps(s);
    EXPECT_FALSE(camdyn_fuzz::has_flag_number(r.message)) << r.message;
    EXPECT_FALSE(camdyn_fuzz::has_flag_number(r.report)) << r.report;
    if (!r.refused) ++ran;
    if (r.finished) ++finished;
  }
  std::printf("300 mutations: %d loaded, %d ran, %d finished their few steps\n", loaded, ran, finished);
  // the mutations reach the simulation, not only the loader's refusals
  EXPECT_GT(ran, 60);
  EXPECT_GT(finished, 30);
}

// Found by the test above (mutation 97 of case_B2): output_dt = 1e-14 asked for 2e11 rows
// over the shortened 2 ms and hung in the output loop. Refused at the start, naming the key.
TEST(FuzzRuns, MoreThan1e8OutputRowsAreRefusedAtTheStart) {
  Scene s = paper_case("B2");
  s.run.output_dt = 1e-14;
  try {
    Simulator sim(s);
    ADD_FAILURE() << "output_dt 1e-14 accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("run.output_dt"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("more than 1e8"), std::string::npos) << e.what();
  }
  s.run.output_dt = 1e-8;  // 1e8 rows over t_end = 1: accepted
  EXPECT_NO_THROW(Simulator{s});
}

}  // namespace
}  // namespace camdyn
