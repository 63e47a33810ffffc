// A rigid or elastic_bar follower's matrices (src/mechanism/follower_matrices.hpp) and the
// one-contact Mechanism built from them, integrated by the mechanism's engines
// (src/engine/ode_engine.hpp) with no contact force, against independent truth:
//   rigid mass–spring (closed-form harmonic motion, convergence orders, CVODE's error
//   proportional to its tolerance), bar free vibration (generalised eigenvalues of (K, M)),
//   the mesh's convergence to the continuum bar at rate h², consistent vs lumped mass
//   bounds, M* = (M⁻¹)₀₀, the preloaded initial shape, the builder's description.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "camdyn/scene.hpp"
#include "camdyn/simulator.hpp"
#include "engine/ode_engine.hpp"
#include "mechanism/follower_matrices.hpp"
#include "mechanism/mechanism.hpp"

namespace camdyn {
namespace {

Scene rigid_scene(Integrator integ) {
  Scene s;  // paper cam, rigid m = 1, k = 500, δ₀ = 7
  s.solver.integrator = integ;
  return s;
}

Scene bar_scene(Integrator integ, int elements, MassMatrixKind mk) {
  Scene s;
  s.follower.kind = FollowerKind::ElasticBar;
  s.follower.elements = elements;
  s.follower.mass_matrix = mk;
  s.solver.integrator = integ;
  return s;
}

// The follower as a one-contact Mechanism and an engine on q̇ = v, M v̇ = f₀ − Kq − Cv
// (no contact force), as the contact methods build it (src/contact/contact_run.cpp).
struct FreeFollower {
  std::shared_ptr<const Mechanism> mech;
  std::unique_ptr<OdeEngine> engine;
};
FreeFollower free_follower(const Scene& s, bool trial) {
  FreeFollower f;
  f.mech = std::make_shared<const Mechanism>(s);
  const Mechanism* m = f.mech.get();
  const int n = m->n();
  OdeSystem sys;
  sys.size = 2 * n;
  sys.rhs = [m, n](double t, const double* y, double* yd) {
    std::copy(y + n, y + 2 * n, yd);
    m->acceleration(t, y, y + n, Eigen::VectorXd(), yd + n);
  };
  auto sn = std::make_shared<SparseNewton>();
  sn->M = &m->M();
  sn->K = &m->K();
  sn->C = m->damped() ? &m->C() : nullptr;
  sn->T = m->T();
  sys.newton = sn;
  sys.linear = true;
  // cvode-bdf: the methods' order limits on an elastic follower (cvode_bdf_order,
  // src/contact/methods/bdf_order.hpp): BDF ≤ 2, up to 5 with stability-limit detection at
  // rtol ≤ 1e-8.
  if (n > 1) {
    const bool tight = s.solver.rtol <= 1e-8;
    sys.max_order = tight ? 5 : 2;
    sys.stability_limit_detection = tight;
  }
  f.engine = OdeEngine::make(s.solver.integrator, s.solver, sys, trial);
  return f;
}

// Closed form for m q̈ = f₀ − k q: q = q_eq + (q₀ − q_eq) cos ωt + (v₀/ω) sin ωt.
double harmonic(double q0, double v0, double qeq, double w, double t) {
  return qeq + (q0 - qeq) * std::cos(w * t) + v0 / w * std::sin(w * t);
}

// Fixed-step trial steps for the rigid follower; max error over [0, T].
double rigid_error_fixed(Integrator integ, int nsteps, double T) {
  const Scene s = rigid_scene(integ);
  FreeFollower f = free_follower(s, true);
  const FollowerMatrices fm = follower_matrices(s);
  Eigen::VectorXd y(2), y1(2);
  const double q0 = fm.q0[0], v0 = 0.3;
  y << q0, v0;
  const double h = T / nsteps;
  const double w = std::sqrt(500.0), qeq = fm.f0[0] / 500.0;
  double err = 0;
  for (int i = 0; i < nsteps; ++i) {
    f.engine->step(i * h, y, h, y1);
    y = y1;
    err = std::max(err, std::abs(y[0] - harmonic(q0, v0, qeq, w, (i + 1) * h)));
  }
  return err;
}

// Least-squares slope of log(error) against log(h) over a step-halving sequence.
double fitted_order(Integrator integ, std::vector<int> ns) {
  const double T = 0.5;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int n : ns) {
    const double x = std::log(T / n), y = std::log(rigid_error_fixed(integ, n, T));
    std::printf("  %s n = %d: max error %.3e\n", to_string(integ), n, std::exp(y));
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double m = double(ns.size());
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

TEST(FollowerEngines, RigidHarmonicConvergenceOrderERK) {
  // Dormand–Prince 5(4): global error ∝ h⁵.
  const double order = fitted_order(Integrator::ArkodeErk, {80, 160, 320, 640});
  std::printf("ERK fitted order %.2f\n", order);
  EXPECT_NEAR(order, 5.0, 0.5);
}

TEST(FollowerEngines, RigidHarmonicConvergenceOrderDIRK) {
  // SDIRK 5-stage, order 4: global error ∝ h⁴.
  const double order = fitted_order(Integrator::ArkodeDirk, {80, 160, 320, 640});
  std::printf("DIRK fitted order %.2f\n", order);
  EXPECT_NEAR(order, 4.0, 0.3);
}

TEST(FollowerEngines, RigidHarmonicCvodeToleranceProportionality) {
  // CVODE controls its own error (native stepping); the global error must fall in
  // proportion to the tolerance (slope ≈ 1 on log–log), and match the closed form.
  const double T = 0.5;
  std::vector<double> tols{1e-6, 1e-8, 1e-10}, errs;
  for (double tol : tols) {
    Scene s = rigid_scene(Integrator::CvodeBdf);
    s.solver.rtol = tol;
    s.solver.atol = tol * 1e-2;
    FreeFollower f = free_follower(s, false);
    const FollowerMatrices fm = follower_matrices(s);
    Eigen::VectorXd y(2), y1(2);
    const double q0 = fm.q0[0];
    y << q0, 0.3;
    f.engine->reinit(0.0, y);
    double t = 0;
    while (t < T) t = f.engine->advance(T, y1);
    const double qeq = fm.f0[0] / 500.0;
    errs.push_back(std::abs(y1[0] - harmonic(q0, 0.3, qeq, std::sqrt(500.0), T)));
  }
  const double slope = std::log10(errs[0] / errs[2]) / std::log10(tols[0] / tols[2]);
  std::printf("CVODE errors %.3e %.3e %.3e, slope %.2f\n", errs[0], errs[1], errs[2], slope);
  EXPECT_GT(slope, 0.7);
  EXPECT_LT(slope, 1.4);
  EXPECT_LT(errs[2], 1e-7);
}

// Free vibration of the bar in mode k from a modal initial shape, F = 0. The modal
// coordinate η = φᵀM(q − q_eq) must oscillate at ω_k (generalised eigenvalue of (K, M),
// computed densely here). 10 elements: the same physics as 40, a few seconds in all
// (measured: relative error ≤ 5e-9 on arkode-erk and arkode-dirk, ≤ 5.6e-9 on cvode-bdf).
double simulated_frequency(Integrator integ, MassMatrixKind mk, int mode, double* exact) {
  Scene s = bar_scene(integ, 10, mk);
  if (integ == Integrator::CvodeBdf) {
    // CVODE natively under its own error control, sampled every h, with the methods' order
    // policy (at rtol ≤ 1e-8 up to BDF5 with stability-limit detection), tolerances above the
    // round-off floor of the nodal accelerations. (Trial steps of h restart CVODE at order 1
    // every step: mode 1 was 3e-6 off that way.)
    s.solver.rtol = 1e-10;
    s.solver.atol = 1e-9;
  }
  const FollowerMatrices fm = follower_matrices(s);
  const bool native = integ == Integrator::CvodeBdf;
  FreeFollower f = free_follower(s, !native);
  const int n = fm.n;
  const Eigen::MatrixXd K(fm.K), M(fm.M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  const double w = std::sqrt(es.eigenvalues()[mode]);
  *exact = w;
  const Eigen::VectorXd phi = es.eigenvectors().col(mode);
  const Eigen::VectorXd qeq = K.ldlt().solve(fm.f0);
  Eigen::VectorXd y(2 * n), y1(2 * n);
  y.head(n) = qeq + 1e-3 * phi / phi.cwiseAbs().maxCoeff();
  y.tail(n).setZero();
  const double period = 2 * M_PI / w;
  // Explicit steps must respect the stability limit of the mesh (DP5: ω_max h ≲ 1.5 on the imaginary axis).
  const double h_stable = 1.0 / std::sqrt(es.eigenvalues()[n - 1]);
  const int per = integ == Integrator::ArkodeErk ? std::max(400, int(std::ceil(period / h_stable))) : 400;
  const int nper = 4;
  const double h = period / per;
  const Eigen::VectorXd Mphi = M * phi;
  double t = 0, eta_prev = Mphi.dot(y.head(n) - qeq);
  std::vector<double> crossings;
  if (native) f.engine->reinit(0.0, y);
  for (int i = 0; i < per * nper; ++i) {
    if (native) {
      double tr = t;
      while (tr < t + h) tr = f.engine->advance(t + h, y1);
    } else {
      f.engine->step(t, y, h, y1);
    }
    const double eta = Mphi.dot(y1.head(n) - qeq);
    // linear interpolation at the crossing (an inflection point of η: error O(h³))
    if ((eta_prev > 0) != (eta > 0)) crossings.push_back(t + h * eta_prev / (eta_prev - eta));
    eta_prev = eta;
    y = y1;
    t += h;
  }
  const double half_periods = double(crossings.size() - 1);
  return M_PI * half_periods / (crossings.back() - crossings.front());
}

TEST(FollowerEngines, BarModalFrequenciesMatchEigenvalues) {
  for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    for (MassMatrixKind mk : {MassMatrixKind::Consistent, MassMatrixKind::Lumped}) {
      for (int mode = 0; mode < 3; ++mode) {
        double exact = 0;
        const double w = simulated_frequency(integ, mk, mode, &exact);
        const double rel = std::abs(w / exact - 1.0);
        std::printf("%s %s mode %d: omega %.9g exact %.9g rel %.2e\n", to_string(integ), to_string(mk), mode + 1,
                    w, exact, rel);
        EXPECT_LT(rel, 1e-6) << to_string(integ) << " " << to_string(mk) << " mode " << mode + 1;
      }
    }
  }
}

// Continuum bar, free at x = 0, spring k at x = L: u = cos βx with
//   −EA β sin βL + k cos βL = 0,  ω = β c,  c = √(E/ρ).
double continuum_omega(int mode, double E, double A, double L, double m, double k) {
  const double EA = E * A, c = std::sqrt(E / (m / (A * L)));
  // Mode j (0-based) has βL in (jπ, (j + ½)π): bisection on g(x) = EA/L x sin x − k cos x.
  auto g = [&](double x) { return EA / L * x * std::sin(x) - k * std::cos(x); };
  double a = mode * M_PI + 1e-12, b = mode * M_PI + M_PI / 2 - 1e-12;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (a + b);
    if ((g(a) > 0) == (g(mid) > 0))
      a = mid;
    else
      b = mid;
  }
  return 0.5 * (a + b) / L * c;
}

TEST(FollowerMatrices, MeshConvergenceToContinuumAtRateH2AndMassBounds) {
  const double E = 1e7, A = 3, L = 24, m = 1, k = 500;
  for (int mode = 1; mode <= 3; ++mode) {
    const double exact = continuum_omega(mode, E, A, L, m, k);
    double err_prev = 0;
    for (int N : {40, 80, 160}) {
      double w[2];
      int i = 0;
      for (MassMatrixKind mk : {MassMatrixKind::Consistent, MassMatrixKind::Lumped}) {
        const FollowerMatrices fm = follower_matrices(bar_scene(Integrator::ArkodeErk, N, mk));
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(fm.K), Eigen::MatrixXd(fm.M));
        w[i++] = std::sqrt(es.eigenvalues()[mode]);
      }
      // FE theory: consistent mass overestimates, lumped mass underestimates.
      EXPECT_GT(w[0], exact) << "mode " << mode << " N " << N;
      EXPECT_LT(w[1], exact) << "mode " << mode << " N " << N;
      const double err = w[0] / exact - 1.0;
      if (err_prev > 0) {
        const double ratio = err_prev / err;
        std::printf("mode %d N %d consistent rel err %.3e ratio %.3f\n", mode, N, err, ratio);
        EXPECT_NEAR(ratio, 4.0, 0.3) << "h² convergence, mode " << mode;
      }
      err_prev = err;
    }
  }
}

TEST(FollowerMatrices, MstarEqualsInverseMassColumn) {
  const Scene s = bar_scene(Integrator::ArkodeErk, 40, MassMatrixKind::Consistent);
  const Eigen::MatrixXd Minv = Eigen::MatrixXd(follower_matrices(s).M).inverse();
  EXPECT_NEAR(Mechanism(s).W()(0, 0), Minv(0, 0), 1e-12 * Minv(0, 0));
  EXPECT_DOUBLE_EQ(Mechanism(rigid_scene(Integrator::ArkodeErk)).W()(0, 0), 1.0);
}

TEST(FollowerMatrices, InitialShapeIsStaticEquilibriumUnderPreload) {
  const FollowerMatrices fm = follower_matrices(bar_scene(Integrator::ArkodeErk, 40, MassMatrixKind::Consistent));
  const Eigen::VectorXd r = fm.f0 - fm.K * fm.q0;
  // Only the contact node is loaded: r = −k δ₀ e₀ (balanced by the contact force).
  EXPECT_NEAR(r[0], -500.0 * 7.0, 1e-6);
  EXPECT_LT(r.tail(r.size() - 1).cwiseAbs().maxCoeff(), 1e-6);
}

// The builder builds only what the scene asks for.
struct DescCase {
  const char* name;
  Scene scene;
  int unknowns;
  const char* mass;
  bool sparse;
  const char* linear_solver;
  bool damping;
  const char* contact;
};

TEST(FollowerMatrices, DescriptionListsOnlyRequestedEffects) {
  std::vector<DescCase> cases;
  {
    Scene s;
    cases.push_back({"rigid erk", s, 2, "scalar", false, "none", false, "unilateral"});
  }
  {
    Scene s;
    s.solver.integrator = Integrator::CvodeBdf;
    s.follower.damping = 2.0;
    cases.push_back({"rigid damped cvode", s, 2, "scalar", false, "dense", true, "unilateral"});
  }
  {
    Scene s = bar_scene(Integrator::ArkodeDirk, 40, MassMatrixKind::Consistent);
    cases.push_back({"bar dirk", s, 82, "consistent", true, "klu", false, "unilateral"});
  }
  {
    Scene s = bar_scene(Integrator::CvodeBdf, 3, MassMatrixKind::Lumped);
    s.follower.rayleigh_beta = 1e-5;
    s.contact.separation = false;
    cases.push_back({"small lumped bar cvode", s, 8, "lumped", true, "dense", true, "holonomic"});
  }
  for (const DescCase& c : cases) {
    const FollowerMatrices fm = follower_matrices(c.scene);
    const ModelDescription& d = fm.description;
    EXPECT_EQ(d.unknowns, c.unknowns) << c.name;
    EXPECT_EQ(d.mass, c.mass) << c.name;
    EXPECT_EQ(d.sparse, c.sparse) << c.name;
    EXPECT_EQ(d.linear_solver, c.linear_solver) << c.name;
    EXPECT_EQ(d.damping, c.damping) << c.name;
    EXPECT_EQ(d.contact, c.contact) << c.name;
    const bool has_damp_term = std::find_if(d.rhs_terms.begin(), d.rhs_terms.end(), [](const std::string& t) {
                                 return t.find("damp") != std::string::npos;
                               }) != d.rhs_terms.end();
    EXPECT_EQ(has_damp_term, c.damping) << c.name;
    if (c.scene.follower.kind == FollowerKind::Rigid) {
      EXPECT_EQ(fm.M.rows(), 1) << "rigid: 1 × 1 matrices, no mesh";
      EXPECT_EQ(fm.M.nonZeros(), 1);
    }
    EXPECT_EQ(fm.C.nonZeros() > 0, c.damping) << c.name;
  }
}


// The full report lists the assembled network, and only what the scene asks for.
TEST(NetworkDescription, ListsTheAssembledNetworkOnly) {
  const Scene s = load_scene_file(std::string(CAMDYN_SOURCE_DIR) + "/examples/ohv_pushrod_train.toml");
  const Simulator sim(s);
  const ModelDescription& d = sim.description();
  EXPECT_EQ(d.follower, "network");
  // lifter, rocker_in, valve + 3 inside pushrod nodes + 6 spring masses (rocker_tip is the
  // lever's output, not an unknown)
  EXPECT_EQ(d.nodes, 12);
  EXPECT_EQ(d.unknowns, 24);
  ASSERT_EQ(d.network.size(), 7u);  // 4 elements, 3 contacts
  EXPECT_NE(d.network[1].find("lever 'rocker'"), std::string::npos) << d.network[1];
  EXPECT_NE(d.network[4].find("contact 'cam'"), std::string::npos) << d.network[4];
  EXPECT_EQ(d.rhs_terms, (std::vector<std::string>{"inertia", "stiffness", "preload", "damping", "levers",
                                                   "contacts"}));
  EXPECT_NE(d.ToString().find("contact 'seat' (stop, stop below valve"), std::string::npos) << d.ToString();
  // an undamped network without preload or levers has none of those terms
  Scene bare = s;
  bare.network.elements.erase(bare.network.elements.begin() + 1);  // the lever
  bare.network.nodes.erase(bare.network.nodes.begin() + 2);        // rocker_tip
  bare.network.contacts.erase(bare.network.contacts.begin() + 1);  // the lash
  for (ElementSpec& e : bare.network.elements) {
    e.preload = 0;
    e.damping = 0;
    e.rayleigh_beta = 0;
  }
  const Simulator sb(bare);
  EXPECT_EQ(sb.description().rhs_terms, (std::vector<std::string>{"inertia", "stiffness", "contacts"}));
}

}  // namespace
}  // namespace camdyn
