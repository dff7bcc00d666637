// The registry lists external backends exactly when they were built in, and lists all of them: in a build
// without Siconos (SMCBENCH_WITH_SICONOS=OFF, or the package absent) no siconos-* name appears and none can be
// created; with it, all fifteen (thirteen box, two MCP adapters) do and can.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {
namespace {

TEST(ExternalBackends, RegistryListsExactlyTheBuiltInOnes) {
  std::vector<ExternalBackend> external;
  AppendExternalBackends(&external);
  EXPECT_TRUE(external.empty() || external.size() == 15u) << external.size();
  std::set<std::string> listed;
  for (auto name : SolverNames()) {
    if (name.substr(0, 8) == "siconos-") listed.emplace(name);
  }
  std::set<std::string> built;
  for (const ExternalBackend& e : external) {
    built.emplace(e.name);
    auto solver = CreateSolver(e.name);
    ASSERT_NE(solver, nullptr);
    EXPECT_EQ(solver->info().name, e.name);
    EXPECT_FALSE(solver->info().reference.empty());
    EXPECT_FALSE(solver->info().algorithm.empty());
  }
  EXPECT_EQ(listed, built);
  // Ours come first and are always there.
  const auto names = SolverNames();
  ASSERT_GE(names.size(), 5u);
  EXPECT_EQ(names[0], "lemke");
  if (external.empty()) {
    EXPECT_THROW(CreateSolver("siconos-relay-lemke"), InvalidInputError);
    std::printf("[ info     ] built without Siconos: no external backend listed\n");
  }
}

}  // namespace
}  // namespace smcbench
