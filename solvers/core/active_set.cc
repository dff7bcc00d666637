#include "solvers/core/active_set.h"

#include <limits>
#include <string>

#include <Eigen/SparseLU>
#include <Eigen/SparseQR>

#include "solvers/core/problem.h"

namespace smcbench {

void ActiveSetFactors::Resize(int n) {
  n_ = n;
  nf_ = 0;
  valid_ = false;
  state_.assign(n, 0);
  free_rows_.assign(n, 0);
  pivots_.assign(n, 0);
  lu_.assign(static_cast<std::size_t>(n) * n, 0.0);
  rhs_.assign(n, 0.0);
}

bool ActiveSetFactors::Factor(const DenseMatrix& M, const signed char* state) {
  valid_ = false;
  if (M.rows() != n_ || M.cols() != n_) {
    throw InvalidInputError("M is " + std::to_string(M.rows()) + "x" + std::to_string(M.cols()) +
                            " but the active set was sized for " + std::to_string(n_) + " rows (Resize)");
  }
  const int n = n_;
  nf_ = 0;
  for (int i = 0; i < n; ++i) {
    state_[i] = state[i];
    if (static_cast<RowState>(state[i]) == RowState::kFree) free_rows_[nf_++] = i;
  }
  const int nf = nf_;
  double* a = lu_.data();
  active_set::GatherFreeBlock(M.data(), n, free_rows_.data(), nf, a, n);
  if (!dense_lu::Factor(a, n, nf, pivots_.data(), 0.0)) return false;  // a zero (or NaN) pivot
  double largest = 0.0, smallest = kInf;
  for (int k = 0; k < nf; ++k) {
    const double pivot = std::abs(a[k + k * n]);
    if (!std::isfinite(pivot)) return false;
    largest = std::max(largest, pivot);
    smallest = std::min(smallest, pivot);
  }
  valid_ = nf == 0 || smallest >= kMinPivotRatio * largest;
  return valid_;
}

template <int N>
bool ActiveSetFactors::Solve(const DenseMatrix& M, const double* q, const double* l, const double* u,
                             double* z) const {
  const int n = N > 0 ? N : n_;
  const int nf = nf_;
  const int* free_rows = free_rows_.data();
  for (int i = 0; i < n; ++i) z[i] = PlacedValue(static_cast<RowState>(state_[i]), l[i], u[i]);
  if (nf == 0) return true;
  double* b = rhs_.data();
  active_set::ReducedRhs<N>(M.data(), n, q, z, free_rows, nf, b);
  dense_lu::Solve(lu_.data(), n, nf, pivots_.data(), b);
  return active_set::ScatterFreeRows(b, free_rows, nf, l, u, z) == FreeRowsFit::kInside;
}

template bool ActiveSetFactors::Solve<0>(const DenseMatrix&, const double*, const double*, const double*,
                                         double*) const;

void ActiveSetFactors::AffineMap(const DenseMatrix& M, const double* l, const double* u, double* A, double* c,
                                 int* free_row) const {
  const int n = n_, nf = nf_;
  *free_row = nf == 1 ? free_rows_[0] : -1;
  std::fill(A, A + n * n, 0.0);
  for (int i = 0; i < n; ++i) c[i] = PlacedValue(static_cast<RowState>(state_[i]), l[i], u[i]);
  // Column j of A restricted to F is −M_FF⁻¹ e_j (j ∈ F); c_F = −M_FF⁻¹ M_FB c_B. One LU solve per column.
  double* b = rhs_.data();
  for (int col = 0; col <= nf; ++col) {  // col < nf: e_{F[col]}; col = nf: the bound part
    for (int k = 0; k < nf; ++k) {
      if (col < nf) {
        b[k] = k == col ? -1.0 : 0.0;
      } else {
        double sum = 0.0;
        for (int j = 0; j < n; ++j) sum += M(free_rows_[k], j) * c[j];
        b[k] = -sum;
      }
    }
    dense_lu::Solve(lu_.data(), n, nf, pivots_.data(), b);
    for (int k = 0; k < nf; ++k) {
      const int i = free_rows_[k];
      if (col < nf) {
        A[i + free_rows_[col] * n] = b[k];
      } else {
        c[i] = b[k];
      }
    }
  }
}

struct SparseFreeBlock::Impl {
  std::vector<int> position;  // position[i]: row i's place in the block, −1 for a bound row
  std::vector<Eigen::Triplet<double, int>> entries;
  SparseMatrix block;
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
};

// Default-initialized (new Impl, not make_unique's value-initialization): zero-filling the SparseLU object first
// would cost a memset of its whole size on every polish.
SparseFreeBlock::SparseFreeBlock() : impl_(new Impl) {}
SparseFreeBlock::~SparseFreeBlock() = default;
SparseFreeBlock::SparseFreeBlock(SparseFreeBlock&&) noexcept = default;
SparseFreeBlock& SparseFreeBlock::operator=(SparseFreeBlock&&) noexcept = default;

bool SparseFreeBlock::Factor(const SparseMatrix& M, const int* free_rows, int nf) {
  Impl& s = *impl_;
  const int n = static_cast<int>(M.rows());
  if (M.cols() != n) {
    throw InvalidInputError("M must be square, got " + std::to_string(n) + "x" + std::to_string(M.cols()));
  }
  s.position.assign(n, -1);
  for (int k = 0; k < nf; ++k) {
    const int i = free_rows[k];
    if (i < 0 || i >= n || (k > 0 && i <= free_rows[k - 1])) {
      throw InvalidInputError("free_rows[" + std::to_string(k) + "] = " + std::to_string(i) +
                              ": the free rows must be increasing row indices of M (0.." + std::to_string(n - 1) + ")");
    }
    s.position[i] = k;
  }
  s.entries.clear();
  for (int c = 0; c < nf; ++c) {
    for (SparseMatrix::InnerIterator it(M, free_rows[c]); it; ++it) {
      const int r = s.position[it.row()];
      if (r >= 0) s.entries.emplace_back(r, c, it.value());
    }
  }
  s.block.resize(nf, nf);
  s.block.setFromTriplets(s.entries.begin(), s.entries.end());  // compressed
  s.lu.compute(s.block);
  return s.lu.info() == Eigen::Success;
}

bool SparseFreeBlock::Solve(const Vector& b, Vector* x) {
  *x = impl_->lu.solve(b);
  return impl_->lu.info() == Eigen::Success;
}

const SparseMatrix& SparseFreeBlock::block() const { return impl_->block; }


struct RobustFreeBlock::Impl {
  DenseMatrix block;
  Eigen::PartialPivLU<DenseMatrix> lu;
  Eigen::CompleteOrthogonalDecomposition<DenseMatrix> cod;
  bool use_cod = false;
  SparseFreeBlock sparse;
  Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>> sparse_qr;
  bool sparse_problem = false;
  bool use_sparse_qr = false;
};

RobustFreeBlock::RobustFreeBlock() : impl_(new Impl) {}
RobustFreeBlock::~RobustFreeBlock() = default;
RobustFreeBlock::RobustFreeBlock(RobustFreeBlock&&) noexcept = default;
RobustFreeBlock& RobustFreeBlock::operator=(RobustFreeBlock&&) noexcept = default;

bool RobustFreeBlock::Factor(const BoxMLCP& problem, const int* free_rows, int nf) {
  Impl& s = *impl_;
  s.sparse_problem = problem.is_sparse();
  if (!s.sparse_problem) {
    const DenseMatrix& M = problem.dense_matrix();
    if (s.block.rows() != nf) s.block.resize(nf, nf);
    active_set::GatherFreeBlock(M.data(), static_cast<int>(M.rows()), free_rows, nf, s.block.data(), nf);
    s.lu.compute(s.block);
    s.use_cod = !(s.lu.rcond() > 1e3 * std::numeric_limits<double>::epsilon());
    if (s.use_cod) s.cod.compute(s.block);
    return true;
  }
  s.use_sparse_qr = !s.sparse.Factor(problem.sparse_matrix(), free_rows, nf);
  if (!s.use_sparse_qr) return true;
  s.sparse_qr.compute(s.sparse.block());
  return s.sparse_qr.info() == Eigen::Success;
}

void RobustFreeBlock::Solve(const Vector& b, Vector* x) {
  Impl& s = *impl_;
  if (s.sparse_problem) {
    if (s.use_sparse_qr) {
      *x = s.sparse_qr.solve(b);
    } else {
      s.sparse.Solve(b, x);
    }
  } else if (s.use_cod) {
    x->noalias() = s.cod.solve(b);
  } else {
    x->noalias() = s.lu.solve(b);
  }
}

}  // namespace smcbench
