// The conformance checks (solvers/conformance) on every bullet-* and dart-* backend built in: they may fail any
// case (these are not complete methods for every P-matrix family, and their PGS stops early by design), but every
// "solved" is checked independently against the planted solution, so a wrong answer can never pass as solved, and a
// session returns the bits of Solve. The one check they fail by design is session-reuse: a session never answers
// for an external backend from a reused active set (SolverInfo::external), so that what is timed is the library.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "solvers/conformance/conformance.h"
#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {
namespace {

// The registry lists exactly the bullet-* and dart-* backends built in (three per library found, none otherwise),
// each an external adapter that gets the problem as written.
TEST(PeerRegistry, ListsExactlyTheBuiltInBulletAndDartBackends) {
  std::vector<ExternalBackend> built;
  AppendBulletBackends(&built);
  EXPECT_TRUE(built.empty() || built.size() == 3u);
  const std::size_t bullet = built.size();
  AppendDartBackends(&built);
  EXPECT_TRUE(built.size() == bullet || built.size() == bullet + 3);
  std::vector<std::string> listed;
  for (std::string_view name : SolverNames()) {
    if (name.substr(0, 7) == "bullet-" || name.substr(0, 5) == "dart-") listed.emplace_back(name);
  }
  ASSERT_EQ(listed.size(), built.size());
  for (std::size_t i = 0; i < built.size(); ++i) {
    EXPECT_EQ(listed[i], built[i].name);
    const auto solver = CreateSolver(built[i].name);
    EXPECT_EQ(solver->info().name, built[i].name);
    EXPECT_TRUE(solver->info().external);
    EXPECT_FALSE(solver->info().equilibrate);
    EXPECT_TRUE(IsExternalBackend(built[i].name));
    EXPECT_TRUE(IsExternalBackendName(built[i].name));
  }
  EXPECT_FALSE(IsExternalBackendName("lemke"));
  EXPECT_TRUE(IsExternalBackendName("siconos-relay-lemke"));
}

TEST(PeerConformance, EveryBulletAndDartBackendIsNeverWronglySolved) {
  int checked = 0;
  for (std::string_view name : SolverNames()) {
    if (name.substr(0, 7) != "bullet-" && name.substr(0, 5) != "dart-") continue;
    ConformanceOptions options;
    options.must_solve = [](const ConformanceCase&) { return false; };
    const ConformanceReport report = CheckConformance(name, options);
    for (const ConformanceFailure& f : report.failures) {
      const bool by_design = f.check == "session-reuse" && f.message.find("answered 0 of") != std::string::npos;
      EXPECT_TRUE(by_design) << name << ": " << f.check << ": " << f.problem << ": " << f.message;
    }
    EXPECT_GT(report.solved_checked, 0) << name;
    std::printf("[ info     ] %s: %d solves, %d solved answers checked\n", std::string(name).c_str(), report.solves,
                report.solved_checked);
    ++checked;
  }
  std::printf("[ info     ] %d bullet-*/dart-* backends checked\n", checked);
}

}  // namespace
}  // namespace smcbench
