// Lift tables as a cam profile (cam.profile = "table") and the cam synthesised from the
// valve lift through the train (include/camdyn/synthesis.hpp), against closed forms and a
// forward kinematics computed here from the synthesised profile's points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <camdyn/cam.hpp>
#include <camdyn/lift_table.hpp>
#include <camdyn/scene.hpp>
#include <camdyn/synthesis.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

std::string tmp_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("camdyn_synth_" + name);
  std::filesystem::create_directories(d);
  return d.string();
}

double p345(double x) { return x * x * x * (10 - 15 * x + 6 * x * x); }
double cyc(double x) { return x - std::sin(2 * kPi * x) / (2 * kPi); }

// "dwell 100; cycloidal 70 9; dwell 10; poly345 70 -9; dwell 110" in closed form [mm].
const char* kValveLaw = "dwell 100; cycloidal 70 9; dwell 10; poly345 70 -9; dwell 110";
double valve_lift(double th) {
  double d = std::fmod(th / kDeg, 360.0);
  if (d < 0) d += 360.0;
  if (d < 100) return 0;
  if (d < 170) return 9 * cyc((d - 100) / 70);
  if (d < 180) return 9;
  if (d < 250) return 9 - 9 * p345((d - 180) / 70);
  return 0;
}

// Minimise f on [a, b] (golden section) to |b − a| < tol; returns the arg min.
double golden_min(const std::function<double(double)>& f, double a, double b, double tol) {
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  while (b - a > tol) {
    if (fc < fd) { b = d; d = c; fd = fc; c = b - g * (b - a); fc = f(c); }
    else { a = c; c = d; fc = fd; d = a + g * (b - a); fd = f(d); }
  }
  return 0.5 * (a + b);
}
double bisect(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double m = 0.5 * (a + b), fm = f(m);
    if ((fm < 0) == (fa < 0)) { a = m; fa = fm; } else b = m;
  }
  return 0.5 * (a + b);
}
}  // namespace

// A law cam exported by lift_table_of (with derivatives) and read back as cam.profile =
// "table" from a scene file (relative path): X_C equals the law's closed form r_b + L(θ)
// between the knots too (quintic Hermite, 0.1° knots; measured max error 1.8e-15).
TEST(LiftTableProfile, RoundTripThroughSceneFile) {
  CamSpec law;
  law.profile = CamProfileKind::Law;
  law.law = "dwell 150; poly345 100 0.4; poly345 110 -0.4";
  law.base_radius = 2.0;
  const Cam src(law);
  const std::string dir = tmp_dir("roundtrip");
  { std::ofstream(dir + "/t.csv") << lift_table_csv(lift_table_of(src, 3600)); }
  { std::ofstream(dir + "/s.toml") << "[cam]\nprofile = \"table\"\nlift_table = \"t.csv\"\nbase_radius = 2.0\n"; }
  const Scene sc = load_scene_file(dir + "/s.toml");
  EXPECT_EQ(sc.cam.profile, CamProfileKind::Table);
  const Cam cam(sc.cam);
  auto L = [](double th) {
    const double d = th / kDeg;
    if (d < 150) return 0.0;
    if (d < 250) return 0.4 * p345((d - 150) / 100);
    return 0.4 - 0.4 * p345((d - 250) / 110);
  };
  double err = 0;
  for (int i = 0; i < 10007; ++i) {
    const double th = 2 * kPi * (i + 0.37) / 10007;
    err = std::max(err, std::fabs(cam.evaluate(th).X_C - (2.0 + L(th))));
  }
  EXPECT_LT(err, 1e-9);
  EXPECT_NEAR(cam.lift(), 0.4, 1e-12);
  // Without the derivatives: the periodic C² cubic spline through a 1° table (measured
  // 6.5e-9; the spline estimate (5/384) h⁴ max|L⁗| = 1.9e-8), well above round-off.
  LiftTable t = lift_table_of(src, 360);
  t.dlift_ddeg.clear();
  t.d2lift_ddeg2.clear();
  { std::ofstream(dir + "/t2.csv") << lift_table_csv(t); }
  CamSpec c2 = sc.cam;
  c2.lift_table = dir + "/t2.csv";
  const Cam spl(c2);
  double e2 = 0;
  for (int i = 0; i < 2001; ++i) {
    const double th = 2 * kPi * (i + 0.37) / 2001;
    e2 = std::max(e2, std::fabs(spl.evaluate(th).X_C - (2.0 + L(th))));
  }
  EXPECT_LT(e2, 5e-8);
  EXPECT_GT(e2, 1e-12);
}

TEST(LiftTableProfile, MissingFileNamesKey) {
  CamSpec c;
  c.profile = CamProfileKind::Table;
  c.lift_table = "/nonexistent/camdyn_table.csv";
  try {
    const Cam cam(c);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "cam.lift_table");
  }
}

namespace {
CamSpec roller_finger(double px, double py, double arm, double rr, double lv) {
  CamSpec c;
  c.profile = CamProfileKind::Law;
  c.law = kValveLaw;
  c.base_radius = 16.0;
  c.follower_motion = FollowerMotion::Oscillating;
  c.follower_face = FollowerFace::Roller;
  c.pivot_x = px;
  c.pivot_y = py;
  c.arm_length = arm;
  c.roller_radius = rr;
  c.valve_arm = lv;
  return c;
}

// The valve lift the synthesised roller-finger cam gives, from its profile points alone:
// the roller centre P + ℓ(cos α, sin α) touching the profile (golden-section distance,
// bisection in α), ψ = α − α_b with α_b from the base-circle triangle, then the valve map
// ℓ_v (sin(ψ₀ + ψ) − sin ψ₀) − lash in closed form. Returns the largest error against the
// valve law's closed form.
double finger_valve_error(const CamSpec& c, const Cam& cam, double psi0, double lash, int n) {
  const double px = c.pivot_x, py = c.pivot_y, l = c.arm_length, rr = c.roller_radius;
  const double d = std::hypot(px, py), Ab = c.base_radius + rr;
  const double alpha_b = std::atan2(-py, -px) + std::acos((l * l + d * d - Ab * Ab) / (2 * l * d));
  double err = 0;
  for (int i = 0; i < n; ++i) {
    const double th = 2 * kPi * (i + 0.5) / n;
    auto gap = [&](double a) {
      const double cx = px + l * std::cos(a), cy = py + l * std::sin(a);
      const double xc = cx * std::cos(th) + cy * std::sin(th), yc = -cx * std::sin(th) + cy * std::cos(th);
      auto dist = [&](double s) {
        const auto q = cam.profile_point(s);
        return std::hypot(q[0] - xc, q[1] - yc);
      };
      return dist(golden_min(dist, th - 0.3, th + 0.3, 1e-11)) - rr;
    };
    const double V = valve_lift(th);
    const double guess = std::asin(std::sin(psi0) + (V + lash) / c.valve_arm) - psi0;
    const double a = bisect(gap, alpha_b + guess - 0.05, alpha_b + guess + 0.05);
    const double Vc = c.valve_arm * (std::sin(psi0 + (a - alpha_b)) - std::sin(psi0)) - lash;
    err = std::max(err, std::fabs(std::max(Vc, 0.0) - V));
  }
  return err;
}
}  // namespace

// Two roller-finger geometries (pivot, arm, roller, valve arm, ψ₀, lash differ): the valve
// lift of the synthesised cam, by the forward kinematics above, equals the requested law
// (measured max error: from ψ 3.3e-14 and 3.0e-14 mm, from the profile points 3.7e-14 and
// 4.4e-14 mm, on 9 mm of lift).
TEST(CamSynthesis, RollerFingerTwoGeometries) {
  struct G {
    CamSpec c;
    double psi0_deg, lash, ramp;
  };
  const G geoms[] = {{roller_finger(40, 18, 30, 8, 45), 0.0, 0.0, 0.0},
                     {roller_finger(44, 26, 36, 9, 52), 12.0, 0.15, 20.0}};
  int k = 0;
  for (const G& g : geoms) {
    ValveTrainOptions t;
    t.valve_end_angle_deg = g.psi0_deg;
    t.lash = g.lash;
    t.ramp_deg = g.ramp;
    const std::string path = tmp_dir("finger") + "/cam" + std::to_string(k++) + ".csv";
    const CamSynthesis s = synthesise_cam_from_valve_lift(g.c, MotionLaw::parse(kValveLaw), t, path);
    const Cam cam(s.spec);
    // ψ of the cam's own kinematics through the valve map, densely
    double e1 = 0;
    for (int i = 0; i < 20011; ++i) {
      const double th = 2 * kPi * (i + 0.29) / 20011;
      const double psi = cam.evaluate(th).psi;
      const double Vc = g.c.valve_arm * (std::sin(g.psi0_deg * kDeg + psi) - std::sin(g.psi0_deg * kDeg)) - g.lash;
      e1 = std::max(e1, std::fabs(std::max(Vc, 0.0) - valve_lift(th)));
    }
    EXPECT_LT(e1, 1e-9) << k;
    EXPECT_LT(finger_valve_error(g.c, cam, g.psi0_deg * kDeg, g.lash, 97), 1e-9) << k;
    EXPECT_GT(s.max_pressure_angle_deg, 0.0);
    EXPECT_GT(s.min_radius_of_curvature, 0.0);
  }
}

// A rocker of constant ratio 1.6 with 0.25 mm lash on a flat-faced follower: the follower
// lift of the synthesised cam, X(θ) = max over the profile points of their X (the flat
// face's support function, golden section here), gives V = 1.6 (X − X_base) − lash on the
// lobe and a closed valve off it (measured max error 2.2e-14 mm).
TEST(CamSynthesis, ConstantRatioRockerWithLash) {
  CamSpec c;
  c.profile = CamProfileKind::Law;
  c.law = "dwell 100; cycloidal 70 9; dwell 10; poly345 70 -9; dwell 110";
  c.base_radius = 20.0;
  ValveTrainOptions t;
  t.ratio = 1.6;
  t.lash = 0.25;
  t.ramp_deg = 30.0;
  const CamSynthesis s =
      synthesise_cam_from_valve_lift(c, MotionLaw::parse(c.law), t, tmp_dir("rocker") + "/cam.csv");
  const Cam cam(s.spec);
  double err = 0;
  for (int i = 0; i < 360; ++i) {
    const double th = 2 * kPi * (i + 0.5) / 360;
    auto negX = [&](double a) {
      const auto q = cam.profile_point(a);
      return -(q[0] * std::cos(th) - q[1] * std::sin(th));
    };
    const double X = -negX(golden_min(negX, th - 0.5, th + 0.5, 1e-11));
    const double Vc = 1.6 * (X - c.base_radius) - t.lash;
    err = std::max(err, std::fabs(std::max(Vc, 0.0) - valve_lift(th)));
    if (valve_lift(th) == 0) EXPECT_LE(X - c.base_radius, t.lash / 1.6 + 1e-12);
  }
  EXPECT_LT(err, 1e-9);
  EXPECT_NEAR(s.lift, 9.25 / 1.6, 1e-9);
}

TEST(CamSynthesis, BadTrainsNameKeyAndRule) {
  auto key_of = [](CamSpec c, ValveTrainOptions t) -> std::string {
    try {
      synthesise_cam_from_valve_lift(c, MotionLaw::parse(kValveLaw), t, tmp_dir("bad") + "/cam.csv");
    } catch (const SceneError& e) {
      return e.key() + " | " + e.value() + " | " + e.rule();
    }
    return "<no error>";
  };
  CamSpec c;
  c.profile = CamProfileKind::Law;
  c.law = kValveLaw;
  c.base_radius = 20.0;
  ValveTrainOptions t;
  t.ratio = 0.0;
  EXPECT_EQ(key_of(c, t).rfind("synthesis.ratio | 0 |", 0), 0u) << key_of(c, t);
  t.ratio = -2.0;
  EXPECT_EQ(key_of(c, t).rfind("synthesis.ratio | -2 |", 0), 0u) << key_of(c, t);
  t.ratio = 1.0;
  t.lash = 0.1;
  EXPECT_EQ(key_of(c, t).rfind("synthesis.ramp_deg", 0), 0u) << key_of(c, t);
  t.ramp_deg = 120;  // two ramps of 120° on a 210° closed valve
  EXPECT_EQ(key_of(c, t).rfind("synthesis.ramp_deg", 0), 0u) << key_of(c, t);
  // A finger whose valve end cannot reach 9 mm: ℓ_v (1 − sin ψ₀) = 12 (1 − sin 30°) = 6.
  CamSpec f = roller_finger(40, 18, 30, 8, 12);
  ValveTrainOptions tf;
  tf.valve_end_angle_deg = 30;
  const std::string m = key_of(f, tf);
  EXPECT_EQ(m.rfind("cam.law", 0), 0u) << m;
  EXPECT_NE(m.find("reach"), std::string::npos) << m;
  tf.valve_end_angle_deg = 95;
  EXPECT_EQ(key_of(f, tf).rfind("synthesis.valve_end_angle_deg", 0), 0u) << key_of(f, tf);
}
