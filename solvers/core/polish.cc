#include "solvers/core/polish.h"

#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseLU>

namespace smcbench {

bool PolishGeneric(const BoxMLCP& equilibrated, const Vector& z, Vector* out) {
  const int n = equilibrated.size();
  if (!equilibrated.is_sparse() && n > kMaxPolishDenseSize) return false;
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
      (*out)[i] = z[i];
    } else {
      (*out)[i] = s == RowState::kLower ? l[i] : u[i];
    }
  }
  const int nf = static_cast<int>(free_rows.size());
  if (nf == 0) return true;
  // Right-hand side −(q_F + M_FB z_B): M applied to the bound part of out only.
  Vector bound_part = *out;
  for (int i : free_rows) bound_part[i] = 0.0;
  Vector rhs_full;
  equilibrated.Affine(bound_part, &rhs_full);
  Vector rhs(nf);
  for (int k = 0; k < nf; ++k) rhs[k] = -rhs_full[free_rows[k]];
  Vector x;
  if (equilibrated.is_sparse()) {
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
    x = lu.solve(rhs);
    if (lu.info() != Eigen::Success) return false;
  } else {
    DenseMatrix block(nf, nf);
    const DenseMatrix& m = equilibrated.dense_matrix();
    for (int c = 0; c < nf; ++c) {
      for (int k = 0; k < nf; ++k) block(k, c) = m(free_rows[k], free_rows[c]);
    }
    Eigen::PartialPivLU<DenseMatrix> lu(block);
    x = lu.solve(rhs);
  }
  for (int k = 0; k < nf; ++k) {
    const int i = free_rows[k];
    if (!std::isfinite(x[k]) || x[k] < l[i] || x[k] > u[i]) return false;
    (*out)[i] = x[k];
  }
  return true;
}

}  // namespace smcbench
