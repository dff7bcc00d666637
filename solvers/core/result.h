// What one solve returns. Reused across solves: vectors keep their storage, so a repeated solve of the same
// size allocates nothing.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "solvers/core/status.h"
#include "solvers/core/types.h"

namespace smcbench {

struct SolveResult {
  SolveStatus status = SolveStatus::kNotRun;
  // Why, for anything but kSolved (empty on success).
  std::string message;
  // Registered name of the backend that produced this result.
  std::string_view solver;

  Vector z;  // the iterate returned
  Vector w;  // F(z): M z + q for a box-MLCP, recomputed by the base class
  int iterations = 0;  // iterations, pivots or nodes, per backend (see its documentation)
  // The merit function at z, computed by the base class (never by the backend).
  double residual_abs = kInf;
  double residual_rel = kInf;
  double solve_seconds = 0.0;  // wall time of the whole Solve() call (0 when options.measure_time is off)

  // Backend-specific numbers (line-search backtracks, Ipopt objective, ...). Fixed capacity: no allocation.
  struct Detail {
    const char* name = nullptr;  // string literal
    double value = 0.0;
  };
  static constexpr int kMaxDetails = 12;
  std::array<Detail, kMaxDetails> details{};
  int num_details = 0;

  bool solved() const { return status == SolveStatus::kSolved; }
  // Adds or overwrites a detail; silently ignores overflow past kMaxDetails.
  void SetDetail(const char* name, double value);
  // Value of a detail, or NaN if absent.
  double GetDetail(std::string_view name) const;
  // Returns to the "not run" state, keeping vector storage.
  void Reset();
};

}  // namespace smcbench
