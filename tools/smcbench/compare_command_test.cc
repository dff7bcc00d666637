// `smcbench compare` end to end: two real `bench` runs of a small suite, the second with psor under-relaxed
// and without its subspace step (--set psor.omega=0.05 --set psor.subspace_sweeps=0: each sweep moves z a
// twentieth of the Gauss–Seidel step and no exact solve cuts the sweeps short, so psor needs some 20× the sweeps),
// and compare flags psor and only psor. The slowdown is well over 5× on every band and the threshold 2 (flag only
// when the whole interval lies above 3): robust to a busy machine, whose run-to-run drift alone has been seen to
// halve or double a backend's times.
#include "tools/smcbench/compare_command.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/compare/compare_runs.h"
#include "bench/replay/results_io.h"
#include "tools/smcbench/cli_test_runner.h"
#include "bench/figures/gnuplot_figure.h"

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
  // "a": lemke and psor on the quick families suite; "b": the same with psor under-relaxed and without its subspace
  // step (which would finish the damped sweeps' job from their active set): plain damped sweeps, far slower.
  static std::string Run(const std::string& name) {
    const fs::path dir = *root_ / name;
    if (!fs::exists(dir / "results.json")) {
      std::vector<std::string> args{"bench", "--suite", "families", "--quick", "--solver", "lemke", "psor",
                                    "--repetitions", "3", "--no-stepper", "--progress-every", "0",
                                    "--out", dir.string()};
      if (name == "b") args.insert(args.end(), {"--set", "psor.omega=0.05", "--set", "psor.subspace_sweeps=0"});
      const auto run = RunSmcbench(args);
      EXPECT_EQ(run.code, 0) << run.err;
    }
    return dir.string();
  }
  static std::string Dir(const char* name) { return (*root_ / name).string(); }
  static fs::path* root_;
};
fs::path* CompareCommandTest::root_ = nullptr;

TEST_F(CompareCommandTest, UnderRelaxedPsorIsFlaggedAndLemkeIsNot) {
  CompareOptions options;
  options.threshold = 2.0;
  const RunComparison c = CompareRuns(ReadBenchResults(Run("a")), ReadBenchResults(Run("b")), options);
  EXPECT_EQ(c.regressions(), 0);  // more sweeps are slower, never wrong
  for (const VerdictChange& v : c.verdict_changes) EXPECT_EQ(v.solver, "psor") << v.problem;
  int psor_groups = 0;
  for (const RatioGroup& g : c.groups) {
    if (g.solver == "lemke") {
      EXPECT_EQ(g.time.flag, TimeFlag::kNone) << ShortName(g.band) << " " << g.time.ratio;
    } else if (g.solver == "psor") {
      ++psor_groups;
      EXPECT_EQ(g.time.flag, TimeFlag::kSlower) << ShortName(g.band) << " " << g.time.ratio;
      EXPECT_GT(g.time.ratio, 5.0);
      EXPECT_LE(g.time.low, g.time.ratio);
      EXPECT_GE(g.time.high, g.time.ratio);
    }
  }
  EXPECT_EQ(psor_groups, 2);  // the quick families have m ≤ 4 and 5–64 problems

  const fs::path out = *root_ / "report";
  std::vector<std::string> args{"compare", Dir("a"), Dir("b"), "--threshold", "2", "--out", out.string()};
  if (!GnuplotAvailable()) args.push_back("--no-plots");
  const auto run = RunSmcbench(args);
  EXPECT_EQ(run.code, kExitCompareRegressed) << run.out << run.err;
  EXPECT_THAT(run.out, Not(testing::ContainsRegex("families/lemke [^\n]*SLOWER")));
  EXPECT_THAT(run.out, testing::ContainsRegex("families/psor +m5-64 [^\n]*SLOWER"));
  EXPECT_THAT(run.out, HasSubstr("differs: settings [] vs [\"psor.omega=0.05\",\"psor.subspace_sweeps=0\"]"));
  EXPECT_THAT(run.out, Not(HasSubstr("different machines")));
  std::ifstream md_file(out / "compare.md");
  std::stringstream md;
  md << md_file.rdbuf();
  EXPECT_THAT(md.str(), HasSubstr("| families | psor | m5-64 |"));
  EXPECT_THAT(md.str(), HasSubstr("paired bootstrap (2000 resamples"));
  EXPECT_THAT(md.str(), HasSubstr("| setting | settings **≠** | [] | [\"psor.omega=0.05\",\"psor.subspace_sweeps=0\"] |"));
  EXPECT_THAT(md.str(), HasSubstr("| setting | repetitions | 3 | 3 |"));
  EXPECT_THAT(md.str(), HasSubstr("Noise floor (A/A calibration"));
  EXPECT_THAT(md.str(), HasSubstr("| iterations A | iterations B |"));
  std::ifstream json_file(out / "compare.json");
  const nlohmann::json j = nlohmann::json::parse(json_file);
  EXPECT_EQ(j["regressed"], true);
  EXPECT_EQ(j["differences"], "settings [] vs [\"psor.omega=0.05\",\"psor.subspace_sweeps=0\"]");
  EXPECT_GE(j["slower_groups"].get<int>(), 2);
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
  EXPECT_THAT(run.out, HasSubstr("same settings, build and machine"));
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
