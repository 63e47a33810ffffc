// camdyn — the two roller valve-train examples (issue 24): an OHC roller finger follower
// (oscillating roller on a law cam, the finger as the equivalent coordinate X = ℓ_v ψ) and
// an OHV roller lifter train. Both run; at low cam speed (inertia negligible) the valve is
// at rest on its seat over the base circle, and its peak lift is the quasi-static one:
//   OHC: the law's valve-end lift less the lash (rigid finger, fixed pivot);
//   OHV: ratio × (cam lift − pushrod compression under the valve load) − lash.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>
#include <camdyn/scene.hpp>
#include <camdyn/simulator.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;

struct Rows : Observer {
  std::vector<HistoryRow> rows;
  void on_row(const HistoryRow& r) override { rows.push_back(r); }
};
int col_index(const std::vector<std::string>& cols, const std::string& name) {
  for (size_t i = 0; i < cols.size(); ++i)
    if (cols[i] == name) return int(i);
  ADD_FAILURE() << "no column " << name;
  return 0;
}
double deg360(double th) {
  double d = std::fmod(th * 180.0 / kPi, 360.0);
  return d < 0 ? d + 360.0 : d;
}

struct Valve {
  double peak = 0, base_max_abs_u = 0, base_max_abs_v = 0;
  long base_rows = 0;
};
// Valve motion of a run: its peak lift, and |u|, |v| over the base circle (cam angles
// outside the law's lobe, [lo, hi] deg, with a margin for the lash take-up).
Valve run_valve(Scene s, double lo, double hi, Summary* sum_out) {
  Simulator sim(s);
  Rows obs;
  const Summary sum = sim.run(&obs);
  *sum_out = sum;
  const auto cols = sim.extra_columns();
  const int iu = col_index(cols, "u_valve"), iv = col_index(cols, "v_valve");
  Valve v;
  for (const HistoryRow& r : obs.rows) {
    const double u = r.extra[iu], d = deg360(r.theta);
    v.peak = std::max(v.peak, u);
    if (d < lo || d > hi) {
      ++v.base_rows;
      v.base_max_abs_u = std::max(v.base_max_abs_u, std::fabs(u));
      v.base_max_abs_v = std::max(v.base_max_abs_v, std::fabs(r.extra[iv]));
    }
  }
  return v;
}
// One revolution at 1 rev/s: the inertia forces are negligible (quasi-static).
Scene slow(Scene s) {
  s.cam.speed_rev_s = 1.0;
  s.run.t_end = 1.0;
  s.run.output_dt = 2e-4;
  return s;
}
}  // namespace

TEST(OscillatingTrains, OhcRollerFingerExampleRunsAndLiftsTheValveByTheLaw) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_roller_finger.toml");
  {  // the example as shipped: one revolution at 25 rev/s
    Summary sum;
    run_valve(s, 95.0, 265.0, &sum);
    ASSERT_TRUE(sum.finished) << sum.message;
    EXPECT_TRUE(std::isfinite(sum.max_hertz_stress));
  }
  // Low speed: one revolution at 1 rev/s.
  Summary sum;
  const Valve v = run_valve(slow(s), 95.0, 265.0, &sum);
  ASSERT_TRUE(sum.finished) << sum.message;
  const double lash = 0.1e-3, lift = 0.009;  // the law's valve-end lift
  EXPECT_NEAR(v.peak, lift - lash, 2e-6);
  EXPECT_GT(v.base_rows, 100);
  EXPECT_LT(v.base_max_abs_u, 1e-9);  // on the seat
  EXPECT_LT(v.base_max_abs_v, 1e-9);
  // Quasi-static cam force on X (the valve end) at the peak: the valve spring and the
  // finger's lash-adjuster spring, F = (230 + 35000 y) + (8 + 2000·lift); the normal force
  // at the roller is F·ℓ_v/a (a: the moment arm there).
  EXPECT_NEAR(sum.max_contact_force, 230.0 + 35000.0 * (lift - lash) + 8.0 + 2000.0 * lift, 1e-3);
  // The roller's lift at the cam: the arm ratio maps it. Roller-centre displacement along
  // its arc ℓ ψ = (ℓ/ℓ_v) X: peak ψ = lift/ℓ_v.
  const Cam cam(s.cam);
  double psimax = 0;
  for (int i = 0; i < 3600; ++i) psimax = std::max(psimax, cam.evaluate(2 * kPi * i / 3600).psi);
  EXPECT_NEAR(psimax * s.cam.valve_arm, lift, 1e-9);
}

TEST(OscillatingTrains, OhvRollerLifterExampleRunsAndLiftsTheValveByTheRockerRatio) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohv_roller_lifter.toml");
  {
    Summary sum;
    run_valve(s, 95.0, 265.0, &sum);
    ASSERT_TRUE(sum.finished) << sum.message;
  }
  Summary sum;
  const Valve v = run_valve(slow(s), 95.0, 265.0, &sum);
  ASSERT_TRUE(sum.finished) << sum.message;
  // Quasi-static: valve lift y = r (L − F_p/k_p) − c with the pushrod force F_p = r·F_v
  // (lever), F_v = preload + k_v y (valve spring), k_p = EA/ℓ (pushrod).
  const double r = 1.5, L = 0.006, c = 0.25e-3, kp = 2.1e11 * 1.81e-5 / 0.25, Fv0 = 330.0, kv = 50000.0;
  const double y = (r * L - r * r * Fv0 / kp - c) / (1.0 + r * r * kv / kp);
  EXPECT_NEAR(v.peak, y, 2e-6) << "rigid-pushrod value " << r * L - c;
  EXPECT_LT(v.base_max_abs_u, 1e-9);
  EXPECT_LT(v.base_max_abs_v, 1e-9);
}

TEST(OscillatingTrains, SceneKeysValidateWithFileKeyValueAndRule) {
  const std::string base = std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_roller_finger.toml";
  Scene s = load_scene_file(base);
  EXPECT_EQ(s.cam.follower_motion, FollowerMotion::Oscillating);
  EXPECT_EQ(s.cam.valve_arm, 0.048);
  s.cam.arm_length = 0.001;  // the roller cannot reach the cam
  try {
    validate(s);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.arm_length");
    EXPECT_EQ(e.value(), "0.001");
    EXPECT_NE(std::string(e.what()).find("ohc_roller_finger.toml"), std::string::npos) << e.what();
    EXPECT_NE(e.rule().find("the roller cannot reach the cam"), std::string::npos) << e.rule();
  }
  try {
    parse_scene("[cam]\nfollower_motion = \"rotating\"\n", "<t>");
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.follower_motion");
    EXPECT_NE(e.rule().find("oscillating"), std::string::npos) << e.rule();
  }
}
