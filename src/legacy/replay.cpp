// camdyn — replay of a Lee step sequence (see replay.hpp).
#include "legacy/replay.hpp"

#include <ctime>

#include "camdyn/cam.hpp"
#include "legacy/engine.hpp"

namespace camdyn {

namespace {
// The run's initial state (run_context.hpp, RunContext::run): q(0) from the model, the
// contact face at the cam's velocity if touching.
Eigen::VectorXd initial_state(const Scene& scene, const FollowerModel& model) {
  const int n = model.n();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  y.head(n) = model.initial_displacement();
  if (scene.contact.initial_gap == 0.0) {
    const Cam cam(scene.cam);
    const CamDrive drive(scene.cam);
    y[n] = cam.motion(drive.theta(0.0), drive.omega(0.0), drive.omega_dot(0.0)).Xdot;
  }
  return y;
}
}  // namespace

ReplayResult replay_lee_steps(const Scene& scene, const std::vector<LeeStep>& steps) {
  const auto model = build_model(scene);
  const int n = model->n();
  Eigen::VectorXd y = initial_state(scene, *model), y1(2 * n);
  ReplayResult r;
  const std::clock_t c0 = std::clock();
  const auto engine = make_engine(model, scene.solver, scene.contact.model == ContactModel::Lee, scene.contact.tol_u);
  StepRamp law;
  engine->set_contact(&law);
  const Eigen::VectorXd& col0 = model->contact_column();  // Δv of a unit impulse
  for (const LeeStep& s : steps) {
    law.t0 = s.t0;
    law.h = s.h;
    law.F0 = s.F0;
    law.F1 = s.F1;
    law.Fc = s.Fc;
    engine->step(s.t0, y, s.h, y1);
    y.swap(y1);
    if (s.impulse != 0.0) y.tail(n) += s.impulse * col0;
  }
  r.cpu_seconds = double(std::clock() - c0) / CLOCKS_PER_SEC;
  r.engine_steps = engine->stats().steps;
  r.y = std::move(y);
  return r;
}

}  // namespace camdyn
