// Timed, repeated solves of one problem by one backend, and their rendering as text and JSON rows.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solvers/core/solver.h"

namespace smcbench {

struct SolveRecord {
  std::string problem;
  std::string solver;
  SolveResult result;             // from the last repetition
  double time_ns_median = 0.0;    // median wall time per cold solve
  double time_ns_min = 0.0;
  double time_ns_max = 0.0;
  int repeats = 0;
  std::string error;              // set when the backend could not even be configured
};

// Solves problem `repeat` times from a cold start with one reused result (the workspace is reused too) and
// records the median, min and max solve time (SolveResult::solve_seconds, the base class's own timer).
SolveRecord TimedSolve(Solver& solver, const BoxMLCP& problem, const SolverOptions& options, int repeat);

// "lemke   solved   iters 3   res 0.0e+00 / 0.0e+00   1.2 us" (fixed columns).
std::string FormatRecordLine(const SolveRecord& record);
// The stable JSON keys scripts depend on: solver, status, iterations, residual_abs, residual_rel,
// time_ns_median, z (plus problem, message, time_ns_min/max, repeats, details).
nlohmann::json RecordToJson(const SolveRecord& record);
// Human time: "850 ns", "12.3 us", "4.56 ms", "1.23 s".
std::string FormatDuration(double ns);

}  // namespace smcbench
