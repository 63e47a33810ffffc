// camdyn (private) — the laws of one contact (src/mechanism/mechanism.hpp: MechanismContact::law).
//
//   Each contact holds its own laws, filled from the contact's scene values with the scene's
//   [contact] table as the defaults (ContactLaw::of):
//     impact   Newton's law on the normal direction: ġ⁺ = −e ġ⁻ (the exact methods: Lee,
//              event-driven, holonomic; src/contact/impact.cpp)
//     penalty  the penalty baseline's normal force (penalty_law.hpp; methods/penalty.cpp)
//   Both act along the contact's normal row T_j. A tangential law (friction) is another member
//   here with its own row (the contact's tangent direction), read by the methods that apply it:
//   the normal laws and their callers do not change when it is added.
#pragma once

#include <optional>

#include "camdyn/scene.hpp"
#include "contact/laws/penalty_law.hpp"

namespace camdyn {

/// Newton's impact law: the normal gap rate after an impact is −e times the one before.
struct ImpactLaw {
  double restitution = 0.0;  ///< e ∈ [0, 1]
};

struct ContactLaw {
  ImpactLaw impact;
  PenaltyNormalLaw penalty;

  /// The laws of a contact whose own values (unset: the [contact] table's) are e, k_p, c_p;
  /// the penalty law's kind and exponent are the [contact] table's.
  static ContactLaw of(const ContactSpec& defaults, std::optional<double> restitution = std::nullopt,
                       std::optional<double> penalty_stiffness = std::nullopt,
                       std::optional<double> penalty_damping = std::nullopt) {
    ContactLaw l;
    l.impact.restitution = restitution.value_or(defaults.restitution);
    l.penalty = PenaltyNormalLaw(defaults.penalty_law, penalty_stiffness.value_or(defaults.penalty_stiffness),
                                 penalty_damping.value_or(defaults.penalty_damping), defaults.penalty_exponent);
    return l;
  }
};

}  // namespace camdyn
