// camdyn — summary.json's sections of the run's results (summary_json.hpp).
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "camdyn/output.hpp"
#include "output/summary_json.hpp"

namespace camdyn {
namespace detail {

namespace {

// summary.json's "verdict" array (indent: of the enclosing object's keys).
std::string verdict_json(const std::vector<VerdictItem>& v, int indent) {
  const std::string in1(size_t(indent + 2), ' '), in0(size_t(indent), ' ');
  std::string t = "[";
  for (size_t i = 0; i < v.size(); ++i) {
    const VerdictItem& x = v[i];
    t += (i ? ",\n" : "\n") + in1 + "{\"kind\": " + json_string(x.kind) + ", \"contact\": " + json_string(x.contact) +
         ", \"theta_deg\": " + json_number(x.theta_deg) + ", \"speed_rev_s\": " + json_number(x.speed_rev_s) +
         ", \"count\": " + std::to_string(x.count) + ", \"text\": " + json_string(x.text) + "}";
  }
  return t + "\n" + in0 + "]";
}

}  // namespace

void put_designer_results(JsonObject& o, const Summary& s) {
  // designer results (issue 15); NaN → null
  o.num("min_contact_force", s.min_contact_force);
  o.num("min_force_theta_deg", s.min_force_theta_deg);
  o.num("first_separation_theta_deg", s.first_separation_theta_deg);
  o.num("first_impact_theta_deg", s.first_impact_theta_deg);
  o.num("max_impact_velocity", s.max_impact_velocity);
  o.num("max_impact_theta_deg", s.max_impact_theta_deg);
  o.num("max_gap", s.max_gap);
  // cam geometry (issue 24)
  o.num("max_pressure_angle_deg", s.max_pressure_angle_deg);
  o.num("min_radius_of_curvature", s.min_radius_of_curvature);
  o.num("max_side_load", s.max_side_load);
  o.num("max_hertz_stress", s.max_hertz_stress);
  o.num("max_hertz_theta_deg", s.max_hertz_theta_deg);
  o.num("cam_torque_peak", s.cam_torque_peak);
  o.num("cam_torque_mean", s.cam_torque_mean);
  o.num("cam_power_peak", s.cam_power_peak);
  o.num("cam_power_mean", s.cam_power_mean);
  if (!std::isnan(s.cam_friction_force_max)) {
    o.num("cam_friction_force_max", s.cam_friction_force_max);
    o.num("cam_friction_torque_mean", s.cam_friction_torque_mean);
    o.num("cam_friction_power_mean", s.cam_friction_power_mean);
    o.num("cam_friction_power_peak", s.cam_friction_power_peak);
    o.num("cam_friction_work", s.cam_friction_work);
  }
  o.str("cam_continuity", s.cam_continuity);
  o.integer("period", s.period);
  o.str("period_kind", s.period_kind);
  {
    std::string t = "[";
    for (size_t i = 0; i < s.poincare.size(); ++i) {
      const PoincareSample& p = s.poincare[i];
      t += i ? ",\n    " : "\n    ";
      t += "{\"revolution\": " + std::to_string(p.revolution) + ", \"t\": " + json_number(p.t) +
           ", \"u_c\": " + json_number(p.u_c) + ", \"v_c\": " + json_number(p.v_c) + "}";
    }
    t += s.poincare.empty() ? "]" : "\n  ]";
    o.raw("poincare", t);
  }
}

void put_contact_results(JsonObject& o, const Summary& s) {
  if (!s.contacts.empty()) {
    // per contact (issue 28; the lash take-up window: include/camdyn/summary.hpp)
    o.raw("contacts", object_array(o, s.contacts, [](JsonObject& k, const ContactResult& c) {
      k.str("name", c.name);
      k.num("min_force", c.min_force);
      k.num("min_force_theta_deg", c.min_force_theta_deg);
      k.num("max_impact_velocity", c.max_impact_velocity);
      k.num("max_impact_theta_deg", c.max_impact_theta_deg);
      k.num("first_separation_theta_deg", c.first_separation_theta_deg);
      k.num("first_impact_theta_deg", c.first_impact_theta_deg);
      k.integer("impacts", c.impacts);
      k.integer("separations", c.separations);
      k.num("max_side_load", c.max_side_load);
      k.num("max_side_load_theta_deg", c.max_side_load_theta_deg);
      if (!c.coil_spring.empty()) k.str("coil_spring", c.coil_spring);
    }));
  }
}

void put_valve_results(JsonObject& o, const Summary& s) {
  // oil film, lift deviation, ramp velocity, seat landings, acceptance criteria (issue 38)
  o.num("min_film_thickness", s.min_film_thickness);
  o.num("min_film_theta_deg", s.min_film_theta_deg);
  o.num("min_lambda", s.min_lambda);
  o.num("max_ramp_velocity", s.max_ramp_velocity);
  o.num("max_ramp_theta_deg", s.max_ramp_theta_deg);
  o.raw("lift_deviation", object_array(o, s.lift_deviation, [](JsonObject& k, const LiftDeviationRevolution& r) {
    k.integer("revolution", r.revolution);
    k.num("min", r.min);
    k.num("min_theta_deg", r.min_theta_deg);
    k.num("max", r.max);
    k.num("max_theta_deg", r.max_theta_deg);
  }));
  o.raw("landings", object_array(o, s.landings, [](JsonObject& k, const SeatLanding& L) {
    k.str("contact", L.contact);
    k.num("t", L.t);
    k.num("theta_deg", L.theta_deg);
    k.num("velocity", L.velocity);
    k.integer("bounces", L.bounces);
    k.num("bounce_height", L.bounce_height);
    k.num("bounce_height_theta_deg", L.bounce_height_theta_deg);
    k.num("max_velocity", L.max_velocity);
    k.num("max_velocity_theta_deg", L.max_velocity_theta_deg);
  }));
  o.raw("criteria", object_array(o, s.criteria, [](JsonObject& k, const CriterionResult& c) {
    k.str("name", c.name);
    k.str("key", c.key);
    k.str("kind", c.is_max ? "max" : "min");
    k.num("limit", c.limit);
    k.num("value", c.value);
    k.num("theta_deg", c.theta_deg);
    k.boolean("pass", c.pass);
    k.str("note", c.note);
  }));
  o.boolean("criteria_pass", s.criteria_pass);
}

void put_part_sections(JsonObject& o, const Summary& s) {
  if (!s.valve_timing.empty()) {
    // a [camshaft]: each valve's timing (include/camdyn/summary.hpp ValveTimingResult)
    o.raw("valve_timing", object_array(o, s.valve_timing, [](JsonObject& k, const ValveTimingResult& v) {
      k.str("valve", v.valve);
      k.str("contact", v.contact);
      k.integer("cam", v.cam);
      k.num("threshold", v.threshold);
      k.num("kinematic_opening_deg", v.kinematic_opening_deg);
      k.num("kinematic_closing_deg", v.kinematic_closing_deg);
      k.num("opening_deg", v.opening_deg);
      k.num("closing_deg", v.closing_deg);
      k.num("opening_error_deg", v.opening_error_deg);
      k.num("closing_error_deg", v.closing_error_deg);
      k.integer("openings", v.openings);
    }));
  }
  if (!s.coil_clash.empty()) {
    // springs whose coils clash (include/camdyn/summary.hpp CoilClashResult)
    o.raw("coil_clash", object_array(o, s.coil_clash, [](JsonObject& k, const CoilClashResult& c) {
      k.str("spring", c.spring);
      k.integer("impacts", c.impacts);
      k.integer("coils_closed", c.coils_closed);
      k.num("first_impact_theta_deg", c.first_impact_theta_deg);
      k.num("max_impact_velocity", c.max_impact_velocity);
    }));
  }
  if (!s.surge.empty()) {
    // springs with coil masses (include/camdyn/summary.hpp SurgeResult)
    o.raw("surge", object_array(o, s.surge, [](JsonObject& k, const SurgeResult& c) {
      k.str("spring", c.spring);
      k.num("amplitude", c.amplitude);
      k.num("theta_deg", c.theta_deg);
      k.nums("per_revolution", c.per_revolution);
      k.nums("per_revolution_theta_deg", c.per_revolution_theta_deg);
    }));
  }
  if (!s.elements.empty()) {
    // per reported element quantity (ElementResult)
    o.raw("elements", object_array(o, s.elements, [](JsonObject& k, const ElementResult& c) {
      k.str("name", c.name);
      k.num("min", c.min);
      k.num("max", c.max);
      k.num("end", c.end);
      k.num("cycle_range", c.cycle_range);
    }));
  }
  if (!s.verdict.empty()) {
    o.raw("verdict", verdict_json(s.verdict, o.child_indent()));
    o.str("verdict_text", s.verdict_text);
  }
}

}  // namespace detail
}  // namespace camdyn
