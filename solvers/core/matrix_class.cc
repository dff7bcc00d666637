#include "solvers/core/matrix_class.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "solvers/core/dense_lu.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

void RequireSquare(const char* owner, Eigen::Index rows, Eigen::Index cols) {
  if (rows != cols) {
    throw InvalidInputError(std::string(owner) + ": M is " + std::to_string(rows) + "×" + std::to_string(cols) +
                            ", not square");
  }
}

void RequireFinite(const char* owner, const DenseMatrix& M) {
  RequireSquare(owner, M.rows(), M.cols());
  if (M.allFinite()) return;
  for (Eigen::Index j = 0; j < M.cols(); ++j) {
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      if (!std::isfinite(M(i, j))) {
        throw InvalidInputError(std::string(owner) + ": M(" + std::to_string(i) + ", " + std::to_string(j) +
                                ") is not finite");
      }
    }
  }
}

void RequireFinite(const char* owner, const SparseMatrix& M) {
  RequireSquare(owner, M.rows(), M.cols());
  for (int j = 0; j < M.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw InvalidInputError(std::string(owner) + ": M(" + std::to_string(it.row()) + ", " + std::to_string(j) +
                                ") is not finite");
      }
    }
  }
}

void RequireWeights(const char* owner, const Vector* weights, Eigen::Index n) {
  if (weights != nullptr && weights->size() != n) {
    throw InvalidInputError(std::string(owner) + ": row_weights has " + std::to_string(weights->size()) +
                            " entries, M has " + std::to_string(n) + " rows");
  }
}

double SmallestPivot(const Eigen::LLT<DenseMatrix>& factor) {
  const double d = factor.matrixLLT().diagonal().cwiseAbs().minCoeff();
  return d * d;
}

}  // namespace

std::string_view ToString(MatrixClassAnswer answer) {
  switch (answer) {
    case MatrixClassAnswer::kNotDecided:
      return "not decided";
    case MatrixClassAnswer::kNo:
      return "no";
    case MatrixClassAnswer::kYes:
      return "yes";
  }
  return "invalid";
}

SymmetryResult ClassifySymmetry(const DenseMatrix& M, const SymmetryOptions& options, const Vector* row_weights) {
  RequireFinite("ClassifySymmetry", M);
  RequireWeights("ClassifySymmetry", row_weights, M.rows());
  const int n = static_cast<int>(M.rows());
  const auto weight = [row_weights](int i) { return row_weights ? (*row_weights)[i] : 1.0; };
  SymmetryResult r;
  // A fused pass over the columns, no n×n temporary; max is exact, so the order of the pass does not matter.
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) r.max_entry = std::max(r.max_entry, std::abs(weight(i) * M(i, j)));
    for (int i = j + 1; i < n; ++i) {
      const double asymmetry = std::abs(weight(i) * M(i, j) - weight(j) * M(j, i));
      if (asymmetry > r.max_asymmetry) r.max_asymmetry = asymmetry, r.row = i, r.col = j;
    }
  }
  r.answer = r.max_asymmetry <= options.relative_tolerance * r.max_entry ? MatrixClassAnswer::kYes
                                                                          : MatrixClassAnswer::kNo;
  return r;
}

SymmetryResult ClassifySymmetry(const SparseMatrix& M, const SymmetryOptions& options, const Vector* row_weights) {
  RequireFinite("ClassifySymmetry", M);
  RequireWeights("ClassifySymmetry", row_weights, M.rows());
  const auto weight = [row_weights](Eigen::Index i) { return row_weights ? (*row_weights)[i] : 1.0; };
  SymmetryResult r;
  // Every stored (i, j) against M(j, i) (zero when not stored): covers the union of the pattern and its transpose.
  for (int j = 0; j < M.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
      const Eigen::Index i = it.row();
      r.max_entry = std::max(r.max_entry, std::abs(weight(i) * it.value()));
      if (i == j) continue;
      const double asymmetry = std::abs(weight(i) * it.value() - weight(j) * M.coeff(j, static_cast<int>(i)));
      if (asymmetry > r.max_asymmetry) r.max_asymmetry = asymmetry, r.row = static_cast<int>(i), r.col = j;
    }
  }
  r.answer = r.max_asymmetry <= options.relative_tolerance * r.max_entry ? MatrixClassAnswer::kYes
                                                                          : MatrixClassAnswer::kNo;
  return r;
}

SymmetricSkewNorms SymmetricAndSkewPartNorms(const DenseMatrix& M) {
  SymmetricSkewNorms norms;
  const Eigen::Index n = M.rows();
  for (Eigen::Index j = 0; j < n; ++j) {  // column by column (column-major M); each pair i > j counts twice
    const double* column = M.data() + j * n;
    norms.symmetric_squared += 4.0 * column[j] * column[j];
    for (Eigen::Index i = j + 1; i < n; ++i) {
      const double a = column[i], b = M(j, i);
      norms.symmetric_squared += 2.0 * (a + b) * (a + b);
      norms.skew_squared += 2.0 * (a - b) * (a - b);
    }
  }
  return norms;
}

DefinitenessResult ClassifySymmetricPartPositiveDefinite(const DenseMatrix& M, const DefinitenessOptions& options) {
  RequireFinite("ClassifySymmetricPartPositiveDefinite", M);
  if (!(options.margin >= 0.0) || !std::isfinite(options.margin)) {
    throw InvalidInputError("ClassifySymmetricPartPositiveDefinite: margin must be a finite number >= 0");
  }
  const int n = static_cast<int>(M.rows());
  DefinitenessResult r;
  if (n == 0) return r;
  if (options.test == DefinitenessTest::kEigenvalues) {
    const DenseMatrix H = 0.5 * (M + M.transpose());
    const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(H, Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success) return r;
    const Vector& lambda = eig.eigenvalues();  // ascending
    const double scale = std::max(std::abs(lambda[0]), std::abs(lambda[n - 1]));
    r.shift = options.margin * static_cast<double>(n) * kEps * scale;
    r.certificate = lambda[0];
    if (scale == 0.0) {
      r.answer = MatrixClassAnswer::kNo;  // H = 0
    } else if (lambda[0] > r.shift) {
      r.answer = MatrixClassAnswer::kYes;
    } else if (lambda[0] < -r.shift) {
      r.answer = MatrixClassAnswer::kNo;
    }
    return r;
  }
  DenseMatrix H = 0.5 * (M + M.transpose());
  r.shift = options.margin * n * kEps * H.cwiseAbs().rowwise().sum().maxCoeff();
  H.diagonal().array() -= r.shift;
  Eigen::LLT<DenseMatrix> factor(H);
  if (factor.info() == Eigen::Success) {
    r.answer = MatrixClassAnswer::kYes;
    r.certificate = SmallestPivot(factor);
    return r;
  }
  // Not clearly definite: clearly indefinite only if even H + δI has no Cholesky factor.
  H.diagonal().array() += 2.0 * r.shift;
  factor.compute(H);
  if (factor.info() == Eigen::Success) {
    r.certificate = SmallestPivot(factor);
  } else {
    r.answer = MatrixClassAnswer::kNo;
  }
  return r;
}

SemidefinitenessResult ClassifySymmetricPartPositiveSemidefinite(const DenseMatrix& S, double tolerance,
                                                                 Eigen::LLT<DenseMatrix>* factor) {
  RequireFinite("ClassifySymmetricPartPositiveSemidefinite", S);
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    throw InvalidInputError("ClassifySymmetricPartPositiveSemidefinite: tolerance must be a finite number >= 0");
  }
  SemidefinitenessResult r;
  const Eigen::Index n = S.rows();
  const double norm = n > 0 ? S.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  if (norm == 0.0) {
    r.answer = MatrixClassAnswer::kYes;  // S = 0
    return r;
  }
  r.shift = tolerance * norm;
  // Evaluated straight into the factorization's own storage (no further n×n temporary).
  factor->compute(0.5 * (S + S.transpose()) + r.shift * DenseMatrix::Identity(n, n));
  if (factor->info() != Eigen::Success) {
    r.answer = MatrixClassAnswer::kNo;
    return r;
  }
  r.answer = MatrixClassAnswer::kYes;
  r.smallest_pivot = SmallestPivot(*factor);
  return r;
}

SemidefinitenessResult ClassifySymmetricPartPositiveSemidefinite(const SparseMatrix& S, double tolerance) {
  RequireFinite("ClassifySymmetricPartPositiveSemidefinite", S);
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    throw InvalidInputError("ClassifySymmetricPartPositiveSemidefinite: tolerance must be a finite number >= 0");
  }
  SemidefinitenessResult r;
  const int n = static_cast<int>(S.rows());
  Vector row_sums = Vector::Zero(n);  // ‖S‖∞ in one pass over the columns
  for (int j = 0; j < S.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(S, j); it; ++it) row_sums[it.row()] += std::abs(it.value());
  }
  const double norm = n > 0 ? row_sums.maxCoeff() : 0.0;
  if (norm == 0.0) {
    r.answer = MatrixClassAnswer::kYes;
    return r;
  }
  r.shift = tolerance * norm;
  SparseMatrix H = 0.5 * (S + SparseMatrix(S.transpose()));
  SparseMatrix shift(n, n);
  shift.setIdentity();
  H += r.shift * shift;
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower> factor(H);
  r.answer = factor.info() == Eigen::Success ? MatrixClassAnswer::kYes : MatrixClassAnswer::kNo;
  return r;
}

PMatrixResult ClassifyPMatrix(const DenseMatrix& M, const PMatrixOptions& options) {
  RequireFinite("ClassifyPMatrix", M);
  if (options.max_size < 0 || options.max_size > kMaxPMatrixTestSize) {
    throw InvalidInputError("ClassifyPMatrix: max_size = " + std::to_string(options.max_size) + " must lie in [0, " +
                            std::to_string(kMaxPMatrixTestSize) + "]");
  }
  if (!(options.margin >= 0.0) || !std::isfinite(options.margin)) {
    throw InvalidInputError("ClassifyPMatrix: margin must be a finite number >= 0");
  }
  const int n = static_cast<int>(M.rows());
  PMatrixResult r;
  if (n > options.max_size) {
    r.too_large = true;
    return r;
  }
  std::vector<int> rows(static_cast<std::size_t>(n)), perm(static_cast<std::size_t>(n));
  DenseMatrix sub;
  bool all_clear = true;
  const auto record = [&](int k, double det) {
    r.minor_rows.assign(rows.begin(), rows.begin() + k);
    r.minor = det;
  };
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    int k = 0;
    for (int i = 0; i < n; ++i) {
      if (mask >> i & 1u) rows[static_cast<std::size_t>(k++)] = i;
    }
    sub.resize(k, k);
    double amax = 0.0;
    for (int c = 0; c < k; ++c) {
      for (int i = 0; i < k; ++i) {
        sub(i, c) = M(rows[static_cast<std::size_t>(i)], rows[static_cast<std::size_t>(c)]);
        amax = std::max(amax, std::abs(sub(i, c)));
      }
    }
    double det = 0.0;
    bool clear = false, positive = false;
    if (options.test == PrincipalMinorTest::kLuPivots) {
      if (dense_lu::FactorRelative(sub.data(), k, k, perm.data())) {
        double sign = 1.0, pmin = kInf;
        det = 1.0;
        for (int i = 0; i < k; ++i) {
          const double d = sub(i, i);
          sign *= d > 0.0 ? 1.0 : -1.0;
          if (perm[static_cast<std::size_t>(i)] != i) sign = -sign;
          pmin = std::min(pmin, std::abs(d));
          det *= std::abs(d);
        }
        det *= sign;
        clear = pmin > options.margin * k * kEps * amax;
        positive = sign > 0.0;  // from the signs, so that an underflowing product keeps its sign
      }
    } else {
      double bound = 1.0;
      for (int c = 0; c < k; ++c) bound *= sub.col(c).norm();
      det = k == 1 ? sub(0, 0) : Eigen::PartialPivLU<DenseMatrix>(sub).determinant();
      const double threshold = k == 1 ? 0.0 : options.margin * k * kEps * bound;
      clear = det < -threshold || det > threshold || (k == 1 && det <= 0.0);
      positive = det > 0.0;
    }
    if (clear && !positive) {
      r.answer = MatrixClassAnswer::kNo;
      record(k, det);
      return r;
    }
    if (!clear && all_clear) {
      all_clear = false;
      record(k, det);
    } else if (all_clear && !(std::abs(det) >= std::abs(r.minor))) {
      record(k, det);  // the smallest clearly positive minor so far (r.minor starts as NaN)
    }
  }
  if (all_clear) r.answer = MatrixClassAnswer::kYes;
  return r;
}

}  // namespace smcbench
