// camdyn — `camdyn bench` / run_bench(): the quick work–precision sweep on case A writes a
// well-formed work_precision.csv whose Lee rows are accurate and improve with tolerance.
// (Timings are not checked: the machine is shared.)
#include <gtest/gtest.h>
#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/bench.hpp"
#include "camdyn/scene.hpp"

namespace fs = std::filesystem;

namespace {

using camdyn_test::slurp;
using camdyn_test::split;

double num(const std::string& s) {
  if (s.empty()) return std::nan("");
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  return (end && *end == '\0') ? x : std::nan("");
}

fs::path temp_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() /
               ("camdyn_test_bench_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(Bench, QuickCaseAWritesWellFormedCsv) {
  const fs::path dir = temp_dir("quick");
  camdyn::BenchOptions o;
  o.scenes = {camdyn::paper_case("A")};
  o.labels = {"A"};
  o.quick = true;
  o.repeats = 3;
  o.repeat_cap_seconds = 1.0;  // the stiffest penalty runs are timed once
  o.out_dir = dir.string();
  camdyn::BenchResult res = camdyn::run_bench(o);

  std::ifstream f(dir / "work_precision.csv");
  ASSERT_TRUE(f.good());
  std::string line;
  ASSERT_TRUE(std::getline(f, line));
  const std::vector<std::string> header = split(line, ',');
  ASSERT_EQ(header, camdyn::bench_columns());
  ASSERT_EQ(header.size(), 16u);
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;

  std::vector<std::vector<std::string>> rows;
  while (std::getline(f, line)) {
    if (line.empty()) continue;
    auto r = split(line, ',');
    ASSERT_EQ(r.size(), header.size()) << "row: " << line;
    rows.push_back(r);
  }
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.size(), res.rows.size());

  // Lee rows of case A: tolerance → err_u.
  std::map<std::string, std::vector<std::pair<double, double>>> lee;  // variant → (tol, err)
  bool have_penalty = false, have_ref_check = false, have_holo = false, have_event = false;
  for (const auto& r : rows) {
    EXPECT_EQ(r[col["scene"]], "A");
    const std::string fin = r[col["finished"]];
    ASSERT_TRUE(fin == "0" || fin == "1") << fin;
    EXPECT_TRUE(num(r[col["cpu_seconds"]]) >= 0 || r[col["cpu_seconds"]].empty());
    if (fin == "1") {
      for (const char* k : {"cpu_seconds", "err_u", "err_force", "impulse_err"}) {
        EXPECT_TRUE(std::isfinite(num(r[col[k]]))) << k << " in " << r[col["method"]];
      }
    }
    const std::string m = r[col["method"]];
    if (m == "lee") {
      EXPECT_EQ(fin, "1") << r[col["note"]];
      lee[r[col["variant"]]].push_back({num(r[col["tol"]]), num(r[col["err_u"]])});
    }
    if (m == "penalty") {
      have_penalty = true;
      EXPECT_TRUE(std::isfinite(num(r[col["kp"]])));
      EXPECT_TRUE(std::isfinite(num(r[col["cp"]])));
    }
    have_ref_check = have_ref_check || m == "reference-check";
    have_holo = have_holo || m == "holonomic";
    have_event = have_event || m == "event";
  }
  EXPECT_TRUE(have_penalty);
  EXPECT_TRUE(have_ref_check);
  EXPECT_TRUE(have_holo);
  EXPECT_TRUE(have_event);
  ASSERT_EQ(lee.size(), 2u);  // eq12 and eq17
  for (auto& [variant, pts] : lee) {
    ASSERT_GE(pts.size(), 2u) << variant;
    std::sort(pts.begin(), pts.end(), [](auto a, auto b) { return a.first > b.first; });
    // At the tighter tolerance the displacement error is small ...
    EXPECT_LT(pts.back().second, 1e-5) << variant;
    // ... and the error does not grow as the tolerance tightens (it may already be at
    // round-off level for the rigid case, which stays in contact).
    for (size_t i = 1; i < pts.size(); ++i) {
      EXPECT_LE(pts[i].second, pts[i - 1].second * (1 + 1e-6) + 1e-11)
          << variant << " tol " << pts[i].first;
    }
  }

  // The Markdown report and the headline exist.
  std::ifstream md(dir / "work_precision.md");
  ASSERT_TRUE(md.good());
  std::stringstream ss;
  ss << md.rdbuf();
  EXPECT_NE(ss.str().find("Headline"), std::string::npos);
  ASSERT_EQ(res.headline_text.size(), 1u);
  EXPECT_FALSE(res.headline_text[0].empty());
  fs::remove_all(dir);
}

#ifdef CAMDYN_CLI_PATH
TEST(Bench, CliBadInputExits2) {
  const std::string cli = CAMDYN_CLI_PATH;
  if (cli.empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = temp_dir("cli");
  const std::string base = "'" + cli + "' bench ";
  const std::string redirect = " >/dev/null 2>&1";
  auto status = [&](const std::string& args) {
    const int rc = std::system((base + args + redirect).c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  EXPECT_EQ(status("'" + (dir / "no_such_scene.toml").string() + "' --out '" +
                   (dir / "o").string() + "'"),
            2);
  EXPECT_EQ(status("A --repeats 0 --out '" + (dir / "o").string() + "'"), 2);
  fs::remove_all(dir);
}
#endif
