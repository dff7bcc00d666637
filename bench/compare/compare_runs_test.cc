// compare on synthetic runs whose answer is known: a 2× slowdown of one backend, identical runs, a verdict change,
// different suites; and the interval's own properties (it holds the true ratio, it is reproducible).
#include "bench/compare/compare_runs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;

ReplayRecord Record(const std::string& solver, int problem, int size, double median) {
  ReplayRecord r;
  r.suite = "families";
  r.problem = "families/p" + std::to_string(problem);
  r.solver = solver;
  r.size = size;
  r.expected = ExpectedOutcome::kSolvable;
  r.status = SolveStatus::kSolved;
  r.verdict = Verdict::kSolved;
  r.tolerance = 1e-10;
  r.time_median = median;
  r.time_mad = 0.02 * median;  // a 2 % spread over the repetitions
  r.samples = 7;
  return r;
}

// 12 problems of sizes 8..96 (two bands) on lemke and psor, times spread over two decades. factor multiplies psor's
// times, with a deterministic ±3 % wobble per problem so the ratio is not exactly constant.
BenchResults SyntheticRun(double psor_factor) {
  BenchResults run;
  SuiteResults suite;
  suite.suite = "families";
  suite.problems = 12;
  suite.checksum = "abc123";
  for (int p = 0; p < 12; ++p) {
    const int size = 8 * (p + 1);
    const double base = 1e-5 * std::pow(10.0, p / 6.0);
    suite.replay.records.push_back(Record("lemke", p, size, base));
    const double wobble = psor_factor == 1.0 ? 1.0 : (p % 2 ? 1.03 : 1.0 / 1.03);
    suite.replay.records.push_back(Record("psor", p, size, 3.0 * base * psor_factor * wobble));
  }
  run.suites.push_back(std::move(suite));
  return run;
}

const RatioGroup* Group(const RunComparison& c, const std::string& solver, SizeBand band) {
  for (const RatioGroup& g : c.groups) {
    if (g.solver == solver && g.band == band) return &g;
  }
  return nullptr;
}

TEST(SizeBand, BoundsAreInclusiveAsDocumented) {
  EXPECT_EQ(SizeBandOf(1), SizeBand::kTiny);
  EXPECT_EQ(SizeBandOf(4), SizeBand::kTiny);
  EXPECT_EQ(SizeBandOf(5), SizeBand::kSmall);
  EXPECT_EQ(SizeBandOf(64), SizeBand::kSmall);
  EXPECT_EQ(SizeBandOf(65), SizeBand::kMedium);
  EXPECT_EQ(SizeBandOf(1024), SizeBand::kMedium);
  EXPECT_EQ(SizeBandOf(1025), SizeBand::kLarge);
}

TEST(CompareRuns, TwofoldSlowdownOfOneBackendIsFlaggedWithAnIntervalHoldingTwo) {
  const RunComparison c = CompareRuns(SyntheticRun(1.0), SyntheticRun(2.0), CompareOptions{});
  EXPECT_TRUE(c.verdict_changes.empty());
  ASSERT_EQ(c.groups.size(), 4u);  // lemke, psor × bands m5-64 (p0..p7), m65-1024 (p8..p11)
  for (SizeBand band : {SizeBand::kSmall, SizeBand::kMedium}) {
    const RatioGroup* psor = Group(c, "psor", band);
    ASSERT_NE(psor, nullptr);
    EXPECT_EQ(psor->time.flag, TimeFlag::kSlower) << ShortName(band);
    EXPECT_LT(psor->time.low, 2.0);
    EXPECT_GT(psor->time.high, 2.0);
    EXPECT_GT(psor->time.low, 1.05);
    EXPECT_NEAR(psor->time.ratio, 2.0, 0.06);
    const RatioGroup* lemke = Group(c, "lemke", band);
    ASSERT_NE(lemke, nullptr);
    EXPECT_EQ(lemke->time.flag, TimeFlag::kNone);
    EXPECT_DOUBLE_EQ(lemke->time.ratio, 1.0);
  }
  EXPECT_EQ(Group(c, "psor", SizeBand::kSmall)->problems, 8);
  EXPECT_EQ(Group(c, "psor", SizeBand::kMedium)->problems, 4);
  EXPECT_EQ(c.slower_groups(), 2);
  EXPECT_TRUE(c.regressed());
}

TEST(CompareRuns, IdenticalRunsGiveRatioOneAndNoFlag) {
  const RunComparison c = CompareRuns(SyntheticRun(1.0), SyntheticRun(1.0), CompareOptions{});
  EXPECT_TRUE(c.verdict_changes.empty());
  EXPECT_EQ(c.matched_records, 24);
  ASSERT_EQ(c.groups.size(), 4u);
  for (const RatioGroup& g : c.groups) {
    EXPECT_DOUBLE_EQ(g.time.ratio, 1.0);
    EXPECT_LT(g.time.low, 1.0);
    EXPECT_GT(g.time.high, 1.0);
    EXPECT_EQ(g.time.flag, TimeFlag::kNone);
  }
  EXPECT_FALSE(c.regressed());
}

TEST(CompareRuns, AFasterBackendIsFlaggedFasterAndIsNoRegression) {
  const RunComparison c = CompareRuns(SyntheticRun(1.0), SyntheticRun(0.5), CompareOptions{});
  EXPECT_EQ(Group(c, "psor", SizeBand::kSmall)->time.flag, TimeFlag::kFaster);
  EXPECT_FALSE(c.regressed());
}

TEST(CompareRuns, VerdictChangesAreListedRegressionsFirst) {
  BenchResults a = SyntheticRun(1.0), b = SyntheticRun(1.0);
  // p3 on psor: failed in A, solved in B (an improvement); p5 on lemke: solved in A, failed in B (a regression).
  ReplayRecord& psor_a = a.suites[0].replay.records[2 * 3 + 1];
  psor_a.status = SolveStatus::kIterationLimit;
  psor_a.verdict = Verdict::kFailed;
  ReplayRecord& lemke_b = b.suites[0].replay.records[2 * 5];
  lemke_b.status = SolveStatus::kNumericalFailure;
  lemke_b.verdict = Verdict::kFailed;
  lemke_b.message = "singular pivot";
  const RunComparison c = CompareRuns(a, b, CompareOptions{});
  ASSERT_EQ(c.verdict_changes.size(), 2u);
  EXPECT_EQ(c.verdict_changes[0].kind, VerdictChangeKind::kRegression);
  EXPECT_EQ(c.verdict_changes[0].problem, "families/p5");
  EXPECT_EQ(c.verdict_changes[0].solver, "lemke");
  EXPECT_EQ(c.verdict_changes[0].status_b, SolveStatus::kNumericalFailure);
  EXPECT_EQ(c.verdict_changes[1].kind, VerdictChangeKind::kImprovement);
  EXPECT_EQ(c.verdict_changes[1].problem, "families/p3");
  EXPECT_EQ(c.regressions(), 1);
  EXPECT_TRUE(c.regressed());  // a verdict regression alone is a regression for CI
  // Only problems solved in both are timed: lemke's small band lost p5, psor's lost p3.
  EXPECT_EQ(Group(c, "lemke", SizeBand::kSmall)->problems, 7);
  EXPECT_EQ(Group(c, "psor", SizeBand::kSmall)->problems, 7);
  const std::string md = CompareMarkdown(c, CompareOptions{}, "a", "b", "");
  EXPECT_LT(md.find("| regression |"), md.find("| improvement |"));
  EXPECT_LT(md.find("## Verdict changes"), md.find("## Time ratio"));
  EXPECT_THAT(CompareSummaryText(c, CompareOptions{}), HasSubstr("regression: families families/p5 lemke"));
}

TEST(CompareRuns, DifferentChecksumsOrSuitesAreRefusedNamingTheDifference) {
  BenchResults b = SyntheticRun(1.0);
  b.suites[0].checksum = "def456";
  EXPECT_THAT(SuitesMismatch(SyntheticRun(1.0), b), HasSubstr("checksum abc123 vs def456"));
  try {
    CompareRuns(SyntheticRun(1.0), b, CompareOptions{});
    FAIL() << "different checksums were compared";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("families"));
    EXPECT_THAT(e.what(), HasSubstr("def456"));
  }
  BenchResults other = SyntheticRun(1.0);
  other.suites[0].suite = "paper";
  EXPECT_THAT(SuitesMismatch(SyntheticRun(1.0), other), HasSubstr("'families' vs 'paper'"));
  EXPECT_EQ(SuitesMismatch(SyntheticRun(1.0), SyntheticRun(2.0)), "");
}

TEST(CompareRuns, InvalidOptionsNameTheField) {
  CompareOptions options;
  options.threshold = -0.1;
  EXPECT_THAT(options.Invalid(), HasSubstr("threshold"));
  EXPECT_THROW(CompareRuns(SyntheticRun(1.0), SyntheticRun(1.0), options), InvalidInputError);
  options = CompareOptions{};
  options.resamples = 10;
  EXPECT_THAT(options.Invalid(), HasSubstr("resamples"));
}

TEST(TimeRatioInterval, OneProblemGetsAnIntervalFromItsRepetitionsAndIsReproducible) {
  // One problem, 7 samples with 10 % MAD each: σ(log median) = 1.2533·1.4826·0.1/√7 ≈ 0.0702 per run, so the
  // log-ratio's σ is ≈ 0.0993 and the 95 % interval about exp(±1.96·0.0993) = [0.823, 1.215] around the ratio.
  const std::vector<PairedTiming> pairs{{1e-3, 1e-4, 7, 1e-3, 1e-4, 7}};
  CompareOptions options;
  options.shift_seconds = 0.0;
  options.resamples = 20000;
  const TimeRatio r = TimeRatioInterval(pairs, options);
  EXPECT_DOUBLE_EQ(r.ratio, 1.0);
  EXPECT_NEAR(std::log(r.low), -1.96 * 0.0993, 0.01);
  EXPECT_NEAR(std::log(r.high), 1.96 * 0.0993, 0.01);
  const TimeRatio again = TimeRatioInterval(pairs, options);
  EXPECT_EQ(r.low, again.low);
  EXPECT_EQ(r.high, again.high);
  // Without spread and with one problem there is nothing to resample: the interval is the point.
  const TimeRatio exact = TimeRatioInterval({{1e-3, 0.0, 7, 3e-3, 0.0, 7}}, options);
  EXPECT_DOUBLE_EQ(exact.ratio, 3.0);
  EXPECT_DOUBLE_EQ(exact.low, 3.0);
  EXPECT_DOUBLE_EQ(exact.high, 3.0);
  EXPECT_EQ(exact.flag, TimeFlag::kSlower);
}

}  // namespace
}  // namespace smcbench
