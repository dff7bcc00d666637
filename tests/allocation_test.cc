// Pins down "hot paths do not allocate": after one warm-up solve, repeated solves of the same problem size with
// a reused result perform zero heap allocations (counted at the malloc level), for every backend but Ipopt,
// whose internals allocate.
#include <gtest/gtest.h>

#include "problems/generators/random_problems.h"
#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

using test_support::CanCountMallocs;
using test_support::CountMallocs;

struct Case {
  MatrixFamily family;
  BoundKind bounds;
  int size;
};

class NoAllocation : public ::testing::TestWithParam<std::string> {};

TEST_P(NoAllocation, RepeatedSolvesOfTheSameSizeDoNotAllocate) {
  if (!CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  const std::string name = GetParam();
  auto solver = CreateSolver(name);
  const Case cases[] = {
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 1},
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 2},
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 4},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kMixed, 8},
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 16},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kBox, 40},
  };
  for (const Case& c : cases) {
    if (c.size > 16 && name == "enum") continue;  // 3^40 active sets: refused with size_limit by design
    GeneratorOptions g;
    g.family = c.family;
    g.bounds = c.bounds;
    g.size = c.size;
    g.seed = 11;
    const GeneratedProblem gen = GenerateProblem(g);
    SolverOptions options;
    SolveResult result;
    solver->Solve(gen.problem, options, &result);  // warm-up: sizes the workspace
    ASSERT_TRUE(result.solved()) << name << " on " << gen.problem.name() << ": " << ToString(result.status) << " "
                                 << result.message;
    const long allocations = CountMallocs([&] {
      for (int k = 0; k < 10; ++k) solver->Solve(gen.problem, options, &result);
    });
    EXPECT_EQ(allocations, 0) << name << " allocated on " << gen.problem.name();
    EXPECT_TRUE(result.solved());
  }
}

std::vector<std::string> NonIpoptSolvers() {
  std::vector<std::string> names;
  for (auto n : SolverNames()) {
    // Ipopt allocates internally; external adapters run each solve in a child process.
    if (n != "ipopt" && !IsExternalBackend(n)) names.emplace_back(n);
  }
  return names;
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, NoAllocation, ::testing::ValuesIn(NonIpoptSolvers()),
                         [](const auto& info) { return info.param; });

TEST(AllocationCounter, SeesOperatorNewAndEigenAllocations) {
  if (!CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  // Explicit calls to operator new are never elided by the compiler.
  EXPECT_GE(CountMallocs([] { ::operator delete(::operator new(64)); }), 1);
  Vector v;
  EXPECT_GE(CountMallocs([&] { v.resize(1000); }), 1);
  EXPECT_EQ(CountMallocs([&] { v.resize(1000); }), 0);  // same size: no allocation
}

}  // namespace
}  // namespace smcbench
