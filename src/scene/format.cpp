// camdyn — the scene's enums as strings (the cam's: src/cam/cam_spec.cpp) and the formatting
// helpers of error messages (declared in scene/detail.hpp).
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

namespace camdyn {

// ---------------------------------------------------------------- enum <-> string
using namespace scene_detail;  // enum names, formatting helpers, network arrays (scene_detail.hpp)


const char* to_string(FollowerKind v) { return enum_to_string(kFollowerNames, v); }
const char* to_string(MassMatrixKind v) { return enum_to_string(kMassNames, v); }
const char* to_string(ContactModel v) { return enum_to_string(kContactNames, v); }
const char* to_string(ErrorVariant v) { return enum_to_string(kVariantNames, v); }
const char* to_string(LeeStepKind v) { return enum_to_string(kLeeStepNames, v); }
const char* to_string(PenaltyLaw v) { return enum_to_string(kPenaltyNames, v); }
const char* to_string(Integrator v) { return enum_to_string(kIntegratorNames, v); }
const char* to_string(LinearSolverKind v) { return enum_to_string(kLinSolNames, v); }
const char* to_string(StackKind v) { return enum_to_string(kStackNames, v); }
const char* to_string(CamshaftDrive v) { return enum_to_string(kCamshaftDriveNames, v); }
const char* to_string(ElementKind v) { return element_kind(v).name; }
const char* to_string(ContactPointKind v) { return enum_to_string(kContactPointNames, v); }
const char* to_string(StopSide v) { return enum_to_string(kStopSideNames, v); }
const char* to_string(BarMass v) { return enum_to_string(kBarMassNames, v); }

bool parse_enum(std::string_view s, FollowerKind* out) { return enum_parse(kFollowerNames, s, out); }
bool parse_enum(std::string_view s, MassMatrixKind* out) { return enum_parse(kMassNames, s, out); }
bool parse_enum(std::string_view s, ContactModel* out) { return enum_parse(kContactNames, s, out); }
bool parse_enum(std::string_view s, ErrorVariant* out) { return enum_parse(kVariantNames, s, out); }
bool parse_enum(std::string_view s, LeeStepKind* out) { return enum_parse(kLeeStepNames, s, out); }
bool parse_enum(std::string_view s, PenaltyLaw* out) { return enum_parse(kPenaltyNames, s, out); }
bool parse_enum(std::string_view s, Integrator* out) { return enum_parse(kIntegratorNames, s, out); }
bool parse_enum(std::string_view s, LinearSolverKind* out) { return enum_parse(kLinSolNames, s, out); }
bool parse_enum(std::string_view s, StackKind* out) { return enum_parse(kStackNames, s, out); }
bool parse_enum(std::string_view s, CamshaftDrive* out) { return enum_parse(kCamshaftDriveNames, s, out); }
bool parse_enum(std::string_view s, ElementKind* out) {
  for (const ElementKindInfo& k : element_kinds())
    if (s == k.name) {
      *out = k.kind;
      return true;
    }
  return false;
}
bool parse_enum(std::string_view s, ContactPointKind* out) { return enum_parse(kContactPointNames, s, out); }
bool parse_enum(std::string_view s, StopSide* out) { return enum_parse(kStopSideNames, s, out); }
bool parse_enum(std::string_view s, BarMass* out) { return enum_parse(kBarMassNames, s, out); }

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

}  // namespace camdyn
