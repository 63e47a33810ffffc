// Lee's method against independent truth.
//
//   Case A (rigid follower, always in contact at 1.75 rev/s): while in contact the exact
//   solution is known in closed form from the cam kinematics alone:
//     u_c(t) = X_C(θ(t)),   F(t) = m Ẍ_C + k δ₀ + k (X_C − X_C(0)).
//   B1: the bar's contact force carries its first axial mode (node 0 held by the cam:
//   fixed–spring bar), and the displacement follows case A.
//   B2: repeated separation and re-contact, revolution after revolution.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>

#include "camdyn/cam.hpp"
#include "mechanism/follower_matrices.hpp"
#include "camdyn/simulator.hpp"

namespace camdyn {
namespace {

struct Exact {
  double u, F;
};
Exact case_a_exact(const Scene& s, double t) {
  static thread_local std::unique_ptr<Cam> cam;
  static thread_local CamSpec spec;
  if (!cam || !(spec == s.cam)) {
    cam = std::make_unique<Cam>(s.cam);
    spec = s.cam;
  }
  CamDrive drive(s.cam);
  const CamMotion m = cam->motion(drive.theta(t), drive.omega(t), drive.omega_dot(t));
  const double X0 = cam->evaluate(drive.theta(0)).X_C;
  const double k = s.spring.stiffness;
  return {m.X, s.follower.mass * m.Xddot + k * s.spring.precompression + k * (m.X - X0)};
}

struct CaseAErrors {
  double u = 0, F = 0, Fpeak = 0;
};
CaseAErrors case_a_errors(const RunResult& r, const Scene& s) {
  CaseAErrors e;
  for (const HistoryRow& row : r.rows) {
    const Exact ex = case_a_exact(s, row.t);
    e.u = std::max(e.u, std::abs(row.u_c - ex.u));
    e.F = std::max(e.F, std::abs(row.contact_force - ex.F));
    e.Fpeak = std::max(e.Fpeak, std::abs(ex.F));
  }
  return e;
}

void check_invariants(const RunResult& r, const Scene& s, const char* what) {
  ASSERT_TRUE(r.summary.finished) << what << ": " << r.summary.message;
  double tol_u = s.contact.tol_u > 0 ? s.contact.tol_u
                                     : (s.follower.kind == FollowerKind::Rigid ? 1e-8 : 1e-7);
  for (const HistoryRow& row : r.rows) {
    ASSERT_TRUE(std::isfinite(row.u_c) && std::isfinite(row.v_c) && std::isfinite(row.a_c) &&
                std::isfinite(row.contact_force))
        << what << " t = " << row.t;
    ASSERT_GE(row.contact_force, 0.0) << what << " t = " << row.t;
    ASSERT_GE(row.gap, -(tol_u + 1e-12)) << what << " penetration at t = " << row.t;
  }
}

TEST(LeeCaseA, LongStepsPeakForceAndWorkAgainstClosedForm) {
  // Coarse output grid (output_dt = 0.02): Lee's steps grow to several ms and straddle the
  // sharp force peak near θ = 120°. The reported max contact force (step ends plus the
  // work quadrature's interior samples) and the work the cam did over one revolution must
  // still match the closed form: max F on a 2e5-point grid, and W = ∫ F Ẋ_C dt = 0 over a
  // revolution of a periodic, conservative motion, with ∫ over the lift
  // half = ΔT + ΔV between θ = 0 and the nose.
  Scene s = paper_case("A");
  const double T = 1.0 / s.cam.speed_rev_s;
  s.run.t_end = T;
  s.run.output_dt = T / 50.0;
  const RunResult r = simulate(s);
  check_invariants(r, s, "case A, coarse grid");
  double Fmax = 0;
  for (int i = 0; i <= 200000; ++i) Fmax = std::max(Fmax, case_a_exact(s, T * i / 200000.0).F);
  const double Fmid = case_a_exact(s, 0.5 * T).F;
  // Work over the lift half: W(T/2) = ΔT + ΔV with u = X_C, v = Ẋ_C exact.
  CamDrive drive(s.cam);
  Cam cam(s.cam);
  auto energy = [&](double t) {
    const CamMotion m = cam.motion(drive.theta(t), drive.omega(t), 0.0);
    const double X0 = cam.evaluate(drive.theta(0)).X_C, k = s.spring.stiffness;
    const double d = m.X - X0;
    return 0.5 * s.follower.mass * m.Xdot * m.Xdot + k * s.spring.precompression * d + 0.5 * k * d * d;
  };
  const HistoryRow* half = nullptr;
  for (const auto& row : r.rows)
    if (std::abs(row.t - 0.5 * T) < 1e-12) half = &row;
  ASSERT_NE(half, nullptr);
  const double W_exact = energy(0.5 * T) - energy(0.0);
  std::printf("coarse case A: %ld steps; max F %.10g (exact %.10g, at the nose %.6g); W(T/2) "
              "%.10g (exact %.10g), W(T) %.3g\n", r.summary.steps, r.summary.max_contact_force,
              Fmax, Fmid, half->work_cam, W_exact, r.rows.back().work_cam);
  EXPECT_LT(r.summary.steps, 1000) << "the point is long steps";
  EXPECT_NEAR(r.summary.max_contact_force, Fmax, 1e-3 * Fmax);
  EXPECT_NEAR(half->work_cam, W_exact, 1e-6 * std::abs(W_exact));
  EXPECT_NEAR(r.rows.back().work_cam, 0.0, 1e-6 * std::abs(W_exact));
}

TEST(LeeSteps, NoSliverStepsBeforeOutputTimes) {
  // Steps land on output times. With max_step 1e-4 and output_dt = 3.00003e-4, a step
  // of 1e-4 would leave a 3e-9 s sliver before each output time; a sliver step cannot
  // correct even round-off in the gap without a force ∝ gap/Δt² (on B1 this collapsed
  // Δt to underflow after 44 s). Remainders under two steps are split in two instead.
  Scene s = paper_case("A");
  s.run.t_end = 0.05;
  s.run.output_dt = 3.00003e-4;
  s.solver.max_step = 1e-4;
  struct Steps : Observer {
    double hmin = INFINITY, hmax = 0;
    void on_step(const StepInfo& st) override {
      hmin = std::min(hmin, st.h);
      hmax = std::max(hmax, st.h);
    }
  } steps;
  Simulator sim(s);
  const Summary sum = sim.run(&steps);
  ASSERT_TRUE(sum.finished) << sum.message;
  std::printf("steps %ld, h in [%.6g, %.6g]\n", sum.steps, steps.hmin, steps.hmax);
  ASSERT_GT(steps.hmax, 0.0) << "on_step was not called";
  EXPECT_GE(steps.hmin, 0.25 * steps.hmax);
}

TEST(LeeCaseA, MatchesClosedFormWithDefaultTolerances) {
  Scene s = paper_case("A");
  const RunResult r = simulate(s);
  check_invariants(r, s, "case A");
  const CaseAErrors e = case_a_errors(r, s);
  std::printf("case A: max |u err| %.3e, max |F err| %.3e (peak %.4g, rel %.3e); %s\n", e.u, e.F,
              e.Fpeak, e.F / e.Fpeak, r.summary.BriefReport().c_str());
  std::printf("%s", r.summary.FullReport().c_str());
  EXPECT_LE(e.u, 1e-7);
  EXPECT_LE(e.F / e.Fpeak, 1e-5);
  EXPECT_EQ(r.summary.separations, 0);
  EXPECT_EQ(r.summary.impacts, 0);
  // Iterations: the constants b, b̂, b̃ are Newton steps for a rigid follower.
  EXPECT_LT(r.summary.level_u.mean(), 2.5);
  EXPECT_LT(r.summary.level_v.mean(), 2.5);
  EXPECT_LT(r.summary.level_a.mean(), 2.5);
  EXPECT_LE(r.summary.level_a.max, 3);
}

TEST(LeeCaseA, ErrorsFallAsTolerancesTighten) {
  double prev_u = INFINITY, prev_F = INFINITY;
  for (double tol : {1e-5, 1e-7, 1e-9}) {
    Scene s = paper_case("A");
    s.solver.rtol = tol;
    s.contact.tol_u = tol * 0.1;
    s.run.t_end = 0.6;
    const RunResult r = simulate(s);
    check_invariants(r, s, "case A sweep");
    const CaseAErrors e = case_a_errors(r, s);
    std::printf("rtol %.0e: u err %.3e F err %.3e steps %ld\n", tol, e.u, e.F / e.Fpeak,
                r.summary.steps);
    // Every level makes one Newton correction, exact for a rigid linear follower: the
    // contact-face error is bounded by tol_u and reaches round-off; it never grows.
    EXPECT_LE(e.u, 0.1 * tol);
    EXPECT_LE(e.u, prev_u + 1e-13);
    EXPECT_LE(e.F, prev_F + 1e-9);
    prev_u = e.u;
    prev_F = e.F;
  }
}

// Total variation of the contact force over each revolution vs the exact one, and
// periodicity revolution to revolution: Lee's force has no spurious oscillation.
TEST(LeeCaseA, NoSpuriousOscillationAndPeriodicForce) {
  Scene s = paper_case("A");
  s.run.t_end = 3.0 / 1.75;  // three revolutions
  s.run.output_dt = 1e-4;
  const RunResult r = simulate(s);
  check_invariants(r, s, "case A TV");
  const double Trev = 1.0 / 1.75;
  std::vector<double> tv(3, 0.0), tv_exact(3, 0.0);
  for (size_t i = 1; i < r.rows.size(); ++i) {
    const int rev = std::min(2, int(r.rows[i].t / Trev));
    tv[rev] += std::abs(r.rows[i].contact_force - r.rows[i - 1].contact_force);
    tv_exact[rev] += std::abs(case_a_exact(s, r.rows[i].t).F - case_a_exact(s, r.rows[i - 1].t).F);
  }
  for (int k = 0; k < 3; ++k) {
    std::printf("rev %d: TV %.10g exact %.10g rel %.2e\n", k, tv[k], tv_exact[k],
                std::abs(tv[k] / tv_exact[k] - 1));
    EXPECT_LT(std::abs(tv[k] / tv_exact[k] - 1), 1e-4);
  }
  // Periodicity: F(t) vs F(t + T_rev) at output rows one revolution apart.
  const size_t lag = size_t(std::llround(Trev / 1e-4));
  double dmax = 0, peak = 0;
  for (size_t i = 0; i + lag < r.rows.size(); ++i) {
    if (std::abs(r.rows[i + lag].t - r.rows[i].t - Trev) > 1e-4) continue;
    peak = std::max(peak, r.rows[i].contact_force);
  }
  // rows are on a 1e-4 grid; T_rev is not a multiple of it: compare with the closed form
  // shifted by one revolution instead (exact periodicity of the reference).
  for (const HistoryRow& row : r.rows) {
    if (row.t + Trev > s.run.t_end) break;
    dmax = std::max(dmax, std::abs(row.contact_force - case_a_exact(s, row.t + Trev).F));
  }
  EXPECT_LT(dmax / peak, 1e-5);
}

TEST(LeeCaseA, EnginesAgree) {
  for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    Scene s = paper_case("A");
    s.solver.integrator = integ;
    s.run.t_end = 0.6;
    const RunResult r = simulate(s);
    check_invariants(r, s, to_string(integ));
    const CaseAErrors e = case_a_errors(r, s);
    std::printf("%s: u err %.3e, F rel err %.3e, steps %ld, rhs %ld, cpu %.3f s\n", to_string(integ), e.u,
                e.F / e.Fpeak, r.summary.steps, r.summary.rhs_evals, r.summary.cpu_seconds);
    EXPECT_LE(e.u, 1e-6) << to_string(integ);
    EXPECT_LE(e.F / e.Fpeak, 1e-4) << to_string(integ);
  }
}

TEST(LeeRigid, PreloadedFollowerOnStillCamStaysAtRest) {
  // Cam at rest: the exact solution is the initial equilibrium forever.
  Scene s = paper_case("A");
  s.cam.speed_rev_s = 0.0;
  s.run.output_dt = 0.0;
  s.solver.max_step = 1e-3;
  s.run.t_end = 100.0;  // 1e5 steps
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_GE(r.summary.steps, 100000);
  const double u0 = r.rows.front().u_c;
  double drift = 0, dF = 0;
  for (const HistoryRow& row : r.rows) {
    drift = std::max(drift, std::abs(row.u_c - u0));
    dF = std::max(dF, std::abs(row.contact_force - 3500.0));
  }
  EXPECT_LT(drift, 1e-12);
  EXPECT_LT(dF, 1e-9);
}

TEST(LeeBar, PreloadedBarOnStillCamStaysAtRest) {
  // The elastic forces K q of the preloaded bar cancel only to round-off (EA/h · |q| ·
  // ε ≈ 5e-8), so "at rest" means: the contact face stays within the contact tolerance
  // and the energy stays at round-off level — no growth over 10⁵ steps.
  Scene s = paper_case("B1");
  s.follower.mass_matrix = MassMatrixKind::Lumped;
  s.cam.speed_rev_s = 0.0;
  s.run.output_dt = 1e-3;
  s.solver.max_step = 1e-5;
  s.run.t_end = 1.0;  // 1e5 steps
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  EXPECT_GE(r.summary.steps, 100000);
  const double u0 = r.rows.front().u_c;
  double drift = 0, kin = 0;
  for (const HistoryRow& row : r.rows) {
    drift = std::max(drift, std::abs(row.u_c - u0));
    kin = std::max(kin, row.kinetic);
  }
  std::printf("bar at rest: max |u_c drift| %.3e, max kinetic energy %.3e\n", drift, kin);
  EXPECT_LE(drift, 1e-7);  // tol_u of the elastic case
  EXPECT_LT(kin, 1e-12);
}

// First axial frequency of the bar with node 0 held (fixed–spring bar), from the FE
// matrices with row/column 0 removed.
double held_bar_first_frequency_hz(const Scene& s) {
  const FollowerMatrices fm = follower_matrices(s);
  const int n = fm.n;
  const Eigen::MatrixXd K(fm.K), M(fm.M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K.bottomRightCorner(n - 1, n - 1),
                                                               M.bottomRightCorner(n - 1, n - 1));
  return std::sqrt(es.eigenvalues()[0]) / (2 * M_PI);
}

TEST(LeeCaseB1, FollowsCaseAAndCarriesFirstAxialMode) {
  Scene s = paper_case("B1");
  s.run.t_end = 0.5;
  const RunResult r = simulate(s);
  check_invariants(r, s, "B1");
  std::printf("%s", r.summary.FullReport().c_str());
  Scene a = paper_case("A");
  double du = 0;
  for (const HistoryRow& row : r.rows) du = std::max(du, std::abs(row.u_c - case_a_exact(a, row.t).u));
  std::printf("B1 vs case A: max |du| %.3e\n", du);
  EXPECT_LT(du, 1e-3);
  // Spectrum of the force minus the rigid (case A) force: its peak is the bar's mode.
  const double f1 = held_bar_first_frequency_hz(s);
  double best_f = 0, best_p = 0;
  for (double f = 50; f <= 2000; f += 1.0) {
    double re = 0, im = 0;
    for (const HistoryRow& row : r.rows) {
      const double x = row.contact_force - case_a_exact(a, row.t).F;
      re += x * std::cos(2 * M_PI * f * row.t);
      im += x * std::sin(2 * M_PI * f * row.t);
    }
    const double p = re * re + im * im;
    if (p > best_p) {
      best_p = p;
      best_f = f;
    }
  }
  std::printf("B1 force spectrum peak %.1f Hz, first axial mode %.1f Hz\n", best_f, f1);
  EXPECT_NEAR(best_f, f1, 0.02 * f1);
  EXPECT_GT(r.summary.max_contact_force, 0.0);
}

TEST(LeeCaseB1, EnginesAgree) {
  std::vector<std::vector<HistoryRow>> runs;
  for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    Scene s = paper_case("B1");
    s.solver.integrator = integ;
    s.run.t_end = 0.01;  // (dirk and cvode restart-per-step are slow on the bar)
    const RunResult r = simulate(s);
    check_invariants(r, s, to_string(integ));
    std::printf("B1 %s: steps %ld cpu %.3f s\n", to_string(integ), r.summary.steps, r.summary.cpu_seconds);
    runs.push_back(r.rows);
  }
  for (size_t k = 1; k < runs.size(); ++k) {
    ASSERT_EQ(runs[k].size(), runs[0].size());
    double du = 0;
    for (size_t i = 0; i < runs[0].size(); ++i) du = std::max(du, std::abs(runs[k][i].u_c - runs[0][i].u_c));
    std::printf("engine %zu vs erk: max |du| %.3e\n", k, du);
    EXPECT_LT(du, 1e-5);
  }
}

TEST(LeeCaseB2, SeparatesAndRestrikesEveryRevolution) {
  {
    Scene s = paper_case("B2");
    s.run.t_end = 0.6;     // three revolutions of 0.2 s
    s.run.output_dt = 0.0;  // every accepted step: impacts last microseconds
    const RunResult r = simulate(s);
    check_invariants(r, s, "B2");
    std::printf("%s", r.summary.FullReport().c_str());
    EXPECT_GT(r.summary.separations, 3);
    EXPECT_GT(r.summary.impacts, 3);
    // Contact impulse per revolution: the pattern repeats each 0.2 s (robust statistic of
    // a chaotic response; docs/method.md: ≈ 712.7 per revolution).
    std::vector<double> imp(3, 0.0);
    for (size_t i = 1; i < r.rows.size(); ++i) {
      const int rev = std::min(2, int(r.rows[i].t / 0.2));
      imp[rev] += 0.5 * (r.rows[i].contact_force + r.rows[i - 1].contact_force) *
                  (r.rows[i].t - r.rows[i - 1].t);
    }
    std::printf("B2 impulse per revolution: %.2f %.2f %.2f\n", imp[0], imp[1], imp[2]);
    for (double I : imp) EXPECT_NEAR(I, 712.7, 0.02 * 712.7);
  }
}

}  // namespace
}  // namespace camdyn
