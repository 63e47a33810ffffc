// OdeEngine::dense against the engine's own step ends and against itself with
// keep_dense_rhs (src/engine/ode_engine.hpp), on each engine (arkode-erk, arkode-dirk,
// cvode-bdf), native stepping of a forced nonlinear oscillator:
//   * at the time advance() returned, dense() is advance()'s state bit for bit (the contact
//     trace takes a step's end sample from the method's own step end on this ground);
//   * with keep_dense_rhs on, dense() inside every step is bit for bit the one of an
//     identical engine without it (ARKODE unchanged: the independent reference), with fewer
//     right-hand-side evaluations where ARKODE's interpolant evaluates f (arkode-erk: one
//     per step instead of one per call), and the interpolant is the solution to its
//     interpolation error (against an RK4 reference at a small step, written here).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/ode_engine.hpp"

namespace camdyn {
namespace {

// y = [x, v]: x'' = −x − x³ − 0.1 x' + cos 2t (Duffing), x(0) = 1, v(0) = 0.
void duffing(double t, const double* y, double* yd) {
  yd[0] = y[1];
  yd[1] = -y[0] - y[0] * y[0] * y[0] - 0.1 * y[1] + std::cos(2.0 * t);
}

OdeSystem system() {
  OdeSystem s;
  s.size = 2;
  s.rhs = duffing;
  return s;
}

SolverSpec spec(Integrator integ) {
  SolverSpec s;
  s.integrator = integ;
  s.rtol = 1e-8;
  s.atol = 1e-10;
  return s;
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * std::size_t(a.size())) == 0;
}

// The solution at t by classic RK4 from 0 with steps of at most 1e-4 (error ≈ 1e-15).
Eigen::VectorXd rk4_reference(double t) {
  Eigen::VectorXd y(2);
  y << 1.0, 0.0;
  const int n = int(std::ceil(t / 1e-4));
  const double h = t / n;
  double k1[2], k2[2], k3[2], k4[2], yt[2];
  double s = 0.0;
  for (int i = 0; i < n; ++i, s += h) {
    duffing(s, y.data(), k1);
    for (int j = 0; j < 2; ++j) yt[j] = y[j] + 0.5 * h * k1[j];
    duffing(s + 0.5 * h, yt, k2);
    for (int j = 0; j < 2; ++j) yt[j] = y[j] + 0.5 * h * k2[j];
    duffing(s + 0.5 * h, yt, k3);
    for (int j = 0; j < 2; ++j) yt[j] = y[j] + h * k3[j];
    duffing(s + h, yt, k4);
    for (int j = 0; j < 2; ++j) y[j] += h / 6.0 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
  }
  return y;
}

class DenseReuse : public testing::TestWithParam<Integrator> {};

TEST_P(DenseReuse, StepEndIsAdvanceStateAndKeptRhsChangesNoBit) {
  auto plain = OdeEngine::make(GetParam(), spec(GetParam()), system(), false);
  auto kept = OdeEngine::make(GetParam(), spec(GetParam()), system(), false);
  Eigen::VectorXd y0(2), ya(2), yb(2), da, db;
  y0 << 1.0, 0.0;
  plain->reinit(0.0, y0);
  kept->reinit(0.0, y0);
  const double t_end = 2.0;
  double t = 0.0;
  int steps = 0;
  long plain_dense_evals = 0, kept_dense_evals = 0;
  double worst = 0.0;
  while (t < t_end) {
    const double t0 = t;
    const double ta = plain->advance(t_end, ya), tb = kept->advance(t_end, yb);
    ASSERT_EQ(ta, tb);
    ASSERT_TRUE(same_bits(ya, yb));
    t = ta;
    ++steps;
    // the step end: advance()'s state
    plain->dense(t, da);
    ASSERT_TRUE(same_bits(da, ya)) << "step " << steps << " at t = " << t;
    // inside the step: the same bits with the evaluations kept
    const long pa = plain->stats().rhs_evals, ka = kept->stats().rhs_evals;
    kept->keep_dense_rhs(true);
    for (double x : {0.0, 0.1, 0.5, 0.7887, 1.0}) {
      const double tau = x >= 1.0 ? t : t0 + x * (t - t0);
      plain->dense(tau, da);
      kept->dense(tau, db);
      ASSERT_TRUE(same_bits(da, db)) << "step " << steps << " at x = " << x;
      if (steps % 10 == 0) worst = std::max(worst, (da - rk4_reference(tau)).cwiseAbs().maxCoeff());
    }
    kept->keep_dense_rhs(false);
    plain_dense_evals += plain->stats().rhs_evals - pa;
    kept_dense_evals += kept->stats().rhs_evals - ka;
  }
  EXPECT_GT(steps, 20);
  EXPECT_LE(kept_dense_evals, plain_dense_evals);
  if (GetParam() == Integrator::ArkodeErk) {
    // ARKODE 6.4's degree-4 Hermite interpolant: one f per GetDky call, kept once per step
    EXPECT_GE(plain_dense_evals, 5L * steps);
    EXPECT_LE(kept_dense_evals, long(steps));
  }
  // the interpolant is the solution (rtol 1e-8: measured 1e-8–1e-7 at these points)
  EXPECT_LT(worst, 2e-6);
}

// With a projection after every step (the event method's; ARKODE: the stepper reset on the
// projected state), dense() at the step end is still advance()'s (projected) state.
TEST_P(DenseReuse, StepEndIsAdvanceStateWithProjection) {
  auto e = OdeEngine::make(GetParam(), spec(GetParam()), system(), false);
  int moved = 0;
  e->set_projection([&moved](double, const double* y, double* corr) {
    corr[0] = 1e-9 * y[1];  // a small deterministic correction, never zero while v ≠ 0
    corr[1] = 0.0;
    ++moved;
  });
  Eigen::VectorXd y(2), d;
  y << 1.0, 0.0;
  e->reinit(0.0, y);
  double t = 0.0;
  int steps = 0;
  while (t < 1.0) {
    t = e->advance(1.0, y);
    ++steps;
    e->dense(t, d);
    ASSERT_TRUE(same_bits(d, y)) << "step " << steps << " at t = " << t;
  }
  EXPECT_GT(steps, 10);
  EXPECT_GT(moved, 10);
}

// The step's start: the interpolant of step n + 1 at t_n is the state y_n the step started
// from, to round-off (Hermite: its end values; CVODE: the BDF correction polynomial that
// updates the Nordsieck history vanishes at t_{n−1}, so the new interpolant passes through the
// old step end), with and without a projection after every step. The contact trace takes a
// continued step's start sample from the previous step's end on this ground
// (ContactRun::trace_step's y_start). Measured over the steps to t = 2, relative to |y|:
// at most 9.2e-17 (arkode-erk), 1.4e-16 (arkode-dirk), 2.2e-16 (cvode-bdf).
TEST_P(DenseReuse, StepStartIsThePreviousStepEnd) {
  for (bool projected : {false, true}) {
    auto e = OdeEngine::make(GetParam(), spec(GetParam()), system(), false);
    if (projected)
      e->set_projection([](double, const double* y, double* corr) {
        corr[0] = 1e-9 * y[1];
        corr[1] = 0.0;
      });
    Eigen::VectorXd y(2), y_prev, d;
    y << 1.0, 0.0;
    e->reinit(0.0, y);
    double t = 0.0, worst = 0.0;
    int steps = 0;
    while (t < 2.0) {
      const double t0 = t;
      y_prev = y;
      t = e->advance(2.0, y);
      ++steps;
      e->dense(t0, d);
      worst = std::max(worst, (d - y_prev).cwiseAbs().maxCoeff() / std::max(1.0, y_prev.cwiseAbs().maxCoeff()));
    }
    EXPECT_GT(steps, 20);
    // round-off: a few ulps of the state (a step's own change is ~1e-2 of it)
    EXPECT_LE(worst, 1e-14) << (projected ? "with" : "without") << " projection";
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, DenseReuse,
                         testing::Values(Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf),
                         [](const testing::TestParamInfo<Integrator>& i) {
                           return std::string(i.param == Integrator::ArkodeErk    ? "erk"
                                              : i.param == Integrator::ArkodeDirk ? "dirk"
                                                                                  : "cvode");
                         });

}  // namespace
}  // namespace camdyn
