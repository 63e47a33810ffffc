// camdyn (private) — the single-follower stack's run machinery (solver.stack = "follower"),
// kept for Lee's classic step (src/legacy/lee_classic.cpp, the bench's comparison), and
// the shared step-size, output-time and run-ending helpers of every method.
//
//   scene → FollowerModel → Engine (SUNDIALS, src/legacy/engines.cpp) + Lee's classic step (a
//   RunContext subclass, registry src/legacy/registry.cpp) → HistoryRow stream + Summary.
//
// Every other method and engine runs on the mechanism (src/contact/contact_run.hpp).
#pragma once

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "cam/stops.hpp"
#include "camdyn/simulator.hpp"
#include "results/designer_stats.hpp"
#include "legacy/engine.hpp"

namespace camdyn {
namespace detail {

inline std::string fmt(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

/// A run that cannot go on (or is asked to stop); the run ends (finished = false) with
/// its termination kind and message.
class StepFailure : public std::runtime_error {
 public:
  StepFailure(Termination kind, const std::string& what)
      : std::runtime_error(what), kind_(kind) {}
  /// A step that failed for a reason without its own Termination value.
  explicit StepFailure(const std::string& what) : StepFailure(Termination::StepFailure, what) {}
  Termination kind() const { return kind_; }

 private:
  Termination kind_;
};
/// A contact iteration that did not converge: recoverable, the step is retried with Δt/2.
class IterationFailure : public StepFailure {
 public:
  IterationFailure()
      : StepFailure(Termination::IterationFailure, "contact iteration did not converge") {}
};
/// The step size fell below the floor (message "step size underflow (h = …)").
class StepSizeUnderflow : public StepFailure {
 public:
  explicit StepSizeUnderflow(double h)
      : StepFailure(Termination::StepSizeUnderflow, "step size underflow (h = " + fmt(h) + ")") {}
};

/// The step to try from t toward t_next (an output time or t_end): at most h and
/// solver.max_step, and no slivers — a remainder below 1e-6 of the step is absorbed into
/// it, a remainder between one and two steps is split into two equal steps. A sliver step
/// (seen: 1.6e-10 s left before an output time after a 3e-6 s step, B1 at t = 44 s)
/// cannot correct even round-off in the gap without a force ∝ gap/Δt², which fails the
/// error test, shrinks Δt, needs a still larger force — and Δt underflows.
/// Shared by RunContext and ContactRun. @throws StepSizeUnderflow.
inline double fit_step_size(const Scene& sc, double t, double h, double t_next) {
  double hs = std::min(h, t_next - t);
  if (sc.solver.max_step > 0) hs = std::min(hs, sc.solver.max_step);
  const double rem = t_next - t;
  if (rem - hs < 1e-6 * hs)
    hs = rem;
  else if (rem < 2.0 * hs)
    hs = 0.5 * rem;
  if (hs <= 1e-14 * std::max(1.0, std::abs(t))) throw StepSizeUnderflow(hs);
  return hs;
}
/// The first step: solver.initial_step, or min(1e-4, t_end/100).
inline double first_step_size(const Scene& sc) {
  if (sc.solver.initial_step > 0) return sc.solver.initial_step;
  return std::min(1e-4, sc.run.t_end / 100.0);
}
/// The next output time after `next_out` − 1 outputs (t_end without output_dt).
inline double output_time(const Scene& sc, long next_out) {
  const double dt = sc.run.output_dt;
  return dt > 0 ? std::min(sc.run.t_end, double(next_out) * dt) : sc.run.t_end;
}

/// Runs a method's loop `body` and sets how the run ended: Finished, or through
/// end_run(kind, what) for a StepFailure (its kind), a SundialsError (SolverError) or any
/// other exception (Error). Shared by RunContext and ContactRun.
template <class EndRun, class Body>
void run_to_end(Summary& sum, EndRun end_run, Body body) {
  try {
    body();
    sum.finished = true;
    sum.termination = Termination::Finished;
    sum.message = "finished";
  } catch (const StepFailure& e) {
    end_run(e.kind(), e.what());
  } catch (const SundialsError& e) {
    end_run(Termination::SolverError, e.what());
  } catch (const std::exception& e) {
    end_run(Termination::Error, e.what());
  }
}

struct Clock {
  std::clock_t c0 = std::clock();
  std::chrono::steady_clock::time_point w0 = std::chrono::steady_clock::now();
  double cpu() const { return double(std::clock() - c0) / CLOCKS_PER_SEC; }
  double wall() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  }
};

/// The run machinery every contact method shares: the initial state, output times and
/// rows (dense rows through dense_row_at), the energy ledger, statistics, events, the
/// designer results, stop (caller's flag, observer's Stop) and failure handling (every end
/// of a run sets Summary::termination: a StepFailure carries its kind, SundialsError is
/// SolverError, any other exception Error). A contact method derives from it and
/// implements run_method(), the loop over its accepted steps, calling after_step() once
/// per accepted step (docs: README "One data path").
class RunContext {
 public:
  RunContext(const Scene& sc, std::shared_ptr<const FollowerModel> model, Observer* obs,
             const std::atomic<bool>* stop)
      : sc_(sc), model_(std::move(model)), m_(*model_), cam_(sc.cam), drive_(sc.cam),
        obs_(obs), stop_(stop), n_(m_.n()), designer_(sc, cam_) {
    engine_ = make_engine(model_, sc_.solver, sc_.contact.model == ContactModel::Lee, sc_.contact.tol_u);
    sum_.scene = sc.title;
    sum_.integrator = to_string(sc.solver.integrator);
    sum_.contact_model = to_string(sc.contact.model);
    sum_.model = m_.description();
    sum_.min_gap = INFINITY;
    bilateral_ = !sc.contact.separation || sc.contact.model == ContactModel::Holonomic;
    tol_u_ = sc.contact.tol_u;
  }

  virtual ~RunContext() = default;
  /// The message of a run ended by the caller's stop flag ("stopped by caller" by default).
  void set_stop_reason(std::string reason) { stop_reason_ = std::move(reason); }
  RunContext(const RunContext&) = delete;
  RunContext& operator=(const RunContext&) = delete;

  Summary run() {
    Clock clock;
    // Initial state: q(0) from the model; node 0 at the cam's velocity if touching.
    const double th0 = drive_.theta(0.0);
    const CamMotion cm0 = cam_.motion(th0, drive_.omega(0.0), drive_.omega_dot(0.0));
    y_ = Eigen::VectorXd::Zero(2 * n_);
    y_.head(n_) = m_.initial_displacement();
    const bool touching = sc_.contact.initial_gap == 0.0;
    if (touching) y_[n_] = cm0.Xdot;
    t_ = 0.0;
    contact_ = touching;
    // Initial contact force from the acceleration level (eq. 16 at t = 0).
    F_ = 0.0;
    if (touching) {
      const double a_free = m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0);
      F_ = (cm0.Xddot - a_free) / m_.mstar();
      if (!bilateral_ && F_ < 0.0) F_ = 0.0;
    }
    V0_ = potential();
    E0_ = m_.kinetic_energy(y_.data() + n_) + V0_;
    emit_row();
    designer_step(cm0.X);
    next_out_ = 1;
    auto end_run = [&](Termination kind, const char* what) {
      sum_.finished = false;
      sum_.termination = kind;
      sum_.message = "at t = " + fmt(t_) + ": " + what;
      // Keep the last accepted state (not after an observer's Stop: it saw its last row).
      if (last_row_t_ < t_ && !observer_stop_) emit_row();
    };
    run_to_end(sum_, end_run, [&] {
      if (observer_stop_) throw_observer_stop();
      run_method();
    });
    sum_.t_end = t_;
    sum_.rhs_evals += engine_->stats().rhs_evals;
    sum_.lin_setups += engine_->stats().lin_setups;
    sum_.engine_restarts += engine_->stats().reinits;  // counted by CVODE only
    sum_.lin_analyses += engine_->stats().lin_analyses;
    sum_.cpu_seconds = clock.cpu();
    sum_.wall_seconds = clock.wall();
    if (!std::isfinite(sum_.min_gap)) sum_.min_gap = 0.0;
    sum_.energy_residual = std::abs(energy_residual());
    designer_.finish(sum_);
    return sum_;
  }

 protected:
  /// The method's loop over accepted steps from (t_, y_, F_, contact_) to t_end.
  virtual void run_method() = 0;

  double out_dt() const { return sc_.run.output_dt; }
  double next_output_time() const { return output_time(sc_, next_out_); }
  // The time to step toward: t_next, or a cam breakpoint before it (cam_stops.hpp).
  double stop_before(double t_next) const { return stops_.before(t_, t_next); }
  double next_stop_time() const { return stop_before(next_output_time()); }
  // The cam's motion at t; the last two values are kept (a step asks for its ends and its
  // midpoint several times).
  CamMotion cam_at(double t) const {
    for (int i = 0; i < 2; ++i)
      if (cam_cache_t_[i] == t) return cam_cache_[i];
    cam_cache_slot_ ^= 1;
    cam_cache_t_[cam_cache_slot_] = t;
    cam_cache_[cam_cache_slot_] = cam_.motion(drive_.theta(t), drive_.omega(t), drive_.omega_dot(t));
    return cam_cache_[cam_cache_slot_];
  }
  mutable double cam_cache_t_[2] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  mutable CamMotion cam_cache_[2]{};
  mutable int cam_cache_slot_ = 0;
  double energy_residual() const {
    const double E = m_.kinetic_energy(y_.data() + n_) + potential();
    return work_ - (E - E0_) - dissipated_;
  }
  // Energy bookkeeping of the history columns (all methods):
  //   work_cam   W = ∫ F Ẋ_C dt         the cam's work on the follower through the contact
  //   kinetic    T = ½ vᵀ M v
  //   potential  V = ½ qᵀ K q − f₀ᵀ q (strain + return spring)
  //   dissipated D = ∫ vᵀ C v dt
  // and W = ΔT + ΔV + D is the balance checked by the stability suite.
  double potential() const { return m_.potential_energy(y_.data()); }
  // Power dissipated at the current state (damping).
  double dissipation_power() const { return m_.damping_power(y_.data() + n_); }

  void emit_row() { emit_row_at(t_, y_, F_, contact_, potential(), work_, dissipated_); }
  void emit_row_at(double t, const Eigen::VectorXd& y, double F, bool contact, double V,
                   double W, double D, const CamMotion* c = nullptr) {
    HistoryRow r;
    r.t = t;
    r.theta = drive_.theta(t);
    const CamMotion cm = c ? *c : cam_at(t);
    r.u_c = y[0];
    r.v_c = y[n_];
    r.a_c = m_.contact_acceleration(y.data(), y.data() + n_, F);
    r.contact_force = F;
    r.gap = y[0] - cm.X;
    r.in_contact = contact ? 1 : 0;
    r.kinetic = m_.kinetic_energy(y.data() + n_);
    r.potential = V - V0_;
    r.work_cam = W;
    r.dissipated = D;
    if (sc_.run.designer_columns) design_cols_.append(cam_.evaluate(r.theta), F, drive_.omega(t), r.extra);
    last_row_t_ = t;
    if (obs_ && obs_->on_output(r) == ObserverAction::Stop) observer_stop_ = true;
  }
  [[noreturn]] static void throw_observer_stop() {
    throw StepFailure(Termination::StoppedByObserver, "stopped by observer");
  }

  // impulse: the impact impulse applied at the instant (0: none); t_event: the event time
  // when it is not the current time t_ (NaN); the event's cam angle is taken there.
  void record_event(EventKind kind, double v, double impulse = 0.0, double t_event = NAN) {
    const double te = std::isnan(t_event) ? t_ : t_event;
    ContactEvent e;
    e.t = te;
    e.kind = to_string(kind);
    e.impact_velocity = v;
    e.theta = drive_.theta(te);
    e.impulse = impulse;
    e.type = kind;
    designer_.event(e);
    sum_.events.push_back(e);
    if (obs_) obs_->on_event(e);
  }

  // Work of the contact force over the step just taken by the trapezoid rule on F·Ẋ_C
  // (state already updated to the step's end).
  double trapezoid_work(double h, double F_prev, double Xdot_prev) const {
    return 0.5 * h * (F_prev * Xdot_prev + F_ * cam_at(t_).Xdot);
  }

  // Statistics and output after an accepted step (state already updated); dW is the
  // work the contact force did over the step.
  // P_end: dissipated power at the end of the step if it differs from the current
  // state's (the pre-impact state of a free flight ended by an impact); NaN: the state's.
  void after_step(double h, double dW, double P_prev, double P_end = NAN) {
    ++sum_.steps;
    const CamMotion cm = cam_at(t_);
    const double P = std::isnan(P_end) ? dissipation_power() : P_end;
    work_ += dW;
    dissipated_ += 0.5 * h * (P_prev + P);
    const double gap = y_[0] - cm.X;
    sum_.max_contact_force = std::max(sum_.max_contact_force, F_);
    sum_.min_gap = std::min(sum_.min_gap, gap);
    sum_.max_penetration = std::max(sum_.max_penetration, -gap);
    designer_step(cm.X);
    if (bilateral_ && F_ < 0.0 && sum_.first_tensile_time < 0) {
      sum_.first_tensile_time = t_;
      record_event(EventKind::Tensile, 0.0);
    }
    if (out_dt() <= 0.0) {
      emit_row();
    } else {
      while (!observer_stop_ && next_out_ * out_dt() <= t_ * (1 + 1e-12) + 1e-300 && next_out_ * out_dt() <= sc_.run.t_end * (1 + 1e-12)) {
        const double to = double(next_out_) * out_dt();
        ++next_out_;
        emit_row();  // steps land on the output times
      }
      if (!observer_stop_ && t_ >= sc_.run.t_end && last_row_t_ < t_) emit_row();
    }
    if (observer_stop_) throw_observer_stop();
    if (stop_ && stop_->load()) throw StepFailure(Termination::StoppedByCaller, stop_reason_);
    if (sum_.steps + sum_.rejected_steps > sc_.run.max_steps)
      throw StepFailure(Termination::MaxSteps,
                        "run.max_steps = " + std::to_string(sc_.run.max_steps) + " reached");
    if (!y_.allFinite() || !std::isfinite(F_))
      throw StepFailure(Termination::NonFinite, "non-finite state");
    if (obs_ && (sum_.steps & 255) == 0) {
      const double w = progress_clock_.wall();
      if (w - last_progress_ > 0.2) {
        last_progress_ = w;
        obs_->on_progress(t_, sc_.run.t_end, sum_.steps);
      }
    }
  }

  // Designer results (designer_stats.hpp) at an accepted state: the step end, and the
  // contact force while in contact.
  // `X_C`: the cam's X at t_ (the caller has it).
  void designer_step(double X_C) {
    const double th = drive_.theta(t_);
    designer_.step(t_, th, y_[0], y_[n_], m_.contact_acceleration(y_.data(), y_.data() + n_, F_),
                   y_[0] - X_C);
    if (contact_) designer_.sample_force(t_, th, F_);
  }

  // The step to try from t_ toward t_next (fit_step_size). @throws StepFailure.
  double fit_step(double h, double t_next) const { return fit_step_size(sc_, t_, h, t_next); }

  // Full acceleration a = M⁻¹(f₀ − Kq − Cv + e₀F) at state y under contact force F.
  void full_acceleration(const Eigen::VectorXd& y, double F, Eigen::VectorXd& a) {
    a.resize(n_);
    rbuf_.resize(n_);
    m_.internal_force(y.data(), y.data() + n_, rbuf_.data());
    rbuf_[0] += F;
    m_.solve_mass(rbuf_.data(), a.data());
  }

  double initial_step() const { return first_step_size(sc_); }

  template <class G>
  static double adaptive_simpson(G& g, double a, double b, double fa, double fm, double fb,
                                 double S, double tol, int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = g(lm), frm = g(rm);
    const double Sl = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    const double Sr = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    const double S2 = Sl + Sr;
    if (depth <= 0 || std::abs(S2 - S) <= 15.0 * tol) return S2 + (S2 - S) / 15.0;
    return adaptive_simpson(g, a, m, fa, flm, fm, Sl, 0.5 * tol, depth - 1) +
           adaptive_simpson(g, m, b, fm, frm, fb, Sr, 0.5 * tol, depth - 1);
  }

  Eigen::VectorXd rbuf_;  // full_acceleration's right-hand side
  Eigen::VectorXd y_prev_, hq_, hv_, ha_, hb_;  // Lee's contact-work quadrature and interpolation

  const Scene& sc_;
  std::shared_ptr<const FollowerModel> model_;
  const FollowerModel& m_;
  Cam cam_;
  CamDrive drive_;
  CamStops stops_{sc_, cam_};
  Observer* obs_;
  const std::atomic<bool>* stop_;
  std::string stop_reason_ = "stopped by caller";
  int n_;
  std::unique_ptr<Engine> engine_;
  detail::DesignerStats designer_;
  detail::DesignerColumns design_cols_{sc_};  // run.designer_columns
  Summary sum_;
  bool bilateral_ = false, contact_ = false;
  bool observer_stop_ = false;  // an observer returned ObserverAction::Stop
  double tol_u_ = 1e-8;
  double t_ = 0, F_ = 0, E0_ = 0, V0_ = 0, work_ = 0, dissipated_ = 0, last_row_t_ = -1;
  long next_out_ = 1;
  Eigen::VectorXd y_;
  Clock progress_clock_;
  double last_progress_ = 0;
};

/// One contact method of the registry: its name (reports), which scenes it runs, and its
/// factory.
struct ContactMethodEntry {
  const char* name;
  bool (*selects)(const Scene&);
  std::unique_ptr<RunContext> (*make)(const Scene&, std::shared_ptr<const FollowerModel>,
                                      Observer*, const std::atomic<bool>*);
};
/// The registry, in order of precedence (src/legacy/registry.cpp).
const std::vector<ContactMethodEntry>& contact_methods();
/// Adds a method in front of the registry (tests: a method defined outside the library).
/// Not thread-safe: register before running.
void register_contact_method(const ContactMethodEntry& entry);
/// The first registered method that selects `scene`. @throws std::logic_error if none.
std::unique_ptr<RunContext> make_contact_method(const Scene& scene,
                                                std::shared_ptr<const FollowerModel> model,
                                                Observer* obs, const std::atomic<bool>* stop);

}  // namespace detail
}  // namespace camdyn
