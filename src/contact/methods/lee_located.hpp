// camdyn (private) — Lee's located step on any mechanism, any number of contacts (the located step for a vector
// of contact forces).
//
//   Over a step t → t + h, each active contact j carries the force shape
//     F_j(τ) = F_j + (F₁ⱼ − F_j)x + F_cⱼ·4x(1 − x),   x = (τ − t)/h,
//   the inactive ones none. The end state is affine in (F₁, F_c) on the one-step engines
//   (ERK, DIRK with an exact Jacobian), y = y_a + Σⱼ (ΔF₁ⱼ D₁ⱼ + ΔF_cⱼ D_cⱼ), with
//   responses D of the (time-invariant) mechanism to a unit shape on contact j, computed
//   from rest without preload once per step size and contact. The displacement and
//   velocity levels, g_j(t + h) = 0 and ġ_j(t + h) = 0 for every active j, are 2k linear
//   equations in the 2k shape parameters, solved together. A network with nonlinear
//   elements (no internal states, no camshaft): the same equations on the responses of its
//   linear part (M, C, K and the elements' tangent frozen at a step's start), the corrected
//   state kept when its estimated linearisation error is within a tenth of the tolerances,
//   else integrated again and iterated. Otherwise (a user's nonlinear follower, element
//   states, a camshaft) iterated with Lee's constants, ∂g/∂F₁ = W h²/6,
//   ∂ġ/∂F₁ = W h/2, ∂g/∂F_c = W h²/3, ∂ġ/∂F_c = 2W h/3, W = T M⁻¹ Tᵀ. The acceleration level gives the
//   forces the equation of motion demands at t + h, W_AA F̃ = Ẍ_C,A − T_A a_free, which
//   start the next step; |F̃ − F₁| is in the error test against
//   rtol·|F| + 2 tol_u/(W_jj h²).
//   Switches are located inside the step and landed on: an active contact whose pointwise
//   held force (acceleration level on the cubic Hermite state) falls to zero separates; an
//   inactive contact whose gap (quintic Hermite from g, ġ, g̈ at both ends) reaches zero
//   impacts, resolved by the Newton law on all contacts taking part (contact_run.cpp).
//   The one-step engines only: on cvode-bdf the three levels are solved inside CVODE's own
//   step (methods/lee_cvode.cpp).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "contact/active_set.hpp"
#include "contact/methods/lee_step_tools.hpp"
#include "contact/methods/switch_search.hpp"
#include "contact/contact_run.hpp"
#include "contact/run_failure.hpp"  // StepFailure, IterationFailure, fmt
#include "contact/step_control.hpp"  // output_time

namespace camdyn {
namespace detail {

class LeeLocated final : public ContactRun {
 public:
  LeeLocated(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
             const std::atomic<bool>* stop)
      : ContactRun(sc, std::move(mech), obs, stop) {
    samples_.resize(m_);
    least_ = Eigen::VectorXd::Constant(m_, INFINITY);
    OdeSystem sys;
    sys.size = ny_;
    sys.atol = absolute_tolerances();
    sys.rhs = [this](double t, const double* y, double* yd) { rhs(t, y, yd); };
    // The mechanism's sparse Newton structure (the force shape does not depend on the
    // state); a user's follower: its dense Jacobian, without one difference quotients.
    std::shared_ptr<SparseNewton> newton = sparse_newton();
    if (newton) {
      // a camshaft: the rows at the state, their stiffness at the step's force shape
      shaft_newton(*newton, [this](double t, const Eigen::VectorXd&, Eigen::VectorXd& F, Eigen::VectorXd&) {
        const double x = (t - s_t0_) / s_h_;
        for (int j = 0; j < m_; ++j) F[j] = F0_[j] + (F1_[j] - F0_[j]) * x + Fc_[j] * 4.0 * x * (1.0 - x);
      });
    }
    if (!newton) sys.jacobian = dense_jacobian(nullptr);
    // A network with nonlinear elements but no internal states and no camshaft: its held
    // steps correct the force shape by the responses of its linear part (solve_step),
    // integrated on an engine of their own that knows the part is linear (DIRK: one
    // Newton iteration per stage on its exact matrix). The force shape is a function of t:
    // the elements' force is the trial system's only nonlinearity.
    linear_part_ = newton && !mk_.linear() && ns_ == 0 && !mk_.camshaft();
    if (linear_part_) {
      newton->element_force = [el = &dynamic_cast<const Mechanism&>(mk_).elements(), n = n_](
                                  double t, const double* y, double* r) { el->add_force(t, y, y + n, r); };
    }
    sys.newton = newton;
    sys.linear = mk_.linear() && (sys.jacobian || sys.newton);
    if (sc.solver.integrator == Integrator::CvodeBdf)
      throw std::logic_error("Lee on cvode-bdf runs in methods/lee_cvode.cpp");
    engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, sys, true));
    eng_ = resp_eng_ = engines_.back().get();
    if (linear_part_) {
      const auto& mech = dynamic_cast<const Mechanism&>(mk_);
      part_M_.compute(mech.M());
      part_Ke_ = mech.elements().stiffness_pattern();
      if (mech.elements().damps()) part_Ce_ = mech.elements().damping_pattern();
      OdeSystem lin = sys;
      auto part = std::make_shared<SparseNewton>(*newton);
      part->element_force = nullptr;
      part->element_tangent = [this](double, const double*, SparseMatrix& Ke, SparseMatrix& Ce) {
        std::copy(part_Ke_.valuePtr(), part_Ke_.valuePtr() + part_Ke_.nonZeros(), Ke.valuePtr());
        if (Ce.size()) std::copy(part_Ce_.valuePtr(), part_Ce_.valuePtr() + part_Ce_.nonZeros(), Ce.valuePtr());
      };
      lin.newton = part;
      lin.linear = true;
      engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, lin, true));
      resp_eng_ = engines_.back().get();
    }
    F0_ = F1_ = Fc_ = Eigen::VectorXd::Zero(m_);
    slope_ = Eigen::VectorXd::Zero(m_);
    fs_.resize(m_);
  }

 private:
  OdeEngine* eng_;
  OdeEngine* resp_eng_;  // the responses' engine (eng_, or the linear part's own)
  // the force shape of the step being integrated
  double s_t0_ = 0, s_h_ = 1;
  bool homogeneous_ = false;
  // Held steps of a nonlinear network corrected by its linear part's responses (the
  // correction's linearisation error estimated, the step integrated again only if it
  // exceeds kLinearisedShare of the tolerances).
  bool linear_part_ = false;
  static constexpr double kLinearisedShare = 0.1;
  // The linear part: M, C, K and the elements' tangent K_e, C_e frozen at a step's start,
  // taken again (the responses with it) after a correction the estimate refused, at most
  // every kPartRefreshSteps accepted steps.
  Eigen::SimplicialLDLT<SparseMatrix> part_M_;
  SparseMatrix part_Ke_, part_Ce_;
  long part_step_ = -1;  // rec_.steps when the tangent was taken (-1: not yet)
  bool part_stale_ = false;
  static constexpr long kPartRefreshSteps = 16;
  Eigen::VectorXd part_r_;
  // a += M⁻¹(−K_e q − C_e v) with the frozen tangent
  void add_part_tangent(const double* q, const double* v, double* a) {
    Eigen::Map<const Eigen::VectorXd> Q(q, n_), V(v, n_);
    part_r_.noalias() = -(part_Ke_ * Q);
    if (part_Ce_.size()) part_r_.noalias() -= part_Ce_ * V;
    Eigen::Map<Eigen::VectorXd>(a, n_) += part_M_.solve(part_r_);
  }
  // The tangent at the step's start; the responses computed with the old one are dropped.
  void refresh_part();
  // The estimated error of a correction dy (= y1 after − y1 before) applied through the
  // linear part's responses over a step of hs ending at t1; into lin_err_ (ny_ entries).
  void linearisation_error(double t1, double hs, const Eigen::VectorXd& y1_before, const Eigen::VectorXd& y1_after);
  Eigen::VectorXd lin_err_, lin_a_, lin_b_, lin_y_, lin_dy_;
  Eigen::VectorXd F0_, F1_, Fc_, fs_, slope_;

  void rhs(double t, const double* y, double* yd) {
    const double x = (t - s_t0_) / s_h_;
    for (int j = 0; j < m_; ++j) fs_[j] = F0_[j] + (F1_[j] - F0_[j]) * x + Fc_[j] * 4.0 * x * (1.0 - x);
    std::copy(y + n_, y + 2 * n_, yd);
    mk_.acceleration(t, y, y + n_, fs_, yd + n_, homogeneous_, states_of(y));
    if (homogeneous_ && linear_part_) add_part_tangent(y, y + n_, yd + n_);
    if (ns_) {  // the elements' internal states (a homogeneous response carries none)
      if (homogeneous_) std::fill(yd + 2 * n_, yd + ny_, 0.0);
      else mk_.state_rate(t, y, y + n_, states_of(y), yd + 2 * n_);
    }
  }
  double integrate(double t, const Eigen::VectorXd& from, double h, Eigen::VectorXd& out) {
    return integrate_on(*eng_, t, from, h, out);
  }
  double integrate_on(OdeEngine& e, double t, const Eigen::VectorXd& from, double h, Eigen::VectorXd& out) {
    s_t0_ = t;
    s_h_ = h;
    return e.step(t, from, h, out);
  }

  // Responses to a unit F₁ and F_c on each contact, per step size (a few sizes cached on
  // the grid 2^(k/8)).
  struct Responses {
    double h = -1;
    std::vector<Eigen::VectorXd> D1, Dc, E1, Ec;
    std::vector<char> have;
  };
  static constexpr int kSlots = 12;
  Responses cache_[kSlots];
  int next_slot_ = 0;
  long resp_gen_ = 0;  // counts the computations of responses
  Responses& responses(double hs, const std::vector<int>& set);

  // The accepted-or-trial step's data for interpolation and switch search.
  struct StepData {
    double t0 = 0, t1 = 0;
    Eigen::VectorXd y0, y1, a0, a1, F0, F1;  // F1: acceleration-level forces at t1
    Eigen::VectorXd r0, r1;                  // ṡ at both ends (the elements' internal states)
    std::vector<int> set;                    // active contacts over the step
    double W0 = 0, D0 = 0, P0 = 0;
    Eigen::VectorXd s0, s1, sc;              // the force shape (start, end, bubble)
    // the cam's power on the held contacts' pointwise forces at the switch search's samples
    // (x = k / kSwitchSamples); empty: the work is taken on the applied shape
    std::vector<double> power;
  } sd_;
  Eigen::VectorXd yi_;
  // State at τ (cubic Hermite from the end states and accelerations).
  void interpolate(const StepData& s, double tau, Eigen::VectorXd& y) const {
    const double h = s.t1 - s.t0, x = (tau - s.t0) / h;
    const double x2 = x * x, x3 = x2 * x;
    const double h00 = 2 * x3 - 3 * x2 + 1, h10 = (x3 - 2 * x2 + x) * h;
    const double h01 = -2 * x3 + 3 * x2, h11 = (x3 - x2) * h;
    y.resize(ny_);
    y.head(n_) = h00 * s.y0.head(n_) + h10 * s.y0.segment(n_, n_) + h01 * s.y1.head(n_) + h11 * s.y1.segment(n_, n_);
    y.segment(n_, n_) = h00 * s.y0.segment(n_, n_) + h10 * s.a0 + h01 * s.y1.segment(n_, n_) + h11 * s.a1;
    if (ns_) y.tail(ns_) = h00 * s.y0.tail(ns_) + h10 * s.r0 + h01 * s.y1.tail(ns_) + h11 * s.r1;
  }
  // The held contacts' largest |gap| inside the step on its Hermite state, over
  // max(10 tol_u, 10⁻⁴ of the cam's lift). The displacement level holds at the step's ends
  // only: a held set whose error test sees nothing (every node held while the cam lifts)
  // lets one step cross a whole lift, its open contacts' gaps closing and reopening unseen
  // inside it. A step whose interpolant leaves the cam by more than this is rejected.
  double held_drift(const StepData& s) {
    if (s.set.empty()) return 0.0;
    const double tol = std::max(10.0 * sc_.contact.tol_u, 1e-4 * cam_.lift());
    double r = 0.0;
    if (!mk_.camshaft()) {
      // g_j = T_j q + g₀_j − X_C·[cam] (gap()) on the Hermite state: T_j q(τ) from the four
      // products T_j q and T_j v at both ends, not the whole interpolated state per sample
      const double h = s.t1 - s.t0;
      for (int j : s.set) {
        const MechanismContact& c = mk_.contacts()[j];
        const double q0 = c.t.dot(s.y0.head(n_)), v0 = c.t.dot(s.y0.segment(n_, n_));
        const double q1 = c.t.dot(s.y1.head(n_)), v1 = c.t.dot(s.y1.segment(n_, n_));
        for (int k = 1; k < kSwitchSamples; ++k) {
          const double x = double(k) / kSwitchSamples, x2 = x * x, x3 = x2 * x;
          const double tq = (2 * x3 - 3 * x2 + 1) * q0 + (x3 - 2 * x2 + x) * h * v0 + (-2 * x3 + 3 * x2) * q1 +
                            (x3 - x2) * h * v1;
          const double g = tq + c.g0 - (c.cam ? cam_at(s.t0 + h * x).X : 0.0);
          r = std::max(r, std::abs(g) / tol);
        }
      }
      return r;
    }
    for (int k = 1; k < kSwitchSamples; ++k) {
      const double tau = s.t0 + (s.t1 - s.t0) * double(k) / kSwitchSamples;
      interpolate(s, tau, yi_);
      const CamMotion c = cam_at(tau);
      for (int j : s.set) r = std::max(r, std::abs(gap(j, yi_, c)) / tol);
    }
    return r;
  }
  // ∫ Σ_cam F_shape Ẋ_C (the cam's work on the applied shape) and ∫ dissipated power (on
  // the step's Hermite state) over [s.t0, tb], 5-point Gauss–Legendre: each step's own
  // quadrature (the trapezoid on the ends left the valve train's stem damping 6e-8 of the
  // cam's work off at rtol 1e-8).
  StepEnergy shape_energy(const StepData& s, double tb) {
    static const double xg[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                 0.9061798459386640};
    static const double wg[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                 0.4786286704993665, 0.2369268850561891};
    const double h = s.t1 - s.t0, len = tb - s.t0;
    StepEnergy e;
    if (len <= 0) return e;
    Eigen::VectorXd& F = Fq_;
    const bool dissipative = mk_.dissipative();  // Lee's contacts dissipate nothing between impacts
    const bool sampled = !s.power.empty();
    if (sampled) e.work = h * sampled_integral(s.power.data(), len / h);
    for (int i = 0; i < 5; ++i) {
      const double tau = s.t0 + 0.5 * len * (1.0 + xg[i]), x = (tau - s.t0) / h;
      if (!s.set.empty() && !sampled) {
        F = s.s0 + (s.s1 - s.s0) * x + s.sc * (4.0 * x * (1.0 - x));
        e.work += 0.5 * len * wg[i] * cam_power(F, cam_at(tau));
      }
      if (dissipative || mk_.camshaft()) interpolate(s, tau, yq_);
      if (dissipative) e.dissipated += 0.5 * len * wg[i] * dissipation_power(tau, yq_);
      // a camshaft: the drive's work (its contacts work inside the mechanism)
      if (mk_.camshaft()) e.work += 0.5 * len * wg[i] * mk_.input_power(tau, yq_.data(), yq_.data() + n_);
    }
    return e;
  }
  Eigen::VectorXd yq_, Fq_;
  // The step's interpolant at tau put on its held contacts (g = ġ = 0, as the step ends
  // are): rows, the least force and the first tensile force inside a step.
  void held_state_at(const StepData& s, double tau, Eigen::VectorXd& y) {
    interpolate(s, tau, y);
    if (s.set.empty()) return;
    const CamMotion cm = cam_at(tau);
    Eigen::VectorXd &g = hg_, &gd = hgd_;
    g.setZero(m_);
    gd.setZero(m_);
    for (int j : s.set) g[j] = gap(j, y, cm), gd[j] = gap_rate(j, y, cm);
    const Rows R = rows_at(y.data());  // a camshaft's rows at this state
    project_on_set(R.MinvTt, R.W, s.set, g, gd, y);
  }
  Eigen::VectorXd hg_, hgd_, hf_, mg_;
  std::vector<char> in_set_;
  StepData* dense_ = nullptr;
  bool dense_row_at(double to) override {
    if (!dense_ || !(to > dense_->t0)) return false;
    const StepData& s = *dense_;
    held_state_at(s, to, yi_);
    const CamMotion cm = cam_at(to);
    Eigen::VectorXd F = held_forces(to, yi_, cm, s.set);
    for (int j : s.set) F[j] = unilateral_ ? std::max(F[j], 0.0) : F[j];
    std::vector<char> act(m_, 0);
    for (int j : s.set) act[j] = 1;
    const StepEnergy e = shape_energy(s, to);
    emit_row_at(to, yi_, F, act, s.W0 + e.work, s.D0 + e.dissipated);
    return true;
  }

  // The least force of held contact j inside the accepted step s (the force margin of a
  // follower that floats, Summary::min_contact_force, ContactResult::min_force): the
  // switch search's samples, and where their interior minimum is below the least force so
  // far, golden section on the step's own interpolant — a minimum between the rows or the
  // step ends, not the grid's.
  std::vector<std::array<double, kSwitchSamples + 1>> samples_;
  Eigen::VectorXd least_;  // per contact, the least held force so far
  void least_force_inside(const StepData& s, int j) {
    const auto& f = samples_[j];
    least_[j] = std::min({least_[j], f[0], f[kSwitchSamples]});  // the step ends are sampled anyway
    int k = 1;
    for (int i = 2; i < kSwitchSamples; ++i)
      if (f[i] < f[k]) k = i;
    // Below the least so far by more than the interpolant's own error (rtol of the force):
    // a flat minimum at a step end (a symmetric cam's θ = 0) is not moved inside the step.
    const double margin = sc_.solver.rtol * std::abs(least_[j]);
    if (!(f[k] < least_[j] - margin) || !(f[k] <= f[k - 1] && f[k] <= f[k + 1])) return;
    const double hs = s.t1 - s.t0;
    auto force = [&](double x) {
      const double tau = s.t0 + x * hs;
      held_state_at(s, tau, yi_);
      held_forces_into(tau, yi_, cam_at(tau), s.set, hf_);
      return hf_[j];
    };
    const Sample m = golden_min(force, double(k - 1) / kSwitchSamples, double(k + 1) / kSwitchSamples, 30);
    const double tau = s.t0 + m.x * hs, F = std::max(m.f, 0.0);
    least_[j] = std::min(least_[j], F);
    sample_held_force(j, tau, F);
  }

  // A bilateral contact (holonomic) whose force turns tensile inside the accepted step:
  // Summary::first_tensile_time where it crosses zero (bisection on the held interpolant).
  void first_tensile_inside(const StepData& s, int j) {
    if (rec_.first_tensile_time >= 0 || !(s.F0[j] >= 0.0 && s.F1[j] < 0.0)) return;
    const double hs = s.t1 - s.t0;
    auto force = [&](double x) {
      const double tau = s.t0 + x * hs;
      held_state_at(s, tau, yi_);
      held_forces_into(tau, yi_, cam_at(tau), s.set, hf_);
      return hf_[j];
    };
    const double x = bisect_fall(force, 0.0, 1.0, hs, s.t1);
    rec_.first_tensile_time = s.t0 + x * hs;
    record_event(EventKind::Tensile, j, 0.0, 0.0, rec_.first_tensile_time);
  }

  // A held contact separates at the current step start.
  void release_now(int j) {
    active_[j] = 0;
    ++rec_.separations;
    record_event(EventKind::Separation, j, 0.0);
    settle_active(cam_at(t_));
    slope_.setZero();
  }

  std::string trial_error_;  // the last failed trial's message
  StepSizeMemory steps_;  // the step-size controller (lee_step_tools.hpp)
  double brk_t_ = NAN;    // the last breakpoint a step landed on
  static constexpr int kMaxRelocations = 4;
  double reloc_t_ = -1.0;  // the step start of the last relocation, and their count there
  int reloc_count_ = 0;
  // A relocation toward a held contact's separation: the contact and the step it cut short.
  // The step to its root, if it is a sliver of that step and fails the error test, is
  // round-off (a held gap corrected by a force ∝ gap/Δt²): the contact is released there.
  int reloc_sep_ = -1;
  double reloc_from_h_ = 0.0;
  static constexpr double kSliver = 1e-6;


  // Solve the shape for the active set over a step of hs; y1 the end state, returns the
  // engine's error norm.
  double solve_step(const std::vector<int>& set, double hs, double t1, Eigen::VectorXd& y1);
  // Why a trial's residual is not finite: the mechanism's own message at the end state
  // (a user force that is not finite), or which part is not finite.
  std::string non_finite_cause(double t1, const Eigen::VectorXd& y1);
  // The 2k × 2k matrix of the levels' responses to the shape parameters of `set` over a
  // step of hs (exact responses R, or Lee's constants), factorised into J_lu_.
  void factor_shape_matrix(const std::vector<int>& set, double hs, const Responses* R);
  double J_h_ = -1.0;  // the step size, responses and set J_lu_ belongs to
  long J_gen_ = -1;
  std::vector<int> J_set_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> J_lu_;
  Eigen::VectorXd le_, r_, d_;

  void run_method() override;
};

}  // namespace detail
}  // namespace camdyn
