// Input checks shared by the stepper's systems, discretizations and runs. Every failure throws
// InvalidInputError "Owner: field ..." so the message names what is wrong.
#pragma once

#include <string>

#include "solvers/core/problem.h"
#include "solvers/core/types.h"

namespace smcbench::stepper_detail {

[[noreturn]] void Fail(const char* owner, const std::string& what);
void CheckShape(const char* owner, const char* field, const DenseMatrix& A, Eigen::Index rows, Eigen::Index cols);
void CheckSize(const char* owner, const char* field, const Vector& v, Eigen::Index size);
void CheckFinite(const char* owner, const char* field, const DenseMatrix& A);
// Throws "<owner>: <field> is singular (...)" when A is square but numerically rank deficient.
void CheckInvertible(const char* owner, const char* field, const DenseMatrix& A);
// h > 0 finite.
void CheckStep(const char* owner, double h);

}  // namespace smcbench::stepper_detail
