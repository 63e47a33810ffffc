// camdyn — Lee's located step on a mechanism: the trial step under the force shape, the
// responses to a unit shape, and the displacement and velocity levels solved for the
// shape parameters (methods/lee_located.hpp).
#include "contact/methods/lee_located.hpp"

namespace camdyn {
namespace detail {

LeeLocated::Responses& LeeLocated::responses(double hs, const std::vector<int>& set) {
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
    integrate_on(*resp_eng_, 0.0, zero, hs, r->D1[j]);
    r->D1[j] /= amp;
    r->E1[j] = resp_eng_->local_error() / amp;
    F1_[j] = 0.0;
    Fc_[j] = amp;
    integrate_on(*resp_eng_, 0.0, zero, hs, r->Dc[j]);
    r->Dc[j] /= amp;
    r->Ec[j] = resp_eng_->local_error() / amp;
    homogeneous_ = false;
    r->have[j] = 1;
    rec_.contact_iterations += 2;
  }
  F0_ = keep0;
  F1_ = keep1;
  Fc_ = keepc;
  return *r;
}

double LeeLocated::solve_step(const std::vector<int>& set, double hs, double t1, Eigen::VectorXd& y1) {
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
  // affine step map: a one-step engine on a linear system. A network with nonlinear
  // elements (linear_part_): the first correction through its linear part's responses,
  // kept if its estimated linearisation error is within kLinearisedShare of the
  // tolerances, else the step is integrated again and iterated. A user's nonlinear
  // follower: iterated with Lee's constants, which see only the contacts' inverse mass W.
  const bool affine = mk_.linear();
  bool linearised = linear_part_;
  Eigen::VectorXd& le = le_;
  le = eng_->local_error();
  if (linearised && (part_step_ < 0 || part_stale_)) refresh_part();
  Responses* R = (affine || linearised) ? &responses(hs, set) : nullptr;
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
      ++rec_.iteration_failures;
      throw IterationFailure();
    }
    d = lu.solve(r);
    if (!d.allFinite()) {
      ++rec_.iteration_failures;
      throw IterationFailure(non_finite_cause(t1, y1));
    }
    ++it;
    ++rec_.contact_iterations;
    if (linearised) lin_y_ = y1;
    for (int l = 0; l < k; ++l) {
      const int j = set[l];
      F1_[j] += d[2 * l];
      Fc_[j] += d[2 * l + 1];
      if (affine || linearised) {
        y1 += d[2 * l] * R->D1[j] + d[2 * l + 1] * R->Dc[j];
        le += d[2 * l] * R->E1[j] + d[2 * l + 1] * R->Ec[j];
      }
    }
    if (affine) {
      err = eng_->wrms(le, y_);
    } else if (linearised) {
      linearised = false;  // one linearised correction per step at most
      linearisation_error(t1, hs, lin_y_, y1);
      bool small = eng_->wrms(lin_err_, y_) <= kLinearisedShare;
      for (int i = 0; i < k && small; ++i) {
        const Eigen::RowVectorXd& ti = mk_.contacts()[set[i]].t;
        small = std::abs(ti.dot(lin_err_.head(n_))) <= kLinearisedShare * sc_.contact.tol_u &&
                std::abs(ti.dot(lin_err_.segment(n_, n_))) <= kLinearisedShare * tol_v;
      }
      if (small) {
        err = eng_->wrms(le, y_);
        break;
      }
      if (rec_.steps - part_step_ >= kPartRefreshSteps) part_stale_ = true;
      err = integrate(t_, y_, hs, y1);
    } else {
      err = integrate(t_, y_, hs, y1);
    }
  }
  rec_.level_u.total += it;
  rec_.level_u.max = std::max(rec_.level_u.max, it);
  ++rec_.level_u.steps;
  rec_.level_v = rec_.level_u;
  return err;
}

void LeeLocated::linearisation_error(double t1, double hs, const Eigen::VectorXd& y1_before,
                                     const Eigen::VectorXd& y1_after) {
  // The responses carry the correction δy through the linear part
  // M δÿ = −(K + K_e⁰) δy − (C + C_e⁰) δẏ + Tᵀ δF (K_e⁰, C_e⁰ the frozen tangent); the
  // mechanism's own correction differs by the rest of its elements' force change,
  // m = Δr_e + K_e⁰δq + C_e⁰δẏ with Δr_e = r_e(y + δy) − r_e(y) (r_e the elements'
  // generalised force; M, C, K and the contact forces are linear and cancel). δy starts
  // from zero at the step's start and grows like x³ (δq) and x² (δẏ) under a ramp or
  // bubble shape (x = (τ − t)/h), so m's effect on the end state is about h²/20 (δq) and
  // h/4 (δẏ) times M⁻¹m(t1); taken as h²/6 and h/2 (a margin of 2–3).
  const ElementSet& el = dynamic_cast<const Mechanism&>(mk_).elements();
  lin_err_.setZero(ny_);
  lin_a_.setZero(n_);
  lin_b_.setZero(n_);
  el.add_force(t1, y1_after.data(), y1_after.data() + n_, lin_a_.data());
  el.add_force(t1, y1_before.data(), y1_before.data() + n_, lin_b_.data());
  lin_a_ -= lin_b_;
  lin_dy_ = y1_after - y1_before;
  lin_a_.noalias() += part_Ke_ * lin_dy_.head(n_);
  if (part_Ce_.size()) lin_a_.noalias() += part_Ce_ * lin_dy_.segment(n_, n_);
  lin_b_ = part_M_.solve(lin_a_);
  lin_err_.head(n_) = (hs * hs / 6.0) * lin_b_;
  lin_err_.segment(n_, n_) = (0.5 * hs) * lin_b_;
}

void LeeLocated::refresh_part() {
  dynamic_cast<const Mechanism&>(mk_).elements().tangent(t_, y_.data(), y_.data() + n_, part_Ke_, part_Ce_);
  for (Responses& c : cache_) c.h = -1.0;
  ++resp_gen_;
  part_step_ = rec_.steps;
  part_stale_ = false;
}

void LeeLocated::factor_shape_matrix(const std::vector<int>& set, double hs, const Responses* R) {
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

std::string LeeLocated::non_finite_cause(double t1, const Eigen::VectorXd& y1) {
  if (!y1.allFinite()) return "the trial step's end state is not finite";
  Eigen::VectorXd a(n_);
  try {
    mk_.acceleration(t1, y1.data(), y1.data() + n_, F1_, a.data(), false, states_of(y1));
  } catch (const std::exception& e) {
    return e.what();
  }
  return a.allFinite() ? "a non-finite residual" : "the acceleration at the trial step's end is not finite";
}

}  // namespace detail
}  // namespace camdyn
