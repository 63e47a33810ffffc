// camdyn — the matrices of a rigid or elastic_bar follower (follower_matrices.hpp;
// docs/method.md §1, §5).
//
//   rigid       n = 1:  M = m, C = c, K = k, f₀ = −k δ₀ + k q(0).
//   elastic_bar n = N+1 nodes, element length h = L/N, element mass mₑ = m/N:
//     Kₑ = EA/h [1 −1; −1 1],   Mₑ = mₑ/6 [2 1; 1 2] (consistent) or mₑ/2 I (lumped),
//     K += k e_N e_Nᵀ,  f₀ = (−k δ₀ + k q_N(0)) e_N,  C = αM + βK.
//   Initial shape: uniform compression by the preload F₀ = k δ₀:
//     q_i(0) = x₀ − i F₀ h / (EA),  x₀ = X_C(θ₀) + initial_gap.
// C exists only if damping was asked for.
#include "mechanism/follower_matrices.hpp"

#include <sstream>
#include <vector>

#include "camdyn/cam.hpp"
#include "scene/linear_solver.hpp"  // resolve_linear_solver
#include "scene/shared_cam.hpp"

namespace camdyn {

std::string ModelDescription::ToString() const {
  std::ostringstream o;
  o << follower << ": " << nodes << " node(s), " << unknowns << " unknowns, mass " << mass
    << (sparse ? ", sparse" : ", dense/scalar") << ", linear solver " << linear_solver
    << ", contact " << contact << (damping ? ", damped" : ", undamped")
    << (preload ? ", preloaded spring" : "") << (varying_speed ? ", varying cam speed" : "")
    << "; rhs terms:";
  for (const auto& t : rhs_terms) o << ' ' << t;
  for (const auto& e : network) o << "\n    " << e;
  return o.str();
}

FollowerMatrices follower_matrices(const Scene& scene) {
  const FollowerSpec& f = scene.follower;
  const double k = scene.spring.stiffness;
  FollowerMatrices r;
  ModelDescription& desc = r.description;
  const double preload = k * scene.spring.precompression;
  r.spring_preload = preload;
  const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(scene.cam);
  const Cam& cam = *cam_owner;
  const CamDrive drive(scene.cam);
  const double x0 = cam.evaluate(drive.theta(0.0)).X_C + scene.contact.initial_gap;

  desc.follower = to_string(f.kind);
  desc.preload = preload != 0.0;
  desc.varying_speed = !drive.constant_speed();
  desc.contact = scene.contact.separation ? "unilateral" : "holonomic";
  desc.rhs_terms = {"inertia"};
  bool damped = false;

  if (f.kind == FollowerKind::Rigid) {
    r.n = 1;
    auto scalar = [](double x) {
      SparseMatrix A(1, 1);
      const Eigen::Triplet<double, long> t(0, 0, x);
      A.setFromTriplets(&t, &t + 1);
      A.makeCompressed();
      return A;
    };
    r.M = scalar(f.mass);
    r.K = scalar(k);
    damped = f.damping != 0.0;
    if (damped) r.C = scalar(f.damping);
    r.q0 = Eigen::VectorXd::Constant(1, x0);
    r.f0 = Eigen::VectorXd::Constant(1, -preload + k * x0);
    desc.nodes = 1;
    desc.mass = "scalar";
    desc.sparse = false;
    if (k != 0.0) desc.rhs_terms.push_back("spring");
    if (damped) desc.rhs_terms.push_back("viscous_damper");
  } else {
    const long N = f.elements;
    const int n = static_cast<int>(N + 1);
    r.n = n;
    const bool lumped = f.mass_matrix == MassMatrixKind::Lumped;
    const double h = f.length / double(N);
    const double EA = f.youngs_modulus * f.area;
    const double ke = EA / h, me = f.mass / double(N);
    // One tridiagonal pattern shared by K, M and C (explicit zeros where needed), so the
    // engines can fill M + γC + γ²K or M − γJ entry by entry without a sparse add.
    std::vector<Eigen::Triplet<double, long>> tk, tm;
    tk.reserve(4 * N + 1);
    tm.reserve(4 * N);
    const double mo = lumped ? 0.0 : me / 6.0, md = lumped ? me / 2.0 : me / 3.0;
    for (long e = 0; e < N; ++e) {
      const long a = e, b = e + 1;
      tk.emplace_back(a, a, ke);
      tk.emplace_back(b, b, ke);
      tk.emplace_back(a, b, -ke);
      tk.emplace_back(b, a, -ke);
      tm.emplace_back(a, a, md);
      tm.emplace_back(b, b, md);
      tm.emplace_back(a, b, mo);
      tm.emplace_back(b, a, mo);
    }
    tk.emplace_back(N, N, k);
    r.K.resize(n, n);
    r.M.resize(n, n);
    r.K.setFromTriplets(tk.begin(), tk.end());
    r.M.setFromTriplets(tm.begin(), tm.end());
    r.K.makeCompressed();
    r.M.makeCompressed();
    const double ar = f.rayleigh_alpha, br = f.rayleigh_beta;
    damped = ar != 0.0 || br != 0.0;
    if (damped) {
      r.C = ar * r.M + br * r.K;  // same pattern (both tridiagonal)
      r.C.makeCompressed();
    }
    // Initial shape: uniform compression under the preload.
    r.q0.resize(n);
    for (long i = 0; i < n; ++i) r.q0[i] = x0 - double(i) * preload / ke;
    r.f0 = Eigen::VectorXd::Zero(n);
    r.f0[N] = -preload + k * r.q0[N];
    desc.nodes = n;
    desc.mass = lumped ? "lumped" : "consistent";
    desc.sparse = true;
    desc.rhs_terms.push_back("bar_stiffness");
    if (k != 0.0) desc.rhs_terms.push_back("spring");
    if (damped) desc.rhs_terms.push_back("rayleigh_damping");
  }
  if (preload != 0.0) desc.rhs_terms.push_back("preload");
  desc.rhs_terms.push_back("contact_force");
  desc.damping = damped;
  desc.unknowns = 2 * r.n + (scene.solver.integrator == Integrator::Ida ? 3 : 0);  // IDA: + λ, μ, W
  desc.linear_solver = to_string(resolve_linear_solver(scene.solver, r.n));
  if (scene.solver.integrator == Integrator::ArkodeErk) desc.linear_solver = "none";
  return r;
}

}  // namespace camdyn
