// camdyn — a rigid or elastic_bar follower as a Mechanism.
//
//   The follower's matrices (src/mechanism/follower_matrices.cpp: M, C, K, f₀ and the
//   preloaded initial shape q(0)) with one contact, the cam on node 0:
//     T = e₀ᵀ,   g = q₀ − X_C(θ)   (X_C absolute: u_c = q₀).
//   rigid: M = [m], K = [k], C = [c] (only if c > 0); elastic_bar: the bar's sparse
//   M, K, C = αM + βK. Every method and engine runs it as any other mechanism.
#include <cmath>

#include "camdyn/cam.hpp"
#include "mechanism/follower_matrices.hpp"
#include "mechanism/mechanism.hpp"
#include "scene/shared_cam.hpp"

namespace camdyn {

void Mechanism::build_follower(const Scene& scene) {
  const FollowerMatrices f = follower_matrices(scene);
  n_ = f.n;
  M_ = f.M;
  K_ = f.K;
  C_ = f.C;
  f0_ = f.f0;
  q0_ = f.q0;
  v0_ = Eigen::VectorXd::Zero(n_);
  // Touching at t = 0 (no initial gap): node 0 moves with the cam.
  if (scene.contact.initial_gap == 0.0) {
    const std::shared_ptr<const Cam> cam_owner = detail::shared_cam(scene.cam);
    const Cam& cam = *cam_owner;
    const CamDrive drive(scene.cam);
    v0_[0] = cam.motion(drive.theta(0.0), drive.omega(0.0), drive.omega_dot(0.0)).Xdot;
  }
  factor_mass();
  r0_ = f0_ - K_ * q0_;
  L_.resize(0, n_);

  MechanismContact c;
  c.name = "cam";
  c.kind = ContactPointKind::Cam;
  c.t = Eigen::RowVectorXd::Zero(n_);
  c.t[0] = 1.0;
  c.g0 = 0.0;
  c.cam = true;
  c.law = ContactLaw::of(scene.contact);
  contacts_.push_back(std::move(c));
  finish_contacts([&](const double* b, double* x) {
    Eigen::Map<Eigen::VectorXd> X(x, n_);
    X = Eigen::Map<const Eigen::VectorXd>(b, n_);
    solve_mass(X);
  });
  force_scale_ = std::abs(f.spring_preload);
  ta_r0_ = MinvTt_.transpose() * r0_;  // contact_free_acceleration's linear forms
  ta_q_ = K_ * MinvTt_;
  if (damped()) ta_v_ = C_ * MinvTt_;
  // No elements, no camshaft: the banded kernel when M is diagonal (rigid, lumped bar) or
  // tridiagonal (consistent bar).
  if (mass_pattern_ != MassPattern::General) acceleration_kernel_ = AccelerationKernel::BandedInPlace;
  traits_.named_contacts = false;
  traits_.cam_lift_absolute = true;
  traits_.one_body = true;
  traits_.stiff_internal_modes = n_ > 1;  // an elastic bar
  traits_.linear_contact_acceleration = true;
  // IDA: a rigid mass takes up to order 5; a bar's stiff axial modes hold BDF to order 2.
  traits_.ida_max_order = n_ == 1 ? 5 : 2;
  desc_ = f.description;
  desc_.sparse = true;
  desc_.contact += " (one-contact mechanism)";
}

}  // namespace camdyn
