// The generic OdeEngine (src/engine/ode_engine.hpp) against closed forms, for each engine
// (arkode-erk, arkode-dirk, cvode-bdf) in each mode (trial steps, native stepping):
//   undamped oscillator x'' = −ω²x (ω = 50) to t = 1, exact and difference-quotient
//   Jacobians; observed order of the local error estimate of trial steps; trial steps
//   affine in a forcing parameter (DIRK, linear = true); rootfinding with two functions;
//   dense output inside the last step; a right-hand side that throws; DIRK trial steps of
//   a nonlinear (Duffing) oscillator against RK4 and their Newton iterations.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/ode_engine.hpp"

namespace camdyn {
namespace {

constexpr double kW = 50.0;  // ω
const double kPi = std::acos(-1.0);

// y = [x, v]: x' = v, v' = −ω²x + p·(cos 3t + t). x(0) = 1, v(0) = 0: x = cos ωt for p = 0.
OdeSystem oscillator(bool exact_jacobian, double p = 0.0, bool linear = false) {
  OdeSystem s;
  s.size = 2;
  s.rhs = [p](double t, const double* y, double* yd) {
    yd[0] = y[1];
    yd[1] = -kW * kW * y[0] + p * (std::cos(3.0 * t) + t);
  };
  if (exact_jacobian)
    s.jacobian = [](double, const double*, Eigen::MatrixXd& J) {
      J(0, 0) = 0.0;
      J(0, 1) = 1.0;
      J(1, 0) = -kW * kW;
      J(1, 1) = 0.0;
    };
  s.linear = linear;
  return s;
}

Eigen::VectorXd y0() { return Eigen::Vector2d(1.0, 0.0); }

// Error of y against (cos ωt, −ω sin ωt), the velocity scaled by 1/ω.
double osc_error(double t, const Eigen::VectorXd& y) {
  return std::max(std::abs(y[0] - std::cos(kW * t)), std::abs(y[1] / kW + std::sin(kW * t)));
}

SolverSpec spec(Integrator integ, double rtol = 1e-10, double atol = 1e-12) {
  SolverSpec s;
  s.integrator = integ;
  s.rtol = rtol;
  s.atol = atol;
  return s;
}

struct Case {
  Integrator integ;
  bool exact_jacobian;
  const char* name;
};
std::string case_name(const testing::TestParamInfo<Case>& i) { return i.param.name; }

// Native stepping to t_end; returns the state at t_end.
Eigen::VectorXd run_native(OdeEngine& e, double t_end) {
  Eigen::VectorXd y = y0();
  e.reinit(0.0, y);
  double t = 0.0;
  while (t < t_end) t = e.advance(t_end, y);
  EXPECT_EQ(t, t_end);
  return y;
}

// Trial steps to t_end with a simple step-size controller on the returned WRMS norm
// (fixed h for an engine without an estimate). Counts rejections.
Eigen::VectorXd run_trial(OdeEngine& e, double t_end, long* rejected = nullptr) {
  Eigen::VectorXd y = y0(), y1;
  double t = 0.0, h = e.estimates_error() ? 1e-3 : 0.01;
  long rej = 0;
  while (t < t_end) {
    const double hs = std::min(h, t_end - t);
    const double err = e.step(t, y, hs, y1);
    if (!e.estimates_error()) {
      t = (hs == t_end - t) ? t_end : t + hs;
      y = y1;
      continue;
    }
    const double fac = std::min(4.0, std::max(0.2, 0.9 * std::pow(std::max(err, 1e-10), -1.0 / e.error_order())));
    if (err <= 1.0) {
      t = (hs == t_end - t) ? t_end : t + hs;
      y = y1;
    } else {
      ++rej;
    }
    h = hs * fac;
  }
  if (rejected) *rejected = rej;
  return y;
}

// ------------------------------------------------------------------ native -------
class OdeNative : public testing::TestWithParam<Case> {};

TEST_P(OdeNative, OscillatorToOne) {
  const Case c = GetParam();
  auto e = OdeEngine::make(c.integ, spec(c.integ), oscillator(c.exact_jacobian), false);
  const Eigen::VectorXd y = run_native(*e, 1.0);
  const double err = osc_error(1.0, y);
  RecordProperty("error", std::to_string(err));
  std::printf("  %s native: error at t = 1: %.3g (%ld steps, %ld rhs, %ld setups)\n", c.name, err,
              e->stats().steps, e->stats().rhs_evals, e->stats().lin_setups);
  EXPECT_LT(err, 1e-7);
  EXPECT_GT(e->stats().steps, 100);
  EXPECT_GT(e->stats().rhs_evals, e->stats().steps);
  if (c.integ != Integrator::ArkodeErk) EXPECT_GT(e->stats().lin_setups, 0);
}

TEST_P(OdeNative, TwoRootFunctions) {
  const Case c = GetParam();
  auto e = OdeEngine::make(c.integ, spec(c.integ), oscillator(c.exact_jacobian), false);
  e->set_roots(2, [](double, const double* y, double* g) {
    g[0] = y[0];
    g[1] = y[0] - 0.5;
  });
  Eigen::VectorXd y = y0();
  e->reinit(0.0, y);
  const double t_half = std::acos(0.5) / kW, t_zero = kPi / (2.0 * kW);
  const double tout = 0.05;
  double t = 0.0;
  // First stop: x = 0.5 (function 1, decreasing).
  while (t < tout && !e->hit_root()) t = e->advance(tout, y);
  ASSERT_TRUE(e->hit_root());
  ASSERT_EQ(e->root_info().size(), 2u);
  EXPECT_EQ(e->root_info()[0], 0);
  EXPECT_EQ(e->root_info()[1], -1);
  EXPECT_NEAR(t, t_half, 1e-10);
  EXPECT_NEAR(y[0], 0.5, 1e-8);
  const double d1 = std::abs(t - t_half);
  // Second stop: x = 0 (function 0, decreasing).
  do t = e->advance(tout, y);
  while (t < tout && !e->hit_root());
  ASSERT_TRUE(e->hit_root());
  EXPECT_EQ(e->root_info()[0], -1);
  EXPECT_EQ(e->root_info()[1], 0);
  EXPECT_NEAR(t, t_zero, 1e-10);
  std::printf("  %s roots: |t - t*| = %.3g, %.3g\n", c.name, d1, std::abs(t - t_zero));
  // Then on to tout without further roots.
  do t = e->advance(tout, y);
  while (t < tout && !e->hit_root());
  EXPECT_FALSE(e->hit_root());
  EXPECT_EQ(t, tout);
  // Rootfinding off again.
  e->set_roots(0, nullptr);
  EXPECT_TRUE(e->root_info().empty());
}

TEST_P(OdeNative, DenseInsideLastStep) {
  const Case c = GetParam();
  auto e = OdeEngine::make(c.integ, spec(c.integ), oscillator(c.exact_jacobian), false);
  Eigen::VectorXd y = y0(), yd;
  e->reinit(0.0, y);
  double t = 0.0, t_prev = 0.0;
  while (t < 0.2) {
    t_prev = t;
    t = e->advance(1.0, y);
  }
  ASSERT_GT(t, t_prev);
  double worst = 0.0;
  for (double th : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const double tt = t_prev + th * (t - t_prev);
    e->dense(tt, yd);
    worst = std::max(worst, osc_error(tt, yd));
  }
  e->dense(t, yd);
  EXPECT_LT((yd - y).norm(), 1e-12 * (1.0 + y.norm()));
  std::printf("  %s dense: worst error in [%.5f, %.5f]: %.3g (step-end error %.3g)\n", c.name, t_prev, t, worst,
              osc_error(t, y));
  EXPECT_LT(worst, 1e-8);
}

TEST_P(OdeNative, ThrowingRhsBecomesSundialsError) {
  const Case c = GetParam();
  OdeSystem s = oscillator(c.exact_jacobian);
  bool armed = true;
  auto rhs = s.rhs;
  s.rhs = [rhs, &armed](double t, const double* y, double* yd) {
    if (armed && t > 0.01) throw std::runtime_error("rhs boom");
    rhs(t, y, yd);
  };
  auto e = OdeEngine::make(c.integ, spec(c.integ), s, false);
  Eigen::VectorXd y = y0();
  e->reinit(0.0, y);
  try {
    double t = 0.0;
    while (t < 1.0) t = e->advance(1.0, y);
    FAIL() << "no exception";
  } catch (const SundialsError& err) {
    EXPECT_NE(std::string(err.what()).find("rhs boom"), std::string::npos) << err.what();
  }
  // Usable again after a restart.
  armed = false;
  EXPECT_LT(osc_error(0.1, run_native(*e, 0.1)), 1e-8);
}

INSTANTIATE_TEST_SUITE_P(Engines, OdeNative,
                         testing::Values(Case{Integrator::ArkodeErk, false, "erk"},
                                         Case{Integrator::ArkodeDirk, true, "dirk_exactJ"},
                                         Case{Integrator::ArkodeDirk, false, "dirk_dqJ"},
                                         Case{Integrator::CvodeBdf, true, "cvode_exactJ"},
                                         Case{Integrator::CvodeBdf, false, "cvode_dqJ"}),
                         case_name);

// ------------------------------------------------------------------ trial --------
class OdeTrial : public testing::TestWithParam<Case> {};

TEST_P(OdeTrial, OscillatorToOne) {
  const Case c = GetParam();
  auto e = OdeEngine::make(c.integ, spec(c.integ), oscillator(c.exact_jacobian), true);
  long rejected = 0;
  const Eigen::VectorXd y = run_trial(*e, 1.0, &rejected);
  const double err = osc_error(1.0, y);
  std::printf("  %s trial: error at t = 1: %.3g (%ld steps, %ld rejected, %ld rhs)\n", c.name, err,
              e->stats().steps, rejected, e->stats().rhs_evals);
  EXPECT_LT(err, 1e-7);
}

TEST_P(OdeTrial, LocalErrorOrder) {
  const Case c = GetParam();
  auto e = OdeEngine::make(c.integ, spec(c.integ), oscillator(c.exact_jacobian), true);
  if (!e->estimates_error()) {
    Eigen::VectorXd y1;
    EXPECT_EQ(e->step(0.0, y0(), 0.01, y1), 0.0);
    EXPECT_LT(osc_error(0.01, y1), 1e-9);
    return;
  }
  // Estimates for ωh = 0.2, 0.1, 0.05, 0.025 from a state mid-oscillation.
  const double t0 = 0.3;
  const Eigen::VectorXd y = Eigen::Vector2d(std::cos(kW * t0), -kW * std::sin(kW * t0));
  Eigen::VectorXd y1;
  std::vector<double> est;
  for (double h : {0.2 / kW, 0.1 / kW, 0.05 / kW, 0.025 / kW}) {
    const double w = e->step(t0, y, h, y1);
    const Eigen::VectorXd& le = e->local_error();
    ASSERT_EQ(le.size(), 2);
    EXPECT_NEAR(w, e->wrms(le, y), 1e-12 * w);
    est.push_back(std::hypot(le[0], le[1] / kW));
    // The step itself is accurate to about the size of its estimate.
    EXPECT_LT(osc_error(t0 + h, y1), 10.0 * est.back() + 1e-14);
  }
  std::printf("  %s local error estimates:", c.name);
  for (double v : est) std::printf(" %.3g", v);
  std::printf("\n  %s observed orders:", c.name);
  for (std::size_t i = 1; i < est.size(); ++i) {
    const double p = std::log2(est[i - 1] / est[i]);
    std::printf(" %.3f", p);
    EXPECT_NEAR(p, double(e->error_order()), 0.5) << "halving " << i;
  }
  std::printf("\n");
}

TEST_P(OdeTrial, ThrowingRhsBecomesSundialsError) {
  const Case c = GetParam();
  OdeSystem s = oscillator(c.exact_jacobian);
  bool armed = true;
  auto rhs = s.rhs;
  s.rhs = [rhs, &armed](double t, const double* y, double* yd) {
    if (armed && t > 0.01) throw std::runtime_error("rhs boom");
    rhs(t, y, yd);
  };
  auto e = OdeEngine::make(c.integ, spec(c.integ), s, true);
  Eigen::VectorXd y1;
  try {
    e->step(0.0, y0(), 0.02, y1);
    FAIL() << "no exception";
  } catch (const SundialsError& err) {
    EXPECT_NE(std::string(err.what()).find("rhs boom"), std::string::npos) << err.what();
  }
  armed = false;
  e->step(0.0, y0(), 1e-3, y1);
  EXPECT_LT(osc_error(1e-3, y1), 1e-9);
}

// Root functions (meant for native mode) do not cut a trial step short: the step of h is
// the same with and without them.
TEST_P(OdeTrial, RootsDoNotCutTrialSteps) {
  const Case c = GetParam();
  auto plain = OdeEngine::make(c.integ, spec(c.integ), oscillator(c.exact_jacobian), true);
  auto rooted = OdeEngine::make(c.integ, spec(c.integ), oscillator(c.exact_jacobian), true);
  rooted->set_roots(1, [](double, const double* y, double* g) { g[0] = y[0] - 0.5; });
  Eigen::VectorXd a, b;
  const double h = 0.03;  // x = 0.5 at t = 0.0209 inside the step
  const double ea = plain->step(0.0, y0(), h, a);
  const double eb = rooted->step(0.0, y0(), h, b);
  EXPECT_EQ(ea, eb);
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-12 * a.cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(Engines, OdeTrial,
                         testing::Values(Case{Integrator::ArkodeErk, false, "erk"},
                                         Case{Integrator::ArkodeDirk, true, "dirk_exactJ"},
                                         Case{Integrator::ArkodeDirk, false, "dirk_dqJ"},
                                         Case{Integrator::CvodeBdf, true, "cvode_exactJ"},
                                         Case{Integrator::CvodeBdf, false, "cvode_dqJ"}),
                         case_name);

// ------------------------------------------------------------------ affinity -----
// DIRK trial steps of a linear system (linear = true, exact Jacobian) are affine in a
// forcing parameter p to round-off: y(a p1 + (1 − a) p2) = a y(p1) + (1 − a) y(p2).
TEST(OdeEngineDirk, LinearTrialStepAffineInForcing) {
  const SolverSpec sp = spec(Integrator::ArkodeDirk);
  const double p1 = 3.0e3, p2 = -1.7e3;
  const Eigen::VectorXd y = Eigen::Vector2d(0.3, -20.0);
  const double t = 0.37, h = 0.004;
  auto run = [&](double p, Eigen::VectorXd* le) {
    auto e = OdeEngine::make(Integrator::ArkodeDirk, sp, oscillator(true, p, true), true);
    Eigen::VectorXd y1;
    e->step(t, y, h, y1);
    if (le) *le = e->local_error();
    return y1;
  };
  Eigen::VectorXd l1, l2, la;
  const Eigen::VectorXd y1 = run(p1, &l1), y2 = run(p2, &l2);
  double worst = 0.0, worst_le = 0.0;
  for (double a : {0.5, 0.25, -0.7, 1.9}) {
    const Eigen::VectorXd ya = run(a * p1 + (1.0 - a) * p2, &la);
    const Eigen::VectorXd comb = a * y1 + (1.0 - a) * y2;
    const double scale = std::max({y1.cwiseAbs().maxCoeff(), y2.cwiseAbs().maxCoeff(), ya.cwiseAbs().maxCoeff()});
    const double rel = (ya - comb).cwiseAbs().maxCoeff() / scale;
    worst = std::max(worst, rel);
    EXPECT_LE(rel, 1e-13) << "a = " << a;
    const Eigen::VectorXd comb_le = a * l1 + (1.0 - a) * l2;
    worst_le = std::max(worst_le, (la - comb_le).cwiseAbs().maxCoeff() /
                                      std::max(l1.cwiseAbs().maxCoeff(), l2.cwiseAbs().maxCoeff()));
  }
  std::printf("  dirk linear trial step: affinity defect %.3g (state), %.3g (local error)\n", worst, worst_le);
  // Also with the same engine retaking the step (no fresh engine per parameter): the
  // Newton matrix from the previous step must not leak into the next.
  OdeSystem s = oscillator(true, 0.0, true);
  double p = p1;
  s.rhs = [&p](double tt, const double* yy, double* yd) {
    yd[0] = yy[1];
    yd[1] = -kW * kW * yy[0] + p * (std::cos(3.0 * tt) + tt);
  };
  auto e = OdeEngine::make(Integrator::ArkodeDirk, sp, s, true);
  Eigen::VectorXd r1, r2, rm;
  e->step(t, y, h, r1);
  p = p2;
  e->step(t, y, h, r2);
  p = 0.5 * (p1 + p2);
  e->step(t, y, h, rm);
  EXPECT_LE((rm - 0.5 * (r1 + r2)).cwiseAbs().maxCoeff() / r1.cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LE((r1 - y1).cwiseAbs().maxCoeff() / y1.cwiseAbs().maxCoeff(), 1e-14);
}

// DIRK trial steps of a nonlinear system (a hardening Duffing oscillator x'' = −ω²x − βx³,
// exact Jacobian) from x = 0.6 mid-oscillation, ωh = 0.01 … 0.00125: each step against a
// classic RK4 of the same ODE over the step (4000 substeps, error ~1e-15). The Newton
// iteration stops where its kept contraction rate says the iterate is converged: the step
// must still be as accurate as its own error estimate says (the Newton error ≪ the
// truncation error), strongly nonlinear (βx² = 0.72 ω², rtol 1e-10; measured: error 0.03
// of the estimate, 11 iterations per step) or mildly (βx² = 7.2e-5 ω², rtol 1e-8: 0.05 of
// the estimate), and the mild one takes one iteration per stage after the first stage's
// two (measured: 6 per step; two per stage would be 10).
double duffing_trial_steps(double beta, double rtol, double* iterations_per_step) {
  OdeSystem s;
  s.size = 2;
  s.rhs = [beta](double, const double* y, double* yd) {
    yd[0] = y[1];
    yd[1] = -kW * kW * y[0] - beta * y[0] * y[0] * y[0];
  };
  s.jacobian = [beta](double, const double* y, Eigen::MatrixXd& J) {
    J(0, 0) = 0.0;
    J(0, 1) = 1.0;
    J(1, 0) = -kW * kW - 3.0 * beta * y[0] * y[0];
    J(1, 1) = 0.0;
  };
  auto rk4 = [&](double t, Eigen::VectorXd y, double h) {
    const int n = 4000;
    const double d = h / n;
    Eigen::Vector2d k1, k2, k3, k4, z;
    for (int i = 0; i < n; ++i, t += d) {
      s.rhs(t, y.data(), k1.data());
      z = y + 0.5 * d * k1;
      s.rhs(t, z.data(), k2.data());
      z = y + 0.5 * d * k2;
      s.rhs(t, z.data(), k3.data());
      z = y + d * k3;
      s.rhs(t, z.data(), k4.data());
      y += d / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return y;
  };
  auto e = OdeEngine::make(Integrator::ArkodeDirk, spec(Integrator::ArkodeDirk, rtol, 1e-2 * rtol), s, true);
  const Eigen::VectorXd y = Eigen::Vector2d(0.6, -20.0);
  Eigen::VectorXd y1;
  long steps = 0;
  double worst = 0.0;  // the largest error / estimate
  for (double h : {0.01 / kW, 0.005 / kW, 0.0025 / kW, 0.00125 / kW}) {
    e->step(0.1, y, h, y1);
    ++steps;
    const Eigen::VectorXd& le = e->local_error();
    const double est = std::hypot(le[0], le[1] / kW);
    const Eigen::VectorXd ref = rk4(0.1, y, h);
    const double err = std::hypot(y1[0] - ref[0], (y1[1] - ref[1]) / kW);
    worst = std::max(worst, err / (est + 1e-14));
  }
  *iterations_per_step = double(e->stats().nonlin_iters) / double(steps);
  return worst;
}

TEST(OdeEngineDirk, NonlinearTrialStepsAsAccurateAsTheirEstimate) {
  double strong = 0.0, mild = 0.0;
  const double e_strong = duffing_trial_steps(2.0 * kW * kW, 1e-10, &strong);
  const double e_mild = duffing_trial_steps(2e-4 * kW * kW, 1e-8, &mild);
  std::printf("  error / estimate: %.3g (strong), %.3g (mild); Newton iterations per step: %.2f, %.2f\n",
              e_strong, e_mild, strong, mild);
  EXPECT_LT(e_strong, 1.0);
  EXPECT_LT(e_mild, 1.0);
  // SDIRK 5(4): five stages; the first takes two iterations (the rate is measured there)
  EXPECT_LE(mild, 7.0);
}

TEST(OdeEngineMake, RejectsIdaAndBadSystems) {
  EXPECT_THROW(OdeEngine::make(Integrator::Ida, SolverSpec{}, oscillator(true), false), std::invalid_argument);
  EXPECT_THROW(OdeEngine::make(Integrator::ArkodeDirk, SolverSpec{}, OdeSystem{}, false), std::invalid_argument);
  EXPECT_THROW(OdeEngine::make(Integrator::ArkodeDirk, SolverSpec{}, oscillator(false, 0.0, true), true),
               std::invalid_argument);
  auto e = OdeEngine::make(Integrator::ArkodeErk, SolverSpec{}, oscillator(false), true);
  EXPECT_STREQ(e->name(), "arkode-erk");
  EXPECT_EQ(e->size(), 2);
  EXPECT_TRUE(e->estimates_error());
  EXPECT_FALSE(OdeEngine::make(Integrator::CvodeBdf, SolverSpec{}, oscillator(false), true)->estimates_error());
}

}  // namespace
}  // namespace camdyn
