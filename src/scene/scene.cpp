// camdyn — scene description: TOML parsing, equality (loading, defaults and the paper cases:
// scene/load.cpp).
//
// One table of field descriptors (kFields) drives everything: parsing a TOML table into a
// Scene, converting a Scene back to a TOML table (used by apply_override, so overrides go
// through exactly the same parse and validation path as files), writing to_toml, and the
// "allowed keys" lists of error messages. Enum names, SceneError and message formatting:
// scene_format.cpp; validation: scene_validate.cpp; --set: scene_override.cpp; to_toml and
// the key table as data: scene_write.cpp.
#include "camdyn/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include <toml++/toml.h>

#include "scene/detail.hpp"
#include "scene/element_kinds.hpp"
#include "scene/fields.hpp"

namespace camdyn {

using namespace scene_detail;  // scene_detail.hpp, scene_fields.hpp

// ---------------------------------------------------------------- equality

bool operator==(const NodeSpec& a, const NodeSpec& b) {
  return a.name == b.name && a.mass == b.mass && a.initial_displacement == b.initial_displacement &&
         a.initial_velocity == b.initial_velocity;
}
bool operator==(const ElementSpec& a, const ElementSpec& b) {
  return a.name == b.name && a.kind == b.kind && a.nodes == b.nodes && element_fields_equal(a, b);
}
bool operator==(const ContactPointSpec& a, const ContactPointSpec& b) {
  return a.name == b.name && a.kind == b.kind && a.nodes == b.nodes && a.clearance == b.clearance &&
         a.side == b.side && a.restitution == b.restitution && a.penalty_stiffness == b.penalty_stiffness &&
         a.penalty_damping == b.penalty_damping;
}
bool operator==(const NetworkSpec& a, const NetworkSpec& b) {
  return a.nodes == b.nodes && a.elements == b.elements && a.contacts == b.contacts;
}
// (the tables' equality, and the Scene's, come from the key table: see after fields())

namespace {


Field mk(const char* t, const char* k, FK kind) {
  Field f;
  f.table = t;
  f.key = k;
  f.kind = kind;
  return f;
}

#define F_REAL(T, M)                                           \
  [] {                                                         \
    Field f = mk(#T, #M, FK::Real);                            \
    f.real = [](Scene& s) -> double& { return s.T.M; };        \
    return f;                                                  \
  }()
#define F_ARR(T, M)                                                     \
  [] {                                                                  \
    Field f = mk(#T, #M, FK::Arr);                                      \
    f.arr = [](Scene& s) -> std::vector<double>& { return s.T.M; };     \
    return f;                                                           \
  }()
#define F_BOOL(T, M)                                        \
  [] {                                                      \
    Field f = mk(#T, #M, FK::Bool);                         \
    f.boolean = [](Scene& s) -> bool& { return s.T.M; };    \
    return f;                                               \
  }()
#define F_INT(T, M, LO, HI)                                                               \
  [] {                                                                                    \
    Field f = mk(#T, #M, FK::Int);                                                        \
    f.get_int = [](const Scene& s) -> long long { return s.T.M; };                        \
    f.set_int = [](Scene& s, long long v) { s.T.M = static_cast<decltype(s.T.M)>(v); };   \
    f.imin = LO;                                                                          \
    f.imax = HI;                                                                          \
    return f;                                                                             \
  }()
#define F_ENUM(T, M, NAMES)                                                            \
  [] {                                                                                 \
    Field f = mk(#T, #M, FK::Enum);                                                    \
    f.get_enum = [](const Scene& s) -> const char* { return to_string(s.T.M); };       \
    f.set_enum = [](Scene& s, std::string_view v) { return parse_enum(v, &s.T.M); };   \
    f.allowed = enum_names(NAMES);                                                     \
    return f;                                                                          \
  }()

const char* const kTables[] = {"cam", "follower", "spring", "contact", "solver", "run", "jump", "criteria", "lubricant",
                               "camshaft", "synthesis"};

Field ruled(Field f, Rule r, double lo, double hi = 0, const char* note = "") {
  f.rule = r;
  f.lo = lo;
  f.hi = hi;
  f.note = note;
  return f;
}

}  // namespace

namespace scene_detail {

const std::vector<Field>& fields() {
  static const std::vector<Field> kFields = [] {
    std::vector<Field> v;
    {
      Field f = mk("", "title", FK::Str);
      f.str = [](Scene& s) -> std::string& { return s.title; };
      v.push_back(f);
    }
    v.push_back(F_ENUM(cam, profile, kProfileNames));
    v.push_back(F_ARR(cam, angles_deg));
    v.push_back(F_ARR(cam, radii));
    v.push_back(ruled(F_REAL(cam, base_radius), Rule::Gt, 0));
    v.push_back(F_ARR(cam, lift_angles_deg));
    v.push_back(F_ARR(cam, lift));
    v.push_back(ruled(F_REAL(cam, radius), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(cam, eccentricity), Rule::Ge, 0));
    v.push_back(F_REAL(cam, speed_rev_s));
    v.push_back(F_ARR(cam, speed_table_t));
    v.push_back(F_ARR(cam, speed_table_rev_s));
    v.push_back(F_REAL(cam, theta0_deg));
    {
      Field f = mk("cam", "law", FK::Str);
      f.str = [](Scene& s) -> std::string& { return s.cam.law; };
      v.push_back(f);
    }
    {
      Field f = mk("cam", "lift_table", FK::Str);
      f.str = [](Scene& s) -> std::string& { return s.cam.lift_table; };
      v.push_back(f);
    }
    v.push_back(ruled(F_REAL(cam, nose_radius), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(cam, nose_distance), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(cam, flank_radius), Rule::Gt, 0));
    v.push_back(F_ARR(cam, arc_centre_x));
    v.push_back(F_ARR(cam, arc_centre_y));
    v.push_back(F_ARR(cam, arc_centre_r));
    v.push_back(F_ARR(cam, arc_centre_deg));
    v.push_back(F_ARR(cam, arc_radius));
    v.push_back(F_ARR(cam, arc_from_deg));
    v.push_back(F_ARR(cam, arc_to_deg));
    v.push_back(F_ENUM(cam, follower_face, kFaceNames));
    v.push_back(F_REAL(cam, follower_offset));
    v.push_back(ruled(F_REAL(cam, roller_radius), Rule::Ge, 0));
    v.push_back(F_ENUM(cam, follower_motion, kMotionNames));
    v.push_back(F_REAL(cam, pivot_x));
    v.push_back(F_REAL(cam, pivot_y));
    v.push_back(ruled(F_REAL(cam, arm_length), Rule::Ge, 0));
    v.push_back(F_REAL(cam, pad_offset));
    v.push_back(ruled(F_REAL(cam, valve_arm), Rule::Ge, 0));
    v.push_back(F_BOOL(cam, land_on_breaks));
    v.push_back(ruled(F_REAL(cam, width), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(cam, youngs_modulus), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(cam, poisson_ratio), Rule::In, 0, 0.4999));
    v.push_back(ruled(F_REAL(cam, follower_youngs_modulus), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(cam, follower_poisson_ratio), Rule::In, 0, 0.4999));
    v.push_back(ruled(F_REAL(cam, friction_coefficient), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(cam, friction_static_coefficient), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(cam, friction_stribeck_speed), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(cam, roller_slip), Rule::In, 0, 1));

    v.push_back(F_ENUM(follower, kind, kFollowerNames));
    v.push_back(ruled(F_REAL(follower, mass), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(follower, damping), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(follower, youngs_modulus), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(follower, area), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(follower, length), Rule::Gt, 0));
    v.push_back(F_INT(follower, elements, 1, 10000000));
    v.push_back(F_ENUM(follower, mass_matrix, kMassNames));
    v.push_back(ruled(F_REAL(follower, rayleigh_alpha), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(follower, rayleigh_beta), Rule::Ge, 0));

    v.push_back(ruled(F_REAL(spring, stiffness), Rule::Ge, 0));
    v.push_back(F_REAL(spring, precompression));

    v.push_back(F_ENUM(contact, model, kContactNames));
    v.push_back(F_ENUM(contact, error_variant, kVariantNames));
    v.push_back(F_ENUM(contact, lee_step, kLeeStepNames));
    v.push_back(ruled(F_REAL(contact, tol_u), Rule::ZeroOrIn, 1e-14, 1.0,
                       "must be between 1e-14 and 1 (or 0 for the paper default); below 1e-14 the gap is round-off"));
    v.push_back(ruled(F_REAL(contact, tol_v), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(contact, tol_a), Rule::Ge, 0));
    v.push_back(F_INT(contact, max_iterations, 1, 10000));
    v.push_back(F_BOOL(contact, separation));
    v.push_back(ruled(F_REAL(contact, restitution), Rule::In, 0, 1));
    v.push_back(ruled(F_REAL(contact, initial_gap), Rule::Ge, 0));
    v.push_back(F_ENUM(contact, penalty_law, kPenaltyNames));
    v.push_back(ruled(F_REAL(contact, penalty_stiffness), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(contact, penalty_damping), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(contact, penalty_exponent), Rule::In, 1, 3));

    v.push_back(F_ENUM(solver, integrator, kIntegratorNames));
    v.push_back(ruled(F_REAL(solver, rtol), Rule::In, 1e-14, 0.1));
    v.push_back(ruled(F_REAL(solver, atol), Rule::GtLe, 0, 1));
    v.push_back(F_ENUM(solver, linear_solver, kLinSolNames));
    v.push_back(ruled(F_REAL(solver, max_step), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(solver, initial_step), Rule::Ge, 0));
    v.push_back(F_ENUM(solver, stack, kStackNames));

    v.push_back(ruled(F_REAL(run, t_end), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(run, output_dt), Rule::Ge, 0));
    v.push_back(F_BOOL(run, land_on_output));
    v.push_back(F_INT(run, max_steps, 1, LLONG_MAX));
    v.push_back(F_REAL(run, poincare_angle_deg));
    v.push_back(F_INT(run, settle_revolutions, 0, 1000000000));
    v.push_back(ruled(F_REAL(run, period_tol), Rule::GtLe, 0, 1));
    v.push_back(F_BOOL(run, designer_columns));
    v.push_back(F_BOOL(run, element_forces));
    {
      Field f = mk("run", "valve_node", FK::Str);
      f.str = [](Scene& s) -> std::string& { return s.run.valve_node; };
      v.push_back(f);
    }

    v.push_back(F_INT(jump, settle_revolutions, 0, 10000));
    v.push_back(F_INT(jump, judge_revolutions, 1, 10000));
    {
      const char* note = "must be > 0 (or 0: no criterion)";
      v.push_back(ruled(F_REAL(criteria, max_seating_velocity), Rule::ZeroOrIn, 1e-50, 1e50, note));
      v.push_back(ruled(F_REAL(criteria, max_bounce_height), Rule::ZeroOrIn, 1e-50, 1e50, note));
      v.push_back(F_INT(criteria, max_bounce_count, -1, 1000000));
      v.push_back(ruled(F_REAL(criteria, min_force_margin), Rule::ZeroOrIn, 1e-50, 1e50, note));
      v.push_back(ruled(F_REAL(criteria, max_hertz_stress), Rule::ZeroOrIn, 1e-50, 1e50, note));
      v.push_back(ruled(F_REAL(criteria, min_film_thickness), Rule::ZeroOrIn, 1e-50, 1e50, note));
      v.push_back(ruled(F_REAL(criteria, min_lambda), Rule::ZeroOrIn, 1e-50, 1e50, note));
      v.push_back(ruled(F_REAL(criteria, max_ramp_velocity), Rule::ZeroOrIn, 1e-50, 1e50, note));
      v.push_back(ruled(F_REAL(criteria, max_lift_deviation), Rule::ZeroOrIn, 1e-50, 1e50, note));
    }
    v.push_back(ruled(F_REAL(lubricant, viscosity), Rule::ZeroOrIn, 1e-50, 1e50,
                      "must be > 0 (or 0: no oil film computed)"));
    v.push_back(ruled(F_REAL(lubricant, pressure_viscosity), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(lubricant, roughness), Rule::Ge, 0));
    v.push_back(F_ARR(camshaft, inertias));
    v.push_back(F_ARR(camshaft, stiffnesses));
    v.push_back(ruled(F_REAL(camshaft, rayleigh_alpha), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(camshaft, rayleigh_beta), Rule::Ge, 0));
    v.push_back(F_ARR(camshaft, cam_stations));
    v.push_back(F_ARR(camshaft, cam_offsets_deg));
    v.push_back(F_ARR(camshaft, cam_offsets_crank_deg));
    v.push_back(F_ARR(camshaft, contact_cams));
    v.push_back(F_INT(camshaft, drive_station, 0, 1000000));
    v.push_back(ruled(F_REAL(camshaft, drive_stiffness), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(camshaft, drive_damping), Rule::Ge, 0));
    v.push_back(F_ARR(camshaft, crank_orders));
    v.push_back(F_ARR(camshaft, crank_amplitudes_deg));
    v.push_back(F_ARR(camshaft, crank_phases_deg));
    v.push_back(F_ENUM(camshaft, drive, kCamshaftDriveNames));
    v.push_back(ruled(F_REAL(synthesis, ratio), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(synthesis, valve_end_angle_deg), Rule::Finite, 0));
    v.push_back(ruled(F_REAL(synthesis, lash), Rule::Ge, 0));
    v.push_back(ruled(F_REAL(synthesis, ramp_deg), Rule::Ge, 0));
    return v;
  }();
  return kFields;
}

}  // namespace scene_detail

namespace {

// ---------------------------------------------------------------- equality (from kFields)

// Two scenes agree on every key of `table` ("" the top-level keys; nullptr every table):
// a new key in kFields is compared without another line here. Doubles compare exactly.
bool same_keys(const Scene& a, const Scene& b, const char* table) {
  Scene& x = const_cast<Scene&>(a);  // the accessors hand out references: only read here
  Scene& y = const_cast<Scene&>(b);
  for (const Field& f : fields()) {
    if (table && std::strcmp(f.table, table) != 0) continue;
    switch (f.kind) {
      case FK::Real:
        if (!(f.real(x) == f.real(y))) return false;
        break;
      case FK::Arr:
        if (f.arr(x) != f.arr(y)) return false;
        break;
      case FK::Bool:
        if (f.boolean(x) != f.boolean(y)) return false;
        break;
      case FK::Str:
        if (f.str(x) != f.str(y)) return false;
        break;
      case FK::Int:
        if (f.get_int(a) != f.get_int(b)) return false;
        break;
      case FK::Enum:
        if (std::strcmp(f.get_enum(a), f.get_enum(b)) != 0) return false;
        break;
    }
  }
  return true;
}
template <class Spec>
bool same_table(const Spec& a, const Spec& b, Spec Scene::*member, const char* table) {
  Scene x, y;
  x.*member = a;
  y.*member = b;
  return same_keys(x, y, table);
}

#undef F_REAL
#undef F_ARR
#undef F_BOOL
#undef F_INT
#undef F_ENUM

const Field* find_field(std::string_view table, std::string_view key) {
  for (const auto& f : fields())
    if (table == f.table && key == f.key) return &f;
  return nullptr;
}

}  // namespace

namespace scene_detail {

bool is_table_name(std::string_view s) {
  for (const char* t : kTables)
    if (s == t) return true;
  return false;
}

std::string allowed_top() {
  std::vector<std::string> k{"title"};
  for (const char* t : kTables) k.emplace_back(t);
  for (const char* a : {"nodes", "elements", "contacts"}) k.emplace_back(a);
  return "allowed keys at top level: " + join(k, ", ");
}

}  // namespace scene_detail

namespace {


std::string allowed_in(std::string_view table) {
  std::vector<std::string> k;
  for (const auto& f : fields()) {
    if (table != f.table) continue;
    k.emplace_back(f.key);
    // The input-only keys in a designer's units (scene_units.cpp), after the key they replace.
    if (f.path() == "cam.speed_rev_s") k.insert(k.end(), {"speed_rpm", "rpm_of"});
    if (f.path() == "run.t_end") k.emplace_back("revolutions");
  }
  return "allowed keys in [" + std::string(table) + "]: " + join(k, ", ");
}


void read_field(const Field& f, const toml::node& n, Scene& s, const std::string& file, bool use_lines,
                LineMap& lines) {
  const std::string key = f.path();
  const int line = use_lines ? line_of(n) : 0;
  lines[key] = line;
  switch (f.kind) {
    case FK::Real:
      if (auto i = n.as_integer())
        f.real(s) = static_cast<double>(i->get());
      else if (auto d = n.as_floating_point())
        f.real(s) = d->get();
      else
        fail(file, line, key, fmt_node(n), "must be a number");
      return;
    case FK::Int: {
      const long long v = toml_integer(n, file, line, key);
      if (v < f.imin || v > f.imax) fail(file, line, key, fmt_node(n), range_rule(f.imin, f.imax));
      f.set_int(s, v);
      return;
    }
    case FK::Bool:
      if (auto b = n.as_boolean())
        f.boolean(s) = b->get();
      else
        fail(file, line, key, fmt_node(n), "must be true or false");
      return;
    case FK::Str:
      if (auto str = n.as_string())
        f.str(s) = str->get();
      else
        fail(file, line, key, fmt_node(n), "must be a string");
      return;
    case FK::Enum: {
      auto str = n.as_string();
      if (!str || !f.set_enum(s, str->get())) fail(file, line, key, fmt_node(n), one_of(f.allowed));
      return;
    }
    case FK::Arr: {
      auto a = n.as_array();
      if (!a) fail(file, line, key, fmt_node(n), "must be an array of numbers");
      std::vector<double> v;
      v.reserve(a->size());
      for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::node& e = *a->get(i);
        const std::string ek = key + "[" + std::to_string(i) + "]";
        const int el = use_lines ? line_of(e) : 0;
        lines[ek] = el;
        if (auto ii = e.as_integer())
          v.push_back(static_cast<double>(ii->get()));
        else if (auto d = e.as_floating_point())
          v.push_back(d->get());
        else
          fail(file, el, ek, fmt_node(e), "must be a number");
      }
      f.arr(s) = std::move(v);
      return;
    }
  }
}
}  // namespace

namespace scene_detail {

Scene from_table(const toml::table& root, const std::string& file, bool use_lines, bool check_rules) {
  Scene s;
  s.source = file;
  LineMap lines;
  // cam.speed_rpm, run.revolutions: checked here, applied after the keys (scene_units.cpp)
  const DesignerUnits units = read_designer_units(root, file, use_lines);
  for (const auto& [k, node] : sorted_entries(root)) {
    const int line = use_lines ? line_of(*node) : 0;
    if (const Field* f = find_field("", k)) {
      read_field(*f, *node, s, file, use_lines, lines);
      continue;
    }
    if (is_network_array(k)) {
      read_network_array(k, *node, s, file, use_lines, lines);
      continue;
    }
    if (!is_table_name(k))
      fail(file, line, k, fmt_node(*node),
           std::string(node->is_table() ? "unknown table; " : "unknown key; ") + allowed_top());
    const toml::table* t = node->as_table();
    if (!t) fail(file, line, k, fmt_node(*node), "must be a table ([" + k + "]); " + allowed_in(k));
    lines[k] = line;
    for (const auto& [kk, nn] : sorted_entries(*t)) {
      const Field* f = find_field(k, kk);
      if (!f && is_designer_unit_key(k + "." + kk)) continue;
      if (!f)
        fail(file, use_lines ? line_of(*nn) : 0, k + "." + kk, fmt_node(*nn),
             std::string(nn->is_table() ? "unknown table; " : "unknown key; ") + allowed_in(k));
      read_field(*f, *nn, s, file, use_lines, lines);
    }
  }
  apply_designer_units(units, s, file, lines);
  resolve_defaults(s);
  if (check_rules) validate_impl(s, file, lines);
  return s;
}

// ---------------------------------------------------------------- Scene -> TOML table

toml::table to_table(const Scene& scene) {
  Scene& s = const_cast<Scene&>(scene);  // accessors are non-const; nothing is modified
  toml::table root;
  for (const char* t : kTables) root.insert_or_assign(t, toml::table{});
  for (const auto& f : fields()) {
    toml::table& dst = *f.table ? *root.get_as<toml::table>(f.table) : root;
    switch (f.kind) {
      case FK::Real: dst.insert_or_assign(f.key, f.real(s)); break;
      case FK::Int: dst.insert_or_assign(f.key, static_cast<int64_t>(f.get_int(s))); break;
      case FK::Bool: dst.insert_or_assign(f.key, f.boolean(s)); break;
      case FK::Str: dst.insert_or_assign(f.key, f.str(s)); break;
      case FK::Enum: dst.insert_or_assign(f.key, std::string(f.get_enum(s))); break;
      case FK::Arr: {
        toml::array a;
        for (double x : f.arr(s)) a.push_back(x);
        dst.insert_or_assign(f.key, std::move(a));
        break;
      }
    }
  }
  // The network: one array of tables per non-empty list.
  for_each_network_entry(scene, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& keys) {
    toml::table t;
    for (const auto& e : keys) {
      switch (e.kind) {
        case SceneEntry::Kind::Real: t.insert_or_assign(e.key, e.real); break;
        case SceneEntry::Kind::Int: t.insert_or_assign(e.key, static_cast<int64_t>(e.integer)); break;
        case SceneEntry::Kind::Bool: t.insert_or_assign(e.key, e.boolean); break;
        case SceneEntry::Kind::Str: t.insert_or_assign(e.key, e.text); break;
        case SceneEntry::Kind::Array: {
          toml::array a;
          for (double x : e.array) a.push_back(x);
          t.insert_or_assign(e.key, std::move(a));
          break;
        }
        case SceneEntry::Kind::Names: {
          toml::array a;
          for (const auto& x : e.names) a.push_back(x);
          t.insert_or_assign(e.key, std::move(a));
          break;
        }
      }
    }
    if (!root.get_as<toml::array>(array)) root.insert_or_assign(array, toml::array{});
    root.get_as<toml::array>(array)->push_back(std::move(t));
  });
  return root;
}

double paper_tol_u(FollowerKind k) { return k == FollowerKind::Rigid ? 1e-8 : 1e-7; }

}  // namespace scene_detail

bool operator==(const CamSpec& a, const CamSpec& b) { return same_table(a, b, &Scene::cam, "cam"); }
bool operator==(const FollowerSpec& a, const FollowerSpec& b) {
  return same_table(a, b, &Scene::follower, "follower");
}
bool operator==(const SpringSpec& a, const SpringSpec& b) { return same_table(a, b, &Scene::spring, "spring"); }
bool operator==(const ContactSpec& a, const ContactSpec& b) {
  return same_table(a, b, &Scene::contact, "contact");
}
bool operator==(const SolverSpec& a, const SolverSpec& b) { return same_table(a, b, &Scene::solver, "solver"); }
bool operator==(const RunSpec& a, const RunSpec& b) { return same_table(a, b, &Scene::run, "run"); }
bool operator==(const JumpSpec& a, const JumpSpec& b) { return same_table(a, b, &Scene::jump, "jump"); }
bool operator==(const CriteriaSpec& a, const CriteriaSpec& b) {
  return same_table(a, b, &Scene::criteria, "criteria");
}
bool operator==(const LubricantSpec& a, const LubricantSpec& b) {
  return same_table(a, b, &Scene::lubricant, "lubricant");
}
bool operator==(const SynthesisSpec& a, const SynthesisSpec& b) {
  return same_table(a, b, &Scene::synthesis, "synthesis");
}
bool operator==(const CamshaftSpec& a, const CamshaftSpec& b) {
  return same_table(a, b, &Scene::camshaft, "camshaft");
}
bool operator==(const Scene& a, const Scene& b) { return same_keys(a, b, nullptr) && a.network == b.network; }
bool operator!=(const Scene& a, const Scene& b) { return !(a == b); }

}  // namespace camdyn
