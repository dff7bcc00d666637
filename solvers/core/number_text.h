// Doubles as text for ids, files and messages: the shortest form that reads back to the same value (std::to_chars:
// locale-independent, exact round trip), "nan" for any NaN. One definition for every writer and message.
#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace smcbench {

inline void AppendNumberText(std::string* out, double value) {
  if (std::isnan(value)) {
    out->append("nan");
    return;
  }
  char buffer[32];  // the longest shortest-round-trip double is 24 characters
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

inline std::string NumberText(double value) {
  std::string out;
  AppendNumberText(&out, value);
  return out;
}

}  // namespace smcbench
