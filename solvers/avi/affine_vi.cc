#include "solvers/avi/affine_vi.h"

#include <cmath>
#include <sstream>
#include <utility>

namespace smcbench {
namespace {

[[noreturn]] void Fail(const std::string& message) { throw InvalidInputError("AffineVI: " + message); }

std::string Shape(const DenseMatrix& A) { return std::to_string(A.rows()) + "x" + std::to_string(A.cols()); }

void CheckMatrixFinite(const char* field, const DenseMatrix& A) {
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      if (std::isfinite(A(i, j))) continue;
      std::ostringstream s;
      s << field << "(" << i << "," << j << ") is " << (std::isnan(A(i, j)) ? "NaN" : "infinite");
      Fail(s.str());
    }
  }
}

// A constraint block (H, K) or (E, f): an empty matrix with an empty right-hand side is "no rows" (stored 0×n).
void CheckBlock(const char* matrix_field, const char* rhs_field, Eigen::Index n, DenseMatrix* A, const Vector& b) {
  if (A->rows() == 0 && b.size() == 0) {
    A->resize(0, n);
    return;
  }
  if (A->cols() != n) {
    Fail(std::string(matrix_field) + " is " + Shape(*A) + " but must have n = " + std::to_string(n) +
         " columns (the size of M)");
  }
  if (b.size() != A->rows()) {
    Fail(std::string(rhs_field) + " has size " + std::to_string(b.size()) + " but " + matrix_field + " has " +
         std::to_string(A->rows()) + " rows");
  }
  CheckMatrixFinite(matrix_field, *A);
  ValidateFinite("AffineVI", rhs_field, b);
  for (Eigen::Index i = 0; i < A->rows(); ++i) {
    if (A->row(i).cwiseAbs().maxCoeff() == 0.0) {
      Fail(std::string(matrix_field) + " row " + std::to_string(i) +
           " is zero (it constrains no unknown: drop it, or it makes P empty)");
    }
  }
}

}  // namespace

AffineVI::AffineVI(DenseMatrix M, Vector q, DenseMatrix H, Vector K, DenseMatrix E, Vector f, std::string name)
    : M_(std::move(M)), q_(std::move(q)), H_(std::move(H)), K_(std::move(K)), E_(std::move(E)), f_(std::move(f)),
      name_(std::move(name)) {
  Validate();
}

AffineVI::AffineVI(DenseMatrix M, Vector q, DenseMatrix H, Vector K, std::string name)
    : AffineVI(std::move(M), std::move(q), std::move(H), std::move(K), DenseMatrix(), Vector(), std::move(name)) {}

void AffineVI::set_q(Vector q) {
  if (q.size() != q_.size()) {
    Fail("q has size " + std::to_string(q.size()) + " but M is " + Shape(M_));
  }
  ValidateFinite("AffineVI", "q", q);
  q_ = std::move(q);
}

void AffineVI::Validate() {
  if (M_.rows() == 0 || M_.cols() == 0) Fail("M is " + Shape(M_) + "; a problem needs at least one unknown");
  if (M_.rows() != M_.cols()) Fail("M is " + Shape(M_) + " but must be square");
  const Eigen::Index n = M_.rows();
  if (q_.size() != n) Fail("q has size " + std::to_string(q_.size()) + " but M is " + Shape(M_));
  CheckMatrixFinite("M", M_);
  ValidateFinite("AffineVI", "q", q_);
  CheckBlock("H", "K", n, &H_, K_);
  CheckBlock("E", "f", n, &E_, f_);
  const PolytopePoint point = FindPolytopePoint(H_, K_, E_, f_);
  if (!point.found) {
    std::ostringstream s;
    s << "P = {λ : Hλ ≥ K, Eλ = f} is empty: a phase-1 simplex found no point within 1e-9 (its least "
      << "violation, in units of λ with each row divided by its largest coefficient: " << point.infeasibility
      << (point.pivot_limit ? "; it stopped at its pivot budget" : "") << ")";
    Fail(s.str());
  }
  feasible_point_ = point.point;
  boundedness_ = ClassifyPolytopeBoundedness(H_, E_);
}

}  // namespace smcbench
