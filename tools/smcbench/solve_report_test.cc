// `smcbench solve --repeat N` times cold repeats as cold: a backend that remembers something between solves (as
// Siconos' mlcp_direct_* cache their last active set) forgets it before each timed repeat, so no repeat is answered
// from that memory; one that cannot forget is flagged; a backend that keeps nothing keeps the batched timing.
#include "tools/smcbench/solve_report.h"

#include <gtest/gtest.h>

#include "solvers/generators/random_problems.h"
#include "tests/support/caching_backend.h"

namespace smcbench {
namespace {

using test_support::CachingBackend;

BoxMLCP Relay() {
  GeneratorOptions g;
  g.size = 12;
  g.family = MatrixFamily::kNonsymmetricPMatrix;
  g.bounds = BoundKind::kRelay;
  g.seed = 5;
  return GenerateProblem(g).problem;
}

TEST(SolveRepeat, EveryColdRepeatOfABackendWithACacheRunsItsAlgorithm) {
  CachingBackend backend(/*can_forget=*/true);
  const SolveRecord record = TimedSolve(backend, Relay(), SolverOptions{}, 10);
  EXPECT_TRUE(record.forgot_between_repeats);
  EXPECT_FALSE(record.cached);
  EXPECT_EQ(record.solves_per_sample, 1);
  EXPECT_EQ(backend.answered_from_cache(), 0);
  EXPECT_EQ(backend.solved_by_lemke(), 11);  // the first solve and the ten timed repeats
  EXPECT_GT(record.result.iterations, 0);    // the last repeat's own pivots, not a cache hit's 0
  EXPECT_TRUE(record.result.solved());
}

TEST(SolveRepeat, ABackendThatCannotForgetIsFlaggedCached) {
  CachingBackend backend(/*can_forget=*/false);
  const SolveRecord record = TimedSolve(backend, Relay(), SolverOptions{}, 10);
  EXPECT_TRUE(record.cached);
  EXPECT_NE(FormatRecordLine(record).find("[cached:"), std::string::npos) << FormatRecordLine(record);
}

TEST(SolveRepeat, WarmRepeatsForgetNothingAndABackendWithoutMemoryIsTimedInBatches) {
  CachingBackend backend(/*can_forget=*/true);
  const SolveRecord warm = TimedSolve(backend, Relay(), SolverOptions{}, 10, /*warm=*/true);
  EXPECT_FALSE(warm.forgot_between_repeats);  // a time-stepper's situation: what was learned is used
  EXPECT_TRUE(warm.result.solved());

  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  const SolveRecord plain = TimedSolve(*lemke, Relay(), SolverOptions{}, 200);
  EXPECT_FALSE(plain.forgot_between_repeats);
  EXPECT_FALSE(plain.cached);
  EXPECT_TRUE(plain.result.solved());
}

}  // namespace
}  // namespace smcbench
