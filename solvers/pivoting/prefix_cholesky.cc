// PrefixCholesky (prefix_cholesky.h): the Cholesky of a symmetric free block, reusing the leading rows of the last.
#include "solvers/pivoting/prefix_cholesky.h"

#include <cmath>
#include <cstddef>


namespace smcbench {

void PrefixCholesky::Resize(int n) {
  if (n_ == n) {
    Invalidate();
    return;
  }
  rows_ = 0;
  n_ = n;
  const std::size_t size = static_cast<std::size_t>(n);
  order_.assign(size, 0);
  place_.assign(size, -1);
  l_.assign(size * size, 0.0);
  inv_diagonal_.assign(size, 0.0);
  in_f_.assign(size, 0);
  by_row_.assign(size, 0.0);
  y_.assign(size, 0.0);
}

PrefixCholesky::Outcome PrefixCholesky::Solve(const double* m, int n, const double* q, const double* ratio,
                                              const double* inv_ratio, const int* free_rows, int nf, double small,
                                              double* z) {
  // The right-hand side first, by row of M: −q_F, less the columns of the bound rows whose value is not 0 (a relay
  // near its solution has few: the free rows' columns, which ReducedRhs sums with z_j = 0, are skipped).
  double* by_row = by_row_.data();
  for (int k = 0; k < nf; ++k) by_row[free_rows[k]] = -q[free_rows[k]];
  for (int j = 0; j < n; ++j) {
    const double zj = z[j];
    if (zj == 0.0) continue;
    const double* column = m + static_cast<std::ptrdiff_t>(j) * n;
    for (int k = 0; k < nf; ++k) by_row[free_rows[k]] -= column[free_rows[k]] * zj;
  }

  // The kept prefix: the leading places whose rows are all still free; the places after it are dropped.
  int* place = place_.data();
  int* order = order_.data();
  for (int k = 0; k < nf; ++k) in_f_[free_rows[k]] = 1;
  int keep = 0;
  while (keep < rows_ && in_f_[order[keep]]) ++keep;
  for (int k = 0; k < nf; ++k) in_f_[free_rows[k]] = 0;
  for (int j = keep; j < rows_; ++j) place[order[j]] = -1;
  int rows = keep;
  for (int k = 0; k < nf; ++k) {
    const int i = free_rows[k];
    if (place[i] < 0) {
      place[i] = rows;
      order[rows++] = i;
    }
  }
  rows_ = rows;  // = nf
  reused_ += keep;
  factored_ += rows - keep;

  // The new rows of L: L_jc = (S_ic − Σ_{k<c} L_jk L_ck) / L_cc for the row i at place j and c < j, then
  // L_jj² = S_ii − Σ_{k<j} L_jk², with S_ic = S_ci = M_ci / r_c read down column i of M.
  double* l = l_.data();
  const std::ptrdiff_t ld = n;
  for (int j = keep; j < rows; ++j) {
    const int i = order[j];
    const double* column = m + static_cast<std::ptrdiff_t>(i) * ld;
    double* lj = l + j * ld;
    double diagonal = column[i] * inv_ratio[i];
    for (int c = 0; c < j; ++c) {
      const int row_c = order[c];
      const double* lc = l + c * ld;
      double sum = column[row_c] * inv_ratio[row_c];
      for (int k = 0; k < c; ++k) sum -= lj[k] * lc[k];
      const double v = sum * inv_diagonal_[c];
      lj[c] = v;
      diagonal -= v * v;
    }
    if (!(ratio[i] * diagonal > small) || !(diagonal < HUGE_VAL)) {
      Invalidate();
      return Outcome::kNotPositive;
    }
    inv_diagonal_[j] = 1.0 / std::sqrt(diagonal);
  }

  // L Lᵀ x = R⁻¹ b in the factor's order: forward by rows of L, backward by the same rows (column updates of Lᵀ).
  double* y = y_.data();
  for (int j = 0; j < rows; ++j) {
    const int i = order[j];
    const double* lj = l + j * ld;
    double sum = by_row_[i] * inv_ratio[i];
    for (int k = 0; k < j; ++k) sum -= lj[k] * y[k];
    y[j] = sum * inv_diagonal_[j];
  }
  for (int j = rows - 1; j >= 0; --j) {
    const double x = y[j] * inv_diagonal_[j];
    y[j] = x;
    const double* lj = l + j * ld;
    for (int k = 0; k < j; ++k) y[k] -= lj[k] * x;
  }
  for (int j = 0; j < rows; ++j) {
    const double v = y[j];
    if (!std::isfinite(v)) return Outcome::kNonFinite;
    z[order[j]] = v;
  }
  return Outcome::kSolved;
}

}  // namespace smcbench
