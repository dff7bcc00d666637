#include "problems/library/matrix_tags.h"

#include <algorithm>

#include "solvers/core/matrix_class.h"

namespace smcbench {
namespace {

Tristate FromAnswer(MatrixClassAnswer answer) {
  switch (answer) {
    case MatrixClassAnswer::kYes:
      return Tristate::kYes;
    case MatrixClassAnswer::kNo:
      return Tristate::kNo;
    case MatrixClassAnswer::kNotDecided:
      break;
  }
  return Tristate::kUnknown;
}

// Tags use the tests that also give λ_min and the smallest minor (see matrix_tags.h for the margins).
constexpr DefinitenessOptions kEigenvalueTest{DefinitenessTest::kEigenvalues, 8.0};
constexpr double kHadamardMargin = 16.0;

}  // namespace

MatrixTags ClassifyMatrix(const BoxMLCP& problem, const ClassifyOptions& options) {
  MatrixTags tags;
  const int n = problem.size();
  tags.symmetric = problem.IsSymmetric() ? Tristate::kYes : Tristate::kNo;
  const bool small = n <= options.max_eigen_size || n <= options.max_minors_size;
  DenseMatrix dense;
  if (small) dense = problem.is_sparse() ? problem.ToDense() : problem.dense_matrix();
  if (n <= options.max_eigen_size) {
    tags.positive_definite = FromAnswer(ClassifySymmetricPartPositiveDefinite(dense, kEigenvalueTest).answer);
  }

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
  } else if (n <= std::min(options.max_minors_size, kMaxPMatrixTestSize)) {
    const PMatrixOptions minors{n, PrincipalMinorTest::kDeterminantVsHadamard, kHadamardMargin};
    tags.p_matrix = FromAnswer(ClassifyPMatrix(dense, minors).answer);
  }
  return tags;
}

}  // namespace smcbench
