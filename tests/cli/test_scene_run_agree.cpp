// One validation, one voice (issue 35 item 5, issue 34 item 4): `camdyn scene` and
// `camdyn run` accept and refuse the same scenes. 40 deterministic mutations of the example
// scenes (a number scaled by 0.1, −1, 10 or replaced by 0, 5e-324, 1e12; a line deleted),
// each given to both commands as a file with the same --set lines; `run` is kept short by
// overrides that both get. Was: 18 of 650 fuzzed scenes accepted by `scene` and refused by
// `run` (e.g. elements.pushrod.mass=5e-324, a penetrating start). Also: no raw SUNDIALS
// text ("[ARKODE ERROR]", "[IDA ERROR]", "[CVODE ERROR]") on stderr.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "../test_support.hpp"

namespace fs = std::filesystem;
using camdyn_test::slurp;

namespace {

const std::string kCli = CAMDYN_CLI_PATH;

int sh(const std::string& cmd) {
  const int raw = std::system(cmd.c_str());
  return raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}

void mutate(std::vector<std::string>& lines, std::mt19937& rng) {
  static const char* const kValues[] = {"0", "5e-324", "1e12", "-3"};
  static const double kFactors[] = {0.1, -1.0, 10.0};
  std::uniform_int_distribution<std::size_t> line(0, lines.size() - 1);
  std::uniform_int_distribution<int> kind(0, 3), val(0, 3), fac(0, 2);
  const std::size_t i = line(rng);
  const int k = kind(rng);
  if (k == 3) {
    lines.erase(lines.begin() + long(i));
    return;
  }
  static const std::regex number("[-+]?[0-9]+(\\.[0-9]*)?([eE][-+]?[0-9]+)?");
  for (std::size_t j = 0; j < lines.size(); ++j) {
    std::string& l = lines[(i + j) % lines.size()];
    std::smatch m;
    if (l.rfind('#', 0) != 0 && l.find('=') != std::string::npos && std::regex_search(l, m, number)) {
      char v[40];
      std::snprintf(v, sizeof v, "%.17g", std::strtod(m.str().c_str(), nullptr) * kFactors[fac(rng)]);
      l = m.prefix().str() + (k == 0 ? std::string(kValues[val(rng)]) : std::string(v)) + m.suffix().str();
      return;
    }
  }
}

}  // namespace

TEST(SceneRunAgree, MutatedExamplesAcceptedOrRefusedByBoth) {
  ASSERT_FALSE(kCli.empty());
  const fs::path dir = fs::temp_directory_path() / ("camdyn_agree_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<std::string> seeds = {"case_A", "case_A7", "case_B2", "circle_cam", "lift_cam",
                                          "law_roller", "ohc_bucket_tappet", "ohv_pushrod_train"};
  // Both commands get these: a run of a few steps.
  const std::string sets = " --set run.t_end=2e-4 --set run.output_dt=1e-4 --set run.max_steps=3000";
  std::mt19937 rng(35);
  std::uniform_int_distribution<std::size_t> pick(0, seeds.size() - 1);
  int refused = 0, accepted = 0;
  for (int i = 0; i < 40; ++i) {
    const std::string seed = seeds[pick(rng)];
    std::vector<std::string> lines =
        lines_of(slurp(fs::path(CAMDYN_SOURCE_DIR) / "examples" / (seed + ".toml")));
    mutate(lines, rng);
    const fs::path f = dir / ("m" + std::to_string(i) + ".toml");
    {
      std::ofstream o(f);
      for (const auto& l : lines) o << l << "\n";
    }
    const std::string base = "'" + kCli + "' ";
    const int rs = sh(base + "scene '" + f.string() + "'" + sets + " >/dev/null 2>'" + (dir / "scene.err").string() + "'");
    const int rr = sh("cd '" + dir.string() + "' && timeout 20 " + base + "run '" + f.string() + "'" + sets +
                      " --quiet --out out >/dev/null 2>'" + (dir / "run.err").string() + "'");
    const std::string scene_err = slurp(dir / "scene.err"), run_err = slurp(dir / "run.err");
    SCOPED_TRACE("mutation " + std::to_string(i) + " of " + seed + ": scene exit " + std::to_string(rs) + " (" +
                 scene_err + "), run exit " + std::to_string(rr) + " (" + run_err + ")");
    EXPECT_NE(rr, 124) << "run hung";
    EXPECT_EQ(rs == 2, rr == 2);
    if (rs == 2) {
      ++refused;
      EXPECT_EQ(scene_err, run_err.substr(0, scene_err.size()));  // the same message
    } else {
      ++accepted;
      EXPECT_EQ(rs, 0);
    }
    for (const char* raw : {"[ARKODE", "[IDA ERROR", "[CVODE", "[ERKStep", "[ARKStep"})
      EXPECT_EQ(run_err.find(raw), std::string::npos) << run_err;
  }
  std::printf("40 mutations: %d refused by both, %d accepted by both\n", refused, accepted);
  EXPECT_GT(refused, 5);
  EXPECT_GT(accepted, 12);
  fs::remove_all(dir);
}
