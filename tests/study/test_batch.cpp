// Batch runs (camdyn/batch.hpp, issue 12): run_batch and simulate_batch on 2 threads give
// results bitwise identical to serial simulate(); one Cam shared by threads gives the
// same values as alone.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "camdyn/batch.hpp"
#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

std::string example(const char* name) { return std::string(CAMDYN_SOURCE_DIR) + "/examples/" + name; }

// Paper case A (points cam, Lee), B1 (elastic bar) shortened, a circle cam (event-driven),
// a lift cam and case A with the penalty method.
std::vector<Scene> mixed_scenes() {
  std::vector<Scene> v;
  Scene a = paper_case("A");
  a.run.t_end = 0.3;
  v.push_back(a);
  Scene b1 = paper_case("B1");
  b1.run.t_end = 0.02;
  v.push_back(b1);
  Scene c = load_scene_file(example("circle_cam.toml"));
  apply_overrides(c, {"run.t_end=0.3", "contact.model=event"});
  v.push_back(c);
  Scene p = paper_case("A");
  apply_overrides(p, {"run.t_end=0.2", "contact.model=penalty"});
  v.push_back(p);
  Scene l = load_scene_file(example("lift_cam.toml"));
  l.run.t_end = 0.2;
  v.push_back(l);
  return v;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_summary(const Summary& a, const Summary& b, const std::string& what) {
  EXPECT_EQ(a.finished, b.finished) << what;
  EXPECT_EQ(a.termination, b.termination) << what;
  EXPECT_EQ(a.message, b.message) << what;
  EXPECT_TRUE(same_bits(a.t_end, b.t_end)) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
  EXPECT_EQ(a.rejected_steps, b.rejected_steps) << what;
  EXPECT_EQ(a.rhs_evals, b.rhs_evals) << what;
  EXPECT_EQ(a.lin_setups, b.lin_setups) << what;
  EXPECT_EQ(a.contact_iterations, b.contact_iterations) << what;
  EXPECT_EQ(a.separations, b.separations) << what;
  EXPECT_EQ(a.impacts, b.impacts) << what;
  EXPECT_EQ(a.events.size(), b.events.size()) << what;
  EXPECT_TRUE(same_bits(a.max_contact_force, b.max_contact_force)) << what;
  EXPECT_TRUE(same_bits(a.min_gap, b.min_gap)) << what;
  EXPECT_TRUE(same_bits(a.energy_residual, b.energy_residual)) << what;
  EXPECT_TRUE(same_bits(a.min_contact_force, b.min_contact_force)) << what;
}

void expect_same_rows(const std::vector<HistoryRow>& a, const std::vector<HistoryRow>& b,
                      const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  // every number bitwise (not the struct's bytes: padding and the extra vector's pointer)
  for (std::size_t i = 0; i < a.size(); ++i) {
    const HistoryRow &x = a[i], &y = b[i];
    const double xs[] = {x.t, x.theta, x.u_c, x.v_c, x.a_c, x.contact_force, x.gap,
                         x.kinetic, x.potential, x.work_cam, x.dissipated};
    const double ys[] = {y.t, y.theta, y.u_c, y.v_c, y.a_c, y.contact_force, y.gap,
                         y.kinetic, y.potential, y.work_cam, y.dissipated};
    ASSERT_EQ(std::memcmp(xs, ys, sizeof xs), 0) << what << ", row " << i;
    ASSERT_EQ(x.in_contact, y.in_contact) << what << ", row " << i;
    ASSERT_EQ(a[i].extra.size(), b[i].extra.size()) << what << ", row " << i;
    if (!a[i].extra.empty())
      ASSERT_EQ(std::memcmp(a[i].extra.data(), b[i].extra.data(), a[i].extra.size() * sizeof(double)), 0)
          << what << ", row " << i;
  }
}

TEST(Batch, TwoThreadsAreBitwiseSerial) {
  const std::vector<Scene> scenes = mixed_scenes();
  std::vector<RunResult> serial;
  for (const Scene& s : scenes) serial.push_back(simulate(s));
  for (const RunResult& r : serial) ASSERT_TRUE(r.summary.finished) << r.summary.message;

  const std::vector<RunResult> batch = simulate_batch(scenes, 2);
  const std::vector<Summary> sums = run_batch(scenes, 2);
  ASSERT_EQ(batch.size(), scenes.size());
  ASSERT_EQ(sums.size(), scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string what = "scene " + std::to_string(i) + " (" + scenes[i].title + ")";
    expect_same_summary(batch[i].summary, serial[i].summary, what);
    expect_same_summary(sums[i], serial[i].summary, what);
    expect_same_rows(batch[i].rows, serial[i].rows, what);
  }
}

TEST(Batch, InvalidSceneIsReportedAndOnDoneSeesEveryRun) {
  std::vector<Scene> scenes = mixed_scenes();
  scenes.resize(2);
  scenes[1].follower.mass = -1;
  std::vector<int> seen(scenes.size(), 0);
  const auto r = simulate_batch(scenes, 2, [&](std::size_t i, const RunResult&) { ++seen[i]; });
  EXPECT_EQ(seen, (std::vector<int>{1, 1}));
  EXPECT_EQ(r[0].summary.termination, Termination::Finished);
  EXPECT_EQ(r[1].summary.termination, Termination::InvalidScene);
  EXPECT_FALSE(r[1].summary.finished);
  EXPECT_NE(r[1].summary.message.find("follower.mass"), std::string::npos) << r[1].summary.message;
  EXPECT_TRUE(r[1].rows.empty());
}

TEST(Batch, StopFlagEndsTheBatch) {
  const std::vector<Scene> scenes = mixed_scenes();
  std::atomic<bool> stop{true};
  const auto r = run_batch(scenes, 2, {}, &stop);
  ASSERT_EQ(r.size(), scenes.size());
  for (const Summary& s : r) EXPECT_FALSE(s.finished);
}

// One Cam evaluated by 4 threads at once (each its own sequence of angles, so the shared
// search hint jumps between them) gives exactly the values of a Cam of its own.
TEST(Batch, SharedCamIsThreadSafe) {
  for (const char* file : {"case_A.toml", "lift_cam.toml"}) {
    const Scene s = load_scene_file(example(file));
    const Cam shared(s.cam);
    const int kThreads = 4, kN = 20000;
    std::vector<std::vector<double>> got(kThreads), want(kThreads);
    auto angle = [](int t, int i) { return 0.37 * t + 1e-3 * i * (t + 1); };
    for (int t = 0; t < kThreads; ++t) {
      const Cam own(s.cam);
      for (int i = 0; i < kN; ++i) want[t].push_back(own.motion(angle(t, i), 10.0, 0.0).X);
    }
    std::vector<std::thread> pool;
    for (int t = 0; t < kThreads; ++t)
      pool.emplace_back([&, t] {
        for (int i = 0; i < kN; ++i) got[t].push_back(shared.motion(angle(t, i), 10.0, 0.0).X);
      });
    for (auto& th : pool) th.join();
    for (int t = 0; t < kThreads; ++t) {
      ASSERT_EQ(got[t].size(), want[t].size());
      for (int i = 0; i < kN; ++i) ASSERT_TRUE(same_bits(got[t][i], want[t][i])) << file << " " << t << " " << i;
    }
  }
}

}  // namespace
}  // namespace camdyn
