// A benchmark plan: its job list for a known suite and backends, when the stepper studies belong to it, and every
// bad input refused with the field named before anything runs.
#include "bench/run/bench_plan.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/mcp_kind.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <unistd.h>

#include <nlohmann/json.hpp>

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
  ASSERT_EQ(BoxSet(*plan.suites[0]).problems.size(), 5u);
  EXPECT_EQ(plan.suites[0]->kind(), "box");
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
    EXPECT_EQ(job.problem_id, BoxSet(*plan.suites[0]).problems[k / 2].id);
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
  for (const LibraryProblem& p : BoxSet(*plan.suites[0]).problems) {
    if (p.expected == ExpectedOutcome::kSolvable) {
      EXPECT_TRUE(p.reference.unique()) << p.id;
    }
  }
  // The suites and options as the manifest records them.
  const std::vector<SuiteResults> suites = PlanSuites(plan);
  ASSERT_EQ(suites.size(), 1u);
  EXPECT_EQ(suites[0].suite, "tiny");
  EXPECT_EQ(suites[0].problems, 5);
  EXPECT_EQ(suites[0].checksum, ProblemSetContentChecksum(BoxSet(*plan.suites[0])));
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

// The ids of a plan's problems, per suite in order: box, MCP, AVI.
std::vector<std::vector<std::string>> PlanIds(const BenchPlan& plan) {
  std::vector<std::vector<std::string>> out;
  for (const PlanSuite& suite : plan.suites) {
    out.emplace_back();
    std::string last;
    for (const SuiteUnit& unit : suite->Units()) {  // an MCP's units are its problem × start: each problem once
      if (unit.problem_id != last) out.back().push_back(unit.problem_id);
      last = unit.problem_id;
    }
  }
  return out;
}

// --problem: every kind of suite keeps exactly the problems whose id matches a glob (box: families and tiny; the
// MCP suite; the AVI suite), the jobs are theirs only, a suite left with none is left out, a warm sequence stays only
// when its own id matches, and the stepper studies need --stepper.
TEST(BenchPlan, ProblemGlobsKeepExactlyTheMatchingProblemsOfEverySuiteKind) {
  BenchRequest request;
  request.suites = {"families", "tiny", "mcp", "avi"};
  request.solvers = {"lemke", "newton"};
  request.quick = true;
  request.certify = false;
  request.calibrate = false;
  request.problems = {"families/murty/*", "tiny/infeasible*", "mcp/hard/three-*", "avi/planted/n2/*"};
  const BenchPlan plan = MakeBenchPlan(request);
  EXPECT_EQ(plan.suite_names, (std::vector<std::string>{"families", "tiny", "mcp", "avi"}));
  const std::vector<std::vector<std::string>> ids = PlanIds(plan);
  ASSERT_EQ(ids.size(), 4u);
  // families: exactly its murty problems (the unfiltered suite's, in order).
  SuiteRequest families_request;
  families_request.quick = true;
  families_request.references = false;
  std::vector<std::string> murty;
  for (const LibraryProblem& p : BuildSuite("families", families_request).problems) {
    if (p.id.rfind("families/murty/", 0) == 0) murty.push_back(p.id);
  }
  ASSERT_FALSE(murty.empty());
  EXPECT_EQ(ids[0], murty);
  EXPECT_EQ(ids[1], std::vector<std::string>{"tiny/infeasible-lcp"});
  EXPECT_EQ(ids[2], std::vector<std::string>{"mcp/hard/three-solutions"});
  EXPECT_EQ(McpSet(*plan.suites[2]).problems[0].starts.size(), 3u);
  EXPECT_EQ(McpSet(*plan.suites[2]).problems[0].references.size(), 3u);  // references of the kept MCP, attached
  ASSERT_FALSE(ids[3].empty());
  for (const std::string& id : ids[3]) EXPECT_EQ(id.rfind("avi/planted/n2/", 0), 0u) << id;
  // The families' warm sequences ("families/warm/...") match no glob: none.
  ASSERT_EQ(plan.warm_sequences.size(), 4u);  // one list per suite; the MCP and AVI suites have none
  EXPECT_TRUE(plan.warm_sequences[0].empty());
  EXPECT_FALSE(plan.stepper);
  // Every job is one of a kept problem.
  std::set<std::string> kept;
  for (const auto& suite : ids) kept.insert(suite.begin(), suite.end());
  for (const BenchJob& job : plan.jobs) {
    EXPECT_TRUE(kept.count(job.problem_id)) << job.id;
  }
  EXPECT_EQ(PlanOptionsJson(plan)["problems"], nlohmann::json(request.problems));

  // A glob for the warm sequences keeps them; a suite none of whose problems matches is left out.
  BenchRequest warm = request;
  warm.suites = {"families", "tiny"};
  warm.problems = {"families/*", "tiny/*"};
  const BenchPlan with_warm = MakeBenchPlan(warm);
  ASSERT_EQ(with_warm.warm_sequences.size(), 2u);
  EXPECT_EQ(with_warm.warm_sequences[0].size(), 2u);  // as without a filter (WarmJobsForTheFamiliesSequences...)
  warm.problems = {"tiny/*"};
  const BenchPlan tiny_only = MakeBenchPlan(warm);
  EXPECT_EQ(tiny_only.suite_names, std::vector<std::string>{"tiny"});
  ASSERT_EQ(tiny_only.suites.size(), 1u);
  EXPECT_EQ(tiny_only.suites[0]->name(), "tiny");
  EXPECT_EQ(BoxSet(*tiny_only.suites[0]).problems.size(), TinySuite().problems.size());
  // A glob for the warm sequences alone keeps the suite for them, with no cold problem and only warm jobs.
  warm.problems = {"families/warm/*"};
  const BenchPlan warm_only = MakeBenchPlan(warm);
  EXPECT_EQ(warm_only.suite_names, std::vector<std::string>{"families"});
  ASSERT_EQ(warm_only.suites.size(), 1u);
  EXPECT_TRUE(BoxSet(*warm_only.suites[0]).problems.empty());
  ASSERT_EQ(warm_only.warm_sequences.size(), 1u);
  EXPECT_EQ(warm_only.warm_sequences[0].size(), 2u);
  ASSERT_FALSE(warm_only.jobs.empty());
  for (const BenchJob& job : warm_only.jobs) {
    EXPECT_TRUE(job.kind == JobKind::kWarm) << job.id;
    EXPECT_EQ(job.problem_id.rfind("families/warm/", 0), 0u) << job.id;
  }
  // Asked for, the stepper studies stay.
  warm.stepper = StepperStudyChoice::kAlways;
  EXPECT_TRUE(MakeBenchPlan(warm).stepper);
}

// A glob that matches no problem of the run is an error naming the flag and every such glob; an empty one too.
TEST(BenchPlan, AProblemGlobThatMatchesNothingIsRefused) {
  BenchRequest r = TinyRequest();
  r.calibrate = false;
  r.problems = {"tiny/*", "nope/*", "mcp/x"};
  EXPECT_THAT(MessageOf(r), HasSubstr("bench: --problem 'nope/*', 'mcp/x' match no problem of the suites tiny (ids "
                                      "look like 'tiny/"));
  r.problems = {"tiny"};
  EXPECT_THAT(MessageOf(r), HasSubstr("--problem 'tiny' matches no problem of the suites tiny"));
  r.problems = {""};
  EXPECT_THAT(MessageOf(r), HasSubstr("--problem needs a non-empty GLOB"));
}

// The globs go into the manifest's options, back unchanged; a run without them writes no "problems" (earlier
// manifests stay resumable), and other globs are another run.
TEST(BenchPlan, ProblemGlobsRoundTripThroughTheManifest) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-plan-problems-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  BenchRequest r = TinyRequest();
  r.calibrate = false;
  r.problems = {"tiny/infeasible*", "tiny/*"};
  const BenchPlan plan = MakeBenchPlan(r);
  RunManifest manifest;
  manifest.options = PlanOptionsJson(plan);
  manifest.suites = PlanSuites(plan);
  manifest.jobs = plan.jobs;
  manifest.job_shard = AssignShards(manifest.jobs, 1);
  WriteRunManifest(manifest, dir.string());
  const RunManifest back = ReadRunManifest(dir.string());
  EXPECT_EQ(back.options.at("problems"), nlohmann::json(r.problems));
  EXPECT_EQ(ManifestMismatch(manifest, back), "");

  r.problems = {"tiny/infeasible*"};
  RunManifest other = manifest;
  other.options = PlanOptionsJson(MakeBenchPlan(r));
  EXPECT_THAT(ManifestMismatch(manifest, other), HasSubstr("options.problems"));
  r.problems.clear();
  const nlohmann::json unfiltered = PlanOptionsJson(MakeBenchPlan(r));
  EXPECT_FALSE(unfiltered.contains("problems"));
  fs::remove_all(dir);
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
