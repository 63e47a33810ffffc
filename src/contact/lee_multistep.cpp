// camdyn — Lee's method on the multistep engine (contact.model = "lee", located step,
// solver.integrator = "cvode-bdf", elastic follower).
//
//   While node 0 is on the cam, the three levels of Lee's step are imposed inside CVODE's
//   own BDF step instead of around it, so CVODE keeps its order and history:
//     acceleration level  the contact force is the force the equation of motion demands,
//                         F = (Ẍ_C − ü₀,free(q, v)) / M*   (eq. 16 with its exact constant
//                         b̃ = 1/M*), evaluated in the right-hand side at the corrector's
//                         state: BDF samples the force only at the new time t_{n+1}, and
//                         the Newton matrix is the bordered one of the held contact
//                         (engines.cpp, SchurSolver::solve), so the linear follower's
//                         corrector converges in one iteration with the force consistent
//                         with the state it accepts;
//     displacement and    the corrected state is put on u₀ = X_C, u̇₀ = Ẋ_C (eqs. 14, 15
//     velocity levels     solved exactly) by translating the follower rigidly — the
//                         correction that changes no strain, so it adds no force —
//                         through CVODE's projection interface, which carries it into
//                         its Nordsieck history (CvodeEngine::project). The reported
//                         force is the acceleration level's at the projected state.
//   Retaking a step with another force, which restarted CVODE at order 1 in every trial
//   step of the located step, never happens: for a linear follower the step map is
//   affine in the force and the force is solved together with the state.
//
//   Separation: the force reaching zero (decreasing) is located by CVODE's rootfinding on
//   its interpolant. Free flight: F = 0, the gap closing located likewise. Impacts: a
//   Newton impulse P = (1 + e) ŝ⁻ / M* on node 0 (Δv = M⁻¹e₀P), then contact if the
//   force is compressive (the velocity and acceleration levels at a zero-length step, as
//   in the located step). CVODE restarts only at these events (the state or its
//   equations change there), as in the event-driven method.
//
//   The contact work: the quadratic through the last three step ends' F·Ẋ_C, integrated
//   over the step (the trapezoid on a phase's first step). Not Simpson's rule with a
//   midpoint from CVODE's interpolant: inside a step that interpolant carries an error of
//   the local tolerance in every nodal position, which the stiff first element turns into
//   force (k_e·δ) — on the stiff bar at rtol 1e-2 the work came out 34 % low. Output rows
//   are step ends (steps land on output times, as in the event-driven method), for the
//   same reason.
#include <algorithm>
#include <cmath>
#include <limits>

#include "free_flight.hpp"
#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

// Node 0 held on the cam's contact point.
class CamHeld final : public HeldContact {
 public:
  CamHeld(const Cam& cam, const CamDrive& drive) : cam_(cam, drive) {}
  CamMotion path(double t) const override { return cam_.at(t); }

 private:
  CamPath cam_;
};

class LeeMultistep final : public RunContext {
 public:
  LeeMultistep(const Scene& sc, std::shared_ptr<const FollowerModel> model, Observer* obs,
               const std::atomic<bool>* stop)
      : RunContext(sc, std::move(model), obs, stop) {
    engine_ = make_engine(model_, sc_.solver, /*trial=*/false);  // native stepping
  }

 private:
  CamHeld held_{cam_, drive_};

  void run_method() override {
    // The event-driven method's order policy (event.cpp), so that the two compare on the
    // same engine: BDF ≤ 2 for bars, up to 5 with stability-limit detection at rtol ≤ 1e-8.
    if (sc_.solver.rtol <= 1e-8) engine_->set_max_order(5);
    FreeFlight free(*this);
    // The previous step end's (t, F·Ẋ_C) inside the current held phase (NaN: none).
    double ta = NAN, ga = 0.0;
    auto start_held = [&]() {
      ta = NAN;
      engine_->set_contact(&held_);
      engine_->set_held_projection(true);
      if (bilateral_)
        engine_->set_root(nullptr, 0);
      else
        engine_->set_root([this](double t, const double* y) { return engine_->held_force(held_.path(t), y); }, -1);
      engine_->reinit(t_, y_);
    };
    auto start_free = [&]() {
      engine_->set_contact(nullptr);
      engine_->set_held_projection(false);
      free.start();
    };
    bool in_contact = bilateral_ || (contact_ && F_ > 0.0);
    contact_ = in_contact;
    if (!in_contact) F_ = 0.0;
    if (in_contact)
      start_held();
    else
      start_free();
    Eigen::VectorXd y1;
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_stop_time();
      const double Ft = F_, Xdot_prev = cam_at(t_).Xdot, P_prev = dissipation_power();
      const double t_prev = t_;
      bool separation = false;
      double dW = 0.0, P_end = NAN, F_end = 0.0;
      const long impacts_before = sum_.impacts;
      if (in_contact) {
        t_ = engine_->advance(tout, y1);
        y_ = y1;
        separation = engine_->hit_root();
        F_ = separation ? 0.0 : engine_->held_force(cam_at(t_), y_.data());
        if (!bilateral_ && F_ < 0.0) F_ = 0.0;
        F_end = F_;
        const double gb = Ft * Xdot_prev, gc = F_ * cam_at(t_).Xdot;
        dW = held_work(ta, ga, t_prev, gb, t_, gc);
        ta = t_prev;
        ga = gb;
        if (separation) {
          in_contact = false;
          start_free();
        }
      } else {
        const FreeFlight::Outcome o =
            free.advance(tout, y1, &P_end, [this]() { return engine_->held_force(cam_at(t_), y_.data()); });
        if (o == FreeFlight::Outcome::Contact) {
          in_contact = true;
          start_held();
        } else if (o != FreeFlight::Outcome::None) {
          start_free();
        }
      }
      if (separation) {
        ++sum_.separations;
        record_event(EventKind::Separation, 0.0);
      }
      contact_ = in_contact;
      // The step's force as the line through its end forces, and its impact impulse
      // (replay: bench/bench_overhead).
      if (obs_)
        obs_->on_lee_shape(t_prev, t_ - t_prev, Ft, F_end, 0.0,
                           sum_.impacts > impacts_before ? sum_.events.back().impulse : 0.0);
      after_step(t_ - t_prev, dW, P_prev, P_end);
    }
  }

  // ∫ g over [b, c] of the quadratic through (a, ga), (b, gb), (c, gc) (Lagrange weights);
  // the trapezoid if a is NaN.
  static double held_work(double a, double ga, double b, double gb, double c, double gc) {
    const double h2 = c - b;
    if (std::isnan(a)) return 0.5 * h2 * (gb + gc);
    const double h1 = b - a;
    const double wa = -h2 * h2 * h2 / (6.0 * h1 * (h1 + h2));
    const double wb = h2 * h2 / (6.0 * h1) + 0.5 * h2;
    const double wc = (h2 * h2 / 3.0 + 0.5 * h1 * h2) / (h1 + h2);
    return wa * ga + wb * gb + wc * gc;
  }
};

}  // namespace

std::unique_ptr<RunContext> make_lee_multistep(const Scene& sc, std::shared_ptr<const FollowerModel> model,
                                               Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<LeeMultistep>(sc, std::move(model), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
