// The report's explanations on handmade results: statuses and failure reasons per backend, the backends that solved
// nothing listed apart, blanks where nothing is defined, the fastest correct backend per size band, the tolerance
// ladder, the audit of the backends' own success flags (and the return code it rests on, through results.json and
// results.csv), the figure styles for many backends, and the sweep's problem and backend selection.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <tuple>
#include <unistd.h>

#include "bench/replay/jobs.h"
#include "bench/replay/replay.h"
#include "bench/replay/results_io.h"
#include "bench/replay/size_band.h"
#include "solvers/registry/registry.h"
#include "bench/analysis/report_markdown.h"
#include "bench/analysis/peer_tables.h"
#include "bench/analysis/report_test_records.h"
#include "bench/analysis/sweep_tables.h"
#include "bench/figures/gnuplot_figure.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/job_list.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using namespace report_test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

// (a user's own suite of 20×20 problems meets enum's size limit this way).
SuiteResults SizeLimitedSuite() {
  SuiteResults s;
  s.suite = "mine";
  s.description = "three problems";
  s.problems = 3;
  for (const char* p : {"p1", "p2", "p3"}) {
    s.replay.records.push_back(Rec(p, "lemke", Verdict::kSolved, 2e-6, 20));
    s.replay.records.push_back(Rec(p, "psor", std::string(p) == "p3" ? Verdict::kFailed : Verdict::kSolved, 1e-6, 20));
    ReplayRecord refused = Rec(p, "enum", Verdict::kFailed, 24e-6, 20, SolveStatus::kSizeLimit);
    refused.message = "refused m > 12";
    s.replay.records.push_back(refused);
  }
  s.replay.records[7].message = "psor: 1000 sweeps";
  return s;
}

TEST(ReportFailures, StatusCountsAndTheMostCommonEnding) {
  SuiteResults s = SizeLimitedSuite();
  s.replay.records[2].message = "refused m > 12 (first call)";  // one of enum's three messages differs
  const std::vector<BackendSummary> summary = SummarizeSuite(s);
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[0].statuses, (std::map<SolveStatus, int>{{SolveStatus::kSolved, 3}}));
  EXPECT_EQ(summary[1].statuses,
            (std::map<SolveStatus, int>{{SolveStatus::kSolved, 2}, {SolveStatus::kIterationLimit, 1}}));
  EXPECT_EQ(summary[2].statuses, (std::map<SolveStatus, int>{{SolveStatus::kSizeLimit, 3}}));
  EXPECT_EQ(summary[0].failure.count, 0);  // nothing to explain
  EXPECT_EQ(summary[1].failure.status, SolveStatus::kIterationLimit);
  EXPECT_EQ(summary[1].failure.count, 1);
  const FailureReason& enum_reason = summary[2].failure;
  EXPECT_EQ(enum_reason.status, SolveStatus::kSizeLimit);
  EXPECT_EQ(enum_reason.count, 3);
  EXPECT_EQ(enum_reason.message, "refused m > 12");  // 2 of 3, the most common
  EXPECT_EQ(enum_reason.message_count, 2);
  EXPECT_DOUBLE_EQ(enum_reason.median_time, 24e-6);
  EXPECT_FALSE(SolvedNothing(summary[0], summary));
  EXPECT_FALSE(SolvedNothing(summary[1], summary));
  EXPECT_TRUE(SolvedNothing(summary[2], summary));
  // When nobody solved anything, nobody is set apart (there is no timing table to keep clean).
  std::vector<BackendSummary> none = summary;
  for (auto& b : none) b.solved = 0;
  EXPECT_FALSE(SolvedNothing(none[2], none));
}

TEST(ReportFailures, SolvedNothingIsListedApartWithItsReasonAndStatusesAreTabled) {
  const std::string md = ReportOf(SizeLimitedSuite(), "apart");
  // The timing table has lemke and psor, never enum with a penalty time.
  EXPECT_THAT(md, HasSubstr("| lemke | 3 | 0 | 0 | 0 | 0 | 0 | 100% | 2 µs |"));
  EXPECT_THAT(md, HasSubstr("| psor | 2 | 0 | 1 | 0 | 0 | 0 | 66.7% |"));
  EXPECT_THAT(md, Not(HasSubstr("| enum | 0 | 0 | 3 | 0 | 0 | 0 | 0% |")));
  EXPECT_THAT(md, HasSubstr("**Solved nothing** in this suite"));
  EXPECT_THAT(md, HasSubstr("| enum | 3 | 0 | 3 | 0 | `size_limit` on 3 of 3: \"refused m > 12\", median 24 µs |"));
  // The penalty convention stands next to the table that uses it.
  EXPECT_THAT(md, HasSubstr("counts as 10× the slowest correct time on that problem, or as 10 s when no backend "
                            "got it right"));
  // Statuses: one column per status met, in the enum's order, then the audit of claims (every flag right here).
  EXPECT_THAT(md, HasSubstr("| backend | `solved` | `iteration_limit` | `size_limit` | flag right | "));
  EXPECT_THAT(md, HasSubstr("|---|---|---|---|---|---|---|---|\n| lemke | 3 | 0 | 0 | 3/3 (100%) | 0 | 0 | 0/3 |\n"
                            "| psor | 2 | 1 | 0 | 3/3 (100%) | 0 | 0 | 0/3 |\n"
                            "| enum | 0 | 0 | 3 | 3/3 (100%) | 0 | 0 | 0/3 |\n"));
}

// A record whose timed solves could not all start cold (mode "cached") is in no table: here lemke's time would
// otherwise be 1 ns on p1 and p2. A line names each such record.
TEST(ReportCached, CachedRecordsStayOutOfTheTablesWithALineNamingThem) {
  SuiteResults s = SizeLimitedSuite();
  for (const char* p : {"p1", "p2"}) {
    ReplayRecord cached = Rec(p, "lemke", Verdict::kSolved, 1e-9, 20);
    cached.mode = "cached";
    s.replay.records.push_back(cached);
  }
  const std::string md = ReportOf(s, "cached");
  EXPECT_THAT(md, HasSubstr("| lemke | 3 | 0 | 0 | 0 | 0 | 0 | 100% | 2 µs |"));  // as without them
  EXPECT_THAT(md, Not(HasSubstr("1 ns")));
  EXPECT_THAT(md, HasSubstr("Left out of the tables and profiles above: 2 record(s) whose timed solves could not all "
                            "start cold (mode `cached`): lemke on p1, lemke on p2.\n"));
  EXPECT_THAT(ReportOf(SizeLimitedSuite(), "not-cached"), Not(HasSubstr("Left out of the tables")));
}

// "worst residual (solved)" of a backend that solved nothing is blank, never a 0 that reads as exact.
TEST(ReportFailures, BlankNotZeroWhereNothingWasSolved) {
  SuiteResults s;
  s.suite = "hopeless";
  s.description = "nobody solves";
  s.replay.records = {Rec("p1", "a", Verdict::kFailed, 1e-3), Rec("p1", "b", Verdict::kFailed, 2e-3)};
  const auto summary = SummarizeSuite(s);
  EXPECT_TRUE(std::isnan(summary[0].worst_residual));
  EXPECT_TRUE(std::isnan(summary[0].worst_residual_scaled));
  EXPECT_TRUE(std::isnan(summary[0].worst_forward_error));
  const std::string md = ReportOf(s, "blank");
  // Nobody solved anything: both stay in the table, at the 10 s penalty, with blank worst errors.
  EXPECT_THAT(md, HasSubstr("| a | 0 | 0 | 1 | 0 | 0 | 0 | 0% | 10 s |  |  |  |\n"));
  EXPECT_THAT(md, HasSubstr("| b | 0 | 0 | 1 | 0 | 0 | 0 | 0% | 10 s |  |  |  |\n"));
  // A solved answer without a unique reference: the residuals are there, the forward error is "–" (no z*).
  s.replay.records[1] = Rec("p1", "b", Verdict::kSolved, 2e-3);
  EXPECT_THAT(ReportOf(s, "blank2"), HasSubstr("| b | 1 | 0 | 0 | 0 | 0 | 0 | 100% | 2 ms | 1e-12 | 2e-12 | – |\n"));
}

TEST(ReportBands, BandsAreOneDefinition) {
  EXPECT_EQ(SizeBandOf(1), SizeBand::kTiny);
  EXPECT_EQ(SizeBandOf(4), SizeBand::kTiny);
  EXPECT_EQ(SizeBandOf(5), SizeBand::kSmall);
  EXPECT_EQ(SizeBandOf(64), SizeBand::kSmall);
  EXPECT_EQ(SizeBandOf(65), SizeBand::kMedium);
  EXPECT_EQ(SizeBandOf(1024), SizeBand::kMedium);
  EXPECT_EQ(SizeBandOf(1025), SizeBand::kLarge);
  EXPECT_EQ(ToString(SizeBand::kSmall), "5 ≤ m ≤ 64");
}

// "fast" is fastest on the small problems but gives one wrong answer at m = 10: it wins m ≤ 4 and is no candidate
// in 5–64, where "sure" (always right) wins although slower.
TEST(ReportBands, FastestCorrectBackendPerBand) {
  SuiteResults s;
  s.suite = "bands";
  s.description = "two bands";
  s.replay.records = {Rec("t1", "fast", Verdict::kSolved, 1e-6, 2),  Rec("t1", "sure", Verdict::kSolved, 4e-6, 2),
                      Rec("t2", "fast", Verdict::kSolved, 1e-6, 3),  Rec("t2", "sure", Verdict::kSolved, 4e-6, 3),
                      Rec("s1", "fast", Verdict::kSolved, 1e-6, 10), Rec("s1", "sure", Verdict::kSolved, 9e-6, 10),
                      Rec("s2", "fast", Verdict::kWronglyClaimed, 1e-6, 10),
                      Rec("s2", "sure", Verdict::kSolved, 9e-6, 10),
                      Rec("s3", "slow", Verdict::kSolved, 1e-3, 10), Rec("s3", "sure", Verdict::kFailed, 1e-3, 10)};
  const std::vector<BandWinner> winners = FastestCorrectPerBand(s);
  ASSERT_EQ(winners.size(), 2u);
  EXPECT_EQ(winners[0].band, SizeBand::kTiny);
  EXPECT_EQ(winners[0].problems, 2);
  EXPECT_EQ(winners[0].solver, "fast");
  EXPECT_EQ(winners[0].correct, 2);
  EXPECT_NEAR(winners[0].shifted_geomean, 1e-6, 1e-18);  // SGM of (1 µs, 1 µs), shift 1 µs
  EXPECT_EQ(winners[0].fastest_on, 2);
  EXPECT_EQ(winners[0].runner_up, "sure");
  EXPECT_NEAR(winners[0].runner_up_geomean, 4e-6, 1e-18);
  // 5–64: fast has a wrong answer; sure has 2 correct of 3, slow 1: sure, with slow the runner-up.
  EXPECT_EQ(winners[1].band, SizeBand::kSmall);
  EXPECT_EQ(winners[1].problems, 3);
  EXPECT_EQ(winners[1].solver, "sure");
  EXPECT_EQ(winners[1].correct, 2);
  EXPECT_EQ(winners[1].fastest_on, 1);  // s2 (fast was wrong there); s1 went to fast
  EXPECT_EQ(winners[1].runner_up, "slow");
  EXPECT_EQ(winners[1].runner_up_correct, 1);
  // sure's SGM in the band: 9 µs, 9 µs, and s3 at 10 × slow's 1 ms.
  EXPECT_NEAR(winners[1].shifted_geomean, std::cbrt(10e-6 * 10e-6 * (1e-2 + 1e-6)) - 1e-6, 1e-15);
  const std::string md = ReportOf(s, "bands");
  EXPECT_THAT(md, HasSubstr("| m ≤ 4 | 2 | **fast** | 2/2 | 1 µs | 2 | sure | 2/2 | 4 µs | 4× |"));
  EXPECT_THAT(md, HasSubstr("| 5 ≤ m ≤ 64 | 3 | **sure** | 2/3 |"));
}

// Sweep records of three tolerances: psor loses problems as the tolerance tightens, lemke keeps them all.
TEST(ReportLadder, SuccessPerBackendAndTolerance) {
  SuiteResults s;
  s.suite = "ladder";
  s.description = "d";
  s.replay.records = {Rec("p1", "psor", Verdict::kSolved, 1e-6), Rec("p1", "lemke", Verdict::kSolved, 1e-6)};
  const auto sweep = [](const std::string& problem, const std::string& solver, double tol, Verdict v) {
    ReplayRecord r = Rec(problem, solver, v, 1e-6);
    r.mode = "sweep";
    r.tolerance = tol;
    return r;
  };
  for (const char* p : {"p1", "p2"}) {
    s.replay.sweep.push_back(sweep(p, "psor", 1e-3, Verdict::kSolved));
    s.replay.sweep.push_back(sweep(p, "psor", 1e-9, std::string(p) == "p1" ? Verdict::kSolved : Verdict::kFailed));
    s.replay.sweep.push_back(sweep(p, "psor", 1e-12, Verdict::kFailed));
    for (double tol : {1e-3, 1e-9, 1e-12}) s.replay.sweep.push_back(sweep(p, "lemke", tol, Verdict::kSolved));
  }
  s.replay.sweep.push_back(sweep("p3", "lemke", 1e-12, Verdict::kCorrectlyRefused));
  const ToleranceLadder ladder = BuildToleranceLadder(s);
  EXPECT_THAT(ladder.tolerances, ElementsAre(1e-3, 1e-9, 1e-12));
  ASSERT_EQ(ladder.rows.size(), 2u);
  EXPECT_EQ(ladder.rows[0].solver, "psor");
  EXPECT_THAT(ladder.rows[0].correct, ElementsAre(2, 1, 0));
  EXPECT_THAT(ladder.rows[0].problems, ElementsAre(2, 2, 2));
  EXPECT_THAT(ladder.rows[1].correct, ElementsAre(2, 2, 3));
  EXPECT_THAT(ladder.rows[1].problems, ElementsAre(2, 2, 3));
  const std::string md = ReportOf(s, "ladder");
  EXPECT_THAT(md, HasSubstr("| backend | tol 0.001 | tol 1e-09 | tol 1e-12 | "));
  EXPECT_THAT(md, HasSubstr("| psor | 2/2 (100%) | 1/2 (50%) | 0/2 (0%) | "));
  EXPECT_THAT(md, HasSubstr("| lemke | 2/2 (100%) | 2/2 (100%) | 3/3 (100%) | "));
  EXPECT_THAT(md, HasSubstr("an untimed warm-up, then at most 3 timed samples"));
}

// Siconos' own return code decides its claim; our backends' claim is their status.
TEST(ReportAudit, OwnSuccessFlagAgainstTheVerdict) {
  SuiteResults s;
  s.suite = "audit";
  s.description = "d";
  const auto peer = [](const std::string& p, Verdict v, SolveStatus status, std::optional<int> code) {
    ReplayRecord r = Rec(p, "siconos-x", v, 1e-6, 2, status);
    r.backend_code = code;
    return r;
  };
  s.replay.records = {
      peer("p1", Verdict::kSolved, SolveStatus::kSolved, 0),            // right
      peer("p2", Verdict::kSolved, SolveStatus::kSolved, 1),            // info 1, our polish finished it: false failure
      peer("p3", Verdict::kFailed, SolveStatus::kInaccurate, 0),        // info 0, our check rejected: false success
      peer("p4", Verdict::kFailed, SolveStatus::kSizeLimit, std::nullopt),  // refused before the call: right
      Rec("p1", "ours", Verdict::kSolved, 1e-6),
      Rec("p2", "ours", Verdict::kWronglyClaimed, 1e-6),                 // status solved: false success
      Rec("p3", "ours", Verdict::kFailed, 1e-6),                         // iteration limit: right
      Rec("p4", "ours", Verdict::kCorrectlyRefused, 1e-6, 2, SolveStatus::kInfeasible)};  // right
  EXPECT_TRUE(ClaimedSolved(s.replay.records[2]));   // code 0 although the status is inaccurate
  EXPECT_FALSE(ClaimedSolved(s.replay.records[1]));  // code 1 although the status is solved
  const std::vector<ClaimAudit> audit = AuditClaims(s);
  ASSERT_EQ(audit.size(), 2u);
  EXPECT_EQ(audit[0].solver, "siconos-x");
  EXPECT_EQ(audit[0].records, 4);
  EXPECT_EQ(audit[0].right, 2);
  EXPECT_EQ(audit[0].false_success, 1);
  EXPECT_EQ(audit[0].false_failure, 1);
  EXPECT_EQ(audit[0].with_return_code, 3);
  EXPECT_EQ(audit[1].right, 3);
  EXPECT_EQ(audit[1].false_success, 1);
  EXPECT_EQ(audit[1].false_failure, 0);
  EXPECT_EQ(audit[1].with_return_code, 0);
  const std::string md = ReportOf(s, "audit");
  // Statuses solved, iteration_limit, size_limit, infeasible, inaccurate; then the audit.
  EXPECT_THAT(md, HasSubstr("| siconos-x | 2 | 0 | 1 | 0 | 1 | 2/4 (50%) | **1** | 1 | 3/4 |\n"));
  EXPECT_THAT(md, HasSubstr("| ours | 2 | 1 | 0 | 1 | 0 | 3/4 (75%) | **1** | 0 | 0/4 |\n"));
}

// The suite heading counts, per problem, the verified references an interval enclosure proved and gives the
// largest radius; reference_radius goes through results.json.
TEST(ReportReferences, HeadingCountsTheProvedReferencesAndTheirLargestRadius) {
  SuiteResults s = SizeLimitedSuite();
  for (ReplayRecord& r : s.replay.records) {
    r.certificate = r.problem == "p3" ? "degenerate" : "unique";  // p3: verified, its degenerate row not proved
    r.reference_radius = r.problem == "p1" ? 2.5e-16 : r.problem == "p2" ? 1e-17 : kNaN;
    r.reference_proved_unique = r.problem == "p2";
  }
  const std::string md = ReportOf(s, "proved");
  EXPECT_THAT(md, HasSubstr("certified references: 1 degenerate, 2 unique (forward errors are judged on the unique "
                            "and degenerate ones); 2 of the 3 verified proved by an interval enclosure (1 the "
                            "only solution: M + Mᵀ proved positive definite), an exact solution within 2.5e-16 of z*."));
  EXPECT_EQ(ReplayRecordFromJson(ReplayRecordToJson(s.replay.records[0])).reference_radius, 2.5e-16);
  EXPECT_TRUE(ReplayRecordFromJson(ReplayRecordToJson(s.replay.records[3])).reference_proved_unique);  // p2
  EXPECT_TRUE(std::isnan(ReplayRecordFromJson(ReplayRecordToJson(s.replay.records[6])).reference_radius));
  nlohmann::json old = ReplayRecordToJson(s.replay.records[0]);
  old.erase("reference_radius");  // results written before the field
  EXPECT_TRUE(std::isnan(ReplayRecordFromJson(old).reference_radius));
}

// The return code survives results.json and results.csv (empty when there is none).
TEST(ReportAudit, ReturnCodeRoundTripsThroughTheResultFiles) {
  ReplayRecord with = Rec("p1", "siconos-x", Verdict::kSolved, 1e-6);
  with.backend_code = 3;
  const ReplayRecord without = Rec("p1", "lemke", Verdict::kSolved, 1e-6);
  EXPECT_EQ(ReplayRecordFromJson(ReplayRecordToJson(with)).backend_code, std::optional<int>(3));
  EXPECT_EQ(ReplayRecordFromJson(ReplayRecordToJson(without)).backend_code, std::nullopt);
  nlohmann::json old = ReplayRecordToJson(with);
  old.erase("backend_code");  // results written before the field
  EXPECT_EQ(ReplayRecordFromJson(old).backend_code, std::nullopt);
  const fs::path dir = fs::temp_directory_path() / ("smcbench-report-code-" + std::to_string(::getpid()));
  BenchResults results;
  results.command = "test";
  SuiteResults suite;
  suite.suite = "s";
  suite.replay.records = {with, without};
  results.suites = {suite};
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const std::string csv = ReadText(dir / "results.csv");
  EXPECT_THAT(csv, HasSubstr(",start,backend_code,reference_radius,reference_proved_unique\n"));
  EXPECT_THAT(csv, HasSubstr(",,3,nan,0\n"));  // empty start, code 3, no proved reference
  EXPECT_THAT(csv, HasSubstr(",,,nan,0\n"));   // empty start, no code
  EXPECT_EQ(ReadBenchResults(dir.string()).suites[0].replay.records[0].backend_code, std::optional<int>(3));
  fs::remove_all(dir);
}

// A Siconos backend, when built: the record keeps Siconos' own info (0 on a problem it solves).
TEST(ReportAudit, SiconosRecordsKeepTheirOwnReturnCode) {
  const auto names = SolverNames();
  if (std::find(names.begin(), names.end(), "siconos-lcp-lemke") == names.end()) {
    GTEST_SKIP() << "built without the siconos-* backends";
  }
  DenseMatrix M(2, 2);
  M << 2.0, 1.0, 1.0, 2.0;
  Vector q(2);
  q << -1.0, -1.0;
  ProblemSet set;
  set.name = "one";
  set.problems.push_back(MakeLibraryProblem("one/spd2", "handmade", BoxMLCP::LCP(M, q, "spd2")));
  ReplayOptions options;
  options.repetitions = 1;
  options.min_sample_seconds = 0.0;
  for (const char* name : {"siconos-lcp-lemke", "lemke"}) {
    auto solver = CreateSolver(name);
    const ReplayRecord r = ReplayOne(set, set.problems[0], solver.get(), name, options, "cold", 1e-10);
    EXPECT_EQ(r.verdict, Verdict::kSolved) << name;
    if (std::string(name) == "lemke") {
      EXPECT_EQ(r.backend_code, std::nullopt);
    } else {
      EXPECT_EQ(r.backend_code, std::optional<int>(0));
    }
  }
}

// 24 backends stay distinct: no two share colour + dash + point type, in one family or across both.
TEST(ReportFigures, TwentyFourBackendsHaveDistinctStyles) {
  const std::set<std::string> okabe_ito = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                           "#E69F00", "#56B4E9", "#000000"};
  using Triple = std::tuple<std::string, int, int>;
  for (const auto& [ours, external] : {std::pair{24, 0}, std::pair{0, 24}, std::pair{12, 12}}) {
    std::set<Triple> seen;
    for (int family = 0; family < 2; ++family) {
      for (int i = 0; i < (family ? external : ours); ++i) {
        const PlotStyle style = StyleOf(static_cast<std::size_t>(i), family == 1);
        EXPECT_TRUE(okabe_ito.count(style.colour)) << style.colour;
        EXPECT_EQ(style.dash == 1, family == 0);  // ours solid, the external ones dashed
        EXPECT_TRUE(seen.insert({style.colour, style.dash, style.point}).second)
            << "index " << i << " of family " << family << " repeats a style";
      }
    }
    EXPECT_EQ(seen.size(), 24u);
  }
  // Every registered backend and the generic sparse path: distinct styles, the same in every figure.
  std::set<std::string> styles;
  std::vector<std::string> names;
  for (auto n : SolverNames()) names.emplace_back(n);
  names.emplace_back("newton-sparse-path");
  for (const std::string& n : names) EXPECT_TRUE(styles.insert(BackendStyle(n)).second) << n;
  EXPECT_EQ(BackendStyle("implicit, lemke"), BackendStyle("lemke"));
}

// The profile leaves out a backend that solved nothing (it would lie on the x-axis) and names it under the figure;
// tick labels in %g.
TEST(ReportFigures, ProfileNamesBackendsWithoutSuccessInsteadOfDrawingThem) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot is not on PATH";
  const std::string md = ReportOf(SizeLimitedSuite(), "profile", /*plots=*/true, /*keep=*/true);
  EXPECT_THAT(md, HasSubstr("Not drawn, since they solved none of those problems: enum."));
  const fs::path dir = ReportDir("profile");
  const std::string script = ReadText(dir / "profile-mine.gp");
  EXPECT_THAT(script, HasSubstr("title 'lemke'"));
  EXPECT_THAT(script, HasSubstr("title 'psor'"));
  EXPECT_THAT(script, Not(HasSubstr("title 'enum'")));
  EXPECT_THAT(script, HasSubstr("set format y '%g'"));
  EXPECT_THAT(script, HasSubstr("set key outside"));
  fs::remove_all(dir);
}

TEST(ReportSweep, ProblemsAreSpreadOverTheSuite) {
  EXPECT_THAT(SweepProblemIndices(10, 4), ElementsAre(1, 3, 6, 8));
  EXPECT_THAT(SweepProblemIndices(3, 16), ElementsAre(0, 1, 2));
  EXPECT_TRUE(SweepProblemIndices(5, 0).empty());
  const std::vector<std::size_t> paper = SweepProblemIndices(468, 16);
  ASSERT_EQ(paper.size(), 16u);
  EXPECT_TRUE(std::is_sorted(paper.begin(), paper.end()));
  EXPECT_EQ(std::set<std::size_t>(paper.begin(), paper.end()).size(), 16u);
  EXPECT_LT(paper.front(), 468u / 16);
  EXPECT_GE(paper.back(), 468u - 468u / 16);
}

// Every backend, exact ones included, gets the ladder: one sweep job per swept problem × backend × tolerance.
TEST(ReportSweep, EveryBackendGetsEveryRung) {
  ProblemSet set;
  set.name = "five";
  for (int i = 0; i < 5; ++i) {
    DenseMatrix M = DenseMatrix::Identity(2, 2);
    Vector q = Vector::Constant(2, -1.0 - i);
    set.problems.push_back(
        MakeLibraryProblem("five/p" + std::to_string(i), "handmade", BoxMLCP::LCP(M, q, "p" + std::to_string(i))));
  }
  ReplayOptions options;
  options.tolerance_sweep_problems = 2;
  JobListRequest request;
  request.solvers = {"lemke", "psor"};
  std::set<std::tuple<std::string, std::string, double>> sweep;
  for (const BenchJob& job : ListBenchJobs(BoxSuites({set}), options, request)) {
    if (job.kind == JobKind::kSweep) sweep.insert({job.problem_id, job.solver, job.tolerance});
  }
  EXPECT_EQ(sweep.size(), 2u * 2u * std::size(kSweepTolerances));
  for (const char* problem : {"five/p1", "five/p3"}) {  // SweepProblemIndices(5, 2) = {1, 3}
    for (const char* solver : {"lemke", "psor"}) {
      for (double tol : {1e-3, 1e-6, 1e-9, 1e-12}) EXPECT_TRUE(sweep.count({problem, solver, tol})) << problem;
    }
  }
}

}  // namespace
}  // namespace smcbench
