// A damaged sweep journal is reported on --resume, never used (issue 35): was, corrupted
// lines went into poincare.csv silently. A torn last line (a killed sweep) is still dropped
// without a word and its point recomputed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "camdyn/designer.hpp"
#include "camdyn/scene.hpp"
#include "../test_support.hpp"

namespace fs = std::filesystem;
using namespace camdyn;
using camdyn_test::slurp;

namespace {

struct Sweep {
  Scene base;
  SweepOptions o;
};

Sweep tiny_sweep(const fs::path& dir) {
  Sweep s;
  s.base = paper_case("A");
  apply_overrides(s.base, {"run.t_end=0.2", "run.output_dt=0.01"});
  s.o.axes = {make_sweep_axis(s.base, "cam.speed_rev_s", 5, 6, NAN, 2, false)};
  s.o.jobs = 1;
  s.o.out_dir = dir.string();
  return s;
}

std::string resume_error(const fs::path& dir) {
  Sweep s = tiny_sweep(dir);
  s.o.resume = true;
  try {
    run_sweep(s.base, s.o);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SweepJournal, DamagedLinesAreReportedOnResume) {
  const fs::path dir = fs::temp_directory_path() / ("camdyn_journal_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  Sweep s = tiny_sweep(dir);
  const SweepResult r = run_sweep(s.base, s.o);
  ASSERT_EQ(r.computed + r.skipped, 2);
  const std::string journal = slurp(dir / "sweep.journal");
  ASSERT_NE(journal.find("E\t1\n"), std::string::npos);
  EXPECT_EQ(resume_error(dir), "");  // the intact journal resumes

  // A Poincaré line with a field that is no number.
  std::ofstream(dir / "sweep.journal", std::ios::binary) << journal << "Q\t0\t5,1,0.2,zz,0\n";
  std::string e = resume_error(dir);
  EXPECT_NE(e.find("line"), std::string::npos) << e;
  EXPECT_NE(e.find("'zz' is not a number"), std::string::npos) << e;
  // A line that is no journal line at all, and a row cut to too few fields.
  std::ofstream(dir / "sweep.journal", std::ios::binary) << journal << "garbage\n";
  EXPECT_NE(resume_error(dir).find("not an R, Q or E line"), std::string::npos);
  std::ofstream(dir / "sweep.journal", std::ios::binary) << "R\t0\t5,1,3\nE\t0\n";
  EXPECT_NE(resume_error(dir).find("fields, expected"), std::string::npos);
  // A torn last line is a killed sweep: resumed without a word.
  std::ofstream(dir / "sweep.journal", std::ios::binary) << journal << "Q\t1\t6,3";
  EXPECT_EQ(resume_error(dir), "");
  fs::remove_all(dir);
}
