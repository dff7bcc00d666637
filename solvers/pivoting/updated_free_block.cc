// The free block solved by a Schur-complement update of a reference LU (updated_free_block.h states the method).
#include "solvers/pivoting/updated_free_block.h"

#include <cmath>
#include <cstddef>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "solvers/core/active_set.h"
#include "solvers/core/dense_lu.h"

namespace smcbench {
namespace {

// Above this many free rows the block is factored by Eigen's blocked LU (matrix-matrix updates) instead of the
// unblocked dense_lu: the factorization is the whole cost of a fresh set there.
constexpr int kBlockedLuRows = 64;

// LU with partial pivoting of the k×k block (column-major, leading dimension ld) in dense_lu's storage: L unit lower
// and U in place, piv[j] the row swapped with row j at step j (Eigen's row transpositions are the same record), so
// dense_lu::Solve solves with either. False when a pivot is ≤ small or not finite.
bool FactorFreeBlock(double* a, int ld, int k, int* piv, double small) {
  if (k <= kBlockedLuRows) return dense_lu::Factor(a, ld, k, piv, small);
  int transpositions = 0;
  Eigen::internal::partial_lu_impl<double, Eigen::ColMajor, int>::blocked_lu(k, k, a, ld, piv, transpositions);
  for (int j = 0; j < k; ++j) {
    if (!(std::abs(a[j + static_cast<std::ptrdiff_t>(j) * ld]) > small)) return false;  // NaN too
  }
  return true;
}

}  // namespace

void UpdatedFreeBlock::Resize(int n) {
  has_base_ = false;
  if (n_ == n && !lu_.empty()) return;
  n_ = n;
  const std::size_t nn = static_cast<std::size_t>(n);
  lu_.assign(nn * nn, 0.0);
  base_rows_.assign(nn, 0);
  base_pos_.assign(nn, -1);
  pivots_.assign(nn, 0);
  slot_row_.assign(kMaxRankCap, 0);
  slot_added_.assign(kMaxRankCap, 0);
  row_slot_.assign(nn, -1);
  w_.assign(nn * kMaxRankCap, 0.0);
  c_.assign(nn * kMaxRankCap, 0.0);
  s_.assign(static_cast<std::size_t>(kMaxRankCap) * kMaxRankCap, 0.0);
  s_lu_.assign(s_.size(), 0.0);
  s_pivots_.assign(kMaxRankCap, 0);
  y_.assign(nn, 0.0);
  t_.assign(kMaxRankCap, 0.0);
  in_f_.assign(nn, 0);
  nf0_ = 0;
  slots_ = 0;
}

bool UpdatedFreeBlock::Solve(const double* m, int n, const double* q, const int* free_rows, int nf, double small,
                             double* z) {
  last_path_ = Path::kFactored;
  if (nf == 0) return true;
  if (updates_ && has_base_ && nf >= kMinRows && nf0_ >= kMinRows && TryUpdate(m, n, q, free_rows, nf, z)) {
    last_path_ = Path::kUpdated;
    ++updates_done_;
    return true;
  }
  return Factor(m, n, q, free_rows, nf, small, z);
}

bool UpdatedFreeBlock::Factor(const double* m, int n, const double* q, const int* free_rows, int nf, double small,
                              double* z) {
  ++factorizations_;
  for (int p = 0; p < nf0_; ++p) base_pos_[base_rows_[p]] = -1;
  for (int j = 0; j < slots_; ++j) row_slot_[slot_row_[j]] = -1;
  slots_ = 0;
  nf0_ = 0;
  has_base_ = false;
  base_cholesky_ = ratio_ != nullptr && !cholesky_failed_ && FactorCholesky(m, n, free_rows, nf, small);
  if (base_cholesky_) {
    ++cholesky_;
  } else {
    if (ratio_ != nullptr) cholesky_failed_ = true;
    active_set::GatherFreeBlock(m, n, free_rows, nf, lu_.data(), n);
    if (!FactorFreeBlock(lu_.data(), n, nf, pivots_.data(), small)) return false;
  }
  nf0_ = nf;
  for (int p = 0; p < nf; ++p) {
    base_rows_[p] = free_rows[p];
    base_pos_[free_rows[p]] = p;
  }
  has_base_ = true;
  double* b = y_.data();
  active_set::ReducedRhs<0>(m, n, q, z, free_rows, nf, b);
  SolveBase(b);
  for (int k = 0; k < nf; ++k) {
    z[free_rows[k]] = b[k];
    if (!std::isfinite(b[k])) return false;
  }
  return true;
}

bool UpdatedFreeBlock::FactorCholesky(const double* m, int n, const int* free_rows, int nf, double small) {
  // The lower triangle of (R⁻¹ M)_FF: row p of the block divided by r of its row.
  double* a = lu_.data();
  const double* inv = inv_ratio_;
  for (int c = 0; c < nf; ++c) {
    const double* column = m + static_cast<std::ptrdiff_t>(free_rows[c]) * n;
    double* out = a + static_cast<std::ptrdiff_t>(c) * n;
    for (int p = c; p < nf; ++p) out[p] = column[free_rows[p]] * inv[free_rows[p]];
  }
  Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>> block(a, nf, nf, Eigen::OuterStride<>(n));
  if (Eigen::internal::llt_inplace<double, Eigen::Lower>::blocked(block) >= 0) return false;
  for (int j = 0; j < nf; ++j) {
    const double l = a[j + static_cast<std::ptrdiff_t>(j) * n];
    if (!(ratio_[free_rows[j]] * l * l > small) || !(l < kInf)) return false;  // NaN too
  }
  return true;
}

void UpdatedFreeBlock::SolveBase(double* b) const {
  const int k = nf0_;
  const double* a = lu_.data();
  const std::ptrdiff_t ld = n_;
  if (!base_cholesky_) {
    dense_lu::Solve(a, n_, k, pivots_.data(), b);
    return;
  }
  // A0 = R L Lᵀ: b ← R⁻¹ b, then L y = b (column axpys) and Lᵀ x = y (column dot products).
  const int* rows = base_rows_.data();
  for (int p = 0; p < k; ++p) b[p] *= inv_ratio_[rows[p]];
  for (int j = 0; j < k; ++j) {
    const double* cj = a + j * ld;
    const double bj = b[j] /= cj[j];
    if (bj == 0.0) continue;
    for (int i = j + 1; i < k; ++i) b[i] -= cj[i] * bj;
  }
  for (int j = k - 1; j >= 0; --j) {
    const double* cj = a + j * ld;
    double sum = b[j];
    for (int i = j + 1; i < k; ++i) sum -= cj[i] * b[i];
    b[j] = sum / cj[j];
  }
}

void UpdatedFreeBlock::AddSlot(const double* m, int n, int row) {
  const int j = slots_++;
  const bool added = base_pos_[row] < 0;
  slot_row_[j] = row;
  slot_added_[j] = added ? 1 : 0;
  row_slot_[row] = j;
  const int nf0 = nf0_;
  const int* base = base_rows_.data();
  double* bj = w_.data() + static_cast<std::size_t>(j) * n;  // B's column, W's once solved
  double* cj = c_.data() + static_cast<std::size_t>(j) * n;  // C's row, stored as a column
  if (added) {
    const double* column = m + static_cast<std::ptrdiff_t>(row) * n;
    for (int p = 0; p < nf0; ++p) {
      bj[p] = column[base[p]];
      cj[p] = m[row + static_cast<std::ptrdiff_t>(base[p]) * n];
    }
  } else {
    std::fill(bj, bj + nf0, 0.0);
    std::fill(cj, cj + nf0, 0.0);
    bj[base_pos_[row]] = 1.0;
    cj[base_pos_[row]] = 1.0;
  }
}

void UpdatedFreeBlock::FinishSlots(const double* m, int n, int first) {
  using Map = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  using ConstMap = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  const int nf0 = nf0_, k = slots_, added = k - first;
  // W's new columns: A0⁻¹ B_new, all at once (row swaps, then the triangular solves with several right-hand sides).
  double* w_new = w_.data() + static_cast<std::size_t>(first) * n;
  const ConstMap a0(lu_.data(), nf0, nf0, Eigen::OuterStride<>(n));
  Map w_block(w_new, nf0, added, Eigen::OuterStride<>(n));
  if (base_cholesky_) {
    // A0 = R L Lᵀ: the rows scaled by R⁻¹, then L and Lᵀ.
    const int* rows = base_rows_.data();
    for (int c = 0; c < added; ++c) {
      double* column = w_new + static_cast<std::size_t>(c) * n;
      for (int p = 0; p < nf0; ++p) column[p] *= inv_ratio_[rows[p]];
    }
    a0.triangularView<Eigen::Lower>().solveInPlace(w_block);
    a0.triangularView<Eigen::Lower>().transpose().solveInPlace(w_block);
  } else {
    const int* piv = pivots_.data();
    for (int j = 0; j < nf0; ++j) {
      if (piv[j] == j) continue;
      for (int c = 0; c < added; ++c) std::swap(w_new[j + static_cast<std::size_t>(c) * n], w_new[piv[j] + c * n]);
    }
    a0.triangularView<Eigen::UnitLower>().solveInPlace(w_block);
    a0.triangularView<Eigen::Upper>().solveInPlace(w_block);
  }
  // S = D − C W: the new rows (every column) and the new columns of the old rows.
  const ConstMap w(w_.data(), nf0, k, Eigen::OuterStride<>(n));
  const ConstMap c(c_.data(), nf0, k, Eigen::OuterStride<>(n));
  Map s(s_.data(), k, k, Eigen::OuterStride<>(kMaxRankCap));
  s.middleRows(first, added).noalias() = -c.middleCols(first, added).transpose() * w;
  if (first > 0) s.topRightCorner(first, added).noalias() = -c.leftCols(first).transpose() * w.middleCols(first, added);
  // D = [M_NN 0; 0 0]: the pairs of added rows that involve a new slot.
  for (int i = first; i < k; ++i) {
    if (!slot_added_[i]) continue;
    const int ri = slot_row_[i];
    for (int j = 0; j < k; ++j) {
      if (!slot_added_[j]) continue;
      const int rj = slot_row_[j];
      S(i, j) += m[ri + static_cast<std::ptrdiff_t>(rj) * n];
      if (j < first) S(j, i) += m[rj + static_cast<std::ptrdiff_t>(ri) * n];
    }
  }
}

void UpdatedFreeBlock::RemoveSlot(int slot) {
  const int last = slots_ - 1;
  const int n = n_;
  row_slot_[slot_row_[slot]] = -1;
  if (slot != last) {
    std::copy_n(w_.data() + static_cast<std::size_t>(last) * n, nf0_, w_.data() + static_cast<std::size_t>(slot) * n);
    std::copy_n(c_.data() + static_cast<std::size_t>(last) * n, nf0_, c_.data() + static_cast<std::size_t>(slot) * n);
    slot_row_[slot] = slot_row_[last];
    slot_added_[slot] = slot_added_[last];
    row_slot_[slot_row_[slot]] = slot;
    for (int i = 0; i < last; ++i) {
      if (i == slot) continue;
      S(slot, i) = S(last, i);
      S(i, slot) = S(i, last);
    }
    S(slot, slot) = S(last, last);
  }
  slots_ = last;
}

bool UpdatedFreeBlock::TryUpdate(const double* m, int n, const double* q, const int* free_rows, int nf, double* z) {
  const int nf0 = nf0_;
  const int* base = base_rows_.data();
  char* in_f = in_f_.data();
  for (int k = 0; k < nf; ++k) in_f[free_rows[k]] = 1;
  int rank = 0;
  for (int k = 0; k < nf; ++k) rank += base_pos_[free_rows[k]] < 0;
  for (int p = 0; p < nf0; ++p) rank += !in_f[base[p]];
  const bool fits = rank <= MaxRank(nf0);
  if (fits) {
    // Rows that returned to their place in F0 leave the difference; rows that left it enter (W, S extended).
    for (int j = slots_ - 1; j >= 0; --j) {
      const int r = slot_row_[j];
      if ((in_f[r] != 0) == (base_pos_[r] >= 0)) RemoveSlot(j);
    }
    const int first = slots_;
    for (int k = 0; k < nf; ++k) {
      const int r = free_rows[k];
      if (base_pos_[r] < 0 && row_slot_[r] < 0) AddSlot(m, n, r);
    }
    for (int p = 0; p < nf0; ++p) {
      if (!in_f[base[p]] && row_slot_[base[p]] < 0) AddSlot(m, n, base[p]);
    }
    if (slots_ > first) FinishSlots(m, n, first);
  }
  for (int k = 0; k < nf; ++k) in_f[free_rows[k]] = 0;
  if (!fits) return false;

  // y = A0⁻¹ b_F0 (rows of R included: their equations are absorbed by λ).
  double* y = y_.data();
  active_set::ReducedRhs<0>(m, n, q, z, base, nf0, y);
  SolveBase(y);
  const int k = slots_;
  double* t = t_.data();
  if (k > 0) {
    // t = b_k − C y; S's LU with its pivots checked against its largest entry; t ← S⁻¹ t.
    using ConstMap = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
    const ConstMap c(c_.data(), nf0, k, Eigen::OuterStride<>(n));
    const ConstMap w(w_.data(), nf0, k, Eigen::OuterStride<>(n));
    Eigen::Map<Eigen::VectorXd> t_vector(t, k);
    Eigen::Map<Eigen::VectorXd> y_vector(y, nf0);
    t_vector.noalias() = -c.transpose() * y_vector;
    double amax = 0.0;
    for (int j = 0; j < k; ++j) {
      if (slot_added_[j]) {
        double b = 0.0;
        active_set::ReducedRhs<0>(m, n, q, z, &slot_row_[j], 1, &b);
        t[j] += b;
      }
      for (int i = 0; i < k; ++i) {
        const double v = S(i, j);
        s_lu_[i + static_cast<std::size_t>(j) * kMaxRankCap] = v;
        amax = std::max(amax, std::abs(v));
      }
    }
    if (!(amax < kInf) ||
        !dense_lu::Factor(s_lu_.data(), kMaxRankCap, k, s_pivots_.data(), kSchurPivotRatio * amax)) {
      return false;
    }
    dense_lu::Solve(s_lu_.data(), kMaxRankCap, k, s_pivots_.data(), t);
    y_vector.noalias() -= w * t_vector;  // x_F0 = y − W t
  }
  for (int p = 0; p < nf0; ++p) {
    if (!std::isfinite(y[p])) return false;
  }
  for (int j = 0; j < k; ++j) {
    if (!std::isfinite(t[j])) return false;
  }
  for (int p = 0; p < nf0; ++p) {
    const int r = base[p];
    if (row_slot_[r] < 0) z[r] = y[p];  // a row of F ∩ F0 (a removed row keeps its bound)
  }
  for (int j = 0; j < k; ++j) {
    if (slot_added_[j]) z[slot_row_[j]] = t[j];
  }
  return true;
}

}  // namespace smcbench
