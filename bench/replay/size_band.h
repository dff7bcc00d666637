// The size bands results are compared in (the report's "fastest correct backend per size band"): what is fastest on
// a one-step problem of a sliding-mode controller (m ≤ 4) says little about a 500-contact problem, so a winner is
// named per band, never over a whole suite. One definition for every reader of the results.
#pragma once

#include <string_view>

namespace smcbench {

// Append-only, explicit values (stored results may name a band).
enum class SizeBand : int {
  kTiny = 0,    // m ≤ 4: one-step problems of small controllers (fixed-size paths)
  kSmall = 1,   // 5 ≤ m ≤ 64: dense, factorizations cheap
  kMedium = 2,  // 65 ≤ m ≤ 1024: dense factorizations start to dominate
  kLarge = 3,   // m > 1024: sparse territory
};

inline constexpr SizeBand kSizeBands[] = {SizeBand::kTiny, SizeBand::kSmall, SizeBand::kMedium, SizeBand::kLarge};

constexpr SizeBand SizeBandOf(int m) {
  return m <= 4 ? SizeBand::kTiny : m <= 64 ? SizeBand::kSmall : m <= 1024 ? SizeBand::kMedium : SizeBand::kLarge;
}

// "m ≤ 4", "5 ≤ m ≤ 64", "65 ≤ m ≤ 1024", "m > 1024".
constexpr std::string_view ToString(SizeBand band) {
  switch (band) {
    case SizeBand::kTiny: return "m ≤ 4";
    case SizeBand::kSmall: return "5 ≤ m ≤ 64";
    case SizeBand::kMedium: return "65 ≤ m ≤ 1024";
    case SizeBand::kLarge: return "m > 1024";
  }
  return "?";
}

// "m<=4", "m5-64", "m65-1024", "m>1024": ASCII, for fixed-width terminal tables (`compare`) and figure axes.
constexpr std::string_view ShortName(SizeBand band) {
  switch (band) {
    case SizeBand::kTiny: return "m<=4";
    case SizeBand::kSmall: return "m5-64";
    case SizeBand::kMedium: return "m65-1024";
    case SizeBand::kLarge: return "m>1024";
  }
  return "?";
}

}  // namespace smcbench
