#include "solvers/core/result.h"

#include <limits>

namespace smcbench {

namespace {
// strcmp(a, b) == 0 inline: names of one backend usually differ in the first character, and a libc call here
// (per detail, per solve) cost more than the rest of SetDetail.
bool SameText(const char* a, const char* b) {
  while (*a != '\0' && *a == *b) ++a, ++b;
  return *a == *b;
}
}  // namespace

void SolveResult::SetEntryByText(const char* name, double value, CodeName code_name) {
  for (int i = 0; i < num_details; ++i) {
    if (SameText(details[i].name, name)) {
      details[i].value = value;
      details[i].code_name = code_name;
      return;
    }
  }
  if (num_details < kMaxDetails) {
    details[num_details++] = {name, value, code_name};
    distinct_prefix_ = num_details;  // older names after the new one may repeat it
  }
}

double SolveResult::GetDetail(std::string_view name) const {
  for (int i = 0; i < num_details; ++i) {
    if (details[i].name == name) return details[i].value;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::string_view SolveResult::CodeText(const Detail& detail) {
  // The range check keeps the cast defined; the namer rejects what its enum lacks.
  if (detail.code_name == nullptr || !(detail.value >= 0.0 && detail.value < 1e9)) return {};
  if (detail.value != static_cast<double>(static_cast<int>(detail.value))) return {};
  return detail.code_name(static_cast<int>(detail.value));
}

}  // namespace smcbench
