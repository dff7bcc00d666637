// What every fuzz target checks: a finding aborts with a one-line reason; an InvalidInputError (the expected
// answer to bad input) must carry a one-line, non-empty message; any other exception is a finding; an accepted
// BoxMLCP must keep its invariants. The targets share these so that each one says only what its reader promises.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>

#include "solvers/core/problem.h"

namespace smcbench::fuzz {

[[noreturn]] inline void Finding(const char* what) {
  std::fprintf(stderr, "FINDING: %s\n", what);
  std::abort();
}

// "FINDING: <context><exception type>: <what>" and abort.
[[noreturn]] inline void UnexpectedException(std::string_view context, const std::exception& e) {
  std::fprintf(stderr, "FINDING: %.*s%s: %s\n", static_cast<int>(context.size()), context.data(), typeid(e).name(),
               e.what());
  std::abort();
}

// What an InvalidInputError's message must be. The CLI prints most messages as they are (one line); a scene error
// may quote the offending lines of the file (several lines, never empty).
enum class MessageRule { kOneLine, kNonEmpty };

inline void CheckErrorMessage(const std::string& message, MessageRule rule = MessageRule::kOneLine) {
  if (message.empty()) Finding("InvalidInputError with an empty message");
  if (rule == MessageRule::kOneLine && message.find('\n') != std::string::npos) {
    Finding("InvalidInputError message spans several lines");
  }
}

// Runs read() on one fuzz input: returning normally (accepted, read's own checks passed) gives true; an
// InvalidInputError (the expected answer to bad input) gives false once its message passes rule; any other
// exception is a finding.
template <typename Read>
bool AcceptOrReject(Read&& read, MessageRule rule = MessageRule::kOneLine) {
  try {
    read();
    return true;
  } catch (const InvalidInputError& e) {
    CheckErrorMessage(e.what(), rule);
  } catch (const std::exception& e) {
    UnexpectedException("unexpected ", e);
  }
  return false;
}

// Runs body(), in which every exception is a finding (e.g. re-writing an accepted input); context starts the line.
template <typename Body>
void NoExceptionAllowed(std::string_view context, Body&& body) {
  try {
    body();
  } catch (const std::exception& e) {
    UnexpectedException(context, e);
  }
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
