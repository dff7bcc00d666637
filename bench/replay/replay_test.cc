// TimeSolves' cold timing (replay.h): every timed solve of a cold record starts from the state the first one did,
// for a backend that keeps something between solves too; a record that could not start cold says so ("cached") and
// that survives the results files.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "bench/replay/replay.h"
#include "bench/replay/results_io.h"
#include "solvers/generators/random_problems.h"
#include "solvers/registry/registry.h"
#include "tests/support/caching_backend.h"

namespace smcbench {
namespace {

using test_support::CachingBackend;

BoxMLCP TwentyRowRelay() {
  GeneratorOptions g;
  g.size = 20;
  g.family = MatrixFamily::kNonsymmetricPMatrix;
  g.bounds = BoundKind::kRelay;
  g.seed = 3;
  return GenerateProblem(g).problem;
}

ReplayOptions QuickTiming() {
  ReplayOptions replay;
  replay.repetitions = 5;
  // Several solves per sample, so the cold loop must forget between them too. The warm-up solve sizes the sample
  // and is the slow one (first allocations; milliseconds under ASan), so the sample is 50 ms, not 1 ms.
  replay.min_sample_seconds = 5e-2;
  return replay;
}

SolverOptions Untimed() {
  SolverOptions o;
  o.measure_time = false;
  return o;
}

TEST(TimeSolves, EveryTimedSolveOfABackendWithACacheStartsCold) {
  const BoxMLCP problem = TwentyRowRelay();
  CachingBackend backend(/*can_forget=*/true);
  SolveResult result;
  ReplayRecord record;
  TimeSolves(&backend, problem, Untimed(), QuickTiming(), &result, &record);
  EXPECT_EQ(backend.answered_from_cache(), 0);
  EXPECT_EQ(backend.solved_by_lemke(), 1 + record.samples * record.solves_per_sample);  // the warm-up and each
  EXPECT_GT(record.solves_per_sample, 1);
  EXPECT_GT(result.iterations, 0);
  EXPECT_TRUE(result.solved());
  EXPECT_EQ(record.mode, "cold");
  EXPECT_GT(record.time_min, 0.0);
  EXPECT_LE(record.time_min, record.time_median);
  EXPECT_LE(record.time_median, record.time_max);
}

TEST(TimeSolves, ABackendThatCannotForgetGivesACachedRecord) {
  const BoxMLCP problem = TwentyRowRelay();
  CachingBackend backend(/*can_forget=*/false);
  SolveResult result;
  ReplayRecord record;
  TimeSolves(&backend, problem, Untimed(), QuickTiming(), &result, &record);
  EXPECT_GT(backend.answered_from_cache(), 0);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(record.mode, "cached");
}

// Warm by request: the session's reused active set may answer the repeats, so the record is not a cold one.
TEST(TimeSolves, ReusingTheActiveSetGivesACachedRecord) {
  const BoxMLCP problem = TwentyRowRelay();
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  ReplayOptions replay = QuickTiming();
  replay.reuse_active_set = true;
  SolveResult result;
  ReplayRecord record;
  TimeSolves(lemke.get(), problem, Untimed(), replay, &result, &record);
  EXPECT_EQ(SessionPathOf(result), SessionPath::kReusedActiveSet);
  EXPECT_EQ(record.mode, "cached");
  // A sweep record keeps its mode: "cached" replaces "cold" only.
  ReplayRecord sweep;
  sweep.mode = "sweep";
  TimeSolves(lemke.get(), problem, Untimed(), replay, &result, &sweep);
  EXPECT_EQ(sweep.mode, "sweep");
}

// A backend that keeps nothing is timed back to back, as before: the same answer bits as a plain Solve.
TEST(TimeSolves, ABackendThatKeepsNothingAnswersAsAPlainSolve) {
  const BoxMLCP problem = TwentyRowRelay();
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  SolveResult timed;
  ReplayRecord record;
  TimeSolves(lemke.get(), problem, Untimed(), QuickTiming(), &timed, &record);
  const SolveResult plain = CreateSolver("lemke")->Solve(problem, Untimed());
  EXPECT_EQ(record.mode, "cold");
  EXPECT_EQ(timed.status, plain.status);
  EXPECT_EQ(timed.iterations, plain.iterations);
  EXPECT_EQ(timed.z, plain.z);
  EXPECT_GT(record.solves_per_sample, 1);
}

// A solve longer than the sampling window is not repeated: the warm-up, answered in this process, is the record's
// one sample (a budgeted run's job keeps to its budget instead of taking two solves for a median of two).
TEST(TimeSolves, AWarmUpLongerThanTheSamplingWindowIsTheOneSample) {
  const BoxMLCP problem = TwentyRowRelay();
  CachingBackend backend(/*can_forget=*/true);
  ReplayOptions replay = QuickTiming();
  replay.max_seconds_per_pair = 0.0;  // every solve outlasts it
  SolveResult result;
  ReplayRecord record;
  TimeSolves(&backend, problem, Untimed(), replay, &result, &record);
  EXPECT_EQ(backend.solved_by_lemke(), 1);
  EXPECT_EQ(record.samples, 1);
  EXPECT_EQ(record.solves_per_sample, 1);
  EXPECT_TRUE(result.solved());
  EXPECT_EQ(record.time_min, record.time_max);
  EXPECT_GT(record.time_median, 0.0);
}

TEST(ResultsIo, ACachedRecordKeepsItsModeThroughTheResultsFiles) {
  ReplayRecord record;
  record.suite = "mine";
  record.problem = "p1";
  record.solver = "caching";
  record.mode = "cached";
  EXPECT_EQ(ReplayRecordFromJson(ReplayRecordToJson(record)).mode, "cached");
  BenchResults results;
  SuiteResults suite;
  suite.suite = "mine";
  suite.problems = 1;
  suite.replay.records.push_back(record);
  results.suites.push_back(suite);
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "replay-cached-roundtrip";
  std::filesystem::remove_all(dir);
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  ASSERT_EQ(back.suites[0].replay.records.size(), 1u);
  EXPECT_EQ(back.suites[0].replay.records[0].mode, "cached");
}

}  // namespace
}  // namespace smcbench
