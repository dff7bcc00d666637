#include "bench/kinds/job_list.h"

#include <map>
#include <string>
#include <utility>

#include "bench/replay/floor.h"
#include "solvers/core/number_text.h"

namespace smcbench {
namespace {

BackendCost CostOf(const JobListRequest& request, const std::string& solver) {
  const auto it = request.costs.find(solver);
  return it == request.costs.end() ? BackendCost{} : it->second;
}

const std::vector<std::string>& SolversOf(const JobListRequest& request, const std::string& kind) {
  const auto it = request.kind_solvers.find(kind);
  return it == request.kind_solvers.end() ? request.solvers : it->second;
}

// "suite|problem|solver|mode|tolerance"; "suite|problem@start|..." for a unit problem × start; "stepper".
std::string JobId(const BenchJob& job) {
  if (job.kind == JobKind::kStepper) return "stepper";
  const char* mode = job.kind == JobKind::kSweep   ? "sweep"
                     : job.kind == JobKind::kWarm  ? "warm"
                     : job.kind == JobKind::kFloor ? kFloorSolver
                                                   : "cold";
  if (job.has_start && (job.kind == JobKind::kCold || !job.start_label.empty())) {
    return job.suite_name + "|" + job.problem_id + "@" + job.start_label + "|" + job.solver + "|" + mode + "|" +
           NumberText(job.tolerance);
  }
  return job.suite_name + "|" + job.problem_id + "|" + job.solver + "|" + mode + "|" + NumberText(job.tolerance);
}

// The backend budget in the estimates, as a single run applies it (run_shard.cc, OverBudget): in job order, a
// backend's jobs on a suite run until their estimates add up to the budget, the rest are not run. The floor and the
// stepper are nobody's budget. Only the estimates change (the shards' costs stay machine-independent).
void ApplyBackendBudget(double budget_seconds, std::vector<BenchJob>* jobs) {
  if (!(budget_seconds > 0.0)) return;
  std::map<std::pair<std::size_t, std::string>, double> spent;
  for (BenchJob& job : *jobs) {
    if (job.kind == JobKind::kFloor || job.kind == JobKind::kStepper) continue;
    double& so_far = spent[{job.suite, job.solver}];
    if (so_far >= budget_seconds) {
      job.estimate = kNotRunJobSeconds;
    } else {
      so_far += job.estimate;
    }
  }
}

}  // namespace

std::vector<BenchJob> ListBenchJobs(const std::vector<PlanSuite>& suites, const ReplayOptions& options,
                                    const JobListRequest& request) {
  std::vector<BenchJob> jobs;
  for (std::size_t s = 0; s < suites.size(); ++s) {
    const KindSuite& suite = *suites[s];
    const std::string suite_name = suite.name();
    for (const SuiteJob& spec : suite.Jobs(SolversOf(request, suite.kind()), options, request.floor)) {
      BenchJob job;
      job.index = jobs.size();
      job.kind = spec.kind;
      job.kind_name = spec.kind == JobKind::kCold ? suite.ColdJobName(spec.solver) : ToString(spec.kind);
      job.suite = s;
      job.problem = spec.unit.problem;
      job.has_start = spec.unit.has_start;
      job.start = spec.unit.start;
      job.start_label = spec.unit.start_label;
      job.suite_name = suite_name;
      job.problem_id = spec.unit.problem_id;
      job.solver = spec.solver;
      job.tolerance = spec.tolerance;
      job.cost = suite.EstimateSeconds(spec, options, {}, request.budgets);
      job.estimate = suite.EstimateSeconds(spec, options, CostOf(request, spec.solver), request.budgets);
      job.id = JobId(job);
      jobs.push_back(std::move(job));
    }
  }
  if (request.warm) {
    for (std::size_t s = 0; s < suites.size() && s < request.warm->size(); ++s) {
      const std::vector<WarmSequence>& sequences = (*request.warm)[s];
      for (std::size_t q = 0; q < sequences.size(); ++q) {
        for (const std::string& solver : request.solvers) {
          BenchJob job;
          job.index = jobs.size();
          job.kind = JobKind::kWarm;
          job.kind_name = ToString(job.kind);
          job.suite = s;
          job.problem = q;
          job.suite_name = suites[s]->name();
          job.problem_id = sequences[q].id;
          job.solver = solver;
          job.tolerance = options.tolerance;
          job.cost = EstimateWarmJobSeconds(sequences[q], options, {}, request.budgets);
          job.estimate = EstimateWarmJobSeconds(sequences[q], options, CostOf(request, solver), request.budgets);
          job.id = JobId(job);
          jobs.push_back(std::move(job));
        }
      }
    }
  }
  if (request.stepper) {
    BenchJob job;
    job.index = jobs.size();
    job.kind = JobKind::kStepper;
    job.kind_name = ToString(job.kind);
    // Measured (`bench --suite paper`, its line "time-stepper studies took"): 112 s for the full studies (6
    // refinements) on a 2-core Xeon; 29-30 s for 5 refinements under a job budget on a 2-core AMD EPYC (2026-12,
    // with the step verdict's cached path).
    job.cost = options.repetitions <= 3 ? 3.0 : request.budgets.job_seconds > 0.0 ? 30.0 : 120.0;
    job.estimate = job.cost;
    job.id = JobId(job);
    jobs.push_back(std::move(job));
  }
  ApplyBackendBudget(request.budgets.backend_seconds, &jobs);
  return jobs;
}

}  // namespace smcbench
