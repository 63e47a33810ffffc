// camdyn (private) — the sparse matrix type of the mechanism's M, C, K and the engines'
// Newton matrices (CSC, long indices: KLU's klu_l interface takes them as they are).
#pragma once

#include <Eigen/SparseCore>

namespace camdyn {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, long>;

}  // namespace camdyn
