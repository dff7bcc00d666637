#include "problems/stepper/validation.h"

#include <cmath>
#include <limits>

#include "solvers/core/number_text.h"

namespace smcbench::stepper_detail {

void Fail(const char* owner, const std::string& what) { throw InvalidInputError(std::string(owner) + ": " + what); }

namespace {
std::string Dims(Eigen::Index rows, Eigen::Index cols) { return std::to_string(rows) + "x" + std::to_string(cols); }
}  // namespace

void CheckShape(const char* owner, const char* field, const DenseMatrix& A, Eigen::Index rows, Eigen::Index cols) {
  if (A.rows() != rows || A.cols() != cols) {
    Fail(owner, std::string(field) + " is " + Dims(A.rows(), A.cols()) + " but must be " + Dims(rows, cols));
  }
}

void CheckSize(const char* owner, const char* field, const Vector& v, Eigen::Index size) {
  if (v.size() != size) {
    Fail(owner, std::string(field) + " has size " + std::to_string(v.size()) + " but must have size " +
                    std::to_string(size));
  }
}

void CheckFinite(const char* owner, const char* field, const DenseMatrix& A) {
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      if (!std::isfinite(A(i, j))) {
        Fail(owner, std::string(field) + "(" + std::to_string(i) + "," + std::to_string(j) + ") is " +
                        (std::isnan(A(i, j)) ? "NaN" : "infinite"));
      }
    }
  }
}

void CheckInvertible(const char* owner, const char* field, const DenseMatrix& A) {
  // Full pivoting gives a rank-revealing factorization: rank < n means singular to working precision.
  Eigen::FullPivLU<DenseMatrix> lu(A);
  if (!lu.isInvertible()) {
    Fail(owner, std::string(field) + " is singular (numerical rank " + std::to_string(lu.rank()) + " < " +
                    std::to_string(A.rows()) + ")");
  }
  const double rcond = A.partialPivLu().rcond();
  if (!(rcond > 10.0 * std::numeric_limits<double>::epsilon())) {
    Fail(owner, std::string(field) + " is singular to working precision (reciprocal condition number " +
                    NumberText(rcond) + ")");
  }
}

void CheckStep(const char* owner, double h) {
  if (!(h > 0.0) || !std::isfinite(h)) Fail(owner, "h must be a positive finite time step, got " + NumberText(h));
}

}  // namespace smcbench::stepper_detail
