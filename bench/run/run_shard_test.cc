// Running a plan's jobs: known verdicts on the tiny suite, the budget, resuming with the jobs done, shards that
// cover every job exactly once, answers that do not depend on which shard ran a job, and warm jobs.
#include "bench/run/run_shard.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "bench/run/warm_sequences.h"
#include "bench/kinds/box_kind.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;

// The tiny suite (4 planted-solution P-matrix problems and one infeasible LCP) on two exact backends and psor,
// one sample per job: the answers, not the times, are under test.
BenchPlan TinyPlan() {
  BenchRequest request;
  request.suites = {"tiny"};
  request.solvers = {"lemke", "enum", "psor"};
  request.quick = true;
  request.repetitions = 1;
  request.backend_budget_seconds = 0.0;
  return MakeBenchPlan(request);
}

// Every line a run gives its sink, by job index; a job given twice fails the test.
std::map<std::size_t, JobLine> RunLines(const BenchPlan& plan, ShardSelection shard, const std::set<std::size_t>& done,
                                        ShardSummary* summary = nullptr) {
  std::map<std::size_t, JobLine> lines;
  const ShardSummary s = RunShard(plan, shard, done, [&](const JobLine& line) {
    EXPECT_TRUE(lines.emplace(line.job, line).second) << "job " << line.job << " given twice";
  });
  if (summary) *summary = s;
  return lines;
}

// What a job's record says about the answer (never times, samples or the host).
void ExpectSameAnswer(const ReplayRecord& a, const ReplayRecord& b, const std::string& id) {
  EXPECT_EQ(a.problem, b.problem) << id;
  EXPECT_EQ(a.solver, b.solver) << id;
  EXPECT_EQ(a.mode, b.mode) << id;
  EXPECT_EQ(a.status, b.status) << id;
  EXPECT_EQ(a.verdict, b.verdict) << id;
  EXPECT_EQ(a.iterations, b.iterations) << id;
  EXPECT_EQ(a.residual_abs, b.residual_abs) << id;
  EXPECT_EQ(a.residual_rel, b.residual_rel) << id;
  EXPECT_EQ(a.residual_scaled, b.residual_scaled) << id;
  EXPECT_TRUE(a.forward_error == b.forward_error || (std::isnan(a.forward_error) && std::isnan(b.forward_error)))
      << id;
}

TEST(RunShard, ExactBackendsSolveThePlantedProblemsAndRefuseTheInfeasibleOne) {
  const BenchPlan plan = TinyPlan();
  ShardSummary summary;
  const std::map<std::size_t, JobLine> lines = RunLines(plan, {}, {}, &summary);
  EXPECT_EQ(lines.size(), plan.jobs.size());
  EXPECT_EQ(summary.jobs_run, plan.jobs.size());
  EXPECT_TRUE(summary.skipped.empty());
  for (const auto& [index, line] : lines) {
    const BenchJob& job = plan.jobs[index];
    ASSERT_TRUE(line.has_record) << job.id;
    EXPECT_EQ(line.id, job.id);
    if (job.kind != JobKind::kCold || job.solver == "psor") continue;
    const bool infeasible = job.problem_id == "tiny/infeasible-lcp";
    EXPECT_EQ(line.record.verdict, infeasible ? Verdict::kCorrectlyRefused : Verdict::kSolved) << job.id;
    if (!infeasible) {
      // Against the planted solution, which the certified reference proves unique (P-matrix).
      EXPECT_LE(line.record.forward_error, 1e-8) << job.id;
      EXPECT_LE(line.record.residual_rel, 1e-10) << job.id;
    }
  }
  // The results in the job list's order, as results.json holds them.
  const BenchResults results = PlanResults(plan, lines);
  ASSERT_EQ(results.suites.size(), 1u);
  EXPECT_EQ(results.suites[0].replay.records.size(), 15u);  // 5 problems x 3 backends
  EXPECT_EQ(results.suites[0].replay.records[0].solver, "lemke");
  EXPECT_EQ(results.suites[0].replay.records[1].solver, "enum");
  EXPECT_FALSE(results.suites[0].replay.sweep.empty());
  EXPECT_FALSE(results.has_stepper);
}

// Warm jobs: each sequence × backend replayed (a warm record in the suite's results), or recorded as not run past
// the budget.
TEST(RunShard, WarmJobsReplayTheirSequencesOrAreNotRunPastTheBudget) {
  BenchPlan plan = TinyPlan();
  WarmSequence sequence = TrajectoryWarmSequences("tiny", /*quick=*/true).front();  // P-matrix relay, m = 8
  CertifyWarmSequence(&sequence);
  plan.warm_sequences = {{sequence}};
  JobListRequest request;
  request.solvers = plan.solvers;
  request.warm = &plan.warm_sequences;
  plan.jobs = ListBenchJobs(plan.suites, plan.options, request);
  const std::map<std::size_t, JobLine> lines = RunLines(plan, {}, {});
  int warm = 0;
  for (const auto& [index, line] : lines) {
    if (plan.jobs[index].kind != JobKind::kWarm) continue;
    ++warm;
    ASSERT_TRUE(line.has_warm) << line.id;
    EXPECT_FALSE(line.has_record) << line.id;
    EXPECT_EQ(line.warm.record.mode, "warm");
    EXPECT_EQ(line.warm.counts.steps, 8);
    if (line.warm.record.solver != "psor") {  // the exact backends solve every step
      EXPECT_EQ(line.warm.record.verdict, Verdict::kSolved) << line.id << ": " << line.warm.record.message;
    }
  }
  EXPECT_EQ(warm, 3);
  EXPECT_EQ(PlanResults(plan, lines).suites.at(0).warm.size(), 3u);

  plan.request.backend_budget_seconds = 1e-12;  // spent by each backend's first job
  for (const auto& [index, line] : RunLines(plan, {}, {})) {
    if (plan.jobs[index].kind != JobKind::kWarm) continue;
    ASSERT_TRUE(line.has_warm) << line.id;
    EXPECT_EQ(line.warm.record.status, SolveStatus::kNotRun) << line.id;
    EXPECT_EQ(line.warm.record.mode, kCutMode) << line.id;
    EXPECT_THAT(line.warm.record.message, HasSubstr("spent its budget of 1e-12 s on suite tiny"));
  }
}

// The per-job budgets: a warm sequence past the sequence budget is cut in or after its first step; a solve stopped
// by a job budget below the time limit cuts its job (newton checks its clock before any iteration). Cut records have
// mode "cut" and no verdict.
TEST(RunShard, JobAndSequenceBudgetsCutTheJobsAndSaySo) {
  BenchPlan plan = TinyPlan();
  WarmSequence sequence = TrajectoryWarmSequences("tiny", /*quick=*/true).front();  // P-matrix relay, m = 8
  CertifyWarmSequence(&sequence);
  plan.warm_sequences = {{sequence}};
  JobListRequest request;
  request.solvers = plan.solvers;
  request.warm = &plan.warm_sequences;
  plan.jobs = ListBenchJobs(plan.suites, plan.options, request);
  plan.request.sequence_budget_seconds = 1e-12;
  int warm = 0;
  for (const auto& [index, line] : RunLines(plan, {}, {})) {
    if (plan.jobs[index].kind != JobKind::kWarm) continue;
    ++warm;
    EXPECT_EQ(line.warm.record.mode, kCutMode) << line.id;
    EXPECT_EQ(line.warm.record.status, SolveStatus::kNotRun) << line.id;
    EXPECT_THAT(line.warm.record.message, HasSubstr("sequence budget of 1e-12 s"));
  }
  EXPECT_EQ(warm, 3);

  BenchRequest newton;
  newton.suites = {"tiny"};
  newton.solvers = {"newton"};
  newton.quick = true;
  newton.repetitions = 1;
  newton.job_budget_seconds = 1e-9;
  newton.calibrate = false;
  BenchPlan budgeted = MakeBenchPlan(newton);
  // One problem no solve ends within a nanosecond (the tiny suite's are solved before newton first reads its clock):
  // the m = 64 P-matrix LCP that starts the families trajectory.
  ProblemSet one_problem = BoxSet(*budgeted.suites[0]);
  one_problem.problems = {TrajectoryWarmSequences("families", /*quick=*/true).back().steps.front()};
  budgeted.suites[0] = MakeBoxSuite(std::move(one_problem));
  JobListRequest one;
  one.solvers = budgeted.solvers;
  budgeted.jobs = ListBenchJobs(budgeted.suites, budgeted.options, one);
  int cold = 0;
  for (const auto& [index, line] : RunLines(budgeted, {}, {})) {
    if (budgeted.jobs[index].kind != JobKind::kCold) continue;
    ++cold;
    ASSERT_TRUE(line.has_record) << line.id;
    EXPECT_EQ(line.record.mode, kCutMode) << line.id;
    EXPECT_EQ(line.record.status, SolveStatus::kNotRun) << line.id;
    EXPECT_THAT(line.record.message, HasSubstr("job budget of 1e-09 s spent (--job-budget; the time limit is 10 s)"));
  }
  EXPECT_EQ(cold, 1);
}

TEST(RunShard, ABackendPastItsBudgetIsNotRunOnTheRestOfTheSuite) {
  BenchPlan plan = TinyPlan();
  plan.request.backend_budget_seconds = 1e-12;  // spent by each backend's first job
  ShardSummary summary;
  const std::map<std::size_t, JobLine> lines = RunLines(plan, {}, {}, &summary);
  std::map<std::string, int> ran, not_run, sweep_skipped;
  for (const auto& [index, line] : lines) {
    const BenchJob& job = plan.jobs[index];
    if (job.kind == JobKind::kSweep) {
      EXPECT_TRUE(line.skipped) << job.id;
      EXPECT_FALSE(line.has_record) << job.id;
      ++sweep_skipped[job.solver];
      continue;
    }
    if (job.kind == JobKind::kFloor) continue;  // the floor is no backend: no budget cuts it (bench/replay/floor.h)
    ASSERT_TRUE(line.has_record) << job.id;
    if (line.record.message.rfind("not run: ", 0) == 0) {
      ++not_run[job.solver];
      EXPECT_EQ(line.record.status, SolveStatus::kNotRun) << job.id;
      EXPECT_EQ(line.record.mode, kCutMode) << job.id;  // no verdict: the report counts it nowhere
      EXPECT_EQ(line.record.samples, 0) << job.id;
      EXPECT_THAT(line.record.message, HasSubstr(job.solver + " spent its budget of 1e-12 s on suite tiny"));
    } else {
      ++ran[job.solver];
      EXPECT_EQ(job.problem, 0u) << "only the first problem runs: " << job.id;
    }
  }
  for (const std::string solver : {"lemke", "enum", "psor"}) {
    EXPECT_EQ(ran[solver], 1) << solver;
    EXPECT_EQ(not_run[solver], 4) << solver;
  }
  EXPECT_GT(sweep_skipped["psor"], 0);
  ASSERT_EQ(summary.skipped.size(), 3u);
  for (const BudgetSkip& skip : summary.skipped) {
    EXPECT_EQ(skip.suite, "tiny");
    EXPECT_EQ(skip.units, "problems");
    EXPECT_EQ(skip.problems, 5u);
    EXPECT_EQ(skip.skipped, 4) << skip.solver;  // problems: the skipped ladder rungs are not counted
  }
}

TEST(RunShard, ShardsCoverEveryJobOnceWithTheSameAnswersAndResumeRunsOnlyWhatIsMissing) {
  const BenchPlan plan = TinyPlan();
  const std::map<std::size_t, JobLine> single = RunLines(plan, {0, 1}, {});
  ASSERT_EQ(single.size(), plan.jobs.size());
  std::map<std::size_t, JobLine> sharded;
  for (int k = 0; k < 3; ++k) {
    for (auto& [index, line] : RunLines(plan, {k, 3}, {})) {
      EXPECT_TRUE(sharded.emplace(index, line).second) << "job " << index << " in two shards";
    }
  }
  ASSERT_EQ(sharded.size(), plan.jobs.size()) << "every job in some shard";
  for (const auto& [index, line] : single) {
    ExpectSameAnswer(line.record, sharded.at(index).record, plan.jobs[index].id);
  }
  // A run that stopped after some jobs: resuming with those done runs exactly the others, with the same answers.
  std::set<std::size_t> done;
  for (std::size_t k = 0; k < plan.jobs.size(); k += 2) done.insert(k);
  ShardSummary summary;
  const std::map<std::size_t, JobLine> rest = RunLines(plan, {0, 1}, done, &summary);
  EXPECT_EQ(summary.jobs_run, plan.jobs.size() - done.size());
  for (std::size_t k = 0; k < plan.jobs.size(); ++k) {
    EXPECT_EQ(rest.count(k), done.count(k) ? 0u : 1u) << k;
    if (rest.count(k)) ExpectSameAnswer(single.at(k).record, rest.at(k).record, plan.jobs[k].id);
  }
  EXPECT_THROW(RunShard(plan, {3, 3}, {}, {}), InvalidInputError);
}

}  // namespace
}  // namespace smcbench
