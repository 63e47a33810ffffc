// camdyn — scene description: enums, TOML parsing, validation, defaults, serialisation.
//
// One table of field descriptors (kFields) drives everything: parsing a TOML table into a
// Scene, converting a Scene back to a TOML table (used by apply_override, so overrides go
// through exactly the same parse and validation path as files), writing to_toml, and the
// "allowed keys" lists of error messages.
#include "camdyn/scene.hpp"
#include "scene_key_table.hpp"

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

#include "camdyn/cam.hpp"
#include "scene_detail.hpp"

namespace camdyn {

// ---------------------------------------------------------------- enum <-> string
using namespace scene_detail;  // enum names, formatting helpers, network arrays (scene_detail.hpp)


const char* to_string(CamProfileKind v) { return enum_to_string(kProfileNames, v); }
const char* to_string(FollowerFace v) { return enum_to_string(kFaceNames, v); }
const char* to_string(FollowerMotion v) { return enum_to_string(kMotionNames, v); }
const char* to_string(FollowerKind v) { return enum_to_string(kFollowerNames, v); }
const char* to_string(MassMatrixKind v) { return enum_to_string(kMassNames, v); }
const char* to_string(ContactModel v) { return enum_to_string(kContactNames, v); }
const char* to_string(ErrorVariant v) { return enum_to_string(kVariantNames, v); }
const char* to_string(LeeStepKind v) { return enum_to_string(kLeeStepNames, v); }
const char* to_string(PenaltyLaw v) { return enum_to_string(kPenaltyNames, v); }
const char* to_string(Integrator v) { return enum_to_string(kIntegratorNames, v); }
const char* to_string(LinearSolverKind v) { return enum_to_string(kLinSolNames, v); }
const char* to_string(ElementKind v) { return enum_to_string(kElementNames, v); }
const char* to_string(ContactPointKind v) { return enum_to_string(kContactPointNames, v); }
const char* to_string(StopSide v) { return enum_to_string(kStopSideNames, v); }
const char* to_string(BarMass v) { return enum_to_string(kBarMassNames, v); }

bool parse_enum(std::string_view s, CamProfileKind* out) { return enum_parse(kProfileNames, s, out); }
bool parse_enum(std::string_view s, FollowerFace* out) { return enum_parse(kFaceNames, s, out); }
bool parse_enum(std::string_view s, FollowerMotion* out) { return enum_parse(kMotionNames, s, out); }
bool parse_enum(std::string_view s, FollowerKind* out) { return enum_parse(kFollowerNames, s, out); }
bool parse_enum(std::string_view s, MassMatrixKind* out) { return enum_parse(kMassNames, s, out); }
bool parse_enum(std::string_view s, ContactModel* out) { return enum_parse(kContactNames, s, out); }
bool parse_enum(std::string_view s, ErrorVariant* out) { return enum_parse(kVariantNames, s, out); }
bool parse_enum(std::string_view s, LeeStepKind* out) { return enum_parse(kLeeStepNames, s, out); }
bool parse_enum(std::string_view s, PenaltyLaw* out) { return enum_parse(kPenaltyNames, s, out); }
bool parse_enum(std::string_view s, Integrator* out) { return enum_parse(kIntegratorNames, s, out); }
bool parse_enum(std::string_view s, LinearSolverKind* out) { return enum_parse(kLinSolNames, s, out); }
bool parse_enum(std::string_view s, ElementKind* out) { return enum_parse(kElementNames, s, out); }
bool parse_enum(std::string_view s, ContactPointKind* out) { return enum_parse(kContactPointNames, s, out); }
bool parse_enum(std::string_view s, StopSide* out) { return enum_parse(kStopSideNames, s, out); }
bool parse_enum(std::string_view s, BarMass* out) { return enum_parse(kBarMassNames, s, out); }

// ---------------------------------------------------------------- SceneError

namespace {

std::string compose_message(const std::string& file, int line, const std::string& key,
                            const std::string& value, const std::string& rule) {
  std::string m = file;
  if (line > 0) m += ":" + std::to_string(line);
  m += ": ";
  if (!key.empty()) m += "key '" + key + "' = " + value + ": ";
  m += rule;
  return m;
}

}  // namespace

SceneError::SceneError(std::string file, int line, std::string key, std::string value, std::string rule)
    : std::runtime_error(compose_message(file, line, key, value, rule)),
      file_(std::move(file)),
      key_(std::move(key)),
      value_(std::move(value)),
      rule_(std::move(rule)),
      line_(line) {}

// ---------------------------------------------------------------- equality

bool operator==(const NodeSpec& a, const NodeSpec& b) {
  return a.name == b.name && a.mass == b.mass && a.initial_displacement == b.initial_displacement &&
         a.initial_velocity == b.initial_velocity;
}
bool operator==(const ElementSpec& a, const ElementSpec& b) {
  return a.name == b.name && a.kind == b.kind && a.nodes == b.nodes && a.stiffness == b.stiffness &&
         a.preload == b.preload && a.damping == b.damping && a.mass == b.mass && a.masses == b.masses &&
         a.youngs_modulus == b.youngs_modulus && a.area == b.area && a.length == b.length &&
         a.elements == b.elements && a.mass_matrix == b.mass_matrix && a.rayleigh_alpha == b.rayleigh_alpha &&
         a.rayleigh_beta == b.rayleigh_beta && a.ratio == b.ratio;
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

// ---------------------------------------------------------------- formatting helpers

namespace scene_detail {

/// Shortest decimal form that reads back to the same double ("nan", "inf", "-inf" too).
std::string fmt_num(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  if (v == std::floor(v) && std::fabs(v) < 1e15) {  // integral: no exponent (90, not 9e+01)
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return buf;
  }
  for (int p = 1; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

/// A double as a TOML float literal (always with '.', 'e', or a nan/inf spelling).
std::string toml_float(double v) {
  std::string s = fmt_num(v);
  if (s.find_first_of(".eni") == std::string::npos) s += ".0";
  return s;
}

std::string quote(std::string_view s) {
  std::string r = "\"";
  for (char c : s) {
    switch (c) {
      case '"': r += "\\\""; break;
      case '\\': r += "\\\\"; break;
      case '\n': r += "\\n"; break;
      case '\t': r += "\\t"; break;
      case '\r': r += "\\r"; break;
      case '\b': r += "\\b"; break;
      case '\f': r += "\\f"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          r += buf;
        } else {
          r += c;
        }
    }
  }
  return r + "\"";
}

/// An array for a message: all values up to 8, else the first three, "...", the last.
std::string fmt_list(const std::vector<std::string>& items) {
  std::string r = "[";
  const std::size_t n = items.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (n > 8 && i == 3) {
      r += "..., ";
      i = n - 1;
    }
    r += items[i];
    if (i + 1 < n) r += ", ";
  }
  return r + "]";
}

std::string fmt_vec(const std::vector<double>& v) {
  std::vector<std::string> items;
  items.reserve(v.size());
  for (double x : v) items.push_back(fmt_num(x));
  return fmt_list(items);
}

std::string fmt_node(const toml::node& n) {
  if (auto s = n.as_string()) return quote(s->get());
  if (auto i = n.as_integer()) return std::to_string(i->get());
  if (auto f = n.as_floating_point()) return fmt_num(f->get());
  if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
  if (auto a = n.as_array()) {
    std::vector<std::string> items;
    for (const auto& e : *a) items.push_back(fmt_node(e));
    return fmt_list(items);
  }
  if (n.is_table()) return "{...}";
  std::ostringstream os;
  n.visit([&](const auto& x) { os << x; });
  return os.str();
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string r;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) r += sep;
    r += v[i];
  }
  return r;
}

std::string one_of(const std::vector<std::string>& allowed) {
  std::vector<std::string> q;
  for (const auto& a : allowed) q.push_back(quote(a));
  return "must be one of " + join(q, ", ");
}

std::string range_rule(long long lo, long long hi) {
  if (hi == LLONG_MAX) return "must be >= " + std::to_string(lo);
  return "must be >= " + std::to_string(lo) + " and <= " + std::to_string(hi);
}

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

void fail(const std::string& file, int line, const std::string& key, const std::string& value,
                       const std::string& rule) {
  throw SceneError(file, line, key, value, rule);
}

long long toml_integer(const toml::node& n, const std::string& file, int line, const std::string& key) {
  if (auto i = n.as_integer()) return i->get();
  if (auto d = n.as_floating_point()) {
    const double x = d->get();
    if (std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 9.0e18) return static_cast<long long>(x);
  }
  fail(file, line, key, fmt_node(n), "must be an integer");
}

std::vector<std::pair<std::string, const toml::node*>> sorted_entries(const toml::table& t) {
  std::vector<std::pair<std::string, const toml::node*>> e;
  for (auto&& [k, v] : t) e.emplace_back(std::string(k.str()), &v);
  std::stable_sort(e.begin(), e.end(), [](const auto& a, const auto& b) {
    return line_of(*a.second) < line_of(*b.second);
  });
  return e;
}

}  // namespace scene_detail

namespace {


// ---------------------------------------------------------------- field descriptors

enum class FK { Real, Int, Bool, Str, Arr, Enum };

// A key's own rule (checked by validate() for every key of the table; rules between keys
// are written out in the Validator). Every number must be finite; then
//   Gt: v > lo   Ge: v ≥ lo   In: lo ≤ v ≤ hi   GtLe: lo < v ≤ hi
//   ZeroOrIn: v = 0 or lo ≤ v ≤ hi (`note` completes the message).
// Int keys: imin ≤ v ≤ imax (also at parse time).
enum class Rule { Finite, Gt, Ge, In, GtLe, ZeroOrIn };

/// Largest magnitude of any real input (and reciprocal of the smallest positive one).
constexpr double kMaxMagnitude = 1e50;

struct Field {
  const char* table;  // "" for a top-level key
  const char* key;
  FK kind;
  double& (*real)(Scene&) = nullptr;
  std::vector<double>& (*arr)(Scene&) = nullptr;
  bool& (*boolean)(Scene&) = nullptr;
  std::string& (*str)(Scene&) = nullptr;
  long long (*get_int)(const Scene&) = nullptr;
  void (*set_int)(Scene&, long long) = nullptr;
  long long imin = 0, imax = 0;
  const char* (*get_enum)(const Scene&) = nullptr;
  bool (*set_enum)(Scene&, std::string_view) = nullptr;
  std::vector<std::string> allowed;
  Rule rule = Rule::Finite;
  double lo = 0, hi = 0;
  const char* note = "";

  std::string path() const { return *table ? std::string(table) + "." + key : std::string(key); }
};

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

const char* const kTables[] = {"cam", "follower", "spring", "contact", "solver", "run"};

Field ruled(Field f, Rule r, double lo, double hi = 0, const char* note = "") {
  f.rule = r;
  f.lo = lo;
  f.hi = hi;
  f.note = note;
  return f;
}

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
    v.push_back(ruled(F_REAL(cam, nose_radius), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(cam, nose_distance), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(cam, flank_radius), Rule::Gt, 0));
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

    v.push_back(ruled(F_REAL(run, t_end), Rule::Gt, 0));
    v.push_back(ruled(F_REAL(run, output_dt), Rule::Ge, 0));
    v.push_back(F_BOOL(run, land_on_output));
    v.push_back(F_INT(run, max_steps, 1, LLONG_MAX));
    v.push_back(F_REAL(run, poincare_angle_deg));
    v.push_back(F_INT(run, settle_revolutions, 0, 1000000000));
    v.push_back(ruled(F_REAL(run, period_tol), Rule::GtLe, 0, 1));
    v.push_back(F_BOOL(run, designer_columns));
    return v;
  }();
  return kFields;
}

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


void validate_impl(const Scene& s, const std::string& file, const LineMap& lines);

Scene from_table(const toml::table& root, const std::string& file, bool use_lines) {
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
  validate_impl(s, file, lines);
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

// ---------------------------------------------------------------- validation

class Validator {
 public:
  Validator(const Scene& s, const std::string& file, const LineMap& lines) : s_(s), file_(file), lines_(lines) {}

  int line(const std::string& key, const std::string& fallback = "") const {
    auto it = lines_.find(key);
    if (it != lines_.end()) return it->second;
    if (!fallback.empty()) {
      it = lines_.find(fallback);
      if (it != lines_.end()) return it->second;
    }
    // An array element not recorded: use the array's line.
    auto br = key.find('[');
    if (br != std::string::npos) {
      it = lines_.find(key.substr(0, br));
      if (it != lines_.end()) return it->second;
    }
    return 0;
  }

  [[noreturn]] void fail_at(const std::string& key, const std::string& value, const std::string& rule,
                            const std::string& fallback = "") const {
    throw SceneError(file_, line(key, fallback), key, value, rule);
  }

  void finite(const std::string& key, double v) const {
    if (!std::isfinite(v)) fail_at(key, fmt_num(v), "must be a finite number");
    // Issue 25: E = 1e308 or a preload of 1e308 passed and the integrator then failed on
    // the overflowing products. No unit system needs magnitudes beyond 1e50, and products
    // of a few such quantities stay far inside double precision.
    if (std::abs(v) > kMaxMagnitude)
      fail_at(key, fmt_num(v),
              "is not a physical magnitude: must be <= " + fmt_num(kMaxMagnitude) +
                  " in absolute value (products with the scene's other quantities would overflow double precision)");
  }
  void finite(const std::string& key, const std::vector<double>& v) const {
    for (std::size_t i = 0; i < v.size(); ++i) finite(elem(key, i), v[i]);
  }
  void gt(const std::string& key, double v, double lo) const {
    finite(key, v);
    if (!(v > lo)) fail_at(key, fmt_num(v), "must be > " + fmt_num(lo));
  }
  void ge(const std::string& key, double v, double lo) const {
    finite(key, v);
    if (!(v >= lo)) fail_at(key, fmt_num(v), "must be >= " + fmt_num(lo));
  }
  void in(const std::string& key, double v, double lo, double hi) const {
    finite(key, v);
    if (!(v >= lo && v <= hi)) fail_at(key, fmt_num(v), "must be >= " + fmt_num(lo) + " and <= " + fmt_num(hi));
  }
  void int_in(const std::string& key, long long v, long long lo, long long hi) const {
    if (v < lo || v > hi) fail_at(key, std::to_string(v), range_rule(lo, hi));
  }
  static std::string elem(const std::string& key, std::size_t i) { return key + "[" + std::to_string(i) + "]"; }

  /// ≥ 4 values, strictly increasing, span < 360°.
  void angle_table(const std::string& key, const std::vector<double>& a, const std::string& context,
                   const std::string& fallback) const {
    if (a.size() < 4)
      fail_at(key, fmt_vec(a), "must have at least 4 values" + context + " (has " + std::to_string(a.size()) + ")",
              fallback);
    increasing(key, a);
    if (!(a.back() - a.front() < 360.0))
      fail_at(elem(key, a.size() - 1), fmt_num(a.back()),
              "must be < " + key + "[0] + 360 = " + fmt_num(a.front() + 360.0) + " (the table spans less than 360 deg)");
  }
  void increasing(const std::string& key, const std::vector<double>& a) const {
    for (std::size_t i = 1; i < a.size(); ++i)
      if (!(a[i] > a[i - 1]))
        fail_at(elem(key, i), fmt_num(a[i]),
                "must be > " + elem(key, i - 1) + " = " + fmt_num(a[i - 1]) + " (strictly increasing)");
  }
  void same_length(const std::string& key, const std::vector<double>& a, const std::string& ref_key,
                   const std::vector<double>& ref) const {
    if (a.size() != ref.size())
      fail_at(key, fmt_vec(a),
              "must have as many values as " + ref_key + " (" + std::to_string(ref.size()) + "), has " +
                  std::to_string(a.size()),
              ref_key);
  }

  /// Every key's own rule from the key table (fields()).
  void key_rules() const {
    Scene& s = const_cast<Scene&>(s_);  // the accessors are non-const; nothing is written
    for (const Field& f : fields()) {
      const std::string key = f.path();
      switch (f.kind) {
        case FK::Arr:
          finite(key, f.arr(s));
          break;
        case FK::Int:
          int_in(key, f.get_int(s), f.imin, f.imax);
          break;
        case FK::Real: {
          const double v = f.real(s);
          finite(key, v);
          if (f.rule == Rule::Gt && f.lo == 0.0 && v > 0.0 && v < 1.0 / kMaxMagnitude)
            fail_at(key, fmt_num(v),
                    "is not a physical magnitude: must be >= " + fmt_num(1.0 / kMaxMagnitude) +
                        " (its reciprocal would overflow double precision in the scene's products)");
          const bool ok = f.rule == Rule::Finite ? true
                          : f.rule == Rule::Gt   ? v > f.lo
                          : f.rule == Rule::Ge   ? v >= f.lo
                          : f.rule == Rule::In   ? (v >= f.lo && v <= f.hi)
                          : f.rule == Rule::GtLe ? (v > f.lo && v <= f.hi)
                                                 : (v == 0.0 || (v >= f.lo && v <= f.hi));
          if (ok) break;
          const std::string rule =
              f.rule == Rule::Gt   ? "must be > " + fmt_num(f.lo)
              : f.rule == Rule::Ge ? "must be >= " + fmt_num(f.lo)
              : f.rule == Rule::In ? "must be >= " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
              : f.rule == Rule::GtLe ? "must be > " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
                                     : std::string(f.note);
          fail_at(key, fmt_num(v), rule);
        }
        default:
          break;
      }
    }
  }

  void run() const {
    const Scene& s = s_;
    key_rules();
    // ---- cam (rules between keys)
    const CamSpec& c = s.cam;
    if (c.profile == CamProfileKind::Points) {
      angle_table("cam.angles_deg", c.angles_deg, "", "cam.profile");
      same_length("cam.radii", c.radii, "cam.angles_deg", c.angles_deg);
      for (std::size_t i = 0; i < c.radii.size(); ++i) gt(elem("cam.radii", i), c.radii[i], 0.0);
    }
    if (c.profile == CamProfileKind::Lift) {
      angle_table("cam.lift_angles_deg", c.lift_angles_deg, " for cam.profile = \"lift\"", "cam.profile");
      same_length("cam.lift", c.lift, "cam.lift_angles_deg", c.lift_angles_deg);
      for (std::size_t i = 0; i < c.lift.size(); ++i)
        if (!(c.base_radius + c.lift[i] > 0))
          fail_at(elem("cam.lift", i), fmt_num(c.lift[i]),
                  "must be > -cam.base_radius = " + fmt_num(-c.base_radius) + " (base_radius + lift > 0)");
    }
    // Motion laws, arc cams and the follower faces (issue 24): their rules live with the
    // geometry (cam.cpp, follower_geometry.cpp); reported here with the scene's file.
    if (c.profile == CamProfileKind::Law || c.profile == CamProfileKind::Arc ||
        c.follower_face != FollowerFace::Flat || c.follower_motion != FollowerMotion::Translating) {
      try {
        Cam check(c);
      } catch (const SceneError& e) {
        fail_at(e.key(), e.value(), e.rule());
      }
    }
    if (!(c.eccentricity < c.radius))
      fail_at("cam.eccentricity", fmt_num(c.eccentricity), "must be < cam.radius = " + fmt_num(c.radius));
    if (!c.speed_table_t.empty() || !c.speed_table_rev_s.empty()) {
      same_length("cam.speed_table_rev_s", c.speed_table_rev_s, "cam.speed_table_t", c.speed_table_t);
      if (c.speed_table_t.front() != 0.0)
        fail_at("cam.speed_table_t[0]", fmt_num(c.speed_table_t.front()), "must be 0 (the speed table starts at t = 0)");
      increasing("cam.speed_table_t", c.speed_table_t);
    }

    // ---- contact
    const ContactSpec& k = s.contact;
    if (!k.separation && k.model != ContactModel::Lee && k.model != ContactModel::Holonomic)
      fail_at("contact.separation", "false",
              std::string("requires contact.model \"lee\" or \"holonomic\" (contact.model is \"") + to_string(k.model) +
                  "\")",
              "contact.model");
    if (k.restitution > 0 && (k.model == ContactModel::Penalty || k.model == ContactModel::Holonomic))
      fail_at("contact.restitution", fmt_num(k.restitution),
              std::string("must be 0 with contact.model \"") + to_string(k.model) +
                  "\" (restitution needs contact.model \"lee\" or \"event\")",
              "contact.model");

    // ---- solver
    const SolverSpec& v = s.solver;
    // IDA integrates the held contact as a DAE (src/ida_engine.cpp): the constraint
    // u₀ = X_C(t) holds at all times, i.e. the holonomic model only.
    if (v.integrator == Integrator::Ida && k.model != ContactModel::Holonomic)
      fail_at("solver.integrator", "\"ida\"",
              std::string("\"ida\" requires contact.model = \"holonomic\" (contact.model is \"") +
                  to_string(k.model) + "\")",
              "contact.model");

    // ---- run
    if (!(s.run.output_dt <= s.run.t_end))
      fail_at("run.output_dt", fmt_num(s.run.output_dt), "must be <= run.t_end = " + fmt_num(s.run.t_end));

    network();
  }

  // ---- network (follower.kind = "network")

  /// The line of `key`, else of the nearest enclosing key recorded ("elements[2].nodes[1]"
  /// → "elements[2].nodes" → "elements[2]" → "elements").
  int net_line(std::string key) const {
    for (;;) {
      auto it = lines_.find(key);
      if (it != lines_.end()) return it->second;
      const auto cut = key.find_last_of(".[");
      if (cut == std::string::npos || cut == 0) return 0;
      key.resize(cut);
    }
  }
  [[noreturn]] void net_fail(const std::string& key, const std::string& value, const std::string& rule) const {
    throw SceneError(file_, net_line(key), key, value, rule);
  }
  void net_finite(const std::string& key, double v, const std::string& who) const {
    if (!std::isfinite(v)) net_fail(key, fmt_num(v), "must be a finite number (" + who + ")");
  }
  void net_ge(const std::string& key, double v, double lo, const std::string& who) const {
    net_finite(key, v, who);
    if (!(v >= lo)) net_fail(key, fmt_num(v), "must be >= " + fmt_num(lo) + " (" + who + ")");
  }
  void net_gt(const std::string& key, double v, double lo, const std::string& who) const {
    net_finite(key, v, who);
    if (!(v > lo)) net_fail(key, fmt_num(v), "must be > " + fmt_num(lo) + " (" + who + ")");
  }
  static std::string quoted_names(const std::vector<std::string>& v) {
    std::vector<std::string> q;
    for (const auto& x : v) q.push_back(quote(x));
    return fmt_list(q);
  }
  static std::string element_label(const ElementSpec& e, std::size_t i) {
    return std::string(to_string(e.kind)) + (e.name.empty() ? " #" + std::to_string(i) : " '" + e.name + "'");
  }
  static std::string contact_label(const ContactPointSpec& c, std::size_t i) {
    return std::string(to_string(c.kind)) + " contact " + (c.name.empty() ? "#" + std::to_string(i) : "'" + c.name + "'");
  }
  static bool valid_node_name(const std::string& n) {
    for (char ch : n)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) return false;
    return true;
  }

  void network() const {
    const Scene& s = s_;
    const NetworkSpec& n = s.network;
    if (s.follower.kind != FollowerKind::Network) {
      const std::pair<const char*, std::size_t> arrays[] = {
          {"nodes", n.nodes.size()}, {"elements", n.elements.size()}, {"contacts", n.contacts.size()}};
      for (const auto& [name, count] : arrays)
        if (count > 0)
          net_fail(name, "(" + std::to_string(count) + (count == 1 ? " entry)" : " entries)"),
                   std::string("[[") + name + "]] needs follower.kind = \"network\" (follower.kind is \"" +
                       to_string(s.follower.kind) + "\")");
      return;
    }
    if (n.nodes.empty()) net_fail("follower.kind", "\"network\"", "needs at least one [[nodes]] entry");
    if (n.contacts.empty()) net_fail("follower.kind", "\"network\"", "needs at least one [[contacts]] entry");

    // ---- nodes
    std::map<std::string, std::size_t> node_index;
    for (std::size_t i = 0; i < n.nodes.size(); ++i) {
      const NodeSpec& nd = n.nodes[i];
      const std::string p = elem("nodes", i);
      const std::string who = "node '" + nd.name + "'";
      if (nd.name.empty()) net_fail(p + ".name", "\"\"", "must not be empty (node names are required)");
      if (nd.name == "ground")
        net_fail(p + ".name", quote(nd.name), "is reserved (\"ground\" is the fixed end of a spring, dashpot or bar)");
      if (!valid_node_name(nd.name))
        net_fail(p + ".name", quote(nd.name), "must contain only letters, digits, '_' and '-'");
      const auto [it, fresh] = node_index.emplace(nd.name, i);
      if (!fresh)
        net_fail(p + ".name", quote(nd.name), "must be unique (" + elem("nodes", it->second) + " has the same name)");
      net_ge(p + ".mass", nd.mass, 0.0, who);
      net_finite(p + ".initial_displacement", nd.initial_displacement, who);
      net_finite(p + ".initial_velocity", nd.initial_velocity, who);
    }
    std::vector<bool> used(n.nodes.size(), false);
    auto node_ref = [&](const std::string& key, const std::string& name, bool ground_ok, const std::string& who,
                        const char* ground_rule) {
      if (name == "ground") {
        if (!ground_ok) net_fail(key, quote(name), std::string(ground_rule) + " (" + who + ")");
        return;
      }
      auto it = node_index.find(name);
      if (it == node_index.end()) net_fail(key, quote(name), "names no node of [[nodes]] (" + who + ")");
      used[it->second] = true;
    };

    // ---- elements
    for (std::size_t i = 0; i < n.elements.size(); ++i) {
      const ElementSpec& e = n.elements[i];
      const std::string p = elem("elements", i);
      const std::string who = element_label(e, i);
      if (e.nodes.size() != 2)
        net_fail(p + ".nodes", quoted_names(e.nodes),
                 "must name exactly 2 nodes, has " + std::to_string(e.nodes.size()) + " (" + who + ")");
      const bool lever = e.kind == ElementKind::Lever;
      for (std::size_t k = 0; k < 2; ++k)
        node_ref(elem(p + ".nodes", k), e.nodes[k], !lever, who, "\"ground\" cannot be a node of a lever");
      if (e.nodes[0] == e.nodes[1]) net_fail(p + ".nodes", quoted_names(e.nodes), "must name two different nodes (" + who + ")");
      switch (e.kind) {
        case ElementKind::Spring:
          net_ge(p + ".stiffness", e.stiffness, 0.0, who);
          net_finite(p + ".preload", e.preload, who);
          net_ge(p + ".damping", e.damping, 0.0, who);
          net_ge(p + ".mass", e.mass, 0.0, who);
          if (e.masses < 0 || e.masses > 100000)
            net_fail(p + ".masses", std::to_string(e.masses), range_rule(0, 100000) + " (" + who + ")");
          if (e.mass > 0 && e.masses < 1)
            net_fail(p + ".masses", std::to_string(e.masses),
                     "must be >= 1 for a spring with mass (" + p + ".mass = " + fmt_num(e.mass) + ") (" + who + ")");
          if (e.masses >= 1 && !(e.mass > 0))
            net_fail(p + ".masses", std::to_string(e.masses), "needs " + p + ".mass > 0 (" + who + ")");
          break;
        case ElementKind::Dashpot: net_gt(p + ".damping", e.damping, 0.0, who); break;
        case ElementKind::Bar:
          net_gt(p + ".mass", e.mass, 0.0, who);
          net_gt(p + ".youngs_modulus", e.youngs_modulus, 0.0, who);
          net_gt(p + ".area", e.area, 0.0, who);
          net_gt(p + ".length", e.length, 0.0, who);
          if (e.elements < 1 || e.elements > 100000)
            net_fail(p + ".elements", std::to_string(e.elements), range_rule(1, 100000) + " (" + who + ")");
          net_ge(p + ".rayleigh_alpha", e.rayleigh_alpha, 0.0, who);
          net_ge(p + ".rayleigh_beta", e.rayleigh_beta, 0.0, who);
          break;
        case ElementKind::Lever:
          if (!(std::isfinite(e.ratio) && e.ratio != 0.0))
            net_fail(p + ".ratio", fmt_num(e.ratio), "must be finite and != 0 (" + who + ")");
          break;
      }
    }

    // ---- contacts
    std::map<std::string, std::size_t> contact_index;
    for (std::size_t i = 0; i < n.contacts.size(); ++i) {
      const ContactPointSpec& c = n.contacts[i];
      const std::string p = elem("contacts", i);
      const std::string who = contact_label(c, i);
      if (c.name.empty()) net_fail(p + ".name", "\"\"", "must not be empty (contact names are required)");
      const auto [it, fresh] = contact_index.emplace(c.name, i);
      if (!fresh)
        net_fail(p + ".name", quote(c.name), "must be unique (" + elem("contacts", it->second) + " has the same name)");
      const std::size_t want = c.kind == ContactPointKind::Lash ? 2 : 1;
      if (c.nodes.size() != want)
        net_fail(p + ".nodes", quoted_names(c.nodes),
                 "must name exactly " + std::to_string(want) + (want == 1 ? " node" : " nodes") + ", has " +
                     std::to_string(c.nodes.size()) + " (" + who + ")");
      for (std::size_t k = 0; k < want; ++k)
        node_ref(elem(p + ".nodes", k), c.nodes[k], false, who, "\"ground\" cannot be a node of a contact");
      if (want == 2 && c.nodes[0] == c.nodes[1])
        net_fail(p + ".nodes", quoted_names(c.nodes), "must name two different nodes (" + who + ")");
      // A cam contact acts on the scene's cam ([cam], always present).
      net_ge(p + ".clearance", c.clearance, 0.0, who);
      if (c.restitution) {
        net_finite(p + ".restitution", *c.restitution, who);
        if (!(*c.restitution >= 0.0 && *c.restitution <= 1.0))
          net_fail(p + ".restitution", fmt_num(*c.restitution), "must be >= 0 and <= 1 (" + who + ")");
      }
      if (c.penalty_stiffness) net_gt(p + ".penalty_stiffness", *c.penalty_stiffness, 0.0, who);
      if (c.penalty_damping) net_ge(p + ".penalty_damping", *c.penalty_damping, 0.0, who);
    }

    // ---- levers: each node the output of at most one lever, no cycles
    std::map<std::string, std::size_t> lever_of_output;  // output node -> element index
    for (std::size_t i = 0; i < n.elements.size(); ++i) {
      const ElementSpec& e = n.elements[i];
      if (e.kind != ElementKind::Lever) continue;
      const auto [it, fresh] = lever_of_output.emplace(e.nodes[1], i);
      if (!fresh)
        net_fail(elem(elem("elements", i) + ".nodes", 1), quote(e.nodes[1]),
                 "is already the output of " + element_label(n.elements[it->second], it->second) + " (" +
                     elem("elements", it->second) + "); a node is the output of at most one lever (" +
                     element_label(e, i) + ")");
    }
    for (std::size_t i = 0; i < n.elements.size(); ++i) {
      const ElementSpec& e = n.elements[i];
      if (e.kind != ElementKind::Lever) continue;
      std::string cur = e.nodes[0];
      for (std::size_t steps = 0; steps <= lever_of_output.size(); ++steps) {
        auto it = lever_of_output.find(cur);
        if (it == lever_of_output.end()) break;
        if (it->second == i)
          net_fail(elem("elements", i) + ".nodes", quoted_names(e.nodes),
                   "levers form a cycle through node '" + e.nodes[1] + "' (" + element_label(e, i) + ")");
        cur = n.elements[it->second].nodes[0];
      }
    }

    // ---- dangling nodes
    for (std::size_t i = 0; i < n.nodes.size(); ++i)
      if (!used[i])
        net_fail(elem("nodes", i) + ".name", quote(n.nodes[i].name),
                 "node '" + n.nodes[i].name + "' is dangling: no element or contact uses it");

    // ---- floating subsystems: components joined by springs (k > 0 or with mass), bars and
    // levers must be held to ground by a spring with k > 0 or a bar.
    const std::size_t nn = n.nodes.size();
    std::vector<std::size_t> parent(nn);
    for (std::size_t i = 0; i < nn; ++i) parent[i] = i;
    auto root = [&](std::size_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::vector<bool> anchored(nn, false);
    for (const auto& e : n.elements) {
      const bool stiff = (e.kind == ElementKind::Spring && e.stiffness > 0) || e.kind == ElementKind::Bar;
      const bool joins = stiff || e.kind == ElementKind::Lever || (e.kind == ElementKind::Spring && e.mass > 0);
      if (!joins) continue;
      const bool g0 = e.nodes[0] == "ground", g1 = e.nodes[1] == "ground";
      if (g0 || g1) {
        if (stiff) anchored[node_index.at(g0 ? e.nodes[1] : e.nodes[0])] = true;
        continue;
      }
      parent[root(node_index.at(e.nodes[0]))] = root(node_index.at(e.nodes[1]));
    }
    std::vector<bool> comp_anchored(nn, false);
    for (std::size_t i = 0; i < nn; ++i)
      if (anchored[i]) comp_anchored[root(i)] = true;
    for (std::size_t i = 0; i < nn; ++i)
      if (!comp_anchored[root(i)])
        net_fail(elem("nodes", i) + ".name", quote(n.nodes[i].name),
                 "node '" + n.nodes[i].name + "' floats: no spring or bar connects it to ground");

    // ---- mass: after lever elimination (a lever's output is tied to its input), every
    // remaining unknown needs positive mass from node masses, bars or springs with mass.
    auto unknown_of = [&](std::string name) {
      for (std::size_t steps = 0; steps <= lever_of_output.size(); ++steps) {
        auto it = lever_of_output.find(name);
        if (it == lever_of_output.end()) break;
        name = n.elements[it->second].nodes[0];
      }
      return node_index.at(name);
    };
    std::vector<bool> has_mass(nn, false);
    for (std::size_t i = 0; i < nn; ++i)
      if (n.nodes[i].mass > 0) has_mass[unknown_of(n.nodes[i].name)] = true;
    for (const auto& e : n.elements) {
      const bool massive = e.kind == ElementKind::Bar || (e.kind == ElementKind::Spring && e.mass > 0);
      if (!massive) continue;
      for (const auto& name : e.nodes)
        if (name != "ground") has_mass[unknown_of(name)] = true;
    }
    for (std::size_t i = 0; i < nn; ++i)
      if (unknown_of(n.nodes[i].name) == i && !has_mass[i])
        net_fail(elem("nodes", i) + ".mass", fmt_num(n.nodes[i].mass),
                 "node '" + n.nodes[i].name +
                     "' has no mass (give it mass, or connect a bar or a spring with mass to it or to a node "
                     "tied to it by a lever)");
  }

 private:
  const Scene& s_;
  const std::string& file_;
  const LineMap& lines_;
};

void validate_impl(const Scene& s, const std::string& file, const LineMap& lines) {
  Validator(s, file, lines).run();
}

double paper_tol_u(FollowerKind k) { return k == FollowerKind::Rigid ? 1e-8 : 1e-7; }

std::string trim(std::string_view s) {
  const char* ws = " \t\r\n";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return "";
  const auto e = s.find_last_not_of(ws);
  return std::string(s.substr(b, e - b + 1));
}

}  // namespace

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
bool operator==(const Scene& a, const Scene& b) { return same_keys(a, b, nullptr) && a.network == b.network; }
bool operator!=(const Scene& a, const Scene& b) { return !(a == b); }

// ---------------------------------------------------------------- public functions

void resolve_defaults(Scene& scene) {
  if (scene.contact.tol_u == 0.0) scene.contact.tol_u = paper_tol_u(scene.follower.kind);
}

void validate(const Scene& scene) { validate_impl(scene, scene.source, LineMap{}); }

Scene parse_scene(std::string_view toml_text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw SceneError(source_name, static_cast<int>(e.source().begin.line), "", "", std::string(e.description()));
  }
  return from_table(root, source_name, true);
}

Scene load_scene_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path, 0, "", "", "cannot read scene file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw SceneError(path, 0, "", "", std::string("cannot read scene file: ") + std::strerror(err ? err : ENOENT));
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw SceneError(path, 0, "", "", std::string("cannot read scene file: ") + std::strerror(errno));
  return parse_scene(ss.str(), path);
}

namespace {

// Put one "dotted.key=value" into `root` (`scene` as a TOML table); returns the key (a
// network key as "ARRAY[INDEX].KEY", the loader's spelling). Only the key's place is checked
// here; the value is checked when the table is parsed.
std::string insert_override(toml::table& root, const Scene& scene, const std::string& assignment) {
  static const std::string kFile = "--set";
  const auto eq = assignment.find('=');
  if (eq == std::string::npos)
    throw SceneError(kFile, 0, "", "", "expected KEY=VALUE (e.g. cam.speed_rev_s=3), got '" + assignment + "'");
  const std::string key = trim(std::string_view(assignment).substr(0, eq));
  const std::string text = trim(std::string_view(assignment).substr(eq + 1));
  if (key.empty())
    throw SceneError(kFile, 0, "", "", "expected KEY=VALUE (e.g. cam.speed_rev_s=3), got '" + assignment + "'");

  // The value: a TOML value if it parses as one, else the bare text as a string.
  toml::table parsed;
  const toml::node* value = nullptr;
  try {
    const std::string doc = "x = " + text;
    parsed = toml::parse(std::string_view(doc), std::string_view("--set"));
    if (parsed.size() == 1) value = parsed.get("x");
  } catch (const toml::parse_error&) {
    value = nullptr;
  }
  if (!value) {
    parsed = toml::table{};
    parsed.insert_or_assign("x", text);
    value = parsed.get("x");
  }

  // A network entry's key, by name or index: "contacts.seat.restitution", "elements[1].preload".
  if (is_network_key(key)) return insert_network_override(root, scene, key, *value, kFile);
  // The key: "title" or "TABLE.KEY".
  std::string table, leaf;
  const auto dot = key.find('.');
  if (dot == std::string::npos) {
    leaf = key;
    if (leaf != "title" && !is_table_name(leaf))
      throw SceneError(kFile, 0, key, fmt_node(*value), "unknown key; " + allowed_top());
  } else {
    table = key.substr(0, dot);
    leaf = key.substr(dot + 1);
    if (!is_table_name(table))
      throw SceneError(kFile, 0, key, fmt_node(*value), "unknown key; " + allowed_top());
  }
  toml::table* dst = table.empty() ? &root : root.get_as<toml::table>(table);
  value->visit([&](const auto& v) { dst->insert_or_assign(leaf, v); });
  return key;
}

}  // namespace

void apply_overrides(Scene& scene, const std::vector<std::string>& assignments) {
  static const std::string kFile = "--set";
  if (assignments.empty()) return;
  // tol_u that is "automatic" (0, or the paper default of the current follower kind) is
  // re-derived after the overrides, so follower.kind=elastic_bar gets 1e-7, not rigid's 1e-8.
  const double tol_u = scene.contact.tol_u;
  const bool tol_u_auto = tol_u == 0.0 || tol_u == paper_tol_u(scene.follower.kind);

  toml::table root = to_table(scene);
  bool sets_tol_u = false;
  std::map<std::string, std::string> spelled;  // "contacts[1].restitution" → "contacts.seat.restitution"
  std::vector<std::string> keys_set;
  for (const auto& a : assignments) {
    const std::string key = insert_override(root, scene, a);
    keys_set.push_back(key);
    sets_tol_u |= key == "contact.tol_u";
    const std::string given = trim(std::string_view(a).substr(0, a.find('=')));
    if (given != key) spelled[key] = given;
  }
  if (tol_u_auto && !sets_tol_u) root.get_as<toml::table>("contact")->insert_or_assign("tol_u", 0.0);
  drop_replaced_by_designer_units(root, keys_set);  // cam.speed_rpm replaces cam.speed_rev_s, …

  // One parse and one validation of the result: the order of the overrides does not matter.
  // A bad value of a network key is reported under the key as the user wrote it.
  Scene out;
  try {
    out = from_table(root, kFile, false);
  } catch (const SceneError& e) {
    const auto it = spelled.find(e.key());
    if (it == spelled.end()) throw;
    throw SceneError(e.file(), e.line(), it->second, e.value(), e.rule());
  }
  out.source = scene.source;
  scene = std::move(out);
}

void apply_override(Scene& scene, const std::string& assignment) {
  apply_overrides(scene, {assignment});
}

// ---------------------------------------------------------------- the key table as data

namespace detail {

std::string format_number(double v) { return fmt_num(v); }

std::vector<KeyTableRow> key_table() {
  std::vector<KeyTableRow> rows;
  for (const Field& f : fields()) {
    KeyTableRow r;
    r.key = f.path();
    switch (f.kind) {
      case FK::Real:
        r.type = "real";
        r.rule = f.rule == Rule::Finite ? "must be finite"
                 : f.rule == Rule::Gt   ? "must be > " + fmt_num(f.lo)
                 : f.rule == Rule::Ge   ? "must be >= " + fmt_num(f.lo)
                 : f.rule == Rule::In   ? "must be >= " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
                 : f.rule == Rule::GtLe ? "must be > " + fmt_num(f.lo) + " and <= " + fmt_num(f.hi)
                                        : std::string(f.note);
        break;
      case FK::Int: r.type = "integer"; r.rule = range_rule(f.imin, f.imax); break;
      case FK::Bool: r.type = "bool"; r.rule = "must be true or false"; break;
      case FK::Str: r.type = "string"; r.rule = "must be a string"; break;
      case FK::Arr: r.type = "array of reals"; r.rule = "must be an array of finite numbers"; break;
      case FK::Enum: r.type = "enum"; r.rule = one_of(f.allowed); r.allowed = f.allowed; break;
    }
    const std::string key = r.key;
    rows.push_back(std::move(r));
    // The input-only keys in a designer's units, after the key each one replaces.
    if (key == "cam.speed_rev_s") {
      rows.push_back({"cam.speed_rpm", "real", "must be finite; needs cam.rpm_of; not with cam.speed_rev_s", {}, {}});
      rows.push_back({"cam.rpm_of", "enum", one_of({"camshaft", "engine"}), {"camshaft", "engine"}, {}});
    }
    if (key == "run.t_end")
      rows.push_back({"run.revolutions", "real", "must be > 0; not with run.t_end", {}, {}});
  }
  for (const auto& k : node_keys()) rows.push_back({"nodes." + k, k == "name" ? "string" : "real", "", {}, {}});
  auto typed = [&](const char* array, const std::vector<std::string>& all, const std::vector<std::string>& types,
                   const std::function<std::vector<std::string>(std::size_t)>& keys_of) {
    for (const auto& k : all) {
      KeyTableRow r;
      r.key = std::string(array) + "." + k;
      for (std::size_t i = 0; i < types.size(); ++i)
        if (contains(keys_of(i), k)) r.applies_to.push_back(types[i]);
      rows.push_back(std::move(r));
    }
  };
  typed("elements", all_element_keys(), enum_names(kElementNames),
        [](std::size_t i) { return element_keys(kElementNames[i].value); });
  typed("contacts", all_contact_keys(), enum_names(kContactPointNames),
        [](std::size_t i) { return contact_keys(kContactPointNames[i].value); });
  return rows;
}

}  // namespace detail

void for_each_scene_entry(const Scene& scene, const std::function<void(const SceneEntry&)>& visit) {
  Scene& s = const_cast<Scene&>(scene);  // the field accessors return references; only read
  SceneEntry e;
  for (const auto& f : fields()) {
    e.table = f.table;
    e.key = f.key;
    switch (f.kind) {
      case FK::Real: e.kind = SceneEntry::Kind::Real; e.real = f.real(s); break;
      case FK::Int: e.kind = SceneEntry::Kind::Int; e.integer = f.get_int(s); break;
      case FK::Bool: e.kind = SceneEntry::Kind::Bool; e.boolean = f.boolean(s); break;
      case FK::Str: e.kind = SceneEntry::Kind::Str; e.text = f.str(s); break;
      case FK::Enum: e.kind = SceneEntry::Kind::Str; e.text = f.get_enum(s); break;
      case FK::Arr: e.kind = SceneEntry::Kind::Array; e.array = f.arr(s); break;
    }
    visit(e);
  }
}


std::string to_toml(const Scene& scene_in) {
  Scene resolved = scene_in;
  resolve_defaults(resolved);
  std::ostringstream os;
  os << "# camdyn scene (every key written; see docs/interface.md)\n";
  std::string current;
  auto write_entry = [&](const SceneEntry& e) {
    os << e.key << " = ";
    switch (e.kind) {
      case SceneEntry::Kind::Real: os << toml_float(e.real); break;
      case SceneEntry::Kind::Int: os << e.integer; break;
      case SceneEntry::Kind::Bool: os << (e.boolean ? "true" : "false"); break;
      case SceneEntry::Kind::Str: os << quote(e.text); break;
      case SceneEntry::Kind::Array: {
        os << "[";
        for (std::size_t i = 0; i < e.array.size(); ++i) os << (i ? ", " : "") << toml_float(e.array[i]);
        os << "]";
        break;
      }
      case SceneEntry::Kind::Names: {
        os << "[";
        for (std::size_t i = 0; i < e.names.size(); ++i) os << (i ? ", " : "") << quote(e.names[i]);
        os << "]";
        break;
      }
    }
    os << "\n";
  };
  for_each_scene_entry(resolved, [&](const SceneEntry& e) {
    if (!e.table.empty() && e.table != current) {
      current = e.table;
      os << "\n[" << e.table << "]\n";
    }
    write_entry(e);
  });
  // The network (follower.kind = "network"): [[nodes]], [[elements]], [[contacts]].
  for_each_network_entry(resolved, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& keys) {
    os << "\n[[" << array << "]]\n";
    for (const auto& e : keys) write_entry(e);
  });
  return os.str();
}

// ---------------------------------------------------------------- paper cases

Scene paper_case(const std::string& name) {
  Scene s;
  s.cam.profile = CamProfileKind::Points;
  s.cam.angles_deg = {0, 45, 90, 135, 180, 225, 270, 315};
  s.cam.radii = {2.0, 2.0, 2.0, 2.1, 3.0, 2.1, 2.0, 2.0};
  s.cam.theta0_deg = 0.0;
  s.spring.stiffness = 500.0;
  s.spring.precompression = 7.0;
  s.contact.model = ContactModel::Lee;
  s.solver.integrator = Integrator::ArkodeErk;
  s.run.t_end = 1.0;
  s.run.output_dt = 1e-4;
  s.follower.mass = 1.0;
  if (name == "A") {
    s.title = "Case A \u2014 rigid follower, 1.75 rev/s (Lee 1997 \u00a74.1)";
    s.follower.kind = FollowerKind::Rigid;
    s.cam.speed_rev_s = 1.75;
    s.solver.rtol = 1e-7;
    s.contact.tol_u = 1e-8;
  } else if (name == "B1" || name == "B2") {
    const bool b2 = name == "B2";
    s.title = b2 ? "Case B2 \u2014 elastic follower, 5 rev/s (Lee 1997 \u00a74.2)"
                 : "Case B1 \u2014 elastic follower, 1.75 rev/s (Lee 1997 \u00a74.2)";
    s.follower.kind = FollowerKind::ElasticBar;
    s.follower.youngs_modulus = 1e7;
    s.follower.area = 3.0;
    s.follower.length = 24.0;
    s.follower.elements = 40;
    s.follower.mass_matrix = MassMatrixKind::Consistent;
    s.cam.speed_rev_s = b2 ? 5.0 : 1.75;
    s.solver.rtol = 1e-6;
    s.contact.tol_u = 1e-7;
  } else {
    throw SceneError("--case", 0, "case", name, "unknown paper case (allowed: A, B1, B2)");
  }
  return s;
}

Scene default_scene() { return paper_case("B2"); }

}  // namespace camdyn
