// What one solve returns. Reused across solves: vectors keep their storage, so a repeated solve of the same
// size allocates nothing.
#pragma once

#include <array>
#include <cmath>
#include <optional>
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
  // An external library's own return code for this answer, 0 meaning it claims success: Siconos' info, Bullet's
  // and DART's success flag as 0 (true) / 1 (false). A claim recorded beside the verdict, never trusted over it;
  // unset for our own backends and for a library that never answered. The typed accessor bench reads instead of a
  // backend's details by name.
  std::optional<int> backend_code;

  // Names the values of a code (an enum's explicit values): "" for a number the enum does not have.
  using CodeName = std::string_view (*)(int value);
  // Backend-specific numbers (line-search backtracks, Ipopt objective, ...) and codes (which path answered, ...).
  // Fixed capacity: no allocation.
  struct Detail {
    const char* name = nullptr;  // string literal
    double value = 0.0;
    // A code's namer (set through CodeDetail), null for a measurement: JSON and Python print a code by its name
    // without knowing every backend's enums.
    CodeName code_name = nullptr;
  };
  static constexpr int kMaxDetails = 12;
  std::array<Detail, kMaxDetails> details{};
  int num_details = 0;

  bool solved() const { return status == SolveStatus::kSolved; }
  Residual residual() const { return {residual_abs, residual_rel, residual_scaled}; }
  // Adds or overwrites a measurement (names compare by text); silently ignores overflow past kMaxDetails. Set
  // details only through it or a CodeDetail (below): they keep names unique.
  void SetDetail(const char* name, double value) { SetEntry(name, value, nullptr); }
  // SetDetail for K measurements at once, in this order: the same result as K calls, with one test (and one count
  // update) for a result reused by a backend that set the same literals in the same order last time (K calls
  // cost a small solve a tenth of its instructions).
  template <int K>
  void SetDetails(const char* const (&names)[K], const double (&values)[K]) {
    const int at = num_details;
    bool same = at + K <= distinct_prefix_;
    for (int k = 0; k < K && same; ++k) same = details[at + k].name == names[k];
    if (same) {
      for (int k = 0; k < K; ++k) {
        details[at + k].value = values[k];
        details[at + k].code_name = nullptr;
      }
      num_details = at + K;
      return;
    }
    for (int k = 0; k < K; ++k) SetEntry(names[k], values[k], nullptr);
  }
  // Adds or overwrites a code; set codes through their CodeDetail, which fixes the name and the namer once.
  void SetCodeDetail(const char* name, int value, CodeName code_name) {
    SetEntry(name, static_cast<double>(value), code_name);
  }
  // Value of a detail, or NaN if absent. A code is read through its CodeDetail, never compared to a number.
  double GetDetail(std::string_view name) const;
  // The name of a code detail's value ("reused_active_set"); "" for a measurement or a number the code lacks.
  static std::string_view CodeText(const Detail& detail);
  // Returns to the "not run" state, keeping vector storage. Inline: runs at the start of every solve.
  void Reset() {
    status = SolveStatus::kNotRun;
    message.clear();
    iterations = 0;
    residual_abs = kInf;
    residual_rel = kInf;
    residual_scaled = kInf;
    solve_seconds = 0.0;
    backend_code.reset();
    num_details = 0;
  }

 private:
  // SetDetail's and SetCodeDetail's work. Inline and usually without comparing text: backends set the same
  // literals in the same order on every solve into a result reused across solves (see distinct_prefix_).
  void SetEntry(const char* name, double value, CodeName code_name) {
    // First the slot this literal held before the last Reset (a backend repeating its sequence of details): no
    // earlier slot can hold the same text, as slots below distinct_prefix_ are pairwise distinct.
    if (num_details < distinct_prefix_ && details[num_details].name == name) {
      details[num_details].code_name = code_name;
      details[num_details++].value = value;
      return;
    }
    for (int i = 0; i < num_details; ++i) {
      if (details[i].name == name) {
        details[i].value = value;
        details[i].code_name = code_name;
        return;
      }
    }
    SetEntryByText(name, value, code_name);
  }
  // details[0 .. distinct_prefix_) have pairwise different names (≥ num_details always). Reset keeps the names
  // in the array, so re-adding the literal found in slot num_details cannot duplicate a name: slots before it are
  // unchanged since they were known distinct. Appending a new name shrinks it to the new num_details.
  int distinct_prefix_ = 0;
  // SetEntry's slow half: the same name under another pointer (a literal from another translation unit), else
  // a new entry.
  void SetEntryByText(const char* name, double value, CodeName code_name);
};

// One detail that holds a code: a value 0 .. kCount−1 of Enum (append-only, explicit values, named by the
// ToString(Enum) beside it). Its owner declares it once, as
//   inline constexpr CodeDetail<SessionPath, 2> kSessionPathDetail{"path"};
// and sets and reads the detail only through it, so no caller compares a stored number (the shape of Drake's typed
// MathematicalProgramResult::get_solver_details<T>()).
template <typename Enum, int kCount>
struct CodeDetail {
  const char* name;  // the detail's name, a string literal (one pointer per code: SetEntry's fast path)

  void Set(SolveResult* result, Enum value) const {
    result->SetCodeDetail(name, static_cast<int>(value), &NameOf);
  }
  // The value, or nullopt when the detail is absent or holds a number that is not one of Enum's values.
  std::optional<Enum> Get(const SolveResult& result) const { return FromNumber(result.GetDetail(name)); }

  static std::optional<Enum> FromNumber(double value) {
    if (!(value >= 0.0 && value < kCount) || value != std::floor(value)) return std::nullopt;
    return static_cast<Enum>(static_cast<int>(value));
  }
  static std::string_view NameOf(int value) {
    const std::optional<Enum> e = FromNumber(value);
    return e ? ToString(*e) : std::string_view();
  }
};

}  // namespace smcbench
