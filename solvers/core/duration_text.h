// Durations as text for terminals and reports: one unit ladder (ns, µs, ms, s) and one precision everywhere, so
// that the same time reads the same in `solve`, `simulate`, `bench` reports and the perf tables.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace smcbench {

// "850 ns", "12.3 µs", "4.56 ms", "1.23 s", "1.23e+03 s": three significant digits (whole nanoseconds below 1 µs);
// "-" for a negative time (not measured), "nan"/"inf" as such.
inline std::string DurationText(double seconds) {
  if (std::isnan(seconds)) return "nan";
  if (std::isinf(seconds)) return seconds > 0.0 ? "inf" : "-";
  if (seconds < 0.0) return "-";
  char buffer[40];
  const double ns = seconds * 1e9;
  if (std::round(ns) < 1e3) {
    std::snprintf(buffer, sizeof buffer, "%.0f ns", ns);
  } else if (ns < 999.5e3) {
    std::snprintf(buffer, sizeof buffer, "%.3g µs", ns / 1e3);
  } else if (ns < 999.5e6) {
    std::snprintf(buffer, sizeof buffer, "%.3g ms", ns / 1e6);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.3g s", seconds);
  }
  return buffer;
}

}  // namespace smcbench
