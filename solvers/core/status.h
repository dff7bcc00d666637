// What a solve found, as an append-only enum with explicit values so stored results stay readable (HiGHS practice).
#pragma once

#include <optional>
#include <string_view>

namespace smcbench {

enum class SolveStatus : int {
  kNotRun = 0,             // Result constructed, no solve happened yet.
  kSolved = 1,             // Merit function at or below tolerance (checked by the base class).
  kIterationLimit = 2,     // Iteration / pivot budget exhausted; z is the last iterate.
  kRayTermination = 3,     // Lemke: secondary ray, no solution found by this method.
  kSingular = 4,           // A linear system the method needs is singular.
  kNotApplicable = 5,      // Problem class outside the backend's scope (e.g. sparse M, nonlinear MCP).
  kNumericalFailure = 6,   // NaN/Inf appeared, pivot too small, line search broke down.
  kSizeLimit = 7,          // Problem larger than the backend's configured limit.
  kInfeasible = 8,         // Proven: no solution exists (exhaustive enumeration).
  kTimeLimit = 9,          // Wall-clock budget exhausted.
  kInvalidOptions = 10,    // Options failed validation; nothing was run. See message.
  kInaccurate = 11,        // Backend claimed success but the merit function is above tolerance.
  kStalled = 12,           // No further progress possible (line search / step length collapsed).
  kDiverged = 13,          // Iterates grew without bound.
};

// Stable lower-case names ("solved", "iteration_limit", ...): scripts and JSON depend on them.
std::string_view ToString(SolveStatus status);
std::optional<SolveStatus> SolveStatusFromString(std::string_view name);

}  // namespace smcbench
