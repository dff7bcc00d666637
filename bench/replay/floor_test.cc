// The floor (floor.h): the factorization chosen from the tags and the storage, timed with the cold protocol
// (the run's repetitions, median between min and max), kept apart from the backends' records through the job list
// and results.json.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "bench/replay/floor.h"
#include "bench/replay/jobs.h"
#include "bench/replay/results_io.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/job_list.h"
#include "solvers/generators/random_problems.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

ReplayOptions FewSamples() {
  ReplayOptions o;
  o.repetitions = 4;
  o.min_sample_seconds = 1e-4;
  o.max_seconds_per_pair = 60.0;  // never cut: every repetition is a sample
  o.tolerance_sweep_problems = 0;
  return o;
}

LibraryProblem Generated(MatrixFamily family, bool sparse, const std::vector<std::string>& tags) {
  GeneratorOptions g;
  g.size = 30;
  g.family = family;
  g.bounds = BoundKind::kRelay;
  g.seed = 5;
  BoxMLCP problem = GenerateProblem(g).problem;
  if (sparse) {
    const SparseMatrix S = problem.dense_matrix().sparseView();
    problem = BoxMLCP(S, problem.q(), problem.l(), problem.u());
  }
  LibraryProblem p = MakeLibraryProblem("floor/p", "generated", std::move(problem));
  p.tags = tags;
  return p;
}

ProblemSet SetOf(LibraryProblem p) {
  ProblemSet set;
  set.name = "mine";
  set.problems.push_back(std::move(p));
  return set;
}

TEST(Floor, TheMethodFollowsTheTagsAndTheStorage) {
  EXPECT_TRUE(TagsSaySpd("spd,relay"));
  EXPECT_TRUE(TagsSaySpd("lcp,symmetric,positive_definite"));
  EXPECT_FALSE(TagsSaySpd("symmetric,lcp"));
  EXPECT_FALSE(TagsSaySpd("pmatrix,relay"));
  EXPECT_FALSE(TagsSaySpd("nonspd"));  // a whole tag, not a part of one
  EXPECT_EQ(ChooseFloorMethod(false, true), FloorMethod::kDenseCholesky);
  EXPECT_EQ(ChooseFloorMethod(false, false), FloorMethod::kDenseLu);
  EXPECT_EQ(ChooseFloorMethod(true, true), FloorMethod::kSparseCholesky);
  EXPECT_EQ(ChooseFloorMethod(true, false), FloorMethod::kSparseLu);
}

TEST(Floor, ARecordTimedAsAColdSolveWithTheRunsRepetitions) {
  const ReplayOptions options = FewSamples();
  const ProblemSet set = SetOf(Generated(MatrixFamily::kSymmetricPositiveDefinite, false, {"spd", "relay"}));
  const ReplayRecord r = ReplayFloor(set, set.problems[0], options);
  EXPECT_EQ(r.solver, kFloorSolver);
  EXPECT_EQ(r.mode, "floor");
  EXPECT_EQ(r.suite, "mine");
  EXPECT_EQ(r.problem, "floor/p");
  EXPECT_EQ(r.tags, "spd,relay");
  EXPECT_EQ(r.size, 30);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.message, "dense Cholesky of a 30×30 matrix");
  EXPECT_EQ(r.samples, options.repetitions);
  EXPECT_GE(r.solves_per_sample, 1);
  EXPECT_GT(r.time_min, 0.0);
  EXPECT_LE(r.time_min, r.time_median);
  EXPECT_LE(r.time_median, r.time_max);
}

TEST(Floor, LuWithoutTheSpdTagAndSparseFactorizationsForASparseM) {
  const ReplayOptions options = FewSamples();
  const ProblemSet p = SetOf(Generated(MatrixFamily::kNonsymmetricPMatrix, false, {"pmatrix", "relay"}));
  EXPECT_EQ(ReplayFloor(p, p.problems[0], options).message, "dense LU (partial pivoting) of a 30×30 matrix");
  const ProblemSet s = SetOf(Generated(MatrixFamily::kSymmetricPositiveDefinite, true, {"spd"}));
  const ReplayRecord sparse = ReplayFloor(s, s.problems[0], options);
  EXPECT_TRUE(sparse.sparse);
  EXPECT_EQ(sparse.message, "sparse Cholesky of a 30×30 matrix");
  const ProblemSet n = SetOf(Generated(MatrixFamily::kNonsymmetricPMatrix, true, {}));
  EXPECT_EQ(ReplayFloor(n, n.problems[0], options).message, "sparse LU (COLAMD) of a 30×30 matrix");
}

TEST(Floor, ACholeskyThatFailsIsReplacedByTheLuAndSaysSo) {
  // Tagged SPD but indefinite: the floor must still be a factorization that completes.
  DenseMatrix M(2, 2);
  M << 1.0, 2.0, 2.0, 1.0;
  ReplayRecord r;
  EXPECT_EQ(TimeFactorization(M, FloorMethod::kDenseCholesky, FewSamples(), &r), FloorMethod::kDenseLu);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.message, "dense LU (partial pivoting) of a 2×2 matrix (dense Cholesky failed: not positive definite)");
}

TEST(Floor, OneJobPerProblemAndItsRecordsStayApartFromTheBackends) {
  ProblemSet set = SetOf(Generated(MatrixFamily::kSymmetricPositiveDefinite, false, {"spd", "relay"}));
  LibraryProblem second = set.problems[0];
  second.id = "floor/q";
  set.problems.push_back(second);
  JobListRequest request;
  request.solvers = {"lemke", "psor"};
  request.floor = true;
  const std::vector<BenchJob> jobs = ListBenchJobs(BoxSuites({set}), FewSamples(), request);
  int floors = 0;
  for (const BenchJob& job : jobs) {
    if (job.kind != JobKind::kFloor) continue;
    ++floors;
    EXPECT_EQ(job.solver, kFloorSolver);
    EXPECT_EQ(job.id, "mine|" + job.problem_id + "|floor|floor|1e-10");
  }
  EXPECT_EQ(floors, 2);
  request.floor = false;
  EXPECT_EQ(ListBenchJobs(BoxSuites({set}), FewSamples(), request).size(), jobs.size() - 2);

  // Through the run's files: the floor records come back as floor records, never as backend records.
  RunManifest manifest;
  SuiteResults listed;
  listed.suite = set.name;
  listed.problems = 2;
  manifest.suites = {listed};
  manifest.options = nlohmann::json::object();
  manifest.jobs = jobs;
  std::map<std::size_t, JobLine> lines;
  for (const BenchJob& job : jobs) {
    if (job.kind != JobKind::kFloor) continue;
    JobLine line;
    line.job = job.index;
    line.id = job.id;
    line.has_record = true;
    line.record = ReplayFloor(set, set.problems[job.problem], FewSamples());
    lines.emplace(job.index, line);
  }
  const BenchResults assembled = AssembleResults(manifest, lines);
  ASSERT_EQ(assembled.suites.size(), 1u);
  EXPECT_TRUE(assembled.suites[0].replay.records.empty());
  ASSERT_EQ(assembled.suites[0].replay.floor.size(), 2u);
  const fs::path dir = fs::temp_directory_path() / ("smcbench-floor-" + std::to_string(::getpid()));
  WriteBenchResults(assembled, dir.string(), nlohmann::json::object());
  const BenchResults back = ReadBenchResults(dir.string());
  fs::remove_all(dir);
  ASSERT_EQ(back.suites[0].replay.floor.size(), 2u);
  EXPECT_TRUE(back.suites[0].replay.records.empty());
  EXPECT_EQ(back.suites[0].replay.floor[1].problem, "floor/q");
  EXPECT_EQ(back.suites[0].replay.floor[1].time_median, assembled.suites[0].replay.floor[1].time_median);
}

}  // namespace
}  // namespace smcbench
