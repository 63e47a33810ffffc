// Tests of the scene file: parsing, validation messages, overrides, round trips, paper cases.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"

#ifndef CAMDYN_SOURCE_DIR
#define CAMDYN_SOURCE_DIR "."
#endif

using namespace camdyn;

namespace {

std::string example(const std::string& name) { return std::string(CAMDYN_SOURCE_DIR) + "/examples/" + name; }

std::string error_of(const std::string& text, const std::string& file = "bad.toml") {
  try {
    parse_scene(text, file);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}

std::string override_error(Scene s, const std::string& assignment) {
  try {
    apply_override(s, assignment);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}

const std::string kCamKeys =
    "profile, angles_deg, radii, base_radius, lift_angles_deg, lift, radius, eccentricity, speed_rev_s, speed_rpm, rpm_of, "
    "speed_table_t, speed_table_rev_s, theta0_deg, law, lift_table, nose_radius, nose_distance, flank_radius, "
    "arc_centre_x, arc_centre_y, arc_centre_r, arc_centre_deg, arc_radius, arc_from_deg, arc_to_deg, "
    "follower_face, follower_offset, roller_radius, follower_motion, pivot_x, pivot_y, arm_length, pad_offset, "
    "valve_arm, land_on_breaks, width, youngs_modulus, poisson_ratio, "
    "follower_youngs_modulus, follower_poisson_ratio";
const std::string kTopKeys = "title, cam, follower, spring, contact, solver, run, nodes, elements, contacts";

}  // namespace

// ---------------------------------------------------------------- enums, errors, cases

TEST(SceneEnums, RoundTripEverySpelling) {
  for (const char* s : {"points", "lift", "circle"}) {
    CamProfileKind v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"rigid", "elastic_bar", "network"}) {
    FollowerKind v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"consistent", "lumped"}) {
    MassMatrixKind v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"lee", "penalty", "holonomic", "event"}) {
    ContactModel v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"eq12", "eq17"}) {
    ErrorVariant v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"linear", "hunt_crossley"}) {
    PenaltyLaw v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"arkode-erk", "arkode-dirk", "cvode-bdf"}) {
    Integrator v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  for (const char* s : {"auto", "dense", "klu"}) {
    LinearSolverKind v;
    ASSERT_TRUE(parse_enum(s, &v));
    EXPECT_STREQ(to_string(v), s);
  }
  ContactModel m = ContactModel::Event;
  EXPECT_FALSE(parse_enum("Lee", &m));
  EXPECT_FALSE(parse_enum("", &m));
  EXPECT_EQ(m, ContactModel::Event);
}

TEST(SceneError, MessageForms) {
  EXPECT_STREQ(SceneError("a.toml", 12, "cam.x", "1", "must be > 0").what(), "a.toml:12: key 'cam.x' = 1: must be > 0");
  EXPECT_STREQ(SceneError("a.toml", 0, "cam.x", "1", "must be > 0").what(), "a.toml: key 'cam.x' = 1: must be > 0");
  EXPECT_STREQ(SceneError("a.toml", 3, "", "", "syntax").what(), "a.toml:3: syntax");
  EXPECT_STREQ(SceneError("a.toml", 0, "", "", "syntax").what(), "a.toml: syntax");
  SceneError e("f", 2, "k", "v", "r");
  EXPECT_EQ(e.file(), "f");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.key(), "k");
  EXPECT_EQ(e.value(), "v");
  EXPECT_EQ(e.rule(), "r");
}

TEST(ScenePaperCases, Parameters) {
  const Scene a = paper_case("A");
  EXPECT_EQ(a.follower.kind, FollowerKind::Rigid);
  EXPECT_EQ(a.follower.mass, 1.0);
  EXPECT_EQ(a.spring.stiffness, 500.0);
  EXPECT_EQ(a.spring.precompression, 7.0);
  EXPECT_EQ(a.cam.speed_rev_s, 1.75);
  EXPECT_EQ(a.solver.rtol, 1e-7);
  EXPECT_EQ(a.contact.tol_u, 1e-8);
  EXPECT_EQ(a.run.t_end, 1.0);
  EXPECT_EQ(a.run.output_dt, 1e-4);
  EXPECT_EQ(a.solver.integrator, Integrator::ArkodeErk);
  EXPECT_EQ(a.cam.radii, (std::vector<double>{2.0, 2.0, 2.0, 2.1, 3.0, 2.1, 2.0, 2.0}));
  EXPECT_EQ(a.cam.angles_deg, (std::vector<double>{0, 45, 90, 135, 180, 225, 270, 315}));
  for (const char* name : {"B1", "B2"}) {
    const Scene b = paper_case(name);
    EXPECT_EQ(b.follower.kind, FollowerKind::ElasticBar);
    EXPECT_EQ(b.follower.mass, 1.0);
    EXPECT_EQ(b.follower.youngs_modulus, 1e7);
    EXPECT_EQ(b.follower.area, 3.0);
    EXPECT_EQ(b.follower.length, 24.0);
    EXPECT_EQ(b.follower.elements, 40);
    EXPECT_EQ(b.follower.mass_matrix, MassMatrixKind::Consistent);
    EXPECT_EQ(b.spring.stiffness, 500.0);
    EXPECT_EQ(b.spring.precompression, 7.0);
    EXPECT_EQ(b.solver.rtol, 1e-6);
    EXPECT_EQ(b.contact.tol_u, 1e-7);
    EXPECT_EQ(b.run.t_end, 1.0);
    EXPECT_EQ(b.cam.radii, a.cam.radii);
  }
  EXPECT_EQ(paper_case("B1").cam.speed_rev_s, 1.75);
  EXPECT_EQ(paper_case("B2").cam.speed_rev_s, 5.0);
  EXPECT_EQ(paper_case("B2").title, "Case B2 \u2014 elastic follower, 5 rev/s (Lee 1997 \u00a74.2)");
  EXPECT_TRUE(default_scene() == paper_case("B2"));
  EXPECT_THROW(paper_case("C"), SceneError);  // one exception type for user errors
  EXPECT_THROW(paper_case("b2"), SceneError);
  for (const char* name : {"A", "B1", "B2"}) EXPECT_NO_THROW(validate(paper_case(name))) << name;
}

TEST(SceneValidate, DefaultsAreValid) {
  EXPECT_NO_THROW(validate(Scene{}));  // tol_u = 0 means "not yet resolved"
  Scene s;
  resolve_defaults(s);
  EXPECT_EQ(s.contact.tol_u, 1e-8);
  resolve_defaults(s);
  EXPECT_EQ(s.contact.tol_u, 1e-8);
  Scene e;
  e.follower.kind = FollowerKind::ElasticBar;
  resolve_defaults(e);
  EXPECT_EQ(e.contact.tol_u, 1e-7);
  EXPECT_EQ(e.contact.tol_v, 0.0);
  EXPECT_EQ(e.contact.tol_a, 0.0);
}

TEST(SceneValidate, DirectValidateNamesSource) {
  Scene s = paper_case("A");
  s.follower.mass = -1;
  try {
    validate(s);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "<built-in>: key 'follower.mass' = -1: must be > 0");
    EXPECT_EQ(e.line(), 0);
  }
}

// ---------------------------------------------------------------- examples

TEST(SceneExamples, PaperCasesMatch) {
  for (const char* name : {"A", "B1", "B2"}) {
    const std::string path = example(std::string("case_") + name + ".toml");
    const Scene s = load_scene_file(path);
    EXPECT_TRUE(s == paper_case(name)) << path << "\n" << to_toml(s);
    EXPECT_EQ(s.source, path);
  }
}

TEST(SceneExamples, LiftAndCircleParse) {
  const Scene lift = load_scene_file(example("lift_cam.toml"));
  EXPECT_EQ(lift.cam.profile, CamProfileKind::Lift);
  EXPECT_EQ(lift.cam.base_radius, 2.0);
  ASSERT_GE(lift.cam.lift_angles_deg.size(), 36u);
  ASSERT_EQ(lift.cam.lift.size(), lift.cam.lift_angles_deg.size());
  EXPECT_EQ(lift.follower.kind, FollowerKind::Rigid);
  double mx = 0;
  for (double l : lift.cam.lift) mx = std::max(mx, l);
  EXPECT_DOUBLE_EQ(mx, 0.8);

  const Scene circle = load_scene_file(example("circle_cam.toml"));
  EXPECT_EQ(circle.cam.profile, CamProfileKind::Circle);
  EXPECT_EQ(circle.cam.radius, 2.0);
  EXPECT_EQ(circle.cam.eccentricity, 0.5);
  EXPECT_EQ(circle.contact.tol_u, 1e-8);  // resolved paper default
}

TEST(SceneLoad, UnreadableFile) {
  try {
    load_scene_file("/nonexistent/dir/scene.toml");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dir/scene.toml: cannot read scene file: No such file or directory");
  }
}

// ---------------------------------------------------------------- parsing details

TEST(SceneParse, EmptyTextGivesResolvedDefaults) {
  Scene s = parse_scene("", "empty.toml");
  Scene d;
  resolve_defaults(d);
  EXPECT_TRUE(s == d);
  EXPECT_EQ(s.source, "empty.toml");
}

TEST(SceneParse, EveryKeyAccepted) {
  const std::string text = R"(
title = "all keys"
[cam]
profile = "points"
angles_deg = [0, 90, 180, 270]
radii = [2, 2.5, 3, 2.5]
base_radius = 1.5
lift_angles_deg = [0, 90, 180, 270]
lift = [0, 0.1, 0.2, 0.1]
radius = 3
eccentricity = 1
speed_rev_s = -2
speed_table_t = [0, 0.5]
speed_table_rev_s = [0, 3]
theta0_deg = 12.5
[follower]
kind = "elastic_bar"
mass = 2
damping = 0.5
youngs_modulus = 2e7
area = 1.5
length = 10
elements = 12.0
mass_matrix = "lumped"
rayleigh_alpha = 0.1
rayleigh_beta = 1e-6
[spring]
stiffness = 0
precompression = -1
[contact]
model = "event"
error_variant = "eq17"
tol_u = 1e-9
tol_v = 1e-3
tol_a = 2
max_iterations = 7
separation = true
restitution = 0.5
initial_gap = 0.01
penalty_law = "hunt_crossley"
penalty_stiffness = 1e8
penalty_damping = 0.2
penalty_exponent = 1
[solver]
integrator = "cvode-bdf"
rtol = 1e-14
atol = 1
linear_solver = "klu"
max_step = 1e-3
initial_step = 1e-6
[run]
t_end = 2
output_dt = 2
max_steps = 1000
)";
  const Scene s = parse_scene(text, "all.toml");
  EXPECT_EQ(s.title, "all keys");
  EXPECT_EQ(s.cam.radii, (std::vector<double>{2, 2.5, 3, 2.5}));
  EXPECT_EQ(s.cam.base_radius, 1.5);
  EXPECT_EQ(s.cam.lift, (std::vector<double>{0, 0.1, 0.2, 0.1}));
  EXPECT_EQ(s.cam.radius, 3.0);
  EXPECT_EQ(s.cam.eccentricity, 1.0);
  EXPECT_EQ(s.cam.speed_rev_s, -2.0);
  EXPECT_EQ(s.cam.speed_table_t, (std::vector<double>{0, 0.5}));
  EXPECT_EQ(s.cam.speed_table_rev_s, (std::vector<double>{0, 3}));
  EXPECT_EQ(s.cam.theta0_deg, 12.5);
  EXPECT_EQ(s.follower.kind, FollowerKind::ElasticBar);
  EXPECT_EQ(s.follower.mass, 2.0);
  EXPECT_EQ(s.follower.damping, 0.5);
  EXPECT_EQ(s.follower.youngs_modulus, 2e7);
  EXPECT_EQ(s.follower.area, 1.5);
  EXPECT_EQ(s.follower.length, 10.0);
  EXPECT_EQ(s.follower.elements, 12);
  EXPECT_EQ(s.follower.mass_matrix, MassMatrixKind::Lumped);
  EXPECT_EQ(s.follower.rayleigh_alpha, 0.1);
  EXPECT_EQ(s.follower.rayleigh_beta, 1e-6);
  EXPECT_EQ(s.spring.stiffness, 0.0);
  EXPECT_EQ(s.spring.precompression, -1.0);
  EXPECT_EQ(s.contact.model, ContactModel::Event);
  EXPECT_EQ(s.contact.error_variant, ErrorVariant::Eq17);
  EXPECT_EQ(s.contact.tol_u, 1e-9);
  EXPECT_EQ(s.contact.tol_v, 1e-3);
  EXPECT_EQ(s.contact.tol_a, 2.0);
  EXPECT_EQ(s.contact.max_iterations, 7);
  EXPECT_TRUE(s.contact.separation);
  EXPECT_EQ(s.contact.restitution, 0.5);
  EXPECT_EQ(s.contact.initial_gap, 0.01);
  EXPECT_EQ(s.contact.penalty_law, PenaltyLaw::HuntCrossley);
  EXPECT_EQ(s.contact.penalty_stiffness, 1e8);
  EXPECT_EQ(s.contact.penalty_damping, 0.2);
  EXPECT_EQ(s.contact.penalty_exponent, 1.0);
  EXPECT_EQ(s.solver.integrator, Integrator::CvodeBdf);
  EXPECT_EQ(s.solver.rtol, 1e-14);
  EXPECT_EQ(s.solver.atol, 1.0);
  EXPECT_EQ(s.solver.linear_solver, LinearSolverKind::Klu);
  EXPECT_EQ(s.solver.max_step, 1e-3);
  EXPECT_EQ(s.solver.initial_step, 1e-6);
  EXPECT_EQ(s.run.t_end, 2.0);
  EXPECT_EQ(s.run.output_dt, 2.0);
  EXPECT_EQ(s.run.max_steps, 1000);
  // ...and it round-trips.
  EXPECT_TRUE(parse_scene(to_toml(s), "rt.toml") == s) << to_toml(s);
}

TEST(SceneParse, AllowedCombinations) {
  // Explicit integrator with a linear solver: allowed (ignored).
  EXPECT_NO_THROW(parse_scene("[solver]\nintegrator = \"arkode-erk\"\nlinear_solver = \"klu\"\n", "x"));
  EXPECT_NO_THROW(parse_scene("[solver]\nintegrator = \"arkode-erk\"\nlinear_solver = \"dense\"\n", "x"));
  EXPECT_NO_THROW(parse_scene("[contact]\nseparation = false\nmodel = \"holonomic\"\n", "x"));
  EXPECT_NO_THROW(parse_scene("[contact]\nseparation = false\n", "x"));
  EXPECT_NO_THROW(parse_scene("[contact]\nrestitution = 1\nmodel = \"event\"\n", "x"));
  // Unused profile fields are not checked structurally.
  EXPECT_NO_THROW(parse_scene("[cam]\nprofile = \"circle\"\nangles_deg = []\nradii = []\n", "x"));
  // Dotted keys at the top level work like tables.
  EXPECT_EQ(parse_scene("cam.speed_rev_s = 3\n", "x").cam.speed_rev_s, 3.0);
  EXPECT_EQ(parse_scene("[follower]\nelements = 7.0\n", "x").follower.elements, 7);
}

// ---------------------------------------------------------------- malformed scenes

struct BadScene {
  const char* what;
  std::string toml;
  std::string message;
};

TEST(SceneMalformed, ExactMessages) {
  const std::vector<BadScene> cases = {
      {"unknown key", "title = \"t\"\n[cam]\nsped_rev_s = 1.75\n",
       "bad.toml:3: key 'cam.sped_rev_s' = 1.75: unknown key; allowed keys in [cam]: " + kCamKeys},
      {"unknown top-level key", "foo = 1\n",
       "bad.toml:1: key 'foo' = 1: unknown key; allowed keys at top level: " + kTopKeys},
      {"unknown table", "title = \"t\"\n\n[camm]\nspeed_rev_s = 1\n",
       "bad.toml:3: key 'camm' = {...}: unknown table; allowed keys at top level: " + kTopKeys},
      {"unknown sub-table", "[spring.extra]\nx = 1\n",
       "bad.toml:1: key 'spring.extra' = {...}: unknown table; allowed keys in [spring]: stiffness, precompression"},
      {"table given a value", "spring = 5\n",
       "bad.toml:1: key 'spring' = 5: must be a table ([spring]); allowed keys in [spring]: stiffness, precompression"},
      {"wrong type: string for number", "[follower]\nmass = \"heavy\"\n",
       "bad.toml:2: key 'follower.mass' = \"heavy\": must be a number"},
      {"wrong type: number for bool", "[contact]\nseparation = 1\n",
       "bad.toml:2: key 'contact.separation' = 1: must be true or false"},
      {"wrong type: number for string", "title = 3\n", "bad.toml:1: key 'title' = 3: must be a string"},
      {"wrong type: scalar for array", "[cam]\nradii = 2.0\n",
       "bad.toml:2: key 'cam.radii' = 2: must be an array of numbers"},
      {"wrong type: string in array", "[cam]\nradii = [2.0, 2.0,\n  \"x\", 2.0]\n",
       "bad.toml:3: key 'cam.radii[2]' = \"x\": must be a number"},
      {"wrong type: number for enum", "[follower]\nkind = 1\n",
       "bad.toml:2: key 'follower.kind' = 1: must be one of \"rigid\", \"elastic_bar\", \"network\""},
      {"negative mass", "[follower]\nmass = -1\n", "bad.toml:2: key 'follower.mass' = -1: must be > 0"},
      {"zero E", "[follower]\nkind = \"elastic_bar\"\nyoungs_modulus = 0\n",
       "bad.toml:3: key 'follower.youngs_modulus' = 0: must be > 0"},
      {"zero area", "[follower]\narea = 0.0\n", "bad.toml:2: key 'follower.area' = 0: must be > 0"},
      {"zero length", "[follower]\nlength = 0\n", "bad.toml:2: key 'follower.length' = 0: must be > 0"},
      {"elements = 0", "[follower]\nelements = 0\n",
       "bad.toml:2: key 'follower.elements' = 0: must be >= 1 and <= 10000000"},
      {"elements = 2.5", "[follower]\nelements = 2.5\n", "bad.toml:2: key 'follower.elements' = 2.5: must be an integer"},
      {"elements too many", "[follower]\nelements = 1e8\n",
       "bad.toml:2: key 'follower.elements' = 100000000: must be >= 1 and <= 10000000"},
      {"elements as string", "[follower]\nelements = \"40\"\n",
       "bad.toml:2: key 'follower.elements' = \"40\": must be an integer"},
      {"NaN value", "[spring]\nprecompression = nan\n",
       "bad.toml:2: key 'spring.precompression' = nan: must be a finite number"},
      {"inf value", "[cam]\nspeed_rev_s = inf\n", "bad.toml:2: key 'cam.speed_rev_s' = inf: must be a finite number"},
      {"-inf in array", "[cam]\nradii = [2, 2, -inf, 2, 3, 2, 2, 2]\n",
       "bad.toml:2: key 'cam.radii[2]' = -inf: must be a finite number"},
      {"NaN mass", "[follower]\nmass = nan\n", "bad.toml:2: key 'follower.mass' = nan: must be a finite number"},
      {"fewer than 4 knots", "[cam]\nangles_deg = [0, 90, 180]\nradii = [2, 2, 2]\n",
       "bad.toml:2: key 'cam.angles_deg' = [0, 90, 180]: must have at least 4 values (has 3)"},
      {"mismatched lengths", "[cam]\nangles_deg = [0, 90, 180, 270]\nradii = [2, 2, 2]\n",
       "bad.toml:3: key 'cam.radii' = [2, 2, 2]: must have as many values as cam.angles_deg (4), has 3"},
      {"mismatched lengths, long array", "[cam]\nangles_deg = [0, 30, 60, 90, 120, 150, 180, 210, 240, 270]\n",
       "bad.toml:2: key 'cam.radii' = [2, 2, 2, 2.1, 3, 2.1, 2, 2]: must have as many values as "
       "cam.angles_deg (10), has 8"},
      {"non-increasing angles", "[cam]\nangles_deg = [0, 90, 80, 270]\nradii = [2, 2, 2, 2]\n",
       "bad.toml:2: key 'cam.angles_deg[2]' = 80: must be > cam.angles_deg[1] = 90 (strictly increasing)"},
      {"duplicate angles", "[cam]\nangles_deg = [0,\n 90,\n 90,\n 270]\nradii = [2, 2, 2, 2]\n",
       "bad.toml:4: key 'cam.angles_deg[2]' = 90: must be > cam.angles_deg[1] = 90 (strictly increasing)"},
      {"angle span 360", "[cam]\nangles_deg = [0, 90, 180, 360]\nradii = [2, 2, 2, 2]\n",
       "bad.toml:2: key 'cam.angles_deg[3]' = 360: must be < cam.angles_deg[0] + 360 = 360 "
       "(the table spans less than 360 deg)"},
      {"non-positive radius", "[cam]\nangles_deg = [0, 90, 180, 270]\nradii = [2, 2, 0, 2]\n",
       "bad.toml:3: key 'cam.radii[2]' = 0: must be > 0"},
      {"negative circle radius", "[cam]\nprofile = \"circle\"\nradius = -2\n",
       "bad.toml:3: key 'cam.radius' = -2: must be > 0"},
      {"eccentricity >= radius", "[cam]\nprofile = \"circle\"\nradius = 1\neccentricity = 1\n",
       "bad.toml:4: key 'cam.eccentricity' = 1: must be < cam.radius = 1"},
      {"bad enum spelling", "[contact]\nmodel = \"pnalty\"\n",
       "bad.toml:2: key 'contact.model' = \"pnalty\": must be one of \"lee\", \"penalty\", \"holonomic\", \"event\""},
      {"bad integrator", "[solver]\nintegrator = \"rk45\"\n",
       "bad.toml:2: key 'solver.integrator' = \"rk45\": must be one of \"arkode-erk\", \"arkode-dirk\", "
       "\"cvode-bdf\", \"ida\""},
      {"ida with lee", "[solver]\nintegrator = \"ida\"\n",
       "bad.toml:2: key 'solver.integrator' = \"ida\": \"ida\" requires contact.model = \"holonomic\" "
       "(contact.model is \"lee\")"},
      {"ida with event", "[contact]\nmodel = \"event\"\n[solver]\nintegrator = \"ida\"\n",
       "bad.toml:4: key 'solver.integrator' = \"ida\": \"ida\" requires contact.model = \"holonomic\" "
       "(contact.model is \"event\")"},
      {"rtol = 0", "[solver]\nrtol = 0\n", "bad.toml:2: key 'solver.rtol' = 0: must be >= 1e-14 and <= 0.1"},
      {"rtol = 1", "[solver]\nrtol = 1.0\n", "bad.toml:2: key 'solver.rtol' = 1: must be >= 1e-14 and <= 0.1"},
      {"atol = 0", "[solver]\natol = 0\n", "bad.toml:2: key 'solver.atol' = 0: must be > 0 and <= 1"},
      {"negative max_step", "[solver]\nmax_step = -1e-3\n", "bad.toml:2: key 'solver.max_step' = -0.001: must be >= 0"},
      {"negative tol_u", "[contact]\ntol_u = -1e-8\n",
       "bad.toml:2: key 'contact.tol_u' = -1e-08: must be between 1e-14 and 1 (or 0 for the paper default); below 1e-14 the gap is round-off"},
      {"negative tol_v", "[contact]\ntol_v = -1\n", "bad.toml:2: key 'contact.tol_v' = -1: must be >= 0"},
      {"max_iterations = 0", "[contact]\nmax_iterations = 0\n",
       "bad.toml:2: key 'contact.max_iterations' = 0: must be >= 1 and <= 10000"},
      {"max_iterations too many", "[contact]\nmax_iterations = 10001\n",
       "bad.toml:2: key 'contact.max_iterations' = 10001: must be >= 1 and <= 10000"},
      {"penalty exponent 4", "[contact]\npenalty_exponent = 4\n",
       "bad.toml:2: key 'contact.penalty_exponent' = 4: must be >= 1 and <= 3"},
      {"zero penalty stiffness", "[contact]\npenalty_stiffness = 0\n",
       "bad.toml:2: key 'contact.penalty_stiffness' = 0: must be > 0"},
      {"negative initial gap", "[contact]\ninitial_gap = -0.1\n",
       "bad.toml:2: key 'contact.initial_gap' = -0.1: must be >= 0"},
      {"t_end = 0", "[run]\nt_end = 0\n", "bad.toml:2: key 'run.t_end' = 0: must be > 0"},
      {"output_dt > t_end", "[run]\nt_end = 0.5\noutput_dt = 1.0\n",
       "bad.toml:3: key 'run.output_dt' = 1: must be <= run.t_end = 0.5"},
      {"max_steps = 0", "[run]\nmax_steps = 0\n", "bad.toml:2: key 'run.max_steps' = 0: must be >= 1"},
      {"restitution 1.5", "[contact]\nrestitution = 1.5\n",
       "bad.toml:2: key 'contact.restitution' = 1.5: must be >= 0 and <= 1"},
      {"restitution with penalty", "[contact]\nmodel = \"penalty\"\nrestitution = 0.5\n",
       "bad.toml:3: key 'contact.restitution' = 0.5: must be 0 with contact.model \"penalty\" "
       "(restitution needs contact.model \"lee\" or \"event\")"},
      {"separation=false with penalty", "[contact]\nmodel = \"penalty\"\nseparation = false\n",
       "bad.toml:3: key 'contact.separation' = false: requires contact.model \"lee\" or \"holonomic\" "
       "(contact.model is \"penalty\")"},
      {"separation=false with event", "[contact]\nseparation = false\nmodel = \"event\"\n",
       "bad.toml:2: key 'contact.separation' = false: requires contact.model \"lee\" or \"holonomic\" "
       "(contact.model is \"event\")"},
      {"TOML syntax error", "title = \"t\"\n[cam]\nspeed_rev_s = \n",
       "bad.toml:3: Error while parsing key-value pair: expected value, saw '\\n'"},
      {"TOML duplicate key", "[cam]\nspeed_rev_s = 1\nspeed_rev_s = 2\n",
       "bad.toml:3: Error while parsing key-value pair: cannot redefine existing integer 'speed_rev_s'"},
      {"speed table not starting at 0", "[cam]\nspeed_table_t = [0.1, 0.5]\nspeed_table_rev_s = [1, 2]\n",
       "bad.toml:2: key 'cam.speed_table_t[0]' = 0.1: must be 0 (the speed table starts at t = 0)"},
      {"speed table lengths", "[cam]\nspeed_table_t = [0, 0.5]\nspeed_table_rev_s = [1, 2, 3]\n",
       "bad.toml:3: key 'cam.speed_table_rev_s' = [1, 2, 3]: must have as many values as cam.speed_table_t (2), "
       "has 3"},
      {"speed table not increasing", "[cam]\nspeed_table_t = [0, 0.5, 0.5]\nspeed_table_rev_s = [1, 2, 3]\n",
       "bad.toml:2: key 'cam.speed_table_t[2]' = 0.5: must be > cam.speed_table_t[1] = 0.5 (strictly increasing)"},
      {"lift profile without table", "[cam]\nprofile = \"lift\"\n",
       "bad.toml:2: key 'cam.lift_angles_deg' = []: must have at least 4 values for cam.profile = \"lift\" (has 0)"},
      {"lift below base circle",
       "[cam]\nprofile = \"lift\"\nbase_radius = 1\nlift_angles_deg = [0, 90, 180, 270]\nlift = [0, -1, 0, 0]\n",
       "bad.toml:5: key 'cam.lift[1]' = -1: must be > -cam.base_radius = -1 (base_radius + lift > 0)"},
  };
  ASSERT_GE(cases.size(), 20u);
  for (const auto& c : cases) EXPECT_EQ(error_of(c.toml), c.message) << "case: " << c.what;
}

TEST(SceneMalformed, ErrorFieldsAndLine) {
  try {
    parse_scene("\n\n[follower]\n\nmass = -1\n", "scene.toml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), "scene.toml");
    EXPECT_EQ(e.line(), 5);
    EXPECT_EQ(e.key(), "follower.mass");
    EXPECT_EQ(e.value(), "-1");
    EXPECT_EQ(e.rule(), "must be > 0");
  }
}

// ---------------------------------------------------------------- round trip

TEST(SceneRoundTrip, ToTomlParsesBackEqual) {
  std::vector<Scene> scenes = {paper_case("A"), paper_case("B1"), paper_case("B2"), Scene{},
                               load_scene_file(example("lift_cam.toml")), load_scene_file(example("circle_cam.toml"))};
  Scene odd = paper_case("A");
  odd.title = "quotes \" and \\ backslash\tand tab, unicode \u03b8";
  odd.cam.speed_rev_s = 0.1 + 0.2;  // needs 17 digits
  odd.cam.theta0_deg = 1.0 / 3.0;
  odd.cam.speed_table_t = {0, 0.1, 0.30000000000000004};
  odd.cam.speed_table_rev_s = {1e-300, 5, 2.5e10};
  odd.contact.max_iterations = 10000;
  odd.run.max_steps = 9'000'000'000'000LL;
  odd.contact.separation = false;
  odd.solver.atol = 5e-324 * 1e10;
  scenes.push_back(odd);
  for (Scene s : scenes) {
    resolve_defaults(s);
    const std::string text = to_toml(s);
    const Scene back = parse_scene(text, "roundtrip.toml");
    EXPECT_TRUE(back == s) << text;
    EXPECT_EQ(to_toml(back), text);
  }
}

TEST(SceneRoundTrip, EveryKeyWritten) {
  const std::string text = to_toml(Scene{});
  for (const char* key :
       {"title", "profile", "angles_deg", "radii", "base_radius", "lift_angles_deg", "lift", "radius", "eccentricity",
        "speed_rev_s", "speed_table_t", "speed_table_rev_s", "theta0_deg", "kind", "mass", "damping",
        "youngs_modulus", "area", "length", "elements", "mass_matrix", "rayleigh_alpha", "rayleigh_beta",
        "stiffness", "precompression", "model", "error_variant", "tol_u", "tol_v", "tol_a", "max_iterations",
        "separation", "restitution", "initial_gap", "penalty_law", "penalty_stiffness", "penalty_damping",
        "penalty_exponent", "integrator", "rtol", "atol", "linear_solver", "max_step", "initial_step", "t_end",
        "output_dt", "max_steps"})
    EXPECT_NE(text.find(std::string("\n") + key + " = "), std::string::npos) << key;
  EXPECT_NE(text.find("tol_u = 1e-08"), std::string::npos) << text;  // resolved
}

// ---------------------------------------------------------------- overrides

TEST(SceneOverride, CommonPaths) {
  Scene s = default_scene();
  apply_override(s, "cam.speed_rev_s=3");
  EXPECT_EQ(s.cam.speed_rev_s, 3.0);
  apply_override(s, "contact.model=penalty");  // bare word = string
  EXPECT_EQ(s.contact.model, ContactModel::Penalty);
  apply_override(s, "contact.model=\"event\"");
  EXPECT_EQ(s.contact.model, ContactModel::Event);
  apply_override(s, "follower.elements=400");
  EXPECT_EQ(s.follower.elements, 400);
  apply_override(s, " solver.rtol = 1e-9 ");
  EXPECT_EQ(s.solver.rtol, 1e-9);
  apply_override(s, "cam.radii=[2, 2, 2, 2.2, 3, 2.2, 2, 2]");
  EXPECT_EQ(s.cam.radii[3], 2.2);
  apply_override(s, "contact.model=lee");
  apply_override(s, "contact.separation=false");
  EXPECT_FALSE(s.contact.separation);
  apply_override(s, "title=My scene = fast");
  EXPECT_EQ(s.title, "My scene = fast");
  apply_override(s, "run.max_steps=12");
  EXPECT_EQ(s.run.max_steps, 12);
  EXPECT_EQ(s.source, "<built-in>");  // the scene's origin is kept
}

TEST(SceneOverride, EveryKeyWithItsOwnValueIsANoOp) {
  // Every key that to_toml writes can be set with --set; setting it to its current value
  // changes nothing.
  for (const char* name : {"A", "B2"}) {
    const Scene ref = paper_case(name);
    Scene s = ref;
    std::istringstream in(to_toml(ref));
    std::string line, table;
    int n = 0;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      if (line[0] == '[') {
        table = line.substr(1, line.size() - 2);
        continue;
      }
      const auto eq = line.find(" = ");
      ASSERT_NE(eq, std::string::npos) << line;
      const std::string key = (table.empty() ? "" : table + ".") + line.substr(0, eq);
      ASSERT_NO_THROW(apply_override(s, key + "=" + line.substr(eq + 3))) << key;
      EXPECT_TRUE(s == ref) << key;
      ++n;
    }
    // 47 + contact.lee_step, run.land_on_output, run.poincare_angle_deg,
    // run.settle_revolutions, run.period_tol; + 13 cam keys of issue 24 (law, arc,
    // follower face, breakpoints, Hertz); + 6 oscillating-follower keys (follower_motion,
    // pivot_x, pivot_y, arm_length, pad_offset, valve_arm); run.designer_columns;
    // solver.stack (issue 23); + 7 arc-list keys of issue 37 (cam.arc_centre_x, _y, _r,
    // _deg, arc_radius, arc_from_deg, arc_to_deg); cam.lift_table
    EXPECT_EQ(n, 81);
  }
}

TEST(SceneOverride, EveryKeyOfCaseAOntoB2GivesCaseA) {
  Scene s = default_scene();
  std::istringstream in(to_toml(paper_case("A")));
  std::string line, table;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] == '[') {
      table = line.substr(1, line.size() - 2);
      continue;
    }
    const auto eq = line.find(" = ");
    const std::string key = (table.empty() ? "" : table + ".") + line.substr(0, eq);
    ASSERT_NO_THROW(apply_override(s, key + "=" + line.substr(eq + 3))) << key;
  }
  EXPECT_TRUE(s == paper_case("A")) << to_toml(s);
}

TEST(SceneOverride, FollowerKindReresolvesDefaultTolU) {
  Scene a = paper_case("A");  // tol_u = 1e-8, the rigid default
  apply_override(a, "follower.kind=elastic_bar");
  EXPECT_EQ(a.contact.tol_u, 1e-7);
  apply_override(a, "follower.kind=rigid");
  EXPECT_EQ(a.contact.tol_u, 1e-8);

  Scene u;  // unresolved: tol_u = 0
  apply_override(u, "follower.kind=elastic_bar");
  EXPECT_EQ(u.contact.tol_u, 1e-7);

  Scene x = paper_case("A");
  apply_override(x, "contact.tol_u=1e-9");  // explicit: kept
  apply_override(x, "follower.kind=elastic_bar");
  EXPECT_EQ(x.contact.tol_u, 1e-9);

  Scene y = paper_case("A");
  apply_override(y, "contact.tol_u=0");  // explicit 0 = paper default
  EXPECT_EQ(y.contact.tol_u, 1e-8);
}

TEST(SceneOverride, Errors) {
  const Scene s = paper_case("A");
  EXPECT_EQ(override_error(s, "cam.speed_rev_s"),
            "--set: expected KEY=VALUE (e.g. cam.speed_rev_s=3), got 'cam.speed_rev_s'");
  EXPECT_EQ(override_error(s, "=3"), "--set: expected KEY=VALUE (e.g. cam.speed_rev_s=3), got '=3'");
  EXPECT_EQ(override_error(s, "cam.sped_rev_s=3"),
            "--set: key 'cam.sped_rev_s' = 3: unknown key; allowed keys in [cam]: " + kCamKeys);
  EXPECT_EQ(override_error(s, "cam.speed.rev_s=3"),
            "--set: key 'cam.speed.rev_s' = 3: unknown key; allowed keys in [cam]: " + kCamKeys);
  EXPECT_EQ(override_error(s, "foo.bar=1"),
            "--set: key 'foo.bar' = 1: unknown key; allowed keys at top level: " + kTopKeys);
  EXPECT_EQ(override_error(s, "speed_rev_s=1"),
            "--set: key 'speed_rev_s' = 1: unknown key; allowed keys at top level: " + kTopKeys);
  EXPECT_EQ(override_error(s, "follower.mass=-2"), "--set: key 'follower.mass' = -2: must be > 0");
  EXPECT_EQ(override_error(s, "follower.mass=heavy"), "--set: key 'follower.mass' = \"heavy\": must be a number");
  EXPECT_EQ(override_error(s, "follower.elements=2.5"), "--set: key 'follower.elements' = 2.5: must be an integer");
  EXPECT_EQ(override_error(s, "follower.mass=nan"), "--set: key 'follower.mass' = nan: must be a finite number");
  EXPECT_EQ(override_error(s, "contact.model=pnalty"),
            "--set: key 'contact.model' = \"pnalty\": must be one of \"lee\", \"penalty\", \"holonomic\", \"event\"");
  EXPECT_EQ(override_error(s, "cam.radii=[1,2"), "--set: key 'cam.radii' = \"[1,2\": must be an array of numbers");
  EXPECT_EQ(override_error(s, "cam.radii=[2,2,2]"),
            "--set: key 'cam.radii' = [2, 2, 2]: must have as many values as cam.angles_deg (8), has 3");
  EXPECT_EQ(override_error(s, "run.output_dt=2"), "--set: key 'run.output_dt' = 2: must be <= run.t_end = 1");
  EXPECT_EQ(override_error(s, "cam=3"),
            "--set: key 'cam' = 3: must be a table ([cam]); allowed keys in [cam]: " + kCamKeys);
  // Cross-field rule triggered by an override.
  Scene p = s;
  apply_override(p, "contact.model=penalty");
  EXPECT_EQ(override_error(p, "contact.separation=false"),
            "--set: key 'contact.separation' = false: requires contact.model \"lee\" or \"holonomic\" "
            "(contact.model is \"penalty\")");
  // A failed override leaves the scene unchanged.
  Scene q = s;
  EXPECT_THROW(apply_override(q, "follower.mass=-2"), SceneError);
  EXPECT_TRUE(q == s);
}

// Equality comes from the key table (scene.cpp kFields): every kind of key in every table
// takes part, and the per-table operators agree with the Scene's.
TEST(SceneEquality, EveryKindOfKeyInEveryTableTakesPart) {
  const camdyn::Scene a = camdyn::default_scene();
  EXPECT_TRUE(a == camdyn::Scene(a));
  struct Case {
    const char* what;
    void (*mutate)(camdyn::Scene&);
    bool (*table_equal)(const camdyn::Scene&, const camdyn::Scene&);
  };
  const Case cases[] = {
      {"title", [](camdyn::Scene& s) { s.title += "x"; }, nullptr},
      {"cam.lift (array)", [](camdyn::Scene& s) { s.cam.lift.push_back(1.0); },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.cam == y.cam; }},
      {"cam.theta0_deg (real)", [](camdyn::Scene& s) { s.cam.theta0_deg += 1.0; },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.cam == y.cam; }},
      {"follower.elements (int)", [](camdyn::Scene& s) { s.follower.elements += 1; },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.follower == y.follower; }},
      {"follower.mass_matrix (enum)",
       [](camdyn::Scene& s) {
         s.follower.mass_matrix = s.follower.mass_matrix == camdyn::MassMatrixKind::Lumped
                                      ? camdyn::MassMatrixKind::Consistent
                                      : camdyn::MassMatrixKind::Lumped;
       },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.follower == y.follower; }},
      {"spring.precompression", [](camdyn::Scene& s) { s.spring.precompression *= 2.0; },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.spring == y.spring; }},
      {"contact.separation (bool)", [](camdyn::Scene& s) { s.contact.separation = !s.contact.separation; },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.contact == y.contact; }},
      {"solver.rtol", [](camdyn::Scene& s) { s.solver.rtol *= 2.0; },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.solver == y.solver; }},
      {"run.max_steps (int)", [](camdyn::Scene& s) { s.run.max_steps += 1; },
       [](const camdyn::Scene& x, const camdyn::Scene& y) { return x.run == y.run; }},
      {"network.nodes", [](camdyn::Scene& s) { s.network.nodes.push_back(camdyn::NodeSpec{"n", 1.0, 0.0, 0.0}); },
       nullptr},
  };
  for (const Case& c : cases) {
    camdyn::Scene b = a;
    c.mutate(b);
    EXPECT_FALSE(a == b) << c.what;
    EXPECT_TRUE(a != b) << c.what;
    if (c.table_equal) EXPECT_FALSE(c.table_equal(a, b)) << c.what;
  }
}

// The key table carries each key's own rule (src/scene/scene.cpp, fields()): every real key of
// every table refuses a non-finite value through the same path, so a new key is checked
// without another line in the Validator; and a table row's range rule gives its message.
TEST(SceneKeyRules, EveryRealKeyRefusesNaNAndRangesComeFromTheTable) {
  const camdyn::Scene base = camdyn::default_scene();
  int checked = 0;
  camdyn::for_each_scene_entry(base, [&](const camdyn::SceneEntry& e) {
    if (e.kind != camdyn::SceneEntry::Kind::Real) return;
    const std::string key = e.table.empty() ? e.key : e.table + "." + e.key;
    camdyn::Scene s = base;
    try {
      camdyn::apply_override(s, key + "=nan");
      ADD_FAILURE() << key << " = nan accepted";
    } catch (const camdyn::SceneError& err) {
      EXPECT_EQ(err.key(), key);
      EXPECT_EQ(err.rule(), "must be a finite number") << key;
    }
    ++checked;
  });
  EXPECT_GE(checked, 30);  // 30 real keys today
  struct Row {
    const char* set;
    const char* key;
    const char* rule;
  };
  const Row rows[] = {
      {"follower.mass=0", "follower.mass", "must be > 0"},
      {"follower.rayleigh_beta=-1", "follower.rayleigh_beta", "must be >= 0"},
      {"contact.restitution=1.5", "contact.restitution", "must be >= 0 and <= 1"},
      {"solver.atol=2", "solver.atol", "must be > 0 and <= 1"},
      {"contact.tol_u=1e-20", "contact.tol_u",
       "must be between 1e-14 and 1 (or 0 for the paper default); below 1e-14 the gap is round-off"},
      {"run.period_tol=0", "run.period_tol", "must be > 0 and <= 1"},
  };
  for (const Row& r : rows) {
    camdyn::Scene s = base;
    try {
      camdyn::apply_override(s, r.set);
      ADD_FAILURE() << r.set << " accepted";
    } catch (const camdyn::SceneError& err) {
      EXPECT_EQ(err.key(), r.key) << r.set;
      EXPECT_EQ(err.rule(), r.rule) << r.set;
    }
  }
}
