#include "problems/library/matrix_tags.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace smcbench {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Tristate PositiveDefinite(const DenseMatrix& M) {
  const Eigen::Index n = M.rows();
  const DenseMatrix H = 0.5 * (M + M.transpose());
  const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(H, Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return Tristate::kUnknown;
  const Vector& lambda = eig.eigenvalues();  // ascending
  const double scale = std::max(std::abs(lambda[0]), std::abs(lambda[n - 1]));
  const double tau = 8.0 * static_cast<double>(n) * kEps * scale;
  if (scale == 0.0) return Tristate::kNo;  // H = 0
  if (lambda[0] > tau) return Tristate::kYes;
  if (lambda[0] < -tau) return Tristate::kNo;
  return Tristate::kUnknown;
}

// Every principal minor, judged against Hadamard's bound (|det A| ≤ ∏ ‖a_j‖₂).
Tristate PrincipalMinors(const DenseMatrix& M) {
  const int n = static_cast<int>(M.rows());
  bool all_positive = true;
  DenseMatrix sub;
  int index[32];
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    int k = 0;
    for (int i = 0; i < n; ++i) {
      if (mask & (1u << i)) index[k++] = i;
    }
    sub.resize(k, k);
    for (int c = 0; c < k; ++c) {
      for (int r = 0; r < k; ++r) sub(r, c) = M(index[r], index[c]);
    }
    double bound = 1.0;
    for (int c = 0; c < k; ++c) bound *= sub.col(c).norm();
    const double det = k == 1 ? sub(0, 0) : Eigen::PartialPivLU<DenseMatrix>(sub).determinant();
    const double tau = k == 1 ? 0.0 : 16.0 * k * kEps * bound;
    if (det < -tau || (k == 1 && det <= 0.0)) return Tristate::kNo;
    if (!(det > tau)) all_positive = false;
  }
  return all_positive ? Tristate::kYes : Tristate::kUnknown;
}

}  // namespace

MatrixTags ClassifyMatrix(const BoxMLCP& problem, const ClassifyOptions& options) {
  MatrixTags tags;
  const int n = problem.size();
  tags.symmetric = problem.IsSymmetric() ? Tristate::kYes : Tristate::kNo;
  const bool small = n <= options.max_eigen_size || n <= options.max_minors_size;
  DenseMatrix dense;
  if (small) dense = problem.is_sparse() ? problem.ToDense() : problem.dense_matrix();
  if (n <= options.max_eigen_size) tags.positive_definite = PositiveDefinite(dense);

  // A non-positive diagonal entry is a non-positive 1×1 principal minor.
  bool diagonal_positive = true;
  if (problem.is_sparse()) {
    const SparseMatrix& S = problem.sparse_matrix();
    for (int j = 0; j < n && diagonal_positive; ++j) diagonal_positive = S.coeff(j, j) > 0.0;
  } else {
    diagonal_positive = (problem.dense_matrix().diagonal().array() > 0.0).all();
  }
  if (!diagonal_positive) {
    tags.p_matrix = Tristate::kNo;
  } else if (tags.positive_definite == Tristate::kYes) {
    tags.p_matrix = Tristate::kYes;
  } else if (n <= std::min(options.max_minors_size, 30)) {
    tags.p_matrix = PrincipalMinors(dense);
  }
  return tags;
}

}  // namespace smcbench
