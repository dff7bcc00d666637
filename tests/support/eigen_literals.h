// Small dense matrices and vectors written as literals in tests: Mat({{2, 1}, {1, 2}}), Vec({-1, -1}).
#pragma once

#include <initializer_list>

#include "solvers/core/types.h"

namespace smcbench::test_support {

inline DenseMatrix Mat(std::initializer_list<std::initializer_list<double>> rows) {
  DenseMatrix M(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.begin()->size()));
  int i = 0;
  for (const auto& row : rows) {
    int j = 0;
    for (double v : row) M(i, j++) = v;
    ++i;
  }
  return M;
}

inline Vector Vec(std::initializer_list<double> values) {
  Vector v(static_cast<Eigen::Index>(values.size()));
  int i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

}  // namespace smcbench::test_support
