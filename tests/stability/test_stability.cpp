// Hard cases stay numerically stable (issue 7, ctest label "stability").
//
// Every scene of tests/hard/*.toml is run through the library (load_scene_file → simulate)
// and checked for the invariants that must hold on any run:
//   - the run finished;
//   - every history value is finite;
//   - the contact force is ≥ 0;
//   - Lee: penetration (−gap) ≤ tol_u + 1e-12;
//   - energy balance from the history columns, at every row:
//       |work_cam − (kinetic − kinetic(0)) − potential − dissipated| ≤ 1e-3 · E
//     with E = max(1, max over the rows so far of |work_cam|, dissipated, |kinetic −
//     kinetic(0)|) — the energy exchanged so far: the work the cam has done, or the energy
//     the preloaded spring released into motion and the impacts dissipated (a follower
//     falling onto the cam through a lash gains and loses energy before the cam does any
//     work). work_cam itself returns to ~0 after each revolution, so a pointwise
//     |work_cam| would demand absolute accuracy there.
// plus per-case checks (periodicity, per-revolution statistics of the chaotic cases,
// separation speed of the ramp, ...). See tests/hard/README.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"

namespace {

using camdyn::ContactModel;
using camdyn::HistoryRow;
using camdyn::RunResult;
using camdyn::Scene;

constexpr double kPi = 3.14159265358979323846;

std::string hard(const std::string& name) {
  return std::string(CAMDYN_SOURCE_DIR) + "/tests/hard/" + name;
}

Scene load(const std::string& name, const std::vector<std::string>& overrides = {}) {
  Scene s = camdyn::load_scene_file(hard(name));
  for (const auto& o : overrides) camdyn::apply_override(s, o);
  return s;
}

struct Checked {
  RunResult r;
  double energy_worst = 0;   ///< worst residual / (1e-3·E); ≤ 1 passes
  double energy_abs = 0;     ///< that residual
  double energy_t = 0;       ///< where
  double max_pen = 0;
};

bool all_finite(const HistoryRow& x) {
  for (double v : {x.t, x.theta, x.u_c, x.v_c, x.a_c, x.contact_force, x.gap, x.kinetic,
                   x.potential, x.work_cam, x.dissipated}) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

/// Run the scene and check the invariants of every hard run.
Checked run_checked(const Scene& scene) {
  Checked c;
  c.r = camdyn::simulate(scene);
  const auto& rows = c.r.rows;
  const auto& sum = c.r.summary;
  const std::string what = scene.title + " [" + camdyn::to_string(scene.contact.model) + ", " +
                           camdyn::to_string(scene.solver.integrator) + "]";
  EXPECT_TRUE(sum.finished) << what << ": " << sum.message;
  EXPECT_GE(rows.size(), 2u) << what;
  if (rows.empty()) return c;
  const bool lee = scene.contact.model == ContactModel::Lee;
  const bool unilateral = lee || scene.contact.model == ContactModel::Event;
  const double k0 = rows.front().kinetic;
  double wmax = 1.0;
  long bad_finite = 0, bad_force = 0, bad_pen = 0;
  for (const auto& x : rows) {
    if (!all_finite(x)) ++bad_finite;
    if (unilateral && x.contact_force < 0) ++bad_force;
    c.max_pen = std::max(c.max_pen, -x.gap);
    if (lee && -x.gap > scene.contact.tol_u + 1e-12) ++bad_pen;
    wmax = std::max({wmax, std::abs(x.work_cam), x.dissipated, std::abs(x.kinetic - k0)});
    const double res = x.work_cam - (x.kinetic - k0) - x.potential - x.dissipated;
    const double ratio = std::abs(res) / (1e-3 * wmax);
    if (!(ratio <= c.energy_worst)) {  // also catches NaN
      c.energy_worst = std::isnan(ratio) ? INFINITY : ratio;
      c.energy_abs = res;
      c.energy_t = x.t;
    }
  }
  EXPECT_EQ(bad_finite, 0) << what << ": rows with a non-finite value";
  EXPECT_EQ(bad_force, 0) << what << ": rows with a tensile contact force";
  if (lee) {
    EXPECT_EQ(bad_pen, 0) << what << ": rows with penetration > tol_u + 1e-12 (max "
                          << c.max_pen << ", tol_u " << scene.contact.tol_u << ")";
  }
  EXPECT_LE(c.energy_worst, 1.0)
      << what << ": energy balance residual W - dT - dV - D = " << c.energy_abs << " at t = "
      << c.energy_t
      << " (bound at the end 1e-3 * E = " << 1e-3 * wmax << ")";
  std::printf("[ stats    ] %s: rows %zu steps %ld rejected %ld impacts %ld separations %ld "
              "maxF %.6g maxpen %.3g energy residual %.3g at t=%.6g (%.3g of bound) cpu %.2fs\n",
              what.c_str(), rows.size(), sum.steps, sum.rejected_steps, sum.impacts,
              sum.separations, sum.max_contact_force, c.max_pen, c.energy_abs, c.energy_t,
              c.energy_worst, sum.cpu_seconds);
  return c;
}

/// Per-revolution statistics over whole revolutions of period T (output rows only).
struct RevStats {
  std::vector<double> impulse;       ///< ∫ F dt per revolution (trapezoid on the rows)
  std::vector<double> contact_frac;  ///< fraction of rows in contact
};

RevStats per_revolution(const std::vector<HistoryRow>& rows, double T,
                        const std::vector<camdyn::ContactEvent>& events = {}) {
  RevStats s;
  if (rows.size() < 2) return s;
  const int nrev = int(std::floor(rows.back().t / T + 1e-9));
  s.impulse.assign(nrev, 0.0);
  std::vector<long> in(nrev, 0), all(nrev, 0);
  for (size_t i = 1; i < rows.size(); ++i) {
    const double tm = 0.5 * (rows[i].t + rows[i - 1].t);
    const int k = int(std::floor(tm / T));
    if (k < 0 || k >= nrev) continue;
    s.impulse[k] += 0.5 * (rows[i].contact_force + rows[i - 1].contact_force) *
                    (rows[i].t - rows[i - 1].t);
    all[k] += 1;
    in[k] += rows[i].in_contact;
  }
  // Impacts resolved as instantaneous impulses (event-driven, Lee "located") are not in
  // the sampled force: add them.
  for (const camdyn::ContactEvent& e : events) {
    const int k = int(std::floor(e.t / T));
    if (k >= 0 && k < nrev) s.impulse[k] += e.impulse;
  }
  for (int k = 0; k < nrev; ++k) s.contact_frac.push_back(all[k] ? double(in[k]) / all[k] : 0);
  return s;
}

void print_revs(const char* what, const RevStats& s) {
  for (size_t k = 0; k < s.impulse.size(); ++k) {
    std::printf("[ rev      ] %s rev %zu: impulse %.6g, contact fraction %.4f\n", what, k + 1,
                s.impulse[k], s.contact_frac[k]);
  }
}

double spread(const std::vector<double>& v) {  // (max − min) / mean
  if (v.empty()) return 0;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  double mean = 0;
  for (double x : v) mean += x;
  mean /= double(v.size());
  return (*hi - *lo) / std::abs(mean);
}

// ---- chaotic elastic cases: per-revolution statistics only ----------------------------

// Total contact impulse per revolution of a follower riding the cam at constant speed,
// from the rigid follower's momentum balance: ∫F dt = ∫(m Ẍ_C + k δ₀ + k (X_C − X_C(0))) dt
// over a revolution = k δ₀ T + k ∫(X_C − X_C(0)) dt (Ẋ_C is periodic), by the trapezoid on
// the cam alone (20 000 points). An elastic follower's impulse differs from it only by the
// bar's momentum change and the spring's response to the bar's elastic motion.
double rigid_impulse_per_revolution(const camdyn::Scene& s) {
  const camdyn::Cam cam(s.cam);
  const camdyn::CamDrive drive(s.cam);
  const double T = 1.0 / s.cam.speed_rev_s, X0 = cam.evaluate(drive.theta(0.0)).X_C;
  const int N = 20000;
  double I = 0;
  for (int i = 0; i < N; ++i) {
    const double a = cam.evaluate(drive.theta(T * i / N)).X_C - X0;
    const double b = cam.evaluate(drive.theta(T * (i + 1) / N)).X_C - X0;
    I += 0.5 * (a + b) * T / N;
  }
  return s.spring.stiffness * (s.spring.precompression * T + I);
}

TEST(Stability, B2ElasticFiveRevsTwoSeconds) {
  // Output every 1e-5 s: the per-revolution impulse is a trapezoid on the rows, and the
  // bar's ringing after each impact needs that grid (1e-4 misses ~1.4 % of it).
  const Scene s = load("b2_2s.toml", {"run.output_dt=1e-5"});
  const auto c = run_checked(s);
  const auto st = per_revolution(c.r.rows, 1.0 / 5.0, c.r.summary.events);
  const auto force_only = per_revolution(c.r.rows, 1.0 / 5.0);
  print_revs("B2", st);
  ASSERT_EQ(st.impulse.size(), 10u);
  // The total impulse per revolution (force plus the impact impulses applied at the
  // instant) against the momentum balance of the follower riding the cam: 720.47 for the
  // paper cam at 5 rev/s. Beyond the first revolution the motion is chaotic, the impulse
  // the same each revolution up to the phase of the bar's elastic oscillation: each within
  // 3 %, their mean within 1 %.
  const double ref = rigid_impulse_per_revolution(s);
  std::printf("[ rev      ] momentum-balance reference %.6g; first revolution without the impact "
              "impulses %.6g (docs/method.md: ≈ 712.7)\n", ref, force_only.impulse[0]);
  EXPECT_NEAR(st.impulse[0], ref, 0.01 * ref);
  // docs/method.md's ≈ 712.7 is the first revolution's force integral without the impulses.
  EXPECT_NEAR(force_only.impulse[0], 712.7, 0.01 * 712.7);
  double mean = 0;
  for (double j : st.impulse) {
    EXPECT_NEAR(j, ref, 0.03 * ref);
    mean += j / double(st.impulse.size());
  }
  EXPECT_NEAR(mean, ref, 0.01 * ref);
  for (double f : st.contact_frac) {
    EXPECT_GT(f, 0.3);  // separations are short: mostly in contact
    EXPECT_LE(f, 1.0);
  }
  EXPECT_LT(spread(st.contact_frac), 0.25);
  EXPECT_GT(c.r.summary.impacts, 50) << "B2 separates and re-strikes again and again";
}

TEST(Stability, ElasticEightAndTenRevs) {
 for (double speed : {8.0, 10.0}) {
  SCOPED_TRACE(speed);
  const Scene s = load("elastic_8revs.toml", {"title=Hard: elastic follower at " + std::to_string(int(speed)) + " rev/s",
                                              "cam.speed_rev_s=" + std::to_string(speed),
                                              "run.t_end=" + std::to_string(2.0 / speed)});
  const auto c = run_checked(s);
  const auto st = per_revolution(c.r.rows, 1.0 / speed, c.r.summary.events);
  print_revs(speed == 8.0 ? "8 rev/s" : "10 rev/s", st);
  ASSERT_EQ(st.impulse.size(), 2u);
  // Two revolutions are not a statistically steady state at 8 rev/s (the follower is
  // thrown off in revolution 2): only bounded, positive impulses are asked for.
  for (double j : st.impulse) {
    EXPECT_GT(j, 0.0);
    EXPECT_LT(j, 5.0 * 712.7);
  }
  EXPECT_GT(c.r.summary.separations, 0) << "far above the separation speed";
 }
}

// ---- stiff and fine bars --------------------------------------------------------------

TEST(Stability, StiffBarErk) {
  run_checked(load("stiff_bar.toml", {"solver.integrator=arkode-erk", "run.t_end=2e-3"}));
}

TEST(Stability, StiffBarCvodeBdfShort) {
  // cvode-bdf on this bar is far slower than arkode-erk (see README): a short window only.
  run_checked(load("stiff_bar.toml", {"run.output_dt=1e-5", "run.t_end=1e-4"}));
}

TEST(Stability, FineBarTenThousandElements) {
  run_checked(load("fine_bar.toml"));
}

// ---- mass matrix and damping ----------------------------------------------------------

TEST(Stability, LumpedVsConsistentMass) {
  const auto lumped = run_checked(load("lumped_b1.toml"));
  const auto consistent = run_checked(load("lumped_b1.toml", {"follower.mass_matrix=consistent"}));
  ASSERT_EQ(lumped.r.rows.size(), consistent.r.rows.size());
  double du = 0, fmax = 0, df = 0;
  for (size_t i = 0; i < lumped.r.rows.size(); ++i) {
    du = std::max(du, std::abs(lumped.r.rows[i].u_c - consistent.r.rows[i].u_c));
    fmax = std::max(fmax, consistent.r.rows[i].contact_force);
  }
  const auto sl = per_revolution(lumped.r.rows, 0.1, lumped.r.summary.events),
             sc = per_revolution(consistent.r.rows, 0.1, consistent.r.summary.events);
  for (size_t k = 0; k < sl.impulse.size(); ++k) {
    df = std::max(df, std::abs(sl.impulse[k] - sc.impulse[k]) / sc.impulse[k]);
  }
  std::printf("[ compare  ] lumped vs consistent: max |du_c| %.3g, impulse per 0.1 s differs "
              "by %.3g (relative)\n", du, df);
  // Same rigid-body motion (the displacement follows the cam); the elastic ripple differs.
  EXPECT_LT(du, 1e-3);
  EXPECT_LT(df, 0.01);
}

TEST(Stability, RayleighDamping) {
  const auto c = run_checked(load("rayleigh_b2.toml"));
  double prev = 0;
  long backwards = 0;
  for (const auto& x : c.r.rows) {
    if (x.dissipated < prev - 1e-9 * std::max(1.0, std::abs(prev))) ++backwards;
    prev = x.dissipated;
  }
  EXPECT_EQ(backwards, 0) << "dissipated energy must not decrease";
  EXPECT_GT(c.r.rows.back().dissipated, 0.0);
}

// ---- rigid follower: lash, long runs, ramps, corners ----------------------------------

TEST(Stability, ValveLash) {
  for (const char* model : {"lee", "event"}) {
    SCOPED_TRACE(model);
    const auto c = run_checked(load("lash.toml", {std::string("contact.model=") + model}));
    const auto& rows = c.r.rows;
    EXPECT_NEAR(rows.front().gap, 0.01, 1e-12) << "starts 0.01 off the cam";
    EXPECT_EQ(rows.front().in_contact, 0);
    EXPECT_GE(c.r.summary.impacts, 1) << "the lash must close with an impact";
    // After the impact the follower rides the cam (1.75 rev/s < 6.4 rev/s).
    EXPECT_EQ(rows.back().in_contact, 1);
  }
}

TEST(Stability, CaseAHundredRevolutionsPeriodic) {
  for (const char* model : {"lee", "event"}) {
    SCOPED_TRACE(model);
    // Lee's work column integrates the linear force ramp of each step; with the ~3 ms
    // steps of this run its quadrature error adds up to ~2 % over 100 revolutions
    // (kinematics at the step ends are exact) — a known gap of the bookkeeping.
    const bool lee = std::string(model) == "lee";
    const auto c = run_checked(load("case_a_100rev.toml", {std::string("contact.model=") + model}));
    const auto& rows = c.r.rows;
    constexpr size_t kPerRev = 200;  // output_dt = 1/(1.75·200)
    ASSERT_EQ(rows.size(), 100 * kPerRev + 1);
    double du = 0, df = 0, fmax = 0, dth = 0;
    for (size_t i = 0; i < kPerRev; ++i) {
      const auto& a = rows[i];
      const auto& b = rows[i + 99 * kPerRev];
      dth = std::max(dth, std::abs(std::remainder(b.theta - a.theta, 2 * kPi)));
      du = std::max(du, std::abs(a.u_c - b.u_c));
      df = std::max(df, std::abs(a.contact_force - b.contact_force));
      fmax = std::max(fmax, a.contact_force);
    }
    std::printf("[ periodic ] case A %s, rev 1 vs rev 100: max |du_c| %.3g, max |dF| %.3g "
                "(max F %.6g), cam angle mismatch %.3g rad\n", model, du, df, fmax, dth);
    EXPECT_LT(dth, 1e-9) << "samples at the same cam angle";
    EXPECT_LT(du, 1e-6);
    EXPECT_LT(df, 1e-4 * fmax);
    EXPECT_EQ(c.r.summary.separations, 0) << "case A keeps contact";
  }
}

// B1 for `revs` revolutions of the undamped elastic follower. The rigid-body part is
// periodic in the cam revolution; the elastic oscillation is not (its frequencies are
// incommensurate with the cam's), so its energy is checked for boundedness: the follower's
// mechanical energy T + V at the same cam angle differs between revolutions only by the
// oscillation's phase, and that difference must not grow from the first revolutions
// (2 … w + 1) to the last w.
void check_b1_periodic_bounded(size_t revs) {
  const double T = 1.0 / 1.75;
  char t_end[64];
  std::snprintf(t_end, sizeof t_end, "run.t_end=%.17g", double(revs) * T);
  const auto c = run_checked(load("b1_long.toml", {t_end}));
  const auto& rows = c.r.rows;
  constexpr size_t kPerRev = 200;
  ASSERT_EQ(rows.size(), revs * kPerRev + 1);
  const size_t w = std::min<size_t>(9, revs / 2 - 1);
  double lift = 0, du = 0;
  for (size_t i = 0; i < kPerRev; ++i) {
    lift = std::max(lift, std::abs(rows[i].u_c - rows[0].u_c));
    du = std::max(du, std::abs(rows[i].u_c - rows[i + (revs - 1) * kPerRev].u_c));
  }
  // dE(k) = max over the revolution's angles of |E_k(θ) − E_1(θ)|, E = T + V.
  auto energy = [&](size_t i) { return rows[i].kinetic + rows[i].potential; };
  std::vector<double> dE(revs, 0.0);
  double emax = 0;
  for (size_t k = 0; k < revs; ++k) {
    for (size_t i = 0; i < kPerRev; ++i) {
      dE[k] = std::max(dE[k], std::abs(energy(i + k * kPerRev) - energy(i)));
      emax = std::max(emax, std::abs(energy(i)));
    }
  }
  const double early = *std::max_element(dE.begin() + 1, dE.begin() + 1 + w);
  const double late = *std::max_element(dE.end() - w, dE.end());
  long in = 0;
  for (const auto& x : rows) in += x.in_contact;
  std::printf("[ periodic ] B1 rev 1 vs rev %zu: max |du_c| %.3g (lift %.4g); energy T+V at equal "
              "angles differs from rev 1 by at most %.4g (revs 2-%zu) and %.4g (last %zu), "
              "of max |T+V| %.6g; in contact %.4f of rows\n",
              revs, du, lift, early, w + 1, late, w, emax, double(in) / rows.size());
  EXPECT_LT(du, 1e-3 * lift) << "displacement periodic (matches case A)";
  EXPECT_LT(late, 2.0 * early + 1e-3 * emax) << "elastic oscillation energy grows";
  EXPECT_LT(late, 1e-2 * emax) << "elastic oscillation energy bounded";
  EXPECT_GT(double(in) / rows.size(), 0.99) << "B1 keeps contact";
}

// 100 revolutions (57 s simulated): `scripts/test.sh --long` (ctest label "long").
TEST(StabilityLong, B1HundredRevolutionsPeriodicBounded) { check_b1_periodic_bounded(100); }

// The same property over 8 revolutions (4.6 s simulated) in the default suite.
TEST(Stability, B1EightRevolutionsPeriodicBounded) { check_b1_periodic_bounded(8); }

TEST(Stability, SpeedRampSeparatesPastSeparationSpeed) {
  for (const char* model : {"lee", "event"}) {
    SCOPED_TRACE(model);
    const auto c = run_checked(load("speed_ramp.toml", {std::string("contact.model=") + model}));
    double t_sep = -1;
    for (const auto& e : c.r.summary.events) {
      if (e.type == camdyn::EventKind::Separation) {
        t_sep = e.t;
        break;
      }
    }
    const double speed = 5.0 * t_sep;  // 0 → 10 rev/s over 2 s
    std::printf("[ ramp     ] %s: first separation at t = %.6g s, %.4g rev/s; %ld separations\n",
                model, t_sep, speed, c.r.summary.separations);
    ASSERT_GT(t_sep, 0) << "the rigid follower must separate";
    EXPECT_GT(speed, 6.0);
    EXPECT_LT(speed, 8.0);
  }
}

TEST(Stability, CornerCam) {
  for (const char* model : {"lee", "event", "penalty"}) {
    SCOPED_TRACE(model);
    const auto c = run_checked(load("corner_cam.toml", {std::string("contact.model=") + model}));
    EXPECT_EQ(c.r.summary.finished, true);
  }
}

// ---- stiff penalty, extreme tolerances ------------------------------------------------

TEST(Stability, PenaltyStiffArkodeErk) { run_checked(load("penalty_erk.toml")); }
TEST(Stability, PenaltyStiffCvodeBdf) { run_checked(load("penalty_bdf.toml")); }
TEST(Stability, PenaltyStiffArkodeDirk) { run_checked(load("penalty_dirk.toml")); }

TEST(Stability, TightAndLooseTolerances) {
  const auto tight = run_checked(load("tight_tol.toml"));
  const auto loose = run_checked(load("loose_tol.toml"));
  ASSERT_EQ(tight.r.rows.size(), loose.r.rows.size());
  double du = 0, df = 0, fmax = 0;
  for (size_t i = 0; i < tight.r.rows.size(); ++i) {
    du = std::max(du, std::abs(tight.r.rows[i].u_c - loose.r.rows[i].u_c));
    df = std::max(df, std::abs(tight.r.rows[i].contact_force - loose.r.rows[i].contact_force));
    fmax = std::max(fmax, tight.r.rows[i].contact_force);
  }
  std::printf("[ compare  ] tolerances 1e-12 vs 1e-3: max |du_c| %.3g, max |dF| %.3g of %.6g\n",
              du, df, fmax);
  EXPECT_LT(du, 1e-3);
  EXPECT_LT(df, 0.05 * fmax);
}

}  // namespace

// ---- valve trains (issue 16): several contacts over many revolutions, at over-speed ------
// Every contact force ≥ 0 (Lee, event-driven), every gap ≥ −tol_u (Lee), the energy balance
// (as run_checked) and as many impacts as separations per contact (± 1: a contact open at
// the start or at the end).
namespace {
void check_network(const std::string& example, double speed, double revolutions, ContactModel model,
                   camdyn::Integrator integ) {
  Scene s = camdyn::load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/" + example);
  s.cam.speed_rev_s = speed;
  s.run.t_end = revolutions / speed;
  s.run.output_dt = 1e-5;
  s.contact.model = model;
  s.solver.integrator = integ;
  const Checked c = run_checked(s);
  const camdyn::Simulator sim(s);
  const std::vector<std::string>& cols = sim.extra_columns();
  double worst_F = 0, worst_gap = 0;
  for (const auto& row : c.r.rows)
    for (size_t i = 0; i < cols.size(); ++i) {
      if (cols[i].rfind("F_", 0) == 0) worst_F = std::min(worst_F, row.extra[i]);
      if (cols[i].rfind("gap_", 0) == 0) worst_gap = std::min(worst_gap, row.extra[i]);
    }
  EXPECT_GE(worst_F, 0.0) << example;
  if (model == ContactModel::Lee) EXPECT_GE(worst_gap, -s.contact.tol_u - 1e-12) << example;
  for (const auto& ct : s.network.contacts) {
    long imp = 0, sep = 0;
    for (const auto& e : c.r.summary.events)
      if (e.contact == ct.name) (e.type == camdyn::EventKind::Impact ? imp : sep) += 1;
    EXPECT_LE(std::abs(imp - sep), 1) << example << " contact " << ct.name << ": " << imp << " impacts, " << sep
                                      << " separations";
  }
  std::printf("[ network  ] %s at %g rev/s, %g revolutions, %s/%s: %ld steps, %ld impacts, energy residual "
              "%.3g of 1e-3·E, min F %.3g N, min gap %.3g m, cpu %.3g s\n",
              example.c_str(), speed, revolutions, camdyn::to_string(model), camdyn::to_string(integ),
              c.r.summary.steps, c.r.summary.impacts, c.energy_worst, worst_F, worst_gap, c.r.summary.cpu_seconds);
}
}  // namespace

TEST(Stability, ValveTrainOhcOverspeedTwentyRevolutionsLee) {
  check_network("ohc_bucket_tappet.toml", 75.0, 20.0, ContactModel::Lee, camdyn::Integrator::ArkodeErk);
}
TEST(Stability, ValveTrainOhcOverspeedEventCvode) {
  check_network("ohc_bucket_tappet.toml", 75.0, 5.0, ContactModel::Event, camdyn::Integrator::CvodeBdf);
}
TEST(Stability, ValveTrainOhvFiveRevolutionsLeeDirk) {
  check_network("ohv_pushrod_train.toml", 45.0, 5.0, ContactModel::Lee, camdyn::Integrator::ArkodeDirk);
}
TEST(Stability, ValveTrainOhvHighSpeedLeeErk) {
  check_network("ohv_pushrod_train.toml", 60.0, 10.0, ContactModel::Lee, camdyn::Integrator::ArkodeErk);
}
