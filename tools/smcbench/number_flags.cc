#include "tools/smcbench/number_flags.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace smcbench {
namespace {

// True when all of text is one number (NaN and inf included), stored in *value.
bool ParseWholeDouble(const std::string& text, double* value) {
  std::size_t used = 0;
  try {
    *value = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size();
}

// True when all of text is one whole number, stored in *value.
bool ParseWholeInteger(const std::string& text, long long* value) {
  std::size_t used = 0;
  try {
    *value = std::stoll(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size();
}

}  // namespace

CLI::Validator PositiveNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!ParseWholeDouble(text, &value) || !(value > 0.0) || !std::isfinite(value)) {
          return "must be a positive finite number, got '" + text + "'";
        }
        return {};
      },
      "POSITIVE");
}

CLI::Validator NonNegativeNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!ParseWholeDouble(text, &value) || !(value >= 0.0) || !std::isfinite(value)) {
          return "must be a finite number ≥ 0, got '" + text + "'";
        }
        return {};
      },
      "SECONDS");
}

CLI::Validator NonNegativeInteger() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        long long value = -1;
        if (!ParseWholeInteger(text, &value) || value < 0 || value > std::numeric_limits<int>::max()) {
          return "must be a whole number ≥ 0, got '" + text + "'";
        }
        return {};
      },
      "N");
}

CLI::Validator PositiveInteger() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        long long value = 0;
        if (!ParseWholeInteger(text, &value) || value < 1 || value > std::numeric_limits<int>::max()) {
          return "must be a whole number ≥ 1, got '" + text + "'";
        }
        return {};
      },
      "N");
}

}  // namespace smcbench
