// The MCP half of `smcbench bench`: one nonlinear MCP × one of its published starting points × one backend is one
// job, timed by cold solves from that start and judged by JudgeMCP (solvers/core/verdict.h) into the same
// ReplayRecord as a box-MLCP job, with the start's label. Only backends with SolverInfo::mcp run MCPs: the others
// get no record (not a failure of theirs, so the report does not count them).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "bench/replay/replay.h"
#include "problems/mcp/mcp_library.h"

namespace smcbench {


// Times cold solves of problem from options.warm_start (the job's start; never the previous answer) as TimeSolves
// does for the box: an untimed warm-up solve, then samples honouring min_sample_seconds, repetitions,
// max_seconds_per_pair and the time limit. *result holds the last solve.
void TimeMcpSolves(Solver* solver, const MCP& problem, const SolverOptions& options, const ReplayOptions& replay,
                   SolveResult* result, ReplayRecord* record);

// One MCP × start (index into problem.starts) × backend at tolerance, timed and judged (mode "cold"). A backend
// without SolverInfo::mcp gets a record with status not applicable, verdict failed (ListBenchJobs never makes
// such a job; a direct caller is told). InvalidInputError when start is out of range.
ReplayRecord ReplayMcpOne(const McpProblemSet& set, const McpLibraryProblem& problem, std::size_t start,
                          Solver* solver, const std::string& solver_name, const ReplayOptions& options,
                          double tolerance);

// Every problem × start of set on every MCP backend among options.solvers (empty: every registered one), in that
// order (problem, start, backend); each backend gets the settings that reach it (a setting for a box-only backend
// of the selection is not an error here). No tolerance sweep. Throws as CreateReplaySolvers.
ReplayResults ReplayMcpProblemSet(const McpProblemSet& set, const ReplayOptions& options);

// What the run's manifest records of an MCP suite, so shards and resumed runs refuse another suite: FNV-1a 64 (as
// 16 hex digits) over every problem's id, source, tags, expected outcome, bounds, variable units, starts and their
// labels, references (certificate, condition, z) and references_complete, and F at every start (F is code, not
// data: its values name it). Doubles enter by their bits.
std::string McpProblemSetChecksum(const McpProblemSet& set);

// A job's record when the backend was not run (its --backend-budget spent): status time limit, verdict failed,
// the message given, infinite residuals.
ReplayRecord McpNotRunRecord(const McpProblemSet& set, const McpLibraryProblem& problem, std::size_t start,
                             const std::string& solver_name, double tolerance, const std::string& message);

}  // namespace smcbench
