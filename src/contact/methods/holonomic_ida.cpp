// camdyn — the holonomic baseline on SUNDIALS IDA (solver.integrator = "ida",
// contact.model = "holonomic") for any mechanism: a single follower (one contact) or a
// network. The contacts closed at the start are held as an index-2 GGL DAE
// (src/engine/ida_engine.cpp); IDA steps natively and stops on every output time (rows are step
// values); the held forces are the multipliers λ (the rows report the acceleration
// level's forces on IDA's state instead, below), the cam's work W = Σ ∫ λ_j Ẋ_C dt a DAE
// component. A root of λ_j (decreasing) is the first tensile time (where a unilateral
// contact would open). A contact open at the start that closes (a root of its gap) takes
// the Newton impact law every contact method shares (contact_run.cpp: resolve_impact); held
// from then on (holonomic contacts never release), IDA restarts on the larger held set.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <memory>
#include <string>

#include "engine/ida_engine.hpp"
#include "contact/contact_run.hpp"
#include "contact/run_failure.hpp"

namespace camdyn {
namespace detail {
namespace {

class HolonomicIda final : public ContactRun {
 public:
  using ContactRun::ContactRun;

 private:
  // Holonomic contacts never release: a held set whose rows are dependent (a contact that
  // closes on a chain the others already fix, e.g. a finger's lash closing while cam and
  // seat hold) has no unique multipliers, and IDA's Newton matrix is singular. Lee's
  // method and the event method release what complementarity opens; this one cannot.
  void refuse_dependent(const std::vector<int>& held) const {
    const int k = int(held.size());
    if (k < 2) return;
    const Rows R = rows_at(y_.data());
    Eigen::MatrixXd W(k, k);
    for (int i = 0; i < k; ++i)
      for (int l = 0; l < k; ++l) W(i, l) = R.W(held[i], held[l]);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(W, Eigen::EigenvaluesOnly);
    const Eigen::VectorXd ev = es.eigenvalues();
    const double tol = 1e-10 * ev.cwiseAbs().maxCoeff();
    int rank = 0;
    for (int i = 0; i < k; ++i) rank += ev[i] > tol;
    if (rank == k) return;
    std::string names;
    for (int j : held) names += (names.empty() ? "'" : ", '") + mk_.contacts()[j].name + "'";
    throw StepFailure("the held contacts " + names + " are dependent at t = " + fmt(t_) + " (rank " +
                      std::to_string(rank) + " of " + std::to_string(k) +
                      "): the holonomic method holds every closed contact for good and cannot share a force "
                      "between redundant constraints; use contact.model = \"lee\" or \"event\", which release "
                      "the contacts complementarity opens");
  }

  void run_method() override {
    const auto* mech = dynamic_cast<const Mechanism*>(mech_.get());
    if (!mech) throw StepFailure("solver.integrator = ida needs a linear mechanism (a user follower: arkode or cvode)");
    std::unique_ptr<IdaHeldSet> ida;
    EngineStats st;  // of the IDA runs before the current one (one per held set)
    long rejected = 0;
    auto start = [&] {  // IDA on the contacts held now, from (t_, y_, F_)
      if (ida) {
        const EngineStats s = ida->stats();
        st.steps += s.steps;
        st.rhs_evals += s.rhs_evals;
        st.lin_setups += s.lin_setups;
        st.lin_analyses += s.lin_analyses;
        st.nonlin_iters += s.nonlin_iters;
        st.nonlin_conv_fails += s.nonlin_conv_fails;
        st.err_test_fails += s.err_test_fails;
        rejected += ida->rejected_steps();
        ++rec_.engine_restarts;
      }
      const std::vector<int> held = active_list();
      refuse_dependent(held);
      ida = std::make_unique<IdaHeldSet>(*mech, held, sc_, [this](double t) { return cam_at(t); });
      Eigen::VectorXd lam(held.size());
      for (std::size_t i = 0; i < held.size(); ++i) lam[Eigen::Index(i)] = F_[held[i]];
      ida->init(t_, y_, lam, sc_.run.t_end);
      if (rec_.first_tensile_time >= 0) ida->stop_tensile_roots();
      rec_.model.linear_solver = to_string(ida->linear_solver());
      rec_.model.unknowns = ida->unknowns();
    };
    start();
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_stop_time();
      const double P_prev = dissipation_power(t_, y_), t_prev = t_, W_prev = ida->work(), D_prev = ida->dissipated();
      t_ = ida->advance(tout, out_dt() <= 0.0);  // output_dt = 0: one row per IDA step
      y_ = ida->state();
      // The rows' forces: the acceleration level on IDA's state (W_SS F_S = Ẍ_C,S − T_S a_free).
      // IDA's λ (an index-2 unknown, the BDF-differentiated state) is off by O(rtol·|v|/h)
      // after the short step that lands on an output time: case A at rtol 1e-11, 2e-5 N at
      // one row (3.9e-9 of the peak) where the state's own force is 5e-10 off.
      F_ = held_forces(t_, y_, cam_at(t_), ida->held());
      if (ida->tensile_contact() >= 0 && rec_.first_tensile_time < 0) {
        rec_.first_tensile_time = t_;
        record_event(EventKind::Tensile, ida->tensile_contact(), 0.0);
        ida->stop_tensile_roots();
      }
      const double dW = ida->work() - W_prev, dD = ida->dissipated() - D_prev;
      const int closing = ida->closing_contact();
      if (closing >= 0) {  // an open contact closes: the Newton impact law, then the new held set
        const CamMotion cm = cam_at(t_);
        resolve_impact({closing}, cm);
        settle_active(cm);
      }
      after_step(t_ - t_prev, dW, P_prev, NAN, dD);
      rec_.steps = st.steps + ida->stats().steps;  // after_step counts output intervals: IDA's steps
      if (closing >= 0) start();
    }
    const EngineStats s = ida->stats();
    rec_.steps = st.steps + s.steps;
    rec_.rejected_steps = rejected + ida->rejected_steps();
    rec_.rhs_evals += st.rhs_evals + s.rhs_evals;
    rec_.lin_setups += st.lin_setups + s.lin_setups;
    rec_.lin_analyses += st.lin_analyses + s.lin_analyses;
    rec_.nonlin_iters += st.nonlin_iters + s.nonlin_iters;
    rec_.nonlin_conv_fails += st.nonlin_conv_fails + s.nonlin_conv_fails;
    rec_.err_test_fails += st.err_test_fails + s.err_test_fails;
  }
};

}  // namespace

std::unique_ptr<ContactRun> make_holonomic_ida(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                               Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<HolonomicIda>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
