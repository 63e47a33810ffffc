// Follower models and integrator engines against independent truth:
//   rigid mass–spring (closed-form harmonic motion, convergence orders),
//   bar free vibration (generalised eigenvalues of (K, M), continuum limit at rate h²),
//   consistent vs lumped mass bounds, the model builder's own description.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "camdyn/model.hpp"
#include "camdyn/scene.hpp"
#include "legacy/engine.hpp"

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

// Closed form for m q̈ = f₀ − k q: q = q_eq + (q₀ − q_eq) cos ωt + (v₀/ω) sin ωt.
double harmonic(double q0, double v0, double qeq, double w, double t) {
  return qeq + (q0 - qeq) * std::cos(w * t) + v0 / w * std::sin(w * t);
}

// Fixed-step trial steps (no contact force) for the rigid follower; max error over [0, T].
double rigid_error_fixed(Integrator integ, int nsteps, double T) {
  Scene s = rigid_scene(integ);
  auto model = build_model(s);
  auto eng = make_engine(model, s.solver, s.contact.model == ContactModel::Lee, s.contact.tol_u);  // "lee" → trial steps; no contact force
  Eigen::VectorXd y(2), y1(2);
  const double q0 = model->initial_displacement()[0], v0 = 0.3;
  y << q0, v0;
  const double h = T / nsteps;
  const double w = std::sqrt(500.0), qeq = model->f0()[0] / 500.0;
  double err = 0;
  for (int i = 0; i < nsteps; ++i) {
    eng->step(i * h, y, h, y1);
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

TEST(Engines, RigidHarmonicConvergenceOrderERK) {
  // Dormand–Prince 5(4): global error ∝ h⁵.
  const double order = fitted_order(Integrator::ArkodeErk, {80, 160, 320, 640});
  std::printf("ERK fitted order %.2f\n", order);
  EXPECT_NEAR(order, 5.0, 0.5);
}

TEST(Engines, RigidHarmonicConvergenceOrderDIRK) {
  // SDIRK 5-stage, order 4: global error ∝ h⁴.
  const double order = fitted_order(Integrator::ArkodeDirk, {80, 160, 320, 640});
  std::printf("DIRK fitted order %.2f\n", order);
  EXPECT_NEAR(order, 4.0, 0.3);
}

TEST(Engines, RigidHarmonicCvodeToleranceProportionality) {
  // CVODE controls its own error inside each outer step; the global error must fall in
  // proportion to the tolerance (slope ≈ 1 on log–log), and match the closed form.
  const double T = 0.5;
  std::vector<double> tols{1e-6, 1e-8, 1e-10}, errs;
  for (double tol : tols) {
    Scene s = rigid_scene(Integrator::CvodeBdf);
    s.solver.rtol = tol;
    s.solver.atol = tol * 1e-2;
    auto model = build_model(s);
    auto eng = make_engine(model, s.solver, s.contact.model == ContactModel::Lee, s.contact.tol_u);  // no contact force
    Eigen::VectorXd y(2), y1(2);
    const double q0 = model->initial_displacement()[0];
    y << q0, 0.3;
    double t = 0;
    const int n = 50;
    for (int i = 0; i < n; ++i) {
      eng->step(t, y, T / n, y1);
      y = y1;
      t += T / n;
    }
    const double qeq = model->f0()[0] / 500.0;
    errs.push_back(std::abs(y[0] - harmonic(q0, 0.3, qeq, std::sqrt(500.0), T)));
  }
  const double slope = std::log10(errs[0] / errs[2]) / std::log10(tols[0] / tols[2]);
  std::printf("CVODE errors %.3e %.3e %.3e, slope %.2f\n", errs[0], errs[1], errs[2], slope);
  EXPECT_GT(slope, 0.7);
  EXPECT_LT(slope, 1.4);
  EXPECT_LT(errs[2], 1e-7);
}

// Free vibration of the bar in mode k from a modal initial shape, F = 0. The modal
// coordinate η = φᵀM(q − q_eq) must oscillate at ω_k (generalised eigenvalue of (K, M)).
double simulated_frequency(Integrator integ, MassMatrixKind mk, int mode, double* exact) {
  Scene s = bar_scene(integ, 40, mk);
  if (integ == Integrator::CvodeBdf) {
    // BDF2 (see engines.cpp) under CVODE's own error control. atol stays above the
    // round-off floor of the nodal accelerations (K q with |q| ≈ 9 and EA/h = 5e7).
    s.solver.rtol = 1e-10;
    s.solver.atol = 1e-9;
  }
  auto model = build_model(s);
  const int n = model->n();
  Eigen::MatrixXd K(model->K()), M(model->M());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  const double w = std::sqrt(es.eigenvalues()[mode]);
  *exact = w;
  Eigen::VectorXd phi = es.eigenvectors().col(mode);
  Eigen::VectorXd qeq = Eigen::MatrixXd(model->K()).ldlt().solve(model->f0());
  auto eng = make_engine(model, s.solver, s.contact.model == ContactModel::Lee, s.contact.tol_u);  // no contact force
  Eigen::VectorXd y(2 * n), y1(2 * n);
  y.head(n) = qeq + 1e-3 * phi / phi.cwiseAbs().maxCoeff();
  y.tail(n).setZero();
  const double period = 2 * M_PI / w;
  // Explicit steps must respect the stability limit of the mesh (DP5: ω_max h ≲ 1.5 on the imaginary axis).
  const double h_stable = 1.0 / std::sqrt(es.eigenvalues()[n - 1]);
  const bool explicit_engine = integ == Integrator::ArkodeErk;
  const int per = explicit_engine ? std::max(400, int(std::ceil(period / h_stable))) : 400;
  const int nper = 4;
  const double h = period / per;
  Eigen::VectorXd Mphi = M * phi;
  double t = 0, eta_prev = Mphi.dot(y.head(n) - qeq);
  std::vector<double> crossings;
  for (int i = 0; i < per * nper; ++i) {
    eng->step(t, y, h, y1);
    const double eta = Mphi.dot(y1.head(n) - qeq);
    if ((eta_prev > 0) != (eta > 0)) {
      // cubic-free estimate: linear interpolation at the inflection point (error O(h³))
      crossings.push_back(t + h * eta_prev / (eta_prev - eta));
    }
    eta_prev = eta;
    y = y1;
    t += h;
  }
  const double half_periods = double(crossings.size() - 1);
  return M_PI * half_periods / (crossings.back() - crossings.front());
}

TEST(Engines, BarModalFrequenciesMatchEigenvalues) {
  for (Integrator integ : {Integrator::ArkodeErk, Integrator::ArkodeDirk, Integrator::CvodeBdf}) {
    for (MassMatrixKind mk : {MassMatrixKind::Consistent, MassMatrixKind::Lumped}) {
      for (int mode = 0; mode < 3; ++mode) {
        double exact = 0;
        const double w = simulated_frequency(integ, mk, mode, &exact);
        const double rel = std::abs(w / exact - 1.0);
        std::printf("%s %s mode %d: omega %.9g exact %.9g rel %.2e\n", to_string(integ),
                    to_string(mk), mode + 1, w, exact, rel);
        EXPECT_LT(rel, 1e-6) << to_string(integ) << " " << to_string(mk) << " mode " << mode + 1;
      }
    }
  }
}

// Continuum bar, free at x = 0, spring k at x = L: u = cos βx with
//   −EA β sin βL + k cos βL = 0,  ω = β c,  c = √(E/ρ).
double continuum_omega(int mode, double E, double A, double L, double m, double k) {
  const double EA = E * A, c = std::sqrt(E / (m / (A * L)));
  // Mode j (0-based) has βL in ((j) π, (j + ½) π) ... bisection on g(x) = x tan x − kL/EA.
  const double r = k * L / EA;
  auto g = [&](double x) { return EA / L * x * std::sin(x) - k * std::cos(x); };
  double a = mode * M_PI + 1e-12, b = mode * M_PI + M_PI / 2 - 1e-12;
  (void)r;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (a + b);
    if ((g(a) > 0) == (g(mid) > 0))
      a = mid;
    else
      b = mid;
  }
  return 0.5 * (a + b) / L * c;
}

TEST(Model, MeshConvergenceToContinuumAtRateH2AndMassBounds) {
  const double E = 1e7, A = 3, L = 24, m = 1, k = 500;
  for (int mode = 1; mode <= 3; ++mode) {
    const double exact = continuum_omega(mode, E, A, L, m, k);
    double err_prev = 0;
    for (int N : {40, 80, 160}) {
      double w[2];
      int i = 0;
      for (MassMatrixKind mk : {MassMatrixKind::Consistent, MassMatrixKind::Lumped}) {
        Scene s = bar_scene(Integrator::ArkodeErk, N, mk);
        auto model = build_model(s);
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(model->K()),
                                                                      Eigen::MatrixXd(model->M()));
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

TEST(Model, MstarEqualsInverseMassColumn) {
  Scene s = bar_scene(Integrator::ArkodeErk, 40, MassMatrixKind::Consistent);
  auto model = build_model(s);
  Eigen::MatrixXd Minv = Eigen::MatrixXd(model->M()).inverse();
  EXPECT_NEAR(model->mstar(), Minv(0, 0), 1e-12 * Minv(0, 0));
  Scene r = rigid_scene(Integrator::ArkodeErk);
  EXPECT_DOUBLE_EQ(build_model(r)->mstar(), 1.0);
}

TEST(Model, InitialShapeIsStaticEquilibriumUnderPreload) {
  Scene s = bar_scene(Integrator::ArkodeErk, 40, MassMatrixKind::Consistent);
  auto model = build_model(s);
  const Eigen::VectorXd& q = model->initial_displacement();
  Eigen::VectorXd r = model->f0() - model->K() * q;
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

TEST(Model, DescriptionListsOnlyRequestedEffects) {
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
    auto model = build_model(c.scene);
    const ModelDescription& d = model->description();
    EXPECT_EQ(d.unknowns, c.unknowns) << c.name;
    EXPECT_EQ(d.mass, c.mass) << c.name;
    EXPECT_EQ(d.sparse, c.sparse) << c.name;
    EXPECT_EQ(d.linear_solver, c.linear_solver) << c.name;
    EXPECT_EQ(d.damping, c.damping) << c.name;
    EXPECT_EQ(d.contact, c.contact) << c.name;
    const bool has_damp_term =
        std::find_if(d.rhs_terms.begin(), d.rhs_terms.end(), [](const std::string& t) {
          return t.find("damp") != std::string::npos;
        }) != d.rhs_terms.end();
    EXPECT_EQ(has_damp_term, c.damping) << c.name;
    if (c.scene.follower.kind == FollowerKind::Rigid) {
      EXPECT_EQ(model->K().nonZeros(), 0) << "rigid builds no sparse matrix";
      EXPECT_EQ(model->M().nonZeros(), 0);
    }
    if (!c.damping) {
      EXPECT_EQ(model->C().nonZeros(), 0) << c.name;
    }
  }
}

}  // namespace
}  // namespace camdyn
