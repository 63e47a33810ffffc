// camdyn — the one place a Summary is made (summary_builder.hpp): the run's record and
// parts, the scene and its warnings, in a fixed order.
#include "run/summary_builder.hpp"

#include <cmath>
#include <cstdio>

#include "contact/flight_log.hpp"
#include "contact/methods/bdf_order.hpp"
#include "results/coil_clash.hpp"
#include "results/criteria.hpp"
#include "results/designer_stats.hpp"
#include "results/run_analysis.hpp"
#include "results/surge.hpp"
#include "results/verdict.hpp"
#include "run/contract.hpp"

namespace camdyn {
namespace detail {

Summary build_summary(const Scene& sc, const MechanicalSystem& mech, const std::vector<std::string>& scene_warnings,
                      const RunRecord& r, const RunParts& parts) {
  Summary s;
  // 1. What ran.
  s.scene = sc.title;
  s.integrator = to_string(sc.solver.integrator);
  s.contact_model = to_string(sc.contact.model);
  s.model = r.model;
  // 2. How the run ended; the engines' and the method's statistics.
  s.finished = r.finished;
  s.termination = r.termination;
  s.message = r.message;
  s.t_end = r.t_end;
  s.steps = r.steps;
  s.rejected_steps = r.rejected_steps;
  s.rhs_evals = r.rhs_evals;
  s.lin_setups = r.lin_setups;
  s.lin_analyses = r.lin_analyses;
  s.nonlin_iters = r.nonlin_iters;
  s.nonlin_conv_fails = r.nonlin_conv_fails;
  s.err_test_fails = r.err_test_fails;
  s.engine_restarts = r.engine_restarts;
  s.contact_iterations = r.contact_iterations;
  s.level_u = r.level_u;
  s.level_v = r.level_v;
  s.level_a = r.level_a;
  s.iteration_failures = r.iteration_failures;
  s.relocated_steps = r.relocated_steps;
  // 3. The contacts.
  s.separations = r.separations;
  s.impacts = r.impacts;
  s.max_contact_force = r.max_contact_force;
  s.min_gap = std::isfinite(r.min_gap) ? r.min_gap : 0.0;  // no step: 0
  s.max_penetration = r.max_penetration;
  s.first_tensile_time = r.first_tensile_time;
  s.events = r.events;
  s.contacts = r.contacts;
  s.elements = r.elements;
  // 4. The energy ledger and the clock.
  s.energy_residual = r.energy_residual;
  s.contract.energy_scale = r.energy_scale;
  s.contract.energy_magnitude = r.energy_magnitude;
  s.cpu_seconds = r.cpu_seconds;
  s.wall_seconds = r.wall_seconds;
  // 5. The parts' sections.
  parts.designer.finish(s);  // designer statistics, Poincaré period, cam geometry
  parts.analysis.finish(s);  // film, lift deviation, ramp velocity, valve timing, landings
  parts.flights.finish(s);   // contract.flights, contract.flight_threshold
  parts.surge.finish(s);     // surge
  // 6. What the tolerances mean.
  describe_tolerance(sc, mech, s);
  // 7. The contract: on the final statistics, energy numbers and flights.
  check_contract(sc, s);
  // 8. The warnings: the scene's, then the run's.
  s.warnings = scene_warnings;
  s.warnings.insert(s.warnings.end(), r.warnings.begin(), r.warnings.end());
  // 9. The verdict from the events; the coil clash from the contacts and events.
  s.verdict = make_verdict(sc, mech.traits().named_contacts ? &mech : nullptr, s.events);
  s.verdict_text = verdict_one_line(s.verdict);
  collect_coil_clash(s);
  // 10. The criteria, on everything above.
  judge_criteria(sc, mech, s);
  return s;
}

void describe_tolerance(const Scene& sc, const MechanicalSystem& mech, Summary& sum) {
  const bool lee = sc.contact.model == ContactModel::Lee;
  const BdfOrderLimit bdf = cvode_bdf_order(sc, mech);  // the limits the methods give CVODE
  const bool bdf_damps = bdf.max_order <= 2;            // A-stable orders only
  std::string m;
  char b[96];
  std::snprintf(b, sizeof b, "rtol %.3g, atol %.3g", sc.solver.rtol, sc.solver.atol);
  m = b;
  switch (sc.solver.integrator) {
    case Integrator::ArkodeErk:
      m += " bound each step's local error (Dormand-Prince 5(4), embedded 4th-order estimate, weighted RMS over the state)";
      break;
    case Integrator::ArkodeDirk:
      m += " bound each step's local error (SDIRK 5-stage 4(3), embedded 3rd-order estimate, weighted RMS over the state)";
      break;
    case Integrator::CvodeBdf:
      std::snprintf(b, sizeof b, " bound each step's local error of BDF orders 1-%d", bdf.max_order);
      m += b;
      if (bdf_damps)
        m += " (A-stable; they damp the follower's resolved modes, so the global error grows faster than on the one-step engines)";
      else if (bdf.stability_limit_detection)
        m += " (CVODE's stability-limit detection lowers the order where orders 3-5 go unstable on the follower's stiff modes)";
      break;
    case Integrator::Ida:
      m += " bound each step's local error of IDA's BDF (the held contact as an index-2 DAE)";
      break;
  }
  if (lee) {
    std::snprintf(b, sizeof b, "; contact.tol_u %.3g", sc.contact.tol_u);
    m += b;
    m += " bounds the displacement residual of a held step, and the contact force's acceleration-level error is held to rtol·|F| + 2 tol_u/(M* h²)";
  }
  sum.tolerance_meaning = m;
  sum.tolerance_warning.clear();
  // The numbers in the warning: docs/tolerances.md (case B1 over 1 s at rtol 1e-6).
  if (sc.solver.integrator == Integrator::CvodeBdf && bdf_damps)
    sum.tolerance_warning =
        "cvode-bdf on an elastic follower: BDF orders 1-2 damp the modes the step resolves, so this "
        "rtol buys less accuracy than on arkode-erk/arkode-dirk (case B1, rtol 1e-6: 1 ms impulse errors "
        "2.3e-3 against 2.6e-5 on arkode-erk); tighten rtol or use a one-step engine";
}


}  // namespace detail
}  // namespace camdyn
