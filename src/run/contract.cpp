// camdyn — the run's contract (issue 35; docs/tolerances.md "The run's contract").
#include "run/contract.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "camdyn/cam.hpp"
#include "scene/shared_cam.hpp"

namespace camdyn {
namespace detail {

namespace {
std::string g(double x) {
  char b[48];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}
}  // namespace

void check_tolerance_scale(const Scene& sc) {
  const double tol_u = sc.contact.tol_u;
  if (!(tol_u > 0)) return;  // 0 = automatic (resolved before a run)
  double lift = 0;
  try {
    lift = detail::shared_cam(sc.cam)->lift();
  } catch (const std::exception&) {
    return;  // the cam's own error is reported where the cam is built
  }
  if (!(lift > 0) || tol_u <= kTolUOfLift * lift) return;
  throw SceneError(sc.source, 0, "contact.tol_u", g(tol_u),
                   "is larger than " + g(kTolUOfLift * 100) + " % of the cam's lift " + g(lift) +
                       ": a contact may then penetrate by a visible part of the motion and the run's "
                       "contract means nothing; use contact.tol_u <= " + g(kTolUOfLift * lift));
}

void flight_warnings(const Scene& sc, RunContract& c) {
  for (const FlightCount& n : c.flights) {
    if (n.unresolved == 0) continue;
    c.warnings.push_back("contact '" + n.contact + "': " + std::to_string(n.unresolved) + " of " +
                         std::to_string(n.flights) + " flights (separation to impact) below what contact.tol_u = " +
                         g(sc.contact.tol_u) + " resolves (largest gap " + g(n.max_unresolved_apex) + " <= " +
                         g(c.flight_threshold) + ", 1e-3 of the method's gap tolerance; longest " +
                         g(n.max_unresolved_duration) +
                         " s): their impacts and separations are not resolved by this tolerance "
                         "(tighten contact.tol_u and solver.rtol to resolve them)");
  }
}

void check_contract(const Scene& sc, Summary& s) {
  RunContract& c = s.contract;
  c.violations.clear();
  c.warnings.clear();
  c.checked = s.finished;
  c.held = true;
  if (!s.finished) return;
  flight_warnings(sc, c);
  const bool penalty = sc.contact.model == ContactModel::Penalty;
  // 1. Closed contacts: the gap held to tol_u (penalty contacts penetrate by their law).
  if (!penalty && sc.contact.tol_u > 0 && s.max_penetration > kContractGaps * sc.contact.tol_u) {
    c.violations.push_back("largest penetration " + g(s.max_penetration) + " > " + g(kContractGaps) +
                           " contact.tol_u = " + g(kContractGaps * sc.contact.tol_u) +
                           ": a closed contact was not held (tighten contact.tol_u or solver.rtol)");
  }
  // 2. The energy ledger: W − ΔE − D closes to the documented bound.
  const double frac = std::min(std::max(kEnergyPerRtol * sc.solver.rtol, kEnergyFloor), kEnergyCap);
  c.energy_bound = std::max(frac * c.energy_scale, kEnergyRoundoff * kEps * c.energy_magnitude);
  if (c.energy_scale > 0 && s.energy_residual > c.energy_bound) {
    c.violations.push_back("energy residual " + g(s.energy_residual) + " > " + g(frac) +
                           " of the energy scale " + g(c.energy_scale) + " (bound min(max(" + g(kEnergyPerRtol) +
                           "·rtol, " + g(kEnergyFloor) + "), " + g(kEnergyCap) + ") of it, at least the round-off " +
                           g(kEnergyRoundoff * kEps * c.energy_magnitude) + " = " + g(c.energy_bound) +
                           "): the steps did not follow the solution (tighten solver.rtol, now " +
                           g(sc.solver.rtol) + ")");
  }
  // 3. The engine's error test: most attempted steps rejected means the step size is not controlled.
  const double tried = double(s.steps + s.rejected_steps);
  if (tried > 100 && s.rejected_steps > kRejectedFraction * tried) {
    c.violations.push_back(std::to_string(s.rejected_steps) + " of " + std::to_string(long(tried)) +
                           " steps rejected (> " + g(kRejectedFraction * 100) +
                           " %): the engine's error test does not control the step (tighten solver.rtol)");
  }
  c.held = c.violations.empty();
}

}  // namespace detail
}  // namespace camdyn
