// camdyn — the acceptance criteria of a run (criteria.hpp).
#include "results/criteria.hpp"

#include <algorithm>
#include <cmath>

#include "results/run_analysis.hpp"  // is_seat

namespace camdyn {
namespace detail {

namespace {

void add(Summary& s, const std::string& name, const char* key, bool is_max, double limit, double value,
         double theta, const std::string& why_none) {
  CriterionResult c;
  c.name = name;
  c.key = key;
  c.is_max = is_max;
  c.limit = limit;
  c.value = value;
  c.theta_deg = std::isnan(value) ? NAN : theta;
  c.pass = std::isnan(value) || (is_max ? value <= limit : value >= limit);
  if (std::isnan(value)) c.note = why_none;
  s.criteria_pass = s.criteria_pass && c.pass;
  s.criteria.push_back(c);
}

}  // namespace

void judge_criteria(const Scene& sc, const MechanicalSystem& mech, Summary& s) {
  s.criteria.clear();
  s.criteria_pass = true;
  const CriteriaSpec& k = sc.criteria;
  // The scene's contacts are named when it lists them ([[contacts]]); otherwise its own
  // follower has one unnamed cam contact (a user follower's contacts are named in s.contacts).
  const bool named = !sc.network.contacts.empty();
  // Seat landings are measured on the scene's seats (is_seat); why a seat criterion has
  // nothing to judge: no impact on a seat, no stop contact at all, or stop contacts that
  // are no seat (a user follower's, a stop above its node).
  const bool seats = std::any_of(sc.network.contacts.begin(), sc.network.contacts.end(), is_seat);
  const int stops = mech.m() - mech.cam_contacts();
  std::string no_seat = "no seat impact in the run";
  if (!seats && stops == 0) no_seat = "no seat: the follower has no stop contact";
  if (!seats && stops > 0)
    no_seat = std::string("no seat: seat landings are measured on the scene's [[contacts]] stops below a node, and ") +
              (stops == 1 ? "the follower's stop contact is not one"
                          : "none of the follower's " + std::to_string(stops) + " stop contacts is one");
  if (k.max_seating_velocity > 0) {
    double v = NAN, th = NAN;
    for (const SeatLanding& L : s.landings)
      if (std::isnan(v) || L.max_velocity > v) v = L.max_velocity, th = L.max_velocity_theta_deg;
    add(s, "seating_velocity", "criteria.max_seating_velocity", true, k.max_seating_velocity, v, th, no_seat);
  }
  if (k.max_bounce_height > 0) {
    double v = NAN, th = NAN;
    for (const SeatLanding& L : s.landings)
      if (std::isnan(v) || L.bounce_height > v) v = L.bounce_height, th = L.bounce_height_theta_deg;
    add(s, "bounce_height", "criteria.max_bounce_height", true, k.max_bounce_height, v, th, no_seat);
  }
  if (k.max_bounce_count >= 0) {
    double v = NAN, th = NAN;
    for (const SeatLanding& L : s.landings)
      if (std::isnan(v) || double(L.bounces) > v) v = double(L.bounces), th = L.theta_deg;
    add(s, "bounce_count", "criteria.max_bounce_count", true, double(k.max_bounce_count), v, th, no_seat);
  }
  if (k.min_force_margin > 0) {
    for (const ContactResult& c : s.contacts)
      add(s, s.contacts.size() == 1 && !named ? std::string("force_margin") : "force_margin_" + c.name,
          "criteria.min_force_margin", false, k.min_force_margin, c.min_force, c.min_force_theta_deg,
          "never closed outside the lash take-up window");
  }
  if (k.max_hertz_stress > 0)
    add(s, "hertz_stress", "criteria.max_hertz_stress", true, k.max_hertz_stress, s.max_hertz_stress,
        s.max_hertz_theta_deg, "the cam never carried a load");
  if (k.min_film_thickness > 0)
    add(s, "film_thickness", "criteria.min_film_thickness", false, k.min_film_thickness, s.min_film_thickness,
        s.min_film_theta_deg, "the cam never carried a load at an output row");
  if (k.min_lambda > 0)
    add(s, "lambda", "criteria.min_lambda", false, k.min_lambda, s.min_lambda, s.min_film_theta_deg,
        "the cam never carried a load at an output row");
  if (k.max_ramp_velocity > 0)
    add(s, "ramp_velocity", "criteria.max_ramp_velocity", true, k.max_ramp_velocity, s.max_ramp_velocity,
        s.max_ramp_theta_deg, "the cam lift never crossed a take-up level > 0 between output rows");
  if (k.max_lift_deviation > 0) {
    double v = NAN, th = NAN;
    for (const LiftDeviationRevolution& r : s.lift_deviation) {
      if (std::isnan(v) || std::abs(r.min) > v) v = std::abs(r.min), th = r.min_theta_deg;
      if (std::abs(r.max) > v) v = std::abs(r.max), th = r.max_theta_deg;
    }
    add(s, "lift_deviation", "criteria.max_lift_deviation", true, k.max_lift_deviation, v, th, "no output row");
  }
}

std::vector<std::string> criterion_names(const Scene& sc) {
  const CriteriaSpec& k = sc.criteria;
  std::vector<std::string> n;
  if (k.max_seating_velocity > 0) n.push_back("seating_velocity");
  if (k.max_bounce_height > 0) n.push_back("bounce_height");
  if (k.max_bounce_count >= 0) n.push_back("bounce_count");
  if (k.min_force_margin > 0) {
    for (const ContactPointSpec& c : sc.network.contacts) n.push_back("force_margin_" + c.name);
    if (sc.network.contacts.empty()) n.push_back("force_margin");  // the one unnamed cam contact
  }
  if (k.max_hertz_stress > 0) n.push_back("hertz_stress");
  if (k.min_film_thickness > 0) n.push_back("film_thickness");
  if (k.min_lambda > 0) n.push_back("lambda");
  if (k.max_ramp_velocity > 0) n.push_back("ramp_velocity");
  if (k.max_lift_deviation > 0) n.push_back("lift_deviation");
  return n;
}

}  // namespace detail
}  // namespace camdyn
