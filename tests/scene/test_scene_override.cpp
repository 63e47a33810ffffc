// Tests of scene overrides (--set), scene equality and the key table's rules.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "scene_test_helpers.hpp"

using namespace camdyn;
using namespace scene_test;

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
    // _deg, arc_radius, arc_from_deg, arc_to_deg); jump.settle_revolutions,
    // jump.judge_revolutions (issue 38); cam.lift_table; run.element_forces; + 14 [camshaft]
    // keys (issue 40); + 4 cam friction keys (friction_coefficient, friction_static_coefficient,
    // friction_stribeck_speed, roller_slip); + 9 [criteria], 3 [lubricant] keys and
    // run.valve_node (issue 38); camshaft.drive (issue 40); + 4 [synthesis] keys (issue 37:
    // ratio, valve_end_angle_deg, lash, ramp_deg)
    EXPECT_EQ(n, 120);
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
