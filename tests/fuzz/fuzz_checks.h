// What every fuzz target checks: a finding aborts with a one-line reason; an InvalidInputError (the expected
// answer to bad input) must carry a one-line, non-empty message; an accepted BoxMLCP must keep its invariants.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "solvers/core/problem.h"

namespace smcbench::fuzz {

[[noreturn]] inline void Finding(const char* what) {
  std::fprintf(stderr, "FINDING: %s\n", what);
  std::abort();
}

// The CLI prints these messages as they are.
inline void CheckErrorMessage(const std::string& message) {
  if (message.empty()) Finding("InvalidInputError with an empty message");
  if (message.find('\n') != std::string::npos) Finding("InvalidInputError message spans several lines");
}

// What a reader promises for an accepted problem (BoxMLCP's constructor): square finite M, finite q, l ≤ u.
inline void CheckAccepted(const BoxMLCP& p) {
  const Eigen::Index n = p.size();
  if (n <= 0) Finding("accepted a problem with no unknowns");
  if (p.q().size() != n || p.l().size() != n || p.u().size() != n) Finding("accepted inconsistent sizes");
  if (!p.q().allFinite()) Finding("accepted a non-finite q");
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isnan(p.l()[i]) || std::isnan(p.u()[i]) || p.l()[i] > p.u()[i]) Finding("accepted bad bounds");
  }
  if (p.is_sparse()) {
    const SparseMatrix& M = p.sparse_matrix();
    if (M.rows() != n || M.cols() != n) Finding("accepted a non-square sparse M");
    for (Eigen::Index k = 0; k < M.nonZeros(); ++k) {
      if (!std::isfinite(M.valuePtr()[k])) Finding("accepted a non-finite sparse M entry");
    }
  } else {
    const DenseMatrix& M = p.dense_matrix();
    if (M.rows() != n || M.cols() != n) Finding("accepted a non-square M");
    if (!M.allFinite()) Finding("accepted a non-finite M");
  }
}

}  // namespace smcbench::fuzz
