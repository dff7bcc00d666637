// compare on synthetic runs whose answer is known: a 2× slowdown of one backend, identical runs, a verdict change,
// different suites; and the interval's own properties (it holds the true ratio, it is reproducible).
#include "bench/compare/compare_runs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <nlohmann/json.hpp>

#include "bench/compare/compare_render.h"
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

// Runs drawn at random: 3 backends × 12 problems (two size bands: 6 groups), each problem timed by 7 samples with a
// 3 % log-normal spread around its true time, the summary (median, MAD, min, max) computed from the draws as
// SampleSolveTimes does. factor[backend] multiplies a backend's true times, drift every time (the floor's too).
struct RandomRunSpec {
  std::uint64_t seed = 1;
  std::map<std::string, double> factor;  // backend → true slowdown (1 when absent)
  double drift = 1.0;
  bool floor = false;                    // also floor records (solver "floor", mode "floor")
};

ReplayRecord DrawnRecord(const std::string& solver, int problem, int size, double true_time, std::mt19937_64& engine) {
  std::lognormal_distribution<double> noise(0.0, 0.03);
  std::vector<double> samples(7);
  for (double& s : samples) s = true_time * noise(engine);
  std::sort(samples.begin(), samples.end());
  ReplayRecord r = Record(solver, problem, size, samples[3]);
  std::vector<double> deviations;
  for (double s : samples) deviations.push_back(std::abs(s - r.time_median));
  std::sort(deviations.begin(), deviations.end());
  r.time_mad = deviations[3];
  r.time_min = samples.front();
  r.time_max = samples.back();
  r.iterations = 10 + problem;
  return r;
}

BenchResults RandomRun(const RandomRunSpec& spec) {
  std::mt19937_64 engine(spec.seed);
  BenchResults run;
  SuiteResults suite;
  suite.suite = "families";
  suite.problems = 12;
  suite.checksum = "abc123";
  for (int p = 0; p < 12; ++p) {
    const int size = 8 * (p + 1);
    const double base = 1e-5 * std::pow(10.0, p / 6.0) * spec.drift;
    for (const std::string solver : {"lemke", "psor", "enum"}) {
      const auto f = spec.factor.find(solver);
      suite.replay.records.push_back(
          DrawnRecord(solver, p, size, base * (f == spec.factor.end() ? 1.0 : f->second), engine));
    }
    if (spec.floor) {
      ReplayRecord floor = DrawnRecord("floor", p, size, 0.2 * base, engine);
      floor.mode = "floor";
      suite.replay.floor.push_back(floor);
    }
  }
  run.suites.push_back(std::move(suite));
  return run;
}

std::vector<std::string> Flagged(const RunComparison& c) {
  std::vector<std::string> flagged;
  for (const RatioGroup& g : c.groups) {
    if (g.time.flag != TimeFlag::kNone) {
      flagged.push_back(g.solver + " " + std::string(ShortName(g.band)) + " " + std::string(ToString(g.time.flag)));
    }
  }
  return flagged;
}

TEST(NoiseFloor, IsTheNinetyFivePercentRangeOfTheRatioOfTwoSamplesOfATypicalProblem) {
  // SyntheticRun: every record has MAD 2 % of its median, so s = 1.4826·0.02 and the floor exp(1.96·√2·s) ≈ 1.0856.
  const NoiseFloor n = NoiseFloors(SyntheticRun(1.0), SyntheticRun(2.0));
  EXPECT_NEAR(n.spread_a, 1.4826 * 0.02, 1e-12);
  EXPECT_NEAR(n.a, std::exp(1.96 * std::sqrt(2.0) * 1.4826 * 0.02), 1e-12);
  EXPECT_NEAR(n.b, n.a, 1e-12);
  EXPECT_EQ(n.records_a, 24);
  const RunComparison c = CompareRuns(SyntheticRun(1.0), SyntheticRun(1.0), CompareOptions{});
  EXPECT_NEAR(c.flag_limit, n.a, 1e-12);  // above 1 + threshold 1.05
  CompareOptions loose;
  loose.threshold = 0.2;
  EXPECT_DOUBLE_EQ(CompareRuns(SyntheticRun(1.0), SyntheticRun(1.0), loose).flag_limit, 1.2);
}

TEST(CompareRuns, RunsDrawnFromTheSameDistributionsFlagNothing) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const RunComparison c = CompareRuns(RandomRun({seed, {}, 1.0, true}), RandomRun({seed + 100, {}, 1.0, true}),
                                        CompareOptions{});
    ASSERT_EQ(c.groups.size(), 6u);
    EXPECT_THAT(Flagged(c), ::testing::IsEmpty()) << "seed " << seed;
    EXPECT_EQ(c.drift.source, DriftSource::kNone) << "seed " << seed;
    EXPECT_FALSE(c.regressed());
  }
}

TEST(CompareRuns, ATrueTwofoldSlowdownOfOneGroupFlagsExactlyThatGroup) {
  // psor twice as slow on the m65-1024 problems only (p8..p11): one group of six.
  BenchResults a = RandomRun({3, {}, 1.0, false}), b = RandomRun({4, {}, 1.0, false});
  for (ReplayRecord& r : b.suites[0].replay.records) {
    if (r.solver == "psor" && SizeBandOf(r.size) == SizeBand::kMedium) r.time_median *= 2.0;
  }
  const RunComparison c = CompareRuns(a, b, CompareOptions{});
  EXPECT_THAT(Flagged(c), ::testing::ElementsAre("psor m65-1024 SLOWER"));
  EXPECT_EQ(c.drift.source, DriftSource::kNone);
  EXPECT_TRUE(c.regressed());
}

TEST(CompareRuns, AUniformDriftIsReportedAsDriftAndFlagsNothing) {
  const CompareOptions options;
  // Without floor records: the groups themselves.
  const RunComparison c = CompareRuns(RandomRun({5, {}, 1.0, false}), RandomRun({6, {}, 1.15, false}), options);
  EXPECT_THAT(Flagged(c), ::testing::IsEmpty());
  EXPECT_EQ(c.drift.source, DriftSource::kGroups);
  EXPECT_NEAR(c.drift.factor, 1.15, 0.03);
  EXPECT_EQ(c.drift.agreeing_groups, 6);
  EXPECT_FALSE(c.regressed());
  for (const RatioGroup& g : c.groups) EXPECT_NEAR(g.time.ratio, 1.15, 0.05);  // the raw ratios are kept
  EXPECT_THAT(CompareSummaryText(c, options), HasSubstr("drift: all 6 groups ×1.1"));
  EXPECT_THAT(CompareSummaryText(c, options), HasSubstr("machine drift?"));
  // With floor records that moved as much: the floor's factor, and no question mark.
  const RunComparison f = CompareRuns(RandomRun({5, {}, 1.0, true}), RandomRun({6, {}, 1.15, true}), options);
  EXPECT_THAT(Flagged(f), ::testing::IsEmpty());
  EXPECT_EQ(f.drift.source, DriftSource::kFloor);
  EXPECT_NEAR(f.drift.factor, 1.15, 0.03);
  EXPECT_THAT(CompareMarkdown(f, options, "a", "b", ""), HasSubstr(": machine drift. Ratios divided by"));
  const nlohmann::json j = CompareJson(f, options, "a", "b");
  EXPECT_EQ(j["format"], "smcbench-compare/1");
  EXPECT_EQ(j["regressed"], false);
  EXPECT_EQ(j["drift"]["source"], "floor");
  EXPECT_EQ(j["drift"]["divided"], true);
  EXPECT_NEAR(j["drift"]["floor"]["ratio"].get<double>(), 1.15, 0.03);
  EXPECT_DOUBLE_EQ(j["flag_limit"].get<double>(), f.flag_limit);
  EXPECT_DOUBLE_EQ(j["noise_floor"]["a"].get<double>(), f.noise.a);
  ASSERT_EQ(j["groups"].size(), 6u);
  EXPECT_EQ(j["groups"][0]["flag"], "none");
  EXPECT_NEAR(j["groups"][0]["ratio_over_drift"].get<double>(), 1.0, 0.05);
  EXPECT_THAT(j["method"]["noise_floor"].get<std::string>(), HasSubstr("1.4826*MAD/median"));
}

TEST(CompareRuns, ADriftIsDividedOutSoTheOneRealSlowdownIsStillFlagged) {
  RandomRunSpec slower{8, {{"enum", 2.0}}, 1.15, true};
  const RunComparison c = CompareRuns(RandomRun({7, {}, 1.0, true}), RandomRun(slower), CompareOptions{});
  EXPECT_EQ(c.drift.source, DriftSource::kFloor);
  EXPECT_EQ(c.drift.agreeing_groups, 4);
  EXPECT_THAT(Flagged(c), ::testing::ElementsAre("enum m5-64 SLOWER", "enum m65-1024 SLOWER"));
}

TEST(CompareRuns, EveryBackendSlowerByOneFactorIsADriftUnlessKept) {
  // Every backend ×1.5, the floor unchanged: compare cannot tell it from a drift (the floor's disagreement is named);
  // with divide_drift false (`--keep-drift`) it is reported and every group flagged on its raw ratio.
  RandomRunSpec slower{10, {{"lemke", 1.5}, {"psor", 1.5}, {"enum", 1.5}}, 1.0, true};
  CompareOptions options;
  const RunComparison c = CompareRuns(RandomRun({9, {}, 1.0, true}), RandomRun(slower), options);
  EXPECT_EQ(c.drift.source, DriftSource::kGroups);
  EXPECT_TRUE(c.drift.divided);
  EXPECT_NEAR(c.drift.floor.ratio, 1.0, 0.03);
  EXPECT_EQ(c.slower_groups(), 0);
  EXPECT_THAT(CompareSummaryText(c, options), HasSubstr("which disagrees): machine drift?"));
  options.divide_drift = false;
  const RunComparison kept = CompareRuns(RandomRun({9, {}, 1.0, true}), RandomRun(slower), options);
  EXPECT_EQ(kept.drift.source, DriftSource::kGroups);
  EXPECT_FALSE(kept.drift.divided);
  EXPECT_DOUBLE_EQ(kept.drift.divisor(), 1.0);
  EXPECT_EQ(kept.slower_groups(), 6);
  EXPECT_THAT(CompareSummaryText(kept, options), HasSubstr("Not divided out (--keep-drift)"));
}

TEST(CompareRuns, IterationCountsAreTheGroupsMedians) {
  BenchResults b = RandomRun({12, {}, 1.0, false});
  for (ReplayRecord& r : b.suites[0].replay.records) r.iterations *= 3;
  const RunComparison c = CompareRuns(RandomRun({11, {}, 1.0, false}), b, CompareOptions{});
  const RatioGroup* lemke = Group(c, "lemke", SizeBand::kSmall);  // p0..p7: iterations 10..17
  ASSERT_NE(lemke, nullptr);
  EXPECT_DOUBLE_EQ(lemke->iterations_a, 13.5);
  EXPECT_DOUBLE_EQ(lemke->iterations_b, 40.5);
  EXPECT_THAT(CompareMarkdown(c, CompareOptions{}, "a", "b", ""), HasSubstr("| 13.5 | 40.5 |"));
  EXPECT_THAT(CompareSummaryText(c, CompareOptions{}), HasSubstr("13.5→40.5"));
}

RunIdentity Identity(const std::string& sha, double tolerance, const std::string& cpu, const std::string& host) {
  BenchResults results = SyntheticRun(1.0);
  for (ReplayRecord& r : results.suites[0].replay.records) r.host = host;
  const nlohmann::json environment = {{"git_sha", sha}, {"compiler", "g++ 13"}, {"build_type", "Release"},
                                      {"cpu", cpu}, {"cores", 8}, {"date", "2026-12-06T00:00:00Z"},
                                      {"libraries", {{"eigen", "3.4.0"}}}};
  const nlohmann::json options = {{"tolerance", tolerance}, {"repetitions", 7}};
  return MakeRunIdentity(results, environment, options);
}

TEST(RunIdentity, DifferingSettingsCommitAndMachineAreNamed) {
  const std::string sha_a = "0123456789abcdef0123", sha_b = "fedcba9876543210fedc";
  const RunIdentity a = Identity(sha_a, 1e-10, "Xeon", "node1");
  const RunIdentity same = Identity(sha_a, 1e-10, "Xeon", "node1");
  const RunIdentity b = Identity(sha_b, 1e-8, "EPYC", "node2");
  EXPECT_EQ(DifferencesLine(IdentityRows(a, same)), "");
  EXPECT_FALSE(MachinesDiffer(IdentityRows(a, same)));
  const std::vector<IdentityRow> rows = IdentityRows(a, b);
  EXPECT_EQ(DifferencesLine(rows),
            "tolerance 1e-10 vs 1e-08; commit 0123456789ab vs fedcba987654; host node1 vs node2; cpu Xeon vs EPYC");
  EXPECT_TRUE(MachinesDiffer(rows));
  // A machine field one run does not record is unknown, not different.
  EXPECT_FALSE(MachinesDiffer(IdentityRows(a, Identity(sha_a, 1e-10, "Xeon", ""))));

  RunComparison c = CompareRuns(SyntheticRun(1.0), SyntheticRun(1.0), CompareOptions{});
  c.identity = rows;
  const std::string md = CompareMarkdown(c, CompareOptions{}, "a", "b", "");
  EXPECT_LT(md.find("## The runs"), md.find("## Verdict changes"));
  EXPECT_THAT(md, HasSubstr("**Differs:** tolerance 1e-10 vs 1e-08; commit 0123456789ab vs fedcba987654"));
  EXPECT_THAT(md, HasSubstr("different machines"));
  EXPECT_THAT(md, HasSubstr("| setting | tolerance **≠** | 1e-10 | 1e-08 |"));
  EXPECT_THAT(md, HasSubstr("| build | eigen | 3.4.0 | 3.4.0 |"));
  EXPECT_THAT(md, HasSubstr("| info | date |"));
  const std::string text = CompareSummaryText(c, CompareOptions{});
  EXPECT_THAT(text, HasSubstr("differs: tolerance 1e-10 vs 1e-08"));
  EXPECT_THAT(text, HasSubstr("WARNING: different machines"));
}

}  // namespace
}  // namespace smcbench
