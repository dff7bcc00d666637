// The MCP replay on hand-made MCPs whose solutions are known in closed form, so the verdicts asserted here follow
// from the problems, not from any backend: a strongly monotone problem (one solution, planted), a problem with no
// solution, and two near-roots (F tiny where J is tiny too, far from any solution) on which a backend that stops
// there is caught by the forward error or by the expected outcome.
#include "bench/replay/mcp_replay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "bench/replay/jobs.h"
#include "bench/replay/results_io.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/job_list.h"
#include "bench/kinds/mcp_kind.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

ReferenceSolution Reference(Certificate certificate, std::initializer_list<double> z, double condition) {
  ReferenceSolution r;
  r.certificate = certificate;
  r.z = Vector(static_cast<Eigen::Index>(z.size()));
  Eigen::Index i = 0;
  for (double v : z) r.z[i++] = v;
  r.condition = condition;
  return r;
}

Vector Constant(int n, double v) { return Vector::Constant(n, v); }

// F_i(z) = z_i³ + z_i − b_i on z ≥ 0, b = (2, −1): J ⪰ I, so F is strongly monotone and the solution unique:
// z* = (1, 0) (1 + 1 − 2 = 0 inside; F_2(0) = 1 > 0 at the bound), strictly complementary; at z* the free row's
// Jacobian is 4, its row scale 4, so μ = 1.
McpLibraryProblem PlantedCubic(double b1 = 2.0) {
  McpLibraryProblem p;
  p.id = "mcp/test/cubic";
  p.source = "generated:test";
  p.tags = {"test"};
  p.problem = std::make_shared<FunctionMCP>(
      Vector::Zero(2), Constant(2, kInf),
      [b1](const Vector& z, Vector* F) { *F << z[0] * z[0] * z[0] + z[0] - b1, z[1] * z[1] * z[1] + z[1] + 1.0; },
      [](const Vector& z, DenseMatrix* J) { *J << 3 * z[0] * z[0] + 1, 0, 0, 3 * z[1] * z[1] + 1; });
  p.starts = {Vector::Zero(2), Constant(2, 3.0)};
  p.start_labels = {"z0=0", "z0=3"};
  p.expected = ExpectedOutcome::kSolvable;
  p.references = {Reference(Certificate::kUnique, {1.0, 0.0}, 1.0)};
  return p;
}

// F(z) = −1 − z on z ≥ 0: F < 0 everywhere, so z would have to sit at its upper bound +∞. No solution.
McpLibraryProblem NoSolution() {
  McpLibraryProblem p;
  p.id = "mcp/test/none";
  p.source = "generated:test";
  p.problem = std::make_shared<FunctionMCP>(
      Vector::Zero(1), Constant(1, kInf), [](const Vector& z, Vector* F) { (*F)[0] = -1.0 - z[0]; },
      [](const Vector&, DenseMatrix* J) { (*J)(0, 0) = -1.0; });
  p.starts = {Vector::Zero(1)};
  p.start_labels = {"z0=0"};
  p.expected = ExpectedOutcome::kInfeasible;
  return p;
}

constexpr double kEps = 1e-24;

// F(z) = (z − 1)((z − 3)² + ε) on [−10, 10]: the second factor is > 0, so z* = 1 is the only root (J(1) = 4 + ε,
// μ = 1). Near z = 3 + δ, F ≈ 2(δ² + ε) and J ≈ 4δ, so for δ = 1e-12 the scale-free residual F/J/(1 + |z|) is
// 2.5e-13: a point 2 away from z* passes the residual test at 1e-10.
McpLibraryProblem NearRootSolvable() {
  McpLibraryProblem p;
  p.id = "mcp/test/near-root";
  p.source = "generated:test";
  p.problem = std::make_shared<FunctionMCP>(
      Constant(1, -10.0), Constant(1, 10.0),
      [](const Vector& z, Vector* F) { (*F)[0] = (z[0] - 1.0) * ((z[0] - 3.0) * (z[0] - 3.0) + kEps); },
      [](const Vector& z, DenseMatrix* J) {
        (*J)(0, 0) = (z[0] - 3.0) * (z[0] - 3.0) + kEps + (z[0] - 1.0) * 2.0 * (z[0] - 3.0);
      });
  p.starts = {Vector::Zero(1)};
  p.start_labels = {"z0=0"};
  p.expected = ExpectedOutcome::kSolvable;
  p.references = {Reference(Certificate::kUnique, {1.0}, 1.0)};
  return p;
}

// F(z) = −((z − 3)² + ε) on z ≥ 0: F < 0 everywhere, no solution; near z = 3 + 1e-12 the scale-free residual is
// 2.5e-13 all the same.
McpLibraryProblem NearRootInfeasible() {
  McpLibraryProblem p;
  p.id = "mcp/test/near-root-none";
  p.source = "generated:test";
  p.problem = std::make_shared<FunctionMCP>(
      Vector::Zero(1), Constant(1, kInf),
      [](const Vector& z, Vector* F) { (*F)[0] = -((z[0] - 3.0) * (z[0] - 3.0) + kEps); },
      [](const Vector& z, DenseMatrix* J) { (*J)(0, 0) = -2.0 * (z[0] - 3.0); });
  p.starts = {Vector::Zero(1)};
  p.start_labels = {"z0=0"};
  p.expected = ExpectedOutcome::kInfeasible;
  return p;
}

McpProblemSet Set(std::vector<McpLibraryProblem> problems) {
  McpProblemSet set;
  set.name = "mcp-test";
  set.description = "hand-made MCPs with known solutions";
  set.problems = std::move(problems);
  return set;
}

// A backend that stops at z = 3 + 1e-12 and calls it solved: the near-roots above.
class StopsAtNearRoot final : public Solver {
 public:
  static constexpr const char* kName = "test-mcp-near-root";
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{kName, "claims z = 3 + 1e-12", "none", true, false, false, false, true};
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) override {
    result->status = SolveStatus::kNotApplicable;
  }
  void DoSolveMCP(const MCP& problem, const SolverOptions&, SolveResult* result) override {
    result->z = Vector::Constant(problem.size(), 3.0 + 1e-12);
    result->iterations = 1;
    result->status = SolveStatus::kSolved;
  }
};

// A backend that claims every MCP has no solution.
class ClaimsNoSolution final : public Solver {
 public:
  static constexpr const char* kName = "test-mcp-claims-none";
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{kName, "claims infeasible", "none", true, false, false, false, true};
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) override {
    result->status = SolveStatus::kNotApplicable;
  }
  void DoSolveMCP(const MCP&, const SolverOptions&, SolveResult* result) override {
    result->status = SolveStatus::kInfeasible;
    result->message = "no solution (claimed)";
  }
};

// Registrations last for the process: once.
void RegisterFakes() {
  static const bool done = [] {
    RegisterSolver(StopsAtNearRoot::kName, [] { return std::make_unique<StopsAtNearRoot>(); });
    RegisterSolver(ClaimsNoSolution::kName, [] { return std::make_unique<ClaimsNoSolution>(); });
    return true;
  }();
  (void)done;
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

const ReplayRecord& Find(const ReplayResults& results, const std::string& problem, const std::string& start,
                         const std::string& solver) {
  for (const ReplayRecord& r : results.records) {
    if (r.problem == problem && r.start == start && r.solver == solver) return r;
  }
  ADD_FAILURE() << "no record " << problem << "@" << start << " " << solver;
  static const ReplayRecord none;
  return none;
}

TEST(McpReplay, NewtonSolvesThePlantedProblemFromEveryStartAndRefusesTheOneWithoutSolution) {
  const McpProblemSet set = Set({PlantedCubic(), NoSolution()});
  const ReplayResults results = ReplayMcpProblemSet(set, Quick({"newton"}));
  ASSERT_EQ(results.records.size(), 3u);  // 2 starts + 1 start, one backend
  EXPECT_TRUE(results.sweep.empty());
  for (const char* start : {"z0=0", "z0=3"}) {
    const ReplayRecord& r = Find(results, "mcp/test/cubic", start, "newton");
    EXPECT_EQ(r.verdict, Verdict::kSolved) << start << ": " << r.message;
    EXPECT_EQ(r.suite, "mcp-test");
    EXPECT_EQ(r.size, 2);
    EXPECT_EQ(r.tags, "test");
    EXPECT_EQ(r.certificate, "unique");
    EXPECT_LE(r.residual_scaled, 1e-10);
    // The forward error against the closed-form z* = (1, 0), within the allowance 10·max(1, μ)·tol·(1 + ‖z*‖).
    EXPECT_LE(r.forward_error, 2e-9);
    EXPECT_DOUBLE_EQ(r.forward_allowance, 10.0 * 1e-10 * 2.0);
    EXPECT_GE(r.samples, 1);
    EXPECT_GT(r.time_median, 0.0);
    EXPECT_LE(r.time_min, r.time_median);
    EXPECT_LE(r.time_median, r.time_max);
  }
  const ReplayRecord& none = Find(results, "mcp/test/none", "z0=0", "newton");
  EXPECT_NE(none.status, SolveStatus::kSolved);
  EXPECT_EQ(none.verdict, Verdict::kCorrectlyRefused) << none.message;
  EXPECT_TRUE(std::isnan(none.forward_error));  // no reference
}

TEST(McpReplay, EveryMcpBackendIsRightOrHonestOnThePlantedSet) {
  std::vector<std::string> ours;
  for (const std::string& name : BackendsWith({}, &SolverInfo::mcp)) {
    if (name.rfind("test-", 0) != 0) ours.push_back(name);  // not this file's fakes
  }
  ASSERT_FALSE(ours.empty());
  EXPECT_NE(std::find(ours.begin(), ours.end(), "newton"), ours.end());
  const ReplayResults results = ReplayMcpProblemSet(Set({PlantedCubic(), NoSolution()}), Quick(ours));
  EXPECT_EQ(results.records.size(), 3 * ours.size());
  for (const ReplayRecord& r : results.records) {
    EXPECT_FALSE(IsWrong(r.verdict)) << r.solver << " on " << r.problem << "@" << r.start << ": "
                                     << ToString(r.verdict) << " (" << r.message << ")";
  }
}

TEST(McpReplay, WrongAnswersAreWronglyClaimedInaccurateOrWronglyRefused) {
  RegisterFakes();
  const McpProblemSet set = Set({NearRootSolvable(), NearRootInfeasible(), PlantedCubic()});
  const ReplayResults results =
      ReplayMcpProblemSet(set, Quick({StopsAtNearRoot::kName, ClaimsNoSolution::kName}));
  // Passes the scale-free residual, 2 away from the only solution: inaccurate.
  const ReplayRecord& near = Find(results, "mcp/test/near-root", "z0=0", StopsAtNearRoot::kName);
  EXPECT_EQ(near.status, SolveStatus::kSolved);
  EXPECT_LE(near.residual_scaled, 1e-10);
  EXPECT_NEAR(near.forward_error, 2.0, 1e-9);
  EXPECT_EQ(near.verdict, Verdict::kInaccurate);
  // "Solved" on a problem with no solution: wrongly claimed, whatever the residual.
  const ReplayRecord& none = Find(results, "mcp/test/near-root-none", "z0=0", StopsAtNearRoot::kName);
  EXPECT_LE(none.residual_scaled, 1e-10);
  EXPECT_EQ(none.verdict, Verdict::kWronglyClaimed);
  // "No solution" on a problem known to have one, and on one that has none.
  EXPECT_EQ(Find(results, "mcp/test/cubic", "z0=3", ClaimsNoSolution::kName).verdict, Verdict::kWronglyRefused);
  EXPECT_EQ(Find(results, "mcp/test/near-root-none", "z0=0", ClaimsNoSolution::kName).verdict,
            Verdict::kCorrectlyRefused);
}

TEST(McpReplay, BackendsWithoutMcpsAreNotRun) {
  EXPECT_EQ(BackendsWith({"lemke", "newton", "psor"}, &SolverInfo::mcp), std::vector<std::string>{"newton"});
  EXPECT_TRUE(ReplayMcpProblemSet(Set({PlantedCubic()}), Quick({"lemke"})).records.empty());
  // A setting for a box-only backend of the selection is not an error on the MCP set; newton gets its own.
  ReplayOptions with_settings = Quick({"psor", "newton"});
  with_settings.settings = {"psor.omega=1.2", "newton.max_backtracks=30"};
  const ReplayResults mixed = ReplayMcpProblemSet(Set({PlantedCubic()}), with_settings);
  ASSERT_EQ(mixed.records.size(), 2u);
  EXPECT_EQ(mixed.records[0].solver, "newton");
  EXPECT_EQ(mixed.records[0].verdict, Verdict::kSolved);
  // Called directly, a box-only backend gets an honest record, never a crash.
  const McpProblemSet set = Set({PlantedCubic()});
  auto lemke = CreateSolver("lemke");
  const ReplayRecord r = ReplayMcpOne(set, set.problems[0], 1, lemke.get(), "lemke", Quick({}), 1e-10);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_EQ(r.verdict, Verdict::kFailed);
  EXPECT_EQ(r.start, "z0=3");
  EXPECT_THROW(ReplayMcpOne(set, set.problems[0], 2, lemke.get(), "lemke", Quick({}), 1e-10), InvalidInputError);
}

TEST(McpReplay, ChecksumCoversIdsStartsReferencesAndF) {
  const std::string base = McpProblemSetChecksum(Set({PlantedCubic(), NoSolution()}));
  EXPECT_EQ(base.size(), 16u);
  EXPECT_EQ(base, McpProblemSetChecksum(Set({PlantedCubic(), NoSolution()})));
  McpProblemSet other = Set({PlantedCubic(), NoSolution()});
  other.problems[0].starts[1][0] = 2.5;
  EXPECT_NE(McpProblemSetChecksum(other), base);
  other = Set({PlantedCubic(), NoSolution()});
  other.problems[0].start_labels[1] = "start2";
  EXPECT_NE(McpProblemSetChecksum(other), base);
  other = Set({PlantedCubic(), NoSolution()});
  other.problems[0].references[0].z[1] = 1e-300;
  EXPECT_NE(McpProblemSetChecksum(other), base);
  other = Set({PlantedCubic(), NoSolution()});
  other.problems[1].id = "mcp/test/none2";
  EXPECT_NE(McpProblemSetChecksum(other), base);
  EXPECT_NE(McpProblemSetChecksum(Set({PlantedCubic(3.0), NoSolution()})), base);  // another F, same data
}

TEST(McpReplay, RecordsRoundTripThroughJsonAndCsvWithTheirStart) {
  const McpProblemSet set = Set({PlantedCubic(), NoSolution()});
  BenchResults results;
  results.command = "smcbench bench --suite mcp";
  SuiteResults suite;
  suite.suite = set.name;
  suite.description = set.description;
  suite.problems = 2;
  suite.checksum = McpProblemSetChecksum(set);
  suite.replay = ReplayMcpProblemSet(set, Quick({"newton"}));
  results.suites.push_back(suite);
  const fs::path dir = fs::path(testing::TempDir()) / "mcp-replay-roundtrip";
  fs::remove_all(dir);
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  ASSERT_EQ(back.suites[0].replay.records.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const ReplayRecord &a = suite.replay.records[i], &b = back.suites[0].replay.records[i];
    EXPECT_EQ(a.start, b.start);
    EXPECT_FALSE(b.start.empty());
    EXPECT_EQ(a.verdict, b.verdict);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.residual_scaled, b.residual_scaled);
    EXPECT_EQ(a.forward_error == a.forward_error ? a.forward_error : 0.0,
              b.forward_error == b.forward_error ? b.forward_error : 0.0);
    EXPECT_EQ(ReplayRecordToJson(a), ReplayRecordToJson(b));
  }
  // CSV: "start" is the last column but backend_code and reference_radius (added after it).
  std::ifstream csv(dir / "results.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  // The record has no backend_code, and an MCP's reference has no proved radius.
  const std::string ends = "," + suite.replay.records[0].start + ",,nan,0";
  const std::string last_columns = ",start,backend_code,reference_radius,reference_proved_unique";
  EXPECT_EQ(header.substr(header.size() - last_columns.size()), last_columns);
  EXPECT_EQ(row.substr(row.size() - ends.size()), ends);
  // A record written before MCPs (no "start") reads as a box record.
  nlohmann::json old = ReplayRecordToJson(suite.replay.records[0]);
  old.erase("start");
  EXPECT_EQ(ReplayRecordFromJson(old).start, "");
}

TEST(McpJobs, ListedPerStartAfterTheBoxSuitesShardedAndAssembled) {
  const McpProblemSet set = Set({PlantedCubic(), NoSolution()});
  ProblemSet box;
  box.name = "empty-box";
  ReplayOptions options = Quick({});
  JobListRequest request;
  request.solvers = {"lemke", "newton"};
  request.kind_solvers["mcp"] = {"newton"};
  const std::vector<BenchJob> jobs = ListBenchJobs({MakeBoxSuite(box), MakeMcpSuite(set)}, options, request);
  ASSERT_EQ(jobs.size(), 3u);  // (2 + 1 starts) × newton; lemke does not solve MCPs
  EXPECT_EQ(jobs[0].id, "mcp-test|mcp/test/cubic@z0=0|newton|cold|1e-10");
  EXPECT_EQ(jobs[1].id, "mcp-test|mcp/test/cubic@z0=3|newton|cold|1e-10");
  EXPECT_EQ(jobs[2].id, "mcp-test|mcp/test/none@z0=0|newton|cold|1e-10");
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    EXPECT_EQ(jobs[i].kind, JobKind::kCold);
    EXPECT_EQ(jobs[i].kind_name, "mcp");  // the manifest's name of an MCP job, as before the problem kinds
    EXPECT_EQ(jobs[i].index, i);
    EXPECT_EQ(jobs[i].suite, 1u);  // after the one box suite
    EXPECT_GT(jobs[i].cost, 0.0);
  }
  EXPECT_EQ(jobs[1].start, 1u);

  // Shards: every job in exactly one of them, the same assignment every time.
  const std::vector<int> shard = AssignShards(jobs, 2);
  EXPECT_EQ(shard, AssignShards(jobs, 2));
  std::set<int> used(shard.begin(), shard.end());
  EXPECT_EQ(used, (std::set<int>{0, 1}));

  // The manifest keeps the start; finished lines are assembled into the MCP suite's records.
  RunManifest manifest;
  manifest.command = "smcbench bench --suite mcp";
  manifest.environment = nlohmann::json::object();
  manifest.options = nlohmann::json::object();
  SuiteResults box_suite, mcp_suite;
  box_suite.suite = box.name;
  mcp_suite.suite = set.name;
  mcp_suite.problems = 2;
  mcp_suite.checksum = McpProblemSetChecksum(set);
  manifest.suites = {box_suite, mcp_suite};
  manifest.jobs = jobs;
  manifest.shards = 2;
  manifest.job_shard = shard;
  const RunManifest back = RunManifestFromJson(RunManifestToJson(manifest), "manifest");
  EXPECT_EQ(ManifestMismatch(manifest, back), "");
  ASSERT_EQ(back.jobs.size(), 3u);
  EXPECT_EQ(back.jobs[1].kind, JobKind::kCold);
  EXPECT_EQ(back.jobs[1].kind_name, "mcp");
  EXPECT_EQ(back.jobs[1].start, 1u);
  EXPECT_EQ(back.jobs[1].start_label, "z0=3");
  auto newton = CreateSolver("newton");
  std::map<std::size_t, JobLine> lines;
  for (const BenchJob& job : back.jobs) {
    JobLine line;
    line.job = job.index;
    line.id = job.id;
    line.has_record = true;
    line.record = ReplayMcpOne(set, set.problems[job.problem], job.start, newton.get(), job.solver, options,
                               job.tolerance);
    lines[job.index] = line;
  }
  const BenchResults assembled = AssembleResults(back, lines);
  ASSERT_EQ(assembled.suites.size(), 2u);
  EXPECT_TRUE(assembled.suites[0].replay.records.empty());
  ASSERT_EQ(assembled.suites[1].replay.records.size(), 3u);
  EXPECT_EQ(assembled.suites[1].replay.records[1].start, "z0=3");
  EXPECT_EQ(assembled.suites[1].replay.records[1].verdict, Verdict::kSolved);
}

}  // namespace
}  // namespace smcbench
