// The one-cam-on-a-compliant-shaft scene of the camshaft tests and its two-degree-of-freedom
// model written out (test_camshaft.cpp, test_camshaft_implicit.cpp).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace camdyn {
namespace camshaft_test {

constexpr double kPi = 3.14159265358979323846;

// An eccentric circle cam (lift X_L(θ) = e(1 + cos θ) for the flat-faced follower) driving
// one rigid follower "f" (mass m on a spring k with preload P to ground) through a cam contact
// with clearance g₀, penalty contact; the cam on station 0 of a one-station shaft of inertia J
// driven by a coupling k_d, c_d from a crank at 42 rev/s, above the jump speed (40.6 rev/s for
// the prescribed cam: m e ω² = P + 2ek). θ₀ = 180°: the start is on the base circle, the
// follower 20 µm above the cam (it falls onto it: an impact and a bounce); it lifts off near
// the nose and lands again (an impact and two bounces) within 0.03 s.
struct TwoDof {
  double R = 0.02, e = 0.004, speed = 42.0, theta0 = kPi;
  double m = 0.1, k = 2000.0, P = 10.0, g0 = 2e-5;
  double kp = 1e7, cp = 400.0;
  double J = 1e-4, kd = 500.0, cd = 0.02;
  std::string model = "penalty";  // event, lee: restitution 0.3
  std::string integrator = "arkode-erk";
  double rtol = 1e-10;
};

inline std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

inline std::string two_dof_toml(const TwoDof& p, bool shaft, double t_end) {
  std::string s = R"(
title = "one cam on a compliant shaft"
[cam]
profile = "circle"
radius = )" + std::to_string(p.R) + R"(
eccentricity = )" + std::to_string(p.e) + R"(
speed_rev_s = )" + std::to_string(p.speed) + R"(
theta0_deg = 180.0
[follower]
kind = "network"
[contact]
model = ")" + p.model + R"("
restitution = )" + (p.model == "penalty" || p.model == "holonomic" ? "0.0" : "0.3") + R"(
penalty_stiffness = )" + std::to_string(p.kp) + R"(
penalty_damping = )" + std::to_string(p.cp) + R"(
tol_u = 1e-9
[solver]
integrator = ")" + p.integrator + R"("
rtol = )" + num(p.rtol) + R"(
atol = 1e-14
[run]
t_end = )" + std::to_string(t_end) + R"(
output_dt = 1e-4
[[nodes]]
name = "f"
mass = )" + std::to_string(p.m) + R"(
[[elements]]
name = "spring"
type = "spring"
nodes = ["f", "ground"]
stiffness = )" + std::to_string(p.k) + R"(
preload = )" + std::to_string(p.P) + R"(
[[contacts]]
name = "cam"
type = "cam"
nodes = ["f"]
clearance = )" + std::to_string(p.g0) + "\n";
  if (shaft)
    s += "[camshaft]\ninertias = [" + std::to_string(p.J) + "]\ncam_stations = [0]\ndrive_stiffness = " +
         std::to_string(p.kd) + "\ndrive_damping = " + std::to_string(p.cd) + "\n";
  return s;
}

// The two-degree-of-freedom model written out: y = (x, ẋ, φ, φ̇),
//   s = −(x + g₀ − e(1 + cos φ)),  ŝ = −(ẋ + e sin φ · φ̇),  F = max(0, k_p s + c_p ŝ) for s > 0,
//   m ẍ = −P − k x + F,   J φ̈ = k_d(ω t + θ₀ − φ) + c_d(ω − φ̇) − (∂X_L/∂φ) F,  ∂X_L/∂φ = −e sin φ.
struct Model {
  TwoDof p;
  double omega() const { return 2 * kPi * p.speed; }
  double force(const Eigen::Vector4d& y) const {
    const double s = -(y[0] + p.g0 - p.e * (1 + std::cos(y[2])));
    const double sd = -(y[1] + p.e * std::sin(y[2]) * y[3]);
    if (s <= 0) return 0.0;
    return std::max(0.0, p.kp * s + p.cp * sd);
  }
  Eigen::Vector4d rhs(double t, const Eigen::Vector4d& y) const {
    const double F = force(y);
    Eigen::Vector4d d;
    d[0] = y[1];
    d[1] = (-p.P - p.k * y[0] + F) / p.m;
    d[2] = y[3];
    d[3] = (p.kd * (omega() * t + p.theta0 - y[2]) + p.cd * (omega() - y[3]) + p.e * std::sin(y[2]) * F) / p.J;
    return d;
  }
  double penetration(const Eigen::Vector4d& y) const { return -(y[0] + p.g0 - p.e * (1 + std::cos(y[2]))); }
  Eigen::Vector4d rk4(double t, const Eigen::Vector4d& y, double dt) const {
    const Eigen::Vector4d k1 = rhs(t, y), k2 = rhs(t + dt / 2, y + dt / 2 * k1),
                          k3 = rhs(t + dt / 2, y + dt / 2 * k2), k4 = rhs(t + dt, y + dt * k3);
    return y + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  // classic RK4 at a fixed step h from (t0, y) to t1; a step across the contact's closing
  // (the damper's force jumps there) is cut at the crossing, located by bisection
  Eigen::Vector4d advance(double t0, Eigen::Vector4d y, double t1, double h) const {
    const int n = int(std::ceil((t1 - t0) / h));
    const double dt = (t1 - t0) / n;
    for (int i = 0; i < n; ++i) {
      const double t = t0 + i * dt;
      Eigen::Vector4d y1 = rk4(t, y, dt);
      if (penetration(y) <= 0 && penetration(y1) > 0) {
        double lo = 0, hi = dt;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          (penetration(rk4(t, y, mid)) > 0 ? hi : lo) = mid;
        }
        const Eigen::Vector4d yc = rk4(t, y, hi);
        y1 = rk4(t + hi, yc, dt - hi);
      }
      y = y1;
    }
    return y;
  }
};

}  // namespace camshaft_test
}  // namespace camdyn
