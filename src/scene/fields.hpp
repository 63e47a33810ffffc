// camdyn — internals of the scene loader: the key table (kFields) that drives parsing,
// validation and serialisation, shared by scene.cpp, scene_validate.cpp, scene_override.cpp
// and scene_write.cpp (not a public header).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "camdyn/scene.hpp"
#include "scene/detail.hpp"

namespace camdyn::scene_detail {

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

/// The key table: every key of every table (src/scene/scene.cpp).
const std::vector<Field>& fields();
/// A top-level table name ("cam", "follower", ...).
bool is_table_name(std::string_view s);
/// "allowed keys at top level: ..." for messages.
std::string allowed_top();
/// Parse a TOML table into a Scene and (check_rules) validate it (errors name lines when
/// use_lines). Without check_rules only the keys and their types are checked (a draft
/// whose network names resolve --set keys before the overrides are in).
/// @throws SceneError (file, line, key, value, rule).
Scene from_table(const toml::table& root, const std::string& file, bool use_lines, bool check_rules = true);
/// A Scene as a TOML table (the inverse of from_table).
toml::table to_table(const Scene& scene);
/// Check a scene (src/scene/validate.cpp); `lines` gives the lines of keys read from a file.
/// @throws SceneError (file, line, key, value, rule).
void validate_impl(const Scene& s, const std::string& file, const LineMap& lines);
/// The paper's contact.tol_u for a follower kind (contact.tol_u = 0 resolves to it).
double paper_tol_u(FollowerKind k);

}  // namespace camdyn::scene_detail
