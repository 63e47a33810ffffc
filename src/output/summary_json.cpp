// camdyn — summary.json (output.hpp): what ran and how it ended, the run's contract, the
// tolerance words and warnings, the results' sections (summary_json_results.cpp), the
// model, the events and the resolved scene, in this order.
#include <cstddef>
#include <string>

#include "camdyn/output.hpp"
#include "output/summary_json.hpp"

namespace camdyn {

using detail::JsonObject;

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

// What ran and how it ended: the counters, the iterations per level, the engines' statistics.
void put_run(JsonObject& o, const Summary& s, const Scene& resolved, const char* status) {
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
}

// The run's contract: whether it held, the energy bound, the flights it resolved.
void put_contract(JsonObject& o, const Summary& s) {
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
  put_run(o, s, resolved, status);
  put_contract(o, s);
  o.str("tolerance_meaning", s.tolerance_meaning);
  o.str("tolerance_warning", s.tolerance_warning);
  {
    std::string t = "[";
    for (size_t i = 0; i < s.warnings.size(); ++i) t += (i ? ", " : "") + json_string(s.warnings[i]);
    o.raw("warnings", t + "]");
  }
  detail::put_designer_results(o, s);
  detail::put_contact_results(o, s);
  detail::put_valve_results(o, s);
  detail::put_part_sections(o, s);
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
