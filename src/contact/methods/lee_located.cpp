// camdyn — Lee's method on a network with several contacts (the located step for a vector
// of contact forces).
//
//   Over a step t → t + h, each active contact j carries the force shape
//     F_j(τ) = F_j + (F₁ⱼ − F_j)x + F_cⱼ·4x(1 − x),   x = (τ − t)/h,
//   the inactive ones none. The end state is affine in (F₁, F_c) on the one-step engines
//   (ERK, DIRK with an exact Jacobian), y = y_a + Σⱼ (ΔF₁ⱼ D₁ⱼ + ΔF_cⱼ D_cⱼ), with
//   responses D of the (time-invariant) mechanism to a unit shape on contact j, computed
//   from rest without preload once per step size and contact. The displacement and
//   velocity levels, g_j(t + h) = 0 and ġ_j(t + h) = 0 for every active j, are 2k linear
//   equations in the 2k shape parameters, solved together (a user's nonlinear follower,
//   whose step map is not affine: iterated with Lee's constants, ∂g/∂F₁ = W h²/6,
//   ∂ġ/∂F₁ = W h/2, ∂g/∂F_c = W h²/3, ∂ġ/∂F_c = 2W h/3, W = T M⁻¹ Tᵀ). The acceleration level gives the
//   forces the equation of motion demands at t + h, W_AA F̃ = Ẍ_C,A − T_A a_free, which
//   start the next step; |F̃ − F₁| is in the error test against
//   rtol·|F| + 2 tol_u/(W_jj h²).
//   Switches are located inside the step and landed on: an active contact whose pointwise
//   held force (acceleration level on the cubic Hermite state) falls to zero separates; an
//   inactive contact whose gap (quintic Hermite from g, ġ, g̈ at both ends) reaches zero
//   impacts, resolved by the Newton law on all contacts taking part (contact_run.cpp).
//   The one-step engines only: on cvode-bdf the three levels are solved inside CVODE's own
//   step (methods/lee_cvode.cpp).
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "contact/active_set.hpp"
#include "contact/methods/lee_step_tools.hpp"
#include "contact/methods/switch_search.hpp"
#include "contact/contact_run.hpp"
#include "contact/run_failure.hpp"  // StepFailure, IterationFailure, fmt
#include "contact/step_control.hpp"  // output_time

namespace camdyn {
namespace detail {
namespace {


class LeeLocated final : public ContactRun {
 public:
  LeeLocated(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
             const std::atomic<bool>* stop)
      : ContactRun(sc, std::move(mech), obs, stop) {
    samples_.resize(m_);
    least_ = Eigen::VectorXd::Constant(m_, INFINITY);
    OdeSystem sys;
    sys.size = ny_;
    sys.rhs = [this](double t, const double* y, double* yd) { rhs(t, y, yd); };
    // The mechanism's sparse Newton structure (the force shape does not depend on the
    // state); a user's follower: its dense Jacobian, without one difference quotients.
    sys.newton = sparse_newton();
    if (!sys.newton) sys.jacobian = dense_jacobian(nullptr);
    sys.linear = mk_.linear() && (sys.jacobian || sys.newton);
    if (sc.solver.integrator == Integrator::CvodeBdf)
      throw std::logic_error("network Lee on cvode-bdf runs in methods/lee_cvode.cpp");
    engines_.push_back(OdeEngine::make(sc.solver.integrator, sc.solver, sys, true));
    eng_ = engines_.back().get();
    F0_ = F1_ = Fc_ = Eigen::VectorXd::Zero(m_);
    slope_ = Eigen::VectorXd::Zero(m_);
    fs_.resize(m_);
  }

 private:
  OdeEngine* eng_;
  // the force shape of the step being integrated
  double s_t0_ = 0, s_h_ = 1;
  bool homogeneous_ = false;
  Eigen::VectorXd F0_, F1_, Fc_, fs_, slope_;

  void rhs(double t, const double* y, double* yd) {
    const double x = (t - s_t0_) / s_h_;
    for (int j = 0; j < m_; ++j) fs_[j] = F0_[j] + (F1_[j] - F0_[j]) * x + Fc_[j] * 4.0 * x * (1.0 - x);
    std::copy(y + n_, y + 2 * n_, yd);
    mk_.acceleration(t, y, y + n_, fs_, yd + n_, homogeneous_, states_of(y));
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
  Responses& responses(double hs, const std::vector<int>& set) {
    Responses* r = nullptr;
    for (Responses& c : cache_)
      if (c.h == hs) r = &c;
    if (!r) {
      r = &cache_[next_slot_];
      next_slot_ = (next_slot_ + 1) % kSlots;
      r->h = hs;
      r->D1.assign(m_, {});
      r->Dc.assign(m_, {});
      r->E1.assign(m_, {});
      r->Ec.assign(m_, {});
      r->have.assign(m_, 0);
    }
    bool all = true;
    for (int j : set) all = all && r->have[j];
    if (all) return *r;
    ++resp_gen_;  // solve_step's factorisation of J is stale
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ny_);
    const Eigen::VectorXd keep0 = F0_, keep1 = F1_, keepc = Fc_;
    for (int j : set) {
      if (r->have[j]) continue;
      const double amp = 1.0 / (mk_.W()(j, j) * hs * hs);
      homogeneous_ = true;
      F0_.setZero();
      F1_.setZero();
      Fc_.setZero();
      F1_[j] = amp;
      integrate_on(*eng_, 0.0, zero, hs, r->D1[j]);
      r->D1[j] /= amp;
      r->E1[j] = eng_->local_error() / amp;
      F1_[j] = 0.0;
      Fc_[j] = amp;
      integrate_on(*eng_, 0.0, zero, hs, r->Dc[j]);
      r->Dc[j] /= amp;
      r->Ec[j] = eng_->local_error() / amp;
      homogeneous_ = false;
      r->have[j] = 1;
      sum_.contact_iterations += 2;
    }
    F0_ = keep0;
    F1_ = keep1;
    Fc_ = keepc;
    return *r;
  }

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
    if (sum_.first_tensile_time >= 0 || !(s.F0[j] >= 0.0 && s.F1[j] < 0.0)) return;
    const double hs = s.t1 - s.t0;
    auto force = [&](double x) {
      const double tau = s.t0 + x * hs;
      held_state_at(s, tau, yi_);
      held_forces_into(tau, yi_, cam_at(tau), s.set, hf_);
      return hf_[j];
    };
    const double x = bisect_fall(force, 0.0, 1.0, hs, s.t1);
    sum_.first_tensile_time = s.t0 + x * hs;
    record_event(EventKind::Tensile, j, 0.0, 0.0, sum_.first_tensile_time);
  }

  std::string trial_error_;  // the last failed trial's message
  StepSizeMemory steps_;  // the step-size controller (lee_step_tools.hpp)
  double brk_t_ = NAN;    // the last breakpoint a step landed on
  static constexpr int kMaxRelocations = 4;
  double reloc_t_ = -1.0;  // the step start of the last relocation, and their count there
  int reloc_count_ = 0;


  // Solve the shape for the active set over a step of hs; y1 the end state, returns the
  // engine's error norm.
  double solve_step(const std::vector<int>& set, double hs, double t1, Eigen::VectorXd& y1) {
    const CamMotion cm = cam_at(t1);
    F0_.setZero();
    F1_.setZero();
    Fc_.setZero();
    for (int j : set) {
      F0_[j] = F_[j];
      F1_[j] = F_[j] + slope_[j] * hs;
    }
    double err = integrate(t_, y_, hs, y1);
    const int k = int(set.size());
    if (k == 0) return err;
    // affine step map: a one-step engine on a linear system; a user's nonlinear follower:
    // iterated with Lee's constants, which see only the contacts' inverse mass W.
    const bool affine = mk_.linear();
    Eigen::VectorXd& le = le_;
    le = eng_->local_error();
    Responses* R = mk_.linear() ? &responses(hs, set) : nullptr;
    // J depends on (hs, set) and the responses only: its factorisation is kept while
    // none of them changes
    if (!(J_h_ == hs && J_gen_ == resp_gen_ && J_set_ == set) || mk_.camshaft()) {  // a camshaft: W̃ at each start
      J_h_ = -1.0;
      factor_shape_matrix(set, hs, R);
      J_h_ = hs;
      J_gen_ = resp_gen_;
      J_set_ = set;
    }
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>& lu = J_lu_;
    const double tol_v = sc_.contact.tol_v > 0 ? sc_.contact.tol_v : sc_.contact.tol_u / hs;
    Eigen::VectorXd &r = r_, &d = d_;
    r.resize(2 * k);
    int it = 0;
    for (;;) {
      double rmax_u = 0, rmax_v = 0;
      for (int i = 0; i < k; ++i) {
        r[2 * i] = -gap(set[i], y1, cm);
        r[2 * i + 1] = -gap_rate(set[i], y1, cm);
        rmax_u = std::max(rmax_u, std::abs(r[2 * i]));
        rmax_v = std::max(rmax_v, std::abs(r[2 * i + 1]));
      }
      if (it > 0 && (affine || (rmax_u < sc_.contact.tol_u && rmax_v < tol_v))) break;
      if (it >= sc_.contact.max_iterations) {
        ++sum_.iteration_failures;
        throw IterationFailure();
      }
      d = lu.solve(r);
      if (!d.allFinite()) {
        ++sum_.iteration_failures;
        throw IterationFailure(non_finite_cause(t1, y1));
      }
      ++it;
      ++sum_.contact_iterations;
      for (int l = 0; l < k; ++l) {
        const int j = set[l];
        F1_[j] += d[2 * l];
        Fc_[j] += d[2 * l + 1];
        if (affine) {
          y1 += d[2 * l] * R->D1[j] + d[2 * l + 1] * R->Dc[j];
          le += d[2 * l] * R->E1[j] + d[2 * l + 1] * R->Ec[j];
        }
      }
      if (affine)
        err = eng_->wrms(le, y_);
      else
        err = integrate(t_, y_, hs, y1);
    }
    sum_.level_u.total += it;
    sum_.level_u.max = std::max(sum_.level_u.max, it);
    ++sum_.level_u.steps;
    sum_.level_v = sum_.level_u;
    return err;
  }
  // Why a trial's residual is not finite: the mechanism's own message at the end state
  // (a user force that is not finite), or which part is not finite.
  std::string non_finite_cause(double t1, const Eigen::VectorXd& y1) {
    if (!y1.allFinite()) return "the trial step's end state is not finite";
    Eigen::VectorXd a(n_);
    try {
      mk_.acceleration(t1, y1.data(), y1.data() + n_, F1_, a.data(), false, states_of(y1));
    } catch (const std::exception& e) {
      return e.what();
    }
    return a.allFinite() ? "a non-finite residual" : "the acceleration at the trial step's end is not finite";
  }
  // The 2k × 2k matrix of the levels' responses to the shape parameters of `set` over a
  // step of hs (exact responses R, or Lee's constants), factorised into J_lu_.
  void factor_shape_matrix(const std::vector<int>& set, double hs, const Responses* R) {
    const int k = int(set.size());
    Eigen::MatrixXd J(2 * k, 2 * k);
    const Eigen::MatrixXd& W = rows_at(y_.data()).W;  // a camshaft's rows at the step's start
    for (int i = 0; i < k; ++i) {
      const Eigen::RowVectorXd& ti = mk_.contacts()[set[i]].t;
      for (int l = 0; l < k; ++l) {
        const int j = set[l];
        if (R) {
          J(2 * i, 2 * l) = ti.dot(R->D1[j].head(n_));
          J(2 * i, 2 * l + 1) = ti.dot(R->Dc[j].head(n_));
          J(2 * i + 1, 2 * l) = ti.dot(R->D1[j].segment(n_, n_));
          J(2 * i + 1, 2 * l + 1) = ti.dot(R->Dc[j].segment(n_, n_));
        } else {
          const double w = W(set[i], j);
          J(2 * i, 2 * l) = w * hs * hs / 6.0;
          J(2 * i, 2 * l + 1) = w * hs * hs / 3.0;
          J(2 * i + 1, 2 * l) = w * hs / 2.0;
          J(2 * i + 1, 2 * l + 1) = 2.0 * w * hs / 3.0;
        }
      }
    }
    J_lu_.compute(J);
  }
  double J_h_ = -1.0;  // the step size, responses and set J_lu_ belongs to
  long J_gen_ = -1;
  std::vector<int> J_set_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> J_lu_;
  Eigen::VectorXd le_, r_, d_;

  void run_method() override {
    const int q = eng_->error_order();
    const bool land = sc_.run.land_on_output || out_dt() <= 0.0;
    const double rtol = sc_.solver.rtol, tol_u = sc_.contact.tol_u;
    const double gap_thr = 1e-3 * tol_u;
    double h = initial_step(), h_try = -1.0;
    Eigen::VectorXd y1(ny_);
    {
      CamMotion m;  // a start on a breakpoint: the first step sees the segment after it
      if (one_sided_motion(cam_, drive_, break_angles_, t_, 1, &m)) brk_t_ = t_;
    }
    while (t_ < sc_.run.t_end * (1 - 1e-15)) {
      if (cam_joint_impact()) slope_.setZero();  // closed contacts on a C0 joint of the cam
      const double t_next = stop_before(land ? next_output_time() : sc_.run.t_end);
      const bool relocating = h_try > 0.0;
      double hs = h_try;
      if (!relocating) try {
          hs = fit_step(h, t_next);
        } catch (const StepSizeUnderflow&) {
          throw StepSizeUnderflow(h, trial_error_);  // naming the failed trials' cause
        }
      h_try = -1.0;
      if (hs <= 1e-14 * std::max(1.0, std::abs(t_))) throw StepSizeUnderflow(hs, trial_error_);
      const double t1 = (!relocating && hs == t_next - t_) ? t_next : t_ + hs;
      hs = t1 - t_;
      // The step's cam: the segment after a breakpoint it starts from, the one before a
      // breakpoint it lands on (the cam's acceleration jumps there: an arc's corner, a C1
      // joint of a law).
      const double t_brk = next_break_time();
      set_cam_window(t_ == brk_t_ ? t_ : NAN, t1 == t_brk ? t1 : NAN);
      const CamMotion cm1 = cam_at(t1);
      const double P_prev = dissipation_power(t_, y_);
      const std::vector<int> set = active_list();
      double err_e = 0;
      try {
        err_e = solve_step(set, hs, t1, y1);
      } catch (const IterationFailure& e) {
        trial_error_ = e.what();
        ++sum_.rejected_steps;
        h = 0.5 * hs;
        if (h <= 1e-14 * std::max(1.0, std::abs(t_))) throw StepSizeUnderflow(h, trial_error_);
        continue;
      } catch (const SundialsError& e) {
        // a trial the integrator cannot complete (a user's right-hand side that throws
        // under a trial force): the step is rejected and retried at half the size; its
        // message names the cause if the steps underflow (a non-finite force)
        trial_error_ = e.what();
        ++sum_.rejected_steps;
        ++sum_.iteration_failures;
        h = 0.5 * hs;
        if (h <= 1e-14 * std::max(1.0, std::abs(t_))) throw StepSizeUnderflow(h, trial_error_);
        continue;
      }
      // acceleration level (complementarity: a contact it opens has no force and a
      // negative margin)
      Eigen::VectorXd margin_a;
      const Eigen::VectorXd Fa = held_forces(t1, y1, cm1, set, &margin_a);
      double err_c = 0.0, pc = 5.0;
      for (int j : set) {
        ++sum_.level_a.total;
        const double Fscale = std::max(std::abs(F_[j]), std::abs(Fa[j]));
        const double Wh2 = rows_at(y_.data()).W(j, j) * hs * hs;
        const double tolF = rtol * Fscale + 2.0 * tol_u / Wh2;
        const double e = std::abs(Fa[j] - F1_[j]) / tolF;
        if (e > err_c) {
          err_c = e;
          pc = (3.0 * rtol * Fscale + 5.0 * (tolF - rtol * Fscale)) / tolF;
        }
      }
      if (!set.empty()) {
        sum_.level_a.max = std::max(sum_.level_a.max, 1);
        ++sum_.level_a.steps;
      }
      const double fe = err_e > 0 ? 0.9 * std::pow(err_e, -1.0 / q) : 5.0;
      const double fc = err_c > 0 ? 0.9 * std::pow(err_c, -1.0 / pc) : 5.0;
      const double fac = std::min(5.0, std::max(0.2, std::min(fe, fc)));
      if (std::max(err_e, err_c) > 1.0) {
        ++sum_.rejected_steps;
        steps_.failed(hs);
        h = grid_step(hs * std::min(0.9, fac));
        continue;
      }
      // the step's data, then switches inside it
      StepData& s = sd_;
      s.t0 = t_;
      s.t1 = t1;
      s.y0 = y_;
      s.y1 = y1;
      s.F0 = F_;
      s.F1 = Fa;
      s.set = set;
      s.s0 = F0_;
      s.s1 = F1_;
      s.sc = Fc_;
      acceleration(t_, y_, F_, s.a0);
      acceleration(t1, y1, Fa, s.a1);
      if (ns_) {
        s.r0.resize(ns_);
        s.r1.resize(ns_);
        mk_.state_rate(t_, y_.data(), y_.data() + n_, states_of(y_), s.r0.data());
        mk_.state_rate(t1, y1.data(), y1.data() + n_, states_of(y1), s.r1.data());
      }
      if (const double r = held_drift(s); r > 1.0) {  // the step does not resolve the cam
        ++sum_.rejected_steps;
        steps_.failed(hs);
        h = grid_step(hs * std::max(0.2, std::min(0.5, 0.9 * std::pow(r, -0.25))));
        continue;
      }
      F_ref_ = std::max({F_ref_, F_.cwiseAbs().maxCoeff(), Fa.cwiseAbs().maxCoeff()});
      const double F_thr = 1e-12 * std::max(F_ref_, 1e-300);
      const double F_sep = std::min(rtol, 1e-6) * F_ref_;
      double x_first = 2.0;
      int who = -1;
      std::vector<char>& in_set = in_set_;
      in_set.assign(m_, 0);
      for (int j : set) in_set[j] = 1;
      if (unilateral_)
        for (int j : set) {
          auto f = [&](double x) {
            const double tau = s.t0 + x * hs;
            interpolate(s, tau, yi_);
            held_forces_into(tau, yi_, cam_at(tau), set, hf_, &mg_);
            return mg_[j];
          };
          const double x = first_below(f, F_[j], margin_a[j], F_thr, hs, t1, samples_[j].data());
          if (x >= 0.0 && x < x_first) {
            x_first = x;
            who = j;
          }
        }
      const CamMotion cm0 = cam_at(t_);
      const double h_now = std::max(1e-9 * hs, 1e-14 * std::max(1.0, std::abs(t_)));
      bool impact_now = false;
      for (int j = 0; j < m_; ++j) {
        if (in_set[j]) continue;
        const MechanismContact& c = mk_.contacts()[j];
        const double g0 = gap(j, y_, cm0), g1 = gap(j, y1, cm1);
        const double gd0 = gap_rate(j, y_, cm0), gd1 = gap_rate(j, y1, cm1);
        const double ga0 = mk_.camshaft() ? rows_at(y_.data()).T.row(j).dot(s.a0) - cam_acc(j, y_, cm0)
                                          : c.t.dot(s.a0) - cam_acc(j, cm0);
        const double ga1 = mk_.camshaft() ? rows_at(y1.data()).T.row(j).dot(s.a1) - cam_acc(j, y1, cm1)
                                          : c.t.dot(s.a1) - cam_acc(j, cm1);
        auto f = [&](double x) {
          double u;
          quintic(g0, gd0, ga0, g1, gd1, ga1, hs, x, &u, nullptr, nullptr);
          return u;
        };
        double x = first_below(f, g0, g1, gap_thr, hs, t1);
        if (x >= 0.0 && x * hs <= h_now) {
          // closed at the step's start: approaching, it is an impact now; not approaching
          // (a contact that has just let go, a round-off below zero gap: the engine's error)
          // the start is no switch — relocating to it would shrink the step to nothing —
          // but the gap may still open and close again inside the step: its first fall
          // below zero after its highest sample
          if (gd0 < 0.0) {
            resolve_impact({j}, cm0);
            impact_now = true;
            break;
          }
          x = reclosing(f, hs, t1);
          if (x < 0.0) continue;
        }
        if (x >= 0.0 && x < x_first) {
          x_first = x;
          who = j;
        }
      }
      if (impact_now) {
        slope_.setZero();
        continue;
      }
      if (who >= 0 && x_first < 1.0 - 1e-9) {
        const double hx = x_first * hs;
        // relocations from this t_ toward a separation: the engine's force error (CVODE:
        // the landed step's end force 2e-5 of the peak above zero on the OHC train) can put
        // the pointwise root a little past every step end, the steps shrinking to nothing
        reloc_count_ = reloc_t_ == t_ ? reloc_count_ + 1 : 1;
        reloc_t_ = t_;
        if (in_set[who] && (F_[who] <= F_sep || hx <= 1e-9 * hs || hx <= 1e-14 * std::max(1.0, std::abs(t_)) ||
                            reloc_count_ > kMaxRelocations)) {
          // the held force is zero at the step's start (or within the located root's
          // resolution after kMaxRelocations relocations): release now
          active_[who] = 0;
          ++sum_.separations;
          record_event(EventKind::Separation, who, 0.0);
          settle_active(cam_at(t_));
          slope_.setZero();
          continue;
        }
        ++sum_.relocated_steps;
        h_try = std::max(x_first, 1e-9) * hs;
        continue;
      }
      // accept
      if (unilateral_)
        for (int j : set) least_force_inside(s, j);
      else
        for (int j : set) first_tensile_inside(s, j);
      s.power.clear();
      if (unilateral_ && !set.empty()) {
        s.power.assign(kSwitchSamples + 1, 0.0);
        for (int k = 0; k <= kSwitchSamples; ++k) {
          const CamMotion c = k == 0 ? cm0 : k == kSwitchSamples ? cm1 : cam_at(s.t0 + hs * double(k) / kSwitchSamples);
          for (int j : set)
            if (mk_.contacts()[j].cam && !(mk_.camshaft() && mk_.camshaft()->contact_cam(j) >= 0))
              s.power[k] += samples_[j][k] * c.Xdot;
        }
      }
      s.W0 = work_;
      s.D0 = dissipated_;
      s.P0 = P_prev;
      const StepEnergy dE = shape_energy(s, t1);
      for (int j : set) slope_[j] = (Fa[j] - F_[j]) / hs;
      y_ = y1;
      t_ = t1;
      F_ = Fa;
      bool changed = false;
      for (int j : set)
        if (unilateral_ && (Fa[j] <= F_sep || (who == j))) {
          active_[j] = 0;
          F_[j] = 0.0;
          slope_[j] = 0.0;
          ++sum_.separations;
          record_event(EventKind::Separation, j, 0.0);
          changed = true;
        }
      for (int j : set)
        if (active_[j]) F_[j] = unilateral_ ? std::max(F_[j], 0.0) : F_[j];
      // impacts: inactive contacts closed at the step's end
      std::vector<int> closing;
      for (int j = 0; j < m_; ++j) {
        if (active_[j] || in_set[j]) continue;
        const double g = gap(j, y_, cm1);
        // closed and not opening (a contact that has just let go may sit within round-off of
        // zero while it opens: that is no impact)
        if ((g <= gap_thr || (relocating && who == j) || (relocating && g <= tol_u)) && gap_rate(j, y_, cm1) <= 0.0)
          closing.push_back(j);
      }
      const double P_end = dissipation_power(t_, y_);
      if (!closing.empty()) {
        resolve_impact(closing, cm1);
        changed = true;
      } else if (changed) {
        settle_active(cm1);
      }
      if (changed) slope_.setZero();
      if (t_ == t_brk) {
        // Landed on a breakpoint: the held forces the next step starts from are those of
        // the segment after it (its shape starts at F_; a force from the segment before
        // put the jump of m Ẍ_C into the next step's force shape, and its work off).
        brk_t_ = t_;
        set_cam_window(t_, NAN);
        if (!changed) {
          const std::vector<int> held = active_list();
          if (!held.empty()) {
            const Eigen::VectorXd Fb = held_forces(t_, y_, cam_at(t_), held);
            for (int j : held) F_[j] = unilateral_ ? std::max(Fb[j], 0.0) : Fb[j];
            slope_.setZero();
          }
        }
      }
      dense_ = land ? nullptr : &sd_;
      after_step(hs, dE.work, P_prev, closing.empty() ? NAN : P_end, dE.dissipated);
      dense_ = nullptr;
      if (!relocating) h = steps_.propose(hs, fac);
    }
  }
};

}  // namespace

std::unique_ptr<ContactRun> make_network_lee(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                             Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<LeeLocated>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
