// camdyn — the closed contacts' switches every contact method shares (contact_run.hpp): the
// acceleration level settling which closed contacts keep force (settle_active), and the
// Newton impact law on several contacts (resolve_impact). Moved out of contact_run.cpp.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "contact/active_set.hpp"  // solve_contact_lcp
#include "contact/contact_run.hpp"
#include "contact/run_failure.hpp"  // StepFailure, fmt

namespace camdyn {
namespace detail {

void ContactRun::settle_active(const CamMotion& cm) {
  const std::vector<int> set = active_list();
  Eigen::VectorXd margin;
  bool ok = true;
  F_ = held_forces(t_, y_, cm, set, &margin, &ok);
  if (!unilateral_) return;  // holonomic: contacts never release
  if (!ok) {
    std::string names;
    for (int j : set) names += (names.empty() ? "'" : ", '") + mk_.contacts()[j].name + "'";
    throw StepFailure("the closed contacts " + names +
                      " jam: no bounded contact forces keep them closed (a node driven into a stop)");
  }
  F_ref_ = std::max(F_ref_, F_.cwiseAbs().maxCoeff());
  // a closed contact the acceleration level opens (no force, its gap accelerating open)
  // leaves the active set; the others' forces do not change (complementarity)
  const double thr = 1e-12 * std::max(F_ref_, 1e-300);
  for (int j : set)
    if (margin[j] < -thr) {
      active_[j] = 0;
      F_[j] = 0.0;
      ++rec_.separations;
      record_event(EventKind::Separation, j, 0.0);
    }
}

void ContactRun::close_creeping_contacts(const CamMotion& cm, double gtol) {
  if (!unilateral_ || !(sc_.contact.tol_u > 0)) return;
  Eigen::VectorXd a;
  acceleration(t_, y_, F_, a);
  bool any = false;
  for (int j = 0; j < m_; ++j) {
    if (active_[j]) continue;
    const CamShaft* cs = mk_.camshaft();
    if (cs && cs->contact_cam(j) >= 0) continue;  // a station's lift: not this rule's
    const double g = gap(j, y_, cm), gd = gap_rate(j, y_, cm);
    if (!(g <= gtol && gd > gtol)) continue;
    const double gdd = mk_.contacts()[j].t.dot(a) - cam_acc(j, cm);
    if (gdd < 0.0 && g + gd * gd / (2.0 * -gdd) <= sc_.contact.tol_u) {
      active_[j] = 1;
      any = true;
    }
  }
  if (!any) return;
  const std::vector<int> set = active_list();
  Eigen::VectorXd g(m_), gd(m_);
  for (int j = 0; j < m_; ++j) {
    g[j] = gap(j, y_, cm);
    gd[j] = gap_rate(j, y_, cm);
  }
  const Rows R = rows_at(y_.data());
  project_on_set(R.MinvTt, R.W, set, g, gd, y_);
  settle_active(cm);
}

void ContactRun::resolve_impact(const std::vector<int>& closing, const CamMotion& cm, bool plastic) {
  std::vector<int> S = active_list();
  std::vector<char> stick(m_, 0), is_closing(m_, 0);
  for (int j : closing) {
    S.push_back(j);
    is_closing[j] = 1;
  }
  // The smallest M-weighted correction of q (level 0) or v (level 1) that zeroes the gaps
  // (gap rates) of the contacts `set`: Δ = −M⁻¹T_sᵀ W_ss⁺ g_s (minimal norm on a singular W_ss).
  auto close_exactly = [&](const std::vector<int>& set, int level) {
    if (set.empty()) return;
    const int k = int(set.size());
    Eigen::MatrixXd Wss(k, k), MTs(n_, k);
    Eigen::VectorXd g(k);
    const Rows R = rows_at(y_.data());
    for (int i = 0; i < k; ++i) {
      g[i] = level == 0 ? gap(set[i], y_, cm) : gap_rate(set[i], y_, cm);
      MTs.col(i) = R.MinvTt.col(set[i]);
      for (int l = 0; l < k; ++l) Wss(i, l) = R.W(set[i], set[l]);
    }
    y_.segment(level * n_, n_) -= MTs * Wss.completeOrthogonalDecomposition().solve(g);
  };
  // Gaps of the contacts taking part: closed exactly (the roots are located to the
  // engine's accuracy).
  close_exactly(S, 0);
  // The contacts held before the impact are held at the velocity level too (ġ = 0): the
  // impact's root lies inside a step, where the interpolated state carries the step's
  // error in ġ (≈ rtol·|v|), and the complementarity solve below would read that drift as
  // a held contact moving apart and release it — a spurious separation and re-impact
  // nanoseconds later (the two-mass train on arkode-erk at rtol 1e-6).
  {
    std::vector<int> A;
    for (int j : active_list())
      if (!is_closing[j]) A.push_back(j);
    close_exactly(A, 1);
  }
  const double T_before = mk_.kinetic_energy(y_.data() + n_);
  const Rows R = rows_at(y_.data());  // q no longer changes below
  Eigen::VectorXd gd(m_);
  for (int j = 0; j < m_; ++j) gd[j] = gap_rate(j, y_, cm);
  Eigen::VectorXd a_free;
  acceleration(t_, y_, Eigen::VectorXd::Zero(m_), a_free);
  // Sticking speed of each contact: below it an approach is a touch (the speed a contact
  // reaches falling through 10⁻³ of the gap tolerance under its relative acceleration, ×4).
  for (int j : closing)
    if (v_impact_ref_ == 0.0 && -gd[j] > 0.0) v_impact_ref_ = -gd[j];
  Eigen::VectorXd v_stick(m_);
  for (int j = 0; j < m_; ++j) {
    const double rel_acc = std::abs(R.T.row(j).dot(a_free) - cam_acc(j, y_, cm));
    v_stick[j] = std::max(1e-6 * v_impact_ref_, 4.0 * std::sqrt(2.0 * rel_acc * 1e-3 * stick_gap_tol_));
  }
  bool soft = true;  // every closing contact only touches
  for (int j : closing) {
    const double approach = -gd[j];
    const double e = mk_.contacts()[j].law.impact.restitution;
    stick[j] = plastic || !unilateral_ || e == 0.0 || (1.0 + e) * approach < v_stick[j];
    soft = soft && approach < v_stick[j];
  }
  // The impulses over the contacts S taking part: the closing ones reach ġ⁺ = −e ġ⁻ (0
  // when they stick), the active ones ġ⁺ = 0.
  auto system = [&](const std::vector<int>& set, Eigen::MatrixXd& Wss, Eigen::VectorXd& b) {
    const int k = int(set.size());
    Wss.resize(k, k);
    b.resize(k);  // ġ⁻ − target
    for (int i = 0; i < k; ++i) {
      const int j = set[i];
      const double target = is_closing[j] && !stick[j] ? -mk_.contacts()[j].law.impact.restitution * gd[j] : 0.0;
      b[i] = gd[j] - target;
      for (int l = 0; l < k; ++l) Wss(i, l) = R.W(j, set[l]);
    }
  };
  Eigen::VectorXd P = Eigen::VectorXd::Zero(m_);
  bool solved = !unilateral_ && S.empty();
  if (!unilateral_ || soft) {
    // Holonomic: every contact held, signed impulses. A touch (soft): a contact whose pull
    // would change its own speed by less than its sticking speed keeps it: the sandwich of
    // a valve landing on its seat while the rocker still rests on it is then held by both,
    // and the acceleration level decides which contact lets go (without it the two
    // contacts traded places at the sticking speed every few nanoseconds, and the step
    // size underflowed; with complementarity alone the OHV train's event method took 5922
    // events for Lee's 42). Only where the held system is consistent: on a singular W_SS
    // (two contacts on one node) its least-squares compromise would leave both half-way.
    std::vector<int> T = S;
    for (;;) {
      const int k = int(T.size());
      if (k == 0) {
        solved = true;
        break;
      }
      Eigen::MatrixXd Wss;
      Eigen::VectorXd b;
      system(T, Wss, b);
      const Eigen::VectorXd Ps = Wss.completeOrthogonalDecomposition().solve(-b);
      const double scale = b.cwiseAbs().maxCoeff() + Wss.cwiseAbs().maxCoeff() * Ps.cwiseAbs().maxCoeff();
      if (unilateral_ && (Wss * Ps + b).cwiseAbs().maxCoeff() > 1e-9 * scale) break;  // inconsistent
      int worst = -1;
      const double thr = 1e-6 * Ps.cwiseAbs().maxCoeff();
      auto pulls = [&](int i) {
        if (!unilateral_ || !(Ps[i] < -thr)) return false;
        return !(-Ps[i] * R.W(T[i], T[i]) < v_stick[T[i]]);
      };
      for (int i = 0; i < k; ++i)
        if (pulls(i) && (worst < 0 || Ps[i] < Ps[worst])) worst = i;
      if (worst < 0) {
        for (int i = 0; i < k; ++i) P[T[i]] = Ps[i];
        S = T;
        solved = true;
        break;
      }
      T.erase(T.begin() + worst);  // it would pull: it leaves (or stays open)
    }
  }
  if (!solved) {
    // By complementarity (active_set.hpp): P ≥ 0, ġ⁺ ≥ target, P·(ġ⁺ − target) = 0,
    // redundant contacts (W_SS singular) sharing by the minimal norm; the ones it leaves
    // moving apart leave S. (The release of the most-pulling contact from a least-squares
    // solve it replaced left both contacts of one node half-way: issue 28.)
    Eigen::MatrixXd Wss;
    Eigen::VectorXd b;
    system(S, Wss, b);
    const ContactLcpResult r = solve_contact_lcp(Wss, b);
    if (!r.ok) {
      std::string names;
      for (int j : S) names += (names.empty() ? "'" : ", '") + mk_.contacts()[j].name + "'";
      throw StepFailure("at an impact the contacts " + names + " jam: no bounded impulses keep them apart");
    }
    const double v_sep = 1e-6 * std::max(v_impact_ref_, 1e-300);
    std::vector<int> kept;
    for (size_t i = 0; i < S.size(); ++i) {
      P[S[i]] = r.F[i];
      if (r.F[i] > 0.0 || r.w[i] <= v_sep) kept.push_back(S[i]);
    }
    S = kept;
  }
  y_.segment(n_, n_) += R.MinvTt * P;
  const double T_after = mk_.kinetic_energy(y_.data() + n_);
  const double W_imp = cam_power(P, cm);  // Σ_cam P_j Ẋ_C
  work_ += W_imp;
  dissipated_ += W_imp - (T_after - T_before);
  for (int j : closing) {
    if (-gd[j] > 0.0) {
      ++rec_.impacts;
      record_event(EventKind::Impact, j, -gd[j], P[j]);
    }
    if (stick[j] && std::find(S.begin(), S.end(), j) != S.end()) active_[j] = 1;
  }
  // An active contact left out of S (its impulse would pull) separates if the impulse of
  // the others opens it; otherwise the acceleration level decides (settle_active).
  const double v_eps = 1e-6 * std::max(v_impact_ref_, 1e-300);
  for (int j = 0; j < m_; ++j)
    if (active_[j] && !is_closing[j] && std::find(S.begin(), S.end(), j) == S.end() &&
        gap_rate(j, y_, cm) > v_eps) {
      active_[j] = 0;
      ++rec_.separations;
      record_event(EventKind::Separation, j, 0.0);
    }
  settle_active(cm);
}

}  // namespace detail
}  // namespace camdyn
