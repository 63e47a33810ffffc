// camdyn — `camdyn bench` / run_bench(): the quick work–precision sweep on case A writes a
// well-formed work_precision.csv whose Lee rows are accurate and improve with tolerance.
// (Timings are not checked: the machine is shared.)
#include <gtest/gtest.h>
#include "../test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "study/bench.hpp"
#include "study/bench_compare.hpp"
#include "camdyn/cam.hpp"
#include "camdyn/simulator.hpp"
#include "camdyn/scene.hpp"

namespace fs = std::filesystem;

namespace {

using camdyn_test::slurp;
using camdyn_test::split;

double num(const std::string& s) {
  if (s.empty()) return std::nan("");
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  return (end && *end == '\0') ? x : std::nan("");
}

fs::path temp_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() /
               ("camdyn_test_bench_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// Quick-mode options for the bench_case() `name`, writing to `dir`.
camdyn::BenchOptions quick_options(const std::string& name, const fs::path& dir, int repeats) {
  camdyn::BenchOptions o;
  o.scenes = {camdyn::bench_case(name)};
  o.labels = {name};
  o.quick = true;
  o.repeats = repeats;
  o.repeat_cap_seconds = 1.0;  // the stiffest penalty runs are timed once
  o.out_dir = dir.string();
  return o;
}

}  // namespace

TEST(Bench, QuickCaseAWritesWellFormedCsv) {
  const fs::path dir = temp_dir("quick");
  camdyn::BenchOptions o = quick_options("A", dir, 3);
  camdyn::BenchResult res = camdyn::run_bench(o);

  std::ifstream f(dir / "work_precision.csv");
  ASSERT_TRUE(f.good());
  std::string line;
  ASSERT_TRUE(std::getline(f, line));
  const std::vector<std::string> header = split(line, ',');
  ASSERT_EQ(header, camdyn::bench_columns());
  ASSERT_EQ(header.size(), 25u);
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;

  std::vector<std::vector<std::string>> rows;
  while (std::getline(f, line)) {
    if (line.empty()) continue;
    auto r = split(line, ',');
    ASSERT_EQ(r.size(), header.size()) << "row: " << line;
    rows.push_back(r);
  }
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.size(), res.rows.size());

  // Lee rows of case A: tolerance → err_u.
  std::map<std::string, std::vector<std::pair<double, double>>> lee;  // variant → (tol, err)
  bool have_penalty = false, have_ref_check = false, have_holo = false, have_event = false;
  std::map<std::string, std::vector<std::pair<double, double>>> pen;  // variant → (k_p, err_u)
  for (const auto& r : rows) {
    EXPECT_EQ(r[col["scene"]], "A");
    const std::string fin = r[col["finished"]];
    ASSERT_TRUE(fin == "0" || fin == "1") << fin;
    EXPECT_TRUE(num(r[col["cpu_seconds"]]) >= 0 || r[col["cpu_seconds"]].empty());
    if (fin == "1") {
      for (const char* k : {"cpu_seconds", "err_u", "err_force", "impulse_err"}) {
        EXPECT_TRUE(std::isfinite(num(r[col[k]]))) << k << " in " << r[col["method"]];
      }
    }
    const std::string m = r[col["method"]];
    // Newton statistics: a BDF step needs at least one Newton iteration; ERK has none.
    if (fin == "1" && r[col["engine"]] == "cvode-bdf" && m != "reference-check")
      EXPECT_GE(num(r[col["nonlin_iters"]]), num(r[col["steps"]])) << m;
    if (r[col["engine"]] == "arkode-erk") EXPECT_EQ(r[col["nonlin_iters"]], "0") << m;
    if (m == "lee") {
      EXPECT_EQ(fin, "1") << r[col["note"]];
      lee[r[col["variant"]]].push_back({num(r[col["tol"]]), num(r[col["err_u"]])});
    }
    if (m == "penalty") {
      have_penalty = true;
      if (fin == "1") pen[r[col["variant"]]].push_back({num(r[col["kp"]]), num(r[col["err_u"]])});
      EXPECT_TRUE(std::isfinite(num(r[col["kp"]])));
      EXPECT_TRUE(std::isfinite(num(r[col["cp"]])));
    }
    if (m == "reference-check") {
      // The reference has converged: one decade looser changes nothing visible.
      EXPECT_LT(num(r[col["err_u"]]), 1e-12);
      EXPECT_LT(num(r[col["err_force"]]), 1e-12);
    }
    have_ref_check = have_ref_check || m == "reference-check";
    have_holo = have_holo || m == "holonomic";
    have_event = have_event || m == "event";
  }
  EXPECT_TRUE(have_penalty);
  EXPECT_TRUE(have_ref_check);
  EXPECT_TRUE(have_holo);
  EXPECT_TRUE(have_event);
  ASSERT_EQ(lee.size(), 1u);  // one series: the located step (no duplicated variants)
  for (auto& [variant, pts] : lee) {
    ASSERT_GE(pts.size(), 2u) << variant;
    std::sort(pts.begin(), pts.end(), [](auto a, auto b) { return a.first > b.first; });
    // On the coarse grid of a rigid follower (1e-2, so the step control sets Lee's steps)
    // the error is the displacement level's tolerance: err_u ≤ tol_u (the reference is
    // event-driven, closed form in contact) ...
    for (const auto& [tol, err] : pts) EXPECT_LE(err, tol) << variant << " tol_u " << tol;
    EXPECT_LT(pts.back().second, 1e-7) << variant;
    // ... and the error does not grow as the tolerance tightens (it may already be at
    // round-off level for the rigid case, which stays in contact).
    for (size_t i = 1; i < pts.size(); ++i) {
      EXPECT_LE(pts[i].second, pts[i - 1].second * (1 + 1e-6) + 1e-11)
          << variant << " tol " << pts[i].first;
    }
  }

  // Penalty, linear law: the displacement error has a floor ∝ 1/k_p (the penetration
  // F/k_p), so err_u·k_p is about the same for the stiff settings (k_p ≥ 1e7). (Hunt–
  // Crossley's penetration (F/k)^(1/n) is not ∝ 1/k.)
  ASSERT_FALSE(pen.empty());
  EXPECT_TRUE(pen.count("hunt_crossley critical")) << "the bench runs both penalty laws";
  for (auto& [variant, pts] : pen) {
    if (variant.rfind("linear", 0) != 0) continue;
    std::vector<double> floor_kp;
    for (const auto& [kp, err] : pts)
      if (kp >= 1e7) floor_kp.push_back(err * kp);
    ASSERT_GE(floor_kp.size(), 2u) << variant;
    const auto [lo, hi] = std::minmax_element(floor_kp.begin(), floor_kp.end());
    EXPECT_LT(*hi / *lo, 1.5) << variant;
  }

  // The Markdown report and the headline exist.
  std::ifstream md(dir / "work_precision.md");
  ASSERT_TRUE(md.good());
  std::stringstream ss;
  ss << md.rdbuf();
  EXPECT_NE(ss.str().find("Headline"), std::string::npos);
  ASSERT_EQ(res.headline_text.size(), 1u);
  EXPECT_FALSE(res.headline_text[0].empty());
  fs::remove_all(dir);
}

#ifdef CAMDYN_CLI_PATH
TEST(Bench, CliBadInputExits2) {
  const std::string cli = CAMDYN_CLI_PATH;
  if (cli.empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = temp_dir("cli");
  const std::string base = "'" + cli + "' bench ";
  const std::string redirect = " >/dev/null 2>&1";
  auto status = [&](const std::string& args) {
    const int rc = std::system((base + args + redirect).c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  EXPECT_EQ(status("'" + (dir / "no_such_scene.toml").string() + "' --out '" +
                   (dir / "o").string() + "'"),
            2);
  EXPECT_EQ(status("A --repeats 0 --out '" + (dir / "o").string() + "'"), 2);
  EXPECT_EQ(status("A7 --output-dt -1 --out '" + (dir / "o").string() + "'"), 2);
  fs::remove_all(dir);
}
#endif

// The bench's penalty baseline starts fairly: in its own equilibrium, pressed into the cam
// by s₀ so that the penalty force carries the initial contact force (simulator.cpp,
// Runner::run()). Truth: case A's exact force F₀ = mẌ_C(0) + kδ₀ from the cam's closed
// kinematics; the rigid follower's equilibrium k_p s₀ = F₀ − k s₀ (the spring relaxes by
// s₀), i.e. F(0) = F₀ k_p/(k_p + k).
TEST(BenchPenaltyStart, CaseAStartsInEquilibrium) {
  const camdyn::Scene a = camdyn::paper_case("A");
  camdyn::Cam cam(a.cam);
  camdyn::CamDrive drive(a.cam);
  const camdyn::CamMotion m0 = cam.motion(drive.theta(0), drive.omega(0), drive.omega_dot(0));
  const double k = a.spring.stiffness;
  const double F0 = a.follower.mass * m0.Xddot + k * a.spring.precompression;
  ASSERT_GT(F0, 0.0);
  for (const auto law : {camdyn::PenaltyLaw::Linear, camdyn::PenaltyLaw::HuntCrossley}) {
    for (double kp : {1e4, 1e10}) {
      camdyn::Scene s = a;
      s.contact.model = camdyn::ContactModel::Penalty;
      s.contact.penalty_law = law;
      s.contact.penalty_stiffness = kp;
      s.contact.penalty_damping = 0.1 * 2.0 * std::sqrt(kp * s.follower.mass);
      s.solver.integrator = camdyn::Integrator::CvodeBdf;
      s.solver.rtol = 1e-10;
      s.solver.atol = 1e-12;
      s.run.t_end = 2e-3;
      const camdyn::RunResult r = camdyn::simulate(s);
      ASSERT_TRUE(r.summary.finished) << r.summary.message;
      ASSERT_GE(r.rows.size(), 2u);
      const camdyn::HistoryRow& r0 = r.rows.front();
      ASSERT_EQ(r0.t, 0.0);
      const double s0 = -r0.gap;  // penetration at t = 0
      ASSERT_GT(s0, 0.0);
      const double n = s.contact.penalty_exponent;
      const double Fpen = law == camdyn::PenaltyLaw::Linear ? kp * s0 : kp * std::pow(s0, n);
      const char* name = law == camdyn::PenaltyLaw::Linear ? "linear" : "hunt_crossley";
      // The row's force is the penalty law's force at that penetration ...
      // (s₀ is read back as a difference of positions ≈ 3: up to ~2 ulp of 3 off)
      const double ds = 4.0 * std::numeric_limits<double>::epsilon() * std::abs(m0.X);
      const double slope = law == camdyn::PenaltyLaw::Linear ? kp : n * Fpen / s0;
      EXPECT_NEAR(r0.contact_force, Fpen, slope * ds + 1e-12 * F0) << name << " k_p " << kp;
      // ... and it balances the exact initial force with the relaxed spring. The force is
      // the law's at the start state, whose penetration X_C − q₀ carries the round-off ds
      // of positions ≈ 2: the force is as exact as slope·ds allows (4e-6 at k_p = 1e10).
      const double dF = (slope + k) * ds + 1e-11 * F0;
      EXPECT_NEAR(r0.contact_force + k * s0, F0, dF) << name << " k_p " << kp;
      EXPECT_NEAR(r0.a_c, m0.Xddot, dF / s.follower.mass + 1e-9 * std::abs(m0.Xddot))
          << name << " k_p " << kp;
      if (law == camdyn::PenaltyLaw::Linear)
        EXPECT_NEAR(r0.contact_force, F0 * kp / (kp + k), dF) << "k_p " << kp;
      // Linear law, stiff contact: the start is the exact force within 1e-6 (Hunt–Crossley
      // presses in further, s₀ = (F₀/k_p)^(1/n), so its k s₀ is larger).
      if (kp >= 1e10 && law == camdyn::PenaltyLaw::Linear) {
        EXPECT_NEAR(r0.contact_force, F0, 1e-6 * F0) << name;
        // No start-up transient: the force stays on the exact one (up to the penalty's
        // own O(k/k_p) and the cam's small motion) over the first 2 ms.
        for (const auto& row : r.rows) {
          const camdyn::CamMotion m =
              cam.motion(drive.theta(row.t), drive.omega(row.t), drive.omega_dot(row.t));
          const double F = a.follower.mass * m.Xddot +
                           k * (a.spring.precompression + m.X - m0.X);
          EXPECT_NEAR(row.contact_force, F, 1e-4 * F0) << name << " t " << row.t;
        }
      }
    }
  }
}

// A7 (case A at 7 rev/s) separates and lands once per revolution. The reference is exact
// (closed form in contact, DP5 at rtol 1e-12 in flight). The classic step's error came
// from the steps in which the contact opens or closes (capping Δt 10× cut err_u ~100×);
// the located step lands on those instants, so its error is set by the tolerance
// (tol_u = 1e-8) with or without a step cap.
TEST(Bench, QuickA7LeeErrorIsSetByTheToleranceNotTheStepCap) {
  const fs::path dir = temp_dir("a7");
  const camdyn::BenchResult res = camdyn::run_bench(quick_options("A7", dir, 1));
  std::map<double, double> cap_err;  // max_step → err_u
  bool ref_ok = false;
  for (const auto& r : res.rows) {
    if (r.method == "reference-check") {
      ref_ok = r.err_u < 1e-10 && r.event_err < 1e-10;
      EXPECT_TRUE(ref_ok) << r.err_u << " " << r.event_err;
    }
    if (r.method == "lee" && std::isfinite(r.max_step)) {
      ASSERT_TRUE(r.finished) << r.note;
      cap_err[r.max_step] = r.err_u;
      EXPECT_LT(r.event_err, 2.0 * r.max_step) << "max_step " << r.max_step;
    }
  }
  EXPECT_TRUE(ref_ok);
  ASSERT_EQ(cap_err.size(), 2u);
  const double fine = cap_err.begin()->second, coarse = cap_err.rbegin()->second;
  std::printf("A7 step cap: err_u %.3e (coarse cap) → %.3e (fine cap)\n", coarse, fine);
  EXPECT_LT(coarse, 1e-8);
  EXPECT_LT(fine, 1e-8);
  fs::remove_all(dir);
}

// The bench's named stiff scene is the example file users run (docs: README "What accuracy
// costs"), and B1_1000 is case B1 with 1000 elements.
TEST(Bench, StiffCasesAreTheDocumentedScenes) {
  camdyn::Scene stiff = camdyn::bench_case("stiff");
  camdyn::Scene file = camdyn::load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/stiff_bar.toml");
  camdyn::resolve_defaults(stiff);
  camdyn::resolve_defaults(file);
  EXPECT_TRUE(stiff == file);
  camdyn::Scene b = camdyn::bench_case("B1_1000");
  EXPECT_EQ(b.follower.elements, 1000);
  b.follower.elements = camdyn::paper_case("B1").follower.elements;
  b.title = camdyn::paper_case("B1").title;
  b.run.t_end = camdyn::paper_case("B1").run.t_end;
  EXPECT_TRUE(b == camdyn::paper_case("B1"));
}

// The bench's event metrics on a hand-made pair: the reference has an impact at 0.100 s
// at 2.0 m/s and a separation at 0.200 s; the run lands at 0.1001 s at 2.1 m/s and
// separates at 0.1995 s. Truth by hand: event_err = max(1e-4, 5e-4) = 5e-4, impact speed
// error |2.1 − 2.0| / 2.0 = 0.05; the pointwise force error is max|ΔF| / max F_ref.
TEST(BenchCompare, EventTimeImpactSpeedAndPointwiseForceErrors) {
  using namespace camdyn;
  using namespace camdyn::bench_detail;
  SceneInfo si;
  si.rigid = false;
  si.dt = 1e-3;
  si.n = 301;
  si.k_point = 300;
  si.k_window = 1;
  auto grid = [&](double bump) {
    Grid g;
    g.n = si.n;
    g.u.assign(si.n, 0.0);
    g.v.assign(si.n, 0.0);
    g.c.assign(si.n, 1);
    g.f.assign(si.n, 10.0);
    g.f[150] += bump;
    g.kick.assign(si.n, 0.0);
    return g;
  };
  auto ev = [](double t, EventKind k, double v) {
    ContactEvent e;
    e.t = t;
    e.type = k;
    e.impact_velocity = v;
    return e;
  };
  si.ref = grid(0.0);
  si.ref_events = {ev(0.100, EventKind::Impact, 2.0), ev(0.200, EventKind::Separation, 0.0)};
  const Grid g = grid(2.5);  // the run's force is 2.5 off at one grid point
  const std::vector<ContactEvent> mine{ev(0.1001, EventKind::Impact, 2.1),
                                       ev(0.1995, EventKind::Separation, 0.0)};
  const Comparison c = compare(si, g, mine);
  EXPECT_NEAR(c.event_err, 5e-4, 1e-12);
  EXPECT_NEAR(c.impact_speed_err, 0.05, 1e-12);
  EXPECT_NEAR(c.err_force_pointwise, 2.5 / 10.0, 1e-12);
  // A run without any impact: the impact speed error is 1 (none of the reference's is met).
  const Comparison none = compare(si, g, {ev(0.1995, EventKind::Separation, 0.0)});
  EXPECT_EQ(none.impact_speed_err, 1.0);
}

// A cached reference is the run itself: the second call reads it back from the cache
// directory (same rows and events to the last bit, as written with 17 digits).
TEST(BenchCompare, ReferenceCacheReturnsTheSameRun) {
  using namespace camdyn::bench_detail;
  const fs::path dir = temp_dir("cache");
  camdyn::Scene s = camdyn::bench_case("A7");
  s.run.t_end = 0.3;
  s.run.output_dt = 1e-3;
  s.contact.model = camdyn::ContactModel::Event;
  bool cached = true;
  const camdyn::bench_detail::Run a = reference_run(s, dir.string(), &cached);
  EXPECT_FALSE(cached);
  ASSERT_TRUE(a.sum.finished);
  ASSERT_FALSE(a.events.empty());
  const camdyn::bench_detail::Run b = reference_run(s, dir.string(), &cached);
  EXPECT_TRUE(cached);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  ASSERT_EQ(a.events.size(), b.events.size());
  for (size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].t, b.rows[i].t);
    EXPECT_EQ(a.rows[i].u_c, b.rows[i].u_c);
    EXPECT_EQ(a.rows[i].contact_force, b.rows[i].contact_force);
  }
  for (size_t i = 0; i < a.events.size(); ++i) {
    EXPECT_EQ(a.events[i].t, b.events[i].t);
    EXPECT_EQ(a.events[i].type, b.events[i].type);
    EXPECT_EQ(a.events[i].impact_velocity, b.events[i].impact_velocity);
  }
  EXPECT_EQ(a.sum.separations, b.sum.separations);
  // Another scene has another key: not read from the cache.
  s.cam.speed_rev_s = 7.5;
  reference_run(s, dir.string(), &cached);
  EXPECT_FALSE(cached);
  fs::remove_all(dir);
}

// The quick sweep's reference of an elastic bar runs on arkode-erk (its check row names the
// engine), and that explicit reference agrees with the implicit one at the same rtol: case
// B1 over 5 ms, event method at rtol 1e-10 on arkode-erk against cvode-bdf, compared on the
// bench's 1e-4 grid (a second formulation of the same reference; measured: err_force
// 3.2e-9, err_force_pointwise 3.2e-8).
TEST(Bench, QuickElasticReferenceIsExplicitAndAgreesWithTheImplicitOne) {
  using namespace camdyn::bench_detail;
  camdyn::Scene s = camdyn::bench_case("B1");
  camdyn::resolve_defaults(s);
  s.run.t_end = 0.005;
  s.run.output_dt = 1e-4;
  s.contact.model = camdyn::ContactModel::Event;
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-10;
  s.solver.integrator = camdyn::Integrator::ArkodeErk;
  const camdyn::bench_detail::Run erk = run_once(s, 0.0, true);
  s.solver.integrator = camdyn::Integrator::CvodeBdf;
  const camdyn::bench_detail::Run bdf = run_once(s, 0.0, true);
  ASSERT_TRUE(erk.sum.finished) << erk.sum.message;
  ASSERT_TRUE(bdf.sum.finished) << bdf.sum.message;
  SceneInfo si;
  ASSERT_TRUE(setup_scene_info(si, s, bdf, 1e-4));
  Grid g = to_grid(erk.rows, 1e-4, si.n);
  add_kicks(g, erk.events, 1e-4);
  ASSERT_TRUE(complete(g));
  const Comparison c = compare(si, g, erk.events);
  EXPECT_LT(c.err_force, 1e-7);
  EXPECT_LT(c.err_force_pointwise, 1e-6);

  const fs::path dir = temp_dir("quick_elastic");
  camdyn::BenchOptions o = quick_options("B1", dir, 1);
  o.t_end = 0.002;
  const camdyn::BenchResult res = camdyn::run_bench(o);
  bool saw_check = false;
  for (const auto& r : res.rows)
    if (r.method == "reference-check") {
      saw_check = true;
      EXPECT_EQ(r.engine, "arkode-erk");
      EXPECT_TRUE(r.finished) << r.note;
      EXPECT_LT(r.err_force, 1e-6) << r.note;
    }
  EXPECT_TRUE(saw_check);
  fs::remove_all(dir);
}

// Issue 36's check "running the regeneration twice on the same build gives the same rows
// (timings aside)": two quick runs of case B1 (2 ms), the second with its reference and check
// from the reference cache, give rows equal in every column but the CPU time (and the note's
// "from the cache"). Every row is also held to the reference rule: a finished row whose
// err_F, err_F_pw or impulse_err is under 10× the check row's says so in its note.
TEST(Bench, TwoQuickRunsGiveTheSameRowsTimingsAside) {
  const fs::path dir = temp_dir("repeat");
  camdyn::BenchOptions o = quick_options("B1", dir / "out", 1);
  o.t_end = 0.002;
  o.reference_cache_dir = (dir / "cache").string();
  const camdyn::BenchResult a = camdyn::run_bench(o);
  const camdyn::BenchResult b = camdyn::run_bench(o);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  ASSERT_GE(a.rows.size(), 10u);
  const camdyn::BenchRow* chk = nullptr;
  for (size_t i = 0; i < a.rows.size(); ++i) {
    const camdyn::BenchRow &x = a.rows[i], &y = b.rows[i];
    SCOPED_TRACE(x.method + " " + x.engine + " " + x.variant);
    EXPECT_EQ(x.method, y.method);
    EXPECT_EQ(x.engine, y.engine);
    EXPECT_EQ(x.variant, y.variant);
    EXPECT_EQ(x.finished, y.finished);
    EXPECT_EQ(x.steps, y.steps);
    EXPECT_EQ(x.rhs_evals, y.rhs_evals);
    EXPECT_EQ(x.nonlin_iters, y.nonlin_iters);
    for (auto [p, q] : {std::pair{x.err_u, y.err_u}, {x.err_force, y.err_force},
                        {x.err_force_pointwise, y.err_force_pointwise}, {x.impulse_err, y.impulse_err},
                        {x.osc_index, y.osc_index}, {x.event_err, y.event_err}})
      EXPECT_TRUE(p == q || (std::isnan(p) && std::isnan(q))) << p << " vs " << q;
    if (x.method == "reference-check") {
      EXPECT_EQ(y.note.find("from the cache") == std::string::npos, false) << y.note;
      chk = &x;
    } else {
      EXPECT_EQ(x.note, y.note);
    }
  }
  ASSERT_NE(chk, nullptr);
  for (const auto& r : a.rows) {
    if (r.method == "reference-check" || !r.finished) continue;
    const bool close = r.err_force < 10 * chk->err_force ||
                       r.err_force_pointwise < 10 * chk->err_force_pointwise ||
                       r.impulse_err < 10 * chk->impulse_err;
    EXPECT_EQ(close, r.note.find("within 10×") != std::string::npos) << r.method << " " << r.note;
  }
  fs::remove_all(dir);
}
