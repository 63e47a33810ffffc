// camdyn — the flights of a run's contacts (flight_log.hpp).
#include "contact/flight_log.hpp"

#include <algorithm>
#include <cmath>

namespace camdyn {
namespace detail {

namespace {
constexpr double kCubicApex = 4.0 / 27.0;            // least apex / (v·Δt) of a flight
constexpr double kRootTimeRel = 100.0 * 2.220446049250313e-16;  // SUNDIALS' root tolerance / |t|
}  // namespace

FlightLog::FlightLog(const std::vector<std::string>& names, double gap_tol) : c_(names.size()), tol_(gap_tol) {
  for (std::size_t j = 0; j < names.size(); ++j) c_[j].count.contact = names[j];
}

void FlightLog::event(EventKind type, int j, double t, double v) {
  if (j < 0 || j >= int(c_.size())) return;
  Contact& c = c_[j];
  if (type == EventKind::Separation) {
    c.flying = true;
    c.t_sep = t;
    c.apex = 0.0;
    return;
  }
  if (type != EventKind::Impact || !c.flying) return;
  c.flying = false;
  const double dt = t - c.t_sep;
  const double apex = std::max(c.apex, kCubicApex * std::abs(v) * dt);
  FlightCount& n = c.count;
  ++n.flights;
  const bool short_time = dt <= kRootTimeRel * std::max(std::abs(t), 1e-300);
  if (tol_ > 0 && (apex <= threshold() || short_time)) {
    ++n.unresolved;
    n.max_unresolved_apex = std::max(n.max_unresolved_apex, apex);
    n.max_unresolved_duration = std::max(n.max_unresolved_duration, dt);
  }
  n.min_apex = std::isnan(n.min_apex) ? apex : std::min(n.min_apex, apex);
}

void FlightLog::sample(int j, double gap) {
  if (j < 0 || j >= int(c_.size()) || !c_[j].flying) return;
  c_[j].apex = std::max(c_[j].apex, gap);
}

void FlightLog::finish(Summary& s) const {
  s.contract.flights.clear();
  s.contract.flight_threshold = threshold();
  for (const Contact& c : c_)
    if (c.count.flights > 0) s.contract.flights.push_back(c.count);
}

}  // namespace detail
}  // namespace camdyn
