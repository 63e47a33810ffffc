// Issue 25: the tolerance is a contract on every method × engine. Each combination runs at
// rtol = tol_u = 1e-4, 1e-7 and 1e-10 (atol scaled alike) on case A, A7 (A at 7 rev/s:
// separates and lands once per revolution), B1 and B2 (0.05 s) and the two-mass valve
// train; every run finishes and its error falls as the tolerance falls (or both errors are
// at the round-off floor of the measure).
//
// The truth each error is measured against:
//   * case A with a rigid-contact method (lee, event, holonomic: it never separates at
//     1.75 rev/s): the closed-form force F = m Ẍ_C + k (δ₀ + X_C − X_C(0)), as a fraction
//     of the peak force;
//   * lee and event elsewhere: the event method on arkode-erk at rtol 1e-12 (u_c at the
//     0.1 ms rows; on the train u_tappet and u_valve);
//   * holonomic (contacts never open: on A7, B1, B2 and the train a different, bilateral
//     solution): holonomic on arkode-erk at rtol 1e-12;
//   * penalty: its own k_p-regularised solution, penalty on arkode-erk at rtol 1e-12. What
//     that solution is, is tested below (PenaltyConvergesToItsRegularisedSolution).
//
// The default run has every combination on A and A7 and a representative subset of B1, B2
// and the train (kDefault: each method and engine at least once, 38 tests); the other 26
// (penalty on the implicit engines over the elastic bar: up to 0.8 M BDF steps at 1e-10;
// lee and holonomic on cvode-bdf over the train: 10 s CPU at 1e-10) are instantiated as
// Long/ToleranceMatrix, ctest label "long" (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"
#include "../network_run_support.hpp"

namespace camdyn {
namespace {

struct Combo {
  std::string scene;  // A, A7, B1, B2, train
  ContactModel model;
  Integrator engine;
};

Scene make_scene(const std::string& name) {
  Scene s;
  if (name == "train") {
    s = camdyn_test::two_mass_train();
  } else {
    s = paper_case(name == "A7" ? "A" : name);
    if (name == "A7") s.cam.speed_rev_s = 7.0;
    s.run.t_end = name[0] == 'A' ? 0.3 : 0.05;
    s.run.output_dt = name == "A" ? 1e-3 : 1e-4;
  }
  if (name == "train") s.run.output_dt = 1e-4;
  return s;
}

// rtol = tol_u = tol; atol scaled alike (displacements are of 1 length unit on the paper's
// cases, of 1e-2 m on the train).
Scene at_tolerance(Scene s, ContactModel model, Integrator engine, double tol) {
  const bool train = s.follower.kind == FollowerKind::Network;
  s.contact.model = model;
  s.solver.integrator = engine;
  s.solver.rtol = tol;
  s.solver.atol = train ? 1e-4 * tol : tol;
  s.contact.tol_u = train ? std::max(1e-2 * tol, 1e-14) : std::max(tol, 1e-12);
  return s;
}

// The measured quantities per output row (keyed by t in ns): u_c, or u_tappet and u_valve.
using Samples = std::map<long long, std::vector<double>>;
struct Outcome {
  Summary sum;
  Samples u;
  double force_error = NAN;  // case A: max |F − F_closed| / max |F_closed|
};

Outcome run(const Scene& s) {
  const camdyn_test::NetRun r = camdyn_test::run_keeping_rows(s);
  Outcome out;
  out.sum = r.sum;
  const bool train = s.follower.kind == FollowerKind::Network;
  // single follower: u_c and the impulse ∫F dt so far (trapezoid over the rows on the
  // output grid; the same rows in every run), the latter in units of 1 ms of the preload
  // k·δ₀ (3500 on the paper's cases: of the order of the 1 ms impulses)
  double J = 0, t_prev = NAN, F_prev = 0;
  const double Fmax = s.spring.stiffness * s.spring.precompression;
  const long long grid = std::llround(s.run.output_dt * 1e9);
  for (const HistoryRow& row : r.rows) {
    const long long key = std::llround(row.t * 1e9);
    if (key % grid != 0) continue;
    if (!std::isnan(t_prev)) J += 0.5 * (row.t - t_prev) * (row.contact_force + F_prev);
    t_prev = row.t;
    F_prev = row.contact_force;
    out.u[key] = train ? std::vector<double>{r.col(row, "u_tappet"), r.col(row, "u_valve")}
                       : std::vector<double>{row.u_c, J / (1e-3 * Fmax)};
  }
  if (!train && s.cam.speed_rev_s == paper_case("A").cam.speed_rev_s && s.follower.kind == FollowerKind::Rigid) {
    Cam cam(s.cam);
    CamDrive d(s.cam);
    const double X0 = cam.evaluate(d.theta(0)).X_C;
    double err = 0, Fmax = 0;
    for (const HistoryRow& row : r.rows) {
      const CamMotion m = cam.motion(d.theta(row.t), d.omega(row.t), d.omega_dot(row.t));
      const double F = s.follower.mass * m.Xddot + s.spring.stiffness * (s.spring.precompression + m.X - X0);
      Fmax = std::max(Fmax, std::abs(F));
      err = std::max(err, std::abs(row.contact_force - F));
    }
    out.force_error = err / Fmax;
  }
  return out;
}

// Largest difference over the rows both runs have.
double distance(const Samples& a, const Samples& ref) {
  double d = 0;
  long shared = 0;
  for (const auto& [t, v] : a) {
    const auto it = ref.find(t);
    if (it == ref.end()) continue;
    ++shared;
    for (size_t i = 0; i < v.size(); ++i) d = std::max(d, std::abs(v[i] - it->second[i]));
  }
  EXPECT_GT(shared, 250);
  return d;
}

// The reference of a scene and solution family (event, holonomic, penalty) at rtol 1e-12
// on arkode-erk, computed once per process.
const Outcome& reference(const std::string& scene, ContactModel family) {
  static std::map<std::pair<std::string, int>, Outcome> cache;
  const auto key = std::make_pair(scene, int(family));
  auto it = cache.find(key);
  if (it == cache.end()) {
    Scene s = at_tolerance(make_scene(scene), family, Integrator::ArkodeErk, 1e-12);
    it = cache.emplace(key, run(s)).first;
    EXPECT_TRUE(it->second.sum.finished) << scene << " reference: " << it->second.sum.message;
  }
  return it->second;
}

ContactModel family_of(ContactModel m) { return m == ContactModel::Lee ? ContactModel::Event : m; }

// The round-off floor of each measure: differences of displacements of order 1 (paper's
// cases) or 1e-2 m (train) below which a falling error is not required; the closed-form
// force error of case A, relative to the peak force.
double floor_of(const std::string& scene, bool force) {
  if (force) return 1e-9;
  return scene == "train" ? 1e-12 : 1e-10;
}

// Combinations whose error is known not to fall; the test checks they still do not (so
// that a fix shows up here and the entry is removed).
//   A_penalty_arkode_dirk: penalty on arkode-dirk sits far above ERK at tight tolerances
//   on both stacks — the impulse error at rtol 1e-4 / 1e-7 / 1e-10 was 1.40e-3 / 3.06e-4 /
//   2.32e-5 on the single-follower stack (8adb79a), 1.01e-3 / 1.47e-3 / 7.02e-5 on the
//   mechanism with the dynamic-equilibrium start (ERK: 4.3e-3 / 1.6e-5 / 1.5e-8). Open.
const std::set<std::string> kKnownNotFalling = {"A_penalty_arkode_dirk"};

std::string name_of(const Combo& c) {
  std::string n = c.scene + "_" + to_string(c.model) + "_" + to_string(c.engine);
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}

void PrintTo(const Combo& c, std::ostream* os) { *os << name_of(c); }

class ToleranceMatrix : public ::testing::TestWithParam<Combo> {};

TEST_P(ToleranceMatrix, EveryRunFinishesAndTheErrorFalls) {
  const Combo& c = GetParam();
  const bool closed_form = c.scene == "A" && c.model != ContactModel::Penalty;
  const Outcome* ref = closed_form ? nullptr : &reference(c.scene, family_of(c.model));
  if (ref) ASSERT_TRUE(ref->sum.finished);
  std::vector<double> err;
  for (double tol : {1e-4, 1e-7, 1e-10}) {
    const Scene s = at_tolerance(make_scene(c.scene), c.model, c.engine, tol);
    const Outcome r = run(s);
    ASSERT_TRUE(r.sum.finished) << name_of(c) << " at rtol " << tol << ": " << r.sum.message;
    err.push_back(closed_form ? r.force_error : distance(r.u, ref->u));
    if (closed_form) EXPECT_LT(err.back(), std::max(100.0 * tol, 1e-9)) << tol;  // of the peak force
    std::printf("%s rtol %g: error %.3g (%ld steps, %.3g s)\n", name_of(c).c_str(), tol, err.back(), r.sum.steps,
                r.sum.cpu_seconds);
  }
  const double fl = floor_of(c.scene, closed_form);
  bool falls = true;
  for (size_t i = 1; i < err.size(); ++i) falls = falls && (err[i] < err[i - 1] || (err[i] < fl && err[i - 1] < fl));
  if (kKnownNotFalling.count(name_of(c)))
    EXPECT_FALSE(falls) << name_of(c) << " now falls: remove it from kKnownNotFalling";
  else
    EXPECT_TRUE(falls) << name_of(c) << ": " << err[0] << ", " << err[1] << ", " << err[2] << " (floor " << fl << ")";
}

// The default run: every method × engine on A and A7, and a representative subset on
// B1, B2 and the train (each method and each engine at least once); the rest is "long".
const std::set<std::string> kDefault = {
    "B1_lee_arkode_erk",       "B1_event_cvode_bdf",        "B1_penalty_arkode_erk",
    "B2_lee_cvode_bdf",        "B2_event_arkode_erk",       "B2_holonomic_cvode_bdf",
    "train_lee_arkode_erk",    "train_event_arkode_erk",    "train_event_arkode_dirk",
    "train_event_cvode_bdf",   "train_holonomic_arkode_erk", "train_penalty_cvode_bdf"};

std::vector<Combo> combos(bool heavy) {
  std::vector<Combo> v;
  const ContactModel models[] = {ContactModel::Lee, ContactModel::Event, ContactModel::Holonomic,
                                 ContactModel::Penalty};
  for (const char* sc : {"A", "A7", "B1", "B2", "train"})
    for (ContactModel m : models)
      for (Integrator e : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf, Integrator::Ida}) {
        if (e == Integrator::Ida && (m != ContactModel::Holonomic || std::string(sc) == "train")) continue;
        const Combo c{sc, m, e};
        const bool is_heavy = sc[0] != 'A' && !kDefault.count(name_of(c));
        if (is_heavy == heavy) v.push_back(c);
      }
  return v;
}

std::string param_name(const ::testing::TestParamInfo<Combo>& i) { return name_of(i.param); }

INSTANTIATE_TEST_SUITE_P(Default, ToleranceMatrix, ::testing::ValuesIn(combos(false)), param_name);
INSTANTIATE_TEST_SUITE_P(Long, ToleranceMatrix, ::testing::ValuesIn(combos(true)), param_name);

}  // namespace
}  // namespace camdyn

namespace camdyn {
namespace {

// The 1 ms contact impulses ∫F dt over [k ms, (k+1) ms] (trapezoid over the 0.1 ms rows).
std::vector<double> impulses_1ms(const RunResult& r) {
  std::vector<double> I;
  for (size_t i = 1; i < r.rows.size(); ++i) {
    const HistoryRow &a = r.rows[i - 1], &b = r.rows[i];
    const size_t k = size_t(std::floor(0.5 * (a.t + b.t) * 1e3));
    if (I.size() <= k) I.resize(k + 1, 0.0);
    I[k] += 0.5 * (b.t - a.t) * (a.contact_force + b.contact_force);
  }
  return I;
}

// Regression of the DIRK fix (issue 25): the event method on arkode-dirk reused its Newton
// matrix until γ moved by 20 % and on the stiff bar (B2 with E = 5e8, 200 elements) its
// 1 ms impulses were 2.0e-3 of the peak off after 0.05 s (against the event method on
// cvode-bdf at rtol 1e-10). Refactored at 1 % of γ: within 1e-4 (5.9e-6 measured). 12 s
// CPU: label "long".
TEST(ToleranceLong, EventOnDirkStiffBarImpulsesWithin1e4OfPeak) {
  Scene s = paper_case("B2");
  apply_overrides(s, {"follower.youngs_modulus=5e8", "follower.elements=200", "run.t_end=0.05",
                      "run.output_dt=1e-4", "contact.model=event"});
  Scene ref_scene = s;
  ref_scene.solver.integrator = Integrator::CvodeBdf;
  ref_scene.solver.rtol = 1e-10;
  const RunResult ref = simulate(ref_scene);
  ASSERT_TRUE(ref.summary.finished) << ref.summary.message;
  s.solver.integrator = Integrator::ArkodeDirk;
  const RunResult r = simulate(s);
  ASSERT_TRUE(r.summary.finished) << r.summary.message;
  const std::vector<double> I = impulses_1ms(r), J = impulses_1ms(ref);
  ASSERT_EQ(I.size(), J.size());
  double peak = 0, err = 0;
  for (size_t k = 0; k < J.size(); ++k) {
    peak = std::max(peak, std::abs(J[k]));
    err = std::max(err, std::abs(I[k] - J[k]));
  }
  std::printf("event on arkode-dirk, stiff bar, 0.05 s: 1 ms impulses %.3g of the peak off (%ld steps)\n",
              err / peak, r.summary.steps);
  EXPECT_LT(err / peak, 1e-4);
}

}  // namespace
}  // namespace camdyn

namespace camdyn {
namespace {

// What penalty converges to as rtol falls (ToleranceMatrix measures it against its own
// solution at rtol 1e-12): the k_p-regularised solution. On case A (always in contact) its
// penetration max |gap| is the law's F/k_p at the peak force (within 20 %; the displacement
// tends to the rigid one as 1/k_p), and its force comes closer to the rigid closed form as
// k_p grows, though slowly: the contact rings (0.22 of the peak force off at k_p = 1e6,
// 0.046 at 1e8, rtol 1e-10).
TEST(PenaltyLimit, RegularisedSolutionApproachesTheRigidOneAsKpGrows) {
  std::vector<double> ferr;
  for (double kp : {1e6, 1e8}) {
    Scene s = at_tolerance(make_scene("A"), ContactModel::Penalty, Integrator::ArkodeErk, 1e-10);
    s.contact.penalty_stiffness = kp;
    const Outcome r = run(s);
    ASSERT_TRUE(r.sum.finished) << r.sum.message;
    const RunResult rr = simulate(s);
    double pen = 0, Fmax = 0;
    for (const HistoryRow& row : rr.rows) {
      pen = std::max(pen, -row.gap);
      Fmax = std::max(Fmax, row.contact_force);
    }
    std::printf("penalty k_p %g: force %.3g of the peak off the rigid closed form, penetration %.4g (F_max/k_p %.4g)\n",
                kp, r.force_error, pen, Fmax / kp);
    EXPECT_NEAR(pen, Fmax / kp, 0.2 * Fmax / kp) << kp;
    ferr.push_back(r.force_error);
  }
  EXPECT_LT(ferr[1], 0.5 * ferr[0]);
}

}  // namespace
}  // namespace camdyn
