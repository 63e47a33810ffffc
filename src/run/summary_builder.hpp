// camdyn (private) — the one place a Summary is made: build_summary takes the scene, the
// mechanism, the scene's warnings, what the run measured (RunRecord,
// src/contact/run_record.hpp) and the run's parts (RunParts: designer statistics, run
// analysis, flight log, surge) and fills every field of the Summary in one function, in a
// fixed order (summary_builder.cpp reads top to bottom). A new summary section: its field in
// include/camdyn/summary.hpp, its measurement in the record or a part, and one line in
// build_summary at the place its inputs are complete.
#pragma once

#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"
#include "contact/run_record.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {
namespace detail {

/// The Summary of one run. The order, each step reading only what the ones before filled:
///  1. what ran: the scene's title, integrator, contact model, the model description;
///  2. how the run ended and the engines' and the method's statistics (the record);
///  3. the contacts: counts, extremes, events, per-contact and per-element results;
///  4. the energy ledger's numbers (residual, scale, magnitude) and the clock;
///  5. the parts' sections: designer statistics and cam geometry, the run analysis (film,
///     lift deviation, ramp velocity, valve timing, seat landings), the contract's flights,
///     the surge;
///  6. what the tolerances mean on this engine and method;
///  7. the contract (it reads 2–5: penetration, the energy numbers, rejected steps, flights);
///  8. the warnings: the scene's first, then the run's;
///  9. the verdict (from the events), then the coil clash (from the contacts and events);
/// 10. the criteria (they read the landings, contacts, Hertz stress, film, lift deviation,
///     ramp velocity: everything above).
/// @param mech the mechanism that ran (the verdict reads its contacts when they are named).
Summary build_summary(const Scene& scene, const MechanicalSystem& mech,
                      const std::vector<std::string>& scene_warnings, const RunRecord& record,
                      const RunParts& parts);

/// Summary::tolerance_meaning and tolerance_warning: what solver.rtol and contact.tol_u
/// bound on the scene's engine and method, in words (docs/tolerances.md). On cvode-bdf the
/// words state the BDF order limits the method gives CVODE on `mech` (the mechanism that
/// ran): cvode_bdf_order (src/contact/methods/bdf_order.hpp); the warning is given where
/// those limits are the A-stable orders 1-2.
void describe_tolerance(const Scene& scene, const MechanicalSystem& mech, Summary& summary);

}  // namespace detail
}  // namespace camdyn
