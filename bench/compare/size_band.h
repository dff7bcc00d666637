// The size bands results are grouped by (m ≤ 4, 5–64, 65–1024, larger): one definition for `compare` and reports, so
// a band means the same problems everywhere.
#pragma once

#include <string_view>

namespace smcbench {

// Append-only, explicit values: stored comparisons stay readable.
enum class SizeBand : int {
  kTiny = 0,    // m ≤ 4: the paper's one-step problems, where call overhead dominates
  kSmall = 1,   // 5 ≤ m ≤ 64: dense methods' home ground
  kMedium = 2,  // 65 ≤ m ≤ 1024
  kLarge = 3,   // m > 1024: sparse methods only, in practice
};
inline constexpr SizeBand kSizeBands[] = {SizeBand::kTiny, SizeBand::kSmall, SizeBand::kMedium, SizeBand::kLarge};

inline SizeBand SizeBandOf(int size) {
  if (size <= 4) return SizeBand::kTiny;
  if (size <= 64) return SizeBand::kSmall;
  if (size <= 1024) return SizeBand::kMedium;
  return SizeBand::kLarge;
}

// "m<=4", "m5-64", "m65-1024", "m>1024": short enough for a table column and a figure's axis.
inline std::string_view ToString(SizeBand band) {
  switch (band) {
    case SizeBand::kTiny: return "m<=4";
    case SizeBand::kSmall: return "m5-64";
    case SizeBand::kMedium: return "m65-1024";
    case SizeBand::kLarge: return "m>1024";
  }
  return "?";
}

}  // namespace smcbench
