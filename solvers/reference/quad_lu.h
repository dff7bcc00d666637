// Complete-pivoting (rank-revealing) LU of a small dense block in quad precision: the one elimination kernel of the
// box-MLCP and the MCP certifiers (certify.cc, mcp_certify.cc), which each had a copy.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "solvers/core/extended_precision_mcp.h"

namespace smcbench {

// P B Q = L U of a k×k row-major block. Elimination stops at the first pivot ≤ tolerance (or not finite): rank
// counts the pivots taken, and the rest of the block is treated as zero.
struct QuadLu {
  int k = 0;
  int rank = 0;
  int swaps = 0;              // row plus column interchanges (the determinant's sign)
  std::vector<Quad> lu;       // row-major: L below the diagonal (unit diagonal implied), U on and above
  std::vector<int> row, col;  // position s holds the block's row row[s] and column col[s]

  Quad& At(int i, int j) { return lu[static_cast<std::size_t>(i) * k + j]; }
  Quad At(int i, int j) const { return lu[static_cast<std::size_t>(i) * k + j]; }
  bool singular() const { return rank < k; }

  void Factor(int size, std::vector<Quad> block, Quad tolerance) {
    k = size, rank = 0, swaps = 0;
    lu = std::move(block);
    row.resize(k), col.resize(k);
    for (int s = 0; s < k; ++s) row[s] = col[s] = s;
    for (int s = 0; s < k; ++s) {
      int pr = s, pc = s;
      Quad best = 0;
      for (int i = s; i < k; ++i) {
        for (int j = s; j < k; ++j) {
          if (Abs(At(i, j)) > best) best = Abs(At(i, j)), pr = i, pc = j;
        }
      }
      if (!(best > tolerance) || !(best - best == 0)) return;  // too small, or not finite
      if (pr != s) {
        for (int j = 0; j < k; ++j) std::swap(At(s, j), At(pr, j));
        std::swap(row[s], row[pr]);
        ++swaps;
      }
      if (pc != s) {
        for (int i = 0; i < k; ++i) std::swap(At(i, s), At(i, pc));
        std::swap(col[s], col[pc]);
        ++swaps;
      }
      const Quad pivot = At(s, s);
      for (int i = s + 1; i < k; ++i) {
        const Quad m = At(i, s) / pivot;
        At(i, s) = m;
        if (m == 0) continue;
        for (int j = s + 1; j < k; ++j) At(i, j) -= m * At(s, j);
      }
      rank = s + 1;
    }
  }

  // x (block order) with the pivot equations met and the rank-deficient variables set to fixed[] (block order;
  // may be null when the block is nonsingular).
  void Solve(const std::vector<Quad>& rhs, const Quad* fixed, std::vector<Quad>* x) const {
    std::vector<Quad> y(rank);
    for (int s = 0; s < rank; ++s) {
      Quad v = rhs[row[s]];
      for (int t = 0; t < s; ++t) v -= At(s, t) * y[t];
      for (int t = rank; t < k; ++t) v -= At(s, t) * fixed[col[t]];
      y[s] = v;
    }
    x->resize(k);
    for (int t = rank; t < k; ++t) (*x)[col[t]] = fixed[col[t]];
    for (int s = rank - 1; s >= 0; --s) {
      Quad v = y[s];
      for (int t = s + 1; t < rank; ++t) v -= At(s, t) * y[t];
      y[s] = v / At(s, s);
      (*x)[col[s]] = y[s];
    }
  }

  // ‖(L U)⁻¹‖∞ over the leading rank×rank block: ‖B⁻¹‖∞ when B is nonsingular (permutations keep the norm).
  Quad InverseNorm() const {
    std::vector<Quad> row_sum(rank, Quad(0)), x(rank);
    for (int c = 0; c < rank; ++c) {
      for (int s = 0; s < rank; ++s) {  // L x = e_c
        Quad v = s == c ? 1 : 0;
        for (int t = c; t < s; ++t) v -= At(s, t) * x[t];
        x[s] = s < c ? 0 : v;
      }
      for (int s = rank - 1; s >= 0; --s) {  // U x = x
        Quad v = x[s];
        for (int t = s + 1; t < rank; ++t) v -= At(s, t) * x[t];
        x[s] = v / At(s, s);
        row_sum[s] += Abs(x[s]);
      }
    }
    Quad norm = 0;
    for (Quad r : row_sum) norm = std::max(norm, r);
    return norm;
  }

  // det B > 0 (nonsingular, and the pivots' signs times the interchanges' parity positive).
  bool PositiveDeterminant() const {
    if (singular()) return false;
    bool negative = swaps % 2 != 0;
    for (int s = 0; s < k; ++s) negative = negative != (At(s, s) < 0);
    return !negative;
  }

 private:
  static Quad Abs(Quad x) { return x < 0 ? -x : x; }
};

}  // namespace smcbench
