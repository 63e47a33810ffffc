// The held phase by coordinate partitioning (src/held_phase.hpp) against a second
// formulation of the same constraint: the contact force as the Lagrange multiplier of
// the full model's acceleration level, F = (Ẍ_C − e₀ᵀM⁻¹(f₀ − Kq − Cv)) / M*, at states with
// node 0 on the cam, and the free part's acceleration against the full model's under F.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>

#include "camdyn/model.hpp"
#include "held_phase.hpp"

namespace camdyn {
namespace {

struct Variant {
  const char* name;
  FollowerKind kind;
  MassMatrixKind mass;
  double alpha, beta;
};

class HeldPhaseTest : public ::testing::TestWithParam<Variant> {};

TEST_P(HeldPhaseTest, ReactionIsTheFullModelsMultiplier) {
  const Variant v = GetParam();
  Scene s = default_scene();
  s.follower.kind = v.kind;
  s.follower.elements = 12;
  s.follower.mass_matrix = v.mass;
  s.follower.rayleigh_alpha = v.alpha;
  s.follower.rayleigh_beta = v.beta;
  if (v.kind == FollowerKind::Rigid) s.follower.damping = v.alpha;
  const auto model = build_model(s);
  const detail::HeldPhase held(*model);
  const int n = model->n(), r = n - 1;
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    CamMotion c{};
    c.X = model->initial_displacement()[0] + 1e-4 * U(gen);
    c.Xdot = 0.3 * U(gen);
    c.Xddot = 50.0 * U(gen);
    Eigen::VectorXd q = model->initial_displacement(), vel(n);
    for (int i = 0; i < n; ++i) {
      q[i] += 1e-5 * U(gen);
      vel[i] = 0.1 * U(gen);
    }
    q[0] = c.X;
    vel[0] = c.Xdot;
    // the full model's multiplier and its acceleration under it; the round-off scale is
    // that of the terms that cancel in e₀ᵀM⁻¹Kq = Σᵢ (KM⁻¹e₀)ᵢ qᵢ (q ≈ 2 m on a stiff bar)
    Eigen::VectorXd rhs(n), a(n), e0 = Eigen::VectorXd::Zero(n), col(n), aq(n);
    e0[0] = 1.0;
    model->solve_mass(e0.data(), col.data());
    if (model->rigid())
      aq[0] = model->k_rigid() * col[0];
    else
      aq = model->K() * col;
    const double S = aq.cwiseAbs().dot(q.cwiseAbs()) + std::abs(c.Xddot);
    model->internal_force(q.data(), vel.data(), rhs.data());
    const double F = (c.Xddot - model->contact_acceleration(q.data(), vel.data(), 0.0)) / model->mstar();
    rhs[0] += F;
    model->solve_mass(rhs.data(), a.data());
    EXPECT_NEAR(a[0], c.Xddot, 1e-12 * S);
    double Fh;
    if (r == 0) {
      ASSERT_FALSE(held.free_part());
      Fh = held.reaction(c, nullptr, nullptr, nullptr);
    } else {
      // the free part's acceleration under the cam's load
      const FollowerModel& h = *held.free_part();
      ASSERT_EQ(h.n(), r);
      Eigen::VectorXd qr = q.tail(r), vr = vel.tail(r), hr(r), ar(r);
      h.internal_force(qr.data(), vr.data(), hr.data());
      hr[0] += held.coupling_load(c);
      h.solve_mass(hr.data(), ar.data());
      EXPECT_LT((ar - a.tail(r)).cwiseAbs().maxCoeff(), 1e-12 * S) << "free-part acceleration";
      Fh = held.reaction(c, qr.data(), vr.data(), ar.data());
    }
    EXPECT_NEAR(Fh, F, 1e-12 * S / model->mstar()) << "trial " << trial << ", |F| " << F;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Followers, HeldPhaseTest,
    ::testing::Values(Variant{"rigid", FollowerKind::Rigid, MassMatrixKind::Consistent, 0, 0},
                      Variant{"rigid_damped", FollowerKind::Rigid, MassMatrixKind::Consistent, 20, 0},
                      Variant{"bar_consistent", FollowerKind::ElasticBar, MassMatrixKind::Consistent, 0, 0},
                      Variant{"bar_lumped", FollowerKind::ElasticBar, MassMatrixKind::Lumped, 0, 0},
                      Variant{"bar_rayleigh", FollowerKind::ElasticBar, MassMatrixKind::Consistent, 30, 1e-6}),
    [](const ::testing::TestParamInfo<Variant>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace camdyn
