// The one kernel that solves an identified active set of a box-MLCP exactly: each row free or at a bound, bound rows
// placed at their bound, the reduced block M_FF factored (dense LU with partial pivoting, or sparse LU) and solved
// for z_F = −M_FF⁻¹(q_F + M_FB z_B), z_F checked against its box and the bound rows' w against their signs. The
// base's polish (polish.h), a session's reused active set (session.h) and lemke's polish build on it, enum on its
// blocked entry point, ipopt's polish on its row states, its dense block gather and RobustFreeBlock (its factors of
// a block that may be singular). Callers keep only their policy.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "solvers/core/dense_lu.h"
#include "solvers/core/types.h"

namespace smcbench {

class BoxMLCP;

// Where a row of an identified active set sits. kFixed: l = u, the row is at that value whatever its w (a caller
// that pins such rows says so; ClassifyRow never answers kFixed).
enum class RowState : signed char { kLower = -1, kFree = 0, kUpper = 1, kFixed = 2 };

// The natural map's classification: row i is at its lower bound when z_i − w_i ≤ l_i, at its upper bound when
// z_i − w_i ≥ u_i, else free (w = M z + q; pass the row-equilibrated w for a test in units of z).
inline RowState ClassifyRow(double z, double w, double l, double u) {
  const double t = z - w;
  return t <= l ? RowState::kLower : (t >= u ? RowState::kUpper : RowState::kFree);
}

// The value a row of this state takes before the free block is solved: its bound, or 0 on a free row (so that a
// full row of M times z is the bound part M_FB z_B).
inline double PlacedValue(RowState s, double l, double u) {
  return s == RowState::kFree ? 0.0 : (s == RowState::kUpper ? u : l);
}

// How the free rows' solution fits their box.
enum class FreeRowsFit { kInside, kOutside, kNonFinite };

// What one solve of an identified active set found.
enum class ActiveSetOutcome {
  kSolved,          // M_FF nonsingular and every z_F finite and inside [l_F, u_F]
  kOutsideBox,      // some z_F left its box (z holds the unclipped values; the set is wrong or degenerate)
  kSingular,        // a pivot of M_FF at or below the caller's threshold (or NaN): z_F not computed
  kNonFinite,       // some z_F overflowed
};

// Caller-owned storage for one dense solve on n rows (each of the documented length): stack arrays for the
// fixed-size small solves, ActiveSetWorkspace for run-time sizes.
struct ActiveSetScratch {
  double* block;       // n·n: the reduced matrix, column-major with leading dimension n (dense_lu.h)
  double* rhs;         // n
  signed char* state;  // n: RowState per row
  int* free_rows;      // n
  int* pivots;         // n: the LU's row swaps
};

namespace active_set {

// z ← the bound rows' values, 0 on the free rows, whose indices are listed in free_rows (increasing); returns their
// number. N = n fixed at compile time, or 0 for a run-time n.
template <int N = 0>
inline int PlaceBoundRows(int n_runtime, const signed char* state, const double* l, const double* u, double* z,
                          int* free_rows) {
  const int n = N > 0 ? N : n_runtime;
  int nf = 0;
  for (int i = 0; i < n; ++i) {
    const auto s = static_cast<RowState>(state[i]);
    if (s == RowState::kFree) free_rows[nf++] = i;
    z[i] = PlacedValue(s, l[i], u[i]);
  }
  return nf;
}

// rhs[k] = −(q_f + Σ_j M_fj z_j) for f = free_rows[k], summed as written (q first, then the columns in order); with
// z = 0 on the free rows that is −(q_F + M_FB z_B). m: dense n×n, column-major.
template <int N = 0>
inline void ReducedRhs(const double* m, int n_runtime, const double* q, const double* z, const int* free_rows, int nf,
                       double* rhs) {
  const int n = N > 0 ? N : n_runtime;
  for (int k = 0; k < nf; ++k) {
    const int f = free_rows[k];
    double b = -q[f];
    for (int j = 0; j < n; ++j) b -= m[f + static_cast<std::ptrdiff_t>(j) * n] * z[j];
    rhs[k] = b;
  }
}

// block (column-major, leading dimension ld ≥ nf) ← M_FF of the dense n×n column-major m.
inline void GatherFreeBlock(const double* m, int n, const int* free_rows, int nf, double* block, int ld) {
  for (int c = 0; c < nf; ++c) {
    const double* mc = m + static_cast<std::ptrdiff_t>(free_rows[c]) * n;
    double* bc = block + static_cast<std::ptrdiff_t>(c) * ld;
    for (int r = 0; r < nf; ++r) bc[r] = mc[free_rows[r]];
  }
}

// z_F ← x (x[k] is row free_rows[k]), and how it fits [l_F, u_F]; a non-finite entry outranks one outside.
inline FreeRowsFit ScatterFreeRows(const double* x, const int* free_rows, int nf, const double* l, const double* u,
                                   double* z) {
  FreeRowsFit fit = FreeRowsFit::kInside;
  for (int k = 0; k < nf; ++k) {
    const int i = free_rows[k];
    const double v = x[k];
    z[i] = v;
    if (!std::isfinite(v)) return FreeRowsFit::kNonFinite;
    if (v < l[i] || v > u[i]) fit = FreeRowsFit::kOutside;
  }
  return fit;
}

// One identified active set of the dense n×n problem (m column-major, q, l, u; state per row) solved from scratch:
// bound rows placed, M_FF gathered and factored by dense_lu (a pivot must exceed `small`, an absolute threshold in
// the units of M; 0 rejects only an exact zero or NaN), z_F solved and scattered into z. Nothing allocated.
// *free_count: the number of free rows (listed in s.free_rows). N = n at compile time, or 0.
template <int N = 0>
inline ActiveSetOutcome SolveDense(const double* m, int n_runtime, const double* q, const double* l, const double* u,
                                   const signed char* state, double small, const ActiveSetScratch& s, double* z,
                                   int* free_count) {
  const int n = N > 0 ? N : n_runtime;
  const int nf = PlaceBoundRows<N>(n, state, l, u, z, s.free_rows);
  *free_count = nf;
  if (nf == 0) return ActiveSetOutcome::kSolved;
  ReducedRhs<N>(m, n, q, z, s.free_rows, nf, s.rhs);
  GatherFreeBlock(m, n, s.free_rows, nf, s.block, n);
  if (!dense_lu::Factor(s.block, n, nf, s.pivots, small)) return ActiveSetOutcome::kSingular;
  dense_lu::Solve(s.block, n, nf, s.pivots, s.rhs);
  switch (ScatterFreeRows(s.rhs, s.free_rows, nf, l, u, z)) {
    case FreeRowsFit::kInside: return ActiveSetOutcome::kSolved;
    case FreeRowsFit::kOutside: return ActiveSetOutcome::kOutsideBox;
    case FreeRowsFit::kNonFinite: break;
  }
  return ActiveSetOutcome::kNonFinite;
}

// The sign check of an identified active set: every bound row's w = M z + q must push against its bound, w_i ≥
// −margin at the lower and w_i ≤ margin at the upper; kFixed rows and rows with l_i = u_i take any w. margin is
// absolute, in the units of w: 0 is the exact test (a session's reused set, where the merit function alone would
// accept a wrong sign of rounding size); a caller that forgives rounding passes its own scale, e.g. tol·(1 + ‖q‖∞).
template <int N = 0>
inline bool BoundRowSignsHold(int n_runtime, const signed char* state, const double* w, const double* l,
                              const double* u, double margin) {
  const int n = N > 0 ? N : n_runtime;
  for (int i = 0; i < n; ++i) {
    const auto row = static_cast<RowState>(state[i]);
    const bool fixed = l[i] == u[i];
    if (!fixed && ((row == RowState::kLower && w[i] < -margin) || (row == RowState::kUpper && w[i] > margin))) {
      return false;
    }
  }
  return true;
}

// The blocked entry point, for a search that factors many small free blocks (enum's fixed-size hot path). These four
// are `static`: with internal linkage GCC inlines them, and the paths around them, into each caller's fixed-size
// loops, which an external-linkage inline does not get.
// The k×k block A factored in place by dense_lu with k ≤ 4 unrolled at compile time and k = 1 its own pivot. False
// if a pivot is ≤ small (numerically singular) or NaN. Split from the solve so a caller can keep factors per set.
static inline bool FactorBlock(double* a, int ld, int k, int* piv, double small) {
  if (k == 1) return std::abs(a[0]) > small;
  if (k == 2) return dense_lu::Factor<2>(a, ld, k, piv, small);
  if (k == 3) return dense_lu::Factor<3>(a, ld, k, piv, small);
  if (k == 4) return dense_lu::Factor<4>(a, ld, k, piv, small);
  return dense_lu::Factor(a, ld, k, piv, small);
}

// Solves A x = b (b becomes x) from FactorBlock's output.
static inline void SolveFactored(const double* a, int ld, int k, const int* piv, double* b) {
  if (k == 1) {
    b[0] /= a[0];
  } else if (k == 2) {
    dense_lu::Solve<2>(a, ld, k, piv, b);
  } else if (k == 3) {
    dense_lu::Solve<3>(a, ld, k, piv, b);
  } else if (k == 4) {
    dense_lu::Solve<4>(a, ld, k, piv, b);
  } else {
    dense_lu::Solve(a, ld, k, piv, b);
  }
}

// FactorBlock then SolveFactored: false, with A and b clobbered, if a pivot is ≤ small or NaN.
static inline bool SolveBlock(double* a, int ld, int k, double* b, int* piv, double small) {
  if (!FactorBlock(a, ld, k, piv, small)) return false;
  SolveFactored(a, ld, k, piv, b);
  return true;
}

// The smallest |pivot| of a block factored by FactorBlock and the sign of its determinant (row swaps included).
struct BlockPivots {
  double smallest = kInf;
  int sign = 1;
};
static inline BlockPivots FactoredPivots(const double* a, int ld, int k, const int* piv) {
  BlockPivots p;
  for (int j = 0; j < k; ++j) {
    const double d = a[j + static_cast<std::ptrdiff_t>(j) * ld];
    p.smallest = std::min(p.smallest, std::abs(d));
    if (d < 0.0) p.sign = -p.sign;
    if (k > 1 && piv[j] != j) p.sign = -p.sign;  // k = 1: FactorBlock records no swap
  }
  return p;
}

}  // namespace active_set

// Storage for run-time sizes, sized once per n: repeated solves of the same size allocate nothing.
class ActiveSetWorkspace {
 public:
  ActiveSetScratch For(int n) {
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

// One active set factored once and re-solved for many q (a session's reused set, the time-stepper's steps): the LU
// factors (partial pivoting) of M_FF for dense n×n M. Storage is sized once (n), so refactoring for a new active
// set allocates nothing.
class ActiveSetFactors {
 public:
  void Resize(int n);
  // Factors M_FF for the row states in `state` (RowState values). False when M_FF is singular or its pivots span
  // more than kMinPivotRatio (then the stored set is not to be trusted). InvalidInputError if M is not n×n.
  bool Factor(const DenseMatrix& M, const signed char* state);
  // z for right-hand side q: bound rows at their bound, z_F = −M_FF⁻¹(q_F + M_FB z_B). False unless every z_F is
  // finite and inside [l_F, u_F]. N = n when known at compile time (the small-solve path), else 0.
  template <int N>
  bool Solve(const DenseMatrix& M, const double* q, const double* l, const double* u, double* z) const;
  // For small n: the same solution as an affine map of q, z = A q + c (A column-major n×n, zero on bound rows; c
  // the bounds there), so a small problem's re-solve is n² multiply-adds and no substitution. Requires valid().
  // free_row: the only free row when there is exactly one (then z_f is computed by one division instead, as the
  // polish does, to keep its bits), else −1.
  void AffineMap(const DenseMatrix& M, const double* l, const double* u, double* A, double* c, int* free_row) const;
  bool valid() const { return valid_; }
  void Invalidate() { valid_ = false; }
  const signed char* state() const { return state_.data(); }

  // Smallest |pivot| / largest |pivot| accepted: below it the block is too close to singular for a stored
  // factorization to be trusted, and the caller's own safeguarded method answers instead.
  static constexpr double kMinPivotRatio = 1e-13;

 private:
  int n_ = 0;
  int nf_ = 0;
  bool valid_ = false;
  std::vector<signed char> state_;
  std::vector<int> free_rows_, pivots_;  // pivots_: dense_lu's row swaps
  std::vector<double> lu_;               // dense_lu's factors of M_FF, nf×nf column-major with leading dimension n
  mutable std::vector<double> rhs_;      // scratch of Solve and AffineMap, sized in Resize
};

// The sparse reduced block: M_FF of a sparse M gathered and factored by Eigen's SparseLU (COLAMD ordering). The
// factorization allocates (sparse problems are not a time-stepper's hot path); the gather's index map is kept.
class SparseFreeBlock {
 public:
  SparseFreeBlock();
  ~SparseFreeBlock();
  SparseFreeBlock(SparseFreeBlock&&) noexcept;
  SparseFreeBlock& operator=(SparseFreeBlock&&) noexcept;

  // Gathers M_FF for the nf rows listed (increasing) and factors it. False when SparseLU fails (structurally or
  // numerically singular); block() is set either way, for a caller's fallback. InvalidInputError (naming M or
  // free_rows) for a non-square M or a list that is not increasing indices of M.
  bool Factor(const SparseMatrix& M, const int* free_rows, int nf);
  // x = M_FF⁻¹ b from the last successful Factor; false when SparseLU reports a failure.
  bool Solve(const Vector& b, Vector* x);
  const SparseMatrix& block() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};


// The free block of a polish that must answer even when M_FF is singular (ipopt's polish of an interior-point
// iterate, whose active set may be wrong or degenerate): dense M_FF factored by LU with partial pivoting, or, when
// that LU's reciprocal condition estimate is at or below 1e3·ε (partial pivoting returns garbage, not an error, on
// a singular block), by the complete orthogonal decomposition, whose solve is the minimum-norm least-squares
// solution (a singular PSD block's); sparse M_FF by SparseFreeBlock, or SparseQR when SparseLU fails. Storage is
// kept between calls; the factorizations allocate when the block's size changes.
class RobustFreeBlock {
 public:
  RobustFreeBlock();
  ~RobustFreeBlock();
  RobustFreeBlock(RobustFreeBlock&&) noexcept;
  RobustFreeBlock& operator=(RobustFreeBlock&&) noexcept;

  // Gathers M_FF of problem's M for the nf rows listed (increasing) and factors it. False when no factorization is
  // usable (sparse: SparseLU and SparseQR both fail).
  bool Factor(const BoxMLCP& problem, const int* free_rows, int nf);
  // *x = M_FF⁻¹ b (the least-squares solution after a fallback) from the last successful Factor.
  void Solve(const Vector& b, Vector* x);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smcbench
