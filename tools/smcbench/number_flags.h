// Checks of numeric flags shared by the commands: a bad value fails parsing with one line naming the flag and the
// value ("--time-limit: must be a positive finite number, got '-1'"), exit status 2, before any work.
#pragma once

#include <CLI/CLI.hpp>

namespace smcbench {

// A finite number > 0 (CLI11's PositiveNumber prints its range with DBL_MAX in full: 300 digits).
CLI::Validator PositiveNumber();
// A finite number ≥ 0 (seconds of a budget where 0 means "no limit").
CLI::Validator NonNegativeNumber();
// A whole number ≥ 0 that fits an int (CLI11's NonNegativeNumber admits fractions).
CLI::Validator NonNegativeInteger();
// A whole number ≥ 1 that fits an int (counts of repetitions).
CLI::Validator PositiveInteger();

}  // namespace smcbench
