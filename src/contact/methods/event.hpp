// camdyn (private) — the held-contact machinery of the contact methods that integrate
// natively (methods/event.cpp): the active contacts' acceleration level as the contact
// force inside the right-hand side, their displacement and velocity levels by the engine's
// projection (CVODE: CVodeSetProjFn), rootfinding for separations (the force reaching zero)
// and impacts (an open gap reaching zero), the Newton impact law (contact_run.cpp).
//
// Two methods run on it:
//   * contact.model = "event" on any engine (EventMethod itself): steps land on the output
//     times;
//   * contact.model = "lee" on cvode-bdf (methods/lee_cvode.cpp: Lee inside CVODE's own
//     step): steps do not land on the output times (rows from CVODE's interpolant).
#pragma once

#include <Eigen/Dense>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "contact/contact_run.hpp"

namespace camdyn {
namespace detail {

/// The event method's gap tolerance: min(tol_u, rtol·X), at least 1000 ulps of X (X: the
/// scale of the cam's X_C, > 0). An open contact's root sits 10⁻³ of it below zero.
inline double event_gap_tolerance(double tol_u, double rtol, double X) {
  const double x = std::max(X, 1e-300);
  return std::min(tol_u, std::max(rtol * x, 1000.0 * 2.220446049250313e-16 * x));
}

class EventMethod : public ContactRun {
 public:
  /// On cvode-bdf the engine takes the BDF order limits of cvode_bdf_order
  /// (methods/bdf_order.hpp) for the scene's method on `mech`.
  EventMethod(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
               const std::atomic<bool>* stop);

 protected:
  void run_method() override;
  /// The time the next step may not pass apart from the cam's breakpoints (the event
  /// method: the next output time); the step goes to stop_before(step_horizon()).
  virtual double step_horizon() { return next_output_time(); }
  /// Called once per step just after the engine returned (t_, y_ the step's end or root,
  /// the engine's interpolant valid over [t_prev, t_]), before any switch is applied.
  /// P_prev: the dissipated power at t_prev.
  virtual void after_advance(double /*t_prev*/, double /*P_prev*/) {}
  /// The cam's work and the dissipated energy over the step [t0, t1] just taken (before
  /// after_advance): 3-point Gauss–Legendre on the engine's interpolant (step_energy).
  virtual StepEnergy advance_energy(double t0, double t1);
  /// The cam's work over [ta, tb] ⊂ the last step (the held forces on the interpolant).
  double held_work(double ta, double tb);
  /// corr = P(y) − y: y put on the active set's g = 0, ġ = 0, M-orthogonally.
  void project(double t, const double* y, double* corr);

  OdeEngine* eng_;
  std::vector<int> set_;  // the active set the right-hand side uses
  // The last step's middle where advance_energy left the engine's interpolant there in
  // se_mid_y_ (its middle Gauss point): the trace's middle sample reads it (NaN: none).
  double mid_t_ = NAN;

 private:
  void restart();
  // After a step that landed on a cam breakpoint (t_): the next steps' cam is the segment
  // after it; where its acceleration jumps, the held contacts take that segment's forces
  // (releasing those it pulls off) and the engine restarts there.
  void enter_segment();
  bool on_break_ = false;  // t_ is on a cam breakpoint the last step landed on
  // The projection's metric for the active set: MTa_ = G⁻¹T_Aᵀ and W_AA = T_A G⁻¹ T_Aᵀ
  // with G = M, or G = S = M + γC + γ²K once stiff_metric() has a γ.
  void set_metric();
  // cvode-bdf on a Mechanism: the metric S with γ the last step size (on the grid 2^k).
  // The M-orthogonal correction moves the contact node alone (lumped mass): behind it a
  // finely meshed bar (the OHV pushrod with 1000 elements) whose first element's period
  // is far below the step has that element strained at every step, and CVODE's history
  // amplified it (error test failures at 1.7 ms). In S the modes faster than 1/γ — those
  // BDF treats as quasi-static — follow the correction statically (no strain added in
  // the stiff elements), the slow ones by their inertia.
  // An elastic body with stiff internal modes (a one-contact bar) takes γ = 10⁶·h: every mode follows
  // statically, the correction that changes the least strain (the rigid translation of
  // the bar). With γ = h the bar's slow modes follow by their inertia, the corrections
  // strain the first element and the held force carries that strain (measured:
  // docs/background/method_notes.md, "The projection's metric on cvode-bdf").
  void stiff_metric(double h);
  const double metric_scale_ = mk_.traits().stiff_internal_modes ? 1e6 : 1.0;
  bool stiff_metric_ = sc_.solver.integrator == Integrator::CvodeBdf && dynamic_cast<const Mechanism*>(&mk_);
  double gamma_p_ = 0.0;  // 0: the metric M
  Eigen::SimplicialLDLT<SparseMatrix> S_ldlt_;

  // cvode-bdf: a release alone does not restart the engine (methods/event.cpp, run_method).
  bool continue_on_release_ = sc_.solver.integrator == Integrator::CvodeBdf;
  // cvode-bdf: the root functions are evaluated on CVODE's interpolant put on the held
  // contacts' manifold (project()); the state at a root is put there on every engine. The raw interpolant is not
  // on it: the held contacts' cam motion enters CVODE's step through the projection only,
  // which its error test does not see, so one step may carry the held nodes across a whole
  // rise (examples/ohc_roller_finger.toml: one step of 8.8 ms from the end of the dwell
  // over the cycloidal rise, the finger up to 8.9 mm off the cam on the raw interpolant).
  // There the lash's closing was found on the raw interpolant with no closing speed,
  // ignored, and the run stopped at 20 ms with the finger 8.9 mm into the valve; on the
  // manifold the lash closes at the event method's time (to 1e-15 s).
  bool on_manifold_roots_ = sc_.solver.integrator == Integrator::CvodeBdf;
  // cvode-bdf: a step that lands on a cam breakpoint with contacts held restarts CVODE
  // there. The held nodes follow the cam through the acceleration level, which BDF samples
  // at the step's end only, and their drift is corrected by the projection, which CVODE's
  // error test does not see: after a dwell (history all at rest) the first step took
  // CVODE's dwell step size across the next law segment, and a cycloidal segment, whose
  // acceleration is zero at both ends, looked like rest to the error test
  // (examples/ohv_roller_lifter.toml: one step of 7 ms over the rise; the pushrod behind
  // the lifter was integrated against a lifter at rest, the lash closed 5.2e-6 s early).
  // Restarted at the joint, CVODE's first step and order grow from the segment's own
  // motion. Not where the held contacts fix every unknown (a rigid follower held on the
  // cam: its state is the projection's, exact; examples/law_roller.toml on the mechanism
  // stack took 774 steps for two revolutions with the restarts, 32 without, same rows).
  bool restart_at_breaks_ = sc_.solver.integrator == Integrator::CvodeBdf;
  // The root functions are seen at the steps' ends only (SUNDIALS looks inside a step only
  // where a function changes sign): an open contact that closes and opens again inside one
  // step is unseen. A step held contacts carry across a lift (their motion comes from the
  // projection, which the error test does not see: examples/ohc_roller_finger.toml on
  // cvode-bdf with cam.land_on_breaks = false and one output row per revolution took one
  // step over the whole valve event, the lash closed for 160° unseen) is therefore scanned:
  // the open contacts' gap functions on the interpolant put on the held manifold, at
  // samples at most kScanDeg of cam rotation apart, and so are the held contacts'
  // separation margins: a held set that fixes every unknown (a finger on a rigid pivot
  // held on the cam, at the lash and on the seat through a dwell) leaves CVODE's error test
  // nothing to see, so its step after the dwell ran to the next cam breakpoint with the
  // seat's margin negative inside it and positive again at its end (the rise's
  // acceleration back at zero): the valve never left its seat and the cam contact ended
  // 3.2 mm deep. The first sample below zero is bisected to its root, which then acts as
  // the engine's root would (its index in who, t1/y1 the root's time and state). Returns
  // false when nothing closed or separated inside the step.
  static constexpr double kScanDeg = 1.0;
  bool scan_switches(double t0, double& t1, Eigen::VectorXd& y1, int& who);
  Eigen::VectorXd yv_, yg_, rc_, rF_, rFh_;
  // An open contact's root is its gap at −10⁻³ tol_e, tol_e = min(tol_u, rtol·X) (X: the
  // cam's largest X_C), at least 1000 ulps of X: an impact is located to the integrator's
  // accuracy, so the event times fall with rtol, and tol_u caps the offset
  // (docs/tolerances.md "The event method").
  double gap_tol_ = event_gap_tolerance(sc_.contact.tol_u, sc_.solver.rtol, cam_scales(cam_).X);
  double gap_thr_ = 1e-3 * gap_tol_;
  // A contact released where its force reaches zero leaves the cam from the root's state
  // put on the held set's manifold (g = ġ = 0 exactly), so its gap root is the normal one
  // at once. (A band of 10 (rtol·|q| + atol) below the cam, for the interpolation error of
  // an unprojected root state, hid real re-contacts: B2 on arkode-erk at rtol 1e-6, a
  // flight of 8 µs after a separation, re-impact at 0.01 m/s, ran 2.1e-6 m into the cam
  // — past the step check's 10 tol_u — inside the band of 2.4e-5 m.)

  // The projection onto the active set's g = 0, ġ = 0 (see the top): M⁻¹T_Aᵀ and the
  // factorisation of W_AA, made once per active set.
  Eigen::MatrixXd MTa_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> Waa_;
  Eigen::VectorXd pg_, pgd_;
  Eigen::VectorXd yp_;  // project()'s state (a camshaft)
};

}  // namespace detail
}  // namespace camdyn
