// `smcbench bench` and `smcbench report` end to end on the tiny suite (what CI runs), and the report's arithmetic
// (success counts, shifted geometric mean, Dolan–Moré ratios, growth exponent) on handmade results.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "tools/smcbench/bench_command.h"
#include "tools/smcbench/bench_report.h"
#include "tools/smcbench/cli_test_runner.h"
#include "tools/smcbench/simulate.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using test_support::CliRun;
using test_support::RunSmcbench;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(Bench, TinySuiteEndToEndWithReport) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-test-" + std::to_string(::getpid()));
  const CliRun r = RunSmcbench({"bench", "--suite", "tiny", "--quick", "--solver", "lemke", "--solver", "psor",
                                "--solver", "enum", "--out", dir.string(), "--report", "--no-plots"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("results.json"));
  const auto j = nlohmann::json::parse(ReadText(dir / "results.json"));
  EXPECT_EQ(j["format"], "smcbench-bench/1");
  for (const char* key : {"git_sha", "compiler", "cxx_flags", "cpu", "cores", "libraries", "date"}) {
    EXPECT_TRUE(j["environment"].contains(key)) << key;
  }
  ASSERT_EQ(j["suites"].size(), 1u);
  const auto& records = j["suites"][0]["records"];
  ASSERT_EQ(records.size(), 5u * 3u);
  int correct = 0;
  for (const auto& rec : records) {
    EXPECT_NE(rec["verdict"], "WRONGLY CLAIMED") << rec.dump();
    EXPECT_GT(rec["time_median"].get<double>(), 0.0);
    EXPECT_LE(rec["time_min"].get<double>(), rec["time_median"].get<double>());
    EXPECT_GE(rec["time_max"].get<double>(), rec["time_median"].get<double>());
    if (rec["problem"] == "tiny/infeasible-lcp") {
      EXPECT_EQ(rec["verdict"], "correctly refused") << rec.dump();
    }
    correct += rec["verdict"] == "solved" || rec["verdict"] == "correctly refused";
  }
  EXPECT_GE(correct, 13);  // lemke and enum get all five; psor at least three
  EXPECT_FALSE(j["suites"][0]["sweep"].empty());  // psor's tolerance sweep
  ASSERT_TRUE(j.contains("stepper"));
  EXPECT_FALSE(j["stepper"]["warm_start"].empty());
  EXPECT_FALSE(j["stepper"]["work_precision"].empty());

  const std::string csv = ReadText(dir / "results.csv");
  EXPECT_EQ(csv.rfind("suite,problem,solver,mode,size", 0), 0u);
  const std::string md = ReadText(dir / "report.md");
  EXPECT_THAT(md, HasSubstr("## Suite `tiny`"));
  EXPECT_THAT(md, HasSubstr("| lemke | 4 | 1 | 0 | 0 | 100% |"));
  EXPECT_THAT(md, HasSubstr("warm against cold"));

  // `report` on the same folder, with plots when gnuplot is there.
  if (GnuplotAvailable()) {
    const CliRun rep = RunSmcbench({"report", dir.string()});
    ASSERT_EQ(rep.code, 0) << rep.err;
    EXPECT_TRUE(fs::is_regular_file(dir / "profile-tiny.png"));
    EXPECT_TRUE(fs::is_regular_file(dir / "work-precision-galias-yu-2007.png"));
  }
  fs::remove_all(dir);
}

TEST(Report, PerfHistoryTableAndPlot) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-history-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path csv = dir / "history.csv";
  std::ofstream(csv) << "date,git_sha,id,unit,instructions,baseline_instructions,ratio,ns\n"
                        "2026-11-01T00:00:00Z,aaaaaaaaaa,solve/p/psor,solve,1000,1000,1,50\n"
                        "2026-11-01T00:00:00Z,aaaaaaaaaa,step/s2/enum,step,400,400,1,20\n"
                        "2026-11-02T00:00:00Z,bbbbbbbbbb,solve/p/psor,solve,1100,1000,1.1,55\n"
                        "2026-11-02T00:00:00Z,bbbbbbbbbb,step/s2/enum,step,300,400,0.75,-\n";
  const fs::path out = dir / "report";
  std::vector<std::string> args = {"report", "--history", csv.string(), out.string()};
  if (!GnuplotAvailable()) args.push_back("--no-plots");
  const CliRun r = RunSmcbench(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string md = ReadText(out / "history.md");
  EXPECT_THAT(md, HasSubstr("from the 2 runs"));
  EXPECT_THAT(md, HasSubstr("| solve/p/psor | 1000 | 1100 | 1.100 | 1000 | 1100 |"));
  EXPECT_THAT(md, HasSubstr("| step/s2/enum | 400 | 300 | 0.750 | 400 | 300 |"));
  EXPECT_THAT(md, HasSubstr("| aaaaaaaa | bbbbbbbb |"));
  if (GnuplotAvailable()) {
    EXPECT_GT(fs::file_size(out / "history.png"), 1000u);
  }

  // Without DIR the report goes next to the history; a malformed history is a one-line error.
  EXPECT_EQ(RunSmcbench({"report", "--history", csv.string(), "--no-plots"}).code, 0);
  EXPECT_TRUE(fs::is_regular_file(dir / "history.md"));
  std::ofstream(csv, std::ios::app) << "broken line\n";
  const CliRun bad = RunSmcbench({"report", "--history", csv.string(), "--no-plots"});
  EXPECT_EQ(bad.code, 1);
  EXPECT_THAT(bad.err, HasSubstr(":6: expected 8 fields"));
  const CliRun neither = RunSmcbench({"report"});
  EXPECT_EQ(neither.code, 1);
  EXPECT_THAT(neither.err, HasSubstr("give DIR"));
  fs::remove_all(dir);
}

TEST(Bench, BadInputIsAOneLineError) {
  CliRun r = RunSmcbench({"bench", "--suite", "nope", "--out", "/tmp/unused-bench"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("unknown suite 'nope'"));
  r = RunSmcbench({"bench", "--suite", "tiny", "--solver", "nope", "--out", "/tmp/unused-bench"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("unknown solver 'nope'"));
  r = RunSmcbench({"report", "/nonexistent/folder"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("cannot read"));
}

ReplayRecord Rec(const std::string& problem, const std::string& solver, Verdict v, double t, int size = 1) {
  ReplayRecord r;
  r.suite = "s";
  r.problem = problem;
  r.solver = solver;
  r.verdict = v;
  r.time_median = t;
  r.size = size;
  r.residual_rel = v == Verdict::kSolved ? 1e-12 : 1.0;
  return r;
}

TEST(Report, SummaryProfileAndExponentArithmetic) {
  SuiteResults s;
  s.suite = "s";
  s.replay.records = {Rec("p1", "a", Verdict::kSolved, 1e-6), Rec("p1", "b", Verdict::kSolved, 4e-6),
                      Rec("p2", "a", Verdict::kFailed, 1.0), Rec("p2", "b", Verdict::kSolved, 2e-6),
                      Rec("p3", "a", Verdict::kCorrectlyRefused, 1e-6), Rec("p3", "b", Verdict::kWronglyClaimed, 1e-6)};
  const auto summary = SummarizeSuite(s);
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(summary[0].solver, "a");
  EXPECT_EQ(summary[0].solved, 1);
  EXPECT_EQ(summary[0].failed, 1);
  EXPECT_EQ(summary[0].correctly_refused, 1);
  EXPECT_NEAR(summary[0].success_rate, 2.0 / 3.0, 1e-15);
  // a: times 1e-6, 10 × 2e-6 (its failure on p2 at 10× the slowest correct), 1e-6; shift 1e-6.
  const double expected_a = std::cbrt((2e-6) * (2e-5 + 1e-6) * (2e-6)) - 1e-6;
  EXPECT_NEAR(summary[0].shifted_geomean, expected_a, 1e-18);
  EXPECT_EQ(summary[1].wrongly_claimed, 1);
  // Dolan–Moré: best times p1 = 1e-6 (a), p2 = 2e-6 (b); p3 nobody solved → left out.
  const auto ratios = PerformanceRatios(s);
  ASSERT_EQ(ratios.size(), 2u);
  EXPECT_THAT(ratios[0].second, ::testing::ElementsAre(1.0, std::numeric_limits<double>::infinity()));
  EXPECT_THAT(ratios[1].second, ::testing::ElementsAre(1.0, 4.0));
  // Growth exponent: t = c m² exactly.
  SuiteResults scale;
  for (int m : {10, 100, 1000}) scale.replay.records.push_back(Rec("m" + std::to_string(m), "x", Verdict::kSolved, 1e-9 * m * m, m));
  EXPECT_NEAR(GrowthExponent(scale, "x"), 2.0, 1e-12);
}

}  // namespace
}  // namespace smcbench
