#include "solvers/core/polish.h"

#include <vector>

namespace smcbench {

bool PolishSparse(const BoxMLCP& equilibrated, const Vector& z, Vector* out) {
  const int n = equilibrated.size();
  const Vector& l = equilibrated.l();
  const Vector& u = equilibrated.u();
  Vector w;
  equilibrated.Affine(z, &w);
  std::vector<signed char> state(n);
  for (int i = 0; i < n; ++i) state[i] = static_cast<signed char>(ClassifyRow(z[i], w[i], l[i], u[i]));
  std::vector<int> free_rows(n);
  out->resize(n);
  const int nf = active_set::PlaceBoundRows(n, state.data(), l.data(), u.data(), out->data(), free_rows.data());
  if (nf == 0) return true;
  // Right-hand side −(q_F + M_FB z_B): out is 0 on the free rows, so M·out + q is exactly that on them.
  Vector rhs_full;
  equilibrated.Affine(*out, &rhs_full);
  Vector rhs(nf);
  for (int k = 0; k < nf; ++k) rhs[k] = -rhs_full[free_rows[k]];
  Vector x;
  if (nf <= kMaxDenseSparsePolishBlock) {
    // A small free block is gathered densely and factored by the dense kernel (threshold 0, as PolishDense): a sparse
    // LU's ordering and symbolic analysis cost many times the O(nf³) of so few rows.
    std::vector<int> position(n, -1);
    for (int k = 0; k < nf; ++k) position[free_rows[k]] = k;
    DenseMatrix block = DenseMatrix::Zero(nf, nf);
    const SparseMatrix& m = equilibrated.sparse_matrix();
    for (int k = 0; k < nf; ++k) {
      for (SparseMatrix::InnerIterator it(m, free_rows[k]); it; ++it) {
        const int row = position[it.index()];
        if (row >= 0) block(row, k) = it.value();
      }
    }
    std::vector<int> pivots(nf);
    x = rhs;
    if (!active_set::SolveBlock(block.data(), nf, nf, x.data(), pivots.data(), 0.0)) return false;
  } else {
    SparseFreeBlock block;
    if (!block.Factor(equilibrated.sparse_matrix(), free_rows.data(), nf)) return false;
    if (!block.Solve(rhs, &x)) return false;
  }
  return active_set::ScatterFreeRows(x.data(), free_rows.data(), nf, l.data(), u.data(), out->data()) ==
         FreeRowsFit::kInside;
}

}  // namespace smcbench
