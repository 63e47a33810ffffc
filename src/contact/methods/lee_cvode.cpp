// camdyn — Lee's method on the multistep engine (contact.model = "lee" or "holonomic",
// located step, solver.integrator = "cvode-bdf"; any mechanism: a rigid or elastic_bar
// follower, a network, a user FollowerSystem): the three levels of every held contact inside CVODE's own BDF step, for
// any number of held contacts, instead of around it (methods/lee_located.cpp restarted CVODE in
// every trial step of the located step and iterated the shape on top of it: one OHC
// revolution 14.7× the arkode-erk run, docs/one_mechanism.md).
//
//   acceleration level   the held set's forces are the forces the equation of motion
//                        demands, W_AA F_A = Ẍ_C,A − T_A M⁻¹(f₀ − Kq − Cv) (dependent sets:
//                        minimal norm by complementarity, active_set.cpp), evaluated in the
//                        right-hand side at the corrector's state; the Newton matrix is the
//                        sparse Schur complement bordered with T_A (sparse_newton.cpp), the
//                        exact Jacobian of this level;
//   displacement and     every step's corrected state is put on g_A = 0, ġ_A = 0
//   velocity levels      M-orthogonally, through CVODE's projection (CVodeSetProjFn), which
//                        carries the correction into its Nordsieck history;
//   switches             CVODE's rootfinding on its interpolant put on the held contacts'
//                        manifold: a held contact separates where its force (its
//                        complementarity margin) reaches zero, an open one impacts where its
//                        gap reaches zero; the impact law is the Newton law on every contact
//                        taking part (contact_run.cpp: resolve_impact). CVODE restarts only
//                        at impacts and at cam breakpoints under held contacts that leave
//                        unknowns free; a separation alone keeps its history
//                        (methods/event.hpp).
//
// This is the held-contact machinery of the event method (methods/event.hpp),
// which Lee's three levels and this one coincide with once the levels are solved inside
// the step: what differs is the output. The event method lands its steps on the output
// times; here, as Lee's located step on the one-step engines (run.land_on_output = false),
// the steps run free and the rows inside a step come from CVODE's interpolant, put on the
// held contacts' manifold by the same projection, with the acceleration level's forces
// there, the cam's work by Gauss–Legendre on the interpolant and the dissipated energy by
// the trapezoid from the step's start. run.land_on_output = true: steps land on the rows.
#include <algorithm>
#include <cmath>

#include "contact/methods/event.hpp"

namespace camdyn {
namespace detail {
namespace {

class LeeInCvode final : public EventMethod {
 public:
  // BDF up to order 4 without stiff internal modes (cvode_bdf_order, methods/bdf_order.hpp)
  LeeInCvode(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
                  const std::atomic<bool>* stop)
      : EventMethod(sc, std::move(mech), obs, stop) {}

 private:
  struct Row {
    double t, W, D;
    Eigen::VectorXd y, F;
    std::vector<char> active;
  };
  std::vector<Row> rows_;  // the output rows inside the last step
  Eigen::VectorXd corr_;

  // The held state at τ inside the last step (CVODE's interpolant put on the held
  // contacts), its forces, and the cam's power and the dissipated power there.
  Eigen::VectorXd yh_, Fh_;
  struct Power {
    double W, D;
  };
  Power power_at(double tau) {
    eng_->dense(tau, yh_);
    corr_.resize(ny_);
    project(tau, yh_.data(), corr_.data());
    yh_ += corr_;
    const CamMotion cm = cam_at(tau);
    Fh_ = held_forces(tau, yh_, cm, set_);
    if (unilateral_)
      for (int j : set_) Fh_[j] = std::max(Fh_[j], 0.0);
    const Power p{cam_power(Fh_, cm), dissipation_power(tau, yh_)};
    scale_.W = std::max(scale_.W, std::abs(p.W));
    scale_.D = std::max(scale_.D, std::abs(p.D));
    return p;
  }
  Power scale_{0.0, 0.0};  // the largest powers so far (the quadrature's tolerance)
  // ∫ over [a, b] of the powers: 3-point Gauss–Legendre, halved (8 times at most) where it
  // differs from Simpson's rule on its midpoint and the ends (pa, pb) by more than
  // rtol·(b − a)·(the largest power so far, at least 10⁻⁶ of the train's power scale: the
  // force scale times the cam's lift speed). Without the floor a dwell, whose powers are
  // round-off, halved every row interval 8 times (a finger on a rigid pivot: 1.6 s of CPU
  // for one revolution with 2000 rows, 0.05 s without rows).
  double power_floor() const {
    return 1e-6 * mk_.force_scale() * std::abs(cam_.lift()) * std::abs(drive_.omega(t_));
  }
  Power integrate(double a, double b, Power pa, Power pb, int depth) {
    static const double xg = 0.7745966692414834;
    const double c = 0.5 * (a + b), r = 0.5 * (b - a);
    const Power p1 = power_at(c - r * xg), pm = power_at(c), p2 = power_at(c + r * xg);
    const Power G{r * (5.0 * (p1.W + p2.W) + 8.0 * pm.W) / 9.0, r * (5.0 * (p1.D + p2.D) + 8.0 * pm.D) / 9.0};
    const Power S{r * (pa.W + 4.0 * pm.W + pb.W) / 3.0, r * (pa.D + 4.0 * pm.D + pb.D) / 3.0};
    const double tol = sc_.solver.rtol * (b - a);
    const double floor = power_floor();
    if (depth >= 8 || (std::abs(G.W - S.W) <= tol * std::max(scale_.W, floor) &&
                       std::abs(G.D - S.D) <= tol * std::max(scale_.D, floor)))
      return G;
    const Power l = integrate(a, c, pa, pm, depth + 1), u = integrate(c, b, pm, pb, depth + 1);
    return {l.W + u.W, l.D + u.D};
  }
  // A held set that fixes every unknown (a rigid follower on the cam) leaves CVODE's error
  // test nothing to see (the held nodes follow the cam through the acceleration level,
  // sampled at the step's end, and the projection), and CVODE does not restart at the
  // cam's breakpoints there (methods/event.hpp: restart_at_breaks_): one step may cross a
  // whole law segment. Its state is the projection's (exact), but the cam's work is not a
  // 3-point rule's over such a step (the ramp law of tests/contact/test_cam_joint_impact.cpp: 71 J
  // of 3200 off; case A, 1 s: 5.7e-7 J, 1.5e-8 J with this): the energies are integrated
  // adaptively on the held state, piece by piece between the rows inside the step (their
  // states, forces and cumulative energies are the rows'). Other held sets leave the
  // motion to CVODE's error test: 3-point Gauss–Legendre over the step.
  bool rows_done_ = false;
  StepEnergy advance_energy(double t0, double t1) override {
    rows_done_ = false;
    if (set_.empty() || int(set_.size()) < n_) return EventMethod::advance_energy(t0, t1);
    rows_.clear();
    rows_done_ = true;
    Power pa = power_at(t0), sum{0.0, 0.0};
    const Power pb = power_at(t1);
    double a = t0;
    for (long k = next_out_;; ++k) {
      const double to = double(k) * out_dt();  // as after_advance
      const bool row = !land() && to < t1 && !(to > sc_.run.t_end * (1 + 1e-12));
      if (row && !(to > t0)) continue;
      const double b = row ? to : t1;
      Row r;
      const Power p = row ? power_at(b) : pb;
      if (row) r = Row{b, 0.0, 0.0, yh_, Fh_, active_};
      const Power e = integrate(a, b, pa, p, 0);
      sum.W += e.W;
      sum.D += e.D;
      a = b;
      pa = p;
      if (!row) break;
      r.W = work_ + sum.W;
      r.D = dissipated_ + sum.D;
      rows_.push_back(std::move(r));
    }
    StepEnergy dE;
    dE.work = sum.W;
    dE.dissipated = sum.D;
    return dE;
  }

  bool land() const { return sc_.run.land_on_output || out_dt() <= 0.0; }
  double step_horizon() override { return land() ? next_output_time() : sc_.run.t_end; }

  void after_advance(double t_prev, double P_prev) override {
    if (rows_done_) return;  // advance_energy's
    rows_.clear();
    if (land()) return;
    for (long k = next_out_;; ++k) {
      const double to = double(k) * out_dt();  // as ContactRun::after_step
      if (!(to < t_) || to > sc_.run.t_end * (1 + 1e-12)) break;
      if (!(to > t_prev)) continue;
      Row r;
      r.t = to;
      eng_->dense(to, r.y);
      if (!set_.empty()) {
        corr_.resize(ny_);
        project(to, r.y.data(), corr_.data());
        r.y += corr_;
      }
      const CamMotion cm = cam_at(to);
      r.F = held_forces(to, r.y, cm, set_);
      if (unilateral_)
        for (int j : set_) r.F[j] = std::max(r.F[j], 0.0);
      r.active = active_;
      r.W = work_ + (set_.empty() ? 0.0 : held_work(t_prev, to));
      r.D = dissipated_ + 0.5 * (to - t_prev) * (P_prev + dissipation_power(to, r.y));
      rows_.push_back(std::move(r));
    }
  }

  bool dense_row_at(double to) override {
    for (const Row& r : rows_)
      if (r.t == to) {
        emit_row_at(r.t, r.y, r.F, r.active, r.W, r.D);
        return true;
      }
    return false;
  }
};

}  // namespace

std::unique_ptr<ContactRun> make_lee_in_cvode(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                              Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<LeeInCvode>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
