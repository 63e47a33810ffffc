// camdyn (private) — the flights of a run's contacts (issue 35, "events the tolerance cannot
// resolve"; docs/tolerances.md "Flights below the gap tolerance").
//
//   A flight of contact j runs from a separation to the next impact of j. Its apex (largest
//   gap) is taken as the larger of the gaps at the accepted step ends inside it and the
//   least apex its two ends imply: a gap that leaves g = 0 at rate ġ₀ ≥ 0 and returns at
//   −v after a duration Δt (g smooth, no force inside) is a cubic at the least (a separation
//   at ġ₀ = 0: g = a τ²(Δt − τ), apex 4/27·v·Δt) and a parabola at the most (a bounce,
//   apex v·Δt/4): 4/27·v·Δt is a lower estimate between step ends.
//   A flight is unresolved when its apex stays at or below contact.tol_u (the tolerance a
//   closed contact's gap is held to: the method cannot tell the flight from the contact
//   staying closed) or its duration is below the rootfinder's time resolution
//   (100·ε·|t|, SUNDIALS' root tolerance).
#pragma once

#include <string>
#include <vector>

#include "camdyn/simulator.hpp"

namespace camdyn {
namespace detail {

class FlightLog {
 public:
  /// `names`: the contacts' names in order; `tol_u`: contact.tol_u (0: no flight is judged).
  FlightLog(const std::vector<std::string>& names, double tol_u);
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
  double tol_u_ = 0;
};

}  // namespace detail
}  // namespace camdyn
