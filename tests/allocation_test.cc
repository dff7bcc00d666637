// Pins down "hot paths do not allocate": after one warm-up solve, repeated solves of the same problem size with
// a reused result perform zero heap allocations (counted at the malloc level), for every backend whose SolverInfo
// says allocation_free.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "solvers/generators/random_problems.h"
#include "solvers/registry/registry.h"
#include "tests/support/malloc_counter.h"
#include "tests/support/test_backend.h"

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
    // A size-limited backend (enum: 3^40 active sets) refuses the largest case by design.
    if (solver->info().default_size_limit > 0 && c.size > solver->info().default_size_limit) continue;
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

// A prepared session (session.h): after Prepare and one call, calls with a new q and a warm start allocate
// nothing, on either path (the backend's algorithm, the reused active set — refactoring on a change of set).
TEST_P(NoAllocation, SessionSolvesDoNotAllocate) {
  if (!CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  const std::string name = GetParam();
  auto solver = CreateSolver(name);
  for (int size : {1, 2, 4, 8}) {
    for (bool reuse : {false, true}) {
      GeneratorOptions g;
      g.family = MatrixFamily::kSymmetricPositiveDefinite;
      g.bounds = BoundKind::kRelay;
      g.size = size;
      g.seed = 5;
      const GeneratedProblem gen = GenerateProblem(g);
      SessionOptions session_options;
      session_options.reuse_active_set = reuse;
      SolveSession session = solver->Prepare(gen.problem, SolverOptions{}, session_options);
      SolveResult result;
      Vector q = gen.problem.q();
      Vector warm = Vector::Zero(size);
      int solved = 0;
      const auto pass = [&] {
        solved = 0;
        for (int k = 0; k < 20; ++k) {
          // Moves some rows on and off their bounds: both paths and refactorizations are exercised.
          for (int i = 0; i < size; ++i) q[i] = gen.problem.q()[i] * (1.0 + 2.0 * std::sin(0.7 * k + i));
          session.Solve(q, &result, &warm);
          if (result.solved()) {
            ++solved;
            warm = result.z;
          }
        }
      };
      pass();  // warm-up: sizes the result and every workspace the sequence needs
      const long allocations = CountMallocs(pass);
      EXPECT_EQ(allocations, 0) << name << " allocated in a session on " << gen.problem.name()
                                << (reuse ? " (reuse on)" : " (reuse off)");
      EXPECT_EQ(solved, 20) << name << " on " << gen.problem.name();
    }
  }
}

// Every backend that promises allocation-free repeated solves (SolverInfo::allocation_free: not Ipopt, whose
// internals allocate, nor the external adapters), the test-only backend included (tests/support/test_backend.h).
std::vector<std::string> AllocationFreeBackends() {
  test_support::RegisterTestBackend();
  std::vector<std::string> names;
  for (std::string_view name : SolverNames()) {
    if (CreateSolver(name)->info().allocation_free) names.emplace_back(name);
  }
  return names;
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, NoAllocation, ::testing::ValuesIn(AllocationFreeBackends()),
                         [](const auto& info) {  // test names allow no '-' (newton-min)
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

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
