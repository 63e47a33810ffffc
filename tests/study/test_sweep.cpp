// Sweeps (issue 15): bad input, the same files for any number of jobs, the journal (killed
// and resumed equals uninterrupted), failing and timed-out points, batches, sweep axes, plots.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/designer.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "../test_support.hpp"
#include "../circle_cam_support.hpp"
#include "sweep_test_support.hpp"

namespace fs = std::filesystem;
using namespace camdyn;
using camdyn_test::circle_scene;
using camdyn_test::example;
using camdyn_test::Csv;
using camdyn_test::kCli;
using camdyn_test::read_csv;
using camdyn_test::slurp;
using camdyn_test::SweepTest;

// ---- sweeps: bad input, determinism, resume ---------------------------------------------

TEST_F(SweepTest, BadInputExitsTwoWithTheRule) {
  const std::string sc = "'" + example("circle_cam.toml") + "' --out S ";
  struct Case { std::string args, needle; };
  const std::vector<Case> cases = {
      {"--key cam.nope --from 1 --to 2 --points 3", "key 'key' = cam.nope: unknown scene key (numeric keys: "},
      {"--key contact.model --from 1 --to 2 --points 3", "key 'key' = contact.model: is a string, not a number"},
      {"--key cam.radii --from 1 --to 2 --points 3", "is an array, not a number"},
      {"--key cam.speed_rev_s --from 2 --to 2 --points 3", "key 'to' = 2: must be > --from = 2 (empty or reversed range)"},
      {"--key cam.speed_rev_s --from 3 --to 2 --points 3", "key 'to' = 2: must be > --from = 3 (empty or reversed range)"},
      {"--key cam.speed_rev_s --from 1 --to 2 --step 0", "key 'step' = 0: must be > 0"},
      {"--key cam.speed_rev_s --from 1 --to 2 --step -0.5", "key 'step' = -0.5: must be > 0"},
      {"--key cam.speed_rev_s --from 1 --to 2 --points 1", "key 'points' = 1: must be >= 2"},
      {"--key cam.speed_rev_s --from 1 --to 2 --points 1000001", "key 'points' = 1000001: at most 1000000 points"},
      {"--key cam.speed_rev_s --from 0 --to 2 --step 1e-6", "at most 1000000 points per sweep"},
      {"--key cam.speed_rev_s --from 1 --to 2 --points 1001 --key2 spring.stiffness --from2 1 --to2 2 --points2 1000",
       "at most 1000000 points per sweep (grid total)"},
      {"--key cam.speed_rev_s --from 0 --to 2 --points 3 --log", "--log needs --from > 0"},
      {"--key cam.speed_rev_s --from 1 --to 2", "give exactly one of --step S and --points N"},
      {"--key cam.speed_rev_s --from 1 --to 2 --step 0.5 --points 3", "give exactly one of --step S and --points N"},
      {"--key cam.speed_rev_s --from 1 --to 2 --points 3 --jobs -1", "must be >= 1 (0: all cores)"},
      {"--key cam.speed_rev_s --from 1 --to 2 --points 3 --key2 spring.stiffness --from2 5 --to2 4 --points2 2",
       "--to2: key 'to2' = 4: must be > --from = 5 (empty or reversed range)"},
      {"--key cam.speed_rev_s --from 1 --to 2 --points 3 --from2 5", "--from2/--to2/--step2/--points2/--log2 need --key2 KEY"},
      {"--key cam.speed_rev_s --from 1 --to 2 --points 3 --key2 cam.speed_rev_s --from2 1 --to2 2 --points2 2",
       "key 'key2' = cam.speed_rev_s: must differ from --key"},
  };
  for (const auto& c : cases) {
    const R r = camdyn("sweep " + sc + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
  }
}

TEST_F(SweepTest, JobsOneAndTwoGiveIdenticalFiles) {
  const std::string common = "sweep '" + example("case_A7.toml") +
                             "' --key cam.speed_rev_s --from 6 --to 7.5 --points 6 --key2 spring.precompression "
                             "--from2 6 --to2 7 --points2 2 --set run.t_end=0.3 --set run.output_dt=0.01 "
                             "--set run.settle_revolutions=1 --no-timing --quiet";
  ASSERT_EQ(camdyn(common + " --jobs 1 --out J1").status, 0);
  const R r2 = camdyn(common + " --jobs 2 --out J2");
  ASSERT_EQ(r2.status, 0) << r2.err;
  const std::string a = slurp(dir_ / "J1" / "sweep.csv"), b = slurp(dir_ / "J2" / "sweep.csv");
  EXPECT_EQ(a, b);
  EXPECT_EQ(slurp(dir_ / "J1" / "poincare.csv"), slurp(dir_ / "J2" / "poincare.csv"));
  const Csv c = read_csv(dir_ / "J1" / "sweep.csv");
  ASSERT_EQ(c.rows.size(), 12u);
  EXPECT_EQ(c.header[0], "cam.speed_rev_s");
  EXPECT_EQ(c.header[1], "spring.precompression");
  EXPECT_EQ(c.header.back(), "message");
  // grid order: first key slowest
  EXPECT_EQ(c.num(0, "cam.speed_rev_s"), 6);
  EXPECT_EQ(c.num(0, "spring.precompression"), 6);
  EXPECT_EQ(c.num(1, "spring.precompression"), 7);
  EXPECT_EQ(c.num(11, "cam.speed_rev_s"), 7.5);
  for (std::size_t i = 0; i < c.rows.size(); ++i) EXPECT_EQ(c.num(i, "cpu_seconds"), 0);
}

TEST_F(SweepTest, KilledAndResumedEqualsUninterrupted) {
  const std::string common = "sweep '" + example("circle_cam.toml") +
                             "' --key cam.speed_rev_s --from 12 --to 16 --points 9 --set run.t_end=0.3 "
                             "--set run.output_dt=0.01 --set contact.restitution=0.5 --no-timing --quiet --jobs 2";
  ASSERT_EQ(camdyn(common + " --out FULL").status, 0);
  ASSERT_EQ(camdyn(common + " --out PART").status, 0);
  // Simulate a kill: keep the first 3 complete points of the journal plus a torn half
  // point (an R line without its E line and a partial line), drop the outputs.
  const std::string j = slurp(dir_ / "PART" / "sweep.journal");
  std::size_t pos = 0;
  for (int e = 0; e < 3; ++e) pos = j.find("\nE\t", pos) + 1;
  pos = j.find('\n', pos) + 1;
  std::string part = j.substr(0, pos);
  const std::size_t next_r = j.find("R\t", pos);
  part += j.substr(next_r, j.find('\n', next_r) + 1 - next_r) + "Q\t7\t13,0,0";
  {
    std::ofstream f(dir_ / "PART" / "sweep.journal", std::ios::binary | std::ios::trunc);
    f << part;
  }
  fs::remove(dir_ / "PART" / "sweep.csv");
  fs::remove(dir_ / "PART" / "poincare.csv");
  const R r = camdyn(common + " --out PART --resume");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "PART" / "sweep.csv"), slurp(dir_ / "FULL" / "sweep.csv"));
  EXPECT_EQ(slurp(dir_ / "PART" / "poincare.csv"), slurp(dir_ / "FULL" / "poincare.csv"));
  // the resumed run computed 6 points and took 3 from the journal
  const R r2 = camdyn(common.substr(0, common.find(" --quiet")) + " --no-timing --jobs 2 --out PART --resume");
  EXPECT_NE(r2.out.find("9 points (0 computed, 9 from the journal)"), std::string::npos) << r2.out;
  // resume against another scene or other keys → exit 2
  const R bad = camdyn(common + " --set spring.stiffness=400 --out PART --resume");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("is from another sweep"), std::string::npos) << bad.err;
  const R bad2 = camdyn("sweep '" + example("circle_cam.toml") +
                        "' --key spring.stiffness --from 400 --to 500 --points 3 --quiet --out PART --resume");
  EXPECT_EQ(bad2.status, 2);
  EXPECT_NE(bad2.err.find("is from another sweep"), std::string::npos) << bad2.err;
}

TEST_F(SweepTest, SigkillMidSweepThenResume) {
  // A real kill: SIGKILL after the first rows are in the journal, then --resume.
  const std::string common = "sweep '" + example("case_A7.toml") +
                             "' --key cam.speed_rev_s --from 6 --to 7.5 --points 8 --set run.t_end=0.5 "
                             "--set run.output_dt=0 --no-timing --quiet --jobs 1";
  ASSERT_EQ(camdyn(common + " --out FULL").status, 0);
  const std::string j = (dir_ / "K" / "sweep.journal").string();
  const std::string cmd = "cd '" + dir_.string() + "' && ('" + kCli + "' " + common +
                          " --out K & pid=$!; for i in $(seq 1 400); do n=$(grep -c '^E' '" + j +
                          "' 2>/dev/null || echo 0); [ \"$n\" -ge 2 ] && break; sleep 0.01; done; kill -9 $pid; "
                          "wait $pid) >/dev/null 2>&1";
  std::system(cmd.c_str());
  const R r = camdyn(common + " --out K --resume");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "K" / "sweep.csv"), slurp(dir_ / "FULL" / "sweep.csv"));
}

TEST_F(SweepTest, FailingPointIsRecordedAndTheSweepGoesOn) {
  // follower.mass = 0 is invalid, and run.max_steps = 20 stops every run early: each
  // point becomes a row with finished = 0 and its message; the sweep still exits 0.
  const R r = camdyn("sweep '" + example("circle_cam.toml") +
                     "' --key follower.mass --from 0 --to 1 --points 3 --set run.t_end=0.05 --set run.max_steps=5 "
                     "--set run.output_dt=0 --quiet --out F");
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv c = read_csv(dir_ / "F" / "sweep.csv");
  ASSERT_EQ(c.rows.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(c.num(i, "finished"), 0);
  const std::string text = slurp(dir_ / "F" / "sweep.csv");
  EXPECT_NE(text.find("follower.mass"), std::string::npos) << text;
  EXPECT_NE(text.find("max_steps"), std::string::npos) << text;
}

TEST(SweepBatch, RunBatchIsIndependentOfThreads) {
  std::vector<Scene> scenes;
  for (double sp : {3.0, 9.0, 13.0, 14.0, 18.0}) {
    Scene s = circle_scene();
    s.cam.speed_rev_s = sp;
    s.run.t_end = 0.2;
    s.run.output_dt = 0;
    scenes.push_back(s);
  }
  scenes[2].follower.mass = -1;  // invalid: reported, not thrown
  const auto a = run_batch(scenes, 1), b = run_batch(scenes, 2);
  ASSERT_EQ(a.size(), scenes.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].finished, b[i].finished);
    EXPECT_EQ(a[i].steps, b[i].steps);
    EXPECT_EQ(a[i].separations, b[i].separations);
    EXPECT_EQ(a[i].max_contact_force, b[i].max_contact_force);
    EXPECT_EQ(a[i].poincare.size(), b[i].poincare.size());
  }
  EXPECT_FALSE(a[2].finished);
  EXPECT_NE(a[2].message.find("follower.mass"), std::string::npos) << a[2].message;
}

TEST(SweepAxes, ValuesAndIntegerKeys) {
  const Scene s = circle_scene();
  const SweepAxis a = make_sweep_axis(s, "cam.speed_rev_s", 1, 2, NAN, 5, false);
  EXPECT_EQ(a.values, (std::vector<double>{1, 1.25, 1.5, 1.75, 2}));
  const SweepAxis b = make_sweep_axis(s, "cam.speed_rev_s", 1, 100, NAN, 3, true);
  ASSERT_EQ(b.values.size(), 3u);
  EXPECT_EQ(b.values[0], 1);
  EXPECT_NEAR(b.values[1], 10, 1e-13);
  EXPECT_EQ(b.values[2], 100);
  const SweepAxis c = make_sweep_axis(s, "cam.speed_rev_s", 0, 1, 0.3, 0, false);
  EXPECT_EQ(c.values.size(), 4u);  // 0, 0.3, 0.6, 0.9
  // An integer key takes whole numbers only (issue 35: 3.33 and 6.67 were rounded silently).
  EXPECT_THROW(make_sweep_axis(s, "run.settle_revolutions", 0, 10, NAN, 4, false), SceneError);
  const SweepAxis d = make_sweep_axis(s, "run.settle_revolutions", 0, 9, NAN, 4, false);
  EXPECT_EQ(d.values, (std::vector<double>{0, 3, 6, 9}));
}

TEST_F(SweepTest, TimeoutStopsAPointAndTheSweepGoesOn) {
  // Case B2 (elastic, chaotic) for 1 s takes ≈ 15 s of CPU: with --timeout 0.3 each point is
  // stopped after about 0.3 CPU seconds and recorded with the reason.
  const R r = camdyn("sweep --case B2 --key cam.speed_rev_s --from 4.9 --to 5 --points 2 --timeout 0.3 "
                     "--jobs 2 --quiet --out T");
  ASSERT_EQ(r.status, 0) << r.err;
  const Csv c = read_csv(dir_ / "T" / "sweep.csv");
  ASSERT_EQ(c.rows.size(), 2u);
  const std::string text = slurp(dir_ / "T" / "sweep.csv");
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(c.num(i, "finished"), 0);
    EXPECT_LT(c.num(i, "t_end"), 1.0);
    EXPECT_LT(c.num(i, "cpu_seconds"), 3.0);
  }
  EXPECT_NE(text.find("timeout: the point took more than 0.3 CPU seconds"), std::string::npos) << text;
}

TEST_F(SweepTest, PlotDrawsTheThreeFigures) {
  if (std::system("/usr/bin/python3 -c 'import numpy, matplotlib' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-matplotlib not installed";
  const R r = camdyn("sweep '" + example("circle_cam.toml") +
                     "' --key cam.speed_rev_s --from 12 --to 15 --points 4 --set run.t_end=0.3 "
                     "--set run.output_dt=0.001 --quiet --plot --out P");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"sweep_force.png", "sweep_bifurcation.png", "sweep_impacts.png"})
    EXPECT_GT(fs::file_size(dir_ / "P" / f), 10000u) << f;
}

// camdyn sweep on a network: one row per speed, the float seen only above the jump speed
// (OHC: 67.8 rev/s), the same numbers as a single run.
TEST(NetworkSweep, SpeedSweepOfTheOhcTrain) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  s.run.t_end = 0.02;
  SweepOptions o;
  o.axes = {SweepAxis{"cam.speed_rev_s", {25.0, 75.0}}};
  o.jobs = 2;
  o.timing = false;
  o.out_dir = (std::filesystem::temp_directory_path() / "camdyn_network_sweep").string();
  std::filesystem::remove_all(o.out_dir);
  const SweepResult r = run_sweep(s, o);
  EXPECT_EQ(r.computed, 2);
  EXPECT_EQ(r.failed, 0);
  std::ifstream f(r.csv_path);
  std::string header, row25, row75;
  std::getline(f, header);
  std::getline(f, row25);
  std::getline(f, row75);
  auto field = [&](const std::string& row, const std::string& name) {
    std::stringstream h(header), v(row);
    std::string hn, vv;
    while (std::getline(h, hn, ',') && std::getline(v, vv, ','))
      if (hn == name) return vv;
    return std::string("?");
  };
  EXPECT_EQ(field(row25, "finished"), "1");
  EXPECT_EQ(field(row75, "finished"), "1");
  EXPECT_EQ(field(row25, "first_separation_theta_deg"), "nan");  // no float at 25 rev/s
  EXPECT_NE(field(row75, "first_separation_theta_deg"), "nan");  // floats at 75 rev/s
  Scene s75 = s;
  s75.cam.speed_rev_s = 75.0;
  EXPECT_EQ(field(row75, "separations"), std::to_string(simulate(s75).summary.separations));
}
