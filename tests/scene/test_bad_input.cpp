// Bad input gets a clear error; nothing computed is lost (issue 7).
//
// BadInput: malformed scene files and command lines, each run through the camdyn CLI:
// exit status exactly 2 (not a signal, not 1), stderr naming the file (or "--set" /
// "--out"), the key and the rule, and nothing run. Cases already in test_cli.cpp
// (BadInputExitsTwoWithKeyAndRule) are not repeated here.
// NothingLost: a run that fails mid-way (max_steps) or is interrupted (SIGINT) exits 1
// and still writes a parseable history.csv and a summary.json saying it did not finish.
#include <gtest/gtest.h>
#include "../test_support.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "camdyn/simulator.hpp"

namespace fs = std::filesystem;

namespace {

using camdyn_test::slurp;
using camdyn_test::split;

const std::string kCli = CAMDYN_CLI_PATH;
const std::string kSrc = CAMDYN_SOURCE_DIR;

struct Proc {
  bool exited = false;  ///< false: killed by a signal (or could not start)
  int code = -1;        ///< exit status, or the signal number
  std::string err;
};

/// fork/exec the CLI with argv (no shell), cwd = dir, stdout to /dev/null, stderr
/// captured; sent `signo` after `sigint_after_s` (if ≥ 0); killed after `timeout_s`.
Proc run_cli(const fs::path& dir, const std::vector<std::string>& args, double timeout_s = 60,
             double sigint_after_s = -1, int signo = SIGINT) {
  Proc r;
  const fs::path errf = dir / "stderr.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) _exit(126);
    FILE* e = std::freopen(errf.c_str(), "w", stderr);
    FILE* o = std::freopen("/dev/null", "w", stdout);
    FILE* i = std::freopen("/dev/null", "r", stdin);
    (void)e, (void)o, (void)i;
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(kCli.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(kCli.c_str(), argv.data());
    _exit(127);
  }
  if (pid < 0) return r;
  const auto t0 = std::chrono::steady_clock::now();
  bool sent_int = false;
  int status = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (sigint_after_s >= 0 && !sent_int && el >= sigint_after_s) {
      ::kill(pid, signo);
      sent_int = true;
    }
    if (el > timeout_s) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (WIFEXITED(status)) {
    r.exited = true;
    r.code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    r.code = WTERMSIG(status);
  }
  r.err = slurp(errf);
  return r;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(kCli.empty()) << "the camdyn CLI was not built";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("camdyn_bad_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream f(dir_ / name, std::ios::binary);
    f << text;
  }
  fs::path dir_;
};

struct Case {
  const char* name;
  std::string file;                 ///< scene file to write ("" = none)
  std::string text;                 ///< its content
  std::vector<std::string> args;    ///< CLI arguments
  std::vector<std::string> expect;  ///< substrings of stderr
};

const std::string kEightKnots = "angles_deg = [0, 45, 90, 135, 180, 225, 270, 315]\n";

TEST_F(BadInput, MalformedScenesAndCommandLinesExitTwo) {
  auto file_case = [](const char* name, const std::string& file, const std::string& text,
                      std::vector<std::string> expect) {
    expect.insert(expect.begin(), file);  // the file is always named
    return Case{name, file, text, {"run", file, "--out", "D", "--set", "run.t_end=0.01"},
                std::move(expect)};
  };
  auto set_case = [](const char* name, std::vector<std::string> sets,
                     std::vector<std::string> expect) {
    std::vector<std::string> args{"run", "--out", "D"};
    for (auto& s : sets) {
      args.push_back("--set");
      args.push_back(s);
    }
    expect.insert(expect.begin(), "--set");
    return Case{name, "", "", args, std::move(expect)};
  };
  const std::vector<Case> cases{
      // wrong types
      file_case("bool for a number", "t1.toml", "[follower]\nmass = true\n",
                {"follower.mass", "must be a number"}),
      file_case("nested array for radii", "t2.toml", "[cam]\nradii = [[2, 2], [2, 2]]\n",
                {"cam.radii", "must be a number"}),
      file_case("array of tables for a table", "t3.toml", "[[cam]]\nradius = 1\n",
                {"'cam'", "must be a table"}),
      file_case("string for a bool", "t4.toml", "[contact]\nseparation = \"yes\"\n",
                {"contact.separation", "true or false"}),
      file_case("date for a number", "t5.toml", "[run]\nt_end = 1979-05-27\n",
                {"run.t_end", "must be a number"}),
      file_case("unknown mass matrix", "t6.toml", "[follower]\nmass_matrix = \"diagonal\"\n",
                {"follower.mass_matrix", "lumped"}),
      file_case("unknown error variant", "t7.toml", "[contact]\nerror_variant = \"eq13\"\n",
                {"contact.error_variant", "eq17"}),
      file_case("unknown linear solver", "t8.toml", "[solver]\nlinear_solver = \"lu\"\n",
                {"solver.linear_solver", "klu"}),
      // negative or zero physical parameters
      file_case("zero mass", "p1.toml", "[follower]\nmass = 0\n", {"follower.mass", "> 0"}),
      file_case("negative E", "p2.toml",
                "[follower]\nkind = \"elastic_bar\"\nyoungs_modulus = -1e7\n",
                {"follower.youngs_modulus", "> 0"}),
      file_case("negative area", "p3.toml", "[follower]\narea = -3\n", {"follower.area", "> 0"}),
      file_case("negative length", "p4.toml", "[follower]\nlength = -24\n",
                {"follower.length", "> 0"}),
      file_case("negative elements", "p5.toml", "[follower]\nelements = -5\n",
                {"follower.elements", ">= 1"}),
      file_case("negative spring", "p6.toml", "[spring]\nstiffness = -500\n",
                {"spring.stiffness", ">= 0"}),
      file_case("negative Rayleigh beta", "p7.toml", "[follower]\nrayleigh_beta = -1e-5\n",
                {"follower.rayleigh_beta", ">= 0"}),
      file_case("negative eccentricity", "p8.toml",
                "[cam]\nprofile = \"circle\"\neccentricity = -0.5\n",
                {"cam.eccentricity", ">= 0"}),
      file_case("negative penalty damping", "p9.toml", "[contact]\npenalty_damping = -1\n",
                {"contact.penalty_damping", ">= 0"}),
      // cam geometry
      file_case("non-convex peanut cam", "c1.toml",
                "[cam]\n" + kEightKnots + "radii = [2, 1, 2, 1, 2, 1, 2, 1]\n",
                {"cam.radii", "not convex"}),
      file_case("self-intersecting cam (knots bunched in 70 deg)", "c2.toml",
                "[cam]\nangles_deg = [0, 10, 20, 30, 40, 50, 60, 70]\n"
                "radii = [2, 2, 2, 2, 2, 2, 2, 2]\n",
                {"cam.radii", "self-intersecting"}),
      file_case("non-convex lift cam", "c3.toml",
                "[cam]\nprofile = \"lift\"\nbase_radius = 0.5\n"
                "lift_angles_deg = [0, 45, 90, 135, 180, 225, 270, 315]\n"
                "lift = [0, 0, 0, 1.4, 1.5, 1.4, 0, 0]\n",
                {"cam.lift", "not convex"}),
      file_case("lift spline dips through the centre", "c4.toml",
                "[cam]\nprofile = \"lift\"\nbase_radius = 0.2\n"
                "lift_angles_deg = [0, 45, 90, 135, 180, 225, 270, 315]\n"
                "lift = [0, 0, 0, 3, 0, 0, 0, 0]\n",
                {"cam.lift", "> 0"}),
      // NaN / inf
      file_case("NaN in the lift table", "n1.toml",
                "[cam]\nprofile = \"lift\"\nlift_angles_deg = [0, 90, 180, 270]\n"
                "lift = [0, 1, nan, 0]\n",
                {"cam.lift[2]", "finite"}),
      // Without the cases' --set run.t_end=0.01, which would repair it (the file and its
      // overrides are validated once, together).
      Case{"inf t_end", "n2.toml", "[run]\nt_end = inf\n", {"run", "n2.toml", "--out", "D"},
           {"n2.toml", "run.t_end", "finite"}},
      file_case("NaN theta0", "n3.toml", "[cam]\ntheta0_deg = nan\n", {"cam.theta0_deg", "finite"}),
      file_case("-inf speed table", "n4.toml",
                "[cam]\nspeed_table_t = [0, 1]\nspeed_table_rev_s = [1, -inf]\n",
                {"cam.speed_table_rev_s[1]", "finite"}),
      // missing required keys
      file_case("speed table without speeds", "m1.toml", "[cam]\nspeed_table_t = [0, 1]\n",
                {"cam.speed_table_rev_s", "as many values"}),
      file_case("lift table without lift values", "m2.toml",
                "[cam]\nprofile = \"lift\"\nlift_angles_deg = [0, 90, 180, 270]\n",
                {"cam.lift", "as many values"}),
      // absurd tolerances and run settings
      file_case("rtol 1e-20", "a1.toml", "[solver]\nrtol = 1e-20\n", {"solver.rtol", ">= 1e-14"}),
      file_case("atol 5", "a2.toml", "[solver]\natol = 5\n", {"solver.atol", "<= 1"}),
      file_case("tol_u 10", "a3.toml", "[contact]\ntol_u = 10\n", {"contact.tol_u", "between 1e-14 and 1"}),
      file_case("negative tol_a", "a4.toml", "[contact]\ntol_a = -1\n", {"contact.tol_a", ">= 0"}),
      file_case("negative output_dt", "a5.toml", "[run]\noutput_dt = -1e-3\n",
                {"run.output_dt", ">= 0"}),
      file_case("negative max_steps", "a6.toml", "[run]\nmax_steps = -3\n",
                {"run.max_steps", ">= 1"}),
      file_case("negative initial step", "a7.toml", "[solver]\ninitial_step = -1\n",
                {"solver.initial_step", ">= 0"}),
      // broken files
      file_case("invalid UTF-8", "u1.toml", std::string("\xff\xfe\x00garbage", 10), {"utf-8"}),
      file_case("integer overflow", "u2.toml", "[follower]\nelements = 99999999999999999999\n",
                {"not representable"}),
      file_case("unterminated string", "u3.toml", "title = \"never closed\n", {":1:"}),
      // command lines
      // network scenes (issue 16)
      file_case("network: lever ratio 0", "w1.toml",
                "[follower]\nkind = \"network\"\n[[nodes]]\nname = \"a\"\nmass = 1\n[[nodes]]\nname = \"b\"\n"
                "[[elements]]\ntype = \"spring\"\nnodes = [\"a\", \"ground\"]\nstiffness = 100\n"
                "[[elements]]\nname = \"rocker\"\ntype = \"lever\"\nnodes = [\"a\", \"b\"]\nratio = 0\n"
                "[[contacts]]\nname = \"cam\"\ntype = \"cam\"\nnodes = [\"a\"]\n",
                {"w1.toml:16", "elements[1].ratio", "> 0", "lever 'rocker'"}),
      file_case("network: dangling node", "w2.toml",
                "[follower]\nkind = \"network\"\n[[nodes]]\nname = \"a\"\nmass = 1\n[[nodes]]\nname = \"spare\"\n"
                "mass = 1\n[[elements]]\ntype = \"spring\"\nnodes = [\"a\", \"ground\"]\nstiffness = 100\n"
                "[[contacts]]\nname = \"cam\"\ntype = \"cam\"\nnodes = [\"a\"]\n",
                {"w2.toml:7", "nodes[1].name", "node 'spare' is dangling"}),
      file_case("network: key of another element type", "w3.toml",
                "[follower]\nkind = \"network\"\n[[nodes]]\nname = \"a\"\nmass = 1\n"
                "[[elements]]\ntype = \"spring\"\nnodes = [\"a\", \"ground\"]\nstiffness = 100\nratio = 2\n"
                "[[contacts]]\nname = \"cam\"\ntype = \"cam\"\nnodes = [\"a\"]\n",
                {"w3.toml:10", "elements[0].ratio", "not a key of a spring element"}),
      set_case("--set NaN", {"follower.mass=nan"}, {"follower.mass", "finite"}),
      set_case("--set absurd rtol", {"solver.rtol=1e-30"}, {"solver.rtol", ">= 1e-14"}),
      set_case("--set missing key", {"=3"}, {"KEY=VALUE"}),
      set_case("--set value for a table", {"cam=3"}, {"'cam'", "must be a table"}),
      set_case("--set zero elements", {"follower.elements=0"}, {"follower.elements", ">= 1"}),
      set_case("--set out-of-range float", {"run.t_end=1e400"}, {"run.t_end", "must be a number"}),
      set_case("--set bad enum", {"follower.kind=elastic"}, {"follower.kind", "elastic_bar"}),
      set_case("--set non-convex radii", {"cam.radii=[2,2,2,2,0.5,2,2,2]"},
               {"cam.radii", "not convex"}),
      Case{"--out under a regular file", "", "", {"run", "--out", "afile/sub"},
           {"--out", "afile/sub", "not writable"}},
      Case{"--out is a regular file", "", "", {"run", "--out", "afile"},
           {"--out", "afile", "not writable"}},
      Case{"--out empty", "", "", {"run", "--out", ""}, {"--out", "not writable"}},
      Case{"scene path is a directory", "", "", {"run", "adir", "--out", "D"},
           {"adir", "cannot read scene file"}},
  };
  ASSERT_GE(cases.size(), 30u);
  write("afile", "not a directory\n");
  fs::create_directories(dir_ / "adir");
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    if (!c.file.empty()) write(c.file, c.text);
    std::string cmd;
    for (const auto& a : c.args) cmd += " '" + a + "'";
    const Proc r = run_cli(dir_, c.args, 30);
    EXPECT_TRUE(r.exited) << "camdyn" << cmd << ": killed by signal " << r.code << "\n" << r.err;
    EXPECT_EQ(r.code, 2) << "camdyn" << cmd << "\nstderr: " << r.err;
    for (const auto& s : c.expect) {
      EXPECT_NE(r.err.find(s), std::string::npos)
          << "camdyn" << cmd << ": stderr lacks '" << s << "':\n" << r.err;
    }
    EXPECT_EQ(r.err.find("terminate called"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "D" / "history.csv")) << "bad input must not run";
    fs::remove_all(dir_ / "D");
  }
}

// ---- nothing computed is lost -----------------------------------------------------------

/// Every line complete and numeric; returns the last t (or −1).
double check_history(const std::string& text, size_t* nrows) {
  const auto lines = split(text, '\n');
  EXPECT_GE(lines.size(), 2u);
  EXPECT_TRUE(text.empty() || text.back() == '\n') << "history.csv ends mid-line";
  const auto& cols = camdyn::history_columns();
  EXPECT_EQ(split(lines.at(0), ',').size(), cols.size()) << lines[0];
  double last_t = -1;
  size_t n = 0;
  for (size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const auto f = split(lines[i], ',');
    EXPECT_EQ(f.size(), cols.size()) << "line " << i + 1 << ": " << lines[i];
    for (const auto& x : f) {
      char* end = nullptr;
      std::strtod(x.c_str(), &end);
      EXPECT_TRUE(!x.empty() && end && *end == '\0') << "line " << i + 1 << ": '" << x << "'";
    }
    last_t = std::strtod(f[0].c_str(), nullptr);
    ++n;
  }
  *nrows = n;
  return last_t;
}

TEST_F(BadInput, FailureMidRunKeepsHistoryAndSummary) {
  const std::string scene = kSrc + "/examples/case_A.toml";
  const Proc r = run_cli(dir_, {"run", scene, "--out", "D", "--set", "run.output_dt=0", "--set",
                                "run.max_steps=100", "--quiet"});
  ASSERT_TRUE(r.exited) << r.err;
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("max_steps"), std::string::npos) << r.err;
  size_t n = 0;
  const double last_t = check_history(slurp(dir_ / "D" / "history.csv"), &n);
  EXPECT_GE(n, 20u) << "rows computed before the failure";
  EXPECT_GT(last_t, 0.0);
  EXPECT_LT(last_t, 1.0) << "stopped before t_end";
  const std::string sum = slurp(dir_ / "D" / "summary.json");
  EXPECT_NE(sum.find("\"finished\": false"), std::string::npos) << sum;
  EXPECT_NE(sum.find("max_steps"), std::string::npos) << "summary gives the reason\n" << sum;
  for (const auto& e : fs::directory_iterator(dir_ / "D")) {
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  }
}

// SIGINT (Ctrl-C) and SIGTERM (kill) each stop the run, keep what was computed, and are
// named as themselves on stderr and in summary.json (issue 27: SIGTERM read "SIGINT").
TEST_F(BadInput, SigintKeepsHistoryAndSummary) {
  for (const int sig : {SIGINT, SIGTERM}) {
    const std::string name = sig == SIGINT ? "SIGINT" : "SIGTERM";
    SCOPED_TRACE(name);
    fs::remove_all(dir_ / "D");
    // The default scene (B2 for 1 s) takes far longer than 1 s: interrupt it.
    const Proc r = run_cli(dir_, {"run", "--out", "D", "--quiet"}, 60, 1.0, sig);
    ASSERT_TRUE(r.exited) << "killed by signal " << r.code << ": " << r.err;
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("camdyn: simulation interrupted at t = "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(": interrupted (" + name + ")\n"), std::string::npos) << r.err;
    size_t n = 0;
    const double last_t = check_history(slurp(dir_ / "D" / "history.csv"), &n);
    EXPECT_GE(n, 10u);
    EXPECT_GT(last_t, 0.0);
    EXPECT_LT(last_t, 1.0);
    const std::string sum = slurp(dir_ / "D" / "summary.json");
    EXPECT_NE(sum.find("\"finished\": false"), std::string::npos) << sum;
    EXPECT_NE(sum.find(": interrupted (" + name + ")\""), std::string::npos) << sum;
    EXPECT_NE(sum.find("\"termination\": \"stopped_by_caller\""), std::string::npos) << sum;
    const std::string other = sig == SIGINT ? "SIGTERM" : "SIGINT";
    EXPECT_EQ(sum.find(other), std::string::npos) << sum;
    for (const auto& e : fs::directory_iterator(dir_ / "D")) {
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
    }
  }
}

}  // namespace
