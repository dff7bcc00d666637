// `smcbench report DIR`: turns a bench run's results.json into DIR/report.md with PNG plots — per suite and
// backend the verdict counts (wrong answers apart), success rate, shifted geometric mean time, worst residuals
// (relative and row-equilibrated) and worst forward error, Dolan–Moré performance profiles, time against the
// forward error and against the residual reached (tolerance sweep), the time-stepper's work-precision diagrams
// and warm/cold table, the scale family's growth exponent, and for an MCP suite its own section (success per
// backend and per start, where each backend fails and with what status, speed against forward error, profile).
#pragma once

#include <string>
#include <vector>

#include "bench/replay/results_io.h"

namespace smcbench {

struct BackendSummary {
  std::string solver;
  int problems = 0, solved = 0, correctly_refused = 0, failed = 0;
  int wrongly_claimed = 0, inaccurate = 0, wrongly_refused = 0;  // the wrong answers (IsWrong)
  double success_rate = 0.0;     // (solved + correctly refused) / problems
  double shifted_geomean = 0.0;  // seconds; see SummarizeSuite
  // Over the records with verdict solved: max relative residual, max row-equilibrated residual, and max forward
  // error ‖z − z*‖∞ over those whose problem has a unique reference (NaN when none has).
  double worst_residual = 0.0;
  double worst_residual_scaled = 0.0;
  double worst_forward_error = kNaN;
  int forward_error_defined = 0;  // solved records with a forward error
  int wrong() const { return wrongly_claimed + inaccurate + wrongly_refused; }
};

// True when the suite's records are MCP problem × start (ReplayRecord::start set): the report's MCP section.
bool IsMcpSuite(const SuiteResults& suite);

// Shifted geometric mean of the per-problem median times, shift 1e-6 s, a problem the backend does not get right
// counted at 10× the slowest correct time on that problem (the time limit if nobody got it right). For an MCP suite
// a problem is a problem × start, here and in PerformanceRatios.
std::vector<BackendSummary> SummarizeSuite(const SuiteResults& suite, double time_limit_seconds = 10.0);

// Dolan–Moré: for each backend, ρ(τ) = fraction of problems solved within τ × the best time on that problem.
// Returns, per backend, the ratios r_p = t_p / min_s t_p (∞ for problems it does not solve), sorted.
std::vector<std::pair<std::string, std::vector<double>>> PerformanceRatios(const SuiteResults& suite);

// Least-squares slope of log(time) against log(size) over the solved records of one backend (NaN if < 2 sizes).
double GrowthExponent(const SuiteResults& suite, const std::string& solver);

// The verdict in two sentences a user can check by hand (the report's text and `smcbench bench --help`).
extern const char* const kVerdictInTwoSentences;

// The report's warning when compared times come from shared hosts: records measured while other bench jobs ran on
// their host (ReplayRecord::concurrent_jobs > 1) or records from more than one host. Empty when neither.
std::string SharedHostWarning(const BenchResults& results);

// Writes dir/report.md (and PNGs when plots is true and gnuplot is on PATH). Returns the markdown.
// InvalidInputError if results are missing or gnuplot is required but absent.
std::string WriteBenchReport(const std::string& dir, bool plots);

}  // namespace smcbench
