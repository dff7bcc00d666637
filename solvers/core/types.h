// Linear-algebra vocabulary shared by every smcbench target: one place to change the scalar and index types.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <limits>

namespace smcbench {

using Vector = Eigen::VectorXd;
using DenseMatrix = Eigen::MatrixXd;
// Column-major with int indices: the layout SuiteSparse (UMFPACK, CHOLMOD) and Eigen's wrappers expect.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace smcbench
