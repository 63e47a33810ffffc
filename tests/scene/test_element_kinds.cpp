// The element kinds' table (src/scene/element_kinds.cpp) drives reading, writing, equality
// and --set of every [[elements]] key: for every kind and every key of it, a changed value
// survives to_toml → parse_scene and arrives through `--set elements.NAME.KEY`; the truth is
// the value set on the ElementSpec member directly.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "scene/element_kinds.hpp"
#include "scene/key_table.hpp"
#include "test_support.hpp"

namespace {

using camdyn::ElementKind;
using camdyn::ElementSpec;
using camdyn::Scene;
using camdyn::scene_detail::ElementField;
using camdyn::scene_detail::ElementKindInfo;

/// The OHC bucket-tappet example with one more element "x" of `kind` on its valve (a lever
/// drives a new node "extra"), every key of the kind given a valid value.
Scene scene_with(ElementKind kind) {
  Scene s = camdyn::load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  ElementSpec e;
  e.kind = kind;
  e.name = "x";
  e.nodes = {"valve", "ground"};
  switch (kind) {
    case ElementKind::Spring:
      e.stiffness = 1e4;
      e.preload = 10.0;
      e.mass = 0.01;
      e.masses = 2;
      e.free_length = 0.05;
      e.solid_length = 0.02;
      e.coil_restitution = 0.2;
      break;
    case ElementKind::Dashpot: e.damping = 3.0; break;
    case ElementKind::Bar:
      e.mass = 0.01;
      e.youngs_modulus = 2e11;
      e.area = 1e-5;
      e.length = 0.1;
      e.elements = 2;
      break;
    case ElementKind::Lever: {
      camdyn::NodeSpec extra;
      extra.name = "extra";
      extra.mass = 0.01;
      s.network.nodes.push_back(extra);
      e.nodes = {"valve", "extra"};
      e.ratio = 1.5;
      break;
    }
    case ElementKind::ProgressiveSpring:
      e.deflections = {0.0, 0.01, 0.02};
      e.forces = {0.0, 100.0, 300.0};
      e.installed_deflection = 0.001;
      break;
    case ElementKind::GuideFriction:
      e.friction_coefficient = 0.1;
      e.normal_load = 5.0;
      break;
    case ElementKind::GasLoad:
      e.crank_angles_deg = {0.0, 90.0, 180.0};
      e.pressures = {1e5, 2e5, 1e5};
      e.area = 1e-3;
      break;
    case ElementKind::HydraulicLashAdjuster:
      e.area = 1e-4;
      e.stiffness = 1e3;
      e.preload = 5.0;
      e.chamber_volume = 1e-7;
      e.plunger_diameter = 0.01;
      e.leak_clearance = 5e-6;
      e.leak_length = 0.005;
      e.viscosity = 0.01;
      e.supply_pressure = 2e5;
      e.check_area = 1e-6;
      // the check valve as a ball, so that each of its keys can change on its own
      e.check_ball_mass = 3e-5;
      e.check_ball_stiffness = 300.0;
      e.check_seat_diameter = 1.4e-3;
      e.check_seat_stiffness = 1e6;
      break;
  }
  s.network.elements.push_back(e);
  camdyn::validate(s);
  return s;
}

/// Another valid value of field f of e (set on e); its TOML text in `text`.
void change(const ElementField& f, ElementSpec& e, std::string& text) {
  switch (f.type) {
    case ElementField::Type::Real: {
      double& v = e.*f.real;
      v = v != 0.0 ? v * 1.25 : 0.5;
      text = camdyn::detail::format_number(v);
      break;
    }
    case ElementField::Type::OptionalReal:
      e.*f.optional = 0.75;
      text = "0.75";
      break;
    case ElementField::Type::Int:
      e.*f.integer += 1;
      text = std::to_string(e.*f.integer);
      break;
    case ElementField::Type::Reals: {
      std::vector<double>& v = e.*f.reals;
      if (std::string(f.key) == "coil_gaps")  // masses + 1 gaps adding up to the travel to solid
        v = {0.01, 0.009, 0.01};
      else
        for (double& x : v) x *= 1.25;
      text = "[";
      for (std::size_t i = 0; i < v.size(); ++i) text += (i ? ", " : "") + camdyn::detail::format_number(v[i]);
      text += "]";
      break;
    }
    case ElementField::Type::MassMatrix:
      e.*f.mass_matrix = camdyn::BarMass::Consistent;
      text = "\"consistent\"";
      break;
  }
}

TEST(ElementKinds, EveryKeyOfEveryKindRoundTripsThroughTomlAndSet) {
  int checked = 0;
  for (const ElementKindInfo& kind : camdyn::scene_detail::element_kinds()) {
    SCOPED_TRACE(kind.name);
    ASSERT_FALSE(kind.fields.empty());
    const Scene base = scene_with(kind.kind);
    // The unchanged scene reads back equal.
    EXPECT_TRUE(camdyn::parse_scene(camdyn::to_toml(base), "<toml>") == base);
    for (const ElementField& f : kind.fields) {
      SCOPED_TRACE(f.key);
      Scene changed = base;
      std::string text;
      change(f, changed.network.elements.back(), text);
      ASSERT_FALSE(changed == base) << "the change of " << f.key << " is not seen by operator==";
      ASSERT_NO_THROW(camdyn::validate(changed)) << text;
      // to_toml → parse_scene gives the changed scene back (the coil-clash keys are written
      // because solid_length > 0; an unset coil_restitution is not written).
      const std::string toml = camdyn::to_toml(changed);
      EXPECT_NE(toml.find(std::string(f.key) + " = "), std::string::npos) << toml;
      Scene read;
      ASSERT_NO_THROW(read = camdyn::parse_scene(toml, "<toml>"));
      EXPECT_TRUE(read == changed);
      // --set elements.x.KEY=VALUE on the base gives the same scene.
      Scene set = base;
      ASSERT_NO_THROW(camdyn::apply_override(set, "elements.x." + std::string(f.key) + "=" + text));
      EXPECT_TRUE(set == changed) << "--set elements.x." << f.key << "=" << text;
      ++checked;
    }
  }
  EXPECT_GT(checked, 40);
}

// A key of another kind is refused through --set with the kind's allowed keys, which come
// from the same table.
TEST(ElementKinds, SetRefusesAKeyTheKindDoesNotTake) {
  Scene s = scene_with(ElementKind::Dashpot);
  try {
    camdyn::apply_override(s, "elements.x.stiffness=5");
    FAIL() << "accepted";
  } catch (const camdyn::SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--set: key 'elements.x.stiffness' = 5: not a key of a dashpot element; allowed keys of a dashpot "
              "element: name, type, nodes, damping");
  }
}

}  // namespace
