#include "solvers/avi/polytope.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace smcbench {

std::string_view ToString(PolytopeBoundedness value) {
  switch (value) {
    case PolytopeBoundedness::kNotDecided: return "not decided";
    case PolytopeBoundedness::kBounded: return "bounded";
    case PolytopeBoundedness::kUnbounded: return "unbounded";
  }
  return "?";
}

namespace {

// Entries of the row-divided tableau are O(1): below this a pivot or a reduced cost is rounding.
constexpr double kPivotTolerance = 1e-11;

double RowScale(const DenseMatrix& A, Eigen::Index row) { return A.row(row).cwiseAbs().maxCoeff(); }

}  // namespace

PolytopePoint FindPolytopePoint(const DenseMatrix& H, const Vector& K, const DenseMatrix& E, const Vector& f,
                                double tolerance) {
  const Eigen::Index m = H.rows(), p = E.rows();
  const Eigen::Index n = std::max(H.cols(), E.cols());
  const Eigen::Index rows = m + p;
  // Columns: λ⁺ (n), λ⁻ (n), the slacks s (m), one artificial per row (rows).
  const Eigen::Index artificial = 2 * n + m, cols = artificial + rows;
  DenseMatrix A = DenseMatrix::Zero(rows, cols);
  Vector b(rows), rhs_divided(rows);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const bool inequality = r < m;
    const Eigen::Index k = inequality ? r : r - m;
    const double scale = inequality ? RowScale(H, k) : RowScale(E, k);
    const double rhs = (inequality ? K[k] : f[k]) / scale;
    rhs_divided[r] = rhs;
    // Negated rows keep the right-hand side ≥ 0, so the artificials start as a feasible basis.
    const double sign = rhs < 0.0 ? -1.0 : 1.0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double a = sign * (inequality ? H(k, j) : E(k, j)) / scale;
      A(r, j) = a;
      A(r, n + j) = -a;
    }
    if (inequality) A(r, 2 * n + k) = -sign;
    A(r, artificial + r) = 1.0;
    b[r] = sign * rhs;
  }
  std::vector<Eigen::Index> basis(static_cast<std::size_t>(rows));
  for (Eigen::Index r = 0; r < rows; ++r) basis[static_cast<std::size_t>(r)] = artificial + r;
  // Reduced costs of min Σ artificials with the artificials basic: 1 − 1 = 0 on them, −Σ_r A_rj elsewhere.
  Vector cost = Vector::Zero(cols);
  for (Eigen::Index j = 0; j < artificial; ++j) cost[j] = -A.col(j).sum();

  PolytopePoint out;
  const int budget = static_cast<int>(50 * (rows + cols) + 100);
  while (true) {
    Eigen::Index entering = -1;
    for (Eigen::Index j = 0; j < cols; ++j) {  // Bland: the first improving column, so no cycling
      if (cost[j] < -kPivotTolerance) {
        entering = j;
        break;
      }
    }
    if (entering < 0) break;
    if (out.pivots >= budget) {
      out.pivot_limit = true;
      break;
    }
    Eigen::Index leaving = -1;
    double best = kInf;
    for (Eigen::Index r = 0; r < rows; ++r) {
      if (A(r, entering) <= kPivotTolerance) continue;
      const double ratio = b[r] / A(r, entering);
      const auto index = static_cast<std::size_t>(r);
      // The first eligible row is taken even when its ratio overflows to +inf, so the tie-break always has a row.
      if (leaving < 0 || ratio < best || (ratio == best && basis[index] < basis[static_cast<std::size_t>(leaving)])) {
        best = ratio;
        leaving = r;
      }
    }
    if (leaving < 0) break;  // cannot happen: Σ artificials is bounded below by 0
    const double pivot = A(leaving, entering);
    A.row(leaving) /= pivot;
    b[leaving] /= pivot;
    for (Eigen::Index r = 0; r < rows; ++r) {
      if (r == leaving || A(r, entering) == 0.0) continue;
      const double factor = A(r, entering);
      A.row(r) -= factor * A.row(leaving);
      b[r] -= factor * b[leaving];
    }
    const double factor = cost[entering];
    cost -= factor * A.row(leaving).transpose();
    basis[static_cast<std::size_t>(leaving)] = entering;
    ++out.pivots;
  }

  Vector x = Vector::Zero(cols);
  double objective = 0.0;
  for (Eigen::Index r = 0; r < rows; ++r) {
    const Eigen::Index j = basis[static_cast<std::size_t>(r)];
    x[j] = std::max(b[r], 0.0);
    if (j >= artificial) objective += x[j];
  }
  out.phase1_objective = objective;
  Vector lambda = x.head(n) - x.segment(n, n);
  double infeasibility = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    infeasibility = std::max(infeasibility, (K[i] - H.row(i).dot(lambda)) / RowScale(H, i));
  }
  for (Eigen::Index j = 0; j < p; ++j) {
    infeasibility = std::max(infeasibility, std::abs(E.row(j).dot(lambda) - f[j]) / RowScale(E, j));
  }
  out.infeasibility = infeasibility;
  const double rhs_norm = rows ? rhs_divided.cwiseAbs().maxCoeff() : 0.0;
  const double lambda_norm = n ? lambda.cwiseAbs().maxCoeff() : 0.0;
  out.found = std::isfinite(infeasibility) && infeasibility <= tolerance * (1.0 + lambda_norm + rhs_norm);
  out.point = std::move(lambda);
  return out;
}

PolytopeBoundedness ClassifyPolytopeBoundedness(const DenseMatrix& H, const DenseMatrix& E) {
  const Eigen::Index n = std::max(H.cols(), E.cols());
  if (n > kMaxBoundednessCheckSize) return PolytopeBoundedness::kNotDecided;
  const Vector zero = Vector::Zero(H.rows());
  DenseMatrix E_extended(E.rows() + 1, n);
  if (E.rows() > 0) E_extended.topRows(E.rows()) = E;
  Vector f_extended = Vector::Zero(E.rows() + 1);
  for (Eigen::Index j = 0; j < n; ++j) {
    E_extended.row(E.rows()).setZero();
    E_extended(E.rows(), j) = 1.0;
    for (const double sign : {1.0, -1.0}) {
      f_extended[E.rows()] = sign;
      const PolytopePoint direction = FindPolytopePoint(H, zero, E_extended, f_extended);
      if (direction.found) return PolytopeBoundedness::kUnbounded;
      if (direction.pivot_limit) return PolytopeBoundedness::kNotDecided;
    }
  }
  return PolytopeBoundedness::kBounded;
}

}  // namespace smcbench
