// The flights the gap tolerance cannot resolve (issue 35; FlightLog, flight_warnings):
// a flight's apex from its step-end gaps and its two ends against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "contact/flight_log.hpp"
#include "run/contract.hpp"

namespace camdyn {
namespace {

using detail::FlightLog;

TEST(FlightLog, ApexOfASeparationFromRestIsTheCubicsBetweenStepEnds) {
  // g(τ) = a τ²(Δt − τ): leaves g = 0 at ġ = 0 (a separation where the force reaches zero),
  // returns at −v = −aΔt²; its apex 4/27·aΔt³ = 4/27·vΔt at τ = 2Δt/3. Step ends at Δt/4,
  // Δt/2 and 7Δt/8 miss the apex: the estimate from the two ends gives it exactly.
  const double a = 2.0, dt = 1e-3, t0 = 0.25, v = a * dt * dt;
  const double apex = 4.0 / 27.0 * a * dt * dt * dt;  // 1.48e-10
  auto g = [&](double tau) { return a * tau * tau * (dt - tau); };
  for (double tol : {2.0 * apex, 0.5 * apex}) {  // the unresolved threshold: 1e-3 gap tolerance
    FlightLog log({"cam", "seat"}, tol / FlightLog::kFlightGaps);
    EXPECT_DOUBLE_EQ(log.threshold(), tol);
    log.event(EventKind::Separation, 1, t0, 0.0);
    for (double f : {0.25, 0.5, 0.875}) {
      ASSERT_LT(g(f * dt), apex);
      log.sample(1, g(f * dt));
    }
    log.event(EventKind::Impact, 1, t0 + dt, v);
    Summary s;
    log.finish(s);
    ASSERT_EQ(s.contract.flights.size(), 1u);  // the cam had no flight
    const FlightCount& n = s.contract.flights[0];
    EXPECT_EQ(n.contact, "seat");
    EXPECT_EQ(n.flights, 1);
    EXPECT_NEAR(n.min_apex, apex, 1e-12 * apex);
    EXPECT_EQ(n.unresolved, tol > apex ? 1 : 0);
  }
}

TEST(FlightLog, AStepEndAboveTheToleranceResolvesTheFlight) {
  FlightLog log({"lash"}, 1e-6);  // threshold 1e-9
  log.event(EventKind::Separation, 0, 1.0, 0.0);
  log.sample(0, 5e-9);  // a step end inside the flight, 5 thresholds open
  log.event(EventKind::Impact, 0, 1.0 + 1e-7, 1e-4);  // its ends alone: 4/27·1e-11
  // an impact without a separation before it (a start, a closing from an open gap) is no flight
  log.event(EventKind::Impact, 0, 1.1, 1e-4);
  Summary s;
  log.finish(s);
  ASSERT_EQ(s.contract.flights.size(), 1u);
  EXPECT_EQ(s.contract.flights[0].flights, 1);
  EXPECT_EQ(s.contract.flights[0].unresolved, 0);
  EXPECT_DOUBLE_EQ(s.contract.flights[0].min_apex, 5e-9);
}

TEST(FlightLog, UnresolvedFlightsAreAWarningNamingTolU) {
  Scene sc;
  sc.contact.tol_u = 1e-9;
  RunContract c;
  c.flight_threshold = 1e-12;
  FlightCount n;
  n.contact = "cam";
  n.flights = 7;
  n.unresolved = 3;
  n.max_unresolved_apex = 4e-13;
  n.max_unresolved_duration = 2e-6;
  c.flights.push_back(n);
  FlightCount ok;
  ok.contact = "seat";
  ok.flights = 2;
  c.flights.push_back(ok);
  detail::flight_warnings(sc, c);
  ASSERT_EQ(c.warnings.size(), 1u);
  const std::string& w = c.warnings[0];
  EXPECT_NE(w.find("contact 'cam'"), std::string::npos) << w;
  EXPECT_NE(w.find("3 of 7"), std::string::npos) << w;
  EXPECT_NE(w.find("contact.tol_u = 1e-09"), std::string::npos) << w;
  EXPECT_NE(w.find("4e-13 <= 1e-12"), std::string::npos) << w;
  EXPECT_TRUE(c.held);  // a warning, not a violation
  EXPECT_TRUE(c.violations.empty());
}

}  // namespace
}  // namespace camdyn
