// A user follower in jump_speed, batches and sweeps (issue 28): they use it, never the
// scene's follower silently. Checked against a second formulation — the same follower as a
// network scene — and the closed form of a rigid valve on an eccentric circle cam:
//   held on the cam, F = m Ẍ_C + P + k X_C ≥ 0 with X_C = e(1 + cos θ) − the lift above the
//   base circle — and Ẍ_C = −e cos θ ω²; F first reaches 0 at the nose (θ = 0), at
//   ω_f² = (2 k e + P) / (m e).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>

#include <algorithm>
#include <atomic>

#include "camdyn/designer.hpp"
#include "camdyn/follower_system.hpp"
#include "camdyn/scene.hpp"
#include "../test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace camdyn;

constexpr double kE = 0.004;  // eccentricity [m]

// The scene: a network valve (m, k, P) on the circle cam R = 0.02, e = 0.004 m, from its
// base circle, one revolution at 100 rev/s.
Scene valve_scene(double m, double k, double P) {
  const std::string t = "title = \"valve\"\n[cam]\nprofile = \"circle\"\nradius = 0.02\neccentricity = 0.004\n"
                        "theta0_deg = 180\nspeed_rev_s = 100\n[follower]\nkind = \"network\"\n"
                        "[contact]\nmodel = \"lee\"\ntol_u = 1e-10\n[solver]\nrtol = 1e-9\natol = 1e-13\n"
                        "[run]\nt_end = 0.014\noutput_dt = 0\n"
                        "[[nodes]]\nname = \"valve\"\nmass = " + std::to_string(m) +
                        "\n[[elements]]\nname = \"spring\"\ntype = \"spring\"\nnodes = [\"valve\", \"ground\"]\n"
                        "stiffness = " + std::to_string(k) + "\npreload = " + std::to_string(P) +
                        "\n[[contacts]]\nname = \"cam\"\ntype = \"cam\"\nnodes = [\"valve\"]\n";
  return parse_scene(t, "valve.toml");
}

double closed_form_rev_s(double m, double k, double P) {
  return std::sqrt((2 * k * kE + P) / (m * kE)) / (2 * M_PI);
}

// The same valve as a user follower: M = m, r = −(P + k q), one cam contact row [1].
struct LinearValve : FollowerSystem {
  double m, k, P;
  LinearValve(double m_, double k_, double P_) : m(m_), k(k_), P(P_) {}
  int size() const override { return 1; }
  std::vector<FollowerContact> contacts() const override {
    FollowerContact c;
    c.name = "cam";
    c.row = {1.0};
    return {c};
  }
  void force(double, const double* q, const double*, double* r) const override { r[0] = -(P + k * q[0]); }
  void solve_mass(const double* b, double* x) const override { x[0] = b[0] / m; }
  bool linear() const override { return true; }
  std::string name() const override { return "linear valve"; }
};

// The scene's valve (0.05 kg, 30 kN/m, 250 N) and the user's (0.1 kg, 20 kN/m, 150 N).
const double kMs = 0.05, kKs = 3e4, kPs = 250.0;
const double kMu = 0.1, kKu = 2e4, kPu = 150.0;

TEST(FollowerEverywhere, JumpSpeedUsesTheUserFollower) {
  const Scene scene = valve_scene(kMs, kKs, kPs);
  const Scene as_network = valve_scene(kMu, kKu, kPu);  // the user's follower, as a network
  JumpOptions o;
  o.rel_tol = 1e-4;
  const JumpResult user = jump_speed(scene, std::make_shared<LinearValve>(kMu, kKu, kPu), o);
  const JumpResult net = jump_speed(as_network, o);
  const double width = user.hi_rev_s - user.lo_rev_s;
  EXPECT_EQ(user.method, "simulation");
  EXPECT_LE(width, 1e-4 * user.hi_rev_s);
  EXPECT_NEAR(user.jump_speed_rev_s, net.jump_speed_rev_s, width);
  const double truth = closed_form_rev_s(kMu, kKu, kPu);  // 140.1 rev/s
  EXPECT_NEAR(user.jump_speed_rev_s, truth, 2e-4 * truth);
  EXPECT_LT(std::min(user.theta_deg, 360.0 - user.theta_deg), 1.0) << user.theta_deg;  // at the nose
  // ... and not the scene's own follower (249 rev/s; the bracket must be given: above 150)
  o.lo_rev_s = 150;
  o.hi_rev_s = 300;
  const JumpResult own = jump_speed(scene, o);
  EXPECT_NEAR(own.jump_speed_rev_s, closed_form_rev_s(kMs, kKs, kPs), 2e-4 * own.jump_speed_rev_s);
  EXPECT_GT(std::abs(own.jump_speed_rev_s - user.jump_speed_rev_s), 100.0);
}

TEST(FollowerEverywhere, NullFollowersAreRefused) {
  const Scene scene = valve_scene(kMs, kKs, kPs);
  try {
    jump_speed(scene, std::shared_ptr<const FollowerSystem>(), JumpOptions{});
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "jump_speed: key 'follower' = null: no follower given (for the scene's own follower call "
              "jump_speed(scene, options))");
  }
  try {
    run_batch({scene}, FollowerFactory{}, 1);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "run_batch: key 'follower' = {}: the follower factory is empty (for the scenes' own followers call "
              "run_batch without one)");
  }
  const auto sums = run_batch({scene}, [] { return std::shared_ptr<const FollowerSystem>(); }, 1);
  ASSERT_EQ(sums.size(), 1u);
  EXPECT_EQ(sums[0].termination, Termination::InvalidScene);
  EXPECT_EQ(sums[0].message, "run_batch: key 'follower' = null: the follower factory returned no follower");
}

// Batches at 60 and 100 rev/s (below the user valve's 140 rev/s): the user valve stays on the
// cam, its largest force is the network valve's (a second formulation) and the closed form
// max_θ F = P + k e + |k e − m e ω²| (F = P + k e + cos θ (k e − m e ω²)), and every run used
// a follower of its own from the factory.
TEST(FollowerEverywhere, BatchesUseTheUserFollower) {
  std::vector<Scene> scenes, nets;
  const std::vector<double> speeds{60.0, 100.0};
  for (double sp : speeds) {
    Scene s = valve_scene(kMs, kKs, kPs);
    s.cam.speed_rev_s = sp;
    scenes.push_back(s);
    Scene n = valve_scene(kMu, kKu, kPu);
    n.cam.speed_rev_s = sp;
    nets.push_back(n);
  }
  std::atomic<int> made{0};
  const FollowerFactory factory = [&] {
    ++made;
    return std::make_shared<LinearValve>(kMu, kKu, kPu);
  };
  const auto user = simulate_batch(scenes, factory, 2);
  EXPECT_EQ(made.load(), 2);
  const auto net = run_batch(nets, 2);
  const auto own = run_batch(scenes, 2);
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    ASSERT_TRUE(user[i].summary.finished) << user[i].summary.message;
    EXPECT_EQ(user[i].summary.separations, 0);
    EXPECT_NEAR(user[i].summary.max_contact_force, net[i].max_contact_force, 1e-6 * net[i].max_contact_force);
    const double w = 2 * M_PI * speeds[i];
    const double truth = kPu + kKu * kE + std::abs(kKu * kE - kMu * kE * w * w);
    EXPECT_NEAR(user[i].summary.max_contact_force, truth, 1e-4 * truth);
    EXPECT_GT(std::abs(user[i].summary.max_contact_force - own[i].max_contact_force), 10.0);
    // one by one gives the same (deterministic runs)
    const Summary one = Simulator(scenes[i], std::make_shared<LinearValve>(kMu, kKu, kPu)).run();
    EXPECT_EQ(one.max_contact_force, user[i].summary.max_contact_force);
    EXPECT_EQ(one.steps, user[i].summary.steps);
  }
}

TEST(FollowerEverywhere, SweepsUseTheUserFollowerAndRefuseItsKeys) {
  const Scene scene = valve_scene(kMs, kKs, kPs);
  const Scene as_network = valve_scene(kMu, kKu, kPu);
  const fs::path dir = fs::temp_directory_path() / ("camdyn_follower_sweep_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  SweepOptions o;
  o.axes = {make_sweep_axis(scene, "cam.speed_rev_s", 100, 160, 60, 0, false)};  // 100, 160
  o.jobs = 2;
  o.timing = false;
  o.out_dir = (dir / "user").string();
  o.follower = [] { return std::make_shared<LinearValve>(kMu, kKu, kPu); };
  run_sweep(scene, o);
  SweepOptions on = o;
  on.follower = nullptr;
  on.out_dir = (dir / "net").string();
  run_sweep(as_network, on);
  // the rows of the user follower are those of the network formulation (separations and
  // first separation angle; the forces to 1e-6), and the user valve floats at 160 rev/s
  const auto rows_user = camdyn_test::split(camdyn_test::slurp(dir / "user" / "sweep.csv"), '\n');
  const auto rows_net = camdyn_test::split(camdyn_test::slurp(dir / "net" / "sweep.csv"), '\n');
  ASSERT_EQ(rows_user.size(), 4u);  // header, two rows, ""
  ASSERT_EQ(rows_net.size(), 4u);
  for (int i = 1; i <= 2; ++i) {
    const auto u = camdyn_test::split(rows_user[i], ','), n = camdyn_test::split(rows_net[i], ',');
    ASSERT_GT(u.size(), 8u);
    EXPECT_EQ(u[1], "1") << rows_user[i];                        // finished
    EXPECT_EQ(u[2] == "0", i == 1) << rows_user[i];              // separations: none at 100, some at 160
    EXPECT_EQ(u[2], n[2]);
    EXPECT_NEAR(std::stod(u[4]), std::stod(n[4]), 1e-6 * std::stod(n[4]));  // max_contact_force
  }
  SweepOptions bad = o;
  bad.axes = {make_sweep_axis(as_network, "elements.spring.preload", 100, 200, 100, 0, false)};
  try {
    plan_sweep(scene, bad);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--key: key 'key' = elements.spring.preload: is replaced by the user follower (follower.*, [spring] "
              "and the network tables are not used): sweeping it would change nothing");
  }
  fs::remove_all(dir);
}

}  // namespace
