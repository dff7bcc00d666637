#include "bench/perf/perf_record.h"

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bench/perf/callgrind_dump.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

PerfFigure Figure(const std::string& id, double instructions, const std::string& status = "solved",
                  double ns = 100.0) {
  PerfFigure f;
  f.id = id;
  f.unit = id.rfind("step/", 0) == 0 ? "step" : "solve";
  f.units = 64;
  f.status = status;
  f.instructions = instructions;
  f.ns = ns;
  f.ns_min = 0.9 * ns;
  f.ns_max = 1.2 * ns;
  return f;
}

PerfRun MakeRun(std::vector<PerfFigure> figures, const std::string& compiler = "g++ 12.2.0") {
  PerfRun r;
  r.environment = {{"compiler", compiler}, {"cxx_flags", "-O3"}, {"build_type", "Release"}, {"assertions", false},
                   {"libraries", {{"eigen", "3.4.0"}}}, {"git_sha", "abc123"}, {"date", "2026-11-21T00:00:00Z"}};
  r.figures = std::move(figures);
  return r;
}

const PerfRow& Row(const PerfComparison& c, const std::string& id) {
  for (const PerfRow& r : c.rows) {
    if (r.id == id) return r;
  }
  throw std::runtime_error("no row " + id);
}

TEST(CallgrindDump, ReadsTriggerAndTotals) {
  const CallgrindDump d = ParseCallgrindDump(
      "# callgrind format\nversion: 1\ncreator: callgrind-3.19.0\npid: 42\ncmd: perf_probe measure\npart: 3\n\n"
      "desc: I1 cache:\ndesc: Timerange: Basic block 10 - 20\ndesc: Trigger: Client Request: solve/a/psor\n\n"
      "positions: line\nevents: Ir\nsummary: 123456\n\nfl=(1) x.cc\nfn=(1) f\n3 123456\n\ntotals: 123450\n",
      "dump");
  EXPECT_EQ(d.trigger, "solve/a/psor");
  EXPECT_EQ(d.instructions, 123450.0);  // totals wins over summary
}

TEST(CallgrindDump, SummaryAloneAndOtherTriggers) {
  const CallgrindDump d = ParseCallgrindDump("desc: Trigger: Program termination\nevents: Ir Dr\nsummary: 77 5\n", "x");
  EXPECT_EQ(d.trigger, "");
  EXPECT_EQ(d.instructions, 77.0);
}

TEST(CallgrindDump, NotADumpIsAnErrorNamingTheFile) {
  try {
    ParseCallgrindDump("hello\n", "cg/callgrind.out.1");
    FAIL() << "expected an error";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cg/callgrind.out.1"));
  }
  EXPECT_THROW(ParseCallgrindDump("events: Dr Ir\ntotals: 5 6\n", "x"), InvalidInputError);
  EXPECT_THROW(ParseCallgrindDump("events: Ir\ntotals: lots\n", "x"), InvalidInputError);
}

TEST(PerfCompare, WithinThresholdPasses) {
  const PerfRun base = MakeRun({Figure("solve/a/psor", 1000), Figure("step/s2/enum", 400)});
  const PerfRun now = MakeRun({Figure("solve/a/psor", 1049), Figure("step/s2/enum", 381)});
  const PerfComparison c = ComparePerfRuns(base, now, 0.05);
  EXPECT_FALSE(c.failed());
  EXPECT_EQ(Row(c, "solve/a/psor").verdict, PerfVerdict::kSame);
  EXPECT_DOUBLE_EQ(Row(c, "solve/a/psor").ratio, 1.049);
  EXPECT_EQ(Row(c, "step/s2/enum").verdict, PerfVerdict::kSame);
}

TEST(PerfCompare, RegressionAboveThresholdFailsAndTheTableSaysWhich) {
  const PerfRun base = MakeRun({Figure("solve/a/psor", 1000), Figure("solve/b/lemke", 5000)});
  const PerfRun now = MakeRun({Figure("solve/a/psor", 1051), Figure("solve/b/lemke", 4000)});
  const PerfComparison c = ComparePerfRuns(base, now, 0.05);
  EXPECT_TRUE(c.failed());
  EXPECT_EQ(Row(c, "solve/a/psor").verdict, PerfVerdict::kRegressed);
  EXPECT_EQ(Row(c, "solve/b/lemke").verdict, PerfVerdict::kImproved);
  const std::string table = FormatComparison(c);
  EXPECT_THAT(table, HasSubstr("perf gate: FAIL"));
  EXPECT_THAT(table, HasSubstr("| solve/a/psor | 1000 | 1051 | 1.051 | REGRESSED |"));
  EXPECT_THAT(table, HasSubstr("| solve/b/lemke | 5000 | 4000 | 0.800 | improved |"));
  EXPECT_THAT(table, HasSubstr("1 regressed by more than 5 %"));
}

TEST(PerfCompare, ImprovementAlonePassesAndSuggestsAnUpdate) {
  const PerfComparison c =
      ComparePerfRuns(MakeRun({Figure("solve/a/psor", 1000)}), MakeRun({Figure("solve/a/psor", 500)}), 0.05);
  EXPECT_FALSE(c.failed());
  EXPECT_THAT(FormatComparison(c), HasSubstr("tools/perf-update"));
}

TEST(PerfCompare, StatusChangeAndMissingFigureFail) {
  const PerfRun base = MakeRun({Figure("solve/a/psor", 1000), Figure("solve/b/psor", 1000)});
  PerfComparison c = ComparePerfRuns(base, MakeRun({Figure("solve/a/psor", 1000, "iteration-limit")}), 0.05);
  EXPECT_TRUE(c.failed());
  EXPECT_EQ(Row(c, "solve/a/psor").verdict, PerfVerdict::kStatusChanged);
  EXPECT_EQ(Row(c, "solve/b/psor").verdict, PerfVerdict::kMissing);
}

TEST(PerfCompare, NewFigureIsInformation) {
  const PerfComparison c = ComparePerfRuns(MakeRun({Figure("solve/a/psor", 1000)}),
                                           MakeRun({Figure("solve/a/psor", 1000), Figure("solve/c/enum", 10)}), 0.05);
  EXPECT_FALSE(c.failed());
  EXPECT_EQ(Row(c, "solve/c/enum").verdict, PerfVerdict::kNew);
}

TEST(PerfCompare, OtherCompilerIsNotComparable) {
  const PerfComparison c =
      ComparePerfRuns(MakeRun({Figure("solve/a/psor", 1000)}), MakeRun({Figure("solve/a/psor", 1000)}, "clang 14"),
                      0.05);
  EXPECT_TRUE(c.failed());
  ASSERT_EQ(c.incomparable.size(), 1u);
  EXPECT_THAT(c.incomparable[0], HasSubstr("compiler"));
  EXPECT_THAT(FormatComparison(c), HasSubstr("not comparable: compiler"));
}

TEST(PerfCompare, RunWithoutInstructionCountsFails) {
  PerfFigure f = Figure("solve/a/psor", -1.0);
  const PerfComparison c = ComparePerfRuns(MakeRun({Figure("solve/a/psor", 1000)}), MakeRun({f}), 0.05);
  EXPECT_TRUE(c.failed());
  EXPECT_EQ(Row(c, "solve/a/psor").verdict, PerfVerdict::kMissing);
}

TEST(PerfCompare, ThresholdMustBeAFraction) {
  const PerfRun r = MakeRun({Figure("solve/a/psor", 1000)});
  EXPECT_THROW(ComparePerfRuns(r, r, 0.0), InvalidInputError);
  EXPECT_THROW(ComparePerfRuns(r, r, 5.0), InvalidInputError);
}

TEST(PerfRecord, JsonRoundTripAndMerge) {
  PerfRun r = MakeRun({Figure("solve/a/psor", 1234.5), Figure("step/s8/lemke", -1.0, "solved", -1.0)});
  const PerfRun back = PerfRunFromJson(ToJson(r));
  ASSERT_EQ(back.figures.size(), 2u);
  EXPECT_EQ(back.figures[0].instructions, 1234.5);
  EXPECT_EQ(back.figures[0].ns_max, r.figures[0].ns_max);
  EXPECT_LT(back.figures[1].instructions, 0.0);  // null stays "not measured"
  EXPECT_EQ(back.environment["compiler"], "g++ 12.2.0");

  PerfRun wall = MakeRun({Figure("step/s8/lemke", -1.0, "solved", 55.0)});
  const PerfRun merged = MergePerfRuns(back, wall);
  EXPECT_EQ(merged.figures[1].ns, 55.0);
  EXPECT_EQ(merged.figures[0].ns, r.figures[0].ns);  // no wall-clock figure of that id: kept
}

TEST(PerfRecord, MalformedRecordsAreNamedErrors) {
  EXPECT_THROW(PerfRunFromJson(nlohmann::json{{"format", "other/1"}, {"figures", nlohmann::json::array()}}),
               InvalidInputError);
  EXPECT_THROW(PerfRunFromJson(nlohmann::json{{"format", "smcbench-perf/1"}}), InvalidInputError);
  nlohmann::json twice = ToJson(MakeRun({Figure("solve/a/psor", 1), Figure("solve/a/psor", 2)}));
  EXPECT_THROW(PerfRunFromJson(twice), InvalidInputError);
  try {
    ReadPerfRun("/nonexistent/perf.json");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/perf.json"));
  }
}

TEST(PerfHistory, AppendsOneLinePerFigureAndReadsBack) {
  const fs::path path = fs::temp_directory_path() / ("smcbench-history-" + std::to_string(::getpid()) + ".csv");
  fs::remove(path);
  const PerfRun base = MakeRun({Figure("solve/a/psor", 1000), Figure("step/s2/enum", 400)});
  PerfRun now = MakeRun({Figure("solve/a/psor", 1010), Figure("step/s2/enum", 400)});
  AppendPerfHistory(path.string(), now, ComparePerfRuns(base, now, 0.05));
  now.environment["git_sha"] = "def456";
  AppendPerfHistory(path.string(), now, ComparePerfRuns(base, now, 0.05));
  const std::vector<PerfHistoryRow> rows = ReadPerfHistory(path.string());
  ASSERT_EQ(rows.size(), 4u);  // header written once
  EXPECT_EQ(rows[0].git_sha, "abc123");
  EXPECT_EQ(rows[0].id, "solve/a/psor");
  EXPECT_EQ(rows[0].instructions, 1010.0);
  EXPECT_EQ(rows[0].baseline_instructions, 1000.0);
  EXPECT_DOUBLE_EQ(rows[0].ratio, 1.01);
  EXPECT_EQ(rows[3].git_sha, "def456");
  EXPECT_EQ(rows[3].unit, "step");

  std::ofstream(path, std::ios::app) << "2026,x,broken\n";
  try {
    ReadPerfHistory(path.string());
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(":6: expected 8 fields"));
  }
  fs::remove(path);
}

}  // namespace
}  // namespace smcbench
