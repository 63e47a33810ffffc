// camdyn — Campbell diagrams (camdyn/campbell.hpp) against closed forms.
//
//   * An eccentric circle cam under a flat-faced rigid follower held on it: the lift is
//     exactly X = e(1 − cos θ) (θ from the base position), so the contact force
//     F = k(δ₀ + X) + m Ẍ = kδ₀ + ke + (m e ω² − k e) cos θ has one order, amplitude
//     |m e ω² − k e| at ω = 2πn, and nothing at order 2.
//   * The surge lines: a spring of stiffness k and coil mass m_s lumped into N inner masses
//     (N + 1 springs) held at both ends has f₁ = ((N + 1)/π)√(k/m_s) sin(π/(2(N + 1))) (the
//     discrete chain's closed form; the library solves the eigenproblem), which tends to
//     ½√(k/m_s), the continuous spring's surge frequency, as N grows.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <camdyn/campbell.hpp>
#include <camdyn/scene.hpp>

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;

Scene eccentric() {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/circle_cam.toml");
  s.contact.model = ContactModel::Event;
  s.solver.rtol = 1e-10;
  s.solver.atol = 1e-12;
  return s;
}

TEST(Campbell, EccentricCamHasOneOrderOfTheClosedFormAmplitude) {
  const Scene s = eccentric();
  CampbellOptions o;
  o.speeds_rev_s = {1.0, 1.75, 2.5};
  o.settle_revolutions = 0;
  o.revolutions = 2;
  o.samples_per_revolution = 256;
  o.max_order = 8;
  o.threads = 2;
  const CampbellDiagram d = campbell(s, o);
  ASSERT_EQ(d.amplitude.size(), 3u);
  const double m = s.follower.mass, k = s.spring.stiffness, e = s.cam.eccentricity;
  for (std::size_t i = 0; i < d.speed_rev_s.size(); ++i) {
    const double w = 2 * kPi * d.speed_rev_s[i];
    ASSERT_EQ(d.runs[i].separations, 0) << "held at " << d.speed_rev_s[i];
    double a1 = -1, a2 = -1;
    for (std::size_t j = 0; j < d.order.size(); ++j) {
      if (std::abs(d.order[j] - 1.0) < 1e-12) a1 = d.amplitude[i][j];
      if (std::abs(d.order[j] - 2.0) < 1e-12) a2 = d.amplitude[i][j];
    }
    const double exact = std::abs(m * e * w * w - k * e);
    // measured: relative error ≤ 2.1e-15, order 2 ≤ 2.3e-15 of order 1 (the rows fall on
    // the spectrum's uniform grid, the held force is the closed form to round-off)
    EXPECT_NEAR(a1, exact, 1e-12 * exact) << d.speed_rev_s[i] << " rev/s";
    EXPECT_LT(a2, 1e-12 * exact) << d.speed_rev_s[i] << " rev/s";
  }
  EXPECT_TRUE(d.lines.empty());  // a single follower has no spring with coil masses
}

TEST(Campbell, SurgeLineOfTheLumpedChainTendsToTheSpringsSurgeFrequency) {
  Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohc_bucket_tappet.toml");
  ElementSpec* spring = nullptr;
  for (ElementSpec& e : s.network.elements)
    if (e.kind == ElementKind::Spring && e.masses > 0) spring = &e;
  ASSERT_NE(spring, nullptr);
  const double k = spring->stiffness, ms = spring->mass, f_cont = 0.5 * std::sqrt(k / ms);
  double prev = INFINITY;
  for (int N : {2, 6, 20, 60}) {
    spring->masses = N;
    const std::vector<CampbellLine> lines = surge_lines(s, 3);
    ASSERT_GE(lines.size(), 1u);
    const double f_chain = (N + 1) / kPi * std::sqrt(k / ms) * std::sin(kPi / (2.0 * (N + 1)));
    EXPECT_NEAR(lines[0].frequency_hz, f_chain, 1e-9 * f_chain) << N;
    const double err = std::abs(lines[0].frequency_hz - f_cont) / f_cont;
    EXPECT_LT(err, prev) << N;  // falls as N grows, ∝ 1/N²: π²/(24 (N+1)²)
    EXPECT_NEAR(err, kPi * kPi / (24.0 * (N + 1) * (N + 1)), 0.1 * err) << N;
    prev = err;
    if (N >= 2) {  // the second surge mode at twice the first, in the limit
      const double f2 = (N + 1) / kPi * std::sqrt(k / ms) * std::sin(2 * kPi / (2.0 * (N + 1)));
      EXPECT_NEAR(lines[1].frequency_hz, f2, 1e-9 * f2) << N;
    }
  }
  EXPECT_LT(prev, 1e-3);
}

TEST(Campbell, BadOptionsNameTheField) {
  const Scene s = eccentric();
  struct Case {
    void (*set)(CampbellOptions&);
    const char* field;
  };
  const Case cases[] = {
      {[](CampbellOptions& o) { o.speeds_rev_s = {1.0}; }, "speeds_rev_s"},
      {[](CampbellOptions& o) { o.speeds_rev_s = {2.0, 1.0}; }, "speeds_rev_s"},
      {[](CampbellOptions& o) { o.speeds_rev_s = {0.0, 1.0}; }, "speeds_rev_s"},
      {[](CampbellOptions& o) { o.revolutions = 0; }, "revolutions"},
      {[](CampbellOptions& o) { o.samples_per_revolution = 8; }, "samples_per_revolution"},
      {[](CampbellOptions& o) { o.max_order = 1000; }, "max_order"},
      {[](CampbellOptions& o) { o.column = "no_such_column"; }, "column"},
  };
  for (const Case& c : cases) {
    CampbellOptions o;
    o.speeds_rev_s = {1.0, 2.0};
    o.revolutions = 1;
    o.settle_revolutions = 0;
    o.samples_per_revolution = 64;
    o.max_order = 8;
    c.set(o);
    try {
      campbell(s, o);
      ADD_FAILURE() << c.field << " accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key(), c.field);
    }
  }
}

}  // namespace
