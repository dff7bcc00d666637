// Exact polish: from an approximate solution z of a row-equilibrated box-MLCP, identify the active set by the
// natural map and solve the reduced linear system M_FF z_F = −(q_F + M_FB z_B) directly. Solver's base layer keeps
// the polished point when its merit is not worse (solver.cc), so every backend ends on an exact answer when it
// found the right active set (the paper's Lemma "yahoo": x is exactly 0 after the arrival, whatever the backend).
#pragma once

#include <cmath>
#include <vector>

#include "solvers/core/dense_lu.h"
#include "solvers/core/problem.h"

namespace smcbench {

// Row i is at its lower bound when z_i − w_i ≤ l_i, at its upper bound when z_i − w_i ≥ u_i, else free
// (w = M z + q of the equilibrated problem, so the test is in units of z).
enum class RowState : signed char { kLower = -1, kFree = 0, kUpper = 1 };
inline RowState ClassifyRow(double z, double w, double l, double u) {
  const double t = z - w;
  return t <= l ? RowState::kLower : (t >= u ? RowState::kUpper : RowState::kFree);
}

// A free row whose exact value leaves the box (a degenerate row the natural map called free) is moved to the bound
// it crossed and the system solved again, at most this many times; then the polish gives up.
inline constexpr int kPolishPasses = 3;

// The active set the polish reads from z: ClassifyRow of every row of the dense equilibrated problem, with
// w = M z + q summed as written (q first, then the columns in order). N = n, or 0 for a run-time n.
template <int N>
inline void ClassifyRowsForPolish(const BoxMLCP& equilibrated, const double* z, signed char* state) {
  const int n = N > 0 ? N : equilibrated.size();
  const double* a = equilibrated.dense_matrix().data();
  const double *q = equilibrated.q().data(), *l = equilibrated.l().data(), *u = equilibrated.u().data();
  for (int i = 0; i < n; ++i) {
    double w = q[i];
    for (int j = 0; j < n; ++j) w += a[i + j * n] * z[j];
    state[i] = static_cast<signed char>(ClassifyRow(z[i], w, l[i], u[i]));
  }
}

// Storage for PolishDense on n rows: the pointers it needs, each of the documented length.
struct PolishScratch {
  double* block;       // n·n: the reduced matrix, column-major with leading dimension n (dense_lu.h)
  double* rhs;         // n
  signed char* state;  // n: RowState per row
  int* free_rows;      // n
  int* pivots;         // n: the LU's row swaps
};

// The polish of a dense n×n problem (N = n fixed at compile time for the time-stepper's small solves, N = 0 for a
// run-time n): the free block factored by dense_lu (partial pivoting), nothing allocated. Writes the polished point
// to out (n entries); false if the free block is singular or the result is not finite or will not stay in the box
// within kPolishPasses passes.
template <int N>
bool PolishDense(const BoxMLCP& equilibrated, const double* z, double* out, const PolishScratch& s) {
  const int n = N > 0 ? N : equilibrated.size();
  const double* a = equilibrated.dense_matrix().data();
  const double *q = equilibrated.q().data(), *l = equilibrated.l().data(), *u = equilibrated.u().data();
  ClassifyRowsForPolish<N>(equilibrated, z, s.state);
  for (int pass = 0; pass < kPolishPasses; ++pass) {
    int nf = 0;
    for (int i = 0; i < n; ++i) {
      const auto st = static_cast<RowState>(s.state[i]);
      if (st == RowState::kFree) s.free_rows[nf++] = i;
      out[i] = st == RowState::kFree ? 0.0 : (st == RowState::kLower ? l[i] : u[i]);
    }
    if (nf == 0) return true;
    // The reduced system on the free rows, the bound rows' values moved to the right-hand side (out is 0 on free
    // rows here, so the full row times out is exactly the bound part).
    for (int k = 0; k < nf; ++k) {
      const int f = s.free_rows[k];
      double b = -q[f];
      for (int j = 0; j < n; ++j) b -= a[f + j * n] * out[j];
      s.rhs[k] = b;
    }
    for (int c = 0; c < nf; ++c) {
      for (int r = 0; r < nf; ++r) s.block[r + c * n] = a[s.free_rows[r] + s.free_rows[c] * n];
    }
    if (!dense_lu::Factor(s.block, n, nf, s.pivots, 0.0)) return false;  // a zero (or NaN) pivot
    dense_lu::Solve(s.block, n, nf, s.pivots, s.rhs);
    bool moved = false;
    for (int k = 0; k < nf; ++k) {
      const double x = s.rhs[k];
      if (!std::isfinite(x)) return false;
      const int i = s.free_rows[k];
      out[i] = x;
      if (x < l[i] || x > u[i]) {
        s.state[i] = static_cast<signed char>(x < l[i] ? RowState::kLower : RowState::kUpper);
        moved = true;
      }
    }
    if (!moved) return true;
  }
  return false;
}

// Workspace for run-time sizes, sized once per n: repeated polishes of the same size allocate nothing.
class PolishWorkspace {
 public:
  PolishScratch For(int n) {
    if (static_cast<int>(rhs_.size()) != n) {
      block_.assign(static_cast<std::size_t>(n) * n, 0.0);
      rhs_.assign(n, 0.0);
      state_.assign(n, 0);
      free_rows_.assign(n, 0);
      pivots_.assign(n, 0);
    }
    return {block_.data(), rhs_.data(), state_.data(), free_rows_.data(), pivots_.data()};
  }

 private:
  std::vector<double> block_, rhs_;
  std::vector<signed char> state_;
  std::vector<int> free_rows_, pivots_;
};

// Dense problems above this size are not polished (the O(n³) solve and n² workspace would dominate an iterative
// backend's time and memory).
inline constexpr int kMaxPolishDenseSize = 512;

// Sparse problems: the same on the free block through Eigen's SparseLU (allocates; sparse problems are not a
// time-stepper's hot path). One pass: false when the result leaves the box.
bool PolishSparse(const BoxMLCP& equilibrated, const Vector& z, Vector* out);

}  // namespace smcbench
