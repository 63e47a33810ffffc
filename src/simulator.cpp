// camdyn — the simulator: scene → model → engine + contact method → history/summary.
//
//   Simulator validates the scene and builds the model once; each run() makes the contact
//   method the scene asks for from the registry (src/contact/registry.cpp; the shared run
//   machinery is src/run_context.hpp) and runs it.
#include "camdyn/simulator.hpp"

#include <cstdio>
#include <sstream>

#include "contact/network_run.hpp"
#include "mechanism.hpp"
#include "run_context.hpp"

namespace camdyn {

using detail::fmt;

const std::vector<std::string>& history_columns() {
  static const std::vector<std::string> cols{"t",       "theta",     "u_c",      "v_c",
                                             "a_c",     "contact_force", "gap", "in_contact",
                                             "kinetic", "potential", "work_cam", "dissipated"};
  return cols;
}

const char* to_string(EventKind k) {
  switch (k) {
    case EventKind::Impact: return "impact";
    case EventKind::Separation: return "separation";
    case EventKind::Tensile: return "tensile";
  }
  return "impact";
}

const char* to_string(Termination v) {
  switch (v) {
    case Termination::Finished: return "finished";
    case Termination::StoppedByObserver: return "stopped_by_observer";
    case Termination::StoppedByCaller: return "stopped_by_caller";
    case Termination::MaxSteps: return "max_steps";
    case Termination::StepSizeUnderflow: return "step_size_underflow";
    case Termination::IterationFailure: return "iteration_failure";
    case Termination::NonFinite: return "non_finite";
    case Termination::StepFailure: return "step_failure";
    case Termination::SolverError: return "solver_error";
    case Termination::InvalidScene: return "invalid_scene";
    case Termination::Error: return "error";
  }
  return "error";
}

Simulator::Simulator(Scene scene) : scene_(std::move(scene)) {
  resolve_defaults(scene_);
  validate(scene_);
  if (scene_.follower.kind == FollowerKind::Network) {
    if (scene_.solver.integrator == Integrator::Ida)
      throw SceneError(scene_.source, 0, "solver.integrator", "ida",
                       "a network runs on arkode-erk, arkode-dirk or cvode-bdf (ida: single-follower "
                       "holonomic scenes only)");
    mech_ = std::make_shared<const Mechanism>(scene_);
    extra_columns_ = detail::NetworkRun::extra_columns(*mech_);
  } else {
    model_ = build_model(scene_);
  }
}

Simulator::Simulator(Scene scene, std::shared_ptr<const FollowerSystem> follower) : scene_(std::move(scene)) {
  resolve_defaults(scene_);
  validate(scene_);
  if (scene_.solver.integrator == Integrator::Ida)
    throw SceneError(scene_.source, 0, "solver.integrator", "ida",
                     "a user-defined follower runs on arkode-erk, arkode-dirk or cvode-bdf (ida: "
                     "single-follower holonomic scenes only)");
  mech_ = make_user_system(scene_, std::move(follower));
  extra_columns_ = detail::NetworkRun::extra_columns(*mech_);
}

const ModelDescription& Simulator::description() const {
  return mech_ ? mech_->description() : model_->description();
}

Simulator::~Simulator() = default;

Summary Simulator::run(Observer* observer, const std::atomic<bool>* stop,
                       const std::string& stop_reason) {
  if (mech_) {
    auto method = detail::make_network_method(scene_, mech_, observer, stop);
    method->set_stop_reason(stop_reason);
    return method->run();
  }
  auto method = detail::make_contact_method(scene_, model_, observer, stop);
  method->set_stop_reason(stop_reason);
  return method->run();
}

namespace {
struct Collector : Observer {
  std::vector<HistoryRow>* rows;
  void on_row(const HistoryRow& r) override { rows->push_back(r); }
};
}  // namespace

RunResult simulate(const Scene& scene) {
  RunResult res;
  Collector c;
  c.rows = &res.rows;
  Simulator sim(scene);
  res.summary = sim.run(&c);
  return res;
}

std::string Summary::BriefReport() const {
  std::ostringstream o;
  o << "camdyn: " << (finished ? "finished" : "NOT finished") << " — " << scene << " — "
    << contact_model << " on " << integrator << ": t = " << fmt(t_end) << ", " << steps
    << " steps (" << rejected_steps << " rejected), " << rhs_evals << " rhs evals, "
    << separations << " separations, " << impacts << " impacts, max force "
    << fmt(max_contact_force) << ", cpu " << fmt(cpu_seconds) << " s";
  if (!finished) o << " — " << message << " [" << to_string(termination) << "]";
  return o.str();
}

std::string Summary::FullReport() const {
  std::ostringstream o;
  auto lv = [&](const char* name, const LevelStats& s) {
    o << "  " << name << ": mean " << fmt(s.mean()) << ", max " << s.max << ", total " << s.total
      << "\n";
  };
  o << "camdyn run summary\n"
    << "  scene:              " << scene << "\n"
    << "  model:              " << model.ToString() << "\n"
    << "  contact model:      " << contact_model << "\n"
    << "  integrator:         " << integrator << "\n"
    << "  finished:           " << (finished ? "yes" : "no") << " (" << message << ")\n"
    << "  termination:        " << to_string(termination) << "\n"
    << "  t reached:          " << fmt(t_end) << "\n"
    << "  steps:              " << steps << " accepted, " << rejected_steps << " rejected\n"
    << "  rhs evaluations:    " << rhs_evals << "\n"
    << "  linear solver:      " << lin_setups << " factorisations, " << lin_analyses
    << " symbolic analyses\n"
    << "  engine restarts:    " << engine_restarts << "\n"
    << "  contact iterations: " << contact_iterations << " (" << iteration_failures
    << " iteration failures)\n";
  lv("displacement level", level_u);
  lv("velocity level    ", level_v);
  lv("acceleration level", level_a);
  o << "  separations:        " << separations << "\n"
    << "  impacts:            " << impacts << "\n"
    << "  max contact force:  " << fmt(max_contact_force) << "\n"
    << "  min gap:            " << fmt(min_gap) << "\n"
    << "  max penetration:    " << fmt(max_penetration) << "\n";
  if (first_tensile_time >= 0)
    o << "  constraint force first tensile at t = " << fmt(first_tensile_time) << "\n";
  for (const ContactResult& c : contacts) {
    auto ang = [&](double d) { return std::isnan(d) ? std::string("-") : fmt(d) + " deg"; };
    o << "  contact '" << c.name << "': min force " << (std::isnan(c.min_force) ? std::string("-") : fmt(c.min_force))
      << " at " << ang(c.min_force_theta_deg) << " (outside the lash take-up), " << c.impacts << " impacts (max "
      << fmt(c.max_impact_velocity) << " at " << ang(c.max_impact_theta_deg) << ", first at "
      << ang(c.first_impact_theta_deg) << "), " << c.separations << " separations (first at "
      << ang(c.first_separation_theta_deg) << ")\n";
  }
  o << "  energy residual:    " << fmt(energy_residual) << "\n"
    << "  cpu / wall:         " << fmt(cpu_seconds) << " s / " << fmt(wall_seconds) << " s\n";
  return o.str();
}

}  // namespace camdyn

