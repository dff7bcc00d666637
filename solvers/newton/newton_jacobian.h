// The Jacobian storage and the linear-algebra plumbing the two semismooth Newtons share (`newton` and `newton-min`):
// dense or sparse algebra for a solve, J = ∇F at the iterate in its native storage with a dense or sparse copy when
// the algebra wants the other, products with J and Jᵀ, and the sparse system's pattern J ∪ diag for UMFPACK (whose
// symbolic analysis is kept while the pattern stays). Each solver's Workspace derives from JacobianStore; the systems
// it factorizes, and how J is evaluated for an MCP, stay in the solver.
#pragma once

#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <vector>

#include "solvers/core/problem.h"
#include "solvers/newton/semismooth_newton_solver.h"

namespace smcbench {
namespace newton {

struct JacobianStore {
  bool native_sparse = false;        // J arrives sparse (sparse M or a sparse MCP Jacobian)
  bool dense_la = true;              // dense (reduced) LU, else UMFPACK on the full system
  const DenseMatrix* Jd = nullptr;   // J at z, dense (native dense, or a copy when dense_la)
  const SparseMatrix* Js = nullptr;  // J at z, sparse (native sparse, or a copy when !dense_la)
  DenseMatrix J_dense;               // MCP dense Jacobian, or dense copy of sparse data
  SparseMatrix J_sparse;             // MCP sparse Jacobian, or sparse copy of dense data
  // ---- Sparse linear algebra ----
  SparseMatrix H;                                 // pattern J ∪ diag
  std::vector<int> pattern_outer, pattern_inner;  // the J pattern H was built for
  bool pattern_ready = false;
  bool umf_analyzed = false;
  Eigen::UmfPackLU<SparseMatrix> umf;

  // After a change of size: no dense copy, no pattern.
  void ResetStorage() {
    J_dense.resize(0, 0);
    pattern_ready = false;
    umf_analyzed = false;
  }

  // The algebra of a solve of size n: auto = dense for dense data and for sparse data up to dense_max_size unknowns.
  void ChooseAlgebra(NewtonOptions::LinearSolver choice, int dense_max_size, int n, bool sparse_data) {
    native_sparse = sparse_data;
    switch (choice) {
      case NewtonOptions::kDenseLinearSolver:
        dense_la = true;
        break;
      case NewtonOptions::kSparseLinearSolver:
        dense_la = false;
        break;
      default:
        dense_la = !sparse_data || n <= dense_max_size;
        break;
    }
    Jd = nullptr;
    Js = nullptr;
  }

  // A box-MLCP's J = M, fixed for the solve, with the copy the algebra needs.
  void BindBoxMatrix(const BoxMLCP& problem) {
    if (problem.is_sparse()) {
      Js = &problem.sparse_matrix();
      if (dense_la) {
        CopySparseToDense(problem.sparse_matrix());
        Jd = &J_dense;
      }
    } else {
      Jd = &problem.dense_matrix();
      if (!dense_la) {
        J_sparse = problem.dense_matrix().sparseView();  // forced sparse LA on dense data
        Js = &J_sparse;
      }
    }
  }

  void CopySparseToDense(const SparseMatrix& S) {
    const Eigen::Index n = S.rows();
    if (J_dense.rows() != n || J_dense.cols() != n) J_dense.resize(n, n);
    J_dense.setZero();
    for (int k = 0; k < S.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(S, k); it; ++it) J_dense(it.row(), it.col()) += it.value();
    }
  }

  // out = J x and out = Jᵀx in the native storage.
  void ApplyJ(const Vector& x, Vector* out) const {
    if (native_sparse) {
      out->noalias() = (*Js) * x;
    } else {
      out->noalias() = (*Jd) * x;
    }
  }
  void ApplyJt(const Vector& x, Vector* out) const {
    if (native_sparse) {
      out->noalias() = Js->transpose() * x;
    } else {
      out->noalias() = Jd->transpose() * x;
    }
  }

  // H ← the pattern J ∪ diag (values unspecified) when J's pattern is not the one H was built for; true then (the
  // caller rebuilds what it derives from H's pattern). Allocates only then.
  bool EnsureSparsePattern(const SparseMatrix& J) {
    const int n = static_cast<int>(J.cols());
    const int nnz = static_cast<int>(J.nonZeros());
    if (pattern_ready && static_cast<int>(pattern_inner.size()) == nnz &&
        std::equal(pattern_outer.begin(), pattern_outer.end(), J.outerIndexPtr()) &&
        std::equal(pattern_inner.begin(), pattern_inner.end(), J.innerIndexPtr())) {
      return false;
    }
    pattern_outer.assign(J.outerIndexPtr(), J.outerIndexPtr() + n + 1);
    pattern_inner.assign(J.innerIndexPtr(), J.innerIndexPtr() + nnz);
    std::vector<Eigen::Triplet<double, int>> triplets;
    triplets.reserve(nnz + n);
    for (int j = 0; j < n; ++j) {
      for (int k = J.outerIndexPtr()[j]; k < J.outerIndexPtr()[j + 1]; ++k) {
        triplets.emplace_back(J.innerIndexPtr()[k], j, 0.0);
      }
      triplets.emplace_back(j, j, 0.0);
    }
    H.resize(n, n);
    H.setFromTriplets(triplets.begin(), triplets.end());
    H.makeCompressed();
    pattern_ready = true;
    umf_analyzed = false;
    return true;
  }
};

}  // namespace newton
}  // namespace smcbench
