// camdyn — internals of the scene loader shared by scene.cpp and scene/network_reader.cpp (not a
// public header): enum names, the formatting helpers of error messages, and the network
// arrays ([[nodes]], [[elements]], [[contacts]]).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "camdyn/scene.hpp"
#include "cam/enum_names.hpp"

namespace camdyn::scene_detail {

// ---------------------------------------------------------------- enum <-> string

// EnumName, its lookups and the cam's tables (kProfileNames, kFaceNames, kMotionNames) live with
// the cam's enumerations (cam/enum_names.hpp).
using detail::EnumName;
using detail::enum_parse;
using detail::enum_to_string;
using detail::kFaceNames;
using detail::kMotionNames;
using detail::kProfileNames;

inline constexpr EnumName<FollowerKind> kFollowerNames[] = {{FollowerKind::Rigid, "rigid"},
                                                     {FollowerKind::ElasticBar, "elastic_bar"},
                                                     {FollowerKind::Network, "network"}};
inline constexpr EnumName<MassMatrixKind> kMassNames[] = {{MassMatrixKind::Consistent, "consistent"},
                                                   {MassMatrixKind::Lumped, "lumped"}};
inline constexpr EnumName<ContactModel> kContactNames[] = {{ContactModel::Lee, "lee"},
                                                    {ContactModel::Penalty, "penalty"},
                                                    {ContactModel::Holonomic, "holonomic"},
                                                    {ContactModel::Event, "event"}};
inline constexpr EnumName<ErrorVariant> kVariantNames[] = {{ErrorVariant::Eq12, "eq12"}, {ErrorVariant::Eq17, "eq17"}};
inline constexpr EnumName<LeeStepKind> kLeeStepNames[] = {{LeeStepKind::Located, "located"}, {LeeStepKind::Classic, "classic"}};
inline constexpr EnumName<PenaltyLaw> kPenaltyNames[] = {{PenaltyLaw::Linear, "linear"},
                                                  {PenaltyLaw::HuntCrossley, "hunt_crossley"}};
inline constexpr EnumName<Integrator> kIntegratorNames[] = {{Integrator::ArkodeErk, "arkode-erk"},
                                                     {Integrator::ArkodeDirk, "arkode-dirk"},
                                                     {Integrator::CvodeBdf, "cvode-bdf"},
                                                     {Integrator::Ida, "ida"}};
inline constexpr EnumName<LinearSolverKind> kLinSolNames[] = {
    {LinearSolverKind::Auto, "auto"}, {LinearSolverKind::Dense, "dense"}, {LinearSolverKind::Klu, "klu"}};
inline constexpr EnumName<StackKind> kStackNames[] = {
    {StackKind::Auto, "auto"}, {StackKind::Follower, "follower"}, {StackKind::Mechanism, "mechanism"}};
inline constexpr EnumName<CamshaftDrive> kCamshaftDriveNames[] = {{CamshaftDrive::Compliant, "compliant"},
                                                                 {CamshaftDrive::Prescribed, "prescribed"}};
inline constexpr EnumName<ContactPointKind> kContactPointNames[] = {
    {ContactPointKind::Cam, "cam"}, {ContactPointKind::Lash, "lash"}, {ContactPointKind::Stop, "stop"}};
inline constexpr EnumName<StopSide> kStopSideNames[] = {{StopSide::Below, "below"}, {StopSide::Above, "above"}};
inline constexpr EnumName<BarMass> kBarMassNames[] = {{BarMass::Lumped, "lumped"}, {BarMass::Consistent, "consistent"}};


template <class E, std::size_t N>
std::vector<std::string> enum_names(const EnumName<E> (&names)[N]) {
  std::vector<std::string> r;
  for (const auto& n : names) r.emplace_back(n.name);
  return r;
}

// ---------------------------------------------------------------- formatting helpers

/// Shortest decimal form that reads back to the same double ("nan", "inf", "-inf" too).
std::string fmt_num(double v);
/// A double as a TOML float literal (always with '.', 'e', or a nan/inf spelling).
std::string toml_float(double v);
/// A TOML basic string literal.
std::string quote(std::string_view s);
/// An array for a message: all values up to 8, else the first three, "...", the last.
std::string fmt_list(const std::vector<std::string>& items);
std::string fmt_vec(const std::vector<double>& v);
/// A TOML value as written in messages.
std::string fmt_node(const toml::node& n);
std::string join(const std::vector<std::string>& v, const char* sep);
/// "must be one of \"a\", \"b\"".
std::string one_of(const std::vector<std::string>& allowed);
std::string range_rule(long long lo, long long hi);
int line_of(const toml::node& n);

/// Lines of the keys read from a file (dotted path, and path[i] for array elements).
using LineMap = std::map<std::string, int>;

/// @throws SceneError(file, line, key, value, rule), always.
[[noreturn]] void fail(const std::string& file, int line, const std::string& key, const std::string& value,
                       const std::string& rule);
/// An integer value: a TOML integer, or a float with an integral value (3.0).
/// @throws SceneError "must be an integer" otherwise.
long long toml_integer(const toml::node& n, const std::string& file, int line, const std::string& key);
/// A table's entries in file order (by line).
std::vector<std::pair<std::string, const toml::node*>> sorted_entries(const toml::table& t);

// ---------------------------------------------------------------- designer units (scene_units.cpp)

/// The input-only keys in a designer's units: "cam.speed_rpm", "cam.rpm_of", "run.revolutions".
const std::vector<std::string>& designer_unit_keys();
bool is_designer_unit_key(std::string_view key);
/// The designer-unit keys of a scene's tables, checked: the camshaft speed of cam.speed_rpm
/// + cam.rpm_of (rev/s) and run.revolutions.
struct DesignerUnits {
  std::optional<double> speed_rev_s, revolutions;
  double rpm_per_rev_s = 0;  ///< 60 (camshaft) or 120 (engine) with cam.speed_rpm
  std::string revolutions_text;
  int speed_line = 0, revolutions_line = 0;
};
/// @throws SceneError (file, line when use_lines) naming the key, both keys when one
/// quantity is given twice, a missing or bad cam.rpm_of, a bad number.
/// The scene of a parsed TOML table (keys and types read, `overrides` applied as --set,
/// every rule checked once on the result). `root` receives the overrides.
Scene scene_from_table(toml::table& root, const std::string& source_name, const std::vector<std::string>& overrides);

DesignerUnits read_designer_units(const toml::table& root, const std::string& file, bool use_lines);
/// Set cam.speed_rev_s and run.t_end = revolutions / |cam.speed_rev_s| in `s` (its keys
/// read): the scene in rev/s and seconds. @throws SceneError for revolutions with a speed
/// table or a speed of 0.
void apply_designer_units(const DesignerUnits& u, Scene& s, const std::string& file, LineMap& lines);
/// --set: the overrides `keys_set` give cam.speed_rpm (run.revolutions) and not
/// cam.speed_rev_s (run.t_end): drop the scene's own cam.speed_rev_s (run.t_end) from
/// `root`, which the override replaces.
void drop_replaced_by_designer_units(toml::table& root, const std::vector<std::string>& keys_set);

// ---------------------------------------------------------------- network arrays (scene/network_reader.cpp)

/// "nodes", "elements" or "contacts".
bool is_network_array(std::string_view s);

/// The allowed keys of [[nodes]], of every element / contact type, and of each one type
/// (src/scene/network_reader.cpp; the scene-key reference lists them too).
const std::vector<std::string>& node_keys();
const std::vector<std::string>& all_element_keys();
std::vector<std::string> element_keys(ElementKind kind);
const std::vector<std::string>& all_contact_keys();
std::vector<std::string> contact_keys(ContactPointKind kind);
bool contains(const std::vector<std::string>& v, std::string_view s);
/// Parse one network array of `root` into s.network (strict types; errors name
/// "ARRAY[i].KEY" and the line when use_lines).
void read_network_array(const std::string& array, const toml::node& node, Scene& s, const std::string& file,
                        bool use_lines, LineMap& lines);
/// Set one network key given by name or index ("contacts.seat.restitution",
/// "contacts[1].restitution") in `root` (`scene` as a TOML table, see to_table; names and
/// indices are resolved against `scene`, resolve_network_key). Only the
/// key's place is checked (entry exists, key belongs to the entry's type); the value is
/// checked when the table is parsed. Returns the canonical key "ARRAY[i].KEY".
/// @pre is_network_array(the key's first component).
/// @throws SceneError(file, 0, key, value, rule).
std::string insert_network_override(toml::table& root, const Scene& scene, const std::string& key,
                                    const toml::node& value, const std::string& file);

}  // namespace camdyn::scene_detail
