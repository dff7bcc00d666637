// Exact polish: from an approximate solution z of a row-equilibrated box-MLCP, identify the active set by the
// natural map and solve the reduced linear system M_FF z_F = −(q_F + M_FB z_B) directly. Solver's base layer keeps
// the polished point when its merit is not worse (solver.cc), so every backend ends on an exact answer when it
// found the right active set (the paper's Lemma "yahoo": x is exactly 0 after the arrival, whatever the backend).
#pragma once

#include <cstddef>

#include "solvers/core/active_set.h"
#include "solvers/core/problem.h"

namespace smcbench {

// A free row whose exact value leaves the box (a degenerate row the natural map called free) is moved to the bound
// it crossed and the system solved again, at most this many times; then the polish gives up.
inline constexpr int kPolishPasses = 3;

// The active set the polish reads from z: ClassifyRow of every row of the dense equilibrated problem, with
// w = M z + q summed as written (q first, then the columns in order). N = n, or 0 for a run-time n; then w is n
// entries of scratch, and the sums run down the columns (M is column-major: a row at a time would read M with a
// stride of n doubles, which at n = 512 costs more than the sums), each row's sum in the same order.
template <int N>
inline void ClassifyRowsForPolish(const BoxMLCP& equilibrated, const double* z, signed char* state,
                                  double* w_scratch) {
  const int n = N > 0 ? N : equilibrated.size();
  const double* a = equilibrated.dense_matrix().data();
  const double *q = equilibrated.q().data(), *l = equilibrated.l().data(), *u = equilibrated.u().data();
  if constexpr (N > 0) {
    for (int i = 0; i < n; ++i) {
      double w = q[i];
      for (int j = 0; j < n; ++j) w += a[i + j * n] * z[j];
      state[i] = static_cast<signed char>(ClassifyRow(z[i], w, l[i], u[i]));
    }
  } else {
    double* w = w_scratch;
    for (int i = 0; i < n; ++i) w[i] = q[i];
    for (int j = 0; j < n; ++j) {
      const double* column = a + static_cast<std::ptrdiff_t>(j) * n;
      const double zj = z[j];
      for (int i = 0; i < n; ++i) w[i] += column[i] * zj;
    }
    for (int i = 0; i < n; ++i) state[i] = static_cast<signed char>(ClassifyRow(z[i], w[i], l[i], u[i]));
  }
}

// Storage for PolishDense on n rows (active_set.h).
using PolishScratch = ActiveSetScratch;
using PolishWorkspace = ActiveSetWorkspace;

// The active set in s.state solved exactly into out, a free row that leaves the box moved to the bound it crossed
// and the set solved again, up to kPolishPasses times (N = n, or 0 for a run-time n). False if the free block is
// singular or the result is not finite or will not stay in the box. Nothing allocated.
template <int N>
bool SolveSetMovingCrossedRows(const BoxMLCP& equilibrated, const PolishScratch& s, double* out) {
  const int n = N > 0 ? N : equilibrated.size();
  const double* a = equilibrated.dense_matrix().data();
  const double *q = equilibrated.q().data(), *l = equilibrated.l().data(), *u = equilibrated.u().data();
  for (int pass = 0; pass < kPolishPasses; ++pass) {
    int nf = 0;
    // Threshold 0: only an exact zero (or NaN) pivot is singular; the merit function judges the result.
    const ActiveSetOutcome outcome = active_set::SolveDense<N>(a, n, q, l, u, s.state, 0.0, s, out, &nf);
    if (outcome == ActiveSetOutcome::kSolved) return true;
    if (outcome != ActiveSetOutcome::kOutsideBox) return false;
    for (int k = 0; k < nf; ++k) {
      const int i = s.free_rows[k];
      if (out[i] < l[i]) s.state[i] = static_cast<signed char>(RowState::kLower);
      if (out[i] > u[i]) s.state[i] = static_cast<signed char>(RowState::kUpper);
    }
  }
  return false;
}

// The polish of a dense n×n problem (N = n fixed at compile time for the time-stepper's small solves, N = 0 for a
// run-time n): the active set read off z (ClassifyRowsForPolish), then SolveSetMovingCrossedRows. Writes the
// polished point to out (n entries); false when that fails.
template <int N>
bool PolishDense(const BoxMLCP& equilibrated, const double* z, double* out, const PolishScratch& s) {
  ClassifyRowsForPolish<N>(equilibrated, z, s.state, s.rhs);  // rhs: scratch until the set is solved
  return SolveSetMovingCrossedRows<N>(equilibrated, s, out);
}

// Dense problems above this size are not polished (the O(n³) solve and n² workspace would dominate an iterative
// backend's time and memory).
inline constexpr int kMaxPolishDenseSize = 512;

// Free blocks of sparse problems up to this many rows are factored densely (gathered, then the dense kernel).
inline constexpr int kMaxDenseSparsePolishBlock = 64;

// Sparse problems: the same on the free block, through the dense kernel up to kMaxDenseSparsePolishBlock free rows,
// else the kernel's SparseFreeBlock (allocates; sparse problems are not a time-stepper's hot path). One pass: false
// when the result leaves the box.
bool PolishSparse(const BoxMLCP& equilibrated, const Vector& z, Vector* out);

}  // namespace smcbench
