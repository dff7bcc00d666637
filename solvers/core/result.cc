#include "solvers/core/result.h"

#include <cstring>
#include <limits>

namespace smcbench {

void SolveResult::SetDetail(const char* name, double value) {
  for (int i = 0; i < num_details; ++i) {
    if (details[i].name == name || std::strcmp(details[i].name, name) == 0) {
      details[i].value = value;
      return;
    }
  }
  if (num_details < kMaxDetails) details[num_details++] = {name, value};
}

double SolveResult::GetDetail(std::string_view name) const {
  for (int i = 0; i < num_details; ++i) {
    if (details[i].name == name) return details[i].value;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void SolveResult::Reset() {
  status = SolveStatus::kNotRun;
  message.clear();
  iterations = 0;
  residual_abs = kInf;
  residual_rel = kInf;
  solve_seconds = 0.0;
  num_details = 0;
}

}  // namespace smcbench
