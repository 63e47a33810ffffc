// The single-follower stack's methods are pluggable (solver.stack = "follower", Lee's
// classic step; every other method is a ContactRun subclass on the mechanism, one line in
// make_contact_method): a method is a RunContext subclass (one file) plus one registry
// entry. This test defines a tiny method outside the library — a bilateral
// contact that never separates: fixed steps, the two-parameter force shape solved with
// Lee's constants of the contact mass M* (exact for a rigid follower), the acceleration
// level's force at each step end — registers it, and checks it against the closed form of
// case A (a rigid follower riding the cam: u_c = X_C, F = m Ẍ_C + k δ₀ + k (X_C − X_C(0))).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"
#include "legacy/run_context.hpp"

namespace camdyn {
namespace {

class TinyBilateral final : public detail::RunContext {
 public:
  using RunContext::RunContext;

 private:
  void run_method() override {
    StepRamp law;  // the method's force on the contact node: a shape over each step
    engine_->set_contact(&law);
    const double Ms = m_.mstar(), h = 1e-3;
    Eigen::VectorXd y1(2 * n_);
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      const double hs = std::min(h, sc_.run.t_end - t_), t1 = t_ + hs;
      const CamMotion cm = cam_at(t1);
      law.t0 = t_;
      law.h = hs;
      law.F0 = F_;
      law.F1 = F_;
      law.Fc = 0.0;
      // (Δu₀, Δu̇₀) per unit F₁ and F_c for the mass M*: M*(h²/6, h/2), M*(h²/3, 2h/3)
      const double a11 = Ms * hs * hs / 6, a12 = Ms * hs * hs / 3, a21 = Ms * hs / 2, a22 = 2 * Ms * hs / 3;
      const double det = a11 * a22 - a12 * a21;
      for (int it = 0; it < 20; ++it) {
        engine_->step(t_, y_, hs, y1);
        const double r0 = cm.X - y1[0], r1 = cm.Xdot - y1[n_];
        if (it > 0 && std::abs(r0) < tol_u_ && std::abs(r1) < tol_u_ / hs) break;
        law.F1 += (r0 * a22 - a12 * r1) / det;
        law.Fc += (a11 * r1 - a21 * r0) / det;
      }
      const double Ft = F_, Xdot0 = cam_at(t_).Xdot, P_prev = dissipation_power();
      y_ = y1;
      t_ = t1;
      F_ = (cm.Xddot - m_.contact_acceleration(y_.data(), y_.data() + n_, 0.0)) / Ms;
      after_step(hs, trapezoid_work(hs, Ft, Xdot0), P_prev);
    }
  }
};

TEST(ContactRegistry, ATinyMethodIsOneClassAndOneRegistryEntry) {
  detail::register_contact_method(
      {"tiny bilateral", [](const Scene& s) { return s.title == "tiny bilateral"; },
       [](const Scene& sc, std::shared_ptr<const FollowerModel> m, Observer* o,
          const std::atomic<bool>* st) -> std::unique_ptr<detail::RunContext> {
         return std::make_unique<TinyBilateral>(sc, std::move(m), o, st);
       }});
  Scene s = paper_case("A");
  s.title = "tiny bilateral";
  s.run.t_end = 0.2;
  s.run.output_dt = 1e-3;
  s.solver.stack = StackKind::Follower;  // the registry of the single-follower stack (classic step)
  s.contact.lee_step = LeeStepKind::Classic;
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_EQ(r.summary.steps, 200);  // its fixed 1 ms steps: the tiny method ran
  const Cam cam(s.cam);
  const CamDrive drive(s.cam);
  const double X0 = cam.evaluate(drive.theta(0.0)).X_C, k = s.spring.stiffness;
  double du = 0, dF = 0, Fmax = 0;
  for (const HistoryRow& row : r.rows) {
    const CamMotion c = cam.motion(drive.theta(row.t), drive.omega(row.t), drive.omega_dot(row.t));
    const double F = s.follower.mass * c.Xddot + k * s.spring.precompression + k * (c.X - X0);
    du = std::max(du, std::abs(row.u_c - c.X));
    dF = std::max(dF, std::abs(row.contact_force - F));
    Fmax = std::max(Fmax, F);
  }
  std::printf("tiny bilateral method, case A: max |Δu_c| %.3e, max |ΔF|/F_max %.3e\n", du, dF / Fmax);
  EXPECT_LT(du, s.contact.tol_u);  // the iteration stops within tol_u
  EXPECT_LT(dF, 1e-8 * Fmax);
  // Scenes it does not select still run the registry's methods (Lee's classic step).
  Scene lee = paper_case("A");
  lee.run.t_end = 0.2;
  lee.run.output_dt = 1e-3;
  lee.solver.stack = StackKind::Follower;
  lee.contact.lee_step = LeeStepKind::Classic;
  const RunResult rl = simulate(lee);
  ASSERT_TRUE(rl.summary.finished);
  EXPECT_NE(rl.summary.steps, 200);
}

}  // namespace
}  // namespace camdyn
