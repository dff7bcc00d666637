// Runs the jobs of a benchmark plan (bench/run/bench_plan.h) one at a time: each timed, judged and handed to a sink
// as it finishes (`bench` appends it to records.jsonl at once, so a killed run keeps its work). A backend past its
// budget on a suite gets its remaining jobs there recorded as not run. Which process runs a job never changes its
// answer: a job's record depends only on the plan and the job.
#pragma once

#include <cstddef>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "bench/run/bench_plan.h"

namespace smcbench {

// Told what a run is doing, for a progress bar or a log. Every method may be left as is (nothing).
class BenchProgress {
 public:
  virtual ~BenchProgress() = default;
  // After each job: finished of total jobs of this call, what the job was ("suite problem[@start] backend"), and
  // the estimated seconds (BenchJob::estimate) of the jobs finished and of all jobs of this call (for an ETA).
  virtual void JobFinished(std::size_t /*finished*/, std::size_t /*total*/, const std::string& /*what*/,
                           double /*estimated_done*/, double /*estimated_total*/) {}
  // A phase inside one long job (the time-stepper studies' scenes): what runs now.
  virtual void Phase(const std::string& /*what*/) {}
  // One line for the user (what the stepper study took).
  virtual void Message(const std::string& /*line*/) {}
};

// The work-precision refinements of the time-stepper studies in a run with a job budget (StepperStudyOptions has 6:
// h down to h/32; 5 stop at h/16 and take half the time).
inline constexpr int kBudgetedStepperRefinements = 5;

// Which share of a plan's jobs a process runs: shard index (0-based) of count (AssignShards, bench/replay/jobs.h).
struct ShardSelection {
  int index = 0;
  int count = 1;
};

// A backend that spent its budget on a suite: how many of the suite's jobs for it were not run (sweep jobs
// included), of how many units (KindSuite::Units: problems, or an MCP's problem x start).
struct BudgetSkip {
  std::string suite, solver;
  std::string units = "problems";  // what the units are (KindSuite::UnitsNoun)
  int skipped = 0;
  std::size_t problems = 0;
};

struct ShardSummary {
  std::size_t jobs_run = 0;          // jobs of the shard not in done, each given to the sink
  std::vector<BudgetSkip> skipped;   // by suite, then backend
};

using JobLineSink = std::function<void(const JobLine& line)>;

// Runs every job of plan in shard that is not in done (job indices), in the job list's order, and gives each
// finished job's line to sink. A backend whose jobs on a suite took plan.request.backend_budget_seconds (when > 0,
// counted in this call) gets its remaining cold and warm jobs there as cut records (mode "cut", status not_run, a
// message naming the budget: no verdict) and its sweep jobs skipped (a line without record). With
// plan.request.job_budget_seconds below the time limit, a cold, sweep, MCP or AVI job's solves run under it and a
// solve it stopped cuts the job the same way; warm jobs get plan.request.sequence_budget_seconds
// (ReplayWarmSequence). InvalidInputError for a shard outside the count.
ShardSummary RunShard(const BenchPlan& plan, ShardSelection shard, const std::set<std::size_t>& done,
                      const JobLineSink& sink, BenchProgress* progress = nullptr);

}  // namespace smcbench
