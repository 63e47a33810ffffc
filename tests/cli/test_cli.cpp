// The command-line tool and the output files (docs/interface.md), driven as a user would:
// the camdyn binary is run through the shell in a fresh temporary directory.
#include <gtest/gtest.h>
#include "../cli_run_support.hpp"
#include "../test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace fs = std::filesystem;

namespace {

using camdyn_test::CliResult;
using camdyn_test::shell_quote;
using camdyn_test::slurp;
using camdyn_test::split;

const std::string kCli = CAMDYN_CLI_PATH;
const std::string kSource = CAMDYN_SOURCE_DIR;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) {
    if (!line.empty()) out.push_back(line);
  }
  return out;
}

bool parses_as_double(const std::string& s) {
  if (s.empty()) return false;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end && *end == '\0';
}

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(kCli.empty()) << "the camdyn CLI was not built (CAMDYN_BUILD_CLI=OFF)";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("camdyn_cli_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }

  /// Run "camdyn ARGS" in the test directory; ARGS is shell text.
  CliResult camdyn(const std::string& args) { return camdyn_test::run_cli(kCli, dir_, args); }

  fs::path write_file(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream f(p, std::ios::binary);
    f << text;
    return p;
  }

  static std::string example(const std::string& name) {
    return (fs::path(kSource) / "examples" / name).string();
  }

  fs::path dir_;
};

bool have_matplotlib() {
  return std::system("/usr/bin/python3 -c 'import numpy, matplotlib' >/dev/null 2>&1") == 0;
}

/// history.csv: header, then rows with as many fields as the header, all numbers.
void expect_history_parseable(const std::string& text, size_t min_rows) {
  const auto lines = lines_of(text);
  ASSERT_FALSE(lines.empty()) << "history.csv is empty";
  const auto header = split(lines[0], ',');
  const auto& cols = camdyn::history_columns();
  ASSERT_EQ(header.size(), cols.size()) << lines[0];
  for (size_t i = 0; i < cols.size(); ++i) EXPECT_EQ(header[i], cols[i]);
  EXPECT_GE(lines.size() - 1, min_rows);
  double t_prev = -std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < lines.size(); ++i) {
    const auto f = split(lines[i], ',');
    ASSERT_EQ(f.size(), header.size()) << "line " << i + 1 << ": " << lines[i];
    for (const auto& x : f) ASSERT_TRUE(parses_as_double(x)) << "line " << i + 1 << ": " << x;
    const double t = std::strtod(f[0].c_str(), nullptr);
    EXPECT_GE(t, t_prev) << "time goes back at line " << i + 1;
    t_prev = t;
  }
}

void expect_no_temp_files(const fs::path& d) {
  for (const auto& e : fs::directory_iterator(d)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos)
        << "left behind: " << e.path();
  }
}

// ---- help -----------------------------------------------------------------------------

TEST_F(CliTest, HelpListsEveryCommand) {
  const auto r = camdyn("--help");
  EXPECT_EQ(r.status, 0) << r.err;
  for (const char* cmd : {"run", "cam", "scene", "plot", "report", "jump", "sweep"}) {
    EXPECT_NE(r.out.find(cmd), std::string::npos) << "--help does not list " << cmd << "\n"
                                                  << r.out;
  }
}

TEST_F(CliTest, EveryCommandHasHelp) {
  for (const char* cmd : {"run", "cam", "scene", "plot", "report", "jump", "sweep"}) {
    const auto r = camdyn(std::string(cmd) + " --help");
    EXPECT_EQ(r.status, 0) << cmd << ": " << r.err;
    EXPECT_NE(r.out.find(cmd), std::string::npos) << r.out;
  }
  const auto r = camdyn("run --help");
  for (const char* opt : {"--out", "--set", "--quiet", "--plot"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << "run --help lacks " << opt;
  }
}

TEST_F(CliTest, NoCommandIsBadInput) {
  const auto r = camdyn("");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("run"), std::string::npos) << r.err;
}

// ---- cam --------------------------------------------------------------------------------

TEST_F(CliTest, CamWritesOneRevolution) {
  const auto r = camdyn("cam --out D");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = slurp(dir_ / "D" / "cam.csv");
  const auto lines = lines_of(text);
  ASSERT_FALSE(lines.empty());
  // The first seven columns as before issue 24, then jerk, pressure angle and the profile.
  EXPECT_EQ(lines[0], "theta,X_C,dX_dtheta,d2X_dtheta2,beta,r,rho,d3X_dtheta3,pressure_angle,profile_x,profile_y");
  ASSERT_EQ(lines.size(), 3601u);
  const double two_pi = 2 * std::acos(-1.0);
  for (size_t i = 1; i < lines.size(); ++i) {
    const auto f = split(lines[i], ',');
    ASSERT_EQ(f.size(), 11u) << lines[i];
    for (const auto& x : f) ASSERT_TRUE(parses_as_double(x)) << lines[i];
    EXPECT_NEAR(std::strtod(f[0].c_str(), nullptr), two_pi * double(i - 1) / 3600.0, 1e-12);
    EXPECT_GT(std::strtod(f[5].c_str(), nullptr), 0.0) << "r > 0: " << lines[i];
    EXPECT_GT(std::strtod(f[6].c_str(), nullptr), 0.0) << "rho > 0: " << lines[i];
  }
  expect_no_temp_files(dir_ / "D");
  if (have_matplotlib()) {
    EXPECT_TRUE(fs::is_regular_file(dir_ / "D" / "cam_profile.png")) << r.err;
    EXPECT_TRUE(fs::is_regular_file(dir_ / "D" / "cam_kinematics.png")) << r.err;
  }
}

TEST_F(CliTest, CamPointsOption) {
  const auto r = camdyn("cam --out D --points 90 --no-plot");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines_of(slurp(dir_ / "D" / "cam.csv")).size(), 91u);
}

// ---- scene ------------------------------------------------------------------------------

TEST_F(CliTest, SceneResolvedReparses) {
  const auto r = camdyn("scene " + shell_quote(example("case_A.toml")) + " --resolved");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_FALSE(r.out.empty());
  camdyn::Scene again;
  ASSERT_NO_THROW(again = camdyn::parse_scene(r.out, "<camdyn scene output>")) << r.out;
  const camdyn::Scene original = camdyn::load_scene_file(example("case_A.toml"));
  EXPECT_EQ(again.title, original.title);
  EXPECT_EQ(again.follower.kind, original.follower.kind);
  EXPECT_EQ(again.follower.mass, original.follower.mass);
  EXPECT_EQ(again.cam.speed_rev_s, original.cam.speed_rev_s);
  EXPECT_GT(again.contact.tol_u, 0.0) << "--resolved fills in tol_u";
  ASSERT_NO_THROW(camdyn::validate(again));
  // Resolving is idempotent: printing the re-parsed scene gives the same text.
  EXPECT_EQ(camdyn::to_toml(again), r.out);
}

TEST_F(CliTest, SceneAppliesOverrides) {
  const auto r = camdyn("scene --resolved --set cam.speed_rev_s=3 --set title=overridden");
  ASSERT_EQ(r.status, 0) << r.err;
  const camdyn::Scene s = camdyn::parse_scene(r.out, "<camdyn scene output>");
  EXPECT_EQ(s.cam.speed_rev_s, 3.0);
  EXPECT_EQ(s.title, "overridden");
}

// ---- bad input: exit status 2, message names the key and the rule ------------------------

struct BadCase {
  const char* name;
  std::string args;          // shell text after "camdyn"
  std::string scene_name;    // if not empty, a scene file written first
  std::string scene_text;
  std::vector<std::string> expect;  // substrings of stderr
};

TEST_F(CliTest, BadInputExitsTwoWithKeyAndRule) {
  const std::vector<BadCase> cases{
      {"nonexistent scene file", "run no_such_scene.toml --out D", "", "",
       {"no_such_scene.toml"}},
      {"unknown --set key", "run --set cam.bogus=1 --out D", "", "", {"bogus", "speed_rev_s"}},
      {"--set without =", "run --set cam.speed_rev_s --out D", "", "",
       {"cam.speed_rev_s", "KEY=VALUE"}},
      {"--set value of the wrong type", "run --set follower.mass=abc --out D", "", "",
       {"follower.mass", "abc"}},
      {"--set unknown enum value", "run --set contact.model=magic --out D", "", "",
       {"contact.model", "magic", "penalty"}},
      {"--set out of range", "run --set run.t_end=-1 --out D", "", "", {"run.t_end", "-1"}},
      {"unknown subcommand", "frobnicate", "", "", {"frobnicate", "run"}},
      {"unknown option", "run --frobnicate --out D", "", "", {"--frobnicate"}},
      {"two scene files", "run a.toml b.toml --out D", "", "", {"b.toml"}},
      {"output dir not writable", "run --out /proc/camdyn", "", "",
       {"/proc/camdyn", "not writable"}},
      {"negative mass", "run neg_mass.toml --out D", "neg_mass.toml",
       "title = \"negative mass\"\n[follower]\nkind = \"rigid\"\nmass = -1.0\n",
       {"neg_mass.toml", "follower.mass", "-1", "> 0"}},
      {"unknown key in a scene file", "run typo.toml --out D", "typo.toml",
       "title = \"typo\"\n[spring]\nstifness = 500.0\n",
       {"typo.toml", "stifness", "stiffness"}},
      {"TOML syntax error", "scene broken.toml", "broken.toml", "title = \n[cam\n",
       {"broken.toml"}},
      {"non-convex cam", "cam dented.toml --out D", "dented.toml",
       "title = \"dented\"\n[cam]\nprofile = \"points\"\n"
       "angles_deg = [0, 45, 90, 135, 180, 225, 270, 315]\n"
       "radii = [2.0, 2.0, 2.0, 2.0, 0.8, 2.0, 2.0, 2.0]\n",
       {"cam.radii", "convex"}},
      {"cam --points out of range", "cam --points 0 --out D", "", "", {"--points"}},
      {"plot of a missing directory", "plot no_such_dir", "", "", {"no_such_dir"}},
      {"report of a missing directory", "report no_such_dir", "", "",
       {"camdyn: report: key 'DIR' = no_such_dir: not a directory\n"}},
      {"report of a directory without results", "report .", "", "",
       {"camdyn: report: key 'DIR' = .: holds neither summary.json (from 'camdyn run') nor sweep.csv (from "
        "'camdyn sweep')\n"}},
      {"unknown paper case", "scene --case Z9", "", "", {"Z9", "B1"}},
  };
  ASSERT_GE(cases.size(), 10u);
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    if (!c.scene_name.empty()) write_file(c.scene_name, c.scene_text);
    const auto r = camdyn(c.args);
    EXPECT_EQ(r.status, 2) << "camdyn " << c.args << "\nstderr: " << r.err;
    for (const auto& s : c.expect) {
      EXPECT_NE(r.err.find(s), std::string::npos)
          << "camdyn " << c.args << ": stderr lacks '" << s << "':\n"
          << r.err;
    }
    EXPECT_EQ(r.err.find("terminate called"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "D" / "history.csv")) << "bad input must not run";
  }
}

// ---- run --------------------------------------------------------------------------------

TEST_F(CliTest, ShortRunWritesAllOutputs) {
  const auto r =
      camdyn("run " + shell_quote(example("case_A.toml")) + " --set run.t_end=0.02 --out D");
  ASSERT_EQ(r.status, 0) << r.err;
  const fs::path d = dir_ / "D";
  const std::string history = slurp(d / "history.csv");
  EXPECT_EQ(history.rfind("t,theta,u_c,v_c,a_c,contact_force,gap,in_contact", 0), 0u)
      << history.substr(0, 200);
  expect_history_parseable(history, 2);
  const auto lines = lines_of(history);
  const auto last = split(lines.back(), ',');
  EXPECT_NEAR(std::strtod(last[0].c_str(), nullptr), 0.02, 1e-9) << "last row at t_end";

  const std::string events = slurp(d / "events.csv");
  EXPECT_EQ(events.rfind("t,kind,impact_velocity", 0), 0u) << events;

  const std::string summary = slurp(d / "summary.json");
  EXPECT_NE(summary.find("\"finished\": true"), std::string::npos) << summary;
  for (const char* key :
       {"\"scene\"", "\"message\"", "\"t_end\"", "\"steps\"", "\"rejected_steps\"",
        "\"rhs_evals\"", "\"contact_iterations\"", "\"separations\"", "\"impacts\"",
        "\"max_contact_force\"", "\"min_gap\"", "\"max_penetration\"", "\"cpu_seconds\"",
        "\"wall_seconds\"", "\"options\"", "\"integrator\"", "\"contact_model\"",
        "\"iterations\"", "\"model\""}) {
    EXPECT_NE(summary.find(key), std::string::npos) << "summary.json lacks " << key;
  }
  EXPECT_EQ(summary.find("nan"), std::string::npos) << summary;
  expect_no_temp_files(d);
  EXPECT_FALSE(r.out.empty()) << "the brief report goes to stdout";
}

TEST_F(CliTest, QuietRunPrintsNothing) {
  const auto r = camdyn("run " + shell_quote(example("case_A.toml")) +
                        " --set run.t_end=0.005 --out D --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "") << "no progress line when stderr is not a terminal";
  EXPECT_TRUE(fs::is_regular_file(dir_ / "D" / "summary.json"));
}

TEST_F(CliTest, FailedRunKeepsWhatItComputed) {
  const auto r = camdyn("run " + shell_quote(example("case_A.toml")) +
                        " --set run.max_steps=50 --set run.output_dt=0 --out D --quiet");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("simulation failed at t ="), std::string::npos) << r.err;
  const fs::path d = dir_ / "D";
  expect_history_parseable(slurp(d / "history.csv"), 2);
  const std::string summary = slurp(d / "summary.json");
  EXPECT_NE(summary.find("\"finished\": false"), std::string::npos) << summary;
  EXPECT_TRUE(fs::is_regular_file(d / "events.csv"));
  expect_no_temp_files(d);
}

// ---- the output library -----------------------------------------------------------------

TEST(Output, JsonStringEscapes) {
  using camdyn::json_string;
  EXPECT_EQ(json_string("plain"), "\"plain\"");
  EXPECT_EQ(json_string("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(json_string("l1\nl2\t\r"), "\"l1\\nl2\\t\\r\"");
  EXPECT_EQ(json_string(std::string("\x01", 1)), "\"\\u0001\"");
  EXPECT_EQ(json_string("ρ ≤ 0"), "\"ρ ≤ 0\"");        // valid UTF-8 passes through
  EXPECT_EQ(json_string("bad\xff"), "\"bad\\ufffd\"");  // invalid byte replaced
}

TEST(Output, JsonNumbers) {
  using camdyn::json_number;
  EXPECT_EQ(json_number(std::nan("")), "null");
  EXPECT_EQ(json_number(std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(json_number(-std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(json_number(0.5), "0.5");
  EXPECT_EQ(std::strtod(json_number(0.1 + 0.2).c_str(), nullptr), 0.1 + 0.2);
}

TEST(Output, FullPrecisionCsv) {
  camdyn::HistoryWriter w;
  camdyn::HistoryRow row;
  row.t = 1.0 / 3.0;
  row.u_c = -2.0e-17 / 7.0;
  row.contact_force = 123456.789012345678;
  row.gap = std::nextafter(1.0, 2.0);
  row.in_contact = 1;
  w.on_row(row);
  w.on_event({0.25, -0.125, 0.0, 0.0, "", camdyn::EventKind::Impact});
  const std::string csv = camdyn::history_csv(w.rows());
  const auto lines = lines_of(csv);
  ASSERT_EQ(lines.size(), 2u);
  const auto f = split(lines[1], ',');
  ASSERT_EQ(f.size(), camdyn::history_columns().size());
  EXPECT_EQ(std::strtod(f[0].c_str(), nullptr), row.t);
  EXPECT_EQ(std::strtod(f[2].c_str(), nullptr), row.u_c);
  EXPECT_EQ(std::strtod(f[5].c_str(), nullptr), row.contact_force);
  EXPECT_EQ(std::strtod(f[6].c_str(), nullptr), row.gap);
  EXPECT_EQ(f[7], "1");
  w.on_event({0.5, 0.0, 7.5, 0.0, "", camdyn::EventKind::Separation});
  // issue 15: the cam angle is a new column; issue 13: the impact impulse applied at the
  // instant the last
  EXPECT_EQ(camdyn::events_csv(w.events()),
            "t,kind,impact_velocity,theta,impulse\n0.25,impact,-0.125,0,0\n0.5,separation,0,7.5,0\n");
}

TEST(Output, AtomicFileRenamesOnlyOnCommit) {
  const fs::path d =
      fs::temp_directory_path() / ("camdyn_atomic_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  const std::string path = (d / "x.txt").string();
  {
    camdyn::AtomicFile f(path);
    f.write("half");
    EXPECT_FALSE(fs::exists(path)) << "visible before commit";
    EXPECT_TRUE(fs::exists(f.temp_path()));
  }  // abandoned
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(d)) << "temporary file left behind";
  camdyn::write_file_atomic(path, "whole\n");
  EXPECT_EQ(slurp(path), "whole\n");
  camdyn::write_file_atomic(path, "replaced\n");
  EXPECT_EQ(slurp(path), "replaced\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  fs::remove_all(d);
}

TEST(Output, EnsureOutputDir) {
  const fs::path d =
      fs::temp_directory_path() / ("camdyn_outdir_" + std::to_string(::getpid())) / "a" / "b";
  EXPECT_NO_THROW(camdyn::ensure_output_dir(d.string()));
  EXPECT_TRUE(fs::is_directory(d));
  fs::remove_all(d.parent_path().parent_path());
  try {
    camdyn::ensure_output_dir("/proc/camdyn/out");
    FAIL() << "no error for /proc/camdyn/out";
  } catch (const camdyn::SceneError& e) {
    EXPECT_EQ(e.file(), "--out");
    EXPECT_EQ(e.key(), "out");
    EXPECT_EQ(e.value(), "/proc/camdyn/out");
    EXPECT_NE(e.rule().find("output directory is not writable"), std::string::npos);
  }
}

TEST(Output, SummaryJsonHasEveryKey) {
  camdyn::Summary s;
  s.scene = "quote \" and backslash \\";
  s.finished = false;
  s.message = "step size too small\nat t = 0.1";
  s.t_end = 0.1;
  s.min_gap = std::numeric_limits<double>::infinity();
  s.max_contact_force = std::nan("");
  s.events.push_back({0.05, 0.3, 0.0, 0.0, "", camdyn::EventKind::Impact});
  s.events.push_back({0.07, 0.0, 0.0, 0.0, "", camdyn::EventKind::Separation});
  camdyn::Scene scene;
  scene.title = "t\"itle";
  scene.contact.tol_u = 1e-8;
  const std::string j = camdyn::summary_json(s, scene);
  for (const char* key :
       {"scene", "finished", "message", "t_end", "steps", "rejected_steps", "rhs_evals",
        "contact_iterations", "separations", "impacts", "max_contact_force", "min_gap",
        "max_penetration", "cpu_seconds", "wall_seconds", "options", "integrator",
        "contact_model", "termination", "iterations", "displacement", "velocity", "acceleration",
        "iteration_failures", "first_tensile_time", "energy_residual", "model", "events",
        // options: every table and a few keys
        "cam", "follower", "spring", "contact", "solver", "run", "angles_deg", "radii",
        "speed_rev_s", "youngs_modulus", "mass_matrix", "stiffness", "precompression",
        "error_variant", "tol_u", "penalty_law", "rtol", "atol", "linear_solver", "output_dt",
        "max_steps"}) {
    EXPECT_NE(j.find("\"" + std::string(key) + "\":"), std::string::npos) << key << "\n" << j;
  }
  // Keys of the summary itself appear once (a duplicated key is invalid JSON for strict
  // readers; lin_setups was written twice after two branches each added it).
  for (const char* key : {"lin_setups", "lin_analyses", "relocated_steps", "min_contact_force", "nonlin_iters",
                          "nonlin_conv_fails", "err_test_fails"}) {
    const std::string k = "\"" + std::string(key) + "\":";
    const size_t first = j.find(k);
    EXPECT_NE(first, std::string::npos) << key;
    EXPECT_EQ(j.find(k, first + 1), std::string::npos) << key << " twice";
  }
  EXPECT_NE(j.find("\"finished\": false"), std::string::npos);
  EXPECT_NE(j.find("\"min_gap\": null"), std::string::npos) << "inf → null";
  EXPECT_NE(j.find("\"max_contact_force\": null"), std::string::npos) << "nan → null";
  EXPECT_NE(j.find("\"events\": 2"), std::string::npos);
  EXPECT_NE(j.find("\"model\": \"lee\""), std::string::npos) << "enums as strings";
  EXPECT_NE(j.find("\"kind\": \"rigid\""), std::string::npos);
  EXPECT_NE(j.find("\"message\": \"step size too small\\nat t = 0.1\""), std::string::npos);
  EXPECT_EQ(j.find("nan"), std::string::npos);
  EXPECT_EQ(j.find("inf"), std::string::npos);
  // Balanced braces outside strings: a cheap well-formedness check.
  int depth = 0;
  bool in_str = false, esc = false;
  for (char c : j) {
    if (in_str) {
      if (esc) esc = false;
      else if (c == '\\') esc = true;
      else if (c == '"') in_str = false;
      continue;
    }
    if (c == '"') in_str = true;
    if (c == '{' || c == '[') ++depth;
    if (c == '}' || c == ']') --depth;
    ASSERT_GE(depth, 0);
  }
  EXPECT_EQ(depth, 0);
  EXPECT_FALSE(in_str);
}

}  // namespace
