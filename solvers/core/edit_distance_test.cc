#include "solvers/core/edit_distance.h"

#include <gtest/gtest.h>

namespace smcbench {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("--solver", "--solver"), 0u);
  EXPECT_EQ(EditDistance("--solvr", "--solver"), 1u);   // one insertion
  EXPECT_EQ(EditDistance("--solverr", "--solver"), 1u);  // one deletion
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);      // the textbook pair
  EXPECT_EQ(EditDistance("abc", ""), 3u);
  EXPECT_EQ(EditDistance("flaw", "lawn"), EditDistance("lawn", "flaw"));
}

TEST(EditDistance, NearestNamesKeepTheListsOrderOnTies) {
  const std::vector<std::string> known = {"newton", "newton-min", "lemke", "enum"};
  EXPECT_EQ(NearestNames("newtonmin", known, 2), (std::vector<std::string>{"newton-min", "newton"}));  // 1, 3
  EXPECT_EQ(NearestNames("xxxx", known, 1), (std::vector<std::string>{"enum"}));  // enum and lemke: 4 vs 5
  EXPECT_TRUE(NearestNames("a", {}, 3).empty());
  EXPECT_EQ(NearestNames("a", known, 10).size(), known.size());
}

}  // namespace
}  // namespace smcbench
