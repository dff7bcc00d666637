#include "bench/run/run_shard.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <utility>

#include "bench/replay/stepper_study.h"
#include "bench/replay/warm_track.h"
#include "solvers/reference/certify.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The jobs of one shard, run in order with one backend instance per name (the timed solves are cold sessions, so
// sharing an instance across problems does not change an answer), the budget counted per suite and backend.
class ShardRunner {
 public:
  ShardRunner(const BenchPlan& plan, BenchProgress* progress)
      : plan_(plan), progress_(progress), options_(BudgetedOptions(plan)) {}

  JobLine Run(const BenchJob& job) {
    const auto job_start = Clock::now();
    JobLine line = RunJob(job);
    line.seconds = SecondsSince(job_start);
    return line;
  }

  std::vector<BudgetSkip> Skipped() const {
    std::vector<BudgetSkip> out;
    for (const auto& [key, count] : skipped_) {
      const KindSuite& suite = *plan_.suites.at(key.first);
      BudgetSkip skip;
      skip.solver = key.second;
      skip.skipped = count;
      skip.suite = suite.name();
      skip.units = suite.UnitsNoun();
      skip.problems = suite.Units().size();
      out.push_back(std::move(skip));
    }
    return out;
  }

  // The run's options with the job budget applied: each solve under min(time limit, budget), sampling stopped
  // after half the budget.
  static ReplayOptions BudgetedOptions(const BenchPlan& plan) {
    ReplayOptions o = plan.options;
    const double budget = plan.request.job_budget_seconds;
    if (budget > 0.0) {
      o.time_limit_seconds = std::min(o.time_limit_seconds, budget);
      o.max_seconds_per_pair = std::min(o.max_seconds_per_pair, 0.5 * budget);
    }
    return o;
  }

 private:
  // One job: its record (or the warm sequence's, the stepper studies), the backend's budget spent.
  JobLine RunJob(const BenchJob& job) {
    const int before = activity_.Count();
    JobLine line;
    line.job = job.index;
    line.id = job.id;
    line.host = activity_.host();
    if (job.kind == JobKind::kStepper) {
      line.has_stepper = true;
      line.stepper = RunStepper();
    } else if (job.kind == JobKind::kWarm) {
      line.has_warm = true;
      if (OverBudget(job)) {
        // Not counted in skipped_, whose counts are the suite's problems (a sequence is not one of them).
        line.warm.record = NotRunRecord(job);
        line.warm.source = plan_.warm_sequences.at(job.suite).at(job.problem).source;
      } else {
        const auto start = Clock::now();
        const WarmSequence& sequence = plan_.warm_sequences.at(job.suite).at(job.problem);
        line.warm = ReplayWarmSequence(sequence, SolverFor(job.solver), job.solver, plan_.options, job.tolerance,
                                       nullptr, plan_.request.sequence_budget_seconds);
        spent_[{job.suite, job.solver}] += SecondsSince(start);
      }
    } else if (OverBudget(job)) {
      line.skipped = job.kind == JobKind::kSweep;
      line.has_record = !line.skipped;
      if (line.has_record) line.record = NotRunRecord(job);
      if (line.has_record) ++skipped_[{job.suite, job.solver}];  // problems; skipped sweep rungs are not problems
    } else {
      const auto start = Clock::now();
      line.has_record = true;
      line.record = Replay(job);
      spent_[{job.suite, job.solver}] += SecondsSince(start);
      if (JobBudgetLimitsSolves() && line.record.status == SolveStatus::kTimeLimit) CutByJobBudget(&line.record);
    }
    line.concurrent_jobs = std::max(before, activity_.Count());
    if (line.has_record) line.record.host = line.host, line.record.concurrent_jobs = line.concurrent_jobs;
    if (line.has_warm) line.warm.record.host = line.host, line.warm.record.concurrent_jobs = line.concurrent_jobs;
    return line;
  }

  bool JobBudgetLimitsSolves() const {
    const double budget = plan_.request.job_budget_seconds;
    return budget > 0.0 && budget < plan_.options.time_limit_seconds;
  }

  // A record whose solve the job budget stopped: no verdict (it might have been solved within the time limit).
  void CutByJobBudget(ReplayRecord* r) const {
    char message[240];
    std::snprintf(message, sizeof message, "cut after 0 of 1 solves: job budget of %g s spent (--job-budget; the "
                  "time limit is %g s)", plan_.request.job_budget_seconds, plan_.options.time_limit_seconds);
    r->mode = kCutMode;
    r->status = SolveStatus::kNotRun;
    r->message = message;
  }

  bool OverBudget(const BenchJob& job) const {
    if (job.kind == JobKind::kFloor) return false;  // a factorization: never a backend's budget
    const auto it = spent_.find({job.suite, job.solver});
    const double budget = plan_.request.backend_budget_seconds;
    return budget > 0.0 && it != spent_.end() && it->second >= budget;
  }

  Solver* SolverFor(const std::string& name) {
    auto it = solvers_.find(name);
    if (it == solvers_.end()) {
      if (name == kGenericSparsePath) {  // the baseline the registry defines (CreateGenericSparsePathSolver)
        it = solvers_.emplace(name, CreateGenericSparsePathSolver()).first;
      } else {
        ReplayOptions o = plan_.options;
        std::vector<std::string> names{name};
        o.settings = SettingsReaching(name, plan_.options.settings);  // checked against the whole selection
        it = solvers_.emplace(name, std::move(CreateReplaySolvers(o, &names).front())).first;
      }
    }
    return it->second.get();
  }

  // A cold, sweep or floor job, replayed by its suite's kind.
  ReplayRecord Replay(const BenchJob& job) {
    const KindSuite& suite = *plan_.suites.at(job.suite);
    if (job.kind == JobKind::kFloor) return suite.Floor(job, plan_.options);
    return suite.Replay(job, SolverFor(job.solver), options_);
  }

  std::string NotRunMessage(const BenchJob& job) const {
    char message[200];
    std::snprintf(message, sizeof message, "not run: %s spent its budget of %g s on suite %s (--backend-budget)",
                  job.solver.c_str(), plan_.request.backend_budget_seconds, job.suite_name.c_str());
    return message;
  }

  // A job of a backend past its budget: no verdict, mode "cut".
  ReplayRecord NotRunRecord(const BenchJob& job) const {
    ReplayRecord r = UnjudgedRecord(job);
    r.mode = kCutMode;
    r.status = SolveStatus::kNotRun;
    return r;
  }

  ReplayRecord UnjudgedRecord(const BenchJob& job) const {
    if (job.kind != JobKind::kWarm) return plan_.suites.at(job.suite)->NotRun(job, NotRunMessage(job));
    const WarmSequence& sequence = plan_.warm_sequences.at(job.suite).at(job.problem);
    ReplayRecord r;
    r.suite = sequence.suite;
    r.problem = sequence.id;
    r.solver = job.solver;
    r.size = sequence.steps.front().size();
    r.sparse = sequence.steps.front().sparse();
    r.expected = sequence.steps.front().expected;
    r.mode = "warm";
    r.status = SolveStatus::kTimeLimit;
    r.message = NotRunMessage(job);
    r.verdict = Verdict::kFailed;
    r.residual_abs = r.residual_rel = r.residual_scaled = kInf;
    r.tolerance = job.tolerance;
    return r;
  }

  StepperStudy RunStepper() {
    StepperStudyOptions so;
    so.solvers = plan_.request.solvers;
    if (so.solvers.empty()) {
      // External adapters run each solve in a child process: along 10⁴-step trajectories that is minutes; they
      // are timed on the replay suites instead (name them with --solver to include them here).
      for (auto n : SolverNames()) {
        if (n.rfind("siconos-", 0) != 0) so.solvers.emplace_back(n);
      }
    }
    if (plan_.request.job_budget_seconds > 0.0) {
      // Budgeted (not --full): the work-precision sweep stops one halving of h earlier, which halves the study (each
      // halving doubles the steps of every run); the diagrams keep five points per backend.
      so.refinements = std::min(so.refinements, kBudgetedStepperRefinements);
    }
    if (plan_.request.quick) {
      so.warm_scenes = {"sign", "galias-yu-2007"};
      so.precision_scenes = {"galias-yu-2007"};
      so.refinements = 3;
      so.min_seconds = 0.002;
    }
    if (progress_) so.progress = [this](const std::string& what) { progress_->Phase(what); };
    so.polish = plan_.options.polish;
    // Per-step forward error of s in the work-precision runs: each step's one-step problem certified from the
    // backend's own answer (the cheapest candidate: usually its active set verifies at once). Its cost is
    // reported, since it adds to the job's time.
    double certify_seconds = 0.0;
    std::int64_t certified_steps = 0;
    so.step_forward_error = [&](const BoxMLCP& problem, const Vector& z) {
      const auto start = Clock::now();
      const ReferenceSolution reference = Certify(problem, {z});
      certify_seconds += SecondsSince(start);
      ++certified_steps;
      return reference.unique() ? (z - reference.z).cwiseAbs().maxCoeff() : kNaN;
    };
    if (progress_) progress_->Message("time-stepper studies");
    const auto stepper_start = Clock::now();
    StepperStudy study = RunStepperStudy(so);
    char line[160];
    std::snprintf(line, sizeof line, "time-stepper studies took %.1f s, of which %.1f s certifying %lld steps",
                  SecondsSince(stepper_start), certify_seconds, static_cast<long long>(certified_steps));
    if (progress_) progress_->Message(line);
    return study;
  }

  const BenchPlan& plan_;
  BenchProgress* progress_;
  const ReplayOptions options_;  // plan_.options with the job budget applied (BudgetedOptions)
  HostActivity activity_;
  std::map<std::string, std::unique_ptr<Solver>> solvers_;
  std::map<std::pair<std::size_t, std::string>, double> spent_;
  std::map<std::pair<std::size_t, std::string>, int> skipped_;
};

std::string JobLabel(const BenchJob& job) {
  if (job.kind == JobKind::kStepper) return "time-stepper studies";
  const std::string start = job.start_label.empty() ? "" : "@" + job.start_label;
  return job.suite_name + " " + job.problem_id + start + " " + job.solver;
}

}  // namespace

ShardSummary RunShard(const BenchPlan& plan, ShardSelection shard, const std::set<std::size_t>& done,
                      const JobLineSink& sink, BenchProgress* progress) {
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    throw InvalidInputError("bench: shard " + std::to_string(shard.index + 1) + " of " + std::to_string(shard.count) +
                            " does not exist (1 <= K <= N)");
  }
  const std::vector<int> job_shard = AssignShards(plan.jobs, shard.count);
  std::vector<const BenchJob*> todo;
  for (const BenchJob& job : plan.jobs) {
    if (job_shard[job.index] == shard.index && !done.count(job.index)) todo.push_back(&job);
  }
  ShardRunner runner(plan, progress);
  ShardSummary summary;
  double estimated_total = 0.0, estimated_done = 0.0;
  for (const BenchJob* job : todo) estimated_total += job->estimate;
  for (const BenchJob* job : todo) {
    const JobLine line = runner.Run(*job);
    if (sink) sink(line);
    ++summary.jobs_run;
    estimated_done += job->estimate;
    if (progress) progress->JobFinished(summary.jobs_run, todo.size(), JobLabel(*job), estimated_done, estimated_total);
  }
  summary.skipped = runner.Skipped();
  return summary;
}

}  // namespace smcbench
