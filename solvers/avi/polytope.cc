#include "solvers/avi/polytope.h"

#include <algorithm>
#include <cmath>
#include <string>
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

namespace {

// A row (divided by its largest coefficient, so its 2-norm is in [1, √n]) whose product with the unit direction is
// below this changes too little along it to bound the step: it neither blocks nor counts as independent.
constexpr double kDirectionTolerance = 1e-9;

// Orthonormal basis of the null space of the rows of W (k×n, k < n, independent by construction): the last n − k
// columns of Q in Wᵀ = QR.
DenseMatrix NullSpace(const DenseMatrix& W, Eigen::Index n) {
  if (W.rows() == 0) return DenseMatrix::Identity(n, n);
  const Eigen::HouseholderQR<DenseMatrix> qr(W.transpose());
  const DenseMatrix Q = qr.householderQ() * DenseMatrix::Identity(n, n);
  return Q.rightCols(n - W.rows());
}

}  // namespace

PolytopeVertex FindPolytopeVertex(const DenseMatrix& H, const Vector& K, const DenseMatrix& E, const Vector& f,
                                  const Vector* start, double tolerance) {
  const Eigen::Index m = H.rows(), p = E.rows();
  const Eigen::Index n = std::max(H.cols(), E.cols());
  PolytopeVertex out;
  // [H; E] with each row divided by its largest coefficient, so slacks and tolerances are in units of λ.
  DenseMatrix rows(m + p, n);
  Vector rhs(m + p);
  for (Eigen::Index r = 0; r < m + p; ++r) {
    const bool inequality = r < m;
    const double scale = inequality ? RowScale(H, r) : RowScale(E, r - m);
    rows.row(r) = (inequality ? H.row(r) : E.row(r - m)) / scale;
    rhs[r] = (inequality ? K[r] : f[r - m]) / scale;
  }
  Vector x;
  if (start != nullptr) {
    x = *start;
  } else {
    const PolytopePoint point = FindPolytopePoint(H, K, E, f, tolerance);
    if (!point.found) {
      out.why = "the phase-1 simplex found no point of P";
      return out;
    }
    x = point.point;
  }
  const double rhs_norm = m + p ? rhs.cwiseAbs().maxCoeff() : 0.0;
  const auto threshold = [&](const Vector& at) {
    return tolerance * (1.0 + (n ? at.cwiseAbs().maxCoeff() : 0.0) + rhs_norm);
  };
  // The working set: active rows, kept linearly independent (a row joins only if it has a component outside the
  // span of those before it). Equalities first, since every point of P has them active.
  DenseMatrix working(0, n);
  const auto try_add = [&](Eigen::Index r) {
    if (working.rows() == n) return;
    const DenseMatrix Z = NullSpace(working, n);
    if ((Z.transpose() * rows.row(r).transpose()).norm() <= kDirectionTolerance * rows.row(r).norm()) return;
    working.conservativeResize(working.rows() + 1, Eigen::NoChange);
    working.row(working.rows() - 1) = rows.row(r);
    out.rows.push_back(static_cast<int>(r));
  };
  for (Eigen::Index j = 0; j < p; ++j) try_add(m + j);
  const double active = threshold(x);
  for (Eigen::Index i = 0; i < m; ++i) {
    if (rows.row(i).dot(x) - rhs[i] <= active) try_add(i);
  }
  const auto in_working = [&](Eigen::Index r) {
    return std::find(out.rows.begin(), out.rows.end(), static_cast<int>(r)) != out.rows.end();
  };
  while (working.rows() < n) {
    Vector d = NullSpace(working, n).col(0);
    // Some row must change along d, else d (and −d) keeps every row's slack: a line through x lies in P.
    double most_negative = 0.0, most_positive = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      const double a = rows.row(i).dot(d) / rows.row(i).norm();
      most_negative = std::min(most_negative, a);
      most_positive = std::max(most_positive, a);
    }
    if (most_negative >= -kDirectionTolerance && most_positive <= kDirectionTolerance) {
      out.contains_line = true;
      out.why = "P contains a line (the rows of H and E have rank " + std::to_string(working.rows()) + " < n = " +
                std::to_string(n) + "), so it has no vertex";
      return out;
    }
    if (most_negative >= -kDirectionTolerance) d = -d;  // walk the way some row decreases
    // Ratio test: the first row to become active; among near-ties the one d crosses most steeply, which keeps the
    // vertex's rows well conditioned.
    Eigen::Index blocking = -1;
    double step = kInf, steepness = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      if (in_working(i)) continue;
      const double a = rows.row(i).dot(d);
      if (a >= -kDirectionTolerance * rows.row(i).norm()) continue;
      const double t = std::max(rows.row(i).dot(x) - rhs[i], 0.0) / -a;
      const bool tie = std::abs(t - step) <= 1e-12 * (1.0 + step);
      if (blocking < 0 || (t < step && !tie) || (tie && -a > steepness)) {
        blocking = i;
        step = std::min(t, step);
        steepness = -a;
      }
    }
    if (blocking < 0) {  // cannot happen: some row decreases along d
      out.why = "no row bounds the walk to a vertex";
      return out;
    }
    x += step * d;
    working.conservativeResize(working.rows() + 1, Eigen::NoChange);
    working.row(working.rows() - 1) = rows.row(blocking);
    out.rows.push_back(static_cast<int>(blocking));
  }
  // The vertex itself: the n working rows as equalities, so rounding along the walk does not stay in it.
  Vector b(n);
  for (Eigen::Index k = 0; k < n; ++k) b[k] = rhs[out.rows[static_cast<std::size_t>(k)]];
  const Vector vertex = working.partialPivLu().solve(b);
  double infeasibility = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) infeasibility = std::max(infeasibility, rhs[i] - rows.row(i).dot(vertex));
  for (Eigen::Index j = 0; j < p; ++j) {
    infeasibility = std::max(infeasibility, std::abs(rows.row(m + j).dot(vertex) - rhs[m + j]));
  }
  out.infeasibility = infeasibility;
  out.point = vertex;
  out.found = std::isfinite(infeasibility) && infeasibility <= threshold(vertex);
  if (!out.found) out.why = "the vertex found is outside P by " + std::to_string(infeasibility) + " (rounding)";
  return out;
}

}  // namespace smcbench
