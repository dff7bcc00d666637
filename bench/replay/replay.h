// The replay benchmark behind `smcbench bench`: every problem of a ProblemSet on every chosen backend, with
// warm-up and repetitions, judged by the one verdict (solvers/core/verdict.h: expected outcome, both residuals
// recomputed from z, forward error against the problem's certified reference); plus the measured dimensions the
// report plots (tolerance sweep of iterative backends, warm vs cold starts along trajectories). Results are plain
// structs, written as JSON and CSV (results_io.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "problems/library/problem_set.h"
#include "solvers/core/solver.h"

namespace smcbench {

struct ReplayOptions {
  std::vector<std::string> solvers;  // registry names; empty = every registered backend
  // Typed backend options "BACKEND.OPTION=VALUE" (as `smcbench solve --set`), applied to that backend.
  std::vector<std::string> settings;
  double tolerance = 1e-10;          // on the relative and the row-equilibrated natural residual
  // SolverOptions::polish: false times the raw algorithms (no exact polish of their answers in the base layer).
  bool polish = true;
  // The timed solves run through one solve session per problem × backend (solvers/core/session.h). Off (the
  // default): every solve runs the backend's own algorithm, what the report compares; on: each repeat may be answered
  // by the previous answer's active set (what a time-stepper gets), so a "cold" record becomes "cached" (TimeSolves).
  bool reuse_active_set = false;
  double time_limit_seconds = 10.0;  // per solve; a backend over it gets kTimeLimit (and is timed once)
  int repetitions = 7;               // timing samples per problem × backend (median and spread over these)
  // Each sample repeats the solve until it lasts at least this long (so a small solve is not timed by a clock read
  // that costs about as much: docs/benchmarks.md); the per-solve time is the sample divided by the count.
  double min_sample_seconds = 2e-4;
  double max_seconds_per_pair = 2.0;  // stop sampling a problem × backend after this much time (≥ 1 sample)
  // Tolerance sweep (the report's tolerance ladder and speed against error): on this many problems of the set,
  // evenly spaced (SweepProblemIndices), every backend is run at each of kSweepTolerances. 0 disables it.
  int tolerance_sweep_problems = 16;
  // Called after each problem × start × backend of ReplayMcpProblemSet with (done, total); for a progress bar.
  std::function<void(std::size_t done, std::size_t total, const std::string& what)> progress;
};

// One problem × backend.
struct ReplayRecord {
  std::string suite;
  std::string problem;  // LibraryProblem::id
  // The label of the starting point an MCP job started from (McpLibraryProblem::start_labels): a problem × start is
  // one MCP instance. Empty for box-MLCP records (they start cold from Π(0)) and in results written before MCPs.
  std::string start;
  std::string solver;
  int size = 0;
  bool sparse = false;
  std::string tags;     // comma-separated LibraryProblem::tags
  ExpectedOutcome expected = ExpectedOutcome::kUnknown;
  SolveStatus status = SolveStatus::kNotRun;
  std::string message;
  Verdict verdict = Verdict::kFailed;
  int iterations = 0;
  // The residuals the verdict recomputed from z (Judgement::residual; the backend's own when it returned no z).
  double residual_abs = 0.0;
  double residual_rel = 0.0;
  double residual_scaled = 0.0;  // of the row-equilibrated problem, relative to 1 + ‖z‖∞
  // ‖z − z*‖∞, that over max(1, ‖z*‖∞), and the allowance it is judged against; NaN unless the problem's
  // reference is unique (ReferenceSolution::unique) and the backend returned z.
  double forward_error = kNaN;
  double forward_error_rel = kNaN;
  double forward_allowance = kNaN;
  std::string certificate = "none";  // ToString of the problem's reference certificate
  double reference_radius = kNaN;     // its ReferenceSolution::proved_radius (NaN: not proved by an enclosure)
  bool reference_proved_unique = false;  // its ReferenceSolution::proved_unique
  double tolerance = 0.0;
  // Per-solve wall time over the samples (seconds): median, min, max, and the median absolute deviation.
  double time_median = 0.0;
  double time_min = 0.0;
  double time_max = 0.0;
  double time_mad = 0.0;
  int samples = 0;
  std::int64_t solves_per_sample = 0;
  // "cold"; "sweep" for tolerance-sweep records; "cached" for a record whose timed solves could not all start from
  // the same state (TimeSolves): the report keeps it out of its cold tables.
  std::string mode = "cold";
  // The timed solves went through an isolation worker, so the times include its inter-process round trip
  // (far more than a small solve: solvers/siconos/README.md, "Isolation"):
  // a siconos-* backend with isolate=always, or a problem whose probe crashed or ran out of time (it is never
  // solved in process). False for every backend of ours, and for siconos-* ones by default: the untimed warm-up
  // solve is the probe, the timed ones run in process (detail "in_process" of solvers/siconos/siconos_solver.h).
  bool timed_in_worker = false;
  // An external library's own return code for this answer, 0 meaning its success (SolveResult::backend_code):
  // what a program calling that library trusts, before our base layer re-judged the answer (its polish may upgrade a
  // short stop, its residual check downgrade a false success). Empty for our backends and when the library was not
  // called (refused, crashed, timed out); the report's audit of claims then takes `status`.
  std::optional<int> backend_code;
  // Where it ran (gethostname) and the most bench jobs that ran on that host at once while it ran, itself included
  // (HostActivity, bench/replay/jobs.h): times measured beside other jobs disturb each other. Empty / 0 in older
  // results that did not record them.
  std::string host;
  int concurrent_jobs = 0;
};

struct ReplayResults {
  std::vector<ReplayRecord> records;        // mode "cold": one per problem × backend
  std::vector<ReplayRecord> sweep;          // mode "sweep": every backend at each of kSweepTolerances
  // Mode "floor": one per problem (MCP: problem × start), the time of one factorization of its matrix measured with
  // the cold protocol (bench/replay/floor.h). Never a backend: kept apart from records so no count or ranking sees
  // it; empty in results written before the floor (the report then says it was not measured).
  std::vector<ReplayRecord> floor;
};

// The tolerances of the tolerance sweep (ReplayOptions::tolerance_sweep_problems), loosest first: the report's
// tolerance ladder, from a loose engineering tolerance to near the limit of double precision.
inline constexpr double kSweepTolerances[] = {1e-3, 1e-6, 1e-9, 1e-12};

// Which problems of a set of `problems` the tolerance sweep runs on: all when sweep_problems ≥ problems, else
// sweep_problems of them evenly spaced (the middle of each of as many equal slices), so that the ladder sees the
// whole suite (its sizes and families) rather than its first problems. Empty when sweep_problems ≤ 0.
std::vector<std::size_t> SweepProblemIndices(std::size_t problems, int sweep_problems);

// The backends by name (empty: every registered one) with options.settings applied, in the order of *names (filled
// in when empty). InvalidInputError for an unknown name or a rejected setting (a setting must reach one of the
// backends: solvers/registry/backend_settings.h).
std::vector<std::unique_ptr<Solver>> CreateReplaySolvers(const ReplayOptions& options, std::vector<std::string>* names);

// The names among names (empty: every registered backend) whose SolverInfo has the capability (e.g.
// &SolverInfo::mcp: the backends of the MCP jobs), in the same order. InvalidInputError for an unknown name.
std::vector<std::string> BackendsWith(const std::vector<std::string>& names, bool SolverInfo::*capability);

// The options of a timed replay solve at tolerance: the run's time limit and polish, the solver's own clock off
// (the replay times from outside, around many solves).
SolverOptions ReplaySolverOptions(const ReplayOptions& options, double tolerance);

// One problem × backend: cold (mode "cold", at options.tolerance) or one step of the tolerance sweep (mode "sweep",
// at tolerance, at most 3 samples), timed (TimeSolves) and judged: what one job of a run (bench/run/run_shard.h)
// runs. A backend that fails on the problem is a record, never an exception.
ReplayRecord ReplayOne(const ProblemSet& set, const LibraryProblem& problem, Solver* solver,
                       const std::string& solver_name, const ReplayOptions& options, const std::string& mode,
                       double tolerance);

// Times one solve configuration: repeated solves of problem with solver/options through one session into *result,
// honouring min_sample_seconds, repetitions and max_seconds (writes median/min/max/mad/samples/solves_per_sample and
// timed_in_worker). An untimed warm-up solve comes first: it sizes the workspace and, for a siconos-* backend, is
// the probe in its isolation worker, after which the timed solves of that problem run in process.
// Cold means cold: every timed solve starts from the state the first one did. A backend that kept nothing after
// the warm-up (ForgetWarmState: nothing_remembered) is timed back to back; for one that keeps something (Siconos'
// mlcp_direct_* cache, auto's choice after a fallback) the session's ForgetWarmState runs untimed before each timed
// solve, which is then timed alone (bench/replay/sample_times.h). A record whose solves could not start cold (a
// backend that cannot forget, or replay.reuse_active_set on) has mode "cached" instead of "cold".
void TimeSolves(Solver* solver, const BoxMLCP& problem, const SolverOptions& options, const ReplayOptions& replay,
                SolveResult* result, ReplayRecord* record);

}  // namespace smcbench
