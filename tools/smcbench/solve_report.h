// Timed, repeated solves of one problem by one backend, and their rendering as text and JSON rows.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solvers/core/solver.h"
#include "solvers/core/verdict.h"

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
  // With `solve --reference`: the judgement against the certified reference (forward errors NaN when the
  // reference does not prove z* unique). has_judgement false: not judged, the keys are not written.
  bool has_judgement = false;
  Judgement judgement;
};

// Solves problem `repeat` times from a cold start with one reused result (the workspace is reused too) and
// records the median, min and max solve time (SolveResult::solve_seconds, the base class's own timer).
SolveRecord TimedSolve(Solver& solver, const BoxMLCP& problem, const SolverOptions& options, int repeat);

// "lemke    solved   iters 3   res 0.00e+00 abs / 0.00e+00 rel / 0.00e+00 eq   1.2 us" (fixed columns), then
// "   fwd err 1.11e-16 (rel 1.11e-16, allowed 2.00e-09)   solved" (or "fwd err n/a") when judged.
std::string FormatRecordLine(const SolveRecord& record);
// The stable JSON keys scripts depend on: solver, status, iterations, residual_abs, residual_rel,
// residual_scaled, time_ns_median, z (plus problem, message, time_ns_min/max, repeats, details); when judged
// against a reference also forward_error, forward_error_rel (null when not defined), forward_allowance, verdict.
nlohmann::json RecordToJson(const SolveRecord& record);
// {certificate, condition, z} of a reference solution (z empty unless verified; condition null when infinite).
nlohmann::json ReferenceToJson(const ReferenceSolution& reference);
// Human time: "850 ns", "12.3 us", "4.56 ms", "1.23 s".
std::string FormatDuration(double ns);

}  // namespace smcbench
