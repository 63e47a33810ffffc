// camdyn (private) — summary.json's sections of the run's results, in the file's order
// (summary_json_results.cpp); summary_json (summary_json.cpp) writes them between the run's
// contract and its model.
#pragma once

#include "camdyn/summary.hpp"
#include "output/json_writer.hpp"

namespace camdyn {
namespace detail {

/// The designer results: contact force, separations and impacts by cam angle, the cam's
/// geometry along the run, cam friction, the cam's continuity, the period and the
/// Poincaré samples.
void put_designer_results(JsonObject& o, const Summary& s);
/// "contacts": one object per contact (networks and user followers; absent otherwise).
void put_contact_results(JsonObject& o, const Summary& s);
/// The valve's results: oil film, ramp velocity, lift deviation per revolution, seat
/// landings, the acceptance criteria and whether they all pass.
void put_valve_results(JsonObject& o, const Summary& s);
/// The parts' sections, each only when the run has it: valve timing, coil clash, surge,
/// element quantities, the verdict.
void put_part_sections(JsonObject& o, const Summary& s);

}  // namespace detail
}  // namespace camdyn
