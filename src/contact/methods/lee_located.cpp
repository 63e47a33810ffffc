// camdyn — Lee's located step on a mechanism: the run loop (the step's trial, error
// test, switch location and acceptance). The method: methods/lee_located.hpp; the trial
// step's force shape and its levels: methods/lee_located_step.cpp.
#include "contact/methods/lee_located.hpp"

namespace camdyn {
namespace detail {

void LeeLocated::run_method() {
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
    const int sep_target = relocating ? reloc_sep_ : -1;
    const double sliver_of = reloc_from_h_;
    reloc_sep_ = -1;
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
      ++rec_.rejected_steps;
      h = 0.5 * hs;
      if (h <= 1e-14 * std::max(1.0, std::abs(t_))) throw StepSizeUnderflow(h, trial_error_);
      continue;
    } catch (const SundialsError& e) {
      // a trial the integrator cannot complete (a user's right-hand side that throws
      // under a trial force): the step is rejected and retried at half the size; its
      // message names the cause if the steps underflow (a non-finite force)
      trial_error_ = e.what();
      ++rec_.rejected_steps;
      ++rec_.iteration_failures;
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
      ++rec_.level_a.total;
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
      rec_.level_a.max = std::max(rec_.level_a.max, 1);
      ++rec_.level_a.steps;
    }
    const double fe = err_e > 0 ? 0.9 * std::pow(err_e, -1.0 / q) : 5.0;
    const double fc = err_c > 0 ? 0.9 * std::pow(err_c, -1.0 / pc) : 5.0;
    const double fac = std::min(5.0, std::max(0.2, std::min(fe, fc)));
    if (std::max(err_e, err_c) > 1.0) {
      if (sep_target >= 0 && hs <= kSliver * sliver_of) {
        release_now(sep_target);  // the separation's root is within round-off of t_
        continue;
      }
      ++rec_.rejected_steps;
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
      ++rec_.rejected_steps;
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
        release_now(who);
        continue;
      }
      ++rec_.relocated_steps;
      if (in_set[who]) {
        reloc_sep_ = who;
        reloc_from_h_ = hs;
      }
      h_try = std::max(x_first, 1e-9) * hs;
      continue;
    }
    // accept
    if (unilateral_)
      for (int j : set) least_force_inside(s, j);
    else
      for (int j : set) first_tensile_inside(s, j);
    trace_step(
        s.t0, t1, [&](double tau, Eigen::VectorXd& y) { held_state_at(s, tau, y); },
        [&](double tau, const Eigen::VectorXd& y, const CamMotion& c, Eigen::VectorXd& F) {
          held_forces_into(tau, y, c, set, F);
        },
        set);
    s.power.clear();
    if (unilateral_ && !set.empty()) {
      s.power.assign(kSwitchSamples + 1, 0.0);
      for (int k = 0; k <= kSwitchSamples; ++k) {
        const CamMotion c = k == 0 ? cm0 : k == kSwitchSamples ? cm1 : cam_at(s.t0 + hs * double(k) / kSwitchSamples);
        for (int j : set) s.power[k] += samples_[j][k] * driven_cam_speed(j, c);
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
        ++rec_.separations;
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

std::unique_ptr<ContactRun> make_lee_located(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech,
                                             Observer* obs, const std::atomic<bool>* stop) {
  return std::make_unique<LeeLocated>(sc, std::move(mech), obs, stop);
}

}  // namespace detail
}  // namespace camdyn
