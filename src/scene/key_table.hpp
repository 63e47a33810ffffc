// camdyn — the scene's key table as data (private): what the key reference
// (include/camdyn/scene_keys.hpp, src/scene/keys.cpp) is generated from.
#pragma once

#include <string>
#include <vector>

namespace camdyn::detail {

/// One key of the scene's key table (kFields in src/scene/scene.cpp), or one key of a network
/// array ([[nodes]], [[elements]], [[contacts]]: key "elements.stiffness").
struct KeyTableRow {
  std::string key;                      ///< dotted path: "contact.tol_u", "elements.preload"
  std::string type;                     ///< "real", "integer", "bool", "string", "array of reals", "enum", "names"
  std::string rule;                     ///< the key's own rule as the loader words it ("" for network keys)
  std::vector<std::string> allowed;     ///< enum: the allowed spellings
  std::vector<std::string> applies_to;  ///< network keys: the element/contact types that take the key
};

/// Every key of the key table in file order (top-level keys first, each table contiguous),
/// then the keys of [[nodes]], [[elements]] and [[contacts]].
std::vector<KeyTableRow> key_table();

/// The loader's number format: the shortest decimal that reads back to the same double
/// (integral values without exponent: 90, not 9e+01).
std::string format_number(double v);

}  // namespace camdyn::detail
