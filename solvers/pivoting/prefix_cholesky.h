// The free block of a pivoting method's active set on a small dense symmetric M, by a Cholesky factor that keeps
// its leading rows between sets: the Cholesky factor of a leading principal block is the leading part of the
// factor, so when the new set F keeps the first p rows of the last factor's order, rows 0..p of L are reused as
// they are and only F's other rows are appended (each a row of L: triangular dot products against the rows before
// it). This is the row-append half of the incremental LDLᵀ of Dantzig–Cottle / ODE's dLCP (Cottle, Pang & Stone,
// The Linear Complementarity Problem, 1992, §4.2; Smith's ODE lcp.cpp, which Bullet's btDantzigLCP is), without
// its row deletions: a row that leaves the set truncates the factor at its place and the rows after it are
// factored again. No update formula is involved, so the factor equals, bit for bit, a fresh Cholesky of M_FF in
// that order: a set's answer is as accurate as a fresh factorization's, and nothing can drift.
//
// M = R·S with S symmetric and R a positive diagonal (the row-equilibrated copy of a symmetric M the base hands a
// backend): the factor is L Lᵀ = S_FF in the order kept, and a solve scales the right-hand side by R⁻¹. A new
// row whose pivot r_j·L_jj² is ≤ small (the LU pivot M_FF would have without row swaps; not positive definite, or
// nearly singular) or not finite ends the factorization with kNotPositive: the caller then solves the set by LU,
// which judges a singular block. Nothing is allocated after Resize.
#pragma once

#include <vector>

namespace smcbench {

class PrefixCholesky {
 public:
  enum class Outcome { kSolved, kNotPositive, kNonFinite };

  // Storage for n rows; drops the factor.
  void Resize(int n);
  // The next Solve factors every row afresh (a new M).
  void Invalidate() {
    for (int j = 0; j < rows_; ++j) place_[order_[j]] = -1;
    rows_ = 0;
  }

  // z_F = M_FF⁻¹ b_F with b_F = −(q_F + M_FB z_B) for the dense n×n column-major m = R·S: z holds the bound rows at
  // their bound and 0 on the free rows (active_set::PlaceBoundRows), free_rows[0..nf) lists F increasing;
  // ratio[i] = r_i and inv_ratio[i] = 1 / r_i. z_F is written into z on kSolved. On kNotPositive the factor is
  // dropped.
  Outcome Solve(const double* m, int n, const double* q, const double* ratio, const double* inv_ratio,
                const int* free_rows, int nf, double small, double* z);

  int reused_rows() const { return reused_; }      // rows of L kept from earlier sets, since ResetCounts
  int factored_rows() const { return factored_; }  // rows of L computed, since ResetCounts
  void ResetCounts() { reused_ = factored_ = 0; }

 private:
  int n_ = 0;
  int rows_ = 0;                // rows of the factor (the last set's free rows, in order_)
  std::vector<int> order_;      // the factor's rows: order_[j] is the row of M at place j
  std::vector<int> place_;      // place_[i]: row i's place in order_, −1 outside
  std::vector<double> l_;       // L row-wise: L_jc at l_[j·n + c], c < j
  std::vector<double> inv_diagonal_;  // 1 / L_jj
  std::vector<double> by_row_, y_;    // the right-hand side by row of M, then by place
  std::vector<char> in_f_;            // scratch: row i is in F (cleared after use)
  int reused_ = 0, factored_ = 0;
};

}  // namespace smcbench
