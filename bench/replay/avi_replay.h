// The AVI half of `smcbench bench`: one AVI of an AviProblemSet × one box backend is one job, timed by cold solves
// through SolveAvi (the exact reduction to a box-MLCP, solvers/avi/avi_solver.h) and judged by JudgeAvi against the
// problem's expected outcome and reference (never by the backend's own flag), into the same ReplayRecord as a
// box-MLCP job (suite "avi"). Every backend that solves box-MLCPs (SolverInfo::box) runs AVIs.
#pragma once

#include <string>
#include <vector>

#include "bench/replay/replay.h"
#include "problems/avi_library/avi_library.h"
#include "solvers/avi/avi_solver.h"

namespace smcbench {


// Times cold solves of avi with SampleSolveTimes as TimeSolves does for the box: an untimed warm-up, then samples;
// the backend's remembered state is forgotten (Solver::ForgetWarmState) before each timed solve when it keeps any.
// A timed solve is all of SolveAvi: building the reduction, the backend's solve, mapping back and the AVI rule for
// "solved" (what a caller of SolveAvi pays). *result holds the last solve.
void TimeAviSolves(Solver* solver, const AffineVI& avi, const SolverOptions& options, const ReplayOptions& replay,
                   AviResult* result, ReplayRecord* record);

// One AVI × backend at tolerance, timed and judged (mode "cold"): the record's residuals are JudgeAvi's (of the
// normalized reduction at the answer), its forward error ‖λ − λ*‖∞ where λ is unique (NaN otherwise), its size n.
// A backend without SolverInfo::box gets a record with status not applicable, verdict failed.
ReplayRecord ReplayAviOne(const AviProblemSet& set, const AviLibraryProblem& problem, Solver* solver,
                          const std::string& solver_name, const ReplayOptions& options, double tolerance);

// Every AVI of set on every box backend among options.solvers (empty: every registered one), in that order
// (problem, backend); each backend gets the settings that reach it. Throws as CreateReplaySolvers.
ReplayResults ReplayAviProblemSet(const AviProblemSet& set, const ReplayOptions& options);

// What the run's manifest records of an AVI suite, so shards and resumed runs refuse another suite: FNV-1a 64 (16
// hex digits) over every problem's id, source, tags, expected outcome, data (M, q, H, K, E, f) and reference
// (certificate, condition, λ's uniqueness, z). Doubles enter by their bits.
std::string AviProblemSetChecksum(const AviProblemSet& set);

// A job's record when the backend was not run (its --backend-budget spent): status time limit, verdict failed,
// the message given, infinite residuals.
ReplayRecord AviNotRunRecord(const AviProblemSet& set, const AviLibraryProblem& problem,
                             const std::string& solver_name, double tolerance, const std::string& message);

}  // namespace smcbench
