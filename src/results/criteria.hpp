// camdyn (private) — the acceptance criteria of a run ([criteria], issue 38): each limit the
// scene sets judged on the run's results (Summary::criteria).
#pragma once

#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {
namespace detail {

/// Fills s.criteria and s.criteria_pass from the results already in `s` (landings, contacts,
/// Hertz stress, film, ramp velocity, lift deviation), in the key table's order.
/// `mech` (the mechanism that ran): its stop contacts, for the words of a seat criterion
/// with nothing to judge (CriterionResult::note).
void judge_criteria(const Scene& scene, const MechanicalSystem& mech, Summary& s);

/// The names judge_criteria gives the criteria `scene` sets, in its order, known before a run
/// (a sweep's columns): the force margins per contact of a network, "force_margin" for a
/// rigid or elastic_bar follower and a one-contact user follower (a user follower with
/// several contacts judges force_margin_<contact>, known only once it is built: its sweep
/// column "force_margin" stays empty).
std::vector<std::string> criterion_names(const Scene& scene);

}  // namespace detail
}  // namespace camdyn
