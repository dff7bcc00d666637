// A fourth problem kind, registered only here, runs through the whole path of a benchmark (plan, job list, two
// shards, merge, compare, report) with no change to the dispatcher: the test of the problem kind interface.
#include "bench/kinds/problem_kind.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "bench/analysis/report_markdown.h"
#include "bench/compare/compare_runs.h"
#include "bench/kinds/avi_kind.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/builtin_kinds.h"
#include "bench/kinds/mcp_kind.h"
#include "bench/replay/floor.h"
#include "bench/replay/jobs.h"
#include "bench/run/bench_plan.h"
#include "bench/run/run_shard.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The toy kind: a scalar root problem x³ + a·x = b (a > 0: one real root, f increasing), solved by its own tiny
// method (Newton from x = 0 for the backend "newton", bisection on [−|b|−1, |b|+1] for any other), judged by
// |f(x)| ≤ tolerance·(1 + |b|), with a reference root by bisection to the last bit.
struct RootProblem {
  std::string id;
  double a = 1.0, b = 0.0;
  double F(double x) const { return x * x * x + a * x - b; }
};

double ReferenceRoot(const RootProblem& p) {
  double lo = -std::fabs(p.b) - 1.0, hi = std::fabs(p.b) + 1.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (p.F(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Its own solver: the root and the iterations taken.
std::pair<double, int> SolveRoot(const RootProblem& p, const std::string& method, double tolerance) {
  const double limit = tolerance * (1.0 + std::fabs(p.b));
  if (method == "newton") {
    double x = 0.0;
    for (int k = 0; k < 100; ++k) {
      if (std::fabs(p.F(x)) <= limit) return {x, k};
      x -= p.F(x) / (3.0 * x * x + p.a);
    }
    return {x, 100};
  }
  double lo = -std::fabs(p.b) - 1.0, hi = std::fabs(p.b) + 1.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (std::fabs(p.F(mid)) <= limit) return {mid, k};
    (p.F(mid) < 0.0 ? lo : hi) = mid;
  }
  return {0.5 * (lo + hi), 200};
}

class RootSuite final : public KindSuite {
 public:
  explicit RootSuite(std::vector<RootProblem> problems) : problems_(std::move(problems)) {}

  std::string kind() const override { return "root"; }
  std::string name() const override { return "root"; }
  SuiteResults Describe() const override {
    SuiteResults suite;
    suite.suite = "root";
    suite.kind = "root";
    suite.description = "scalar roots of x^3 + a x = b";
    suite.problems = static_cast<int>(problems_.size());
    suite.checksum = StableHashHex(std::to_string(problems_.size()));
    return suite;
  }
  std::vector<SuiteUnit> Units() const override {
    std::vector<SuiteUnit> units;
    for (std::size_t p = 0; p < problems_.size(); ++p) units.push_back({p, problems_[p].id, false, 0, ""});
    return units;
  }
  double EstimateSeconds(const SuiteJob&, const ReplayOptions&, const BackendCost& cost,
                         const JobBudgets&) const override {
    return cost.job_seconds;
  }
  ReplayRecord Replay(const BenchJob& job, Solver* /*solver: the toy solves alone*/,
                      const ReplayOptions& /*options*/) const override {
    const RootProblem& p = problems_.at(job.problem);
    const auto [x, iterations] = SolveRoot(p, job.solver, job.tolerance);
    ReplayRecord r = Describe(job);
    r.iterations = iterations;
    r.residual_abs = std::fabs(p.F(x));
    r.residual_rel = r.residual_scaled = r.residual_abs / (1.0 + std::fabs(p.b));
    r.forward_error = std::fabs(x - ReferenceRoot(p));
    const bool solved = r.residual_rel <= job.tolerance;
    r.status = solved ? SolveStatus::kSolved : SolveStatus::kIterationLimit;
    r.verdict = solved ? Verdict::kSolved : Verdict::kFailed;
    r.samples = 1;
    r.solves_per_sample = 1;
    r.time_median = r.time_min = r.time_max = 1e-7;
    return r;
  }
  ReplayRecord Floor(const BenchJob& job, const ReplayOptions&) const override {
    ReplayRecord r = Describe(job);
    r.mode = kFloorSolver;
    r.status = SolveStatus::kSolved;
    r.message = "a scalar: nothing to factor";
    r.samples = 1;
    r.time_median = r.time_min = r.time_max = 1e-9;
    return r;
  }
  ReplayRecord NotRun(const BenchJob& job, const std::string& message) const override {
    ReplayRecord r = Describe(job);
    r.status = SolveStatus::kTimeLimit;
    r.message = message;
    r.verdict = Verdict::kFailed;
    r.residual_abs = r.residual_rel = r.residual_scaled = kInf;
    return r;
  }

 private:
  ReplayRecord Describe(const BenchJob& job) const {
    ReplayRecord r;
    r.suite = "root";
    r.problem = problems_.at(job.problem).id;
    r.solver = job.solver;
    r.size = 1;
    r.expected = ExpectedOutcome::kSolvable;
    r.certificate = "bisection";
    r.tolerance = job.tolerance;
    return r;
  }

  std::vector<RootProblem> problems_;
};

class RootKind final : public ProblemKind {
 public:
  std::string name() const override { return "root"; }
  bool Builds(const std::string& suite_name) const override { return suite_name == "root"; }
  BuiltSuite Build(const std::string&, const SuiteBuildRequest&, ProblemFilter* filter) const override {
    std::vector<RootProblem> problems = {{"root/a1/b2", 1.0, 2.0}, {"root/a3/b-7", 3.0, -7.0},
                                         {"root/a0.5/b100", 0.5, 100.0}};
    BuiltSuite built;
    built.first_id = problems.front().id;
    KeepSelected(&problems, [](const RootProblem& p) -> const std::string& { return p.id; }, filter);
    built.line = "suite root (" + std::to_string(problems.size()) + " scalar roots)";
    if (!problems.empty()) built.suite = std::make_shared<RootSuite>(std::move(problems));
    return built;
  }
  // Which of its own methods runs is named by the backend: Newton for newton, bisection for the others.
  std::vector<std::string> Backends(const std::vector<std::string>& solvers) const override { return solvers; }
};

BenchRequest RootRequest() {
  BenchRequest request;
  request.suites = {"root", "tiny"};  // the box suite comes first in the plan: kinds are grouped in their order
  request.solvers = {"lemke", "newton"};
  request.quick = true;
  request.repetitions = 1;
  request.calibrate = false;
  request.warm = false;
  request.stepper = StepperStudyChoice::kNever;
  request.kinds = BuiltinProblemKinds();
  request.kinds.push_back(std::make_shared<RootKind>());
  return request;
}

// One shard of the plan run into its own folder, as `smcbench bench --shard K/2 --out DIR` writes it.
void RunShardInto(const BenchPlan& plan, int shard, const std::string& dir) {
  fs::create_directories(dir);
  RunManifest manifest;
  manifest.command = "test";
  manifest.environment = nlohmann::json::object();
  manifest.options = PlanOptionsJson(plan);
  manifest.suites = PlanSuites(plan);
  manifest.jobs = plan.jobs;
  manifest.shard = shard;
  manifest.shards = 2;
  manifest.job_shard = AssignShards(plan.jobs, 2);
  WriteRunManifest(manifest, dir);
  JobLineWriter writer((fs::path(dir) / "records.jsonl").string());
  RunShard(plan, {shard, 2}, {}, [&](const JobLine& line) { writer.Write(line); });
}

TEST(ProblemKind, AFourthKindRunsThroughPlanShardsMergeCompareAndReport) {
  const BenchPlan plan = MakeBenchPlan(RootRequest());
  ASSERT_EQ(plan.suites.size(), 2u);
  EXPECT_EQ(plan.suites[0]->kind(), "box");
  EXPECT_EQ(plan.suites[1]->kind(), "root");
  std::vector<std::string> root_ids;
  for (const BenchJob& job : plan.jobs) {
    if (job.suite == 1) root_ids.push_back(job.id);
  }
  // Per problem: each backend, then the floor (the default layout of KindSuite::Jobs).
  ASSERT_EQ(root_ids.size(), 9u);
  EXPECT_EQ(root_ids[0], "root|root/a1/b2|lemke|cold|1e-10");
  EXPECT_EQ(root_ids[1], "root|root/a1/b2|newton|cold|1e-10");
  EXPECT_EQ(root_ids[2], "root|root/a1/b2|floor|floor|1e-10");

  const fs::path dir = fs::temp_directory_path() / ("smcbench-kind-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  RunShardInto(plan, 0, (dir / "s1").string());
  RunShardInto(plan, 1, (dir / "s2").string());
  const MergeReport merged = MergeRunFolders({(dir / "s1").string(), (dir / "s2").string()});
  EXPECT_TRUE(merged.missing.empty());
  EXPECT_TRUE(merged.duplicated.empty());
  ASSERT_EQ(merged.results.suites.size(), 2u);
  const SuiteResults& root = merged.results.suites[1];
  EXPECT_EQ(root.suite, "root");
  ASSERT_EQ(root.replay.records.size(), 6u);
  EXPECT_EQ(root.replay.floor.size(), 3u);
  for (const ReplayRecord& r : root.replay.records) {
    EXPECT_EQ(r.verdict, Verdict::kSolved) << r.problem << " " << r.solver;
    EXPECT_LE(r.forward_error, 1e-8) << r.problem << " " << r.solver;
  }
  EXPECT_LT(root.replay.records[1].iterations, root.replay.records[0].iterations) << "Newton beats bisection";
  // The merged results are what a single run of the same plan gives, record for record (the toy is deterministic).
  std::map<std::size_t, JobLine> single;
  RunShard(plan, {0, 1}, {}, [&](const JobLine& line) { single[line.job] = line; });
  const BenchResults one_run = PlanResults(plan, single);
  for (std::size_t i = 0; i < root.replay.records.size(); ++i) {
    EXPECT_EQ(ReplayRecordToJson(root.replay.records[i])["iterations"],
              ReplayRecordToJson(one_run.suites[1].replay.records[i])["iterations"]);
  }

  // compare: the run against itself, no verdict change; report: the fourth kind's suite is in it.
  CompareOptions compare;
  compare.resamples = 100;
  EXPECT_TRUE(CompareRuns(merged.results, merged.results, compare).verdict_changes.empty());
  WriteBenchResults(merged.results, (dir / "merged").string());
  const std::string report = WriteBenchReport((dir / "merged").string(), /*plots=*/false);
  EXPECT_THAT(report, HasSubstr("root"));
  fs::remove_all(dir);
}

// A suite name no kind builds is refused before anything runs; the kind's own filter works as the others'.
TEST(ProblemKind, UnknownSuitesAreRefusedAndTheFilterReachesEveryKind) {
  BenchRequest request = RootRequest();
  request.kinds = BuiltinProblemKinds();  // without the root kind
  request.suites = {"root"};
  EXPECT_THROW(MakeBenchPlan(request), InvalidInputError);

  request = RootRequest();
  request.problems = {"root/a3/*"};
  const BenchPlan plan = MakeBenchPlan(request);
  ASSERT_EQ(plan.suites.size(), 1u);  // tiny left out
  EXPECT_EQ(plan.suites[0]->Units().size(), 1u);
  EXPECT_EQ(plan.suite_names, std::vector<std::string>{"root"});
}

// A built-in suite of one kind goes to that kind even beside a file of its name: `bench --suite mcp` in a folder
// that holds a file named mcp runs the MCP suite, as it did before the kinds (the box kind reads files).
TEST(ProblemKind, ABuiltInSuiteNameIsNeverReadAsAFile) {
  const fs::path dir = fs::path(testing::TempDir()) / "kind-names";
  fs::create_directories(dir);
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  for (const char* name : {"mcp", "avi", "mine.smcps"}) std::ofstream(name) << "not a problem set\n";
  EXPECT_FALSE(BoxProblemKind()->Builds("mcp"));
  EXPECT_FALSE(BoxProblemKind()->Builds("avi"));
  EXPECT_TRUE(McpProblemKind()->Builds("mcp"));
  EXPECT_TRUE(AviProblemKind()->Builds("avi"));
  EXPECT_TRUE(BoxProblemKind()->Builds("mine.smcps"));  // a file: the box reader says what is wrong with it
  EXPECT_TRUE(BoxProblemKind()->Builds("paper"));
  fs::current_path(before);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace smcbench
