// camdyn — the run machinery every contact method shares (contact_run.hpp).
#include "contact/contact_run.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "cam/lift_base.hpp"
#include "contact/active_set.hpp"
#include "mechanism/element_set.hpp"
#include "cam/joints.hpp"  // one_sided_motion
#include "contact/run_clock.hpp"
#include "contact/run_failure.hpp"
#include "contact/step_control.hpp"
#include "scene/shared_cam.hpp"

namespace camdyn {
namespace detail {

namespace {
std::vector<std::string> contact_names(const MechanicalSystem& m) {
  std::vector<std::string> n;
  for (const MechanismContact& c : m.contacts()) n.push_back(c.name);
  return n;
}
constexpr double kFloatLift = 0.01;  // a float: the cam above clearance + 1 % of its lift
constexpr double kCheckGaps = 10.0;  // the step check's gap tolerance in tol_u
}  // namespace

ContactRun::ContactRun(const Scene& sc, std::shared_ptr<const MechanicalSystem> mech, Observer* obs,
                       const std::atomic<bool>* stop)
    : sc_(sc), mech_(std::move(mech)), mk_(*mech_), cam_owner_(shared_cam(sc.cam)), cam_(*cam_owner_), drive_(sc.cam), obs_(obs),
      stop_(stop), n_(mk_.n()), m_(mk_.m()), ns_(mk_.states()), ny_(2 * n_ + ns_), designer_(sc, cam_owner_),
      analysis_(sc, contact_names(*mech_), mech_->node_names(), cam_.lift(), &cam_),
      flights_(contact_names(*mech_), sc.contact.model == ContactModel::Penalty ? 0.0 : sc.contact.tol_u),
      surge_(mech_->surge_names(), drive_.theta(0.0)), surge_buf_(mech_->surge_names().size(), 0.0) {
  rec_.model = mk_.description();
  for (const MechanismContact& c : mk_.contacts()) {
    rec_.contacts.emplace_back();
    rec_.contacts.back().name = c.name;
    rec_.contacts.back().coil_spring = c.coil_spring;
  }
  unilateral_ = sc.contact.separation && sc.contact.model != ContactModel::Holonomic;
  element_force_count_ = mk_.element_force_names().size();
  if (!mk_.linear() && mk_.traits().named_contacts && element_force_count_ > 0) {
    element_results_ = true;
    for (const std::string& name : mk_.element_force_names()) {
      rec_.elements.emplace_back();
      rec_.elements.back().name = name;
    }
    element_buf_.assign(element_force_count_, 0.0);
    element_cyc_min_.assign(element_force_count_, INFINITY);
    element_cyc_max_.assign(element_force_count_, -INFINITY);
  }
  if (sc.cam.land_on_breaks) break_angles_ = cam_.breakpoints();
  // The base circle, so that a cam contact's gap sees the lift X_C − X_base
  // (cam_lift_base, cam/lift_base.hpp: cam.base_radius for a lift table,
  // min over θ of X_C otherwise).
  // A cam_lift_absolute mechanism's gap sees the cam's X_C itself (u_c = q₀).
  if (!mk_.traits().cam_lift_absolute && (sc.cam.profile == CamProfileKind::Lift || mk_.cam_contacts() > 0))
    x_base_ = cam_lift_base(cam_, sc.cam);
  // The lash take-up window: the cam lifts from the lowest to the highest level where a
  // clearance on the path is taken up (each cam contact's own, each lash contact's reached
  // from a cam contact), widened by kFloatLift of the lift on both sides.
  std::vector<double> levels = analysis_.take_up_levels();
  for (const MechanismContact& c : mk_.contacts())
    if (c.cam) levels.push_back(c.g0);
  if (!levels.empty()) {
    const double d = kFloatLift * cam_.lift();
    take_up_lo_ = *std::min_element(levels.begin(), levels.end()) - d;
    take_up_hi_ = *std::max_element(levels.begin(), levels.end()) + d;
  }
}

OdeSystem ContactRun::contact_system(ForceFn forces) {
  OdeSystem sys;
  sys.size = ny_;
  sys.atol = absolute_tolerances();
  sys.rhs = [this, forces = std::move(forces)](double t, const double* y, double* yd) {
    sys_y_ = Eigen::Map<const Eigen::VectorXd>(y, ny_);
    forces(t, sys_y_, sys_F_);
    std::copy(y + n_, y + 2 * n_, yd);
    mk_.acceleration(t, y, y + n_, sys_F_, yd + n_, false, states_of(y));
    if (ns_) mk_.state_rate(t, y, y + n_, states_of(y), yd + 2 * n_);
  };
  return sys;
}

std::shared_ptr<SparseNewton> ContactRun::sparse_newton() const {
  const auto* mech = dynamic_cast<const Mechanism*>(&mk_);
  if (!mech) return nullptr;
  auto sn = std::make_shared<SparseNewton>();
  sn->M = &mech->M();
  sn->K = &mech->K();
  sn->C = mech->damped() ? &mech->C() : nullptr;
  sn->T = mk_.T();
  const ElementSet& el = mech->elements();
  if (!el.empty()) {
    sn->Ke_pattern = &el.stiffness_pattern();
    sn->Ce_pattern = el.damps() ? &el.damping_pattern() : nullptr;
    sn->element_tangent = [this, mech, n = n_](double t, const double* y, SparseMatrix& Ke, SparseMatrix& Ce) {
      mech->elements().tangent(t, y, y + n, Ke, Ce, states_of(y));
    };
  }
  if (el.states() > 0) {
    sn->states = el.states();
    sn->Rs_pattern = &el.rs_pattern();
    sn->Gq_pattern = &el.gq_pattern();
    sn->state_blocks = [this, mech, n = n_](double t, const double* y, SparseMatrix& Rs, SparseMatrix& Gq,
                                            SparseMatrix& Gv, Eigen::MatrixXd& Gs) {
      mech->elements().state_tangent(t, y, y + n, states_of(y), Rs, Gq, Gv, Gs);
    };
  }
  return sn;
}

std::function<void(double, const double*, Eigen::MatrixXd&)> ContactRun::dense_jacobian(
    const std::vector<int>* held) const {
  Eigen::MatrixXd dq, dv;
  const Eigen::VectorXd q0 = mk_.q0(), v0 = mk_.v0();
  if (!mk_.acceleration_jacobian(0.0, q0.data(), v0.data(), dq, dv)) return {};
  return [this, held](double t, const double* y, Eigen::MatrixXd& J) {
    Eigen::MatrixXd dadq, dadv;
    mk_.acceleration_jacobian(t, y, y + n_, dadq, dadv);
    const int k = held ? int(held->size()) : 0;
    if (k > 0) {
      const std::vector<int>& S = *held;
      Eigen::MatrixXd MT(n_, k), Ts(k, n_), Wss(k, k);
      for (int i = 0; i < k; ++i) {
        MT.col(i) = mk_.MinvTt().col(S[std::size_t(i)]);
        Ts.row(i) = mk_.T().row(S[std::size_t(i)]);
        for (int l = 0; l < k; ++l) Wss(i, l) = mk_.W()(S[std::size_t(i)], S[std::size_t(l)]);
      }
      const Eigen::MatrixXd G = MT * Wss.completeOrthogonalDecomposition().solve(Ts);
      dadq -= G * dadq;
      dadv -= G * dadv;
    }
    J.setZero();
    J.topRightCorner(n_, n_).setIdentity();
    J.bottomLeftCorner(n_, n_) = dadq;
    J.bottomRightCorner(n_, n_) = dadv;
  };
}

CamMotion ContactRun::cam_at(double t) const {
  // At a breakpoint that starts (ends) the window: the segment after (before) it. Only the
  // window's breakpoint ends can be within 1e-9 rad of θ(t) (steps land on breakpoints).
  int side = 0;
  if (!std::isnan(win_lo_) || !std::isnan(win_hi_)) {
    const double dlo = std::isnan(win_lo_) ? INFINITY : std::abs(t - win_lo_);
    const double dhi = std::isnan(win_hi_) ? INFINITY : std::abs(t - win_hi_);
    side = dlo <= dhi ? 1 : -1;
  }
  // The last few times asked for are asked again (a row: its state, forces, energies).
  for (const CamCache& c : cam_cache_)
    if (c.t == t && c.side == side) return c.m;
  CamMotion m;  // on a C0 joint: the motion before it, or after it once passed (joint_t_)
  const bool on_joint = !joints_.empty() && joints_.at(cam_, t, t == joint_t_ ? 1 : -1, &m);
  if (!on_joint && !(side && one_sided_motion(cam_, drive_, break_angles_, t, side, &m)))
    m = cam_.motion(drive_.theta(t), drive_.omega(t), drive_.omega_dot(t));
  m.X -= x_base_;
  m.t = t;
  cam_cache_[cam_next_] = {t, side, m};
  cam_next_ = (cam_next_ + 1) % kCamCache;
  return m;
}
double ContactRun::gap(int j, const Eigen::VectorXd& y, const CamMotion& cm) const {
  const MechanismContact& c = mk_.contacts()[j];
  if (const CamShaft* cs = mk_.camshaft(); cs && cs->contact_cam(j) >= 0)  // the cam at its station's angle
    return c.t.dot(y.head(n_)) + c.g0 - cs->lift(j, shaft_time(j, cm), y.data()).X;
  return c.t.dot(y.head(n_)) + c.g0 - (c.cam ? cm.X : 0.0);
}
double ContactRun::gap_rate(int j, const Eigen::VectorXd& y, const CamMotion& cm) const {
  const MechanismContact& c = mk_.contacts()[j];
  if (const CamShaft* cs = mk_.camshaft(); cs && cs->contact_cam(j) >= 0)  // T̃_j v = T_j v − X_L′ φ̇_s
    return c.t.dot(y.segment(n_, n_)) - cs->contact_cam_motion(j, shaft_time(j, cm), y.data(), y.data() + n_).Xdot;
  return c.t.dot(y.segment(n_, n_)) - (c.cam ? cm.Xdot : 0.0);
}
double ContactRun::cam_acc(int j, const CamMotion& cm) const {
  return mk_.contacts()[j].cam ? cm.Xddot : 0.0;
}
void ContactRun::acceleration(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& F,
                              Eigen::VectorXd& a) const {
  for (int i = 0; i < 2; ++i) {
    const AccCache& c = acc_cache_[(acc_last_ + i) % 2];
    if (c.t == t && c.F.size() == F.size() && c.y.size() == y.size() && c.F == F && c.y == y) {
      a = c.a;
      acc_last_ = (acc_last_ + i) % 2;
      return;
    }
  }
  acc_last_ = (acc_last_ + 1) % 2;
  AccCache& c = acc_cache_[acc_last_];
  c.t = NAN;  // invalid until filled (a user's force may throw)
  c.a.resize(n_);
  mk_.acceleration(t, y.data(), y.data() + n_, F, c.a.data(), false, states_of(y));
  c.t = t;
  c.y = y;
  c.F = F;
  a = c.a;
}

Eigen::VectorXd ContactRun::held_forces(double t, const Eigen::VectorXd& y, const CamMotion& cm,
                                        const std::vector<int>& set, Eigen::VectorXd* margin,
                                        bool* ok) const {
  Eigen::VectorXd F;
  held_forces_into(t, y, cm, set, F, margin, ok);
  return F;
}

void ContactRun::held_forces_into(double t, const Eigen::VectorXd& y, const CamMotion& cm,
                                  const std::vector<int>& set, Eigen::VectorXd& F, Eigen::VectorXd* margin,
                                  bool* ok) const {
  F.setZero(m_);
  if (margin) margin->setZero(m_);
  if (ok) *ok = true;
  if (set.empty()) return;
  Eigen::VectorXd& Ta = hf_ta_;
  const Rows R = rows_at(y.data());
  if (mk_.camshaft()) {  // T̃ a_free at the state's rows
    hf_a_.resize(n_);
    mk_.acceleration(t, y.data(), y.data() + n_, Eigen::VectorXd(), hf_a_.data(), false, states_of(y));
    Ta = R.T * hf_a_;
  } else {
    mk_.contact_free_acceleration(t, y.data(), y.data() + n_, Ta, states_of(y));  // T a_free
  }
  const int k = int(set.size());
  if (k == 1) {  // one held contact (a single follower): scalars, the same arithmetic
    const int j = set[0];
    const double W = R.W(j, j), b = Ta[j] - cam_acc(j, y, cm);
    if (!unilateral_) {
      F[j] = -b / W;
      if (margin) (*margin)[j] = F[j];
      return;
    }
    double w = 0.0;
    const bool good = solve_contact_lcp1(W, b, F[j], w);
    if (ok) *ok = good;
    if (margin) (*margin)[j] = F[j] - w / W;
    return;
  }
  // per thread, not per call (this runs inside every right-hand side of the event method)
  thread_local Eigen::MatrixXd Wss;
  thread_local Eigen::VectorXd b;  // the gap accelerations without contact forces
  Wss.resize(k, k);
  b.resize(k);
  for (int i = 0; i < k; ++i) {
    b[i] = Ta[set[i]] - cam_acc(set[i], y, cm);
    for (int l = 0; l < k; ++l) Wss(i, l) = R.W(set[i], set[l]);
  }
  if (!unilateral_) {  // holonomic: every contact held, pulls allowed
    const Eigen::VectorXd Fs = k == 1 ? Eigen::VectorXd(-b / Wss(0, 0))
                                      : Eigen::VectorXd(Wss.completeOrthogonalDecomposition().solve(-b));
    for (int i = 0; i < k; ++i) F[set[i]] = Fs[i];
    if (margin)
      for (int i = 0; i < k; ++i) (*margin)[set[i]] = Fs[i];
    return;
  }
  // complementarity (active_set.hpp): an open-going contact carries no force, redundant
  // ones share by the minimal norm
  const ContactLcpResult r = solve_contact_lcp(Wss, b);
  if (ok) *ok = r.ok;
  for (int i = 0; i < k; ++i) F[set[i]] = r.F[i];
  if (margin)
    for (int i = 0; i < k; ++i) (*margin)[set[i]] = r.F[i] - r.w[i] / Wss(i, i);
}

std::vector<int> ContactRun::active_list() const {
  std::vector<int> a;
  for (int j = 0; j < m_; ++j)
    if (active_[j]) a.push_back(j);
  return a;
}

double ContactRun::potential(double t, const Eigen::VectorXd& y) const {
  return mk_.potential_energy(y.data(), states_of(y)) + contact_potential(t, y.data());
}
double ContactRun::dissipation_power(double t, const Eigen::VectorXd& y) const {
  return mk_.damping_power(t, y.data(), y.data() + n_, states_of(y)) + contact_dissipation(t, y);
}
double ContactRun::cam_power(const Eigen::VectorXd& F, const CamMotion& cm) const {
  double p = 0.0;
  for (int j = 0; j < m_; ++j)
    if (F[j] != 0.0) p += F[j] * driven_cam_speed(j, cm);
  return p;
}
double ContactRun::driven_cam_speed(int j, const CamMotion& cm) const {
  if (!mk_.contacts()[j].cam) return 0.0;
  const CamShaft* cs = mk_.camshaft();
  if (!cs || cs->contact_cam(j) < 0) return cm.Xdot;
  if (cs->on_free_station(j)) return 0.0;  // works inside the mechanism
  return cs->contact_cam_motion(j, shaft_time(j, cm), nullptr, nullptr).Xdot;  // the prescribed station's
}
double ContactRun::shaft_time(int j, const CamMotion& cm) const {
  const CamShaft* cs = mk_.camshaft();
  if (cs && cs->on_prescribed_station(j) && std::isnan(cm.t))
    throw std::logic_error("ContactRun: a cam on the prescribed drive station evaluated without the time");
  return cm.t;
}

ContactRun::StepEnergy ContactRun::step_energy(
    double t0, double t1, const std::function<void(double, Eigen::VectorXd&)>& state,
    const std::function<void(double, const Eigen::VectorXd&, const CamMotion&, Eigen::VectorXd&)>& forces) const {
  static const double xg[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static const double wg[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  StepEnergy e;
  const double h = t1 - t0;
  if (!(h > 0)) return e;
  Eigen::VectorXd &y = se_y_, &F = se_F_;
  y.resize(ny_);
  F.resize(m_);
  for (int g = 0; g < 3; ++g) {
    const double tau = t0 + 0.5 * h * (1.0 + xg[g]);
    state(tau, y);
    const CamMotion cm = cam_at(tau);
    forces(tau, y, cm, F);
    e.work += 0.5 * h * wg[g] * (cam_power(F, cm) + mk_.input_power(tau, y.data(), y.data() + n_));
    e.dissipated += 0.5 * h * wg[g] * dissipation_power(tau, y);
    if (g == 1) {
      se_mid_t0_ = t0;
      se_mid_t1_ = t1;
      se_mid_y_ = y;
      se_mid_F_ = F;
    }
  }
  return e;
}

void ContactRun::after_step(double h, double dW, double P_prev, double P_end, double dD) {
  ++rec_.steps;
  sample_elements();
  const CamMotion cm = cam_at(t_);
  const double P = std::isnan(P_end) ? dissipation_power(t_, y_) : P_end;
  work_ += dW;
  dissipated_ += std::isnan(dD) ? 0.5 * h * (P_prev + P) : dD;
  rec_.energy_scale = std::max({rec_.energy_scale, std::abs(work_), std::abs(dissipated_)});
  for (int j = 0; j < m_; ++j) {
    const double g = gap(j, y_, cm);
    rec_.min_gap = std::min(rec_.min_gap, g);
    rec_.max_penetration = std::max(rec_.max_penetration, -g);
    rec_.max_contact_force = std::max(rec_.max_contact_force, F_[j]);
    if (!active_[j]) flights_.sample(j, g);
  }
  check_complementarity(cm);
  if (!surge_.empty()) {
    mk_.surge(y_.data(), surge_buf_.data());
    surge_.sample(drive_.theta(t_), surge_buf_.data());
  }
  if (obs_) {
    StepInfo info;
    info.t0 = t_ - h;
    info.h = h;
    info.step = rec_.steps;
    info.contacts = m_;
    info.force_start = step_F0_.data();
    info.force_end = F_.data();
    obs_->on_step(info);
  }
  step_F0_ = F_;
  for (int j = 0; j < m_ && !unilateral_ && rec_.first_tensile_time < 0; ++j)
    if (active_[j] && F_[j] < 0.0) {  // a bilateral contact pulls: where a follower would leave
      rec_.first_tensile_time = t_;
      record_event(EventKind::Tensile, j, 0.0);
    }
  const int p = mk_.primary();
  const MechanismContact& c = mk_.contacts()[p];
  const double th = drive_.theta(t_);
  designer_.step(t_, th, c.t.dot(y_.head(n_)) + c.g0, c.t.dot(y_.segment(n_, n_)), contact_acceleration(p), gap(p, y_, cm));
  // the cam at the step end: the trace's end sample's when it is at this angle
  const CamPoint* cp = traced_end_cam(t_, th);
  sample_side_loads(th, cp);
  if (active_[p]) designer_.sample_force(t_, th, F_[p], cp);
  if (out_dt() <= 0.0) {
    emit_row();
  } else {
    while (!observer_stop_ && next_out_ * out_dt() <= t_ * (1 + 1e-12) + 1e-300 &&
           next_out_ * out_dt() <= sc_.run.t_end * (1 + 1e-12)) {
      const double to = double(next_out_) * out_dt();
      ++next_out_;
      if (!(to < t_ && dense_row_at(to))) emit_row();
    }
    if (!observer_stop_ && t_ >= sc_.run.t_end && last_row_t_ < t_) emit_row();
  }
  if (observer_stop_) throw StepFailure(Termination::StoppedByObserver, "stopped by observer");
  if (stop_ && stop_->load()) throw StepFailure(Termination::StoppedByCaller, stop_reason_);
  if (rec_.steps + rec_.rejected_steps > sc_.run.max_steps)
    throw StepFailure(Termination::MaxSteps, "run.max_steps = " + std::to_string(sc_.run.max_steps) + " reached");
  if (!y_.allFinite() || !F_.allFinite()) throw StepFailure(Termination::NonFinite, "non-finite state");
  if (obs_ && (rec_.steps & 255) == 0) obs_->on_progress(t_, sc_.run.t_end, rec_.steps);
}

double ContactRun::contact_acceleration(int p) const {
  if (!mk_.traits().linear_contact_acceleration) {
    Eigen::VectorXd a;
    acceleration(t_, y_, F_, a);
    return mk_.contacts()[p].t.dot(a);
  }
  // T_p a = T_p a_free + W_p F: O(n) linear forms, no mass solve (the same value to round-off)
  mk_.contact_free_acceleration(t_, y_.data(), y_.data() + n_, hf_ta_, states_of(y_));
  return hf_ta_[p] + mk_.W().row(p).dot(F_);
}

void ContactRun::check_complementarity(const CamMotion& cm) const {
  // Tolerances: a closed contact's gap is held to tol_u by Lee's displacement level and
  // drifts a little under the event method's acceleration level; kCheckGaps·tol_u allows
  // that and still catches a contact pushing across an open gap or a node sinking into a
  // stop by a visible amount. Penalty contacts penetrate by their law (F/k_p): only the
  // force-on-open-gap check applies there (the law cannot violate it).
  if (!unilateral_) return;
  const double tol = kCheckGaps * sc_.contact.tol_u;
  const double F_thr = 1e-9 * std::max(F_ref_, mk_.force_scale());
  for (int j = 0; j < m_; ++j) {
    const double g = gap(j, y_, cm);
    // the message only when it is thrown (its formatting cost a run 5 % of its time)
    auto where = [&] {
      return "at t = " + fmt(t_) + " (cam angle " + fmt(angle_deg_mod360(drive_.theta(t_))) + " deg): contact '" +
             mk_.contacts()[j].name + "' ";
    };
    if (F_[j] > F_thr && g > tol)
      throw StepFailure(where() + "carries a force of " + fmt(F_[j]) + " N while its gap is open (" + fmt(g) +
                        " > " + fmt(kCheckGaps) + " tol_u): complementarity violated");
    if (penetration_checked() && -g > tol)
      throw StepFailure(where() + "penetrates by " + fmt(-g) + " (> " + fmt(kCheckGaps) +
                        " tol_u = " + fmt(tol) + ")");
  }
}

double ContactRun::fit_step(double h, double t_next) const { return fit_step_size(sc_, t_, h, t_next); }
double ContactRun::initial_step() const { return first_step_size(sc_); }
double ContactRun::next_output_time() const { return output_time(sc_, next_out_); }

const RunRecord& ContactRun::run() {
  Clock clock;
  y_.resize(ny_);
  y_.head(n_) = mk_.q0();
  y_.segment(n_, n_) = mk_.v0();
  y_.tail(ns_) = mk_.s0();
  t_ = 0.0;
  F_ = Eigen::VectorXd::Zero(m_);
  active_.assign(m_, 0);
  // Closed contacts at t = 0 (gap ≤ 0 and not opening) start active with the forces of
  // the acceleration level; the ones that would pull are released at once.
  const CamMotion cm0 = cam_at(0.0);
  const double gtol = 1e-12 * std::max(1.0, y_.head(n_).cwiseAbs().maxCoeff());
  for (int j = 0; j < m_; ++j)
    if (gap(j, y_, cm0) <= gtol && gap_rate(j, y_, cm0) <= gtol) active_[j] = 1;
  settle_active(cm0);
  close_creeping_contacts(cm0, gtol);
  if (sc_.contact.model != ContactModel::Penalty) flights_.set_gap_tolerance(stick_gap_tol_);
  prepare_start();
  note_shaft_frequencies();
  for (int j = 0; j < m_; ++j)  // the start's forces are samples of the least force too
    if (active_[j]) sample_held_force(j, 0.0, F_[j]);
  sample_elements();
  V0_ = potential(0.0, y_);
  E0_ = mk_.kinetic_energy(y_.data() + n_) + V0_;
  emit_row();
  step_F0_ = F_;
  {
    const int p = mk_.primary();
    const MechanismContact& c = mk_.contacts()[p];
    Eigen::VectorXd a;
    acceleration(t_, y_, F_, a);
    designer_.step(0.0, drive_.theta(0.0), c.t.dot(y_.head(n_)) + c.g0, c.t.dot(y_.segment(n_, n_)),
                   c.t.dot(a), gap(p, y_, cm0));
  }
  next_out_ = 1;
  auto end_run = [&](Termination kind, const char* what) {
    rec_.finished = false;
    rec_.termination = kind;
    rec_.message = "at t = " + fmt(t_) + ": " + what;
    if (last_row_t_ < t_ && !observer_stop_) emit_row();  // keep the last accepted state
  };
  run_to_end(rec_, end_run, [&] {
    if (observer_stop_) throw StepFailure(Termination::StoppedByObserver, "stopped by observer");
    run_method();
  });
  rec_.t_end = t_;
  for (const auto& e : engines_) {
    rec_.rhs_evals += e->stats().rhs_evals;
    rec_.lin_setups += e->stats().lin_setups;
    rec_.lin_analyses += e->stats().lin_analyses;
    rec_.nonlin_iters += e->stats().nonlin_iters;
    rec_.nonlin_conv_fails += e->stats().nonlin_conv_fails;
    rec_.err_test_fails += e->stats().err_test_fails;
    rec_.engine_restarts += e->stats().reinits;
    rec_.max_bdf_order_used = std::max(rec_.max_bdf_order_used, e->stats().max_order_used);
  }
  rec_.cpu_seconds = clock.cpu();
  rec_.wall_seconds = clock.wall();
  const double E = mk_.kinetic_energy(y_.data() + n_) + potential(t_, y_);
  rec_.energy_residual = std::abs(work_ - (E - E0_) - dissipated_);
  rec_.energy_magnitude =
      std::max({std::abs(E0_), std::abs(E), rec_.max_contact_force * cam_.lift()});
  if (!atol_note_.empty()) rec_.warnings.push_back(atol_note_);
  return rec_;
}

}  // namespace detail
}  // namespace camdyn

namespace camdyn {
namespace detail {

// One factory per method file (methods/*.cpp); each runs every follower kind.
std::unique_ptr<ContactRun> make_lee_located(const Scene&, std::shared_ptr<const MechanicalSystem>, Observer*,
                                             const std::atomic<bool>*);
std::unique_ptr<ContactRun> make_penalty_method(const Scene&, std::shared_ptr<const MechanicalSystem>,
                                                Observer*, const std::atomic<bool>*);
std::unique_ptr<ContactRun> make_event_method(const Scene&, std::shared_ptr<const MechanicalSystem>,
                                              Observer*, const std::atomic<bool>*);
std::unique_ptr<ContactRun> make_lee_in_cvode(const Scene&, std::shared_ptr<const MechanicalSystem>,
                                              Observer*, const std::atomic<bool>*);
std::unique_ptr<ContactRun> make_holonomic_ida(const Scene&, std::shared_ptr<const MechanicalSystem>, Observer*,
                                               const std::atomic<bool>*);

// The contact methods: Lee's located step (lee; holonomic = Lee with contacts that never
// release; on cvode-bdf Lee's levels inside CVODE's own step, methods/lee_cvode.cpp), the
// penalty baseline, the event-driven method; on ida (validated: holonomic only) the held
// contacts as a DAE (methods/holonomic_ida.cpp).
std::unique_ptr<ContactRun> make_contact_method(const Scene& scene, std::shared_ptr<const MechanicalSystem> mech,
                                                Observer* obs, const std::atomic<bool>* stop) {
  if (scene.solver.integrator == Integrator::Ida) return make_holonomic_ida(scene, std::move(mech), obs, stop);
  switch (scene.contact.model) {
    case ContactModel::Lee:
    case ContactModel::Holonomic:
      if (scene.solver.integrator == Integrator::CvodeBdf)
        return make_lee_in_cvode(scene, std::move(mech), obs, stop);
      return make_lee_located(scene, std::move(mech), obs, stop);
    case ContactModel::Penalty:
      return make_penalty_method(scene, std::move(mech), obs, stop);
    case ContactModel::Event:
      return make_event_method(scene, std::move(mech), obs, stop);
  }
  throw std::logic_error("no contact method for this contact.model");
}

}  // namespace detail
}  // namespace camdyn
