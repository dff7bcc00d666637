// A `bench` run cut into jobs (problem × backend × tolerance × mode, plus the time-stepper study as one job), so
// that Slurm array tasks or GNU parallel can each run a deterministic share (--shard K/N), every finished job is on
// disk at once (one JSON line, flushed: a killed shard keeps its work and --resume runs only what is missing), and
// `smcbench merge` puts the shards back together into the results.json of a single run, refusing to mix builds,
// suites or options.
//
// A run folder holds manifest.json (what the run is: build, options, suites with their checksums, the whole job
// list and this folder's shard) and records.jsonl (one line per finished job, in the order they finished).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/replay/avi_replay.h"
#include "bench/replay/mcp_replay.h"
#include "bench/replay/replay.h"
#include "bench/replay/results_io.h"

namespace smcbench {

// What one job runs. The kind of problem is not a job kind: a cold, sweep or floor job runs whatever its suite's
// problem kind replays (bench/kinds/problem_kind.h).
enum class JobKind {
  kCold,     // unit × backend at the run's tolerance (mode "cold"): a box problem, an MCP × start, an AVI, ...
  kSweep,    // problem × backend at one tolerance of kSweepTolerances (mode "sweep")
  kStepper,  // the time-stepper studies (warm/cold starts, work-precision), one job
  kWarm,     // warm sequence × backend at the run's tolerance (ReplayWarmSequence, mode "warm")
  kFloor,    // one factorization of the unit's matrix, timed as a cold solve (bench/replay/floor.h)
};
const char* ToString(JobKind kind);

struct BenchJob {
  std::size_t index = 0;    // position in the run's job list (the order of a single run's results)
  JobKind kind = JobKind::kCold;
  std::size_t suite = 0;    // index of the suite in the run (not used by kStepper)
  std::size_t problem = 0;  // index of the problem in its suite (kWarm: of the sequence in the suite's sequences)
  bool has_start = false;   // the unit is problem × start (an MCP's)
  std::size_t start = 0;    // with has_start: index of the start in McpLibraryProblem::starts
  std::string suite_name, problem_id, solver;
  std::string start_label;  // with has_start: McpLibraryProblem::start_labels[start]
  // The manifest's "kind" (ToString(kind), or for a cold job its suite's KindSuite::ColdJobName: "mcp", "avi" and
  // "generic-sparse" as manifests wrote them before the problem kinds); read back as written.
  std::string kind_name;
  double tolerance = 0.0;
  // Estimated seconds for balancing shards (EstimateJobSeconds with BackendCost's defaults): the same on every
  // machine, so every shard of a run computes the same shards.
  double cost = 0.0;
  // Estimated seconds on this machine (EstimateJobSeconds with JobListRequest::costs, measured by a probe): what
  // `--list-jobs` prints and the progress line's ETA scales. Not in the manifest (read back: cost).
  double estimate = 0.0;
  // "suite|problem|solver|mode|tolerance" (tolerance in shortest round-trip form): the job's identity across
  // processes, machines and resumed runs; "suite|problem@start|solver|cold|tolerance" for an MCP job (start: its
  // label); "suite|sequence|solver|warm|tolerance" for a warm job; "stepper" for the stepper job.
  std::string id;
};

// What the manifest and `bench --list-jobs` call a job's kind: BenchJob::kind_name, or ToString(kind) when unset.
std::string JobKindName(const BenchJob& job);

// The name the generic sparse path's records carry as their backend.
inline constexpr const char* kGenericSparsePath = "newton-sparse-path";

// What one backend's jobs cost, for the estimates: a job's fixed seconds (its warm-up and minimum samples of a
// tiny solve, an external adapter's probe in its worker, judging, the record) and the seconds of one solve per
// unit of work m·(m + nnz(M)) (a dense pivoting method's m³ on a dense M; m·nnz on a sparse one). The defaults are
// a guess; bench/run/bench_plan.h's CalibrateBackendCosts measures them with a probe.
struct BackendCost {
  double job_seconds = 2e-3;
  double seconds_per_unit = 1e-9;
};

// The seconds the budgets allow (bench/run/bench_plan.h: BenchRequest; 0: no limit), for the estimates.
struct JobBudgets {
  double job_seconds = 0.0;       // one cold, sweep, MCP or AVI job: its solves under min(time limit, this)
  double sequence_seconds = 0.0;  // one warm sequence × backend
  // One backend on one suite: past it the backend's remaining jobs there are not run (bench/run/run_shard.h), so
  // ListBenchJobs estimates them at kNotRunJobSeconds.
  double backend_seconds = 0.0;
};

// The estimate of a job its backend's budget stops before it runs: a record written, nothing solved.
inline constexpr double kNotRunJobSeconds = 1e-4;

// Estimated seconds of one job: one solve at cost.seconds_per_unit·m·(m + nnz(M)) under the time limit (and the
// job budget), the job at cost.job_seconds plus a warm-up solve plus its samples beyond a tiny solve's (each
// sample at least min_sample_seconds, together at most max_seconds_per_pair, or half the job budget); a solve that
// reaches the limit is not repeated. The stepper job is a fixed 120 s as measured (30 s with a job budget, which
// shortens it; quick: 3 s). With BackendCost's defaults it balances shards (BenchJob::cost); with a backend's
// measured costs it is what `--list-jobs` adds up and what the progress line's ETA scales (BenchJob::estimate);
// never changes what runs.
double EstimateJobSeconds(const LibraryProblem& problem, const ReplayOptions& options, JobKind kind,
                          const BackendCost& cost = {}, const JobBudgets& budgets = {});
// The same for one MCP job: 20 Newton steps, each cost.seconds_per_unit·n·(n + nnz(J)) with nnz(J) taken as n²
// (dense J) or 10·n (sparse J; not evaluated for an estimate).
double EstimateMcpJobSeconds(const McpLibraryProblem& problem, const ReplayOptions& options,
                             const BackendCost& cost = {}, const JobBudgets& budgets = {});
// The same for one AVI job: one solve of the reduction (N = n + m + p rows, dense) at 2N³ units, plus as much again
// for SolveAvi's building of it and its verdict.
double EstimateAviJobSeconds(const AviLibraryProblem& problem, const ReplayOptions& options,
                             const BackendCost& cost = {}, const JobBudgets& budgets = {});
// The same for one warm job: an untimed and the timed passes of every step, each step a cold solve's guess (at
// least 1 µs, a call's fixed cost), plus cost.job_seconds once; with a sequence budget, a pass longer than it is
// cut at the budget, one longer than half of it is the only pass, and the timed passes end inside it.
double EstimateWarmJobSeconds(const WarmSequence& sequence, const ReplayOptions& options,
                              const BackendCost& cost = {}, const JobBudgets& budgets = {});

struct JobListRequest {
  std::vector<std::string> solvers;  // resolved names (never empty)
  bool stepper = false;              // add the stepper job (last)
  // The backends of the jobs of each problem kind (KindSuite::kind(); the plan asks ProblemKind::Backends, e.g. the
  // names whose backend has SolverInfo::mcp for "mcp"); a kind not named here: solvers.
  std::map<std::string, std::vector<std::string>> kind_solvers;
  // The warm sequences of each box suite (indexed as the suites; null or shorter: none), run on every backend of
  // solvers (warm_track.h).
  const std::vector<std::vector<WarmSequence>>* warm = nullptr;
  // Each backend's costs for the estimates (a backend not named: BackendCost's defaults), and the budgets.
  std::map<std::string, BackendCost> costs;
  JobBudgets budgets;
  // Add one floor job (solver kFloorSolver, bench/replay/floor.h) per box problem, per MCP problem × start and per
  // AVI problem that has jobs, after that problem's (or suite's) backend jobs.
  bool floor = false;
};

// Every job of a run: ListBenchJobs (bench/kinds/job_list.h).

// The shard (0-based, < shards) of every job: longest estimated job first (ties in the order of a stable hash of
// the job's id, FNV-1a 64), each to the shard with the least estimated work so far (ties: the lowest shard).
// Deterministic: the same job list gives the same shards on every machine.
std::vector<int> AssignShards(const std::vector<BenchJob>& jobs, int shards);

// FNV-1a 64 of text as 16 hex digits.
std::string StableHashHex(const std::string& text);

// "K/N" (1 ≤ K ≤ N) → {K−1, N}. InvalidInputError naming --shard otherwise.
std::pair<int, int> ParseShard(const std::string& text);

// How many `bench` processes run on this host now: each process holds a file named by its pid in a per-user
// folder (SMCBENCH_ACTIVITY_DIR, default <tmp>/smcbench-activity-<uid>); Count() counts those whose process is
// alive (removing stale ones). A Slurm node's array tasks, or GNU parallel's, see each other this way.
class HostActivity {
 public:
  HostActivity();
  ~HostActivity();
  HostActivity(const HostActivity&) = delete;
  HostActivity& operator=(const HostActivity&) = delete;
  int Count() const;
  const std::string& host() const { return host_; }

 private:
  std::string dir_, own_file_, host_;
};

// One finished job as records.jsonl holds it.
struct JobLine {
  std::size_t job = 0;
  std::string id;
  std::string host;
  int concurrent_jobs = 0;
  // Wall seconds the job took here (judging and the record included): what --list-jobs' estimate is checked
  // against, per backend and kind (docs/benchmarks.md, "Time budgets"). NaN in lines written before it existed.
  double seconds = kNaN;
  bool skipped = false;  // a sweep job of a backend past its --backend-budget: no record
  bool has_record = false;
  ReplayRecord record;
  bool has_stepper = false;
  StepperStudy stepper;
  bool has_warm = false;  // a warm job's record (has_record false)
  WarmRecord warm;
};
nlohmann::json JobLineToJson(const JobLine& line);

// Appends one line per finished job to a records.jsonl and flushes it (fsync is not needed: a killed process's
// written lines are in the page cache).
class JobLineWriter {
 public:
  explicit JobLineWriter(const std::string& path);  // opened for appending; InvalidInputError if it cannot
  ~JobLineWriter();
  JobLineWriter(const JobLineWriter&) = delete;
  JobLineWriter& operator=(const JobLineWriter&) = delete;
  void Write(const JobLine& line);

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

// Reads a records.jsonl: every complete line; a last line without its newline (a process killed while writing it)
// is dropped, and with truncate_partial the file is cut back to the last complete line so appending continues it.
// A malformed complete line is an InvalidInputError naming the file and line. A missing file is no lines.
std::vector<JobLine> ReadJobLines(const std::string& path, bool truncate_partial);

// What a run is, for comparing runs and shards: manifest.json without the shard and the machine.
struct RunManifest {
  std::string command;
  nlohmann::json environment;     // BenchEnvironment of the process that started the folder
  nlohmann::json options;         // the options that change what is measured (BenchRunOptions)
  // suite, description, problems, checksum; no records. The plan's suites in its order (BenchJob::suite).
  std::vector<SuiteResults> suites;
  std::vector<BenchJob> jobs;     // the whole run's job list
  int shard = 0, shards = 1;      // this folder's share (0-based)
  std::vector<int> job_shard;     // AssignShards(jobs, shards)
};
nlohmann::json RunManifestToJson(const RunManifest& manifest);
RunManifest RunManifestFromJson(const nlohmann::json& document, const std::string& name_for_errors);
void WriteRunManifest(const RunManifest& manifest, const std::string& dir);  // dir/manifest.json
RunManifest ReadRunManifest(const std::string& dir);  // InvalidInputError naming the file

// The first difference that forbids putting the two runs' results together (other build, options, suites or their
// checksums, job list), as one line "<what>: '<a>' vs '<b>'", or empty when they may be merged.
std::string ManifestMismatch(const RunManifest& a, const RunManifest& b);

// The results of the finished jobs in lines, in the job list's order (what a single run of the same jobs writes):
// suites as the manifest lists them, records of cold and generic jobs, sweep records, the stepper study when its
// job finished, warm records. Lines for jobs not in the list are ignored.
BenchResults AssembleResults(const RunManifest& manifest, const std::map<std::size_t, JobLine>& lines);

struct MergeReport {
  std::vector<std::string> missing;     // ids of jobs no folder finished
  std::vector<std::string> duplicated;  // ids finished in more than one folder (or twice): the first is kept
  std::vector<std::string> hosts;       // hosts the records came from
  BenchResults results;
  nlohmann::json environment;           // the first folder's, with "hosts"
};
// Reads dir/manifest.json and dir/records.jsonl of every folder and puts them together. InvalidInputError with one
// line ("merge: <dir>: <what differs>") when two folders come from different builds, options, suites or job lists.
MergeReport MergeRunFolders(const std::vector<std::string>& dirs);

}  // namespace smcbench
