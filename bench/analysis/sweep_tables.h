// The tolerance sweep as tables: success per backend at each tolerance (the ladder), and per backend and tolerance
// the medians of forward error, residual reached and time (the speed-against-error rows).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "bench/replay/results_io.h"

namespace smcbench {

// Success at each tolerance of the sweep records (mode "sweep"): correct answers (solved or correctly refused) of
// each backend over the swept problems, per tolerance.
struct ToleranceLadder {
  std::vector<double> tolerances;  // loosest first, those the sweep records hold (kSweepTolerances today)
  struct Row {
    std::string solver;
    std::vector<int> correct, problems;  // per tolerance (problems 0: that rung was not run, e.g. skipped)
  };
  std::vector<Row> rows;  // in the order the backends first appear
};
ToleranceLadder BuildToleranceLadder(const SuiteResults& suite);

// One (backend, tolerance) row of the tolerance sweep: medians over the swept problems.
struct SweepRow {
  std::string solver;
  double tolerance = 0.0;
  double forward_error = kNaN;  // median over the problems with a unique certified reference
  std::size_t with_reference = 0, problems = 0;
  int solved = 0;
  double residual = kNaN, residual_scaled = kNaN;  // achieved, median
  double time = kNaN;                              // median over every swept problem
  double time_with_reference = kNaN;               // median over the problems with a reference
};

// Loosest tolerance first per backend. A non-finite error counts as 1e300 (NaN residual_scaled: not defined).
std::vector<SweepRow> SweepRows(const SuiteResults& suite);

}  // namespace smcbench
