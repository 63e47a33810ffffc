// camdyn — JSON output: number and string formatting, summary.json (see output.hpp).
#include "camdyn/output.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace camdyn {

// ---- JSON formatting -----------------------------------------------------------------

namespace {

void append_json_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, x);
  std::string_view s;
  if (res.ec == std::errc()) {
    s = std::string_view(buf, static_cast<size_t>(res.ptr - buf));
  } else {
    int n = std::snprintf(buf, sizeof buf, "%.17g", x);
    s = std::string_view(buf, static_cast<size_t>(n));
  }
  // JSON has no "inf"; to_chars never writes a leading '+' or '.', so s is valid JSON.
  out += s;
}

// Length of the valid UTF-8 sequence at s[i], or 0 if invalid.
size_t utf8_len(std::string_view s, size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  size_t n = 0;
  unsigned cp = 0;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0) {
    n = 2;
    cp = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    n = 3;
    cp = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    n = 4;
    cp = c & 0x07;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    const auto d = static_cast<unsigned char>(s[i + k]);
    if ((d & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (d & 0x3F);
  }
  // reject overlong forms, surrogates and out-of-range code points
  if ((n == 2 && cp < 0x80) || (n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000) ||
      (cp >= 0xD800 && cp <= 0xDFFF) || cp > 0x10FFFF) {
    return 0;
  }
  return n;
}

void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (size_t i = 0; i < s.size();) {
    const char c = s[i];
    const auto uc = static_cast<unsigned char>(c);
    if (uc >= 0x80) {
      size_t n = utf8_len(s, i);
      if (n == 0) {
        out += "\\ufffd";
        ++i;
      } else {
        out.append(s.substr(i, n));
        i += n;
      }
      continue;
    }
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (uc < 0x20 || uc == 0x7F) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", uc);
          out += buf;
        } else {
          out += c;
        }
    }
    ++i;
  }
  out += '"';
}

// A tiny pretty-printing JSON object writer.
class JsonObject {
 public:
  explicit JsonObject(std::string& out, int indent) : out_(out), indent_(indent) {
    out_ += '{';
  }
  void key(std::string_view k) {
    out_ += first_ ? "\n" : ",\n";
    first_ = false;
    out_.append(static_cast<size_t>(indent_ + 2), ' ');
    append_json_string(out_, k);
    out_ += ": ";
  }
  void num(std::string_view k, double v) {
    key(k);
    append_json_number(out_, v);
  }
  void integer(std::string_view k, long long v) {
    key(k);
    out_ += std::to_string(v);
  }
  void boolean(std::string_view k, bool v) {
    key(k);
    out_ += v ? "true" : "false";
  }
  void str(std::string_view k, std::string_view v) {
    key(k);
    append_json_string(out_, v);
  }
  void nums(std::string_view k, const std::vector<double>& v) {
    key(k);
    out_ += '[';
    for (size_t i = 0; i < v.size(); ++i) {
      if (i) out_ += ", ";
      append_json_number(out_, v[i]);
    }
    out_ += ']';
  }
  void strs(std::string_view k, const std::vector<std::string>& v) {
    key(k);
    out_ += '[';
    for (size_t i = 0; i < v.size(); ++i) {
      if (i) out_ += ", ";
      append_json_string(out_, v[i]);
    }
    out_ += ']';
  }
  void raw(std::string_view k, std::string_view json) {
    key(k);
    out_ += json;
  }
  int child_indent() const { return indent_ + 2; }
  void close() {
    if (!first_) {
      out_ += '\n';
      out_.append(static_cast<size_t>(indent_), ' ');
    }
    out_ += '}';
  }

 private:
  std::string& out_;
  int indent_;
  bool first_ = true;
};

// A JSON array of objects, one per item, each filled by fill(JsonObject&, item), its lines
// indented as the children of `o` ("[]" when empty).
template <class T, class Fill>
std::string object_array(const JsonObject& o, const std::vector<T>& items, Fill fill) {
  std::string t = "[";
  for (size_t i = 0; i < items.size(); ++i) {
    std::string u;
    JsonObject k(u, o.child_indent() + 2);
    fill(k, items[i]);
    k.close();
    t += (i ? ",\n" : "\n") + std::string(size_t(o.child_indent() + 2), ' ') + u;
  }
  t += items.empty() ? "]" : "\n" + std::string(size_t(o.child_indent()), ' ') + "]";
  return t;
}

// One scene key as a JSON member, by its kind (the tables and the network's objects).
void put_entry(JsonObject& w, const SceneEntry& e) {
  switch (e.kind) {
    case SceneEntry::Kind::Real: w.num(e.key, e.real); break;
    case SceneEntry::Kind::Int: w.integer(e.key, e.integer); break;
    case SceneEntry::Kind::Bool: w.boolean(e.key, e.boolean); break;
    case SceneEntry::Kind::Str: w.str(e.key, e.text); break;
    case SceneEntry::Kind::Array: w.nums(e.key, e.array); break;
    case SceneEntry::Kind::Names: w.strs(e.key, e.names); break;
  }
}

}  // namespace

std::string json_number(double x) {
  std::string s;
  append_json_number(s, x);
  return s;
}

std::string json_string(std::string_view s) {
  std::string out;
  append_json_string(out, s);
  return out;
}

// ---- summary.json -----------------------------------------------------------------------

std::string scene_json(const Scene& s, int indent) {
  std::string out;
  JsonObject o(out, indent);
  // One nested object per table, filled from the scene's own key list (the one the loader
  // and to_toml use), so no key can be missing here.
  std::string table, body;
  std::unique_ptr<JsonObject> child;
  auto close_table = [&] {
    if (!child) return;
    child->close();
    o.raw(table, body);
    child.reset();
    body.clear();
  };
  for_each_scene_entry(s, [&](const SceneEntry& e) {
    if (e.table != table) {
      close_table();
      table = e.table;
      if (!table.empty()) child = std::make_unique<JsonObject>(body, o.child_indent());
    }
    JsonObject& w = child ? *child : o;
    put_entry(w, e);
  });
  close_table();
  // The network (follower.kind = "network"): "nodes", "elements", "contacts" as arrays of
  // objects with the keys of the scene file. Absent for the other follower kinds.
  if (s.follower.kind == FollowerKind::Network || !s.network.nodes.empty() || !s.network.elements.empty() ||
      !s.network.contacts.empty()) {
    std::map<std::string, std::vector<std::string>> objects;
    for_each_network_entry(s, [&](const std::string& array, std::size_t, const std::vector<SceneEntry>& keys) {
      std::string body;
      JsonObject w(body, o.child_indent() + 2);
      for (const auto& e : keys) {
        put_entry(w, e);
      }
      w.close();
      objects[array].push_back(std::move(body));
    });
    for (const char* array : {"nodes", "elements", "contacts"}) {
      const auto& list = objects[array];
      std::string a = "[";
      for (std::size_t i = 0; i < list.size(); ++i) {
        a += i ? ",\n" : "\n";
        a.append(static_cast<std::size_t>(o.child_indent() + 2), ' ');
        a += list[i];
      }
      if (!list.empty()) {
        a += '\n';
        a.append(static_cast<std::size_t>(o.child_indent()), ' ');
      }
      a += ']';
      o.raw(array, a);
    }
  }
  o.str("source", s.source);
  o.close();
  return out;
}

namespace {

std::string level_json(const LevelStats& l, int indent) {
  std::string t;
  JsonObject c(t, indent);
  c.num("mean", l.mean());
  c.integer("max", l.max);
  c.integer("total", l.total);
  c.integer("steps", l.steps);
  c.close();
  return t;
}

std::string model_json(const ModelDescription& m, int indent) {
  std::string t;
  JsonObject c(t, indent);
  c.str("follower", m.follower);
  c.integer("nodes", m.nodes);
  c.integer("unknowns", m.unknowns);
  c.str("mass", m.mass);
  c.boolean("sparse", m.sparse);
  c.str("linear_solver", m.linear_solver);
  c.boolean("damping", m.damping);
  c.boolean("preload", m.preload);
  c.boolean("varying_speed", m.varying_speed);
  c.str("contact", m.contact);
  c.strs("rhs_terms", m.rhs_terms);
  // Network followers: one line per assembled element and contact (FullReport's lines).
  if (!m.network.empty()) c.strs("network", m.network);
  c.close();
  return t;
}

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

const char* summary_status(const Summary& s) {
  switch (s.termination) {
    case Termination::Finished: return "finished";
    case Termination::StoppedByObserver:
    case Termination::StoppedByCaller: return "interrupted";
    default: return "failed";
  }
}

std::string summary_json(const Summary& s, const Scene& resolved, const char* status) {
  std::string out;
  JsonObject o(out, 0);
  o.str("scene", s.scene.empty() ? resolved.title : s.scene);
  o.str("status", status ? status : summary_status(s));
  o.boolean("finished", s.finished);
  o.str("termination", to_string(s.termination));
  o.str("message", s.message);
  o.num("t_end", s.t_end);
  o.num("t_end_requested", resolved.run.t_end);
  o.integer("steps", s.steps);
  o.integer("rejected_steps", s.rejected_steps);
  o.integer("rhs_evals", s.rhs_evals);
  o.integer("contact_iterations", s.contact_iterations);
  o.integer("separations", s.separations);
  o.integer("impacts", s.impacts);
  o.num("max_contact_force", s.max_contact_force);
  o.num("min_gap", s.min_gap);
  o.num("max_penetration", s.max_penetration);
  o.num("cpu_seconds", s.cpu_seconds);
  o.num("wall_seconds", s.wall_seconds);
  o.str("integrator", s.integrator);
  o.str("contact_model", s.contact_model);
  {
    std::string t;
    JsonObject c(t, o.child_indent());
    c.raw("displacement", level_json(s.level_u, c.child_indent()));
    c.raw("velocity", level_json(s.level_v, c.child_indent()));
    c.raw("acceleration", level_json(s.level_a, c.child_indent()));
    c.close();
    o.raw("iterations", t);
  }
  o.integer("iteration_failures", s.iteration_failures);
  o.integer("relocated_steps", s.relocated_steps);
  o.integer("lin_setups", s.lin_setups);
  o.integer("lin_analyses", s.lin_analyses);
  o.integer("engine_restarts", s.engine_restarts);
  o.integer("nonlin_iters", s.nonlin_iters);
  o.integer("nonlin_conv_fails", s.nonlin_conv_fails);
  o.integer("err_test_fails", s.err_test_fails);
  if (s.first_tensile_time >= 0) {
    o.num("first_tensile_time", s.first_tensile_time);
  } else {
    o.raw("first_tensile_time", "null");
  }
  o.num("energy_residual", s.energy_residual);
  {
    std::string t;
    JsonObject c(t, o.child_indent());
    c.boolean("checked", s.contract.checked);
    c.boolean("held", s.contract.held);
    c.strs("violations", s.contract.violations);
    c.num("energy_scale", s.contract.energy_scale);
    c.num("energy_magnitude", s.contract.energy_magnitude);
    c.num("energy_bound", s.contract.energy_bound);
    c.strs("warnings", s.contract.warnings);
    c.num("flight_threshold", s.contract.flight_threshold);
    {
      std::string f = "[";
      for (size_t i = 0; i < s.contract.flights.size(); ++i) {
        const FlightCount& n = s.contract.flights[i];
        std::string e;
        JsonObject fo(e, c.child_indent());
        fo.str("contact", n.contact);
        fo.integer("flights", n.flights);
        fo.integer("unresolved", n.unresolved);
        fo.num("min_apex", n.min_apex);
        fo.num("max_unresolved_apex", n.max_unresolved_apex);
        fo.num("max_unresolved_duration", n.max_unresolved_duration);
        fo.close();
        f += (i ? ", " : "") + e;
      }
      c.raw("flights", f + "]");
    }
    c.close();
    o.raw("contract", t);
  }
  o.str("tolerance_meaning", s.tolerance_meaning);
  o.str("tolerance_warning", s.tolerance_warning);
  {
    std::string t = "[";
    for (size_t i = 0; i < s.warnings.size(); ++i) t += (i ? ", " : "") + json_string(s.warnings[i]);
    o.raw("warnings", t + "]");
  }
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
  o.raw("model", model_json(s.model, o.child_indent()));
  o.integer("events", static_cast<long long>(s.events.size()));
  {
    long impacts = 0, separations = 0, tensile = 0, other = 0;
    for (const auto& e : s.events) {
      switch (e.type) {
        case EventKind::Impact: ++impacts; break;
        case EventKind::Separation: ++separations; break;
        case EventKind::Tensile: ++tensile; break;
        default: ++other;
      }
    }
    std::string t;
    JsonObject c(t, o.child_indent());
    c.integer("impact", impacts);
    c.integer("separation", separations);
    c.integer("tensile", tensile);
    if (other) c.integer("other", other);
    c.close();
    o.raw("event_counts", t);
  }
  o.raw("options", scene_json(resolved, o.child_indent()));
  o.close();
  out += '\n';
  return out;
}

void write_summary(const std::string& dir, const Summary& summary, const Scene& resolved) {
  write_file_atomic(join_path(dir, "summary.json"), summary_json(summary, resolved));
}

void write_running_summary(const std::string& dir, const Scene& resolved) {
  Summary s;
  s.scene = resolved.title;
  s.finished = false;
  s.termination = Termination::Error;
  s.message = "running (a run that ends without replacing this file did not finish)";
  write_file_atomic(join_path(dir, "summary.json"), summary_json(s, resolved, "running"));
}

}  // namespace camdyn
