// camdyn — scene validation: the Validator (every key's own rule from the key table, and
// the rules between keys).
#include "camdyn/scene.hpp"

#include <algorithm>
#include <atomic>
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
#include <set>
#include <sstream>
#include <utility>

#include <toml++/toml.h>

#include "scene/detail.hpp"
#include "scene/fields.hpp"
#include "scene/validation_count.hpp"
#include "scene/validator.hpp"

namespace camdyn {

using namespace scene_detail;  // scene_detail.hpp, scene_fields.hpp

namespace scene_detail {

namespace {
std::atomic<std::uint64_t> g_validations{0};
}  // namespace

std::uint64_t validation_count() { return g_validations.load(); }

void validate_impl(const Scene& s, const std::string& file, const LineMap& lines) {
  g_validations.fetch_add(1, std::memory_order_relaxed);
  Validator(s, file, lines).run();
}

}  // namespace scene_detail

void validate(const Scene& scene) { validate_impl(scene, scene.source, LineMap{}); }

ValidatedScene validated(Scene scene, const std::vector<std::string>& overrides) {
  if (!overrides.empty()) {
    apply_overrides(scene, overrides);  // the table with the overrides, parsed and checked once
  } else {
    resolve_defaults(scene);
    validate(scene);
  }
  return ValidatedScene(std::move(scene));
}

}  // namespace camdyn
