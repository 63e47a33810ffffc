// camdyn — the holonomic baseline on SUNDIALS IDA (solver.integrator = "ida"): the held
// contact as an index-2 GGL DAE (src/ida_engine.cpp). IDA steps natively and stops on
// every output time (rows are step values); the force is the multiplier λ, the cam's work
// W = ∫ λ Ẋ_C dt a DAE component; a root of λ (decreasing) is the first tensile time.
#include "ida_engine.hpp"
#include "run_context.hpp"

namespace camdyn {
namespace detail {
namespace {

class IdaHolonomic final : public RunContext {
 public:
  using RunContext::RunContext;

 private:
  void run_method() override {
    IdaHeldContact ida(model_, sc_, [this](double t) { return cam_at(t); });
    ida.set_tensile_root(true);
    ida.init(t_, y_, sc_.run.t_end);
    y_ = ida.state();
    F_ = ida.lambda();
    contact_ = true;
    sum_.model.linear_solver = to_string(ida.linear_solver());
    sum_.model.unknowns = ida.unknowns();
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double tout = next_stop_time();
      const double P_prev = dissipation_power(), t_prev = t_, W_prev = ida.work();
      t_ = ida.advance(tout, out_dt() <= 0.0);  // output_dt = 0: one row per IDA step
      y_ = ida.state();
      F_ = ida.lambda();
      if (ida.hit_root() && sum_.first_tensile_time < 0) {
        sum_.first_tensile_time = t_;
        record_event(EventKind::Tensile, 0.0);
        ida.set_tensile_root(false);
      }
      after_step(t_ - t_prev, ida.work() - W_prev, P_prev);
      sum_.steps = ida.stats().steps;  // after_step counts output intervals: IDA's steps
    }
    const EngineStats st = ida.stats();
    sum_.steps = st.steps;
    sum_.rejected_steps = ida.rejected_steps();
    sum_.rhs_evals += st.rhs_evals;
    sum_.lin_setups += st.lin_setups;
    sum_.lin_analyses += st.lin_analyses;
  }
};

}  // namespace

std::unique_ptr<RunContext> make_ida_holonomic(const Scene& sc, std::shared_ptr<const FollowerModel> model,
                                               Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<IdaHolonomic>(sc, std::move(model), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
