// camdyn — the contact LCP with the minimal-norm split (active_set.hpp has the maths). When
// the whole set is not the answer, W is split into the blocks of its non-zeros (contacts
// that share no unknown) and each block is its own LCP: the supports are enumerated per
// block (up to kMaxEnumerated contacts each), and the smallest ‖F‖ is the blocks' together.
#include "contact/active_set.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

namespace camdyn {
namespace detail {

namespace {
constexpr int kMaxEnumerated = 10;  // 2¹⁰ supports of tiny solves at most
constexpr double kRel = 1e-9;       // round-off allowance relative to the problem's scale

struct Candidate {
  Eigen::VectorXd F, w;
  bool valid = false;
};

// try_support's workspace, one per thread: solve_contact_lcp runs inside every right-hand
// side of the event method, so it allocates nothing per call (docs/background/performance.md,
// "The event and penalty methods' probes"). Reusing them changes no arithmetic (the
// decomposition is computed anew from Wp).
struct SupportWork {
  Eigen::MatrixXd Wp;
  Eigen::VectorXd bp, z;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  std::vector<char> in;
  std::vector<int> all;
  Candidate whole;  // solve_contact_lcp's first candidate: the whole set held
};
SupportWork& support_work() {
  thread_local SupportWork w;
  return w;
}

// The minimal-norm F supported on `P` (mask over 0..k−1) and its validity, into c.
void try_support(const Eigen::MatrixXd& W, const Eigen::VectorXd& b, const std::vector<int>& P, Candidate& c) {
  const int k = int(b.size()), p = int(P.size());
  SupportWork& ws = support_work();
  c.F.setZero(k);
  if (p > 0) {
    Eigen::MatrixXd& Wp = ws.Wp;
    Eigen::VectorXd& bp = ws.bp;
    Wp.resize(p, p);
    bp.resize(p);
    for (int i = 0; i < p; ++i) {
      bp[i] = b[P[i]];
      for (int l = 0; l < p; ++l) Wp(i, l) = W(P[i], P[l]);
    }
    if (p == 1) {
      c.F[P[0]] = -bp[0] / Wp(0, 0);
    } else {
      ws.cod.compute(Wp);
      ws.z = ws.cod.solve(-bp);
      for (int i = 0; i < p; ++i) c.F[P[i]] = ws.z[i];
    }
  }
  c.w = W * c.F + b;
  const double Fmax = c.F.cwiseAbs().maxCoeff();
  const double sw = b.cwiseAbs().maxCoeff() + W.cwiseAbs().maxCoeff() * Fmax + 1e-300;
  std::vector<char>& in = ws.in;
  in.assign(std::size_t(k), 0);
  for (int j : P) in[std::size_t(j)] = 1;
  c.valid = c.F.allFinite();
  for (int j = 0; j < k && c.valid; ++j) {
    if (in[std::size_t(j)])
      c.valid = c.F[j] >= -kRel * Fmax && std::abs(c.w[j]) <= kRel * sw;
    else
      c.valid = c.w[j] >= -kRel * sw;
  }
  if (c.valid) {
    c.F = c.F.cwiseMax(0.0);
    for (int j = 0; j < k; ++j)
      if (in[std::size_t(j)]) c.w[j] = 0.0;  // held: exactly, up to the round-off just allowed
  }
}
Candidate try_support(const Eigen::MatrixXd& W, const Eigen::VectorXd& b, const std::vector<int>& P) {
  Candidate c;
  try_support(W, b, P, c);
  return c;
}
}  // namespace

// try_support on the whole set, then on the empty set, for one contact (the same
// operations in the same order as the vector code, so the same bits).
bool solve_contact_lcp1(double W, double b, double& F, double& w) {
  {  // held: F = −b/W
    const double f = -b / W, Fmax = std::abs(f);
    const double r = W * f + b, sw = std::abs(b) + std::abs(W) * Fmax + 1e-300;
    if (std::isfinite(f) && f >= -kRel * Fmax && std::abs(r) <= kRel * sw) {
      F = std::max(f, 0.0);
      w = 0.0;
      return true;
    }
  }
  // open: F = 0, w = b
  const double r = W * 0.0 + b, sw = std::abs(b) + std::abs(W) * 0.0 + 1e-300;
  F = 0.0;
  w = r;
  return r >= -kRel * sw;
}

ContactLcpResult solve_contact_lcp(const Eigen::MatrixXd& W, const Eigen::VectorXd& b) {
  const int k = int(b.size());
  ContactLcpResult r;
  if (k == 0) {
    r.F = r.w = Eigen::VectorXd();
    r.ok = true;
    return r;
  }
  if (k == 1) {
    r.F.resize(1);
    r.w.resize(1);
    r.ok = solve_contact_lcp1(W(0, 0), b[0], r.F[0], r.w[0]);
    return r;
  }
  SupportWork& ws = support_work();
  std::vector<int>& all = ws.all;
  all.resize(std::size_t(k));
  for (int j = 0; j < k; ++j) all[std::size_t(j)] = j;
  // the whole set held (the usual case: every contact carries force)
  try_support(W, b, all, ws.whole);
  if (ws.whole.valid) {
    r.F = ws.whole.F;
    r.w = ws.whole.w;
    r.ok = true;
    return r;
  }
  Candidate best = ws.whole;  // not valid: the enumeration below replaces it
  // W block-diagonal after a permutation (contacts that share no unknown: a camshaft's cams on
  // different stations of a lumped shaft, separate trains): one LCP per connected block of W's
  // non-zeros. The smallest ‖F‖ is the blocks' smallest ones together.
  std::vector<int> block(std::size_t(k), -1);
  int blocks = 0;
  for (int s0 = 0; s0 < k; ++s0) {
    if (block[std::size_t(s0)] >= 0) continue;
    std::vector<int> stack{s0};
    block[std::size_t(s0)] = blocks;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (int j = 0; j < k; ++j)
        if (block[std::size_t(j)] < 0 && (W(i, j) != 0.0 || W(j, i) != 0.0)) {
          block[std::size_t(j)] = blocks;
          stack.push_back(j);
        }
    }
    ++blocks;
  }
  if (blocks > 1) {
    r.F.setZero(k);
    r.w.resize(k);
    r.ok = true;
    for (int c = 0; c < blocks; ++c) {
      std::vector<int> idx;
      for (int j = 0; j < k; ++j)
        if (block[std::size_t(j)] == c) idx.push_back(j);
      const int kc = int(idx.size());
      Eigen::MatrixXd Wc(kc, kc);
      Eigen::VectorXd bc(kc);
      for (int i = 0; i < kc; ++i) {
        bc[i] = b[idx[std::size_t(i)]];
        for (int j = 0; j < kc; ++j) Wc(i, j) = W(idx[std::size_t(i)], idx[std::size_t(j)]);
      }
      const ContactLcpResult rc = solve_contact_lcp(Wc, bc);
      r.ok = r.ok && rc.ok;
      for (int i = 0; i < kc; ++i) r.F[idx[std::size_t(i)]] = rc.F[i];
    }
    r.w = W * r.F + b;
    if (!r.ok) r.F.setZero(k), r.w = b;
    return r;
  }
  if (k <= kMaxEnumerated) {
    for (unsigned mask = 0; mask + 1 < (1u << k); ++mask) {
      std::vector<int> P;
      for (int j = 0; j < k; ++j)
        if (mask & (1u << j)) P.push_back(j);
      Candidate c = try_support(W, b, P);
      if (c.valid && (!best.valid || c.F.norm() < best.F.norm())) best = std::move(c);
    }
  } else {
    // greedy: add the contact accelerating most into its gap, drop the ones that pull
    std::vector<int> P;
    for (int it = 0; it < 4 * k && !best.valid; ++it) {
      Candidate c = try_support(W, b, P);
      if (c.valid) {
        best = std::move(c);
        break;
      }
      int worst = -1;
      for (int j : P)
        if (c.F[j] < 0 && (worst < 0 || c.F[j] < c.F[worst])) worst = j;
      if (worst >= 0) {
        P.erase(std::find(P.begin(), P.end(), worst));
        continue;
      }
      int add = -1;
      for (int j = 0; j < k; ++j)
        if (std::find(P.begin(), P.end(), j) == P.end() && (add < 0 || c.w[j] < c.w[add])) add = j;
      if (add < 0) break;
      P.push_back(add);
    }
  }
  r.ok = best.valid;
  r.F = best.valid ? best.F : Eigen::VectorXd::Zero(k);
  r.w = best.valid ? best.w : Eigen::VectorXd(W * r.F + b);
  return r;
}

void project_on_set(const Eigen::MatrixXd& MinvTt, const Eigen::MatrixXd& W, const std::vector<int>& set,
                    const Eigen::VectorXd& g, const Eigen::VectorXd& gd, Eigen::VectorXd& y) {
  const int k = int(set.size()), n = int(MinvTt.rows());
  if (k == 0) return;
  if (k == 1) {  // one held contact (a single follower, a valve on its seat): W_jj > 0
    const int j = set[0];
    if (!(W(j, j) > 0.0)) return;
    y.head(n).noalias() -= (g[j] / W(j, j)) * MinvTt.col(j);
    y.segment(n, n).noalias() -= (gd[j] / W(j, j)) * MinvTt.col(j);
    return;
  }
  Eigen::MatrixXd Wss(k, k), B(n, k);
  Eigen::MatrixXd rhs(k, 2);
  for (int a = 0; a < k; ++a) {
    B.col(a) = MinvTt.col(set[a]);
    rhs(a, 0) = g[set[a]];
    rhs(a, 1) = gd[set[a]];
    for (int b = 0; b < k; ++b) Wss(a, b) = W(set[a], set[b]);
  }
  const Eigen::MatrixXd lam = Wss.completeOrthogonalDecomposition().solve(rhs);
  y.head(n).noalias() -= B * lam.col(0);
  y.segment(n, n).noalias() -= B * lam.col(1);
}

}  // namespace detail
}  // namespace camdyn
