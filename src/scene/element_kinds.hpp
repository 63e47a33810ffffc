// camdyn — the element kinds of a network as data (private): one table of field descriptors
// per kind ([[elements]] type = "..."), which drives reading a [[elements]] entry, writing it
// (to_toml, summary.json), ElementSpec's equality, `--set elements.NAME.KEY`, the
// allowed-key messages, each key's own rule in the validator and the scene-key reference.
// Adding an element kind: its ElementKind value and ElementSpec members
// (include/camdyn/network.hpp), one ElementKindInfo in src/scene/element_kinds.cpp, and the
// rules between its keys (if any) in src/scene/validate_network.cpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "camdyn/network.hpp"

namespace camdyn::scene_detail {

/// One key of an element kind: its name, the ElementSpec member it reads and writes, the
/// value's type, unit, documentation and own rule.
struct ElementField {
  enum class Type { Real, Int, Reals, OptionalReal, MassMatrix };
  /// A key's own rule, checked by the validator for every element of the kind (rules
  /// between keys are written out in the validator):
  ///   Finite: v finite   Ge: v >= lo   Gt: v > lo   IntRange: imin <= v <= imax
  ///   Custom: only rules between keys (the validator's kind-specific checks); `rule_text`
  ///   says them for the reference.
  enum class Rule { Finite, Ge, Gt, IntRange, Custom };

  const char* key;
  Type type;
  const char* unit;
  const char* doc;
  Rule rule = Rule::Finite;
  double lo = 0.0;
  long long imin = 0, imax = 0;
  /// Rule::Custom (and any rule the generated wording does not say): the rule as the
  /// key reference prints it.
  const char* rule_text = nullptr;
  /// The key reference's default when the default-constructed spec does not give it.
  const char* fixed_default = nullptr;
  /// to_toml writes the key only when this holds (null: always; an unset optional is never
  /// written).
  bool (*written)(const ElementSpec&) = nullptr;

  double ElementSpec::*real = nullptr;
  int ElementSpec::*integer = nullptr;
  std::vector<double> ElementSpec::*reals = nullptr;
  std::optional<double> ElementSpec::*optional = nullptr;
  BarMass ElementSpec::*mass_matrix = nullptr;

  /// The rule as the key reference words it ("must be >= 0").
  std::string rule_words() const;
  /// "real", "integer", "array of reals", "enum".
  const char* type_name() const;
};

/// An element kind: its type name in [[elements]] and its keys besides name, type and nodes
/// (in the order they are written).
struct ElementKindInfo {
  ElementKind kind;
  const char* name;
  std::vector<ElementField> fields;
};

/// Every element kind, in ElementKind order.
const std::vector<ElementKindInfo>& element_kinds();
/// The descriptor of one kind.
const ElementKindInfo& element_kind(ElementKind kind);
/// The field `key` of `kind`, or null when the kind does not take it.
const ElementField* element_field(ElementKind kind, const std::string& key);
/// Whether every field of every kind is equal in a and b (ElementSpec's operator== adds
/// name, kind and nodes).
bool element_fields_equal(const ElementSpec& a, const ElementSpec& b);

/// The key reference's row of one element key ("elements.KEY"), merged over the kinds that
/// take it ("spring: ...; bar: ..." where they differ).
struct ElementKeyDoc {
  std::string key, unit, text, type, rule, fixed_default;
  std::vector<std::string> applies_to;
};
/// Every element key besides name, type and nodes, in first-appearance order over the kinds.
std::vector<ElementKeyDoc> element_key_docs();

}  // namespace camdyn::scene_detail
