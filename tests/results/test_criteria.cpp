// Acceptance criteria, seat landings, the oil film in a run and the valve's lift deviation
// (src/results/run_analysis.cpp, criteria.cpp, kinematic_path.cpp) against closed forms and
// recomputations written here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "camdyn/designer.hpp"
#include "camdyn/scene_warnings.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "results/kinematic_path.hpp"
#include "results/run_analysis.hpp"
#include "camdyn/cam.hpp"

using namespace camdyn;
namespace fs = std::filesystem;

namespace {

Scene parse(const std::string& text) { return parse_scene(text, "<test>"); }

constexpr double kPi = 3.14159265358979323846;

// A valve on its seat, lifted through a 0.2 mm lash by a law cam (cycloidal opening, 3-4-5
// closing over 80° each, 8 mm): the valve lands on the seat where the cam's closing flank
// passes the lash, at the cam's velocity there, and bounces (restitution 0.6 at the seat)
// against its spring's preload.
std::string bouncing_valve(double speed_rev_s, const std::string& criteria = "") {
  return R"(title = "bouncing valve"
[cam]
profile = "law"
law = "dwell 100; cycloidal 80 0.008; poly345 80 -0.008; dwell 100"
base_radius = 0.02
follower_face = "point"
speed_rev_s = )" +
         std::to_string(speed_rev_s) + R"(
[follower]
kind = "network"
[contact]
model = "lee"
tol_u = 1e-10
restitution = 0.0
[solver]
integrator = "arkode-erk"
rtol = 1e-9
atol = 1e-13
[run]
t_end = 0.075
output_dt = 1e-6
[[nodes]]
name = "valve"
mass = 0.05
[[elements]]
name = "valve_spring"
type = "spring"
nodes = ["valve", "ground"]
stiffness = 30000.0
preload = 200.0
[[contacts]]
name = "cam"
type = "cam"
nodes = ["valve"]
clearance = 0.0002
[[contacts]]
name = "seat"
type = "stop"
nodes = ["valve"]
side = "below"
restitution = 0.6
)" + criteria;
}

// The closing flank s = L(1 − (10x³ − 15x⁴ + 6x⁵)), x = (θ − 180°)/80°: the cam's speed
// |ds/dt| where s = c (bisection on x), at ω = 2π·speed.
double closing_speed_at(double c, double speed_rev_s) {
  const double L = 0.008, beta = 80.0 * kPi / 180.0;
  auto s = [&](double x) { return L * (1 - (10 * x * x * x - 15 * x * x * x * x + 6 * x * x * x * x * x)); };
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (s(mid) > c ? lo : hi) = mid;
  }
  const double x = 0.5 * (lo + hi);
  const double dsdx = -L * (30 * x * x - 60 * x * x * x + 30 * x * x * x * x);
  return std::abs(dsdx / beta * 2 * kPi * speed_rev_s);
}

struct Rows : Observer {
  std::vector<HistoryRow> rows;
  void on_row(const HistoryRow& r) override { rows.push_back(r); }
};

int column(const Simulator& sim, const std::string& name) {
  const auto& c = sim.extra_columns();
  const auto it = std::find(c.begin(), c.end(), name);
  return it == c.end() ? -1 : int(it - c.begin());
}

double deg(double theta) {
  double d = std::fmod(theta * 180.0 / kPi, 360.0);
  return d < 0 ? d + 360.0 : d;
}

}  // namespace

TEST(Criteria, SeatingVelocityAndBouncesFromTheEventsAndRows) {
  Simulator sim(parse(bouncing_valve(10.0, R"(
[criteria]
max_seating_velocity = 0.5
max_bounce_height = 1e-6
max_bounce_count = 2
)")));
  Rows obs;
  const Summary s = sim.run(&obs);
  ASSERT_TRUE(s.finished) << s.message;
  // Recompute from the events and the history (events.csv and history.csv hold the same):
  // seat impacts; a bounce when the cam lift stayed below the seat's take-up (the lash
  // 0.2 mm + 1 % of the 8 mm lift) between two impacts; its height the largest seat gap
  // over the rows strictly between them.
  const int gap_seat = column(sim, "gap_seat");
  ASSERT_GE(gap_seat, 0);
  std::vector<ContactEvent> imp;
  for (const ContactEvent& e : s.events)
    if (e.contact == "seat" && e.type == EventKind::Impact) imp.push_back(e);
  ASSERT_GE(imp.size(), 3u) << "the valve should land and bounce";
  const double opened = 0.0002 + 0.01 * 0.008;
  double vmax = 0, hmax = 0;
  long most = 0, count = 0;
  for (std::size_t i = 0; i < imp.size(); ++i) {
    vmax = std::max(vmax, imp[i].impact_velocity);
    if (i == 0) continue;
    double h = 0, X = -1;
    for (const HistoryRow& r : obs.rows)
      if (r.t > imp[i - 1].t && r.t < imp[i].t) {
        h = std::max(h, r.extra[std::size_t(gap_seat)]);
        X = std::max(X, r.u_c - r.gap);  // the cam's lift: u_c − gap of the primary (cam) contact
      }
    const bool bounce = !(X > opened);
    count = bounce ? count + 1 : 0;
    most = std::max(most, count);
    if (bounce) hmax = std::max(hmax, h);
  }
  ASSERT_EQ(s.criteria.size(), 3u);
  EXPECT_EQ(s.criteria[0].name, "seating_velocity");
  EXPECT_DOUBLE_EQ(s.criteria[0].value, vmax);
  EXPECT_EQ(s.criteria[1].name, "bounce_height");
  // the bounce height is the flight's apex located inside its step: at least every row's
  // seat gap (the rows are the same interpolant), the criterion the landings' largest
  EXPECT_GE(s.criteria[1].value * (1 + 1e-12), hmax);
  double lmax = 0;
  for (const SeatLanding& L : s.landings) lmax = std::max(lmax, L.bounce_height);
  EXPECT_DOUBLE_EQ(s.criteria[1].value, lmax);
  EXPECT_EQ(s.criteria[2].name, "bounce_count");
  EXPECT_EQ(s.criteria[2].value, double(most));
  ASSERT_EQ(s.landings.size(), 1u);
  EXPECT_EQ(s.landings[0].bounces, long(imp.size()) - 1);

  // Against closed forms. The landing: the valve rides the cam down and meets the seat where
  // the closing flank passes the lash, at the cam's speed there (0.1691 m/s; measured
  // relative error 1e-13).
  const double v0 = closing_speed_at(0.0002, 10.0);
  EXPECT_NEAR(s.landings[0].velocity, v0, 1e-9 * v0);
  EXPECT_NEAR(s.criteria[0].value, v0, 1e-9 * v0);
  // The first bounce: up at e·v₀ against the preload P and the spring k (no damping):
  // q(t) = (P/k)(cos wt − 1) + (e v₀/w) sin wt, highest −P/k + √((P/k)² + (e v₀/w)²)
  // (1.287 µm); the apex located in the flight's step (the root of the gap rate) matches it
  // to 6.0e-6 (measured; the rows 1 µs apart caught it to 1.6e-5): the cubic Hermite state
  // of the flight's steps bounds it.
  const double P = 200, k = 30000, m = 0.05, w = std::sqrt(k / m), e = 0.6;
  const double h1 = -P / k + std::sqrt(P / k * P / k + (e * v0 / w) * (e * v0 / w));
  EXPECT_NEAR(s.landings[0].bounce_height, h1, 2e-5 * h1);
  // 1.29 µm > 1 µm: fails; 0.169 m/s ≤ 0.5: passes
  EXPECT_TRUE(s.criteria[0].pass);
  EXPECT_FALSE(s.criteria[1].pass);
  EXPECT_FALSE(s.criteria_pass);
  EXPECT_NEAR(s.criteria[0].theta_deg, deg(imp[0].theta), 1e-9);
  // The ramp velocity at the take-up: the cam's speed where its lift crosses the lash, on the
  // opening (cycloidal: ω(L/β)(1 − cos 2πx), 0.1645 m/s) and on the closing flank (v₀, the
  // larger), the root of X(t) = lash located inside the step (was linear between rows 1 µs
  // apart: 2e-8); the same with rows 100× coarser.
  EXPECT_NEAR(s.max_ramp_velocity, v0, 1e-9 * v0);
}

TEST(Criteria, SweepJudgesEachSpeed) {
  // The seating velocity grows with the speed (the cam's speed at the lash); a limit between
  // the closed forms at 6 and 12 rev/s (0.101 and 0.203 m/s) passes the first and fails the second.
  const double v6 = closing_speed_at(0.0002, 6.0), v12 = closing_speed_at(0.0002, 12.0);
  const double limit = 0.5 * (v6 + v12);
  Scene sc = parse(bouncing_valve(6.0, "[criteria]\nmax_seating_velocity = " + std::to_string(limit) + "\n"));
  sc.run.t_end = 0.12;  // past the landing at 6 rev/s (249° at 0.115 s), before the second at 12 rev/s
  sc.run.output_dt = 1e-5;
  const fs::path dir = fs::temp_directory_path() / ("camdyn_criteria_sweep_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  SweepOptions o;
  o.axes = {SweepAxis{"cam.speed_rev_s", {12.0, 6.0}}};
  o.jobs = 2;
  o.out_dir = dir.string();
  o.timing = false;
  const SweepResult res = run_sweep(sc, o);
  ASSERT_EQ(res.failed, 0);
  std::ifstream in(dir / "sweep.csv");
  std::string head, r1, r2;
  std::getline(in, head);
  std::getline(in, r1);
  std::getline(in, r2);
  auto field = [&](const std::string& row, const std::string& name) {
    std::vector<std::string> h, f;
    std::string x;
    for (char c : head + ",") (c == ',' ? (h.push_back(x), x.clear()) : void(x += c));
    for (char c : row + ",") (c == ',' ? (f.push_back(x), x.clear()) : void(x += c));
    const auto it = std::find(h.begin(), h.end(), name);
    return it == h.end() || std::size_t(it - h.begin()) >= f.size() ? std::string("?") : f[std::size_t(it - h.begin())];
  };
  // rows in the axis's order: 12 then 6 rev/s
  EXPECT_EQ(field(r1, "criterion_seating_velocity_pass"), "0");
  EXPECT_EQ(field(r2, "criterion_seating_velocity_pass"), "1");
  EXPECT_NEAR(std::stod(field(r1, "criterion_seating_velocity_value")), v12, 1e-9 * v12);
  EXPECT_NEAR(std::stod(field(r2, "criterion_seating_velocity_value")), v6, 1e-9 * v6);
  EXPECT_EQ(head.find("criterion_seating_velocity_pass") < head.find(",message"), true);
  const std::vector<SweepCriterion> t = sweep_criteria_table((dir / "sweep.csv").string());
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].name, "seating_velocity");
  EXPECT_EQ(t[0].judged, 2);
  EXPECT_EQ(t[0].failed, 1);
  EXPECT_EQ(t[0].first_failure, 12.0);
  fs::remove_all(dir);
}

TEST(Criteria, BadLimitsAreSceneErrors) {
  auto err = [](const std::string& extra) {
    try {
      Simulator sim(parse(bouncing_valve(10.0, extra)));
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(err("[criteria]\nmax_seating_velocity = -1\n").find("criteria.max_seating_velocity"), std::string::npos);
  EXPECT_NE(err("[criteria]\nmax_bounce_count = -2\n").find("criteria.max_bounce_count"), std::string::npos);
  EXPECT_NE(err("[criteria]\nmin_film_thickness = 1e-7\n").find("lubricant.viscosity"), std::string::npos);
  EXPECT_NE(err("[criteria]\nmax_lift_deviation = 1e-4\n").find("run.valve_node"), std::string::npos);
  EXPECT_NE(err("[lubricant]\nviscosity = 0.01\n").find("cam.width"), std::string::npos);
  EXPECT_NE(err("[lubricant]\nroughness = -1e-7\n").find("lubricant.roughness"), std::string::npos);
  Scene sc = parse(bouncing_valve(10.0));
  sc.run.valve_node = "stem";
  EXPECT_THROW(Simulator{sc}, SceneError);
  try {
    Simulator sim(sc);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "run.valve_node");
  }
}

TEST(OilFilm, RunColumnIsHamrockAtTheRowsLoadRadiusAndSpeed) {
  // A rigid flat-faced follower on an eccentric circle cam (R = 20 mm, e = 4 mm): ρ = R, the
  // face at X_C = R + e cos(θ − θ_e), so X_C″ = R − X_C and ũ = −½ω(X_C + 2X_C″) = −½ω(2R − X_C);
  // a flat face's axial force is the normal force. Hamrock's h written here in its
  // dimensional form h = 1.714 w′^−0.128 (η₀ũ)^0.694 ξ^0.568 E′^0.002 R^0.434.
  Scene sc = parse(R"(title = "flat tappet film"
[cam]
profile = "circle"
radius = 0.02
eccentricity = 0.004
follower_face = "flat"
width = 0.01
youngs_modulus = 2.1e11
follower_youngs_modulus = 2.1e11
speed_rev_s = 20
[follower]
kind = "rigid"
mass = 0.1
[spring]
stiffness = 20000
precompression = 0.02
[run]
t_end = 0.05
output_dt = 1e-4
[lubricant]
viscosity = 0.01
pressure_viscosity = 2e-8
roughness = 2e-7
[criteria]
min_film_thickness = 1e-8
min_lambda = 0.5
)");
  Simulator sim(sc);
  const int hcol = column(sim, "film_thickness"), lcol = column(sim, "lambda");
  ASSERT_GE(hcol, 0);
  ASSERT_GE(lcol, 0);
  Rows obs;
  const Summary s = sim.run(&obs);
  ASSERT_TRUE(s.finished) << s.message;
  const double R = 0.02, w = 2 * kPi * 20, Ep = 2.1e11 / (1 - 0.3 * 0.3);
  double hmin = INFINITY;
  int checked = 0;
  for (const HistoryRow& r : obs.rows) {
    const double h = r.extra[std::size_t(hcol)];
    if (r.contact_force <= 0) {
      EXPECT_TRUE(std::isnan(h));
      continue;
    }
    const double XC = r.u_c, u = std::abs(0.5 * w * (2 * R - XC));
    const double wp = r.contact_force / 0.01;
    const double ref = 1.714 * std::pow(wp, -0.128) * std::pow(0.01 * u, 0.694) * std::pow(2e-8, 0.568) *
                       std::pow(Ep, 0.002) * std::pow(R, 0.434);
    // the row's X_C is the follower's u_c on the cam (measured: agreement to 1e-12)
    EXPECT_NEAR(h / ref, 1.0, 1e-10) << "t = " << r.t;
    EXPECT_NEAR(r.extra[std::size_t(lcol)], h / 2e-7, 1e-12 * h / 2e-7);
    hmin = std::min(hmin, h);
    ++checked;
  }
  EXPECT_GT(checked, 400);
  EXPECT_DOUBLE_EQ(s.min_film_thickness, hmin);
  EXPECT_DOUBLE_EQ(s.min_lambda, hmin / 2e-7);
  ASSERT_EQ(s.criteria.size(), 2u);
  EXPECT_EQ(s.criteria[0].name, "film_thickness");
  EXPECT_EQ(s.criteria[0].value, hmin);
  EXPECT_EQ(s.criteria[1].name, "lambda");
  // no lubricant: no column
  sc.lubricant = LubricantSpec{};
  sc.criteria = CriteriaSpec{};
  EXPECT_LT(column(Simulator(sc), "film_thickness"), 0);
}

namespace {
// A tappet driven by the cam through a stiff spring k_p (the pushrod) to the valve (mass m,
// spring k_v, both preloaded by P: q = 0 is the installed equilibrium).
std::string pushrod_train(double speed_rev_s, double kp) {
  return R"(title = "pushrod"
[cam]
profile = "law"
law = "dwell 100; cycloidal 80 0.008; cycloidal 80 -0.008; dwell 100"
base_radius = 0.02
follower_face = "point"
speed_rev_s = )" +
         std::to_string(speed_rev_s) + R"(
[follower]
kind = "network"
[contact]
tol_u = 1e-11
[solver]
rtol = 1e-10
atol = 1e-14
[run]
t_end = )" + std::to_string(0.99 / speed_rev_s) +
         R"(
output_dt = )" + std::to_string(0.5e-3 / speed_rev_s) +
         R"(
valve_node = "valve"
[criteria]
max_lift_deviation = 1e-3
[[nodes]]
name = "tappet"
mass = 0.02
[[nodes]]
name = "valve"
mass = 0.05
[[elements]]
type = "spring"
name = "pushrod"
nodes = ["tappet", "valve"]
stiffness = )" + std::to_string(kp) +
         R"(
preload = 300
[[elements]]
type = "spring"
name = "valve_spring"
nodes = ["valve", "ground"]
stiffness = 30000
preload = 300
[[contacts]]
name = "cam"
type = "cam"
nodes = ["tappet"]
)";
}
}  // namespace

TEST(LiftDeviation, QuasiStaticClosedFormAtLowSpeed) {
  // At 0.5 rev/s the valve follows the quasi-static solution k_p (X − q) = k_v q + m Ẍ
  // (its inertia to first order: (ω/ω_n)² ≈ 1e-6), so q − X = −(k_v X + m Ẍ)/(k_p + k_v): the
  // lift deviation. Stiff pushrod (k_p = 1e8 N/m): |deviation| ≤ 30000·8e-3/1e8 = 2.4e-6 m.
  // Measured: largest error 4e-13 m at k_p = 1e8; 1.9e-10 m at k_p = 3e6 (the deviation
  // reaches 7.9e-5 m there; without the inertia term the error was 4e-9 m).
  for (double kp : {1e8, 3e6}) {
    Simulator sim(parse(pushrod_train(0.5, kp)));
    const int dcol = column(sim, "lift_deviation"), ut = column(sim, "u_tappet");
    ASSERT_GE(dcol, 0);
    Rows obs;
    const Summary s = sim.run(&obs);
    ASSERT_TRUE(s.finished) << s.message;
    double lo = INFINITY, hi = -INFINITY, err = 0;
    for (const HistoryRow& r : obs.rows) {
      const double X = r.extra[std::size_t(ut)];  // the tappet rides the cam: its lift is X (gap held to tol_u)
      // the cycloidal law's acceleration Ẍ = ±ω²(2πL/β²) sin 2πx on the rise (100°–180°) and
      // the fall (180°–260°); the valve's inertia m Ẍ adds to its spring's force (first order)
      const double th = r.theta * 180.0 / kPi, beta = 80.0 * kPi / 180.0, w = 2 * kPi * 0.5;
      double Xdd = 0;
      if (th > 100 && th < 180) Xdd = w * w * 2 * kPi * 0.008 / (beta * beta) * std::sin(2 * kPi * (th - 100) / 80);
      if (th > 180 && th < 260) Xdd = -w * w * 2 * kPi * 0.008 / (beta * beta) * std::sin(2 * kPi * (th - 180) / 80);
      const double want = -(30000.0 * X + 0.05 * Xdd) / (kp + 30000.0);
      err = std::max(err, std::abs(r.extra[std::size_t(dcol)] - want) / (5e-10 + 1e-5 * std::abs(want)));
      EXPECT_NEAR(r.extra[std::size_t(dcol)], want, 5e-10 + 1e-5 * std::abs(want)) << "t = " << r.t;
      lo = std::min(lo, r.extra[std::size_t(dcol)]);
      hi = std::max(hi, r.extra[std::size_t(dcol)]);
    }
    EXPECT_LT(err, 1.0);
    ASSERT_EQ(s.lift_deviation.size(), 1u);
    // the extremes are located inside the steps: beyond every row's value, and within the
    // closed form's tolerance of the rows' extremes (the rows resolve the quasi-static curve)
    const Summary& S = s;
    EXPECT_LE(S.lift_deviation[0].min, lo + 1e-18);
    EXPECT_GE(S.lift_deviation[0].min, lo - (5e-10 + 1e-5 * std::abs(lo)));
    EXPECT_GE(S.lift_deviation[0].max, hi - 1e-18);
    EXPECT_LE(S.lift_deviation[0].max, hi + (5e-10 + 1e-5 * std::abs(hi)));
    ASSERT_EQ(s.criteria.size(), 1u);
    EXPECT_EQ(s.criteria[0].value, std::max(std::abs(S.lift_deviation[0].min), std::abs(S.lift_deviation[0].max)));
    EXPECT_TRUE(s.criteria[0].pass);
    if (kp == 1e8) {
      EXPECT_LT(std::max(std::abs(lo), std::abs(hi)), 2.5e-6);
    }
  }
}

TEST(Examples, ShippedScenesRaiseNoPlausibilityWarning) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(fs::path(CAMDYN_SOURCE_DIR) / "examples")) {
    if (e.path().extension() != ".toml") continue;
    const std::vector<std::string> w = scene_warnings(load_scene_file(e.path().string()));
    EXPECT_TRUE(w.empty()) << e.path() << ": " << (w.empty() ? "" : w[0]);
    ++n;
  }
  EXPECT_GT(n, 10);
}

TEST(TakeUpWindow, EveryLashOnThePathToTheCam) {
  // The roller finger: the finger's lash adjuster spring holds it on the cam (8 N) while the
  // 0.1 mm valve lash is open, the cam lifting X from 0 to 0.1 mm: the window spans the cam
  // lifts [0 − 1 %, 0.1 mm + 1 %] of the 9 mm lift, so the cam contact's least force is
  // the one on the lobe. Recomputed here from the rows (in_cam, F_cam, the cam lift
  // u_c − gap of the primary cam contact) outside that window; the run also samples the
  // step ends between rows, so its least force is at most the rows' (measured: equal to 1e-3).
  Scene sc = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_roller_finger.toml");
  Simulator sim(sc);
  const int F = column(sim, "F_cam"), in = column(sim, "in_cam");
  Rows obs;
  const Summary s = sim.run(&obs);
  ASSERT_TRUE(s.finished) << s.message;
  const double d = 0.01 * 0.009, lo = 0.0 - d, hi = 1e-4 + d;
  double fmin = INFINITY;
  for (const HistoryRow& r : obs.rows) {
    const double X = r.u_c - r.gap;
    if (r.extra[std::size_t(in)] > 0.5 && !(X >= lo && X <= hi)) fmin = std::min(fmin, r.extra[std::size_t(F)]);
  }
  ASSERT_EQ(s.contacts[0].name, "cam");
  EXPECT_LE(s.contacts[0].min_force, fmin * (1 + 1e-12));
  EXPECT_NEAR(s.contacts[0].min_force, fmin, 1e-2 * fmin);
  EXPECT_GT(s.contacts[0].min_force, 8.0 + 2000.0 * hi);  // not the adjuster spring on the base circle
}

TEST(KinematicPath, LeverAndLashesByHand) {
  // cam (clearance 0.1 mm) → tappet —bar— pushrod → rocker (ratio 1.5) → valve end —lash
  // 0.3 mm→ valve. By hand: tappet = max(0, X − 0.1 mm), the pushrod the same, the valve end
  // 1.5·max(0, X − 0.1 mm), the valve 1.5·max(0, X − 0.1 mm − 0.3 mm/1.5); the lash closes at
  // X = 0.3 mm. A node on a spring to ground only is not reached.
  Scene sc = parse(R"(title = "path"
[cam]
profile = "circle"
radius = 0.02
eccentricity = 0.004
[follower]
kind = "network"
[[nodes]]
name = "tappet"
mass = 0.05
[[nodes]]
name = "pushrod"
mass = 0.01
[[nodes]]
name = "valve_end"
[[nodes]]
name = "valve"
mass = 0.05
[[nodes]]
name = "other"
mass = 0.01
[[elements]]
type = "bar"
nodes = ["tappet", "pushrod"]
mass = 0.02
youngs_modulus = 2.1e11
area = 1e-5
length = 0.2
[[elements]]
type = "lever"
nodes = ["pushrod", "valve_end"]
ratio = 1.5
[[elements]]
type = "spring"
nodes = ["valve", "ground"]
stiffness = 30000
preload = 300
[[elements]]
type = "spring"
nodes = ["other", "ground"]
stiffness = 30000
[[elements]]
type = "spring"
nodes = ["tappet", "ground"]
stiffness = 2000
preload = 5
[[contacts]]
name = "cam"
type = "cam"
nodes = ["tappet"]
clearance = 0.0001
[[contacts]]
name = "lash"
type = "lash"
nodes = ["valve_end", "valve"]
clearance = 0.0003
)");
  const detail::KinematicPath p(sc);
  EXPECT_DOUBLE_EQ(p.node("pushrod").gain, 1.0);
  EXPECT_DOUBLE_EQ(p.node("pushrod").take_up, 1e-4);
  EXPECT_DOUBLE_EQ(p.node("valve_end").gain, 1.5);
  const detail::KinematicNode v = p.node("valve");
  ASSERT_TRUE(v.reached);
  EXPECT_DOUBLE_EQ(v.gain, 1.5);
  EXPECT_NEAR(v.take_up, 1e-4 + 3e-4 / 1.5, 1e-18);
  EXPECT_NEAR(v.lift(2e-3), 1.5 * (2e-3 - 3e-4), 1e-15);
  EXPECT_EQ(v.lift(2e-4), 0.0);
  EXPECT_FALSE(p.node("other").reached);
  ASSERT_EQ(p.take_up_levels().size(), 2u);
  EXPECT_DOUBLE_EQ(p.take_up_levels()[0], 1e-4);
  EXPECT_NEAR(p.take_up_levels()[1], 3e-4, 1e-18);
}

TEST(OilFilm, RollingSpeedFromTheCamFrameIsTheInLineRollerFormula) {
  // An in-line translating roller (r_r = 8 mm on a law cam): the contact point travels over
  // the cam at the roller centre's speed relative to the cam, |ω|√(X_C² + X_C′²), times
  // ρ/(ρ + r_r) (the centre runs on the pitch curve, ρ + r_r from the same centre of
  // curvature). The run computes it for any roller from the contact point in the cam's frame
  // (central differences): the two agree to 2e-9 (measured 3e-10) over the revolution, which
  // also fixes the cam's sense of rotation in that frame.
  Scene sc = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/law_roller.toml");
  sc.cam.follower_offset = 0.0;
  sc.lubricant.viscosity = 0.01;
  const Cam cam(sc.cam);
  const detail::RunAnalysis a(sc, {"cam"}, {}, cam.lift(), &cam);
  const double w = 2 * kPi * 25.0, rr = 8.0;
  double worst = 0;
  for (int i = 0; i < 360; ++i) {
    const CamPoint p = cam.evaluate(2 * kPi * (i + 0.37) / 360);
    const double ref = w * std::hypot(p.X_C, p.dX_dtheta) * p.rho / (p.rho + rr);
    worst = std::max(worst, std::abs(a.entrainment(p, w) / ref - 1));
  }
  EXPECT_LT(worst, 2e-9);
}
