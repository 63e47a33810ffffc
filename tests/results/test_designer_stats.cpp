// Designer results of a run (results/designer_stats.hpp) against closed forms of the
// eccentric circle cam (tests/circle_cam_support.hpp) and of a lift cam: the separation
// angle, Poincaré samples, the period detector, the force margin.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "camdyn/cam.hpp"
#include "camdyn/designer.hpp"
#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "results/designer_stats.hpp"
#include "../circle_cam_support.hpp"

using namespace camdyn;
using camdyn_test::circle_scene;
using camdyn_test::example;
using camdyn_test::kPi;

// ---- designer results against closed forms --------------------------------------------

TEST(Designer, SeparationAngleFromTheCircleFormula) {
  // θ₀ = 180°, ω chosen so that cos θ* = 1/2: the first separation is at θ* = 300°.
  const double k = 500, d0 = 7, m = 1, e = 0.5;
  const double w = std::sqrt((k * d0 + k * e) / (m * e * 0.5) + k / m);
  Scene s = circle_scene(k, d0, m, e);
  s.contact.model = ContactModel::Event;
  s.cam.theta0_deg = 180;
  s.cam.speed_rev_s = w / (2 * kPi);
  s.run.t_end = 0.06;  // < one revolution (0.0506 s to 300°)
  s.run.output_dt = 1e-3;
  const Summary r = Simulator(s).run();
  ASSERT_TRUE(r.finished) << r.message;
  ASSERT_GE(r.separations, 1);
  EXPECT_NEAR(r.first_separation_theta_deg, 300.0, 1e-6);
  EXPECT_EQ(r.min_contact_force, 0.0);
  EXPECT_NEAR(r.min_force_theta_deg, 300.0, 1e-6);
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(std::string(to_string(r.events.front().type)), "separation");
  EXPECT_NEAR(std::fmod(r.events.front().theta * 180 / kPi, 360.0), 300.0, 1e-6);
  // An impact follows in free flight: its angle and velocity are reported with the event.
  if (r.impacts > 0) {
    EXPECT_GT(r.max_impact_velocity, 0);
    EXPECT_FALSE(std::isnan(r.first_impact_theta_deg));
    EXPECT_GT(r.max_gap, 0);
  }
}

TEST(Designer, PoincareSamplesOnTheCamAreExact) {
  // Below the jump speed the follower rides the cam: at section angle θ_s the contact
  // face is at R + e cos θ_s with velocity −e ω sin θ_s.
  for (const ContactModel model : {ContactModel::Lee, ContactModel::Event}) {
    Scene s = circle_scene();
    s.contact.model = model;
    s.cam.speed_rev_s = 5.0;
    s.run.t_end = 1.0;
    s.run.output_dt = 1e-3;
    s.run.poincare_angle_deg = 90;
    s.run.settle_revolutions = 2;
    const Summary r = Simulator(s).run();
    ASSERT_TRUE(r.finished) << r.message;
    ASSERT_EQ(r.poincare.size(), 3u);  // revolutions 2, 3, 4 (θ = 90° at t = 0.05 + 0.2 k)
    const double w = 2 * kPi * 5.0;
    for (std::size_t i = 0; i < r.poincare.size(); ++i) {
      EXPECT_EQ(r.poincare[i].revolution, long(i) + 2);
      EXPECT_NEAR(r.poincare[i].t, 0.05 + 0.2 * double(i + 2), 1e-12);
      EXPECT_NEAR(r.poincare[i].u_c, 2.0, 1e-7);
      EXPECT_NEAR(r.poincare[i].v_c, -0.5 * w, 1e-5 * 0.5 * w);
    }
    EXPECT_EQ(r.period, 1);
    EXPECT_EQ(r.period_kind, "period-1");
    EXPECT_EQ(r.separations, 0);
    // margin: min_θ (kδ₀ + k e (cos θ − 1) − m e ω² cos θ) = at θ = 0 (k < m ω²)
    EXPECT_NEAR(r.min_contact_force, 3500 - 0.5 * w * w, 1e-6 * 3500);
    EXPECT_NEAR(std::min(r.min_force_theta_deg, 360 - r.min_force_theta_deg), 0.0, 1e-9);
  }
}

TEST(Designer, PeriodDetectorOnSyntheticSequences) {
  auto seq = [](std::vector<double> u) {
    std::vector<PoincareSample> s;
    for (std::size_t i = 0; i < u.size(); ++i) s.push_back({long(i), double(i), u[i], 0.0});
    return s;
  };
  std::string kind;
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 1, 1, 1}), 1, 1, 1e-3, &kind), 1);
  EXPECT_EQ(kind, "period-1");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 2, 1, 2, 1, 2}), 1, 1, 1e-3, &kind), 2);
  EXPECT_EQ(kind, "period-2");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 2, 3, 1, 2, 3, 1}), 1, 1, 1e-3, &kind), 3);
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 2, 1, 2}), 1, 1, 1e-3, &kind), 0);  // needs 2p + 1
  EXPECT_EQ(kind, "not periodic");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({0.1, 0.7, 0.3, 0.9, 0.2, 0.55, 0.8}), 1, 1, 1e-3, &kind), 0);
  EXPECT_EQ(kind, "not periodic");
  EXPECT_EQ(detail::DesignerStats::detect_period(seq({1, 1}), 1, 1, 1e-3, &kind), 0);
  EXPECT_EQ(kind, "too few samples");
}

TEST(Designer, PeriodOneThenIrregularAboveTheJumpSpeed) {
  // Scene: the eccentric circle cam (k = 500, δ₀ = 7, m = 1, e = 0.5, jump 13.32 rev/s),
  // rigid follower, restitution 0.8, exact event-driven method, 30 revolutions settled.
  // At 14 rev/s (5 % above the jump speed) the follower leaves the cam near θ = 0 each
  // revolution, bounces with a chattering sequence that ends on the cam: period-1.
  // At 20 rev/s it never re-sticks: the Poincaré samples do not repeat (not periodic
  // within 1e-3 of the lift over 16 revolutions).
  Scene s = circle_scene();
  s.contact.model = ContactModel::Event;
  s.contact.restitution = 0.8;
  s.run.output_dt = 0;
  s.run.settle_revolutions = 30;
  s.cam.speed_rev_s = 14;
  s.run.t_end = 50.0 / 14;
  const Summary a = Simulator(s).run();
  ASSERT_TRUE(a.finished) << a.message;
  EXPECT_GT(a.separations, 0);
  EXPECT_EQ(a.period, 1) << a.period_kind;
  EXPECT_EQ(a.period_kind, "period-1");
  s.cam.speed_rev_s = 20;
  s.run.t_end = 70.0 / 20;
  const Summary b = Simulator(s).run();
  ASSERT_TRUE(b.finished) << b.message;
  EXPECT_GT(b.impacts, 0);
  EXPECT_GE(b.poincare.size(), 33u);
  EXPECT_NE(b.period, 1) << b.period_kind;
  EXPECT_TRUE(b.period_kind == "not periodic" || b.period >= 2) << b.period_kind;
}

TEST(Designer, LiftCamMarginMatchesClosedForm) {
  // The lift-table cam below its jump speed (9.2 rev/s): the closed-form margin
  // min_θ F_req(θ, ω) vs the simulated minimum contact force (Lee, rigid, one revolution,
  // steps of the integrator's own choosing). Both use the cam's spline h(θ); the simulation
  // gets its force from the dynamics: the held-contact force (Ẍ_C − a_free)/M* sampled
  // inside steps by the work quadrature (exact for a rigid follower) and Lee's acceleration
  // level at step ends. Tolerance 1e-5 of the preload (0.035): measured 5e-5 (3 rev/s),
  // 6e-5 (6 rev/s) and 3.4e-3 (8.5 rev/s; steps of 3.4 ms). The minimum lies on a knot of
  // the lift spline (210°), where h‴ jumps and F_req has a corner, so a sample at δ from
  // the knot misses it by |F′|δ; step-end forces carry the acceleration level's tolerance
  // tol_u/Δt² · m. The cam is symmetric (F_req(90°) = F_req(210°)), so the angle is
  // checked through F_req at the simulated angle, not against one of the two twins.
  const Scene base = load_scene_file(example("lift_cam.toml"));
  for (double speed : {3.0, 6.0, 8.5}) {
    Scene s = base;
    s.cam.speed_rev_s = speed;
    s.run.t_end = 1.0 / speed;  // one revolution
    s.run.output_dt = 0;
    s.solver.rtol = 1e-7;
    // F_req = m h″ω² + kδ₀ + k (h(θ) − h(0)) (docs/method.md §1–2) on a 0.01° grid, from the
    // cam's support function; required_contact_force must agree at the minimum.
    const Cam cam(s.cam);
    const double w = 2 * kPi * speed, h0 = cam.evaluate(0).X_C;
    double closed = 1e300, th_min = 0;
    const int N = 36000;
    for (int i = 0; i < N; ++i) {
      const double th = 2 * kPi * i / N;
      const CamPoint p = cam.evaluate(th);
      const double F = p.d2X_dtheta2 * w * w + 3500 + 500 * (p.X_C - h0);
      if (F < closed) closed = F, th_min = th;
    }
    EXPECT_NEAR(required_contact_force(s, th_min), closed, 1e-9 * 3500);
    const Summary r = Simulator(s).run();
    ASSERT_TRUE(r.finished) << r.message;
    EXPECT_EQ(r.separations, 0);
    EXPECT_NEAR(r.min_contact_force, closed, 1e-5 * 3500) << speed << " rev/s";
    EXPECT_NEAR(required_contact_force(s, r.min_force_theta_deg * kPi / 180), closed, 1e-5 * 3500)
        << speed << " rev/s, at " << r.min_force_theta_deg << " deg";
  }
}
