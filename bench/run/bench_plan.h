// What a benchmark run is, before anything runs: the suites by name (built, validated and certified), the backends
// with their settings, the options, and the list of jobs (bench/replay/jobs.h). `smcbench bench` and Python's
// smcbench.bench make a plan from a request and run it with RunShard (bench/run/run_shard.h); every bad input is an
// InvalidInputError from MakeBenchPlan, before a caller writes anything.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "bench/kinds/job_list.h"
#include "bench/kinds/problem_filter.h"
#include "bench/kinds/problem_kind.h"
#include "bench/replay/jobs.h"
#include "bench/replay/warm_track.h"
#include "problems/suites/catalogue.h"

namespace smcbench {

// The suites a run knows by name ("all": every one but tiny); anything else must be a problem-set file.
inline constexpr const char* kBenchSuiteNames[] = {"paper", "families", "hard", "siconos", "scale", "tiny", "mcp",
                                                   "avi", "all"};
// What a request without suites runs, and what "all" stands for.
inline constexpr const char* kDefaultBenchSuites[] = {"paper", "families", "hard", "siconos", "mcp", "avi"};
inline constexpr const char* kAllBenchSuites[] = {"paper", "families", "hard", "siconos", "scale", "mcp", "avi"};

// Whether a run includes the time-stepper studies (warm/cold starts, work-precision on the paper's scenes).
enum class StepperStudyChoice {
  kIfSceneSuite = 0,  // only when a suite of the run is captured from the scenes ("paper", or "all")
  kAlways = 1,        // `bench --stepper`
  kNever = 2,         // `bench --no-stepper`
};

// Whether a run of these suites (resolved names) includes the stepper studies under choice: with kIfSceneSuite,
// only when "paper" is among them (the studies run the paper's scenes; a user's problem-set file has none).
bool IncludesStepperStudy(const std::vector<std::string>& suite_names, StepperStudyChoice choice);

// The budgets of a default run, chosen so that the main job (tools/bench.sh) fits in 10 min on a 2-core machine
// (docs/benchmarks.md); `bench --full` sets all three to 0, the full campaign.
inline constexpr double kDefaultJobBudgetSeconds = 1.0;
inline constexpr double kDefaultSequenceBudgetSeconds = 1.0;

struct BenchRequest {
  std::vector<std::string> suites;    // kBenchSuiteNames or problem-set files; empty: kDefaultBenchSuites
  std::vector<std::string> solvers;   // registry names; empty: every registered backend
  std::vector<std::string> settings;  // typed backend options "BACKEND.OPTION=VALUE" (solvers/registry)
  std::string siconos_dir = SuiteRequest().siconos_dir;  // the collection suites hard and siconos read
  double tolerance = 1e-10;           // on the relative and the row-equilibrated natural residual
  double time_limit_seconds = 10.0;   // per solve
  int repetitions = 7;                // timing samples per job (quick: at most 3)
  // Seconds one backend may spend on one suite before its remaining jobs there are cut (0: no limit).
  double backend_budget_seconds = 60.0;
  // Seconds one cold job (cold, sweep, MCP, AVI; 0: no limit) may take: each of its solves runs under
  // min(time limit, this), a solve stopped by it cuts the job (a record of mode "cut", no verdict), and its timed
  // samples stop after half of it. Only matters when below the time limit.
  double job_budget_seconds = kDefaultJobBudgetSeconds;
  // Seconds one warm sequence × backend may take (ReplayWarmSequence's budget; 0: no limit): its untimed pass is
  // cut after the step that spent it (a record of mode "cut": "cut after N of M steps").
  double sequence_budget_seconds = kDefaultSequenceBudgetSeconds;
  bool quick = false;                 // smaller suites, fewer samples, a shorter sweep and stepper study (CI)
  bool polish = true;                 // SolverOptions::polish of every solve (false: time the raw algorithms)
  StepperStudyChoice stepper = StepperStudyChoice::kIfSceneSuite;
  // The warm track (bench/replay/warm_track.h): sequences of the suites that have them (paper, families, a
  // problem-set file; bench/run/warm_sequences.h) replayed in order on every box backend. `bench --no-warm`: off.
  bool warm = true;
  // Measure each backend's job costs with a probe before listing the jobs (CalibrateBackendCosts), so that the
  // estimates (--list-jobs, the progress line's ETA, the shards' balance) are seconds of this machine. Off: guesses.
  bool calibrate = true;
  // Attach certified references to the suites' problems. Off only to list the jobs (their cost does not depend
  // on them): verdicts without references cannot judge forward errors.
  bool certify = true;
  // `bench --problem GLOB` (repeatable; empty: every problem): only the problems whose id matches one of these globs
  // run, in every suite (ProblemFilter); a suite left with none is left out, and with globs the stepper studies run
  // only when asked for (StepperStudyChoice::kAlways). Each glob must match some problem.
  std::vector<std::string> problems;
  // The problem kinds the run knows (bench/kinds/problem_kind.h), in the order their suites come in the plan; a
  // suite name is built by the first kind that Builds it. Empty: BuiltinProblemKinds() (box, MCP, AVI). A caller
  // adds a kind of its own here, and nothing else changes.
  ProblemKinds kinds;
};

struct BenchPlan {
  BenchRequest request;
  std::vector<std::string> suite_names;  // the request's, defaults filled in and "all" expanded
  std::vector<std::string> solvers;      // resolved (never empty), in the order of the jobs
  ReplayOptions options;                 // what each job's KindSuite::Replay is given
  // The suites of every kind, grouped by kind in the order of request.kinds (box, MCP, AVI, ...), each kind's in
  // the order named; BenchJob::suite indexes this list.
  std::vector<PlanSuite> suites;
  bool stepper = false;                  // the job list ends with the stepper job
  // The warm sequences of each suite (indexed as suites: none for a suite without; empty without request.warm).
  std::vector<std::vector<WarmSequence>> warm_sequences;
  std::vector<BenchJob> jobs;            // every job, in the order a single run writes its results
};

// Every check that needs no suite built: suite names (or readable problem-set files), the Siconos folder when its
// suites are named, backend names, settings (tried on a fresh instance of each backend), numbers. InvalidInputError
// naming the field and value; the caller's flag names are its own business.
void CheckBenchRequest(const BenchRequest& request);

// Checks the request (CheckBenchRequest), builds and validates its suites, keeps the problems request.problems
// selects (ProblemFilter, before any reference is computed: a filtered run pays only for what it runs), attaches
// certified references (unless request.certify is false) and lists the jobs. One line per suite (size, time
// taken, certificates; or that the filter left it out) goes to log when given, and one when no chosen backend
// solves the MCP (or the AVI) suite. InvalidInputError for any bad input, including a problem-set file that cannot
// be read or holds no problem, and a --problem glob that matches no problem of the suites (naming it).
BenchPlan MakeBenchPlan(const BenchRequest& request, const std::function<void(const std::string&)>& log = {});

// Each backend's job costs (bench/replay/jobs.h: BackendCost) measured on this machine: one cold job (as a run
// times it, options' repetitions) of a 2 × 2 LCP gives job_seconds, one of a dense 32 × 32 SPD LCP the seconds per
// unit of work (the first job of each, which pays a backend's one-time start, is not counted). The generic sparse
// path gets newton's. A backend whose probe fails keeps the defaults.
std::map<std::string, BackendCost> CalibrateBackendCosts(const ReplayOptions& options,
                                                         const std::vector<std::string>& solvers);

// The plan's suites as results.json and the manifest list them (KindSuite::Describe: name, description, problems,
// checksum; no records), in the plan's order.
std::vector<SuiteResults> PlanSuites(const BenchPlan& plan);

// The options that change what a run measures, as the manifest records them (shards and resumed runs must agree).
nlohmann::json PlanOptionsJson(const BenchPlan& plan);

// The results of the finished jobs in done (by job index), in the job list's order: what `bench` writes to
// results.json, without the command line.
BenchResults PlanResults(const BenchPlan& plan, const std::map<std::size_t, JobLine>& done);

}  // namespace smcbench
