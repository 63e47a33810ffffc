// camdyn — Lee's method on the multistep engine (contact.model = "lee" or "holonomic",
// located step, solver.integrator = "cvode-bdf"; any mechanism: a rigid or elastic_bar
// follower, a network, a user FollowerSystem): the three levels of every held contact inside CVODE's own BDF step, for
// any number of held contacts, instead of around it (network_lee.cpp restarted CVODE in
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
//                        taking part (network_run.cpp: resolve_impact). CVODE restarts only
//                        at impacts and at cam breakpoints under held contacts that leave
//                        unknowns free; a separation alone keeps its history
//                        (network_event.hpp).
//
// This is the held-contact machinery of the network event method (network_event.hpp),
// which Lee's three levels and this one coincide with once the levels are solved inside
// the step: what differs is the output. The event method lands its steps on the output
// times; here, as Lee's located step on the one-step engines (run.land_on_output = false),
// the steps run free and the rows inside a step come from CVODE's interpolant, put on the
// held contacts' manifold by the same projection, with the acceleration level's forces
// there, the cam's work by Gauss–Legendre on the interpolant and the dissipated energy by
// the trapezoid from the step's start. run.land_on_output = true: steps land on the rows.
#include <algorithm>
#include <cmath>

#include "network_event.hpp"

namespace camdyn {
namespace detail {
namespace {

class NetworkLeeCvode final : public NetworkEvent {
 public:
  // BDF up to order 4 (measured: at CVODE's default 5 the OHC train at 40 rev/s, rtol 1e-8,
  // met its small re-impact after a 33 µs flight with an impulse 1.9e-4 off the event
  // method's on ERK at rtol 1e-12 — the stiff stem turns the valve's position error at the
  // rtol level into force —, at order 4 4e-5; one revolution of OHC / OHV takes 1.6× / 1.3×
  // the steps of order 5, order 3 3.6× / 2.4×)
  NetworkLeeCvode(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
                  const std::atomic<bool>* stop)
      : NetworkEvent(sc, std::move(mech), obs, stop, /*max_order=*/4) {}

 private:
  struct Row {
    double t, W, D;
    Eigen::VectorXd y, F;
    std::vector<char> active;
  };
  std::vector<Row> rows_;  // the output rows inside the last step
  Eigen::VectorXd corr_;

  bool land() const { return sc_.run.land_on_output || out_dt() <= 0.0; }
  double step_horizon() override { return land() ? next_output_time() : sc_.run.t_end; }

  void after_advance(double t_prev, double P_prev) override {
    rows_.clear();
    if (land()) return;
    for (long k = next_out_;; ++k) {
      const double to = double(k) * out_dt();  // as NetworkRun::after_step
      if (!(to < t_) || to > sc_.run.t_end * (1 + 1e-12)) break;
      if (!(to > t_prev)) continue;
      Row r;
      r.t = to;
      eng_->dense(to, r.y);
      if (!set_.empty()) {
        corr_.resize(2 * n_);
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

std::unique_ptr<NetworkRun> make_network_lee_cvode(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                                   Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<NetworkLeeCvode>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
