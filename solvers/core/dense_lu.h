// The one small dense LU of the backends (Lemke's free block and polish, the enumerative search's free blocks, the
// base's exact polish and a solve session's stored active set):
// partial pivoting in caller-owned storage, so repeated solves never allocate, with the block size optionally
// fixed at compile time for the m ≤ 4 blocks of the enumerative hot path (fully unrolled there).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "solvers/core/types.h"

namespace smcbench::dense_lu {

// Storage: a k×k column-major block with leading dimension ld ≥ k (element (i, j) at a[i + j·ld]).

// LU with partial pivoting in place, P A = L U (L unit lower, below the diagonal; U on and above it; piv[j] = the
// row swapped with row j at step j). False if a pivot is ≤ small (numerically singular) or NaN; A is then
// partly factored. K > 0 fixes k at compile time (unrolled small blocks), K = 0 reads it at run time.
template <int K = 0>
inline bool Factor(double* a, int ld, int k_runtime, int* piv, double small) {
  const int k = K > 0 ? K : k_runtime;
  for (int j = 0; j < k; ++j) {
    double* cj = a + static_cast<std::ptrdiff_t>(j) * ld;
    int p = j;
    double pmax = std::abs(cj[j]);
    for (int i = j + 1; i < k; ++i) {
      const double v = std::abs(cj[i]);
      if (v > pmax) pmax = v, p = i;
    }
    piv[j] = p;
    if (!(pmax > small)) return false;
    if (p != j) {
      for (std::ptrdiff_t c = 0; c < k; ++c) std::swap(a[j + c * ld], a[p + c * ld]);
    }
    // Multipliers by division, not by a reciprocal: the same bits as the elimination by hand that the closed forms
    // and the tests of the small blocks compute (and one instruction fewer per multiplier of a 2×2 block).
    const double pivot = cj[j];
    for (int i = j + 1; i < k; ++i) cj[i] /= pivot;
    for (int c = j + 1; c < k; ++c) {
      double* cc = a + static_cast<std::ptrdiff_t>(c) * ld;
      const double f = cc[j];
      if (f == 0.0) continue;
      for (int i = j + 1; i < k; ++i) cc[i] -= cj[i] * f;
    }
  }
  return true;
}

// Factor with the singularity threshold relative to the block: a pivot must exceed max(k, 1)·ε·max|A|. False for
// an all-zero block.
inline bool FactorRelative(double* a, int ld, int k, int* piv) {
  double amax = 0.0;
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) amax = std::max(amax, std::abs(a[i + static_cast<std::ptrdiff_t>(j) * ld]));
  }
  if (!(amax > 0.0)) return false;
  return Factor(a, ld, k, piv, std::max(k, 1) * std::numeric_limits<double>::epsilon() * amax);
}

// Solves A x = b from Factor's output; b is overwritten by x. Column-oriented (axpy) substitutions.
template <int K = 0>
inline void Solve(const double* a, int ld, int k_runtime, const int* piv, double* b) {
  const int k = K > 0 ? K : k_runtime;
  for (int j = 0; j < k; ++j) {
    if (piv[j] != j) std::swap(b[j], b[piv[j]]);
  }
  for (int j = 0; j < k; ++j) {
    const double bj = b[j];
    if (bj == 0.0) continue;
    const double* cj = a + static_cast<std::ptrdiff_t>(j) * ld;
    for (int i = j + 1; i < k; ++i) b[i] -= cj[i] * bj;
  }
  for (int j = k - 1; j >= 0; --j) {
    const double* cj = a + static_cast<std::ptrdiff_t>(j) * ld;
    b[j] /= cj[j];
    const double bj = b[j];
    for (int i = 0; i < j; ++i) b[i] -= cj[i] * bj;
  }
}

// Solves A X = B in place for m right-hand sides stored row-major (B is k×m, row i at b + i·m; m = 1: a vector).
// Row-oriented substitutions: each row of X is finished before the next, so a wide B is swept once per row of U.
inline void SolveRows(const double* a, int ld, int k, const int* piv, double* b, int m) {
  const auto at = [&](int i, int j) { return a[i + static_cast<std::ptrdiff_t>(j) * ld]; };
  for (int j = 0; j < k; ++j) {
    if (piv[j] == j) continue;
    double* row_j = b + static_cast<std::ptrdiff_t>(j) * m;
    std::swap_ranges(row_j, row_j + m, b + static_cast<std::ptrdiff_t>(piv[j]) * m);
  }
  for (int i = 1; i < k; ++i) {  // L (unit diagonal)
    double* bi = b + static_cast<std::ptrdiff_t>(i) * m;
    for (int j = 0; j < i; ++j) {
      const double l = at(i, j);
      if (l == 0.0) continue;
      const double* bj = b + static_cast<std::ptrdiff_t>(j) * m;
      for (int c = 0; c < m; ++c) bi[c] -= l * bj[c];
    }
  }
  for (int i = k - 1; i >= 0; --i) {  // U
    double* bi = b + static_cast<std::ptrdiff_t>(i) * m;
    for (int j = i + 1; j < k; ++j) {
      const double u = at(i, j);
      if (u == 0.0) continue;
      const double* bj = b + static_cast<std::ptrdiff_t>(j) * m;
      for (int c = 0; c < m; ++c) bi[c] -= u * bj[c];
    }
    const double inv = 1.0 / at(i, i);
    for (int c = 0; c < m; ++c) bi[c] *= inv;
  }
}

// Solves Aᵀ x = b in place (Aᵀ = Uᵀ Lᵀ P).
inline void SolveTransposed(const double* a, int ld, int k, const int* piv, double* b) {
  const auto at = [&](int i, int j) { return a[i + static_cast<std::ptrdiff_t>(j) * ld]; };
  for (int i = 0; i < k; ++i) {  // Uᵀ t = b
    double s = b[i];
    for (int j = 0; j < i; ++j) s -= at(j, i) * b[j];
    b[i] = s / at(i, i);
  }
  for (int i = k - 1; i >= 0; --i) {  // Lᵀ s = t
    double s = b[i];
    for (int j = i + 1; j < k; ++j) s -= at(j, i) * b[j];
    b[i] = s;
  }
  for (int j = k - 1; j >= 0; --j) {
    if (piv[j] != j) std::swap(b[j], b[piv[j]]);
  }
}

// Hager's estimate of ‖A⁻¹‖₁ from the factors (Hager 1984; Higham, Accuracy and Stability of Numerical Algorithms,
// §15.3), at most five solve pairs; x and y are k doubles of scratch. A lower bound that is almost always within a
// small factor of the truth; +∞ when a solve overflows.
inline double InverseNorm1Estimate(const double* a, int ld, int k, const int* piv, double* x, double* y) {
  for (int i = 0; i < k; ++i) x[i] = 1.0 / k;
  double estimate = 0.0;
  int last_j = -1;
  for (int iter = 0; iter < 5; ++iter) {
    std::copy(x, x + k, y);
    SolveRows(a, ld, k, piv, y, 1);
    double norm = 0.0;
    for (int i = 0; i < k; ++i) norm += std::abs(y[i]);
    if (!std::isfinite(norm)) return kInf;
    if (iter > 0 && norm <= estimate) break;
    estimate = norm;
    for (int i = 0; i < k; ++i) y[i] = y[i] >= 0.0 ? 1.0 : -1.0;
    SolveTransposed(a, ld, k, piv, y);
    int j = 0;
    for (int i = 1; i < k; ++i) {
      if (std::abs(y[i]) > std::abs(y[j])) j = i;
    }
    double ztx = 0.0;
    for (int i = 0; i < k; ++i) ztx += y[i] * x[i];
    if (iter > 0 && (std::abs(y[j]) <= ztx || j == last_j)) break;
    last_j = j;
    std::fill(x, x + k, 0.0);
    x[j] = 1.0;
  }
  return estimate;
}

}  // namespace smcbench::dense_lu
