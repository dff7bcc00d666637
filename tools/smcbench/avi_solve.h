// `smcbench solve FILE.avi.json` and `solve FILE.smcps` on a set of AVIs: every chosen backend on each AVI through
// SolveAvi (solvers/avi/avi_solver.h), judged by the AVI verdict (JudgeAvi), rendered as text and JSON in the style
// of the box solve (solve_report.h).
#pragma once

#include <nlohmann/json.hpp>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solvers/avi/avi_solver.h"
#include "solvers/core/solver.h"
#include "tools/smcbench/problem_files.h"

namespace smcbench {

struct AviSolveRecord {
  std::string problem;
  std::string solver;
  AviResult result;            // from the last repetition; result.judgement is the verdict (never the backend's flag)
  bool judged_against_reference = false;  // `--reference`: result.judgement was recomputed against a CertifyAvi
  double time_ns_median = 0.0;  // wall time per SolveAvi call (the reduction is built in each call)
  double time_ns_min = 0.0;
  double time_ns_max = 0.0;
  int repeats = 0;
  // Cold means cold: before every repeat but the first the backend forgot what it remembers (Solver::
  // ForgetWarmState, untimed); cached: it said it cannot, so its repeats may not have started cold.
  bool cached = false;
};

// Solves avi `repeat` times with solver, each call timed alone, after an untimed ForgetWarmState (cold).
AviSolveRecord TimedAviSolve(const AffineVI& avi, Solver& solver, const SolverOptions& options, int repeat);

// "lemke    solved   iters 3   res 0.00e+00 rel / 0.00e+00 scaled   primal 0.00e+00   compl 0.00e+00   1.2 us
// verdict solved", then the λ, μ and ν lines (shortest round-trip numbers).
std::string FormatAviRecord(const AviSolveRecord& record);
// Keys: problem, solver, status, message, verdict, iterations, residual_rel, residual_scaled, primal_infeasibility,
// complementarity, forward_error, forward_error_rel, forward_allowance (null when not judged), lambda, mu, nu,
// time_ns_median, time_ns_min, time_ns_max, repeats, cached, reduced (the backend's status, iterations and details
// on the reduction).
nlohmann::json AviRecordToJson(const AviSolveRecord& record);

// The whole `solve` of an AVI file: read (ReadAviProblemFile), every backend solved and judged; with reference, the
// AVI certified (CertifyAvi from the file's "solution" and every answer) and every answer judged against it.
// json: an array of records, or {reference, results} with reference (as the box solve of one file).
int RunSolveAvi(const std::string& path, std::optional<ProblemFormat> format,
                std::vector<std::unique_ptr<Solver>>& solvers, const SolverOptions& options, int repeat, bool json,
                bool reference, std::ostream& out);

// `solve FILE.smcps [--id ID ...]` on a set of AVIs (ReadAviProblemSetById: all of them, or those ids, 'PREFIX*' by
// prefix): each AVI as RunSolveAvi solves a file, judged by the set's expected outcome; with reference, against the
// set's own verified reference where it has one (else certified here from the answers). Text: one block per AVI,
// titled by its id; json: an array with one object per AVI {problem, n, m, p, expected, results, reference (with
// reference)}.
int RunSolveAviSet(const std::string& path, const std::vector<std::string>& ids,
                   std::vector<std::unique_ptr<Solver>>& solvers, const SolverOptions& options, int repeat, bool json,
                   bool reference, std::ostream& out);

}  // namespace smcbench
