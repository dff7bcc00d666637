// The report's analysis on a hand-made results set: classes from tags, the floor kept out of every ranking and
// count, the summary's fastest / most reliable / gap to the floor per class, the failures per backend, and the
// report's text (summary first, the floor column, "floor not measured" for older results, the verdict in the
// appendix, the failure list).
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "bench/replay/floor.h"
#include "bench/analysis/class_tables.h"
#include "bench/analysis/report_markdown.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

ReplayRecord Record(const std::string& problem, const std::string& solver, Verdict verdict, double t, int size,
                    const std::string& tags, SolveStatus status = SolveStatus::kSolved, const std::string& message = "") {
  ReplayRecord r;
  r.suite = "mine";
  r.problem = problem;
  r.solver = solver;
  r.verdict = verdict;
  r.status = status;
  r.message = message;
  r.time_median = r.time_min = r.time_max = t;
  r.samples = 3;
  r.size = size;
  r.tags = tags;
  return r;
}

ReplayRecord Floor(const std::string& problem, double t, int size, const std::string& tags) {
  ReplayRecord r = Record(problem, kFloorSolver, Verdict::kSolved, t, size, tags);
  r.mode = "floor";
  r.message = "dense LU (partial pivoting) of a matrix";
  return r;
}

// Two SPD relay problems at m = 16 (fast solves everything at 2 µs, slow at 8 µs), two nonsymmetric LCPs at m = 16
// where fast fails one with an iteration limit and slow solves both; a floor of 1 µs on every problem, the fastest
// time of all, which must never make "floor" a winner.
BenchResults HandMade(bool with_floor) {
  SuiteResults s;
  s.suite = "mine";
  s.description = "hand-made";
  s.problems = 4;
  for (const char* p : {"spd1", "spd2"}) {
    s.replay.records.push_back(Record(p, "fast", Verdict::kSolved, 2e-6, 16, "spd,relay"));
    s.replay.records.push_back(Record(p, "slow", Verdict::kSolved, 8e-6, 16, "spd,relay"));
    if (with_floor) s.replay.floor.push_back(Floor(p, 1e-6, 16, "spd,relay"));
  }
  s.replay.records.push_back(Record("ns1", "fast", Verdict::kSolved, 3e-6, 16, "pmatrix,lcp"));
  s.replay.records.push_back(Record("ns2", "fast", Verdict::kFailed, 5e-6, 16, "pmatrix,lcp",
                                    SolveStatus::kIterationLimit, "1000 sweeps"));
  for (const char* p : {"ns1", "ns2"}) {
    s.replay.records.push_back(Record(p, "slow", Verdict::kSolved, 9e-6, 16, "pmatrix,lcp"));
    if (with_floor) s.replay.floor.push_back(Floor(p, 1e-6, 16, "pmatrix,lcp"));
  }
  BenchResults results;
  results.command = "test";
  results.suites = {s};
  return results;
}

TEST(ReportClasses, MatrixClassAndBoundsFromTheTags) {
  ReplayRecord r;
  r.tags = "spd,relay";
  EXPECT_EQ(MatrixClassOf(r), "SPD");
  EXPECT_EQ(BoundsClassOf(r), "relay");
  r.tags = "pmatrix,lcp";
  EXPECT_EQ(MatrixClassOf(r), "nonsymmetric P");
  EXPECT_EQ(BoundsClassOf(r), "LCP");
  r.tags = "diagdom,mixed";
  EXPECT_EQ(MatrixClassOf(r), "nonsymmetric P");
  EXPECT_EQ(BoundsClassOf(r), "mixed");
  r.tags = "capture,paper";
  EXPECT_EQ(MatrixClassOf(r), "general");
  EXPECT_EQ(BoundsClassOf(r), "untagged");
  r.sparse = true;
  EXPECT_EQ(MatrixClassOf(r), "sparse");
  r.solver = "newton-sparse-path";  // a sparse copy of a dense problem: the problem's class
  EXPECT_EQ(MatrixClassOf(r), "general");
  EXPECT_EQ(MatrixClassOf(r, /*mcp_suite=*/true), "MCP");
  r.tags = "siconos,mlcp";
  EXPECT_EQ(BoundsClassOf(r), "mixed");
}

TEST(ReportClasses, FastestMostReliableAndTheGapToTheFloorPerClass) {
  const std::vector<ClassSummary> rows = SummarizeClasses(HandMade(true));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(ClassName(rows[0].problem_class), "SPD · relay");  // SPD first
  EXPECT_EQ(rows[0].problem_class.band, SizeBand::kSmall);
  EXPECT_EQ(rows[0].problems, 2);
  EXPECT_EQ(rows[0].fastest, "fast");
  EXPECT_EQ(rows[0].fastest_correct, 2);
  EXPECT_DOUBLE_EQ(rows[0].fastest_over_floor, 2.0);  // 2 µs over 1 µs
  EXPECT_EQ(rows[0].floor_instances, 2);
  EXPECT_EQ(ClassName(rows[1].problem_class), "nonsymmetric P · LCP");
  // fast failed ns2: its penalty (10 × 9 µs) makes slow the fastest correct, and slow is the most reliable.
  EXPECT_EQ(rows[1].fastest, "slow");
  EXPECT_EQ(rows[1].most_reliable, "slow");
  EXPECT_EQ(rows[1].reliable_correct, 2);
  EXPECT_DOUBLE_EQ(rows[1].fastest_over_floor, 9.0);
  for (const ClassSummary& c : rows) EXPECT_NE(c.most_reliable, kFloorSolver);
}

TEST(ReportClasses, WithoutFloorRecordsTheGapIsNotDefined) {
  const std::vector<ClassSummary> rows = SummarizeClasses(HandMade(false));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_TRUE(std::isnan(rows[0].fastest_over_floor));
  EXPECT_EQ(rows[0].floor_instances, 0);
}

TEST(ReportClasses, FailuresPerBackendWithTheirMostCommonCause) {
  const std::vector<BackendFailures> all = FailuresPerBackend(HandMade(true));
  ASSERT_EQ(all.size(), 2u);  // fast, slow: never the floor
  EXPECT_EQ(all[0].solver, "fast");
  EXPECT_EQ(all[0].records, 4);
  EXPECT_EQ(all[0].not_correct, 1);
  EXPECT_EQ(all[0].cause.status, SolveStatus::kIterationLimit);
  EXPECT_EQ(all[0].cause.message, "1000 sweeps");
  ASSERT_EQ(all[0].entries.size(), 1u);
  EXPECT_EQ(all[0].entries[0].instance, "mine/ns2");
  EXPECT_EQ(all[0].entries[0].problem_class, "nonsymmetric P · LCP · m5-64");
  EXPECT_EQ(all[1].not_correct, 0);
}

TEST(ReportClasses, TheFloorIsInNoRankingOrCount) {
  const BenchResults results = HandMade(true);
  const SuiteResults& suite = results.suites[0];
  for (const BackendSummary& b : SummarizeSuite(suite)) EXPECT_NE(b.solver, kFloorSolver);
  for (const BandWinner& w : FastestCorrectPerBand(suite)) {
    EXPECT_NE(w.solver, kFloorSolver);
    EXPECT_NE(w.runner_up, kFloorSolver);
  }
  for (const auto& [solver, ratios] : PerformanceRatios(suite)) EXPECT_NE(solver, kFloorSolver);
  EXPECT_EQ(FloorRatios(suite.replay.records, FloorTimes(suite), "fast"), (std::vector<double>{2.0, 2.0, 3.0}));
  EXPECT_TRUE(FloorRatios(suite.replay.records, FloorTimes(suite), kFloorSolver).empty());
}

std::string ReportOf(const BenchResults& results, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-classes-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const std::string md = WriteBenchReport(dir.string(), /*plots=*/false);
  fs::remove_all(dir);
  return md;
}

TEST(ReportClasses, TheReportOpensOnTheSummaryAndEndsOnTheFailuresAndTheVerdict) {
  const std::string md = ReportOf(HandMade(true), "floor");
  const auto summary = md.find("## Summary");
  const auto suite = md.find("## Suite `mine`");
  const auto failures = md.find("## Failures per backend");
  const auto appendix = md.find("## Appendix: the verdict and the timing");
  ASSERT_NE(summary, std::string::npos);
  ASSERT_NE(suite, std::string::npos);
  ASSERT_NE(failures, std::string::npos);
  ASSERT_NE(appendix, std::string::npos);
  EXPECT_LT(summary, suite);
  EXPECT_LT(suite, failures);
  EXPECT_LT(failures, appendix);
  EXPECT_GT(md.find("**The verdict.**"), appendix);  // the definition moved to the appendix
  EXPECT_NE(md.find("| SPD · relay | 5 ≤ m ≤ 64 | 2 | **fast** | 2/2 |"), std::string::npos);
  EXPECT_NE(md.find("| 2× (2) |", summary), std::string::npos);
  EXPECT_NE(md.find("| fast | 4 | 1 | 0 | `iteration_limit` on 1 of 1: \"1000 sweeps\""), std::string::npos);
  EXPECT_NE(md.find("| mine/ns2 | nonsymmetric P · LCP · m5-64 | `iteration_limit` | failed | 1000 sweeps |"),
            std::string::npos);
  EXPECT_NE(md.find(" time / floor |", suite), std::string::npos);
  EXPECT_EQ(md.find("| floor |"), std::string::npos);  // never a backend row
  EXPECT_EQ(md.find("Floor not measured"), std::string::npos);
}

TEST(ReportClasses, ResultsWithoutFloorRecordsSayItWasNotMeasured) {
  const std::string md = ReportOf(HandMade(false), "nofloor");
  EXPECT_NE(md.find("Floor not measured in this run"), std::string::npos);
  EXPECT_NE(md.find("floor not measured in this run"), std::string::npos);  // the summary's
  EXPECT_EQ(md.find(" time / floor |"), std::string::npos);
}

}  // namespace
}  // namespace smcbench
