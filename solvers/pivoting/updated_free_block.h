// The free block of a pivoting method's active set, solved by updating one factorization instead of refactoring
// each set: the LU (partial pivoting) of a reference block A0 = M_F0F0 is kept, and a set F that differs from F0 by
// the added rows N = F \ F0 and the removed rows R = F0 \ F is solved through the bordered system
//     [ A0      M_F0N   E_R ] [x_F0]   [b_F0]
//     [ M_NF0   M_NN    0   ] [x_N ] = [b_N ]        (E_R: the columns of I for R; x_R = 0, λ absorbs rows R)
//     [ E_Rᵀ    0       0   ] [ λ  ]   [ 0  ]
// by its Schur complement S = D − C A0⁻¹ B (k×k, k = |N| + |R|), as in the Schur-complement active-set updates of
// Gill, Murray, Saunders & Wright (Sparse matrix methods in optimization, SIAM J. Sci. Stat. Comput. 5, 1984) and
// Bartlett & Biegler's qpSchur (Optim. Eng. 7, 2006). The bordered matrix is nonsingular exactly when M_FF is, and
// its solution restricted to F is M_FF⁻¹ b_F. Each row entering the difference costs one solve with A0's factors
// (its column of W = A0⁻¹ B, kept while F0 stays; the rows that enter together are solved together, a level-3
// triangular solve) and a row and column of S; each set then costs one solve with A0,
// an LU of S and O(k·|F0|). A row that leaves the difference drops its column.
//
// Safeguards: the update is used only for blocks of at least kMinRows rows, while k ≤ max_rank(|F0|), and while S's
// LU has no pivot below kSchurPivotRatio of its largest entry and every value is finite; otherwise F is factored
// from scratch and becomes the new reference (so a singular M_FF is always judged by a fresh LU, as without
// updates). Nothing is allocated after Resize.
//
// Symmetric M (set_symmetric_scale): when the caller knows M = R·S with S symmetric and R a positive diagonal (the
// row-equilibrated copy of a symmetric M), the reference block is factored by Cholesky instead: A0 = R_F0 L Lᵀ with
// L L ᵀ = (R⁻¹ M)_F0F0, half the flops of the LU; a solve with A0 scales by R⁻¹ and runs the two triangular
// solves. A block whose Cholesky meets a pivot r_j·L_jj² ≤ small (the LU pivot M_FF would have without row swaps;
// not positive definite, or nearly singular) is factored by the LU instead, and the LU is used for every later block
// until the next set_symmetric_scale: so an indefinite M costs at most one failed Cholesky per solve, and a
// singular block is still judged by a fresh LU. The Schur complement S stays an LU (it is k×k, and indefinite when
// rows leave the set).
#pragma once

#include <algorithm>
#include <vector>

#include "solvers/core/types.h"

namespace smcbench {

class UpdatedFreeBlock {
 public:
  // Blocks below this many rows are refactored every time (an LU of 16 rows costs less than the bookkeeping).
  static constexpr int kMinRows = 16;
  // Most rows that may differ from the reference set (the columns of W kept).
  static constexpr int kMaxRankCap = 128;
  // A pivot of S's LU below this fraction of max |S_ij| sends the set to a fresh factorization.
  static constexpr double kSchurPivotRatio = 1e-10;

  // Storage for n rows; drops the reference factorization.
  void Resize(int n);
  // The next Solve factors from scratch (a new M, or a caller's doubt about the last update).
  void Invalidate() { has_base_ = false; }
  // Use updates (true) or factor every set from scratch (false, the method without updates).
  void set_updates(bool on) { updates_ = on; }
  // M = R·S with S symmetric (see above): ratio[i] = r_i > 0 and inv_ratio[i] = 1 / r_i for every row, kept by the
  // caller while it solves with this M; nullptrs: M is not known to be symmetric, every block is factored by LU.
  // Also re-arms the Cholesky after a failure.
  void set_symmetric_scale(const double* ratio, const double* inv_ratio) {
    ratio_ = ratio;
    inv_ratio_ = inv_ratio;
    cholesky_failed_ = false;
  }

  // How the last Solve found z_F.
  enum class Path { kFactored, kUpdated };
  // Solves the set of the dense n×n column-major m: z_F = M_FF⁻¹ b_F with b_F = −(q_F + M_FB z_B), where z holds the
  // bound rows at their bound and 0 on the free rows listed (increasing) in free_rows[0..nf). z_F is written into z.
  // False when the fresh factorization of M_FF has a pivot ≤ small (or NaN) or z_F is not finite.
  bool Solve(const double* m, int n, const double* q, const int* free_rows, int nf, double small, double* z);

  Path last_path() const { return last_path_; }
  int factorizations() const { return factorizations_; }  // fresh LUs since the last ResetCounts
  int updates() const { return updates_done_; }           // sets solved through the Schur complement
  int cholesky_factorizations() const { return cholesky_; }  // of factorizations(), those by Cholesky
  bool reference_is_cholesky() const { return has_base_ && base_cholesky_; }  // the current reference's factors
  void ResetCounts() { factorizations_ = updates_done_ = cholesky_ = 0; }

  // Most rows that may differ from a reference of nf0 rows before F is refactored: the update's cost grows with k
  // (k solves with A0 when the rows enter, an LU of S per set), a refactor costs (2/3)·nf³.
  static int MaxRank(int nf0) { return std::min(kMaxRankCap, std::max(4, nf0 / 4)); }

 private:
  bool Factor(const double* m, int n, const double* q, const int* free_rows, int nf, double small, double* z);
  bool TryUpdate(const double* m, int n, const double* q, const int* free_rows, int nf, double* z);
  // Enters a row into the difference: its columns of B (in w_) and C (in c_, a removed row's as e_pos).
  void AddSlot(const double* m, int n, int row);
  // For the slots from `first` on: W's columns solved with A0's factors (several right-hand sides at once) and
  // their rows and columns of S.
  void FinishSlots(const double* m, int n, int first);
  void RemoveSlot(int slot);
  // The reference block's Cholesky (true) of (R⁻¹ M)_FF, gathered into lu_ (lower triangle); false when a pivot is
  // ≤ small (r_j·L_jj², in units of M) or not finite.
  bool FactorCholesky(const double* m, int n, const int* free_rows, int nf, double small);
  // b ← A0⁻¹ b for one right-hand side of nf0 entries (the LU's or the Cholesky's factors).
  void SolveBase(double* b) const;
  double& S(int i, int j) { return s_[i + static_cast<std::size_t>(j) * kMaxRankCap]; }

  int n_ = 0;
  bool updates_ = true;
  bool has_base_ = false;
  Path last_path_ = Path::kFactored;
  int factorizations_ = 0, updates_done_ = 0, cholesky_ = 0;
  const double* ratio_ = nullptr;      // set_symmetric_scale's r (nullptr: LU only)
  const double* inv_ratio_ = nullptr;  // and 1 / r
  bool cholesky_failed_ = false;       // a Cholesky failed since set_symmetric_scale: LU only
  bool base_cholesky_ = false;         // the reference's factors in lu_ are a Cholesky (else an LU)
  // The reference set F0 and its LU (column-major, leading dimension n; dense_lu's row swaps in pivots_), or its
  // Cholesky factor L (lower triangle of lu_).
  int nf0_ = 0;
  std::vector<int> base_rows_, base_pos_, pivots_;  // base_pos_[i]: row i's place in F0, −1 outside
  std::vector<double> lu_;
  // The rows of F Δ F0 (slots): their row, whether added (in F, not F0), W's column (nf0 long, leading dimension n)
  // and, for an added row, its row of M on F0 (C's row, same layout); S (kMaxRankCap × kMaxRankCap).
  int slots_ = 0;
  std::vector<int> slot_row_, row_slot_;
  std::vector<char> slot_added_;
  std::vector<double> w_, c_, s_, s_lu_;
  std::vector<int> s_pivots_;
  std::vector<double> y_, t_;  // A0⁻¹ b_F0 (n), S's right-hand side (kMaxRankCap)
  std::vector<char> in_f_;     // scratch: row i is in F (cleared after each update)
};

}  // namespace smcbench
