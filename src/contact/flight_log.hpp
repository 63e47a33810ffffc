// camdyn (private) — the flights of a run's contacts (issue 35, "events the tolerance cannot
// resolve"; docs/tolerances.md "Flights below the gap tolerance").
//
//   A flight of contact j runs from a separation to the next impact of j. Its apex (largest
//   gap) is taken as the larger of the gaps at the accepted step ends inside it and the
//   least apex its two ends imply: a gap that leaves g = 0 at rate ġ₀ ≥ 0 and returns at
//   −v after a duration Δt (g smooth, no force inside) is a cubic at the least (a separation
//   at ġ₀ = 0: g = a τ²(Δt − τ), apex 4/27·v·Δt) and a parabola at the most (a bounce,
//   apex v·Δt/4): 4/27·v·Δt is a lower estimate between step ends.
//   A flight is unresolved when its apex stays at or below kFlightGaps = 10⁻³ of the
//   method's gap tolerance (Lee: contact.tol_u; the event method: its root gap tolerance
//   min(tol_u, max(rtol·X, 1000ε·X))), the scale at which the methods root a closing gap
//   (an offset of 10⁻³ gap tolerance) and make an impact stick (a rebound of that height),
//   or its duration is below the rootfinder's time resolution (100·ε·|t|, SUNDIALS' root
//   tolerance). Not apex ≤ tol_u: on examples/ohv_pushrod_train.toml flights of apex
//   1e-11 … 1e-10 (tol_u = 1e-9) appear at every rtol from 1e-6 to 1e-10 on Lee and the
//   event method alike (docs/tolerances.md "Flights below the gap tolerance").
#pragma once

#include <string>
#include <vector>

#include "camdyn/summary.hpp"

namespace camdyn {
namespace detail {

class FlightLog {
 public:
  /// Apex threshold of an unresolved flight in units of the method's gap tolerance.
  static constexpr double kFlightGaps = 1e-3;
  /// `names`: the contacts' names in order; `gap_tol`: the method's gap tolerance (0: no
  /// flight is judged, e.g. penalty, whose contacts penetrate by their law).
  FlightLog(const std::vector<std::string>& names, double gap_tol);
  /// Sets the method's gap tolerance (a method that roots gaps with its own: at its start).
  void set_gap_tolerance(double gap_tol) { tol_ = gap_tol; }
  double threshold() const { return kFlightGaps * tol_; }
  /// An event of contact j at time t (an impact with approach speed v).
  void event(EventKind type, int j, double t, double v);
  /// The gap of contact j at an accepted step end (used while j is in flight).
  void sample(int j, double gap);
  /// The contacts' flight counts into s.contract.flights (only contacts with flights).
  void finish(Summary& s) const;

 private:
  struct Contact {
    bool flying = false;
    double t_sep = 0, apex = 0;
    FlightCount count;
  };
  std::vector<Contact> c_;
  double tol_ = 0;
};

}  // namespace detail
}  // namespace camdyn
