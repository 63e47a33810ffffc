// camdyn — the reference of every scene key, generated from the scene's key table.
//
// `camdyn scene --keys` prints it (Markdown, or JSON with --json); the documentation site's
// scene-key page is generated from that output by scripts/docs.sh, so the page cannot
// drift from the loader.
#pragma once

#include <string>
#include <vector>

namespace camdyn {

/// One scene key as documented: what the loader takes, its default and its rule.
struct SceneKeyInfo {
  std::string key;          ///< dotted path as for --set: "contact.tol_u"; network keys "elements.preload"
  std::string type;         ///< "real", "integer", "bool", "string", "array of reals", "enum", "names"
  std::string unit;         ///< "length", "force/length", "rev/s", "deg", … or "—"
  std::string default_value;  ///< TOML spelling of the default (Scene{} / NodeSpec{} / …), or "(required)" …
  std::string rule;         ///< the key's own rule as the loader words it (rules between keys: in `description`)
  std::string description;  ///< what the key means, and the rules it shares with other keys
  std::vector<std::string> applies_to;  ///< network keys: the element / contact types that take it
  /// An input-only key in a designer's units (cam.speed_rpm, cam.rpm_of, run.revolutions):
  /// converted to the SI key it replaces when the scene is loaded, never written back.
  bool input_only = false;
};

/// Every key of the scene's key table (top-level tables in file order), then the keys of
/// [[nodes]], [[elements]] and [[contacts]]. Defaults come from the default-constructed
/// specs, rules and types from the key table, units and descriptions from one documentation
/// table kept next to it (src/scene/keys.cpp).
/// @throws std::logic_error when the documentation table and the key table disagree (a key
///         without documentation or documentation of no key): a build-time mistake, which
///         the test suite catches.
std::vector<SceneKeyInfo> scene_keys();

/// scene_keys() as a Markdown page (one table per scene table / network array).
std::string scene_keys_markdown();
/// scene_keys() as a JSON array of objects with the members of SceneKeyInfo.
std::string scene_keys_json();

struct Scene;
/// Why `key` ("TABLE.KEY") has no effect on a run of `scene`, or "" when it may have one:
/// [spring] and follower.* but follower.kind on a network; the elastic bar's follower keys
/// on a rigid follower; another profile's cam keys (cam.radius and cam.eccentricity only
/// for profile "circle", …); contact.penalty_* with another contact model. A sweep over such
/// a key is refused (its rows would all be the same run).
std::string unused_key_reason(const Scene& scene, const std::string& key);

}  // namespace camdyn
