// The AVI replay on hand-made AVIs whose answers are known in closed form (a projection onto a box, an AVI with no
// solution), so the verdicts asserted here follow from the problems, not from any backend: records, cold timing
// of a backend with a cache, the checksum, results on disk, AVI jobs and their assembly.
#include "bench/replay/avi_replay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/replay/jobs.h"
#include "bench/replay/results_io.h"
#include "bench/kinds/avi_kind.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/job_list.h"
#include "solvers/registry/registry.h"
#include "tests/support/caching_backend.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

// M = I over the box [−1, 1]²: λ = Π(−q), here (1, −0.5), unique (M positive definite).
AviLibraryProblem BoxProjection() {
  DenseMatrix H(4, 2);
  H << 1, 0, 0, 1, -1, 0, 0, -1;
  Vector q(2), K = -Vector::Ones(4);
  q << -2.0, 0.5;
  AviLibraryProblem p;
  p.id = "avi/test/box-projection";
  p.source = "hand-made:projection";
  p.problem = std::make_shared<const AffineVI>(DenseMatrix::Identity(2, 2), q, H, K, p.id);
  p.tags = {"test"};
  p.expected = ExpectedOutcome::kSolvable;
  Vector lambda(2), mu = Vector::Zero(4);
  lambda << 1.0, -0.5;
  mu[2] = 1.0;  // −λ₁ ≥ −1 active: Mλ + q = (−1, 0) = Hᵀμ
  p.reference = CertifyAvi(*p.problem, {AviSolution{lambda, mu, Vector()}});
  return p;
}

// λ ≥ 0, M = 0, q = −1: Mλ + q = −1 = μ ≥ 0 is impossible.
AviLibraryProblem NoSolution() {
  AviLibraryProblem p;
  p.id = "avi/test/no-solution";
  p.source = "hand-made:no solution";
  p.problem = std::make_shared<const AffineVI>(DenseMatrix::Zero(1, 1), -Vector::Ones(1), DenseMatrix::Identity(1, 1),
                                               Vector::Zero(1), p.id);
  p.expected = ExpectedOutcome::kInfeasible;
  return p;
}

AviProblemSet Set() {
  AviProblemSet set;
  set.name = "avi-test";
  set.description = "hand-made AVIs";
  set.problems = {BoxProjection(), NoSolution()};
  set.Validate();
  return set;
}

ReplayOptions Quick(std::vector<std::string> solvers) {
  ReplayOptions o;
  o.solvers = std::move(solvers);
  o.tolerance = 1e-10;
  o.repetitions = 2;
  o.min_sample_seconds = 0.0;
  o.max_seconds_per_pair = 0.05;
  o.time_limit_seconds = 5.0;
  return o;
}

// Says "no solution" to everything: judged by the problem's expected outcome, not by the flag.
class ClaimsNoSolution final : public Solver {
 public:
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"claims-no-solution", "refuses every problem", "none"};
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& /*options*/, SolveResult* result) override {
    result->z = Vector::Zero(problem.size());
    result->status = SolveStatus::kInfeasible;
  }
};

TEST(AviReplay, LemkeSolvesTheProjectionAndRefusesTheAviWithoutSolution) {
  const AviProblemSet set = Set();
  ASSERT_TRUE(set.problems[0].reference.verified());
  ASSERT_TRUE(set.problems[0].reference.lambda_unique);
  const ReplayResults results = ReplayAviProblemSet(set, Quick({"lemke", "psor"}));
  ASSERT_EQ(results.records.size(), 4u);  // (problem, backend)
  const ReplayRecord& solved = results.records[0];
  EXPECT_EQ(solved.suite, "avi-test");
  EXPECT_EQ(solved.problem, "avi/test/box-projection");
  EXPECT_EQ(solved.solver, "lemke");
  EXPECT_EQ(solved.size, 2);
  EXPECT_EQ(solved.tags, "test");
  EXPECT_EQ(solved.mode, "cold");
  EXPECT_EQ(solved.status, SolveStatus::kSolved);
  EXPECT_EQ(solved.verdict, Verdict::kSolved);
  EXPECT_LE(solved.forward_error, 1e-14);  // against λ* = (1, −0.5)
  EXPECT_GT(solved.forward_allowance, 0.0);
  EXPECT_GE(solved.samples, 1);
  EXPECT_GT(solved.time_median, 0.0);
  EXPECT_EQ(solved.certificate, std::string(ToString(set.problems[0].reference.reduced.certificate)));
  EXPECT_EQ(results.records[1].solver, "psor");
  EXPECT_NE(results.records[1].verdict, Verdict::kWronglyClaimed);
  const ReplayRecord& refused = results.records[2];
  EXPECT_EQ(refused.problem, "avi/test/no-solution");
  EXPECT_NE(refused.status, SolveStatus::kSolved);
  EXPECT_EQ(refused.verdict, Verdict::kCorrectlyRefused);
  EXPECT_TRUE(std::isnan(refused.forward_error));
}

TEST(AviReplay, RefusalsAreJudgedByTheExpectedOutcome) {
  const AviProblemSet set = Set();
  ClaimsNoSolution refuser;
  const ReplayOptions options = Quick({});
  EXPECT_EQ(ReplayAviOne(set, set.problems[0], &refuser, "claims-no-solution", options, 1e-10).verdict,
            Verdict::kWronglyRefused);
  EXPECT_EQ(ReplayAviOne(set, set.problems[1], &refuser, "claims-no-solution", options, 1e-10).verdict,
            Verdict::kCorrectlyRefused);
  EXPECT_EQ(BackendsWith({"lemke", "newton", "psor"}, &SolverInfo::box), (std::vector<std::string>{"lemke", "newton", "psor"}));
}

// Cold means cold: a backend with a cache answers no timed solve from it; one that cannot forget is "cached".
TEST(AviReplay, EveryTimedSolveStartsCold) {
  const AviProblemSet set = Set();
  test_support::CachingBackend forgets(true);
  const ReplayRecord cold = ReplayAviOne(set, set.problems[0], &forgets, "caching", Quick({}), 1e-10);
  EXPECT_EQ(cold.mode, "cold");
  EXPECT_EQ(cold.verdict, Verdict::kSolved);
  EXPECT_EQ(forgets.answered_from_cache(), 0);
  EXPECT_EQ(forgets.solved_by_lemke(), 1 + cold.samples * cold.solves_per_sample);  // the warm-up, then samples
  test_support::CachingBackend keeps(false);
  EXPECT_EQ(ReplayAviOne(set, set.problems[0], &keeps, "caching", Quick({}), 1e-10).mode, "cached");
}

TEST(AviReplay, ChecksumCoversDataAndReferences) {
  const std::string base = AviProblemSetChecksum(Set());
  EXPECT_EQ(base.size(), 16u);
  EXPECT_EQ(base, AviProblemSetChecksum(Set()));
  AviProblemSet other = Set();
  other.problems[1].id = "avi/test/none2";
  EXPECT_NE(AviProblemSetChecksum(other), base);
  other = Set();
  other.problems[0].reference.reduced.z[0] = 0.75;
  EXPECT_NE(AviProblemSetChecksum(other), base);
  other = Set();
  Vector q = other.problems[0].problem->q();
  q[1] = 0.25;
  auto changed = std::make_shared<AffineVI>(*other.problems[0].problem);
  changed->set_q(q);
  other.problems[0].problem = changed;
  EXPECT_NE(AviProblemSetChecksum(other), base);
}

TEST(AviReplay, RecordsRoundTripThroughJsonAndCsv) {
  const AviProblemSet set = Set();
  BenchResults results;
  results.command = "smcbench bench --suite avi";
  SuiteResults suite;
  suite.suite = set.name;
  suite.description = set.description;
  suite.problems = 2;
  suite.checksum = AviProblemSetChecksum(set);
  suite.replay = ReplayAviProblemSet(set, Quick({"lemke", "newton"}));
  results.suites.push_back(suite);
  const fs::path dir = fs::path(testing::TempDir()) / "avi-replay-roundtrip";
  fs::remove_all(dir);
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  EXPECT_EQ(back.suites[0].checksum, suite.checksum);
  ASSERT_EQ(back.suites[0].replay.records.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(ReplayRecordToJson(suite.replay.records[i]), ReplayRecordToJson(back.suites[0].replay.records[i]));
  }
  std::ifstream csv(dir / "results.csv");
  std::string line;
  std::getline(csv, line);  // header
  int rows = 0;
  while (std::getline(csv, line)) {
    EXPECT_EQ(line.rfind("avi-test,avi/test/", 0), 0u) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 4);
  fs::remove_all(dir);
}

TEST(AviJobs, ListedAfterTheOtherSuitesShardedAndAssembled) {
  const AviProblemSet set = Set();
  ProblemSet box;
  box.name = "empty-box";
  const ReplayOptions options = Quick({});
  JobListRequest request;
  request.solvers = {"lemke"};
  request.kind_solvers["avi"] = {"lemke", "newton"};
  const std::vector<BenchJob> jobs = ListBenchJobs({MakeBoxSuite(box), MakeAviSuite(set)}, options, request);
  ASSERT_EQ(jobs.size(), 4u);
  EXPECT_EQ(jobs[0].id, "avi-test|avi/test/box-projection|lemke|cold|1e-10");
  EXPECT_EQ(jobs[3].id, "avi-test|avi/test/no-solution|newton|cold|1e-10");
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    EXPECT_EQ(jobs[i].kind, JobKind::kCold);
    EXPECT_EQ(jobs[i].kind_name, "avi");  // the manifest's name of an AVI job, as before the problem kinds
    EXPECT_EQ(jobs[i].index, i);
    EXPECT_EQ(jobs[i].suite, 1u);  // after the one box suite (and no MCP suite)
    EXPECT_GT(jobs[i].cost, 0.0);
  }
  const std::vector<int> shard = AssignShards(jobs, 2);
  EXPECT_EQ(shard, AssignShards(jobs, 2));

  RunManifest manifest;
  manifest.command = "smcbench bench --suite avi";
  manifest.environment = nlohmann::json::object();
  manifest.options = nlohmann::json::object();
  SuiteResults box_suite, avi_suite;
  box_suite.suite = box.name;
  avi_suite.suite = set.name;
  avi_suite.problems = 2;
  avi_suite.checksum = AviProblemSetChecksum(set);
  manifest.suites = {box_suite, avi_suite};
  manifest.jobs = jobs;
  manifest.shards = 2;
  manifest.job_shard = shard;
  const RunManifest back = RunManifestFromJson(RunManifestToJson(manifest), "manifest");
  EXPECT_EQ(ManifestMismatch(manifest, back), "");
  ASSERT_EQ(back.jobs.size(), 4u);
  EXPECT_EQ(back.jobs[2].kind, JobKind::kCold);
  EXPECT_EQ(back.jobs[2].kind_name, "avi");
  std::map<std::size_t, JobLine> lines;
  for (const BenchJob& job : back.jobs) {
    auto solver = CreateSolver(job.solver);
    JobLine line;
    line.job = job.index;
    line.id = job.id;
    line.has_record = true;
    line.record = ReplayAviOne(set, set.problems[job.problem], solver.get(), job.solver, options, job.tolerance);
    lines[job.index] = line;
  }
  const BenchResults assembled = AssembleResults(back, lines);
  ASSERT_EQ(assembled.suites.size(), 2u);
  EXPECT_TRUE(assembled.suites[0].replay.records.empty());
  ASSERT_EQ(assembled.suites[1].replay.records.size(), 4u);
  EXPECT_EQ(assembled.suites[1].replay.records[0].verdict, Verdict::kSolved);
  EXPECT_EQ(assembled.suites[1].replay.records[3].verdict, Verdict::kCorrectlyRefused);
}

}  // namespace
}  // namespace smcbench
