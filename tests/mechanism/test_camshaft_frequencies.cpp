// The natural frequencies of a camshaft with its trains attached (held_frequencies_hz,
// src/mechanism/camshaft.hpp; issue 40 item 4) against the closed form: a two-inertia shaft
// (J₁ at the drive, k_d to the crank held fixed, k to J₂) whose cam on station 1 holds a rigid
// follower (mass m on a spring k_f) at the shaft angle φ. Held, the follower turns with the
// cam, x = X_L(φ₂) − g₀: linearised it adds m X_L′² to J₂'s inertia and k_f X_L′² + X_L″F to
// its stiffness (F the contact force on the cam's curvature), so
//   det([[k_d + k, −k], [−k, k + k_f X′² + X″F]] − ω² diag(J₁, J₂ + m X′²)) = 0,
// with the eccentric circle cam's X_L = e(1 + cos φ): X′ = −e sin φ, X″ = −e cos φ.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "camdyn/scene.hpp"
#include "contact/camshaft_test_support.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {
namespace {

using camshaft_test::kPi;
using camshaft_test::num;
using camshaft_test::TwoDof;
using camshaft_test::two_dof_toml;

TEST(CamshaftFrequencies, HeldFollowerAddsItsMassAndStiffnessThroughTheCam) {
  TwoDof p;
  const double J1 = 3e-4, J2 = 1e-4, k = 2e3, kd = 800.0, F = 25.0;
  const Scene sc = parse_scene(two_dof_toml(p, false, 0.01) + "[camshaft]\ninertias = [" + num(J1) + ", " + num(J2) +
                                   "]\nstiffnesses = [" + num(k) + "]\ncam_stations = [1]\ndrive_stiffness = " +
                                   num(kd) + "\n",
                               "<test>");
  const Mechanism mech(sc);
  const CamShaft* cs = mech.camshaft();
  ASSERT_NE(cs, nullptr);
  for (double phi : {0.7, 2.0, 4.1}) {
    Eigen::VectorXd q = mech.q0();
    q[cs->station_dof(1)] = phi;
    std::vector<double> Fv(std::size_t(mech.m()), 0.0);
    Fv[0] = F;
    const std::vector<double> f = held_frequencies_hz(mech, q.data(), {0}, Fv.data());
    ASSERT_EQ(f.size(), 2u);
    const double X1 = -p.e * std::sin(phi), X2 = -p.e * std::cos(phi);
    const double M11 = J1, M22 = J2 + p.m * X1 * X1, K11 = kd + k, K12 = -k, K22 = k + p.k * X1 * X1 + X2 * F;
    const double a = M11 * M22, b = -(K11 * M22 + K22 * M11), c = K11 * K22 - K12 * K12;
    const double disc = std::sqrt(b * b - 4 * a * c);
    const double w1 = std::sqrt((-b - disc) / (2 * a)) / (2 * kPi), w2 = std::sqrt((-b + disc) / (2 * a)) / (2 * kPi);
    // measured: 4e-16 relative at most
    EXPECT_NEAR(f[0], w1, 1e-9 * w1) << "phi " << phi;
    EXPECT_NEAR(f[1], w2, 1e-9 * w2) << "phi " << phi;
  }
  // nothing held: the follower's own mode sqrt(k_f/m) joins the shaft's two
  Eigen::VectorXd q = mech.q0();
  const std::vector<double> Fv(std::size_t(mech.m()), 0.0);
  const std::vector<double> f = held_frequencies_hz(mech, q.data(), {}, Fv.data());
  ASSERT_EQ(f.size(), 3u);
  const double wf = std::sqrt(p.k / p.m) / (2 * kPi);
  double closest = INFINITY;
  for (double x : f) closest = std::min(closest, std::abs(x - wf));
  EXPECT_LT(closest, 1e-9 * wf);
}

}  // namespace
}  // namespace camdyn
