// The contact LCP of solve_contact_lcp (src/contact/active_set.hpp) when W splits into blocks
// of contacts that share no non-zero (a camshaft's cams on different stations of a lumped
// shaft; separate trains): 12 independent pairs, 24 contacts, whose whole set is not the
// answer (some contacts open). Before the split the 24 contacts went past the enumeration's 10
// to a greedy pass; per block every support is tried. Checked against the LCP's definition
// (F ≥ 0, w = W F + b ≥ 0, F·w = 0) and against each pair solved on its own by enumerating its
// four supports here (the smallest ‖F‖ of the valid ones). Three pairs are dependent (two
// contacts on one node, W singular): their forces share by the minimal norm, which the greedy
// pass over all 24 missed (it loaded one contact of such a pair with the whole force).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "contact/active_set.hpp"

namespace camdyn {
namespace {

using detail::ContactLcpResult;
using detail::solve_contact_lcp;

// The smallest-norm solution of a 2 × 2 LCP by its four supports, written out.
Eigen::Vector2d pair_lcp(const Eigen::Matrix2d& W, const Eigen::Vector2d& b) {
  Eigen::Vector2d best(NAN, NAN);
  double best_norm = INFINITY;
  auto consider = [&](const Eigen::Vector2d& F) {
    const Eigen::Vector2d w = W * F + b;
    const double tol = 1e-12 * (W.cwiseAbs().maxCoeff() * F.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
    if (!F.allFinite() || F.minCoeff() < -tol || w.minCoeff() < -tol) return;
    for (int i = 0; i < 2; ++i)
      if (F[i] > tol && std::abs(w[i]) > tol) return;  // complementarity
    if (F.norm() < best_norm) best = F, best_norm = F.norm();
  };
  consider(Eigen::Vector2d::Zero());
  consider(Eigen::Vector2d(-b[0] / W(0, 0), 0.0));
  consider(Eigen::Vector2d(0.0, -b[1] / W(1, 1)));
  consider(W.completeOrthogonalDecomposition().solve(-b));  // minimal norm where W is singular
  return best;
}

TEST(ContactLcpBlocks, IndependentPairsAreSolvedEachOnItsOwn) {
  const int pairs = 12, k = 2 * pairs;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd b(k);
  for (int p = 0; p < pairs; ++p) {
    const double a = 1.0 + 0.1 * p, c = 2.0 + 0.05 * p, off = 0.6 * std::sqrt(a * c) * (p % 2 ? 1 : -1);
    W(2 * p, 2 * p) = a;
    W(2 * p + 1, 2 * p + 1) = c;
    W(2 * p, 2 * p + 1) = W(2 * p + 1, 2 * p) = off;
    // pulling apart, pushing in, or one of each: the whole set's forces are not all ≥ 0
    b[2 * p] = (p % 3 == 0) ? 1.0 : -1.0 - 0.2 * p;
    b[2 * p + 1] = (p % 3 == 1) ? 0.5 : -0.3 - 0.1 * p;
    if (p % 4 == 3) {  // two contacts on one node: W singular, they share by the minimal norm
      W(2 * p, 2 * p + 1) = W(2 * p + 1, 2 * p) = W(2 * p + 1, 2 * p + 1) = a;
      b[2 * p + 1] = b[2 * p] = -1.0;
    }
  }
  // a permutation, so that no block is contiguous
  Eigen::PermutationMatrix<Eigen::Dynamic> P(k);
  for (int i = 0; i < k; ++i) P.indices()[i] = (7 * i) % k;  // 7 and 24 coprime
  const Eigen::MatrixXd Wp = P * W * P.transpose();
  const Eigen::VectorXd bp = P * b;
  const ContactLcpResult r = solve_contact_lcp(Wp, bp);
  ASSERT_TRUE(r.ok);
  const Eigen::VectorXd F = P.transpose() * r.F, w = W * F + b;
  EXPECT_GE(F.minCoeff(), 0.0);
  EXPECT_GE(w.minCoeff(), -1e-12);
  EXPECT_LT(std::abs(F.dot(w)), 1e-12);
  int open = 0;
  for (int p = 0; p < pairs; ++p) {
    const Eigen::Vector2d ref = pair_lcp(W.block<2, 2>(2 * p, 2 * p), b.segment<2>(2 * p));
    // measured: equal to 2e-16
    EXPECT_NEAR(F[2 * p], ref[0], 1e-12) << "pair " << p;
    EXPECT_NEAR(F[2 * p + 1], ref[1], 1e-12) << "pair " << p;
    open += (F[2 * p] == 0.0) + (F[2 * p + 1] == 0.0);
  }
  EXPECT_GT(open, 0);  // the whole set was not the answer
}

}  // namespace
}  // namespace camdyn
