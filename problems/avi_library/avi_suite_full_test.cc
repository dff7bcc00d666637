// The full `avi` suite (bench without --quick): every reference verified and passing the AVI verdict at the sizes the
// quick suite leaves out. Label release-only: the same code path runs under ASan in avi_library_test's quick-suite
// checks, and the full sizes would take minutes there.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "problems/avi_library/avi_suite.h"

namespace smcbench {
namespace {

constexpr double kTightTolerance = 1e-12;

bool HasTag(const AviLibraryProblem& p, const std::string& tag) {
  return std::find(p.tags.begin(), p.tags.end(), tag) != p.tags.end();
}

// The full sizes (n up to 32, reductions of up to 138 rows): every reference still verified and passing.
TEST(AviSuite, FullSuiteReferencesPassTheVerdict) {
  const AviProblemSet set = BuildAviSuite(false);
  std::map<int, int> planted_sizes;
  for (const AviLibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    if (HasTag(p, "planted")) ++planted_sizes[p.size()];
    if (p.expected == ExpectedOutcome::kInfeasible) continue;
    ASSERT_TRUE(p.reference.verified()) << p.metadata.at("certificate");
    EXPECT_EQ(JudgeAvi(*p.problem, p.expected, &p.reference, SolveStatus::kSolved, p.reference.solution,
                       kTightTolerance).verdict,
              Verdict::kSolved);
  }
  EXPECT_EQ(planted_sizes, (std::map<int, int>{{2, 2}, {4, 2}, {8, 2}, {16, 2}, {32, 2}}));
  EXPECT_GT(set.problems.size(), BuildAviSuite(true).problems.size());
}

}  // namespace
}  // namespace smcbench
