// camdyn (private) — the run's contract (issue 35): what a finished run checks about its
// own result, and the tolerances refused at the start because no result could honour them.
#pragma once

#include "camdyn/scene.hpp"
#include "camdyn/summary.hpp"

namespace camdyn {
namespace detail {

/// The contract's gap tolerance in units of contact.tol_u: a closed contact's penetration
/// must stay within kContractGaps·tol_u (the step check of ContactRun uses the same).
constexpr double kContractGaps = 10.0;
/// contact.tol_u may be at most this fraction of the cam's lift.
constexpr double kTolUOfLift = 1e-2;
/// The energy ledger must close to min(max(kEnergyPerRtol·rtol, kEnergyFloor), kEnergyCap)
/// of its scale. The floor: early in a run the scale is small and the residual's own
/// quadrature error dominates (holonomic on ida over the OHC train's first 0.01 s at rtol
/// 1e-8 reads 1.3e-6 of a 0.12 J scale; 1.9e-8 over its revolution).
constexpr double kEnergyPerRtol = 100.0;
constexpr double kEnergyFloor = 1e-5;
constexpr double kEnergyCap = 1e-2;
/// ... and never below round-off: kEnergyRoundoff·ε times RunContract::energy_magnitude (a
/// run in which almost nothing moves — the OHV train at θ₀ = 20° over 1.5 ms: scale 8.6e-13 J,
/// residual 3.7e-15 J, bound 8.6e-18 J without the floor; the seat's 330 N over the cam's
/// 6 mm lift makes the floor 4.4e-13 J).
constexpr double kEnergyRoundoff = 1000.0;
constexpr double kEps = 2.220446049250313e-16;
/// More rejected than this fraction of all attempted steps: the error test does not control the step.
constexpr double kRejectedFraction = 0.5;

/// Refuses a contact.tol_u larger than kTolUOfLift of the cam's lift (a gap tolerance of
/// that size is a visible part of the motion it is meant to resolve).
/// @throws SceneError naming contact.tol_u, its value and the largest accepted value.
void check_tolerance_scale(const Scene& scene);

/// Fills summary.contract for a finished run from its statistics (penetration against
/// tol_u, the energy residual against its bound, the engine's rejected steps); leaves it
/// unchecked (held) for a run that did not finish. summary.contract.energy_scale must have
/// been set by the run.
void check_contract(const Scene& scene, Summary& summary);

/// One warning line in contract.warnings per contact of contract.flights with flights the
/// gap tolerance cannot resolve (FlightCount::unresolved > 0), naming contact.tol_u and the
/// numbers. A warning: the contract still holds.
void flight_warnings(const Scene& scene, RunContract& contract);

}  // namespace detail
}  // namespace camdyn
