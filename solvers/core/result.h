// What one solve returns. Reused across solves: vectors keep their storage, so a repeated solve of the same
// size allocates nothing.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "solvers/core/problem.h"
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
  double residual_scaled = kInf;  // of the row-equilibrated problem, relative to 1 + ‖z‖∞ (Residual::scaled)
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
  Residual residual() const { return {residual_abs, residual_rel, residual_scaled}; }
  // Adds or overwrites a detail (names compare by text); silently ignores overflow past kMaxDetails. Set details
  // only through it: it keeps names unique. Inline and usually without comparing text: backends set the same
  // literals in the same order on every solve into a result reused across solves (see distinct_prefix_).
  void SetDetail(const char* name, double value) {
    // First the slot this literal held before the last Reset (a backend repeating its sequence of details): no
    // earlier slot can hold the same text, as slots below distinct_prefix_ are pairwise distinct.
    if (num_details < distinct_prefix_ && details[num_details].name == name) {
      details[num_details++].value = value;
      return;
    }
    for (int i = 0; i < num_details; ++i) {
      if (details[i].name == name) {
        details[i].value = value;
        return;
      }
    }
    SetDetailByText(name, value);
  }
  // Value of a detail, or NaN if absent.
  double GetDetail(std::string_view name) const;
  // Returns to the "not run" state, keeping vector storage. Inline: runs at the start of every solve.
  void Reset() {
    status = SolveStatus::kNotRun;
    message.clear();
    iterations = 0;
    residual_abs = kInf;
    residual_rel = kInf;
    residual_scaled = kInf;
    solve_seconds = 0.0;
    num_details = 0;
  }

 private:
  // details[0 .. distinct_prefix_) have pairwise different names (≥ num_details always). Reset keeps the names
  // in the array, so re-adding the literal found in slot num_details cannot duplicate a name: slots before it are
  // unchanged since they were known distinct. Appending a new name shrinks it to the new num_details.
  int distinct_prefix_ = 0;
  // SetDetail's slow half: the same name under another pointer (a literal from another translation unit), else
  // a new entry.
  void SetDetailByText(const char* name, double value);
};

}  // namespace smcbench
