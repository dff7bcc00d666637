// The warm track on sequences whose answers are known: M = I with relay bounds (z = Π(−q) row by row, so the
// active set of every step, and the steps where it changes, follow from q by hand), and a families trajectory
// (P-matrix: one answer per step, certified), replayed in order and compared with cold solves of each step.
#include "bench/replay/warm_track.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "bench/replay/jobs.h"
#include "bench/replay/results_io.h"
#include "bench/run/warm_sequences.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/job_list.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

ReplayOptions FewRepeats() {
  ReplayOptions o;
  o.repetitions = 2;
  o.max_seconds_per_pair = 0.05;
  return o;
}

// M = I (3 × 3), l = −1, u = 1: z_i = clamp(−q_i, −1, 1). Active sets: steps 0, 1 all free; step 2 row 0 at its
// lower bound (q_0 = 2); step 3 the same; step 4 row 1 at its upper bound too (q_1 = −3); step 5 row 0 free again.
// So the set changes at steps 2, 4 and 5.
WarmSequence IdentityRelaySequence() {
  const double qs[6][3] = {{0.5, 0.5, 0.5}, {0.4, 0.5, 0.5}, {2.0, 0.5, 0.5},
                           {2.1, 0.5, 0.5}, {2.1, -3.0, 0.5}, {0.1, -3.0, 0.5}};
  WarmSequence sequence;
  sequence.suite = "handmade";
  sequence.id = "handmade/warm/identity-relay";
  sequence.source = WarmSource::kCapture;
  for (int k = 0; k < 6; ++k) {
    const Vector q = Eigen::Map<const Vector>(qs[k], 3);
    LibraryProblem p = MakeLibraryProblem("handmade/identity-relay/k" + std::to_string(k), "handmade",
                                          BoxMLCP::Relay(DenseMatrix::Identity(3, 3), q));
    p.expected = ExpectedOutcome::kSolvable;
    p.solution = (-q).cwiseMax(-1.0).cwiseMin(1.0);
    sequence.steps.push_back(std::move(p));
  }
  CertifyWarmSequence(&sequence);
  return sequence;
}

TEST(WarmTrack, CountsActiveSetChangesAndFallbacksAtTheKnownSteps) {
  const WarmSequence sequence = IdentityRelaySequence();
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  std::vector<Vector> answers;
  const WarmRecord w = ReplayWarmSequence(sequence, lemke.get(), "lemke", FewRepeats(), 1e-10, &answers);
  EXPECT_EQ(w.record.mode, "warm");
  EXPECT_EQ(w.record.problem, sequence.id);
  EXPECT_EQ(w.record.verdict, Verdict::kSolved) << w.record.message;
  EXPECT_EQ(w.counts.steps, 6);
  EXPECT_EQ(w.counts.steps_solved, 6);
  EXPECT_EQ(w.counts.active_set_changes, 3);
  // Our session's reused set answers where the set did not change (steps 1, 3) and falls back where it did.
  EXPECT_TRUE(w.counts.reuse);
  EXPECT_EQ(w.counts.reused_steps, 2);
  EXPECT_EQ(w.counts.fallbacks, 3);
  ASSERT_EQ(answers.size(), 6u);
  for (std::size_t k = 0; k < answers.size(); ++k) {
    EXPECT_LE((answers[k] - sequence.steps[k].solution).cwiseAbs().maxCoeff(), 1e-14) << "step " << k;
  }
  EXPECT_LE(w.record.forward_error, 1e-14);
  EXPECT_GE(w.record.samples, 1);
  EXPECT_GT(w.record.time_median, 0.0);
}

TEST(WarmTrack, StepsInOrderGiveTheColdAnswersWithNoMoreIterations) {
  const std::vector<WarmSequence> sequences = TrajectoryWarmSequences("families", /*quick=*/true);
  ASSERT_EQ(sequences.size(), 2u);
  WarmSequence sequence = sequences.front();  // P-matrix relay, m = 8: one answer per step
  CertifyWarmSequence(&sequence);
  ASSERT_EQ(sequence.steps.size(), 8u);
  for (const char* name : {"lemke", "newton", "newton-min"}) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    std::vector<Vector> answers;
    const WarmRecord w = ReplayWarmSequence(sequence, solver.get(), name, FewRepeats(), 1e-10, &answers);
    EXPECT_EQ(w.record.verdict, Verdict::kSolved) << name << ": " << w.record.message;
    std::int64_t cold_iterations = 0;
    for (std::size_t k = 0; k < sequence.steps.size(); ++k) {
      SolverOptions o;
      o.tolerance = 1e-10;
      const SolveResult cold = solver->Solve(sequence.steps[k].problem, o);
      ASSERT_EQ(cold.status, SolveStatus::kSolved) << name << " step " << k;
      cold_iterations += cold.iterations;
      EXPECT_LE((answers[k] - cold.z).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + cold.z.cwiseAbs().maxCoeff()))
          << name << " step " << k;
      ASSERT_TRUE(sequence.steps[k].reference.unique()) << "step " << k;
      EXPECT_LE((answers[k] - sequence.steps[k].reference.z).cwiseAbs().maxCoeff(),
                1e-8 * (1.0 + sequence.steps[k].reference.z.cwiseAbs().maxCoeff()));
    }
    EXPECT_LE(w.counts.iterations, cold_iterations) << name;
    EXPECT_EQ(w.counts.reused_steps + w.counts.fallbacks, 7) << name;
  }
}

TEST(WarmTrack, AStepOverTheTimeLimitEndsThePassAndIsNotRepeated) {
  const std::vector<WarmSequence> sequences = TrajectoryWarmSequences("families", /*quick=*/true);
  const WarmSequence& sequence = sequences.back();  // m = 64: no solve ends within a nanosecond
  ReplayOptions options = FewRepeats();
  options.time_limit_seconds = 1e-9;
  const std::unique_ptr<Solver> newton = CreateSolver("newton");
  std::vector<Vector> answers;
  const WarmRecord w = ReplayWarmSequence(sequence, newton.get(), "newton", options, 1e-10, &answers);
  EXPECT_EQ(w.record.status, SolveStatus::kTimeLimit);
  EXPECT_EQ(w.record.verdict, Verdict::kFailed);
  EXPECT_EQ(w.record.samples, 1);
  EXPECT_EQ(answers.size(), 1u);  // the pass stopped at step 0
  EXPECT_EQ(w.counts.steps_solved, 0);
  EXPECT_EQ(w.counts.steps, 8);
}

// A sequence budget shorter than one step: the untimed pass stops after step 0 and the record is cut (no verdict,
// no sample), its message saying how far it got; a budget it fits in leaves the record as without one.
TEST(WarmTrack, ASequencePastItsBudgetIsCutAfterTheStepThatSpentIt) {
  const WarmSequence sequence = IdentityRelaySequence();  // 6 steps
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  std::vector<Vector> answers;
  const WarmRecord cut = ReplayWarmSequence(sequence, lemke.get(), "lemke", FewRepeats(), 1e-10, &answers, 1e-12);
  EXPECT_EQ(cut.record.mode, kCutMode);
  EXPECT_EQ(cut.record.status, SolveStatus::kNotRun);
  EXPECT_EQ(cut.record.samples, 0);
  EXPECT_EQ(cut.record.message.rfind("cut after 1 of 6 steps: the next would pass the sequence budget of 1e-12 s (", 0),
            0u)
      << cut.record.message;
  ASSERT_EQ(answers.size(), 1u);  // step 0 ran, and was solved: z = clamp(-q) = -0.5
  EXPECT_EQ(answers[0], Vector::Constant(3, -0.5));
  EXPECT_EQ(cut.counts.steps, 6);
  EXPECT_EQ(cut.counts.steps_solved, 1);

  const WarmRecord whole = ReplayWarmSequence(sequence, lemke.get(), "lemke", FewRepeats(), 1e-10, &answers, 100.0);
  EXPECT_EQ(whole.record.mode, "warm");
  EXPECT_EQ(whole.record.verdict, Verdict::kSolved) << whole.record.message;
  EXPECT_EQ(whole.counts.steps_solved, 6);
  EXPECT_GE(whole.record.samples, 1);
  EXPECT_EQ(answers.size(), 6u);
}

// The estimates' cost model on its inputs (jobs.h), by hand: a 3 × 3 dense problem is 3·(3 + 9) = 36 units.
TEST(WarmTrack, JobEstimatesFollowTheCostModelAndTheBudgets) {
  const WarmSequence sequence = IdentityRelaySequence();  // 6 steps of m = 3
  ReplayOptions o;  // 7 repetitions, samples of at least 0.2 ms, at most 2 s of sampling, 10 s per solve
  BackendCost cost;
  cost.job_seconds = 0.01;
  cost.seconds_per_unit = 1e-4;  // one solve: 3.6 ms
  const LibraryProblem& p = sequence.steps[0];
  // 0.01 + (3.6 ms warm-up + 7 × 3.6 ms) − (a tiny solve's 7 × 0.2 ms), the last already in job_seconds.
  EXPECT_NEAR(EstimateJobSeconds(p, o, JobKind::kCold, cost), 0.01 + 0.0288 - 0.0014, 1e-12);
  EXPECT_NEAR(EstimateJobSeconds(p, o, JobKind::kSweep, cost), 0.01 + 0.0144 - 0.0006, 1e-12);  // 3 samples
  // A job budget of 1 ms, below one solve: the solve stops at 1 ms and is not repeated; a tiny job samples 0.7 ms.
  const JobBudgets budgets{1e-3, 0.0};
  EXPECT_NEAR(EstimateJobSeconds(p, o, JobKind::kCold, cost, budgets), 0.01 + 0.001 - 0.0007, 1e-12);
  // Warm: a pass is 6 × 3.6 ms = 21.6 ms; unbudgeted, the untimed pass and 7 timed ones.
  EXPECT_NEAR(EstimateWarmJobSeconds(sequence, o, cost), 0.01 + 8 * 0.0216, 1e-12);
  // A sequence budget below the pass: cut before the step that would pass it, so the budget.
  EXPECT_NEAR(EstimateWarmJobSeconds(sequence, o, cost, {0.0, 0.01}), 0.01 + 0.01, 1e-12);
  // A pass over half the budget is its own only sample.
  EXPECT_NEAR(EstimateWarmJobSeconds(sequence, o, cost, {0.0, 0.04}), 0.01 + 0.0216, 1e-12);
  // Under half: the timed passes end inside the budget (the untimed pass and 0.0284 s of timed ones).
  EXPECT_NEAR(EstimateWarmJobSeconds(sequence, o, cost, {0.0, 0.05}), 0.01 + 0.05, 1e-12);
  // A budget far above the passes: the repetitions, as without one.
  EXPECT_NEAR(EstimateWarmJobSeconds(sequence, o, cost, {0.0, 100.0}), 0.01 + 8 * 0.0216, 1e-12);
}

// A machine's measured costs change the estimates (--list-jobs, the ETA) but not BenchJob::cost, so every process
// of a sharded run computes the same shards whatever its probe measured.
TEST(WarmTrack, MeasuredCostsChangeTheEstimatesNotTheShards) {
  const WarmSequence sequence = IdentityRelaySequence();  // 6 steps of m = 3
  ProblemSet set;
  set.name = "handmade";
  set.problems = {sequence.steps[0], sequence.steps[1]};
  const std::vector<std::vector<WarmSequence>> warm = {{sequence}};
  ReplayOptions options;
  options.tolerance_sweep_problems = 0;
  JobListRequest request;
  request.solvers = {"lemke", "psor"};
  request.warm = &warm;
  const std::vector<BenchJob> guessed = ListBenchJobs(BoxSuites({set}), options, request);
  BackendCost slow;  // lemke measured 100 times slower per unit of work than the guess, plus 0.5 s per job
  slow.job_seconds = 0.5;
  slow.seconds_per_unit = 1e-7;
  request.costs["lemke"] = slow;
  const std::vector<BenchJob> measured = ListBenchJobs(BoxSuites({set}), options, request);
  ASSERT_EQ(measured.size(), 6u);  // 2 problems × 2 backends cold, 1 sequence × 2 backends warm
  for (std::size_t i = 0; i < measured.size(); ++i) {
    SCOPED_TRACE(measured[i].id);
    EXPECT_EQ(measured[i].cost, guessed[i].cost);
    EXPECT_EQ(guessed[i].estimate, guessed[i].cost);  // no measured cost: the guess
    const BenchJob& job = measured[i];
    if (job.solver != "lemke") {
      EXPECT_EQ(job.estimate, job.cost);
    } else if (job.kind == JobKind::kWarm) {
      EXPECT_DOUBLE_EQ(job.estimate, EstimateWarmJobSeconds(sequence, options, slow));
    } else {
      EXPECT_DOUBLE_EQ(job.estimate, EstimateJobSeconds(set.problems[job.problem], options, JobKind::kCold, slow));
    }
  }
  EXPECT_EQ(AssignShards(measured, 3), AssignShards(guessed, 3));
}

// The backend budget in the estimates, as a run applies it: a backend's jobs on a suite, in order, until their
// estimates reach the budget; the later ones are estimated at kNotRunJobSeconds (a record, nothing solved). The
// warm sequence counts against its box suite; the other backend is untouched; the shards' costs never change.
TEST(WarmTrack, TheBackendBudgetCutsTheEstimatesWhereTheRunCutsTheJobs) {
  const WarmSequence sequence = IdentityRelaySequence();
  ProblemSet set;
  set.name = "handmade";
  set.problems = {sequence.steps[0], sequence.steps[1], sequence.steps[2]};
  const std::vector<std::vector<WarmSequence>> warm = {{sequence}};
  ReplayOptions options;
  options.tolerance_sweep_problems = 0;
  JobListRequest request;
  request.solvers = {"lemke", "psor"};
  request.warm = &warm;
  BackendCost slow;  // lemke: 0.5 s per job
  slow.job_seconds = 0.5;
  request.costs["lemke"] = slow;
  const std::vector<BenchJob> unbudgeted = ListBenchJobs(BoxSuites({set}), options, request);
  request.budgets.backend_seconds = 0.9;  // lemke's second cold job reaches it
  const std::vector<BenchJob> budgeted = ListBenchJobs(BoxSuites({set}), options, request);
  ASSERT_EQ(budgeted.size(), 8u);  // 3 problems × 2 backends cold, 1 sequence × 2 backends warm
  int lemke_run = 0, lemke_cut = 0;
  for (std::size_t i = 0; i < budgeted.size(); ++i) {
    SCOPED_TRACE(budgeted[i].id);
    EXPECT_EQ(budgeted[i].cost, unbudgeted[i].cost);
    if (budgeted[i].solver != "lemke") {
      EXPECT_EQ(budgeted[i].estimate, unbudgeted[i].estimate);
    } else if (budgeted[i].estimate == kNotRunJobSeconds) {
      ++lemke_cut;
    } else {
      EXPECT_EQ(budgeted[i].estimate, unbudgeted[i].estimate);
      ++lemke_run;
    }
  }
  EXPECT_EQ(lemke_run, 2);  // 0.5 + 0.5 ≥ 0.9: the third cold job and the warm sequence are not run
  EXPECT_EQ(lemke_cut, 2);
}

TEST(WarmTrack, TrajectoryMovesOnlyQAndASequenceWithAnotherMIsRefused) {
  const std::vector<WarmSequence> sequences = TrajectoryWarmSequences("families", /*quick=*/true);
  const WarmSequence& sequence = sequences.back();  // P-matrix LCP, m = 64
  EXPECT_EQ(sequence.id, "families/warm/pmatrix-lcp/m64/s1");
  EXPECT_NO_THROW(CheckWarmSequence(sequence));
  const BoxMLCP& first = sequence.steps[0].problem;
  // Step 0 is the family's own problem (its planted solution kept); later steps move q by at most 5 % of 1 + ‖q‖∞.
  EXPECT_EQ(sequence.steps[0].solution.size(), 64);
  const double scale = 1.0 + first.q().cwiseAbs().maxCoeff();
  double largest_move = 0.0;
  for (const LibraryProblem& step : sequence.steps) {
    largest_move = std::max(largest_move, (step.problem.q() - first.q()).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest_move, 0.0);
  EXPECT_LE(largest_move, 0.05 * 3.0 * scale);  // |sin| ≤ 1, 1 − cos ≤ 2
  // TrajectoryStep at k = K is the start again (a closed loop).
  const LibraryProblem again = TrajectoryStep(sequence.steps[0], 8, 8, 0.05);
  EXPECT_LE((again.problem.q() - first.q()).cwiseAbs().maxCoeff(), 1e-12 * scale);

  WarmSequence mixed = IdentityRelaySequence();
  mixed.steps[3].problem = BoxMLCP::Relay(2.0 * DenseMatrix::Identity(3, 3), mixed.steps[3].problem.q());
  try {
    CheckWarmSequence(mixed);
    ADD_FAILURE() << "a step with another M was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("step 3"), std::string::npos) << e.what();
  }
}

TEST(WarmTrack, CaptureSequencesAreRunsOfProblemsSharingMlu) {
  ProblemSet set;
  set.name = "mine";
  const WarmSequence identity = IdentityRelaySequence();
  for (const LibraryProblem& p : identity.steps) set.problems.push_back(p);
  LibraryProblem other = identity.steps[0];
  other.id = "mine/other";
  other.problem = BoxMLCP::Relay(2.0 * DenseMatrix::Identity(3, 3), other.problem.q());
  set.problems.insert(set.problems.begin() + 2, other);  // splits the run: 2 steps, the lone one, then 4 steps
  const std::vector<WarmSequence> runs = CaptureWarmSequences(set, 8, 200);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].steps.size(), 2u);
  EXPECT_EQ(runs[1].steps.size(), 4u);
  EXPECT_EQ(runs[0].id, "mine/warm/handmade/identity-relay/k0");
  EXPECT_EQ(CaptureWarmSequences(set, 1, 200).size(), 1u);
  EXPECT_EQ(CaptureWarmSequences(set, 8, 3)[1].steps.size(), 3u);
}

TEST(WarmTrack, WarmRecordsRoundTripThroughResultsAndJobLines) {
  const WarmSequence sequence = IdentityRelaySequence();
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  const WarmRecord w = ReplayWarmSequence(sequence, lemke.get(), "lemke", FewRepeats(), 1e-10);
  BenchResults results;
  results.command = "test";
  SuiteResults suite;
  suite.suite = "handmade";
  suite.description = "hand-made";
  suite.warm.push_back(w);
  results.suites.push_back(suite);
  const fs::path dir = fs::temp_directory_path() / ("warm_track_test_" + std::to_string(::getpid()));
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  ASSERT_EQ(back.suites[0].warm.size(), 1u);
  const WarmRecord& r = back.suites[0].warm[0];
  EXPECT_EQ(r.record.mode, "warm");
  EXPECT_EQ(r.record.problem, w.record.problem);
  EXPECT_EQ(r.record.time_median, w.record.time_median);
  EXPECT_EQ(r.record.verdict, w.record.verdict);
  EXPECT_EQ(r.source, WarmSource::kCapture);
  EXPECT_EQ(r.counts.steps, 6);
  EXPECT_EQ(r.counts.active_set_changes, 3);
  EXPECT_EQ(r.counts.fallbacks, 3);
  EXPECT_EQ(r.counts.reused_steps, 2);
  EXPECT_EQ(r.counts.iterations, w.counts.iterations);
  EXPECT_TRUE(back.suites[0].replay.records.empty());
  std::ifstream csv(dir / "results.csv");
  std::stringstream text;
  text << csv.rdbuf();
  EXPECT_NE(text.str().find("handmade,handmade/warm/identity-relay,lemke,warm,3,"), std::string::npos) << text.str();
  fs::remove_all(dir);

  // A warm job: listed after the cold jobs with its own id, and its line assembled into the suite's warm records.
  ProblemSet set;
  set.name = "handmade";
  set.problems.push_back(sequence.steps[0]);
  const std::vector<std::vector<WarmSequence>> warm = {{sequence}};
  JobListRequest request;
  request.solvers = {"lemke"};
  request.warm = &warm;
  ReplayOptions options = FewRepeats();
  options.tolerance_sweep_problems = 0;
  const std::vector<BenchJob> jobs = ListBenchJobs(BoxSuites({set}), options, request);
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[1].kind, JobKind::kWarm);
  EXPECT_EQ(jobs[1].id, "handmade|handmade/warm/identity-relay|lemke|warm|1e-10");
  JobLine line;
  line.job = 1;
  line.id = jobs[1].id;
  line.has_warm = true;
  line.warm = w;
  line.seconds = 0.25;
  RunManifest manifest;
  SuiteResults listed;
  listed.suite = "handmade";
  manifest.suites = {listed};
  manifest.jobs = jobs;
  manifest.job_shard = {0, 0};
  manifest.options = nlohmann::json::object();
  const JobLine read = [&] {
    const fs::path file = fs::temp_directory_path() / ("warm_track_test_" + std::to_string(::getpid()) + ".jsonl");
    {
      JobLineWriter writer(file.string());
      writer.Write(line);
    }
    JobLine out = ReadJobLines(file.string(), false).at(0);
    fs::remove(file);
    return out;
  }();
  ASSERT_TRUE(read.has_warm);
  EXPECT_EQ(read.warm.counts.active_set_changes, 3);
  EXPECT_EQ(read.seconds, 0.25);  // the job's wall time, what --list-jobs' estimate is checked against
  const BenchResults assembled = AssembleResults(manifest, {{1, read}});
  ASSERT_EQ(assembled.suites[0].warm.size(), 1u);
  EXPECT_EQ(assembled.suites[0].warm[0].record.problem, sequence.id);
}

}  // namespace
}  // namespace smcbench
