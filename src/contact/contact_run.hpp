// camdyn (private) — the run machinery every contact method shares:
//
//   scene (any follower: a rigid or elastic_bar follower as a one-contact mechanism,
//   src/mechanism/follower_builder.cpp; a network; a user FollowerSystem) → Mechanism
//   (src/mechanism/mechanism.hpp) → OdeEngine (src/engine/ode_engine.hpp) or IDA (src/engine/ida_engine.hpp) + a
//   contact method (a ContactRun subclass, one file each: methods/lee_located.cpp,
//   methods/lee_cvode.cpp, methods/penalty.cpp, methods/event.cpp, methods/holonomic_ida.cpp; chosen
//   by make_contact_method, contact_run.cpp) → HistoryRow stream + RunRecord (run_record.hpp)
//   and the parts (RunParts), of which SummaryBuilder (src/run/summary_builder.hpp) makes
//   the Summary.
//
// The state is y = [q; v; s] over the mechanism's unknowns q (v = q̇) and its elements'
// internal states s (MechanicalSystem::states(), often none; continuous: impacts and
// projections leave them unchanged), F the contact forces (one per
// contact, ≥ 0), `active` the contacts that are closed and carry force. Shared here: the
// initial state and its consistent forces, gaps, the acceleration-level forces of an
// active set, the Newton impact law on several contacts, output rows (standard columns for
// the primary contact, then per contact and per node), the energy ledger, events,
// statistics, stop and failure handling.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "cam/joints.hpp"
#include "cam/stops.hpp"
#include "camdyn/observer.hpp"
#include "camdyn/summary.hpp"
#include "results/designer_stats.hpp"
#include "results/run_analysis.hpp"
#include "contact/flight_log.hpp"
#include "results/surge.hpp"
#include "mechanism/mechanism.hpp"
#include "engine/ode_engine.hpp"
#include "contact/run_failure.hpp"
#include "contact/run_record.hpp"
#include "contact/step_control.hpp"
#include "scene/shared_cam.hpp"

namespace camdyn {
namespace detail {

/// The cam's scales over one turn (360 samples): the largest |X_C| (the scale of a cam
/// contact's gap) and the largest |dX_C/dθ|.
struct CamScales {
  double X = 0.0, dX = 0.0;
};
inline CamScales cam_scales(const Cam& cam) {
  CamScales s;
  for (int k = 0; k < 360; ++k) {
    const CamPoint p = cam.evaluate(6.283185307179586 * k / 360);
    s.X = std::max(s.X, std::abs(p.X_C));
    s.dX = std::max(s.dX, std::abs(p.dX_dtheta));
  }
  return s;
}

class ContactRun {
 public:
  ContactRun(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
             const std::atomic<bool>* stop);
  virtual ~ContactRun() = default;
  ContactRun(const ContactRun&) = delete;
  ContactRun& operator=(const ContactRun&) = delete;
  void set_stop_reason(std::string reason) { stop_reason_ = std::move(reason); }
  /// Runs the method from the start state to run.t_end (or until it stops or fails: the
  /// record's termination says which) and returns what it measured. The parts() hold the
  /// rest of the run's results; SummaryBuilder (src/run/summary_builder.hpp) makes the
  /// Summary of both. Call once.
  const RunRecord& run();
  /// The run's parts that contribute their sections of the Summary (valid while this lives).
  RunParts parts() const { return RunParts{designer_, analysis_, flights_, surge_}; }

  /// Names of HistoryRow::extra for a mechanism.
  /// element_forces: with the elements' force_<name> columns (run.element_forces).
  static std::vector<std::string> extra_columns(const MechanicalSystem& mech, bool element_forces = false);

 protected:
  /// The method's loop over accepted steps from (t_, y_, F_, active_) to t_end.
  virtual void run_method() = 0;
  /// Method-specific start after the common initial state and its held forces, before
  /// the t = 0 row and the energy ledger's origin (penalty: its own equilibrium).
  virtual void prepare_start() {}
  /// Dense output inside the step just accepted: emit the row at `to` (< t_) and return
  /// true; false: the caller emits the step-end row.
  virtual bool dense_row_at(double /*to*/) { return false; }
  /// Penalty: energy stored in the contact springs at (t, q), and the power its dampers
  /// dissipate at (t, y); 0 for the other methods.
  virtual double contact_potential(double /*t*/, const double* /*q*/) const { return 0.0; }
  virtual double contact_dissipation(double /*t*/, const Eigen::VectorXd& /*y*/) const { return 0.0; }

  /// The first-order system the native methods integrate: y = [q; v; s], q̇ = v,
  /// v̇ = M⁻¹(r(t, q, v, s) + TᵀF), ṡ = g(t, q, v, s) with the method's contact forces
  /// forces(t, y, F) (m entries).
  using ForceFn = std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& F)>;
  OdeSystem contact_system(ForceFn forces);
  /// The engine's absolute tolerance per unknown: solver.atol raised to the round-off floor
  /// of the positions and velocities (contact_run_tolerance.cpp); empty when solver.atol is
  /// above it everywhere (the scalar is used). Notes the raise as a run warning.
  Eigen::VectorXd absolute_tolerances();
  /// The implicit engines' sparse Newton structure (M, K, C, T) of a linear Mechanism;
  /// null for a user's FollowerSystem (dense Jacobian). The method adds its contact
  /// derivatives or held set.
  std::shared_ptr<SparseNewton> sparse_newton() const;
  /// A camshaft (shaft_rows.cpp): the state-dependent rows T̃ of its cam contacts in the
  /// implicit engines' Newton structure, with their stiffness at the method's forces:
  /// forces(t, y, F, dFdgd) writes the contact forces at (t, y) (m entries) and their
  /// ∂F/∂ġ (zero where F does not depend on ġ). No camshaft: nothing.
  using ShaftForceFn = std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& F,
                                          Eigen::VectorXd& dFdgd)>;
  void shaft_newton(SparseNewton& sn, ShaftForceFn forces);
  /// A camshaft: the shaft's natural frequencies with its trains attached (held_frequencies_hz
  /// at the start state, the contacts active there held) into the run's model description.
  void note_shaft_frequencies();
  /// A user's follower: the dense Jacobian J = [0 I; P ∂a/∂q P ∂a/∂v] of the native system
  /// from its acceleration_jacobian (empty if it has none). `held` (read at every call; null:
  /// none): the contacts held at the acceleration level inside f, a = a_free + M⁻¹T_SᵀF_S with
  /// F_S = W_SS⁺(Ẍ_C,S − T_S a_free), so P = I − M⁻¹T_Sᵀ W_SS⁺ T_S; else P = I.
  std::function<void(double, const double*, Eigen::MatrixXd&)> dense_jacobian(const std::vector<int>* held) const;

  // ---- geometry and forces
  /// The cam's lift above its base circle at t: X = X_C − min_θ X_C, Ẋ_C, Ẍ_C. Inside
  /// a window set by set_cam_window, one-sided at the cam's breakpoints (cam_joints.hpp).
  CamMotion cam_at(double t) const;
  /// The step about to be taken or just taken lies in [lo, hi]: at a cam breakpoint at
  /// its start the cam is evaluated on the segment after it (the right limit), at its end
  /// on the segment before it (the left limit), so that no stage of a step that lands on a
  /// joint, or starts from one, sees the other segment's acceleration. lo / hi: a time
  /// where θ is on a breakpoint, NaN if the window's end is none. Both NaN (the default):
  /// the cam as Cam::motion evaluates it (the segment that holds θ).
  void set_cam_window(double lo, double hi) {
    win_lo_ = lo;
    win_hi_ = hi;
  }
  /// The first cam breakpoint time after t_ (steps land on them: cam.land_on_breaks),
  /// +inf if none before t_end.
  double next_break_time() const { return stops_.before(t_, INFINITY); }
  /// g_j = T_j q + g₀_j − X_C·[cam], ġ_j, and the cam's part of g̈_j (−Ẍ_C·[cam]).
  double gap(int j, const Eigen::VectorXd& y, const CamMotion& cm) const;
  double gap_rate(int j, const Eigen::VectorXd& y, const CamMotion& cm) const;
  double cam_acc(int j, const CamMotion& cm) const;
  /// The part of g̈_j besides T̃_j q̈, at the state y: a camshaft's cam contact X_L″ φ̇_s²
  /// (camshaft.hpp), the others cam_acc(j, cm).
  double cam_acc(int j, const Eigen::VectorXd& y, const CamMotion& cm) const;
  /// The contact rows at the unknowns q: T̃ (m × n), M⁻¹T̃ᵀ, W̃ = T̃M⁻¹T̃ᵀ. A camshaft's cam
  /// contact j gains the column −X_L′ on its station (camshaft.hpp); without a camshaft these
  /// are the mechanism's constant T, M⁻¹Tᵀ, W (no copy). Valid until the next call.
  struct Rows {
    const Eigen::MatrixXd& T;
    const Eigen::MatrixXd& MinvTt;
    const Eigen::MatrixXd& W;
  };
  Rows rows_at(const double* q) const;
  /// a = M⁻¹(f₀ − Kq − Cv + TᵀF).
  void acceleration(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& F, Eigen::VectorXd& a) const;
  /// The acceleration level of the closed contacts `set`, by complementarity
  /// (src/contact/active_set.hpp): F_S ≥ 0, g̈_S = W_SS F_S + T_S a_free − Ẍ_C,S ≥ 0,
  /// F_S·g̈_S = 0; redundant contacts (W_SS singular: two contacts on one node or one rigid
  /// chain) share by the minimal norm; zero off the set. Holonomic (contact.separation =
  /// false): g̈_S = 0 with signed forces. `margin` (m entries): F_j − g̈_j/W_jj on the set,
  /// a force that is > 0 while contact j carries force and < 0 once the acceleration level
  /// opens it, continuous through the switch (the separation function); `ok` false: no
  /// bounded forces (the contacts jam).
  Eigen::VectorXd held_forces(double t, const Eigen::VectorXd& y, const CamMotion& cm,
                              const std::vector<int>& set, Eigen::VectorXd* margin = nullptr,
                              bool* ok = nullptr) const;
  /// held_forces into F (no allocation once F and margin have m entries).
  void held_forces_into(double t, const Eigen::VectorXd& y, const CamMotion& cm, const std::vector<int>& set,
                        Eigen::VectorXd& F, Eigen::VectorXd* margin = nullptr, bool* ok = nullptr) const;
  /// Active contacts as a list.
  std::vector<int> active_list() const;
  /// F_ from the acceleration level for the active set, releasing (with a separation
  /// event) every contact the complementarity solution opens (margin < −thr·scale).
  /// @throws StepFailure naming the contacts if they jam.
  void settle_active(const CamMotion& cm);
  /// At the start, after settle_active: an open contact whose gap is closed (g ≤ gtol) but
  /// opens at a rate ġ > 0 so small that, under the start's acceleration (g̈ < 0), its gap
  /// never opens past contact.tol_u (g + ġ²/(2|g̈|) ≤ tol_u: a rate of round-off size, such
  /// as a lift table's interpolant between equal base-circle samples) is closed: it joins the
  /// active set, the start state is projected onto the active set's g = 0, ġ = 0
  /// (M-orthogonally) and the forces are settled again. An event method could not find its
  /// closing otherwise: its gap root starts below the root's offset and never crosses it.
  void close_creeping_contacts(const CamMotion& cm, double gtol);
  /// Resolve an impact at the current state: `closing` contacts (gap ≈ 0, approaching)
  /// and the active ones take a Newton impulse (g⁺ = −e g⁻ on the closing ones, or 0 when
  /// they stick; 0 on the active ones), impulses ≥ 0 (a contact whose impulse would pull
  /// is left out). Sticking contacts join the active set; forces are settled afterwards.
  /// Records the impacts; books the cam's impulse work and the loss.
  /// plastic: the closing contacts stick whatever their restitution (a cam joint's impact).
  void resolve_impact(const std::vector<int>& closing, const CamMotion& cm, bool plastic = false);
  /// On a C0 joint of the cam (cam_joints.hpp) at t_: from now on cam_at(t_) is the motion
  /// after the joint, and the closed cam contacts take its velocity jump (cam_joint.cpp):
  /// the cam strikes (a plastic impact: ġ⁺ = 0, resolve_impact) or, slower, leaves (a
  /// separation; holonomic: a signed impulse). True if the state changed (restart).
  bool cam_joint_impact();

  // ---- energies
  double potential(double t, const Eigen::VectorXd& y) const;
  double dissipation_power(double t, const Eigen::VectorXd& y) const;
  /// Σ over cam contacts F_j Ẋ_C: the work of the cams the run drives (the prescribed cam,
  /// a camshaft's cams on a prescribed drive station; not the cams on the shaft's unknowns).
  double cam_power(const Eigen::VectorXd& F, const CamMotion& cm) const;
  /// Contact j's Ẋ in cam_power (0: it does no work on the driver).
  double driven_cam_speed(int j, const CamMotion& cm) const;
  /// cm.t, the time a camshaft's cam on the prescribed station is evaluated at (cam_at sets it).
  /// @throws std::logic_error for such a contact when cm has no time.
  double shaft_time(int j, const CamMotion& cm) const;

  // ---- output and bookkeeping
  void emit_row();
  void emit_row_at(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& F,
                   const std::vector<char>& active, double W, double D);
  /// Inside the lash take-up window at t (summary.hpp ContactResult).
  bool in_take_up(double t) const;
  /// The side loads |F_j tan φ| of the closed cam contacts at an accepted step end
  /// (ContactResult::max_side_load); `cp`: the cam at theta when known (else evaluated).
  void sample_side_loads(double theta, const CamPoint* cp = nullptr);
  /// A force sample of closed contact j for its ContactResult::min_force.
  void sample_contact(int j, double F, double theta_deg);
  /// The held force F of contact j at t as a sample of its least force (outside the lash
  /// take-up window) and, for the primary contact, of the designer's force statistics.
  void sample_held_force(int j, double t, double F);
  void record_event(EventKind type, int contact, double v, double impulse = 0.0,
                    double t_event = NAN);
  /// After an accepted step (state updated): dW the cam's work over the step, P_prev the
  /// dissipated power at its start (P_end at its end if not the current state's); dD the
  /// energy dissipated over the step by the method's own quadrature (NaN: the trapezoid
  /// on P_prev and P_end).
  void after_step(double h, double dW, double P_prev, double P_end = NAN, double dD = NAN);
  /// The cam's work and the dissipated energy over [t0, t1] by 3-point Gauss–Legendre on
  /// the step's own dense state (state(τ, y)) and contact forces (forces(τ, y, cm, F)):
  /// each step's own quadrature (issue 25; the trapezoid on the step ends left the stem
  /// damping's energy of the valve train 6e-8 of the cam's work off at rtol 1e-8).
  struct StepEnergy {
    double work = 0.0, dissipated = 0.0;
  };
  StepEnergy step_energy(double t0, double t1, const std::function<void(double, Eigen::VectorXd&)>& state,
                         const std::function<void(double, const Eigen::VectorXd&, const CamMotion&,
                                                  Eigen::VectorXd&)>& forces) const;
  /// The accepted step [t0, t1] before the events at its end, on its own dense state
  /// state(τ, y) and contact forces forces(τ, y, cm, F) (as step_energy); `set` the
  /// contacts held over it. The designer extremes located inside the step
  /// (results/step_extremes.hpp; contact_run_trace.cpp): each contact's least force and side
  /// load, DesignerStats::step_inside, RunAnalysis::step_inside. Once a method traces its
  /// steps, the rows add no extreme (the output grid changes no result). `energy_alike`:
  /// step_energy was just called on [t0, t1] with the same state and forces functions, so
  /// its middle Gauss point is the middle sample. `y_end`, `F_end` (optional, both or none):
  /// the method's own state and forces at t1, the step's end: the engine's step end, which
  /// its interpolant returns at t1 bit for bit (OdeEngine::dense) and which the engine's
  /// projection has put on the held set's manifold already (state(t1) projects it again:
  /// the same state to round-off); the end sample takes them instead of evaluating them
  /// again. `y_start` (optional): the method's state at t0 that the step started from.
  /// When it is bitwise the state of the previous traced step's end sample, at the same
  /// time and with the same held set (no impact, projection or restart between the two
  /// steps), that sample is the start sample without evaluating state(t0): the step's
  /// interpolant passes through the state it started from (Hermite: its end values;
  /// CVODE's Nordsieck history: the BDF correction polynomial vanishes at t_{n−1}), so the
  /// two agree to round-off. Without it the start sample is taken from the previous end
  /// only when state(t0) gives that state bit for bit.
  using StateFn = std::function<void(double, Eigen::VectorXd&)>;
  using ForcesFn = std::function<void(double, const Eigen::VectorXd&, const CamMotion&, Eigen::VectorXd&)>;
  void trace_step(double t0, double t1, const StateFn& state, const ForcesFn& forces, const std::vector<int>& set,
                  bool energy_alike = false, const Eigen::VectorXd* y_end = nullptr,
                  const Eigen::VectorXd* F_end = nullptr, const Eigen::VectorXd* y_start = nullptr);
  /// θ within 1e-9 rad of one of the cam's breakpoints (Cam::breakpoints(), modulo 2π):
  /// a step end there sees the cam one-sided in the trace.
  bool near_cam_breakpoint(double theta) const;
  /// The cam at the last traced step's end sample when it is at time t and angle theta
  /// (the same point of the cam), else nullptr: after_step's samples there read it.
  const CamPoint* traced_end_cam(double t, double theta) const;
  /// The trace's samples read the state beyond the contact forces (the seats' gaps, the
  /// named nodes' displacements).
  bool trace_reads_state() const { return analysis_.wants_gaps() || analysis_.wants_nodes(); }
  bool traced_ = false;
  Eigen::VectorXd trace_y_, trace_F_;
  std::vector<char> trace_in_;
  std::vector<StepSample> trace_samples_;
  /// The previous traced step's end probe and its state: the next step's start probe when
  /// that step starts at the same time, from the same state, with the same held set.
  StepSample trace_prev_end_;
  Eigen::VectorXd trace_prev_y_;
  bool trace_prev_valid_ = false;
  /// The check after every accepted step (issue 28): a contact carrying force across an
  /// open gap, or a gap below −kCheckGaps·tol_u (not for penalty: its law penetrates),
  /// stops the run with a StepFailure naming the contact, the time and the cam angle.
  void check_complementarity(const CamMotion& cm) const;
  /// T_p a at the current state (t_, y_, F_): contact p's acceleration.
  double contact_acceleration(int p) const;
  /// false for the penalty method (its contacts penetrate by their law).
  virtual bool penetration_checked() const { return true; }
  double fit_step(double h, double t_next) const;
  double initial_step() const;
  double out_dt() const { return sc_.run.output_dt; }
  double next_output_time() const;
  // The time to step toward: t_next, or a cam breakpoint before it (cam_stops.hpp).
  double stop_before(double t_next) const { return stops_.before(t_, t_next); }
  double next_stop_time() const { return stop_before(next_output_time()); }

  const Scene& sc_;
  std::shared_ptr<const MechanicalSystem> mech_;
  const MechanicalSystem& mk_;
  std::string atol_note_;  // absolute_tolerances(): the warning when the floor was used
  std::shared_ptr<const Cam> cam_owner_;  // the run's cam, shared (scene/shared_cam.hpp)
  const Cam& cam_;
  CamDrive drive_;
  CamStops stops_{sc_.cam, sc_.run.t_end, cam_};
  CamJoints joints_{sc_.cam, cam_};
  double joint_t_ = -INFINITY;  // the last C0 joint passed: cam_at(joint_t_) is after it
  Observer* obs_;
  const std::atomic<bool>* stop_;
  std::string stop_reason_ = "stopped by caller";
  int n_, m_;
  int ns_, ny_;  // the elements' internal states, and the state's size 2n + ns
  /// s inside a state y = [q; v; s] (null without internal states).
  const double* states_of(const double* y) const { return ns_ ? y + 2 * n_ : nullptr; }
  const double* states_of(const Eigen::VectorXd& y) const { return states_of(y.data()); }
  DesignerStats designer_;
  DesignerColumns design_cols_{sc_};  // run.designer_columns
  RunAnalysis analysis_;              // film, lift deviation, landings, ramp velocity
  FlightLog flights_;                 // separation → impact flights (the contract's warning)
  SurgeTracker surge_;                // springs with coil masses: surge amplitude
  std::vector<double> surge_buf_;
  double take_up_lo_ = NAN, take_up_hi_ = NAN;  // the lash take-up window of the cam's lift
  std::vector<double> row_gaps_, row_u_;        // emit_row_at's buffers for analysis_
  std::size_t element_force_count_ = 0;  // run.element_forces: the mechanism's reported forces
  /// A network with nonlinear elements: its reported quantities' extremes, end values and
  /// per-revolution ranges (Summary::elements) at the current state.
  void sample_elements();
  bool element_results_ = false;
  long element_rev_ = -1;  // the camshaft revolution of the last sample
  std::vector<double> element_buf_, element_cyc_min_, element_cyc_max_;
  RunRecord rec_;  // what the run measures (the methods write it; never a Summary)
  double t_ = 0, work_ = 0, dissipated_ = 0, E0_ = 0, V0_ = 0, last_row_t_ = -1;
  Eigen::VectorXd y_, F_;
  Eigen::VectorXd step_F0_;  // the forces the last accepted step ended with (StepInfo::force_start)
  std::vector<char> active_;
  Eigen::VectorXd sys_y_, sys_F_;  // contact_system()'s buffers
  mutable Eigen::VectorXd hf_ta_;  // held_forces' T a_free
  mutable Eigen::VectorXd hf_a_;   // held_forces' a_free (a camshaft)
  mutable Eigen::VectorXd rows_q_;  // rows_at's state and rows (a camshaft)
  mutable Eigen::MatrixXd rows_T_, rows_MT_, rows_W_;
  SparseMatrix shaft_kr_pattern_;                // shaft_newton's stiffness pattern
  Eigen::VectorXd shaft_y_, shaft_F_, shaft_dF_;  // shaft_newton's state and forces
  mutable Eigen::VectorXd se_y_, se_F_;  // step_energy's state and forces
  // step_energy's middle Gauss point (x = ½) of the last interval [t0, t1] it integrated:
  // trace_step's middle sample when the method hands both the same state and forces
  mutable double se_mid_t0_ = NAN, se_mid_t1_ = NAN;
  mutable Eigen::VectorXd se_mid_y_, se_mid_F_;
  double x_base_ = 0.0;     // the base circle's X_C: cam_at() returns the lift X_C − x_base_
  bool unilateral_ = true;
  bool observer_stop_ = false;  // an observer returned ObserverAction::Stop  // false: contact.separation = false or holonomic (never release)
  long next_out_ = 1;
  double F_ref_ = 0.0;        // largest contact force so far (force thresholds)
  double v_impact_ref_ = 0.0;  // first approach velocity (sticking threshold)
  // The gap tolerance of an impact's sticking speed (impact.cpp): contact.tol_u; the event
  // method's own gap tolerance (event.hpp: event_gap_tolerance), with which it roots gaps.
  double stick_gap_tol_ = sc_.contact.tol_u;
  double last_progress_ = 0;
  std::vector<std::unique_ptr<OdeEngine>> engines_;  // for the statistics
  // cam_at's last results (the cam is evaluated once per time, not once per use)
  struct CamCache {
    double t = NAN;
    int side = 0;  // cam_at's side at a breakpoint: 0 none, +1 right, −1 left
    CamMotion m;
  };
  double win_lo_ = NAN, win_hi_ = NAN;  // set_cam_window
  std::vector<double> break_angles_;    // the cam's breakpoints where steps land on them
  // 16: a Lee step asks for its end, 7 switch samples and 5 quadrature points, and its
  // end again afterwards (with 4 the end was evicted and evaluated twice)
  static constexpr int kCamCache = 16;
  mutable CamCache cam_cache_[kCamCache];
  mutable int cam_next_ = 0;
  // acceleration()'s last two results, keyed by (t, y, F): a step's end state is asked
  // for again at the next step's start, by the step check and by its row
  struct AccCache {
    double t = NAN;
    Eigen::VectorXd y, F, a;
  };
  mutable AccCache acc_cache_[2];
  mutable int acc_last_ = 0;
};

/// The contact method a scene asks for (contact.model: lee | penalty | event | holonomic).
std::unique_ptr<ContactRun> make_contact_method(const Scene& scene,
                                                std::shared_ptr<const MechanicalSystem> mech,
                                                Observer* obs, const std::atomic<bool>* stop);

}  // namespace detail
}  // namespace camdyn
