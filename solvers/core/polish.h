// Exact polish: from an approximate solution z of a row-equilibrated box-MLCP, identify the active set by the
// natural map and solve the reduced linear system M_FF z_F = −(q_F + M_FB z_B) directly. Solver's base layer keeps
// the polished point when its merit is not worse (solver.cc), so every backend ends on an exact answer when it
// found the right active set (the paper's Lemma "yahoo": x is exactly 0 after the arrival, whatever the backend).
#pragma once

#include <cmath>

#include "solvers/core/problem.h"

namespace smcbench {

// Row i is at its lower bound when z_i − w_i ≤ l_i, at its upper bound when z_i − w_i ≥ u_i, else free
// (w = M z + q of the equilibrated problem, so the test is in units of z).
enum class RowState : signed char { kLower = -1, kFree = 0, kUpper = 1 };
inline RowState ClassifyRow(double z, double w, double l, double u) {
  const double t = z - w;
  return t <= l ? RowState::kLower : (t >= u ? RowState::kUpper : RowState::kFree);
}

// Dense n = N ≤ BoxMLCP::kSmallSize: fixed-size arrays, Gaussian elimination with partial pivoting on the free
// block, nothing allocated. Writes the polished point to out (size N); false if the free block is singular, or the
// result is not finite or leaves the box.
template <int N>
bool PolishSmallDense(const BoxMLCP& equilibrated, const double* z, double* out) {
  const double* a = equilibrated.dense_matrix().data();
  const double *q = equilibrated.q().data(), *l = equilibrated.l().data(), *u = equilibrated.u().data();
  int free_rows[N];
  int nf = 0;
  for (int i = 0; i < N; ++i) {
    double w = q[i];
    for (int j = 0; j < N; ++j) w += a[i + j * N] * z[j];
    const RowState s = ClassifyRow(z[i], w, l[i], u[i]);
    if (s == RowState::kFree) {
      free_rows[nf++] = i;
      out[i] = z[i];
    } else {
      out[i] = s == RowState::kLower ? l[i] : u[i];
    }
  }
  if (nf == 0) return true;
  // The reduced system on the free rows, with the bound rows' values moved to the right-hand side.
  double A[N][N], b[N];
  for (int k = 0; k < nf; ++k) {
    const int f = free_rows[k];
    b[k] = -q[f];
    for (int j = 0; j < N; ++j) {
      bool is_free = false;
      for (int c = 0; c < nf; ++c) is_free = is_free || free_rows[c] == j;
      if (!is_free) b[k] -= a[f + j * N] * out[j];
    }
    for (int c = 0; c < nf; ++c) A[k][c] = a[f + free_rows[c] * N];
  }
  for (int k = 0; k < nf; ++k) {
    int p = k;
    for (int r = k + 1; r < nf; ++r) {
      if (std::abs(A[r][k]) > std::abs(A[p][k])) p = r;
    }
    if (!(A[p][k] != 0.0)) return false;
    if (p != k) {
      for (int c = 0; c < nf; ++c) std::swap(A[k][c], A[p][c]);
      std::swap(b[k], b[p]);
    }
    for (int r = k + 1; r < nf; ++r) {
      const double m = A[r][k] / A[k][k];
      for (int c = k; c < nf; ++c) A[r][c] -= m * A[k][c];
      b[r] -= m * b[k];
    }
  }
  for (int k = nf - 1; k >= 0; --k) {
    double s = b[k];
    for (int c = k + 1; c < nf; ++c) s -= A[k][c] * out[free_rows[c]];
    const double x = s / A[k][k];
    // A free row whose exact value leaves the box was not free: this is not the active set.
    if (!std::isfinite(x) || x < l[free_rows[k]] || x > u[free_rows[k]]) return false;
    out[free_rows[k]] = x;
  }
  return true;
}

// Any size and storage (dense through Eigen's partial-pivot LU, sparse through Eigen's SparseLU); allocates, so it
// serves the larger problems, which are not a time-stepper's hot path. Dense problems above kMaxPolishDenseSize are
// not polished (the O(n³) solve would dominate an iterative backend's time): returns false.
inline constexpr int kMaxPolishDenseSize = 512;
bool PolishGeneric(const BoxMLCP& equilibrated, const Vector& z, Vector* out);

}  // namespace smcbench
