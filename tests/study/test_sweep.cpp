// Issue 15: designer results, required force and jump speed, sweeps (threads, journal,
// resume), checked against closed forms (never against numbers copied from the program).
//
// Truths used here:
//  * Eccentric circle cam (centre (e, 0), radius R), θ₀ = 0: X_C = R + e cos θ,
//    h″ = −e cos θ, so with the spring convention of docs/method.md §1 (spring force on the
//    follower −(kδ₀ + k(u − X_C(θ₀)))) a rigid follower needs
//      F_req(θ, ω) = −m e ω² cos θ + kδ₀ + k e (cos θ − 1),
//    smallest at θ = 0 when δ₀ > e, and the jump speed is √(kδ₀/(m e))/(2π) rev/s.
//  * Same cam started at θ₀ = 180° (x₀ = R − e): F_req = −m e ω² cos θ + kδ₀ + k e(cos θ + 1)
//    turns zero first (θ > 180°) at cos θ* = (kδ₀ + k e)/(m e ω² − k e), θ* = 360° − acos(·).
//  * While the follower rides the cam its contact face is at X_C(θ) with velocity
//    −e ω sin θ: the Poincaré samples at the section angle are known exactly.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/output.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "results/designer_stats.hpp"
#include "study/speed_map.hpp"
#include "../test_support.hpp"

namespace fs = std::filesystem;
using namespace camdyn;
using camdyn_test::slurp;
using camdyn_test::split;

namespace {

const std::string kCli = CAMDYN_CLI_PATH;
const std::string kSource = CAMDYN_SOURCE_DIR;
constexpr double kPi = 3.14159265358979323846;

std::string example(const std::string& name) { return (fs::path(kSource) / "examples" / name).string(); }

Scene circle_scene(double k = 500, double d0 = 7, double m = 1, double e = 0.5, double R = 2) {
  Scene s = load_scene_file(example("circle_cam.toml"));
  s.spring.stiffness = k;
  s.spring.precompression = d0;
  s.follower.mass = m;
  s.cam.eccentricity = e;
  s.cam.radius = R;
  return s;
}

double analytic_jump(double k, double d0, double m, double e) { return std::sqrt(k * d0 / (m * e)) / (2 * kPi); }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) nl = text.size();
    if (nl > pos) out.push_back(text.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return out;
}

// Columns of a sweep.csv as name → values (the message column is left as text).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t col(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  double num(std::size_t r, const std::string& name) const { return std::strtod(rows[r][col(name)].c_str(), nullptr); }
};
Csv read_csv(const fs::path& p) {
  Csv c;
  const auto lines = lines_of(slurp(p));
  if (lines.empty()) return c;
  c.header = split(lines[0], ',');
  for (std::size_t i = 1; i < lines.size(); ++i) c.rows.push_back(split(lines[i], ','));
  return c;
}

class SweepTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("camdyn_sweep_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  struct R {
    int status = -1;
    std::string out, err;
  };
  R camdyn(const std::string& args) {
    const fs::path o = dir_ / "stdout.txt", e = dir_ / "stderr.txt";
    const std::string cmd = "cd '" + dir_.string() + "' && '" + kCli + "' " + args + " >'" + o.string() + "' 2>'" +
                            e.string() + "' </dev/null";
    const int raw = std::system(cmd.c_str());
    R r;
    r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(o);
    r.err = slurp(e);
    return r;
  }
  fs::path dir_;
};

}  // namespace

// ---- required force and jump speed (closed form) ----------------------------------------

TEST(JumpSpeed, CircleCamClosedFormMatchesAnalytic) {
  struct Case { double k, d0, m, e; };
  for (const Case c : {Case{500, 7, 1, 0.5}, Case{1200, 3, 0.25, 0.8}, Case{50, 2.5, 4, 0.01}, Case{1e5, 0.4, 0.03, 0.15}}) {
    const Scene s = circle_scene(c.k, c.d0, c.m, c.e);
    const JumpResult r = jump_speed(s);
    const double truth = analytic_jump(c.k, c.d0, c.m, c.e);
    EXPECT_EQ(r.method, "closed-form");
    EXPECT_NEAR(r.jump_speed_rev_s / truth - 1.0, 0.0, 1e-10) << "k " << c.k << " e " << c.e;
    EXPECT_NEAR(std::min(r.theta_deg, 360 - r.theta_deg), 0.0, 1e-4);
  }
}

TEST(JumpSpeed, RequiredForceIsTheCircleFormula) {
  const double k = 500, d0 = 7, m = 1.5, e = 0.5;
  Scene s = circle_scene(k, d0, m, e);
  s.follower.damping = 3.0;  // c Ẋ_C = c (−e ω sin θ)
  for (double th : {0.0, 0.7, 2.0, 3.5, 5.9})
    for (double w : {0.0, 10.0, 60.0}) {
      const double truth = -m * e * w * w * std::cos(th) + 3.0 * (-e * w * std::sin(th)) + k * d0 + k * e * (std::cos(th) - 1) +
                           m * (-e * std::sin(th)) * 4.0;
      EXPECT_NEAR(required_contact_force(s, th, w, 4.0), truth, 1e-9 * (k * d0 + m * e * w * w)) << th << " " << w;
    }
}

TEST(JumpSpeed, DampedAndReversedSpeedAndErrors) {
  // Damping c: at θ (small) F_req = −m e ω² cos θ − c e ω sin θ + …: the closed form takes
  // it into account, so the damped jump speed differs from the undamped one; for a negative
  // cam speed the sign follows the speed and the damping term flips (θ → −θ symmetry).
  Scene s = circle_scene();
  s.follower.damping = 20.0;
  const JumpResult a = jump_speed(s);
  s.cam.speed_rev_s = -1.0;
  const JumpResult b = jump_speed(s);
  EXPECT_NEAR(a.jump_speed_rev_s, -b.jump_speed_rev_s, 1e-9 * a.jump_speed_rev_s);
  EXPECT_NEAR(a.theta_deg, 360.0 - b.theta_deg, 1e-4);
  EXPECT_LT(a.jump_speed_rev_s, analytic_jump(500, 7, 1, 0.5));  // the damper pulls on the rise side
  // At the jump speed the minimum over θ of the required force is zero.
  Scene sp = circle_scene();
  sp.follower.damping = 20.0;
  double fmin = 1e300;
  for (int i = 0; i < 36000; ++i) fmin = std::min(fmin, required_contact_force(sp, 2 * kPi * i / 36000, 2 * kPi * a.jump_speed_rev_s, 0));
  EXPECT_NEAR(fmin, 0.0, 1e-6 * 3500);
  Scene t = circle_scene();
  t.cam.speed_table_t = {0, 1};
  t.cam.speed_table_rev_s = {1, 2};
  EXPECT_THROW(jump_speed(t), SceneError);
  JumpOptions bad;
  bad.rel_tol = 0;
  EXPECT_THROW(jump_speed(circle_scene(), bad), SceneError);
}

TEST_F(SweepTest, JumpCliPrintsTheAnalyticSpeed) {
  const R r = camdyn("jump '" + example("circle_cam.toml") + "' --set spring.stiffness=800 --out J");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_FALSE(lines.empty());
  const std::string last = lines.back();
  ASSERT_EQ(last.rfind("jump_speed_rev_s = ", 0), 0u) << last;
  const double v = std::strtod(last.c_str() + 19, nullptr);
  EXPECT_NEAR(v / analytic_jump(800, 7, 1, 0.5) - 1.0, 0.0, 1e-10) << last;
  const std::string j = slurp(dir_ / "J" / "jump.json");
  EXPECT_NE(j.find("\"method\": \"closed-form\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"theta_deg\": 0"), std::string::npos) << j;
  EXPECT_NE(j.find("\"jump_speed_rev_s\": " + format_double(v)), std::string::npos) << j;
  // no scene → exit 2
  EXPECT_EQ(camdyn("jump --out J").status, 2);
}

TEST(JumpSpeed, SimulationBisectionBracketsTheClosedForm) {
  // The simulated route on a rigid follower (forced): the bisection bracket must contain
  // the analytic jump speed (Lee, one revolution at the top speed is enough: the margin
  // is smallest at θ₀ = 0).
  Scene s = circle_scene();
  s.run.t_end = 0.08;
  s.run.output_dt = 1e-4;  // Lee's steps ≤ 1e-4 s (with 1e-3 s steps Lee reports a spurious
                           // separation at 0.9999 J near θ = 359.5°, where the margin is 0.7)
  JumpOptions o;
  o.force_simulation = true;
  o.rel_tol = 1e-4;
  const JumpResult r = jump_speed(s, o);
  const double truth = analytic_jump(500, 7, 1, 0.5);
  EXPECT_EQ(r.method, "simulation");
  EXPECT_LE(r.lo_rev_s, truth * (1 + 1e-12));
  EXPECT_GE(r.hi_rev_s, truth * (1 - 1e-12));
  EXPECT_LE(r.hi_rev_s - r.lo_rev_s, 1e-4 * r.hi_rev_s);
}

// ---- simulated sweep brackets the jump speed ------------------------------------------

TEST_F(SweepTest, SimulatedSweepBracketsJumpSpeedWithin1e4) {
  const double J = analytic_jump(500, 7, 1, 0.5);
  Scene s = circle_scene();
  s.run.t_end = 0.08;  // > one revolution at J (0.075 s)
  s.run.output_dt = 1e-4;  // Lee's steps ≤ 1e-4 s (see SimulationBisectionBracketsTheClosedForm)
  SweepOptions o;
  o.axes = {SweepAxis{"cam.speed_rev_s", {J * (1 - 1e-2), J * (1 - 1e-4), J * (1 + 1e-4), J * (1 + 1e-2)}}};
  o.jobs = 2;
  o.out_dir = (dir_ / "S").string();
  const SweepResult res = run_sweep(s, o);
  EXPECT_EQ(res.computed, 4);
  const Csv c = read_csv(dir_ / "S" / "sweep.csv");
  ASSERT_EQ(c.rows.size(), 4u);
  EXPECT_EQ(c.header[0], "cam.speed_rev_s");
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c.num(i, "finished"), 1);
    if (i < 2) {
      EXPECT_EQ(c.num(i, "separations"), 0) << "below the jump speed, row " << i;
      // margin: F_req(0) = kδ₀ − m e ω², at θ = 0
      const double w = 2 * kPi * c.num(i, "cam.speed_rev_s");
      EXPECT_NEAR(c.num(i, "min_contact_force"), 3500 - 0.5 * w * w, 1e-6 * 3500);
    } else {
      EXPECT_GT(c.num(i, "separations"), 0) << "above the jump speed, row " << i;
      EXPECT_EQ(c.num(i, "min_contact_force"), 0);
    }
  }
}

// ---- designer results against closed forms --------------------------------------------

TEST(Designer, SeparationAngleFromTheCircleFormula) {
  // θ₀ = 180°, ω chosen so that cos θ* = 1/2: the first separation is at θ* = 300°.
  const double k = 500, d0 = 7, m = 1, e = 0.5;
  const double w = std::sqrt((k * d0 + k * e) / (m * e * 0.5) + k / m);
  Scene s = circle_scene(k, d0, m, e);
  s.contact.model = ContactModel::Event;
  s.cam.theta0_deg = 180;
  s.cam.speed_rev_s = w / (2 * kPi);
  s.run.t_end = 0.06;  // < one revolution (0.0506 s to 300°)
  s.run.output_dt = 1e-3;
  const Summary r = Simulator(s).run();
  ASSERT_TRUE(r.finished) << r.message;
  ASSERT_GE(r.separations, 1);
  EXPECT_NEAR(r.first_separation_theta_deg, 300.0, 1e-6);
  EXPECT_EQ(r.min_contact_force, 0.0);
  EXPECT_NEAR(r.min_force_theta_deg, 300.0, 1e-6);
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(std::string(to_string(r.events.front().type)), "separation");
  EXPECT_NEAR(std::fmod(r.events.front().theta * 180 / kPi, 360.0), 300.0, 1e-6);
  // An impact follows in free flight: its angle and velocity are reported with the event.
  if (r.impacts > 0) {
    EXPECT_GT(r.max_impact_velocity, 0);
    EXPECT_FALSE(std::isnan(r.first_impact_theta_deg));
    EXPECT_GT(r.max_gap, 0);
  }
}

TEST(Designer, PoincareSamplesOnTheCamAreExact) {
  // Below the jump speed the follower rides the cam: at section angle θ_s the contact
  // face is at R + e cos θ_s with velocity −e ω sin θ_s.
  for (const ContactModel model : {ContactModel::Lee, ContactModel::Event}) {
    Scene s = circle_scene();
    s.contact.model = model;
    s.cam.speed_rev_s = 5.0;
    s.run.t_end = 1.0;
    s.run.output_dt = 1e-3;
    s.run.poincare_angle_deg = 90;
    s.run.settle_revolutions = 2;
    const Summary r = Simulator(s).run();
    ASSERT_TRUE(r.finished) << r.message;
    ASSERT_EQ(r.poincare.size(), 3u);  // revolutions 2, 3, 4 (θ = 90° at t = 0.05 + 0.2 k)
    const double w = 2 * kPi * 5.0;
    for (std::size_t i = 0; i < r.poincare.size(); ++i) {
      EXPECT_EQ(r.poincare[i].revolution, long(i) + 2);
      EXPECT_NEAR(r.poincare[i].t, 0.05 + 0.2 * double(i + 2), 1e-12);
      EXPECT_NEAR(r.poincare[i].u_c, 2.0, 1e-7);
      EXPECT_NEAR(r.poincare[i].v_c, -0.5 * w, 1e-5 * 0.5 * w);
    }
    EXPECT_EQ(r.period, 1);
    EXPECT_EQ(r.period_kind, "period-1");
    EXPECT_EQ(r.separations, 0);
    // margin: min_θ (kδ₀ + k e (cos θ − 1) − m e ω² cos θ) = at θ = 0 (k < m ω²)
    EXPECT_NEAR(r.min_contact_force, 3500 - 0.5 * w * w, 1e-6 * 3500);
    EXPECT_NEAR(std::min(r.min_force_theta_deg, 360 - r.min_force_theta_deg), 0.0, 1e-9);
  }
}

TEST(Designer, PeriodDetectorOnSyntheticSequences) {
  auto seq = [](std::vector<double> u) {
    std::vector<PoincareSample> s;
    for (std::size_t i = 0; i < u.size(); ++i) s.push_back({long(i), double(i), u[i], 0.0});
    return s;
  };
  std::string kind;
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 1, 1, 1}), 1, 1, 1e-3, &kind), 1);
  EXPECT_EQ(kind, "period-1");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 2, 1, 2, 1, 2}), 1, 1, 1e-3, &kind), 2);
  EXPECT_EQ(kind, "period-2");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 2, 3, 1, 2, 3, 1}), 1, 1, 1e-3, &kind), 3);
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 2, 1, 2}), 1, 1, 1e-3, &kind), 0);  // needs 2p + 1
  EXPECT_EQ(kind, "not periodic");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({0.1, 0.7, 0.3, 0.9, 0.2, 0.55, 0.8}), 1, 1, 1e-3, &kind), 0);
  EXPECT_EQ(kind, "not periodic");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 1}), 1, 1, 1e-3, &kind), 0);
  EXPECT_EQ(kind, "too few samples");
}

TEST(Designer, PeriodOneThenIrregularAboveTheJumpSpeed) {
  // Scene: the eccentric circle cam (k = 500, δ₀ = 7, m = 1, e = 0.5, jump 13.32 rev/s),
  // rigid follower, restitution 0.8, exact event-driven method, 30 revolutions settled.
  // At 14 rev/s (5 % above the jump speed) the follower leaves the cam near θ = 0 each
  // revolution, bounces with a chattering sequence that ends on the cam: period-1.
  // At 20 rev/s it never re-sticks: the Poincaré samples do not repeat (not periodic
  // within 1e-3 of the lift over 16 revolutions).
  Scene s = circle_scene();
  s.contact.model = ContactModel::Event;
  s.contact.restitution = 0.8;
  s.run.output_dt = 0;
  s.run.settle_revolutions = 30;
  s.cam.speed_rev_s = 14;
  s.run.t_end = 50.0 / 14;
  const Summary a = Simulator(s).run();
  ASSERT_TRUE(a.finished) << a.message;
  EXPECT_GT(a.separations, 0);
  EXPECT_EQ(a.period, 1) << a.period_kind;
  EXPECT_EQ(a.period_kind, "period-1");
  s.cam.speed_rev_s = 20;
  s.run.t_end = 70.0 / 20;
  const Summary b = Simulator(s).run();
  ASSERT_TRUE(b.finished) << b.message;
  EXPECT_GT(b.impacts, 0);
  EXPECT_GE(b.poincare.size(), 33u);
  EXPECT_NE(b.period, 1) << b.period_kind;
  EXPECT_TRUE(b.period_kind == "not periodic" || b.period >= 2) << b.period_kind;
}

TEST(Designer, LiftCamMarginMatchesClosedForm) {
  // The lift-table cam below its jump speed (9.2 rev/s): the closed-form margin
  // min_θ F_req(θ, ω) vs the simulated minimum contact force (Lee, rigid, one revolution,
  // steps of the integrator's own choosing). Both use the cam's spline h(θ); the simulation
  // gets its force from the dynamics: the held-contact force (Ẍ_C − a_free)/M* sampled
  // inside steps by the work quadrature (exact for a rigid follower) and Lee's acceleration
  // level at step ends. Tolerance 1e-5 of the preload (0.035): measured 5e-5 (3 rev/s),
  // 6e-5 (6 rev/s) and 3.4e-3 (8.5 rev/s; steps of 3.4 ms). The minimum lies on a knot of
  // the lift spline (210°), where h‴ jumps and F_req has a corner, so a sample at δ from
  // the knot misses it by |F′|δ; step-end forces carry the acceleration level's tolerance
  // tol_u/Δt² · m. The cam is symmetric (F_req(90°) = F_req(210°)), so the angle is
  // checked through F_req at the simulated angle, not against one of the two twins.
  const Scene base = load_scene_file(example("lift_cam.toml"));
  for (double speed : {3.0, 6.0, 8.5}) {
    Scene s = base;
    s.cam.speed_rev_s = speed;
    s.run.t_end = 1.0 / speed;  // one revolution
    s.run.output_dt = 0;
    s.solver.rtol = 1e-7;
    // F_req = m h″ω² + kδ₀ + k (h(θ) − h(0)) (docs/method.md §1–2) on a 0.01° grid, from the
    // cam's support function; required_contact_force must agree at the minimum.
    const Cam cam(s.cam);
    const double w = 2 * kPi * speed, h0 = cam.evaluate(0).X_C;
    double closed = 1e300, th_min = 0;
    const int N = 36000;
    for (int i = 0; i < N; ++i) {
      const double th = 2 * kPi * i / N;
      const CamPoint p = cam.evaluate(th);
      const double F = p.d2X_dtheta2 * w * w + 3500 + 500 * (p.X_C - h0);
      if (F < closed) closed = F, th_min = th;
    }
    EXPECT_NEAR(required_contact_force(s, th_min), closed, 1e-9 * 3500);
    const Summary r = Simulator(s).run();
    ASSERT_TRUE(r.finished) << r.message;
    EXPECT_EQ(r.separations, 0);
    EXPECT_NEAR(r.min_contact_force, closed, 1e-5 * 3500) << speed << " rev/s";
    EXPECT_NEAR(required_contact_force(s, r.min_force_theta_deg * kPi / 180), closed, 1e-5 * 3500)
        << speed << " rev/s, at " << r.min_force_theta_deg << " deg";
  }
}

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

TEST(JumpSpeed, ElasticFollowerBySimulationKeepsItsBracket) {
  // Elastic bar (case B1 with 8 elements): no closed form; the map's contract is checked by
  // judging both ends of the reported bracket again (settle + judge revolutions each): the
  // low end keeps contact, the high end departs, and the bracket is within rel_tol.
  Scene s = paper_case("B1");
  s.follower.elements = 8;
  s.jump.settle_revolutions = 0;  // one judged revolution per trial: the test's cost
  s.jump.judge_revolutions = 1;
  JumpOptions o;
  o.rel_tol = 1e-2;
  o.grid_points = 4;
  o.jobs = 2;
  const JumpResult r = jump_speed(s, o);
  EXPECT_EQ(r.method, "simulation");
  EXPECT_GT(r.simulations, 4);
  EXPECT_LE(r.hi_rev_s - r.lo_rev_s, 1e-2 * r.hi_rev_s);
  EXPECT_DOUBLE_EQ(r.jump_speed_rev_s, 0.5 * (r.lo_rev_s + r.hi_rev_s));
  const SpeedTrial lo = detail::run_speed_trial(s, r.lo_rev_s, nullptr);
  double theta = NAN;
  const SpeedTrial hi = detail::run_speed_trial(s, r.hi_rev_s, nullptr, nullptr, &theta);
  ASSERT_TRUE(lo.finished && hi.finished);
  for (const std::string& k : lo.kinds) EXPECT_FALSE(detail::is_departure_kind(k)) << k;
  bool departs = false;
  for (const std::string& k : hi.kinds) departs = departs || detail::is_departure_kind(k);
  EXPECT_TRUE(departs) << hi.text;
  EXPECT_DOUBLE_EQ(r.theta_deg, theta);
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
