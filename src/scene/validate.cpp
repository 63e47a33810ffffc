// camdyn — scene validation: the Validator (every key's own rule from the key table, and
// the rules between keys).
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
#include <set>
#include <sstream>
#include <utility>

#include <toml++/toml.h>

#include "camdyn/cam.hpp"
#include "scene/detail.hpp"
#include "scene/fields.hpp"
#include "scene/validator.hpp"

namespace camdyn {

using namespace scene_detail;  // scene_detail.hpp, scene_fields.hpp

namespace scene_detail {

void validate_impl(const Scene& s, const std::string& file, const LineMap& lines) {
  Validator(s, file, lines).run();
}

}  // namespace scene_detail

void validate(const Scene& scene) { validate_impl(scene, scene.source, LineMap{}); }

}  // namespace camdyn
