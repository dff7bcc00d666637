// A benchmark plan: its job list for a known suite and backends, when the stepper studies belong to it, and every
// bad input refused with the field named before anything runs.
#include "bench/run/bench_plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <unistd.h>

#include "problems/library/problem_set_io.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The tiny suite (4 planted-solution problems and one infeasible LCP) on an exact and an iterative backend.
BenchRequest TinyRequest() {
  BenchRequest request;
  request.suites = {"tiny"};
  request.solvers = {"lemke", "psor"};
  request.quick = true;
  return request;
}

std::string MessageOf(const BenchRequest& request) {
  try {
    MakeBenchPlan(request);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BenchPlan, ListsColdJobsProblemByProblemThenTheIterativeBackendsSweep) {
  const BenchPlan plan = MakeBenchPlan(TinyRequest());
  ASSERT_EQ(plan.suites.size(), 1u);
  ASSERT_EQ(plan.suites[0].problems.size(), 5u);
  EXPECT_TRUE(plan.mcp_suites.empty());
  EXPECT_EQ(plan.solvers, (std::vector<std::string>{"lemke", "psor"}));
  EXPECT_FALSE(plan.stepper) << "tiny is not a scene suite";
  EXPECT_EQ(plan.options.repetitions, 3) << "quick: at most 3 samples";
  // Cold jobs: problem by problem, the backends in the order named, at the run's tolerance.
  for (std::size_t k = 0; k < 10; ++k) {
    const BenchJob& job = plan.jobs.at(k);
    EXPECT_EQ(job.index, k);
    EXPECT_EQ(job.kind, JobKind::kCold);
    EXPECT_EQ(job.problem, k / 2);
    EXPECT_EQ(job.solver, k % 2 == 0 ? "lemke" : "psor");
    EXPECT_EQ(job.tolerance, 1e-10);
    EXPECT_EQ(job.problem_id, plan.suites[0].problems[k / 2].id);
  }
  // Then the floor, one job per problem (one factorization of its M, bench/replay/floor.h), then the tolerance
  // ladder, for every backend (exact ones too: the ladder is a success rate per tolerance), and nothing else.
  ASSERT_GT(plan.jobs.size(), 15u);
  for (std::size_t k = 10; k < 15; ++k) {
    EXPECT_EQ(plan.jobs[k].kind, JobKind::kFloor) << plan.jobs[k].id;
    EXPECT_EQ(plan.jobs[k].problem, k - 10);
  }
  std::set<std::string> ids, swept;
  for (std::size_t k = 15; k < plan.jobs.size(); ++k) {
    EXPECT_EQ(plan.jobs[k].kind, JobKind::kSweep) << plan.jobs[k].id;
    swept.insert(plan.jobs[k].solver);
  }
  EXPECT_EQ(swept, (std::set<std::string>{"lemke", "psor"}));
  for (const BenchJob& job : plan.jobs) EXPECT_TRUE(ids.insert(job.id).second) << "duplicate id " << job.id;
  // Every problem got its certified reference (the verdict judges forward errors against it).
  for (const LibraryProblem& p : plan.suites[0].problems) {
    if (p.expected == ExpectedOutcome::kSolvable) {
      EXPECT_TRUE(p.reference.unique()) << p.id;
    }
  }
  // The suites and options as the manifest records them.
  const std::vector<SuiteResults> suites = PlanSuites(plan);
  ASSERT_EQ(suites.size(), 1u);
  EXPECT_EQ(suites[0].suite, "tiny");
  EXPECT_EQ(suites[0].problems, 5);
  EXPECT_EQ(suites[0].checksum, ProblemSetContentChecksum(plan.suites[0]));
  EXPECT_EQ(PlanOptionsJson(plan)["stepper"], false);
}

TEST(BenchPlan, StepperStudiesOnlyWithASceneSuiteOrWhenAsked) {
  using C = StepperStudyChoice;
  EXPECT_TRUE(IncludesStepperStudy({"paper", "families"}, C::kIfSceneSuite));
  EXPECT_FALSE(IncludesStepperStudy({"families", "tiny", "mcp"}, C::kIfSceneSuite));
  EXPECT_FALSE(IncludesStepperStudy({"my-problems.smcps"}, C::kIfSceneSuite));
  EXPECT_TRUE(IncludesStepperStudy({"my-problems.smcps"}, C::kAlways));
  EXPECT_FALSE(IncludesStepperStudy({"paper"}, C::kNever));
  // The plan follows the rule: asked for, the stepper job comes last.
  BenchRequest request = TinyRequest();
  request.stepper = C::kAlways;
  const BenchPlan plan = MakeBenchPlan(request);
  EXPECT_TRUE(plan.stepper);
  EXPECT_EQ(plan.jobs.back().kind, JobKind::kStepper);
  EXPECT_EQ(PlanOptionsJson(plan)["stepper"], true);
}

// The warm track: the families suite's trajectories as warm jobs after the cold ones (one per sequence × backend),
// none for a suite without sequences (tiny), none with --no-warm; the run's options record the choice.
TEST(BenchPlan, WarmJobsForTheFamiliesSequencesUnlessTurnedOff) {
  BenchRequest request;
  request.suites = {"families", "tiny"};
  request.solvers = {"lemke", "psor"};
  request.quick = true;
  request.stepper = StepperStudyChoice::kNever;
  request.certify = false;  // listing only
  const BenchPlan plan = MakeBenchPlan(request);
  ASSERT_EQ(plan.warm_sequences.size(), 2u);
  EXPECT_EQ(plan.warm_sequences[0].size(), 2u);  // quick: P-matrix relay m = 8, P-matrix LCP m = 64
  EXPECT_TRUE(plan.warm_sequences[1].empty());   // tiny: no problems sharing M, l, u
  std::vector<std::string> warm_ids;
  bool warm_seen = false;
  for (const BenchJob& job : plan.jobs) {
    if (job.kind == JobKind::kWarm) {
      warm_seen = true;
      warm_ids.push_back(job.id);
    } else {
      EXPECT_FALSE(warm_seen) << "a " << ToString(job.kind) << " job after the warm ones";
    }
  }
  EXPECT_THAT(warm_ids, ::testing::ElementsAre("families|families/warm/pmatrix-relay/m8/s1|lemke|warm|1e-10",
                                               "families|families/warm/pmatrix-relay/m8/s1|psor|warm|1e-10",
                                               "families|families/warm/pmatrix-lcp/m64/s1|lemke|warm|1e-10",
                                               "families|families/warm/pmatrix-lcp/m64/s1|psor|warm|1e-10"));
  EXPECT_EQ(PlanOptionsJson(plan)["warm"], true);

  request.warm = false;
  const BenchPlan cold = MakeBenchPlan(request);
  EXPECT_TRUE(cold.warm_sequences.empty());
  EXPECT_EQ(cold.jobs.size(), plan.jobs.size() - 4);
  EXPECT_EQ(PlanOptionsJson(cold)["warm"], false);
}

TEST(BenchPlan, EveryBadInputIsRefusedNamingTheField) {
  BenchRequest r = TinyRequest();
  r.suites = {"tiny", "tinny"};
  EXPECT_THAT(MessageOf(r), HasSubstr("unknown suite 'tinny'"));
  r = TinyRequest();
  r.solvers = {"lemkee"};
  EXPECT_THAT(MessageOf(r), HasSubstr("'lemkee'"));
  r = TinyRequest();
  r.settings = {"psor.omega=abc"};
  EXPECT_THAT(MessageOf(r), HasSubstr("psor.omega=abc"));
  r = TinyRequest();
  r.suites = {"siconos"};
  r.siconos_dir = "/nonexistent";
  EXPECT_THAT(MessageOf(r), HasSubstr("'/nonexistent' is not a folder"));
  r = TinyRequest();
  r.repetitions = 0;
  EXPECT_THAT(MessageOf(r), HasSubstr("repetitions must be a whole number >= 1, got 0"));
  r = TinyRequest();
  r.time_limit_seconds = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(MessageOf(r), HasSubstr("time limit must be a positive finite number of seconds, got nan"));
  r = TinyRequest();
  r.time_limit_seconds = -1.0;
  EXPECT_THAT(MessageOf(r), HasSubstr("time limit must be a positive finite number of seconds, got -1"));
  r = TinyRequest();
  r.backend_budget_seconds = -1.0;
  EXPECT_THAT(MessageOf(r), HasSubstr("backend budget must be a finite number of seconds >= 0, got -1"));
  r = TinyRequest();
  r.job_budget_seconds = std::numeric_limits<double>::infinity();
  EXPECT_THAT(MessageOf(r), HasSubstr("job budget must be a finite number of seconds >= 0, got inf"));
  r = TinyRequest();
  r.sequence_budget_seconds = -2.0;
  EXPECT_THAT(MessageOf(r), HasSubstr("sequence budget must be a finite number of seconds >= 0, got -2"));
  r = TinyRequest();
  r.tolerance = 0.0;
  EXPECT_THAT(MessageOf(r), HasSubstr("tolerance must be a positive finite number, got 0"));
}

// A problem-set file that is empty, or holds a set without problems, is an error of MakeBenchPlan: a caller that
// writes only after the plan leaves nothing behind.
TEST(BenchPlan, AnEmptyProblemSetFileIsRefused) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-plan-empty-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path empty_file = dir / "empty.smcps";
  std::ofstream(empty_file).close();
  BenchRequest r = TinyRequest();
  r.suites = {empty_file.string()};
  EXPECT_THAT(MessageOf(r), HasSubstr("empty.smcps"));
  ProblemSet none;
  none.name = "none";
  const fs::path no_problems = dir / "none.smcps";
  WriteProblemSetFile(none, no_problems.string());
  r.suites = {no_problems.string()};
  EXPECT_THAT(MessageOf(r), HasSubstr("holds no problem"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace smcbench
