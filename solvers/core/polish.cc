#include "solvers/core/polish.h"

#include <Eigen/SparseLU>

namespace smcbench {

bool PolishSparse(const BoxMLCP& equilibrated, const Vector& z, Vector* out) {
  const int n = equilibrated.size();
  const Vector& l = equilibrated.l();
  const Vector& u = equilibrated.u();
  Vector w;
  equilibrated.Affine(z, &w);
  // free_index[i]: position of row i in the reduced system, −1 for a bound row.
  std::vector<int> free_index(n, -1);
  std::vector<int> free_rows;
  out->resize(n);
  for (int i = 0; i < n; ++i) {
    const RowState s = ClassifyRow(z[i], w[i], l[i], u[i]);
    if (s == RowState::kFree) {
      free_index[i] = static_cast<int>(free_rows.size());
      free_rows.push_back(i);
      (*out)[i] = 0.0;
    } else {
      (*out)[i] = s == RowState::kLower ? l[i] : u[i];
    }
  }
  const int nf = static_cast<int>(free_rows.size());
  if (nf == 0) return true;
  // Right-hand side −(q_F + M_FB z_B): out is 0 on the free rows, so M·out + q is exactly that on them.
  Vector rhs_full;
  equilibrated.Affine(*out, &rhs_full);
  Vector rhs(nf);
  for (int k = 0; k < nf; ++k) rhs[k] = -rhs_full[free_rows[k]];
  std::vector<Eigen::Triplet<double, int>> entries;
  const SparseMatrix& m = equilibrated.sparse_matrix();
  for (int col = 0; col < m.outerSize(); ++col) {
    if (free_index[col] < 0) continue;
    for (SparseMatrix::InnerIterator it(m, col); it; ++it) {
      if (free_index[it.row()] >= 0) entries.emplace_back(free_index[it.row()], free_index[col], it.value());
    }
  }
  SparseMatrix block(nf, nf);
  block.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(block);
  if (lu.info() != Eigen::Success) return false;
  const Vector x = lu.solve(rhs);
  if (lu.info() != Eigen::Success) return false;
  for (int k = 0; k < nf; ++k) {
    const int i = free_rows[k];
    if (!std::isfinite(x[k]) || x[k] < l[i] || x[k] > u[i]) return false;
    (*out)[i] = x[k];
  }
  return true;
}

}  // namespace smcbench
