// `smcbench compare` end to end: two real `bench` runs of a small suite, the second with enum forced to its
// exhaustive search (--set enum.guided_steps=0: no block principal pivoting steps first, so every problem enumerates
// up to 2^n active sets), and compare flags enum and only enum. The slowdown on the 5–64 band is ≥ 5× and the
// threshold 2 (flag only when the whole interval lies above 3): robust to a busy machine, whose run-to-run drift
// alone has been seen to halve or double a backend's times.
#include "tools/smcbench/compare_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/compare/compare_runs.h"
#include "bench/replay/results_io.h"
#include "tools/smcbench/cli_test_runner.h"
#include "tools/smcbench/simulate.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using test_support::RunSmcbench;

// Each test runs in its own process under ctest: a run is made the first time a test asks for it.
class CompareCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(fs::temp_directory_path() / ("smcbench-compare-test-" + std::to_string(::getpid())));
    fs::remove_all(*root_);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
  }
  // "a": lemke and enum on the quick families suite; "b": the same with enum's guided steps off.
  static std::string Run(const std::string& name) {
    const fs::path dir = *root_ / name;
    if (!fs::exists(dir / "results.json")) {
      std::vector<std::string> args{"bench", "--suite", "families", "--quick", "--solver", "lemke", "enum",
                                    "--repetitions", "3", "--no-stepper", "--progress-every", "0",
                                    "--out", dir.string()};
      if (name == "b") args.insert(args.end(), {"--set", "enum.guided_steps=0"});
      const auto run = RunSmcbench(args);
      EXPECT_EQ(run.code, 0) << run.err;
    }
    return dir.string();
  }
  static std::string Dir(const char* name) { return (*root_ / name).string(); }
  static fs::path* root_;
};
fs::path* CompareCommandTest::root_ = nullptr;

TEST_F(CompareCommandTest, ForcedExhaustiveEnumIsFlaggedAndLemkeIsNot) {
  CompareOptions options;
  options.threshold = 2.0;
  const RunComparison c = CompareRuns(ReadBenchResults(Run("a")), ReadBenchResults(Run("b")), options);
  EXPECT_EQ(c.regressions(), 0);  // exhaustive enumeration is slower, never wrong
  bool enum_flagged = false;
  for (const RatioGroup& g : c.groups) {
    if (g.solver == "lemke") {
      EXPECT_EQ(g.time.flag, TimeFlag::kNone) << ToString(g.band) << " " << g.time.ratio;
    }
    if (g.solver == "enum" && g.band == SizeBand::kSmall) {
      EXPECT_EQ(g.time.flag, TimeFlag::kSlower);
      EXPECT_GT(g.time.ratio, 5.0);
      EXPECT_LE(g.time.low, g.time.ratio);
      EXPECT_GE(g.time.high, g.time.ratio);
      enum_flagged = g.time.flag == TimeFlag::kSlower;
    }
  }
  EXPECT_TRUE(enum_flagged);

  const fs::path out = *root_ / "report";
  std::vector<std::string> args{"compare", Dir("a"), Dir("b"), "--threshold", "2", "--out", out.string()};
  if (!GnuplotAvailable()) args.push_back("--no-plots");
  const auto run = RunSmcbench(args);
  EXPECT_EQ(run.code, kExitCompareRegressed) << run.out << run.err;
  EXPECT_THAT(run.out, HasSubstr("families/enum"));
  EXPECT_THAT(run.out, Not(testing::ContainsRegex("families/lemke [^\n]*SLOWER")));
  EXPECT_THAT(run.out, testing::ContainsRegex("families/enum +m5-64 [^\n]*SLOWER"));
  std::ifstream md_file(out / "compare.md");
  std::stringstream md;
  md << md_file.rdbuf();
  EXPECT_THAT(md.str(), HasSubstr("| families | enum | m5-64 |"));
  EXPECT_THAT(md.str(), HasSubstr("paired bootstrap (2000 resamples"));
  if (GnuplotAvailable()) {
    EXPECT_TRUE(fs::is_regular_file(out / "compare-ratios.png"));
    EXPECT_THAT(md.str(), HasSubstr("(compare-ratios.png)"));
  }
}

TEST_F(CompareCommandTest, ARunAgainstItselfHasRatioOneAndExitsZero) {
  const auto run = RunSmcbench({"compare", Run("a"), Run("a")});
  EXPECT_EQ(run.code, 0) << run.out << run.err;
  EXPECT_THAT(run.out, HasSubstr("0 verdict change(s)"));
  EXPECT_THAT(run.out, HasSubstr("0 flagged slower"));
}

TEST_F(CompareCommandTest, OtherSuitesOrNoResultsCannotBeCompared) {
  const auto tiny = RunSmcbench({"bench", "--suite", "tiny", "--solver", "lemke", "--repetitions", "1",
                                 "--no-stepper", "--progress-every", "0", "--out", Dir("tiny")});
  ASSERT_EQ(tiny.code, 0) << tiny.err;
  const auto other = RunSmcbench({"compare", Run("a"), Dir("tiny")});
  EXPECT_EQ(other.code, kExitCompareRefused);
  EXPECT_THAT(other.err, HasSubstr("other suites ('families' vs 'tiny')"));
  const auto missing = RunSmcbench({"compare", Dir("a"), Dir("nowhere")});
  EXPECT_EQ(missing.code, kExitCompareRefused);
  EXPECT_THAT(missing.err, HasSubstr("nowhere"));
  const auto bad = RunSmcbench({"compare", Dir("a"), Dir("b"), "--threshold", "-1"});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--threshold"));
}

}  // namespace
}  // namespace smcbench
