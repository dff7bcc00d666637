// The isolation of the bullet-* and dart-* backends costs no allocation in this process: solves in the worker
// allocate nothing here once the workspace is sized, and the probe policy's bookkeeping on the in-process path
// allocates nothing beyond what the library itself does (the same solves with isolate=never make as many).
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "solvers/generators/random_problems.h"
#include "solvers/registry/registry.h"
#include "solvers/isolation/child_process.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

std::vector<std::string> PeerNames() {
  std::vector<std::string> names;
  for (std::string_view name : SolverNames()) {
    if (name.substr(0, 7) == "bullet-" || name.substr(0, 5) == "dart-") names.emplace_back(name);
  }
  return names;
}

std::unique_ptr<Solver> Make(const std::string& name, const char* isolate) {
  auto solver = CreateSolver(name);
  std::string error;
  EXPECT_TRUE(solver->SetOption("isolate", isolate, &error)) << error;
  return solver;
}

BoxMLCP SmallRelay() {
  GeneratorOptions g;
  g.bounds = BoundKind::kRelay;
  g.size = 4;
  return GenerateProblem(g).problem;
}

TEST(IsolationPolicy, RepeatedSolvesInTheWorkerDoNotAllocateInThisProcess) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  const BoxMLCP problem = SmallRelay();
  for (const std::string& name : PeerNames()) {
    SCOPED_TRACE(name);
    auto solver = Make(name, "always");
    SolverOptions options;
    SolveResult result;
    solver->Solve(problem, options, &result);  // starts the worker, sizes the workspace
    ASSERT_TRUE(result.solved()) << result.message;
    const long count = test_support::CountMallocs([&] {
      for (int k = 0; k < 10; ++k) solver->Solve(problem, options, &result);
    });
    EXPECT_EQ(count, 0);
    EXPECT_TRUE(result.solved());
    EXPECT_EQ(AnswerProcessOf(result), AnswerProcess::kWorker);
  }
}

TEST(IsolationPolicy, InProcessSolvesAllocateNoMoreThanTheLibraryDoesItself) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  const BoxMLCP problem = SmallRelay();
  for (const std::string& name : PeerNames()) {
    SCOPED_TRACE(name);
    auto first = Make(name, "first");
    auto never = Make(name, "never");
    SolverOptions options;
    SolveResult a, b;
    first->Solve(problem, options, &a);  // the probe
    first->Solve(problem, options, &a);
    never->Solve(problem, options, &b);
    never->Solve(problem, options, &b);
    ASSERT_EQ(AnswerProcessOf(a), AnswerProcess::kThisProcess);
    const long with_probe_policy = test_support::CountMallocs([&] {
      for (int k = 0; k < 10; ++k) first->Solve(problem, options, &a);
    });
    const long bare = test_support::CountMallocs([&] {
      for (int k = 0; k < 10; ++k) never->Solve(problem, options, &b);
    });
    EXPECT_EQ(with_probe_policy, bare);
    std::printf("[ info     ] %s: %ld allocations in 10 in-process solves (the library's own)\n", name.c_str(), bare);
    EXPECT_TRUE(a.solved()) << a.message;
    EXPECT_EQ(a.z, b.z);
  }
}

}  // namespace
}  // namespace smcbench
