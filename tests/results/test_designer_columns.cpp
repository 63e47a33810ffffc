// camdyn — designer results per history row (issue 24, run.designer_columns) and the side
// load of a network's cam contact, against independent truth: the closed-form kinematics of
// a roller follower with offset on an eccentric circle cam (pressure angle, s′), the
// textbook Hertz formula for two cylinders, the power balance T ω = F ṡ and its integral
// (the run's own work column, accumulated by another quadrature).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <camdyn/cam.hpp>
#include <camdyn/initial_state.hpp>
#include <camdyn/output.hpp>
#include <camdyn/scene.hpp>
#include <camdyn/simulator.hpp>

#include "../network_run_support.hpp"

using namespace camdyn;
using camdyn_test::NetRun;
using camdyn_test::run_keeping_rows;

namespace {
constexpr double kPi = 3.14159265358979323846;
// The cam and the follower face of every scene below.
constexpr double R = 2.0, e = 0.5, rr = 0.4, eps = 0.3, width = 1.5, E = 2.1e5, nu = 0.3;
const char* kCam = R"([cam]
profile = "circle"
radius = 2.0
eccentricity = 0.5
follower_face = "roller"
roller_radius = 0.4
follower_offset = 0.3
speed_rev_s = 1.0
width = 1.5
youngs_modulus = 2.1e5
poisson_ratio = 0.3
follower_youngs_modulus = 2.1e5
follower_poisson_ratio = 0.3
)";

// Closed form: the roller centre on Y = ε at distance R + r_r from the cam centre
// (e cos θ, e sin θ); the normal through both centres.
double q_of(double th) { return eps - e * std::sin(th); }
double root_of(double th) { return std::sqrt((R + rr) * (R + rr) - q_of(th) * q_of(th)); }
double s1_of(double th) { return -e * std::sin(th) + q_of(th) * e * std::cos(th) / root_of(th); }
double tan_phi(double th) { return q_of(th) / root_of(th); }

// Hertz, two parallel cylinders (Johnson, Contact Mechanics, eq. 4.45 with 4.43):
//   p₀ = √(N E* / (π L R')),  1/R' = 1/R₁ + 1/R₂,  1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
double hertz_p0(double N) {
  const double Es = 1.0 / (2.0 * (1 - nu * nu) / E), Rp = 1.0 / (1.0 / R + 1.0 / rr);
  return std::sqrt(N * Es / (kPi * width * Rp));
}

Scene rigid_scene(bool columns, double output_dt) {
  Scene sc = parse_scene(std::string(kCam) + R"([follower]
kind = "rigid"
mass = 1.0
[spring]
stiffness = 500.0
precompression = 7.0
[run]
t_end = 1.0
)", "<test>");
  sc.run.output_dt = output_dt;
  sc.run.designer_columns = columns;
  return sc;
}

Scene network_scene(bool columns, double output_dt) {
  Scene sc = parse_scene(std::string(kCam) + R"([follower]
kind = "network"
[[nodes]]
name = "tappet"
mass = 1.0
[[elements]]
name = "spring"
type = "spring"
nodes = ["tappet", "ground"]
stiffness = 500.0
preload = 3500.0
[[contacts]]
name = "cam"
type = "cam"
nodes = ["tappet"]
[run]
t_end = 1.0
)", "<test>");
  sc.run.output_dt = output_dt;
  sc.run.designer_columns = columns;
  // Start on the cam with its velocity (X measured from the base circle: the lift).
  const Cam cam(sc.cam);
  sc.network.nodes[0].initial_displacement = cam.evaluate(0.0).X_C - cam_lift_base(cam, sc.cam);
  sc.network.nodes[0].initial_velocity = s1_of(0.0) * 2 * kPi;
  return sc;
}

// Every designer column of every row against the closed forms, with F the row's axial
// contact force of the cam (F_cam: the network's, contact_force: the single follower's).
void check_rows(const NetRun& r, const char* force_col) {
  const double w = 2 * kPi;
  int checked = 0;
  double dmax = 0;
  for (const HistoryRow& row : r.rows) {
    const double th = row.theta;
    const double F = force_col ? r.col(row, force_col) : row.contact_force;
    const double tp = tan_phi(th);
    EXPECT_NEAR(r.col(row, "pressure_angle_deg"), std::atan(tp) * 180 / kPi, 1e-10);
    EXPECT_NEAR(r.col(row, "radius_of_curvature"), R, 1e-12);
    EXPECT_NEAR(r.col(row, "side_load"), F * tp, 1e-10 * (1 + std::fabs(F)));
    const double Fdot_s = F * s1_of(th) * w;  // contact power F ṡ, ṡ = s′(θ) ω
    EXPECT_NEAR(r.col(row, "cam_torque") * w, Fdot_s, 1e-10 * (1 + std::fabs(Fdot_s)));
    EXPECT_NEAR(r.col(row, "cam_power"), Fdot_s, 1e-10 * (1 + std::fabs(Fdot_s)));
    const double N = F * std::sqrt(1 + tp * tp);  // F / cos φ
    EXPECT_NEAR(r.col(row, "contact_stress"), hertz_p0(N), 1e-10 * hertz_p0(N));
    dmax = std::max(dmax, std::fabs(r.col(row, "side_load")));
    ++checked;
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(dmax, 10.0);  // the offset roller does load its guide
}

// ∫ cam_power dt over the rows (trapezoid) against the run's work column (adaptive
// quadrature of F Ẋ_C inside the steps): the same work by two quadratures.
void check_work(const NetRun& r) {
  double W = 0;
  for (size_t i = 1; i < r.rows.size(); ++i)
    W += 0.5 * (r.rows[i].t - r.rows[i - 1].t) * (r.col(r.rows[i], "cam_power") + r.col(r.rows[i - 1], "cam_power"));
  double Pmax = 0;
  for (const HistoryRow& row : r.rows) Pmax = std::max(Pmax, std::fabs(r.col(row, "cam_power")));
  ASSERT_GT(Pmax, 0);
  // trapezoid at Δt = 1e-4 s over 1 s: error ≈ Δt² ω² Pmax / 12 ≈ 3e-8 Pmax
  EXPECT_NEAR(W, r.rows.back().work_cam, 1e-6 * Pmax);
}
}  // namespace

TEST(DesignerColumns, AbsentByDefaultAndRunUnchanged) {
  for (bool network : {false, true}) {
    SCOPED_TRACE(network);
    const Scene a = network ? network_scene(false, 1e-3) : rigid_scene(false, 1e-3);
    const Scene b = network ? network_scene(true, 1e-3) : rigid_scene(true, 1e-3);
    const NetRun ra = run_keeping_rows(a), rb = run_keeping_rows(b);
    ASSERT_TRUE(ra.sum.finished && rb.sum.finished);
    // without the key: no designer column; the history's header is the documented one
    for (const std::string& c : ra.cols) EXPECT_TRUE(c.rfind("F_", 0) == 0 || c.rfind("gap_", 0) == 0 ||
                                                     c.rfind("in_", 0) == 0 || c.rfind("u_", 0) == 0 ||
                                                     c.rfind("v_", 0) == 0) << c;
    ASSERT_EQ(rb.cols.size(), ra.cols.size() + 6);
    EXPECT_EQ(rb.cols.back(), "cam_power");
    // the same run: every row's standard and network columns bit for bit
    ASSERT_EQ(ra.rows.size(), rb.rows.size());
    for (size_t i = 0; i < ra.rows.size(); ++i) {
      EXPECT_EQ(ra.rows[i].t, rb.rows[i].t);
      EXPECT_EQ(ra.rows[i].u_c, rb.rows[i].u_c);
      EXPECT_EQ(ra.rows[i].contact_force, rb.rows[i].contact_force);
      for (size_t j = 0; j < ra.rows[i].extra.size(); ++j) EXPECT_EQ(ra.rows[i].extra[j], rb.rows[i].extra[j]);
    }
    // events.csv keeps its header (the contact column only for a network)
    const std::string ev = events_csv({}, network);
    EXPECT_EQ(history_csv({}, ra.cols).find("pressure_angle_deg"), std::string::npos);
    EXPECT_NE(history_csv({}, rb.cols).find(",pressure_angle_deg,radius_of_curvature,contact_stress,side_load,"
                                            "cam_torque,cam_power\n"),
              std::string::npos);
    (void)ev;
  }
}

TEST(DesignerColumns, SingleFollowerRowsAgainstClosedForms) {
  const NetRun r = run_keeping_rows(rigid_scene(true, 1e-4));
  ASSERT_TRUE(r.sum.finished) << r.sum.message;
  ASSERT_EQ(r.sum.separations, 0);
  check_rows(r, nullptr);
  check_work(r);
}

TEST(DesignerColumns, NetworkCamContactRowsAndSideLoad) {
  const NetRun r = run_keeping_rows(network_scene(true, 1e-4));
  ASSERT_TRUE(r.sum.finished) << r.sum.message;
  check_rows(r, "F_cam");
  check_work(r);
  // The per-contact side load: the largest |F tan φ| located inside the steps. Against rows
  // 20 µs apart (0.0072° of cam) of the closed form F_cam·tan φ(θ): at least every row's
  // value and above the largest by less than the rows' own resolution (measured 3.8e-10
  // relative, the angle 1.9e-3°); the step ends alone (rows at output_dt = 0) were 1.1e-4
  // low and 1.0° off.
  const NetRun s = run_keeping_rows(network_scene(true, 2e-5));
  ASSERT_TRUE(s.sum.finished) << s.sum.message;
  ASSERT_EQ(s.sum.contacts.size(), 1u);
  double best = 0, best_th = NAN;
  for (const HistoryRow& row : s.rows) {
    const double v = std::fabs(s.col(row, "F_cam") * tan_phi(row.theta));
    if (s.col(row, "in_cam") > 0 && v > best) {
      best = v;
      best_th = std::fmod(row.theta * 180 / kPi, 360.0);
    }
  }
  EXPECT_GE(s.sum.contacts[0].max_side_load, best * (1 - 1e-12));
  EXPECT_LE(s.sum.contacts[0].max_side_load, best * (1 + 1e-8));
  EXPECT_NEAR(s.sum.contacts[0].max_side_load_theta_deg, best_th, 0.0072);
  EXPECT_DOUBLE_EQ(s.sum.max_side_load, s.sum.contacts[0].max_side_load);
}
