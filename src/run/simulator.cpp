// camdyn — the simulator: scene → mechanism → engine + contact method → history/summary.
//
//   Simulator takes a validated scene (a ValidatedScene is not checked again; a Scene is
//   validated once) and builds the mechanism once (any follower kind, or the user's
//   FollowerSystem); each run() makes the contact method the scene asks for
//   (make_contact_method, src/contact/contact_run.hpp), runs it (→ its RunRecord and parts)
//   and builds the Summary of them (build_summary, src/run/summary_builder.hpp).
#include "camdyn/simulator.hpp"
#include "run/contract.hpp"  // check_tolerance_scale
#include "run/summary_builder.hpp"
#include "camdyn/scene_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "contact/contact_run.hpp"
#include "results/designer_columns.hpp"
#include "results/run_analysis.hpp"
#include "run/initial_check.hpp"
#include "mechanism/mechanism.hpp"
#include "cam/format.hpp"  // detail::fmt

namespace camdyn {

using detail::fmt;

const std::vector<std::string>& history_columns() {
  static const std::vector<std::string> cols{"t",       "theta",     "u_c",      "v_c",
                                             "a_c",     "contact_force", "gap", "in_contact",
                                             "kinetic", "potential", "work_cam", "dissipated"};
  return cols;
}

bool has_named_contacts(const std::vector<std::string>& extra) {
  // ContactRun::extra_columns: named contacts come first, three columns each
  if (extra.size() < 3 || extra[0].rfind("F_", 0) != 0) return false;
  const std::string name = extra[0].substr(2);
  return extra[1] == "gap_" + name && extra[2] == "in_" + name;
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

namespace {

// Largest cam radius: the scale of X_C, whose round-off the displacement tolerance of a
// gap that sees X_C itself must stay above (check_gap_round_off).
double cam_scale(const CamSpec& c) {
  double r = 1.0;
  switch (c.profile) {
    case CamProfileKind::Points:
      for (double x : c.radii) r = std::max(r, std::abs(x));
      break;
    case CamProfileKind::Lift:
      for (double x : c.lift) r = std::max(r, std::abs(c.base_radius + x));
      break;
    case CamProfileKind::Circle:
      r = std::max(r, c.radius + c.eccentricity);
      break;
    case CamProfileKind::Arc:
      r = std::max(r, c.nose_distance + c.nose_radius);
      break;
    case CamProfileKind::Arcs:
      for (std::size_t i = 0; i < c.arc_radius.size(); ++i) {
        const double d = i < c.arc_centre_r.size() ? std::abs(c.arc_centre_r[i])
                         : i < c.arc_centre_x.size() && i < c.arc_centre_y.size()
                             ? std::hypot(c.arc_centre_x[i], c.arc_centre_y[i])
                             : 0.0;
        r = std::max(r, d + std::abs(c.arc_radius[i]));
      }
      break;
    case CamProfileKind::Table:
    case CamProfileKind::Law:  // the base circle: the lift is of its order or smaller
      r = std::max(r, std::abs(c.base_radius));
      break;
  }
  return r;
}

// Run sizes the scene cannot hold, refused at the start (not a hang or an allocation
// failure somewhere in the run).
void check_run_size(const Scene& sc) {
  {
    // One Poincaré sample (and one designer record) per revolution: a cam speed of 1e22
    // rev/s would ask for 1e19 of them in the first step (std::bad_alloc).
    const CamSpec& c = sc.cam;
    double w = c.speed_table_t.empty() ? std::abs(c.speed_rev_s) : 0.0;
    for (double x : c.speed_table_rev_s) w = std::max(w, std::abs(x));
    if (w * sc.run.t_end > 1e7) {
      char v[64], b[200];
      std::snprintf(v, sizeof v, "%g", w);
      std::snprintf(b, sizeof b,
                    "times run.t_end = %g must be <= 1e7 revolutions (one Poincaré sample is kept per revolution)",
                    sc.run.t_end);
      throw SceneError(sc.source, 0, c.speed_table_t.empty() ? "cam.speed_rev_s" : "cam.speed_table_rev_s", v, b);
    }
  }
  // One history row per output time: run.output_dt = 1e-14 over 2 ms would ask for 2e11
  // rows (a hang even with no history kept).
  if (sc.run.output_dt > 0.0 && sc.run.t_end / sc.run.output_dt > 1e8) {
    char v[64], b[200];
    std::snprintf(v, sizeof v, "%g", sc.run.output_dt);
    std::snprintf(b, sizeof b, "gives run.t_end / run.output_dt = %.3g rows, more than 1e8 (use a larger output_dt)",
                  sc.run.t_end / sc.run.output_dt);
    throw SceneError(sc.source, 0, "run.output_dt", v, b);
  }
}

// A displacement tolerance below what double precision holds is refused at the start (not
// a step size underflow somewhere in the run). A mechanism whose cam contact sees the cam's
// X_C itself (MechanismTraits::cam_lift_absolute) holds the gap q₀ − X_C, a difference of
// two numbers of the cam's size: below 1000 ulps of the largest cam radius it is round-off
// (the other mechanisms' gaps see the lift above the base circle). The floor holds for
// every method: Lee's displacement level and the event method's gap roots
// (docs/tolerances.md) both measure the gap against tol_u.
void check_gap_round_off(const Scene& sc, const MechanicalSystem& mech) {
  if (!mech.traits().cam_lift_absolute) return;
  const double floor = 1000.0 * std::numeric_limits<double>::epsilon() * cam_scale(sc.cam);
  if (sc.contact.tol_u < floor) {
    char b[256];
    std::snprintf(b, sizeof b,
                  "is below what double precision holds for this scene: the gap is a difference of "
                  "cam positions up to %.3g, whose round-off (1000 ulps) is %.3g; use tol_u >= %.3g",
                  cam_scale(sc.cam), floor, floor);
    char v[64];
    std::snprintf(v, sizeof v, "%g", sc.contact.tol_u);
    throw SceneError(sc.source, 0, "contact.tol_u", v, b);
  }
}

}  // namespace

namespace {

// Keys of the retired single-follower stack (one release of grace): a scene that still
// sets them runs on the mechanism with a warning, except Lee's classic step, which is gone.
void retired_keys(const Scene& sc, std::vector<std::string>& warnings) {
  if (sc.contact.lee_step == LeeStepKind::Classic)
    throw SceneError(sc.source, 0, "contact.lee_step", "classic",
                     "Lee's classic step was retired (docs/background/changelog.md): use contact.lee_step = "
                     "\"located\" (the default), or remove the key");
  if (sc.solver.stack != StackKind::Auto)
    warnings.push_back(std::string("solver.stack = \"") + to_string(sc.solver.stack) +
                       "\" is deprecated and ignored: every follower runs on the mechanism (remove the key)");
  if (sc.contact.tol_a != 0.0)
    warnings.push_back("contact.tol_a = " + detail::fmt(sc.contact.tol_a) +
                       " is deprecated and ignored: it was the classic step's acceleration-level tolerance (remove "
                       "the key)");
  if (sc.contact.error_variant != ErrorVariant::Eq12)
    warnings.push_back(std::string("contact.error_variant = \"") + to_string(sc.contact.error_variant) +
                       "\" is deprecated and ignored: it chose the classic step's equations; the located "
                       "step has one form (remove the key)");
}

}  // namespace

Simulator::Simulator(Scene scene) : Simulator(validated(std::move(scene))) {}

Simulator::Simulator(ValidatedScene scene) : scene_(std::move(scene).scene()) {
  check_run_size(scene_);
  detail::check_tolerance_scale(scene_);
  warnings_ = scene_warnings(scene_);
  retired_keys(scene_, warnings_);
  mech_ = std::make_shared<const Mechanism>(scene_);
  check_gap_round_off(scene_, *mech_);
  extra_columns_ = detail::ContactRun::extra_columns(*mech_, scene_.run.element_forces);
  detail::check_start(scene_, *mech_, detail::StartKeys::Scene);
  add_designer_columns();
}

void Simulator::add_designer_columns() {
  if (scene_.run.designer_columns) {
    const auto& d = detail::DesignerColumns::names();
    extra_columns_.insert(extra_columns_.end(), d.begin(), d.end());
  }
  const std::vector<std::string> a = detail::RunAnalysis::columns(scene_);
  extra_columns_.insert(extra_columns_.end(), a.begin(), a.end());
  if (scene_.cam.friction_coefficient > 0 || scene_.cam.friction_static_coefficient > 0) {
    const auto& f = detail::DesignerColumns::friction_names();
    extra_columns_.insert(extra_columns_.end(), f.begin(), f.end());
  }
}

Simulator::Simulator(Scene scene, std::shared_ptr<const FollowerSystem> follower)
    : Simulator(validated(std::move(scene)), std::move(follower)) {}

Simulator::Simulator(ValidatedScene scene, std::shared_ptr<const FollowerSystem> follower)
    : scene_(std::move(scene).scene()) {
  if (scene_.solver.integrator == Integrator::Ida)
    throw SceneError(scene_.source, 0, "solver.integrator", "ida",
                     "a user-defined follower runs on arkode-erk, arkode-dirk or cvode-bdf (ida needs a "
                     "linear mechanism: rigid, elastic_bar or network)");
  check_run_size(scene_);
  detail::check_tolerance_scale(scene_);
  warnings_ = scene_warnings(scene_, follower.get());
  retired_keys(scene_, warnings_);
  mech_ = make_user_system(scene_, std::move(follower));
  check_gap_round_off(scene_, *mech_);
  extra_columns_ = detail::ContactRun::extra_columns(*mech_);
  detail::check_start(scene_, *mech_, detail::StartKeys::User);
  add_designer_columns();
}

const ModelDescription& Simulator::description() const { return mech_->description(); }

Simulator::~Simulator() = default;

Summary Simulator::run(Observer* observer, const std::atomic<bool>* stop,
                       const std::string& stop_reason) {
  auto method = detail::make_contact_method(scene_, mech_, observer, stop);
  method->set_stop_reason(stop_reason);
  const detail::RunRecord& record = method->run();
  return detail::build_summary(scene_, *mech_, warnings_, record, method->parts());
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
  if (!verdict_text.empty()) o << " — " << verdict_text;
  if (!criteria.empty()) {
    long failed = 0;
    for (const CriterionResult& c : criteria) failed += c.pass ? 0 : 1;
    o << " — criteria: " << (criteria.size() - std::size_t(failed)) << " of " << criteria.size() << " pass";
    for (const CriterionResult& c : criteria)
      if (!c.pass)
        o << "; " << c.name << " FAILS (" << fmt(c.value) << (c.is_max ? " > " : " < ") << fmt(c.limit) << " at "
          << fmt(c.theta_deg) << " deg)";
  }
  for (const SurgeResult& sg : surge)
    o << " — surge '" << sg.spring << "' " << fmt(sg.amplitude) << " at " << fmt(sg.theta_deg) << " deg";
  if (!valve_timing.empty()) {  // a camshaft: the largest timing errors
    const ValveTimingResult *op = nullptr, *cl = nullptr;
    for (const ValveTimingResult& v : valve_timing) {
      if (!std::isnan(v.opening_error_deg) && (!op || std::abs(v.opening_error_deg) > std::abs(op->opening_error_deg)))
        op = &v;
      if (!std::isnan(v.closing_error_deg) && (!cl || std::abs(v.closing_error_deg) > std::abs(cl->closing_error_deg)))
        cl = &v;
    }
    o << " — valve timing error: opening " << (op ? fmt(op->opening_error_deg) + " deg ('" + op->valve + "')" : "-")
      << ", closing " << (cl ? fmt(cl->closing_error_deg) + " deg ('" + cl->valve + "')" : "-");
  }
  if (!finished) o << " — " << message << " [" << to_string(termination) << "]";
  if (contract.checked && !contract.held) {
    o << "\ncamdyn: CONTRACT NOT HELD — the result is not to be trusted:";
    for (const std::string& v : contract.violations) o << "\n  - " << v;
  }
  for (const std::string& w : contract.warnings) o << "\ncamdyn: warning: " << w;
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
    << "  Newton:             " << nonlin_iters << " iterations, " << nonlin_conv_fails
    << " convergence failures, " << err_test_fails << " error-test failures\n"
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
  if (!cam_continuity.empty()) o << "  motion law joints:  " << cam_continuity << "\n";
  if (std::isfinite(cam_torque_peak))
    o << "  cam torque:         peak " << fmt(cam_torque_peak) << ", mean " << fmt(cam_torque_mean)
      << "; power peak " << fmt(cam_power_peak) << ", mean " << fmt(cam_power_mean) << "\n";
  if (!std::isnan(cam_friction_force_max))
    o << "  cam friction:       force max " << fmt(cam_friction_force_max) << ", torque mean "
      << fmt(cam_friction_torque_mean) << "; power peak " << fmt(cam_friction_power_peak) << ", mean "
      << fmt(cam_friction_power_mean) << ", energy " << fmt(cam_friction_work) << "\n";
  if (std::isfinite(max_pressure_angle_deg) && max_pressure_angle_deg > 0)
    o << "  pressure angle:     max " << fmt(max_pressure_angle_deg) << " deg, side load max "
      << fmt(max_side_load) << "\n";
  if (std::isfinite(max_hertz_stress))
    o << "  Hertz stress:       max " << fmt(max_hertz_stress) << " at " << fmt(max_hertz_theta_deg) << " deg\n";
  if (!tolerance_meaning.empty()) o << "  tolerance:          " << tolerance_meaning << "\n";
  if (!tolerance_warning.empty()) o << "  warning:            " << tolerance_warning << "\n";
  for (const std::string& w : warnings) o << "  warning:            " << w << "\n";
  for (const ContactResult& c : contacts) {
    auto ang = [&](double d) { return std::isnan(d) ? std::string("-") : fmt(d) + " deg"; };
    o << "  contact '" << c.name << "': min force " << (std::isnan(c.min_force) ? std::string("-") : fmt(c.min_force))
      << " at " << ang(c.min_force_theta_deg) << " (outside the lash take-up), " << c.impacts << " impacts (max "
      << fmt(c.max_impact_velocity) << " at " << ang(c.max_impact_theta_deg) << ", first at "
      << ang(c.first_impact_theta_deg) << "), " << c.separations << " separations (first at "
      << ang(c.first_separation_theta_deg) << ")\n";
  }
  if (std::isfinite(min_film_thickness))
    o << "  oil film:           min " << fmt(min_film_thickness) << " at " << fmt(min_film_theta_deg) << " deg"
      << (std::isfinite(min_lambda) ? ", lambda " + fmt(min_lambda) : std::string()) << "\n";
  if (std::isfinite(max_ramp_velocity))
    o << "  ramp velocity:      " << fmt(max_ramp_velocity) << " at the lash take-up, " << fmt(max_ramp_theta_deg)
      << " deg\n";
  for (const LiftDeviationRevolution& r : lift_deviation)
    o << "  lift deviation:     revolution " << r.revolution << ": min " << fmt(r.min) << " at " << fmt(r.min_theta_deg)
      << " deg, max " << fmt(r.max) << " at " << fmt(r.max_theta_deg) << " deg\n";
  if (!landings.empty()) {
    const SeatLanding* hard = &landings[0];
    long most = 0;
    double high = 0;
    for (const SeatLanding& L : landings) {
      if (L.max_velocity > hard->max_velocity) hard = &L;
      most = std::max(most, L.bounces);
      high = std::max(high, L.bounce_height);
    }
    o << "  seat landings:      " << landings.size() << ", hardest " << fmt(hard->max_velocity) << " at "
      << fmt(hard->max_velocity_theta_deg) << " deg ('" << hard->contact << "'), most bounces " << most
      << ", highest bounce " << fmt(high) << "\n";
  }
  for (const CriterionResult& c : criteria)
    o << "  criterion:          " << c.name << " " << (c.pass ? "pass" : "FAIL") << ": "
      << (std::isnan(c.value) ? std::string("-") : fmt(c.value)) << (c.is_max ? " <= " : " >= ") << fmt(c.limit)
      << " (worst at " << (std::isnan(c.theta_deg) ? std::string("-") : fmt(c.theta_deg) + " deg") << ")"
      << (c.note.empty() ? std::string() : ": " + c.note) << "\n";
  for (const ValveTimingResult& v : valve_timing) {
    auto ang = [&](double d) { return std::isnan(d) ? std::string("-") : fmt(d); };
    o << "  valve timing '" << v.valve << "' (cam " << v.cam << ", above " << fmt(v.threshold) << "): opens "
      << ang(v.opening_deg) << " deg (kinematic " << ang(v.kinematic_opening_deg) << ", error "
      << ang(v.opening_error_deg) << "), closes " << ang(v.closing_deg) << " deg (kinematic "
      << ang(v.kinematic_closing_deg) << ", error " << ang(v.closing_error_deg) << "), " << v.openings
      << " openings\n";
  }
  for (const SurgeResult& sg : surge)
    o << "  surge '" << sg.spring << "':" << std::string(sg.spring.size() < 11 ? 11 - sg.spring.size() : 1, ' ')
      << fmt(sg.amplitude) << " (largest |coil − quasi-static shape|, at " << fmt(sg.theta_deg) << " deg)\n";
  for (const CoilClashResult& c : coil_clash)
    o << "  coil clash '" << c.spring << "': " << c.impacts << " coil impacts on " << c.coils_closed
      << " coils (first at " << (std::isnan(c.first_impact_theta_deg) ? std::string("-") : fmt(c.first_impact_theta_deg) + " deg")
      << ", max closing speed " << fmt(c.max_impact_velocity) << ")\n";
  if (!verdict_text.empty()) o << "  verdict:            " << verdict_text << "\n";
  o << "  energy residual:    " << fmt(energy_residual) << "\n"
    << "  cpu / wall:         " << fmt(cpu_seconds) << " s / " << fmt(wall_seconds) << " s\n";
  return o.str();
}

}  // namespace camdyn

