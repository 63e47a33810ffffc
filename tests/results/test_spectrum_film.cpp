// Order spectra (src/results/spectrum.cpp) and the EHL line-contact film
// (src/results/oil_film.cpp) against closed forms written here.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "camdyn/scene.hpp"
#include "results/oil_film.hpp"
#include "camdyn/spectrum.hpp"

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(OrderSpectrum, RecoversTheOrdersAndAmplitudesOfKnownSinusoids) {
  // y(θ) = 3 + 2 cos(θ + 0.3) + 0.5 cos(7θ − 1) + 0.25 sin(12.5θ) over 4 revolutions
  // (order 12.5 is a bin of a 2-revolution window too), sampled 2048 times per revolution
  // starting at θ = 0.7 rad, the cam turning backwards (θ falls). Analysed: the last 2
  // revolutions, resampled on the record's own grid. Measured error ≈ 1e-13.
  const int S = 2048, R = 4;
  std::vector<double> th, y;
  for (int i = 0; i <= R * S; ++i) {
    const double p = 2 * kPi * i / S;  // progress
    th.push_back(0.7 - p);
    y.push_back(3 + 2 * std::cos(p + 0.3) + 0.5 * std::cos(7 * p - 1) + 0.25 * std::sin(12.5 * p));
  }
  SpectrumOptions o;
  o.revolutions = 2;
  o.samples_per_revolution = S;
  o.max_order = 20;
  const OrderSpectrum s = order_spectrum(th, y, o);
  ASSERT_EQ(s.revolutions, 2);
  ASSERT_EQ(s.order.size(), 41u);  // orders 0, 0.5, …, 20
  for (std::size_t j = 0; j < s.order.size(); ++j) {
    const double ord = s.order[j];
    double want = 0;
    if (ord == 0) want = 3;
    if (ord == 1) want = 2;
    if (ord == 7) want = 0.5;
    if (ord == 12.5) want = 0.25;
    EXPECT_NEAR(s.amplitude[j], want, 1e-6) << "order " << ord;
  }
  // phases relative to the window's start (progress 4π): order 1 → 0.3 + 4π ≡ 0.3 rad
  EXPECT_NEAR(s.phase_deg[2], 0.3 * 180 / kPi, 1e-6);
}

TEST(OrderSpectrum, RejectsBadRecords) {
  EXPECT_THROW(order_spectrum({0, 1, 2}, {1, 2, 3}), SceneError);        // < 1 revolution
  EXPECT_THROW(order_spectrum({0, 4, 2, 8}, {1, 2, 3, 4}), SceneError);  // not monotone
  EXPECT_THROW(order_spectrum({0, 7}, {1}), SceneError);                 // sizes differ
  SpectrumOptions o;
  o.max_order = 1000;  // > 1024 / 2
  EXPECT_THROW(order_spectrum({0, 7}, {1, 2}, o), SceneError);
}

TEST(OilFilm, HamrockLineContactAgainstItsDimensionalForm) {
  // Steel on steel (E = 207 GPa, ν = 0.3: E′ = 227.47 GPa), R_x = 10 mm, w′ = 1e5 N/m
  // (1000 N over 10 mm), η₀ = 0.01 Pa·s, ξ = 2e-8 1/Pa, ũ = 5 m/s. The formula regrouped
  // in dimensional form: h = 1.714 w′^−0.128 (η₀ũ)^0.694 ξ^0.568 E′^0.002 R_x^0.434.
  const double Ep = effective_modulus(207e9, 0.3, 207e9, 0.3);
  EXPECT_NEAR(Ep, 207e9 / (1 - 0.09), 1e-6 * Ep);
  Lubricant oil;
  oil.viscosity = 0.01;
  oil.pressure_viscosity = 2e-8;
  const double w = 1e5, R = 0.01, u = 5;
  const double h = line_contact_min_film(w, R, u, oil, Ep);
  const double dim = 1.714 * std::pow(w, -0.128) * std::pow(0.01 * u, 0.694) * std::pow(2e-8, 0.568) *
                     std::pow(Ep, 0.002) * std::pow(R, 0.434);
  EXPECT_NEAR(h / dim, 1.0, 1e-12);
  EXPECT_GT(h, 0.1e-6);  // a flat tappet's film: tenths of a micrometre
  EXPECT_LT(h, 1e-6);
  // scaling: ũ → 2ũ multiplies h by 2^0.694; w′ → 2w′ by 2^−0.128
  EXPECT_NEAR(line_contact_min_film(w, R, 2 * u, oil, Ep) / h, std::pow(2.0, 0.694), 1e-12);
  EXPECT_NEAR(line_contact_min_film(2 * w, R, u, oil, Ep) / h, std::pow(2.0, -0.128), 1e-12);
  EXPECT_EQ(line_contact_min_film(w, R, 0.0, oil, Ep), 0.0);
  EXPECT_TRUE(std::isnan(line_contact_min_film(0.0, R, u, oil, Ep)));
  oil.viscosity = -1;
  EXPECT_THROW(oil.validate(), SceneError);
}

TEST(OilFilm, FlatFaceEntrainmentOnAnEccentricFromItsGeometry) {
  // A circle of radius R whose centre C = e (sin θ, −cos θ) turns about O; the flat face
  // rests on top of it at P = (x_C, y_C + R). The cam's material point at P moves along the
  // face at −ω y_P, the contact point at ẋ_C = e ω cos θ, the face not at all: the mean
  // velocity relative to the contact is ½(−ω y_P − ẋ_C − ẋ_C).
  const double R = 0.02, e = 0.004, w = 300;
  for (double th = 0; th < 2 * kPi; th += 0.1) {
    const double yP = -e * std::cos(th) + R, xdot = e * w * std::cos(th);
    const double truth = 0.5 * ((-w * yP - xdot) + (-xdot));
    const double s = e * (1 - std::cos(th)), sdd = e * std::cos(th);
    EXPECT_NEAR(flat_face_entrainment(w, R - e, s, sdd), truth, 1e-12) << th;
  }
}

TEST(OilFilm, RollerEntrainmentOnAnEccentric) {
  // Roller of radius r on the same eccentric, its centre on the line x = 0 at y = y_C +
  // √((R + r)² − x_C²) (in-line follower). In the cam's frame the contact point runs along
  // the circle at the roller centre's speed × R/(R + r); rolling, ũ equals that speed.
  // The roller centre's speed in the cam frame: finite differences of its position
  // rotated into the cam frame (h = 1e-6 rad, error ≈ 1e-9 relative).
  const double R = 0.02, e = 0.004, r = 0.008, w = 300;
  auto centre_in_cam_frame = [&](double th) {
    const double xC = e * std::sin(th), yC = -e * std::cos(th);
    const double yR = yC + std::sqrt((R + r) * (R + r) - xC * xC);
    // rotate the world point (0, yR) by −θ (the cam turns by +θ)
    return std::make_pair(yR * std::sin(th), yR * std::cos(th));
  };
  for (double th = 0.05; th < 2 * kPi; th += 0.3) {
    const double h = 1e-6;
    const auto a = centre_in_cam_frame(th - h), b = centre_in_cam_frame(th + h);
    const double Vc = w * std::hypot(b.first - a.first, b.second - a.second) / (2 * h);
    const double truth = Vc * R / (R + r);
    // s, s′ of the roller centre: y_R − (R − e + r)
    const double xC = e * std::sin(th), yC = -e * std::cos(th);
    const double yR = yC + std::sqrt((R + r) * (R + r) - xC * xC);
    const double s = yR - (R - e + r);
    const auto yRof = [&](double t) {
      const double x = e * std::sin(t), y = -e * std::cos(t);
      return y + std::sqrt((R + r) * (R + r) - x * x);
    };
    const double sd = (yRof(th + h) - yRof(th - h)) / (2 * h);
    EXPECT_NEAR(roller_entrainment(w, R - e, r, s, sd, R) / truth, 1.0, 1e-8) << th;
  }
}
