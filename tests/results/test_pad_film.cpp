// The oil film at the flat pad of an oscillating follower (src/results/run_analysis.cpp
// pad_entrainment): the entrainment velocity against the contact point's travel over the
// cam and along the pad computed here from a brute-force tangency, and the film against
// Hamrock's formula written out at one state.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "camdyn/cam.hpp"
#include "camdyn/scene.hpp"
#include "results/run_analysis.hpp"

using namespace camdyn;

namespace {
constexpr double kPi = 3.14159265358979323846;

// The cam: a circle (R = 20 mm, eccentricity 5 mm) under a finger's flat pad (pivot at
// (40, 45) mm, pad 4 mm off the pivot line, valve arm 45 mm), mm–N–s units.
const char* kScene = R"(
[cam]
profile = "circle"
radius = 20.0
eccentricity = 5.0
follower_motion = "oscillating"
follower_face = "flat"
pivot_x = 40.0
pivot_y = 45.0
pad_offset = 4.0
valve_arm = 45.0
width = 10.0
speed_rev_s = 50.0
[lubricant]
viscosity = 1e-8
pressure_viscosity = 0.02
roughness = 2e-4
)";
}  // namespace

TEST(OilFilm, OscillatingFlatPadEntrainmentFromTheContactPointsTravel) {
  const Scene sc = parse_scene(kScene, "<test>");  // accepted now (it was a SceneError)
  const Cam cam(sc.cam);
  const detail::RunAnalysis an(sc, {"cam"}, {}, cam.lift(), &cam);
  const double R = 20, e = 5, f = 4, px = 40, py = 45, lv = 45, w = 2 * kPi * 50.0;
  // Brute force: the arm angle α at which the pad line {Z : n(α)·(Z − P) = f} is tangent to
  // the cam circle (centre K = Rot(θ)(e, 0)) on the side facing K (bisection); Q = K + R n.
  auto alpha = [&](double th) {
    const double kx = e * std::cos(th), ky = e * std::sin(th);
    const double beta = std::atan2(ky - py, kx - px);
    auto sd = [&](double a) { return -std::sin(a) * (kx - px) + std::cos(a) * (ky - py) - f + R; };
    double lo = beta - kPi / 2 + 1e-9, hi = beta + kPi / 2 - 1e-9, flo = sd(lo);
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
      const double mid = 0.5 * (lo + hi), fm = sd(mid);
      if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
      else hi = mid;
    }
    return 0.5 * (lo + hi);
  };
  auto Q = [&](double th, double* qx, double* qy) {
    const double a = alpha(th);
    *qx = e * std::cos(th) - R * std::sin(a);
    *qy = e * std::sin(th) + R * std::cos(a);
  };
  // the point's coordinate along the pad, and its position in the cam's frame
  auto along_pad = [&](double th) {
    double qx, qy;
    Q(th, &qx, &qy);
    const double a = alpha(th);
    return std::cos(a) * (qx - px) + std::sin(a) * (qy - py);
  };
  auto cam_x = [&](double th) {
    double qx, qy;
    Q(th, &qx, &qy);
    return std::cos(th) * qx + std::sin(th) * qy;
  };
  auto cam_y = [&](double th) {
    double qx, qy;
    Q(th, &qx, &qy);
    return -std::sin(th) * qx + std::cos(th) * qy;
  };
  auto d1 = [](const std::function<double(double)>& g, double x) {
    const double h = 1e-3;
    return (45 * (g(x + h) - g(x - h)) - 9 * (g(x + 2 * h) - g(x - 2 * h)) + (g(x + 3 * h) - g(x - 3 * h))) / (60 * h);
  };
  double worst = 0, worst_rigid = 0;
  for (int i = 0; i < 36; ++i) {
    const double th = 2 * kPi * (i + 0.37) / 36;
    const double a = alpha(th), ux = std::cos(a), uy = std::sin(a);
    // the surfaces' velocities relative to the contact point, along the pad u
    const double dcx = d1(cam_x, th), dcy = d1(cam_y, th);
    const double u_cam = -w * ((std::cos(th) * dcx - std::sin(th) * dcy) * ux + (std::sin(th) * dcx + std::cos(th) * dcy) * uy);
    const double u_pad = -w * d1(along_pad, th);
    // Their difference is the sliding speed of the two bodies' material points at Q: the
    // cam's ω J Q and the pad's α̇ J (Q − P) (rigid-body kinematics, a separate check).
    double qx, qy;
    Q(th, &qx, &qy);
    const double da = d1(alpha, th);
    const double slide = (w * -qy - w * da * -(qy - py)) * ux + (w * qx - w * da * (qx - px)) * uy;
    worst_rigid = std::max(worst_rigid, std::abs((u_cam - u_pad) - slide) / (std::abs(slide) + w * R));
    const double ref = std::abs(0.5 * (u_cam + u_pad));
    worst = std::max(worst, std::abs(an.entrainment(cam.evaluate(th), w) - ref) / (w * R));
  }
  // Measured: 2.9e-10 of ωR (the library's central differences of δθ = 1e-6 against this
  // 6th-order stencil); the rigid-body identity 5.2e-13.
  EXPECT_LT(worst, 1e-8);
  EXPECT_LT(worst_rigid, 1e-10);

  // The film at one state: Hamrock's h_min = R_x 1.714 W′^−0.128 U^0.694 G^0.568 with the
  // load per width N/w (N = F ℓ_v/a, a = |(Q − P)·u| the normal's moment arm), R_x = R (the
  // pad is flat), E′ = E/(1 − ν²) (both steel), at θ = 1.1 and F = 300 N on X.
  const double th = 1.1, F = 300, width = 10, E = 2.1e5, nu = 0.3, eta = 1e-8, xi = 0.02;
  const double a = alpha(th);
  double qx, qy;
  Q(th, &qx, &qy);
  const double arm = std::abs(std::cos(a) * (qx - px) + std::sin(a) * (qy - py));
  const double N = F * lv / arm, Ep = E / (1 - nu * nu);
  const double dcx = d1(cam_x, th), dcy = d1(cam_y, th);
  const double ut = std::abs(0.5 * (-w * ((std::cos(th) * dcx - std::sin(th) * dcy) * std::cos(a) +
                                         (std::sin(th) * dcx + std::cos(th) * dcy) * std::sin(a)) -
                                    w * d1(along_pad, th)));
  const double Wp = N / width / (Ep * R), U = eta * ut / (Ep * R), G = xi * Ep;
  const double h = R * 1.714 * std::pow(Wp, -0.128) * std::pow(U, 0.694) * std::pow(G, 0.568);
  const double got = an.film(cam.evaluate(th), w, F);
  // Measured 2.1e-11 relative (the entrainment's differences, to the power 0.694).
  EXPECT_NEAR(got, h, 1e-8 * h) << "film " << got << " vs " << h;
}
