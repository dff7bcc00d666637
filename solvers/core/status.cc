#include "solvers/core/status.h"

#include <array>
#include <utility>

namespace smcbench {
namespace {

constexpr std::array<std::pair<SolveStatus, std::string_view>, 14> kNames{{
    {SolveStatus::kNotRun, "not_run"},
    {SolveStatus::kSolved, "solved"},
    {SolveStatus::kIterationLimit, "iteration_limit"},
    {SolveStatus::kRayTermination, "ray_termination"},
    {SolveStatus::kSingular, "singular"},
    {SolveStatus::kNotApplicable, "not_applicable"},
    {SolveStatus::kNumericalFailure, "numerical_failure"},
    {SolveStatus::kSizeLimit, "size_limit"},
    {SolveStatus::kInfeasible, "infeasible"},
    {SolveStatus::kTimeLimit, "time_limit"},
    {SolveStatus::kInvalidOptions, "invalid_options"},
    {SolveStatus::kInaccurate, "inaccurate"},
    {SolveStatus::kStalled, "stalled"},
    {SolveStatus::kDiverged, "diverged"},
}};

}  // namespace

std::string_view ToString(SolveStatus status) {
  for (const auto& [value, name] : kNames) {
    if (value == status) return name;
  }
  return "unknown";
}

std::optional<SolveStatus> SolveStatusFromString(std::string_view name) {
  for (const auto& [value, text] : kNames) {
    if (text == name) return value;
  }
  return std::nullopt;
}

}  // namespace smcbench
