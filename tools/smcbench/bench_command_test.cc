// `smcbench bench` and `smcbench report` end to end on the tiny suite (what CI runs), and the report's arithmetic
// (success counts, shifted geometric mean, Dolan–Moré ratios, growth exponent) on handmade results.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <unistd.h>

#include "bench/figures/gnuplot_figure.h"
#include "bench/replay/jobs.h"
#include "bench/run/bench_plan.h"
#include "bench/run/run_shard.h"
#include "problems/library/problem_set_io.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/bench_command.h"
#include "bench/analysis/report_markdown.h"
#include "tools/smcbench/cli_test_runner.h"
#include "tools/smcbench/compare_command.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using test_support::CliRun;
using test_support::RunSmcbench;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(Bench, TinySuiteEndToEndWithReport) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-test-" + std::to_string(::getpid()));
  const CliRun r = RunSmcbench({"bench", "--suite", "tiny", "--quick", "--solver", "lemke", "--solver", "psor",
                                "--solver", "enum", "--stepper", "--out", dir.string(), "--report", "--no-plots"});
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
    EXPECT_NE(rec["verdict"], "INACCURATE") << rec.dump();
    EXPECT_NE(rec["verdict"], "WRONGLY REFUSED") << rec.dump();
    for (const char* key :
         {"residual_scaled", "forward_error", "forward_error_rel", "forward_allowance", "certificate"}) {
      EXPECT_TRUE(rec.contains(key)) << key;
    }
    EXPECT_EQ(rec["timed_in_worker"], false) << rec.dump();  // our backends run in this process
    // The four generated problems are P-matrix problems with a planted solution: bench attaches a certified
    // reference to each, so every solved answer has a forward error within its allowance.
    if (rec["problem"] != "tiny/infeasible-lcp") {
      EXPECT_TRUE(rec["certificate"] == "unique" || rec["certificate"] == "degenerate") << rec.dump();
      if (rec["verdict"] == "solved") {
        EXPECT_LE(rec["forward_error"].get<double>(), rec["forward_allowance"].get<double>()) << rec.dump();
      }
    }
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
  EXPECT_THAT(csv, HasSubstr(",residual_scaled,forward_error,forward_error_rel,forward_allowance,certificate,"
                             "timed_in_worker,host,concurrent_jobs,start,backend_code,reference_radius,reference_proved_unique\n"));
  const std::string md = ReadText(dir / "report.md");
  EXPECT_THAT(md, HasSubstr("## Suite `tiny`"));
  // solved, correctly refused, failed, wrongly claimed, inaccurate, wrongly refused, success.
  EXPECT_THAT(md, HasSubstr("| lemke | 4 | 1 | 0 | 0 | 0 | 0 | 100% |"));
  EXPECT_THAT(md, HasSubstr("recomputed by us from z"));  // the verdict, in words a reader can check
  EXPECT_THAT(md, HasSubstr("worst forward error"));
  EXPECT_THAT(md, HasSubstr("warm against cold"));

  // `report` on the same folder, with plots when gnuplot is there.
  if (GnuplotAvailable()) {
    const CliRun rep = RunSmcbench({"report", dir.string()});
    ASSERT_EQ(rep.code, 0) << rep.err;
    EXPECT_TRUE(fs::is_regular_file(dir / "profile-tiny.png"));
    EXPECT_TRUE(fs::is_regular_file(dir / "work-precision-galias-yu-2007.png"));
    // Every figure also as SVG, with its data and gnuplot script beside it, which remake it from there.
    for (const char* file : {"profile-tiny.svg", "profile-tiny.dat", "profile-tiny.gp",
                             "work-precision-galias-yu-2007.svg", "work-precision-galias-yu-2007.gp"}) {
      EXPECT_TRUE(fs::is_regular_file(dir / file)) << file;
    }
    const std::string script = ReadText(dir / "profile-tiny.gp");
    EXPECT_THAT(script, HasSubstr("'profile-tiny.dat' index 0"));
    EXPECT_THAT(script, HasSubstr("set output 'profile-tiny.svg'"));
    EXPECT_THAT(script, Not(HasSubstr(dir.string())));  // relocatable: no absolute path
    EXPECT_THAT(ReadText(dir / "profile-tiny.dat"), HasSubstr("# lemke\n1 0\n"));
    EXPECT_THAT(ReadText(dir / "report.md"), HasSubstr("([SVG](profile-tiny.svg), [data](profile-tiny.dat), "
                                                       "[gnuplot script](profile-tiny.gp))"));
    // Our three backends: solid lines, three different colours.
    std::set<std::string> colours;
    for (std::size_t at = script.find("lc rgb '"); at != std::string::npos; at = script.find("lc rgb '", at + 1)) {
      colours.insert(script.substr(at + 8, 7));
      EXPECT_EQ(script.substr(script.find(' ', at + 16) + 1, 4), "dt 1") << script.substr(at, 40);
    }
    EXPECT_EQ(colours.size(), 3u) << script;
    fs::remove(dir / "profile-tiny.svg");
    const std::string remake = "cd '" + dir.string() + "' && gnuplot profile-tiny.gp 2>/dev/null";
    EXPECT_EQ(std::system(remake.c_str()), 0);
    EXPECT_GT(fs::file_size(dir / "profile-tiny.svg"), 1000u);
  }
  fs::remove_all(dir);
}

// A suite file whose stored reference contradicts its data: M = [[2, 1], [1, 2]], q = (−1, −1) has the single
// solution z = (1/3, 1/3) (both rows free: 2a + b = 1, a + 2b = 1), but the file claims z* = (1, 0) is unique. A
// correct backend's answer is then 2/3 away from "z*": judged inaccurate, a wrong answer.
fs::path WriteContradictorySuite(const fs::path& dir) {
  DenseMatrix M(2, 2);
  M << 2.0, 1.0, 1.0, 2.0;
  Vector q(2);
  q << -1.0, -1.0;
  LibraryProblem p = MakeLibraryProblem("contradiction/spd2", "handmade", BoxMLCP::LCP(M, q, "spd2"));
  p.expected = ExpectedOutcome::kSolvable;
  p.reference.certificate = Certificate::kUnique;
  p.reference.z = Vector::Zero(2);
  p.reference.z[0] = 1.0;
  p.reference.condition = 1.0;
  ProblemSet set;
  set.name = "contradiction";
  set.description = "a stored reference that contradicts the data";
  set.problems.push_back(std::move(p));
  fs::create_directories(dir);
  const fs::path path = dir / "contradiction.smcps";
  WriteProblemSetFile(set, path.string());
  return path;
}

TEST(Bench, ExitsThreeOnAWrongAnswerUnlessTheBackendIsAllowed) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-wrong-" + std::to_string(::getpid()));
  const fs::path suite = WriteContradictorySuite(dir);
  const std::vector<std::string> base = {"bench", "--suite", suite.string(), "--solver", "lemke", "--quick",
                                         "--no-stepper", "--out", (dir / "out").string(), "--overwrite", "--report",
                                         "--no-plots"};
  const CliRun wrong = RunSmcbench(base);
  EXPECT_EQ(wrong.code, 3) << wrong.err;
  // The cold record and the 4 rungs of its tolerance ladder: a wrong answer at a loose tolerance is still wrong.
  EXPECT_THAT(wrong.err, HasSubstr("bench: 5 wrong answers (INACCURATE 5; lemke 5)"));
  // The results and the report are written before the exit status says so.
  const auto j = nlohmann::json::parse(ReadText(dir / "out" / "results.json"));
  const auto& rec = j["suites"][0]["records"][0];
  EXPECT_EQ(rec["verdict"], "INACCURATE") << rec.dump();
  EXPECT_NEAR(rec["forward_error"].get<double>(), 2.0 / 3.0, 1e-15);
  EXPECT_THAT(ReadText(dir / "out" / "report.md"), HasSubstr("| contradiction/spd2 | lemke | INACCURATE |"));

  std::vector<std::string> allowed = base;
  allowed.insert(allowed.end(), {"--allow-wrong", "siconos-*", "--allow-wrong", "lem*"});
  const CliRun excused = RunSmcbench(allowed);
  EXPECT_EQ(excused.code, 0) << excused.err;
  EXPECT_THAT(excused.err, HasSubstr("5 of them allowed by --allow-wrong"));  // still reported

  std::vector<std::string> other = base;
  other.insert(other.end(), {"--allow-wrong", "siconos-*"});
  EXPECT_EQ(RunSmcbench(other).code, 3);
  fs::remove_all(dir);
}

// The progress line's ETA: elapsed time scaled by the estimated work left over the estimated work done.
TEST(Bench, EtaScalesTheElapsedTimeByTheEstimatedWorkLeft) {
  EXPECT_EQ(FormatEta(10.0, 0.0, 5.0), "ETA ?");           // nothing estimated done yet
  EXPECT_EQ(FormatEta(10.0, 1.0, 5.0), "ETA 40s");         // 1 of 5 estimated seconds in 10 s: 4 left take 40 s
  EXPECT_EQ(FormatEta(30.0, 1.0, 4.0), "ETA 1m30s");
  EXPECT_EQ(FormatEta(600.0, 1.0, 7.5), "ETA 1h05m");
  EXPECT_EQ(FormatEta(12.0, 5.0, 5.0), "ETA 0s");          // all done
  EXPECT_EQ(FormatEta(12.0, 6.0, 5.0), "ETA 0s");          // never negative
}

TEST(Bench, GlobMatchesBackendNames) {
  EXPECT_TRUE(GlobMatch("siconos-*", "siconos-lcp-lemke"));
  EXPECT_TRUE(GlobMatch("siconos-*", "siconos-"));
  EXPECT_FALSE(GlobMatch("siconos-*", "lemke"));
  EXPECT_TRUE(GlobMatch("*lemke", "siconos-lcp-lemke"));
  EXPECT_TRUE(GlobMatch("*-lcp-*", "siconos-lcp-lemke"));
  EXPECT_TRUE(GlobMatch("ps?r", "psor"));
  EXPECT_FALSE(GlobMatch("ps?r", "pso"));
  EXPECT_TRUE(GlobMatch("enum", "enum"));
  EXPECT_FALSE(GlobMatch("enum", "enum2"));
  EXPECT_TRUE(GlobMatch("*", ""));
  EXPECT_TRUE(GlobMatch("a*b*c", "aXbYbZc"));
  EXPECT_FALSE(GlobMatch("a*b*c", "aXbYbZ"));
}

// Runs set (written to a problem-set file, as a user's suite is given) through the engine `bench` runs.
ReplayResults RunSet(const ProblemSet& set, BenchRequest request) {
  const fs::path file = fs::temp_directory_path() / ("smcbench-bench-set-" + std::to_string(::getpid()) + ".smcps");
  WriteProblemSetFile(set, file.string());
  request.suites = {file.string()};
  const BenchPlan plan = MakeBenchPlan(request);
  std::map<std::size_t, JobLine> lines;
  RunShard(plan, {}, {}, [&](const JobLine& line) { lines[line.job] = line; });
  fs::remove(file);
  return PlanResults(plan, lines).suites.at(0).replay;
}

// A siconos-* backend's untimed warm-up solve is its probe in the isolation worker: the timed solves then run in
// process (timed_in_worker false), unless isolate=always or the probe crashed, which is never run in process.
TEST(Bench, SiconosIsTimedInProcessAfterItsProbeUnlessItCrashed) {
  bool built_in = false;
  for (auto name : SolverNames()) built_in = built_in || name == "siconos-mlcp-lemke";
  if (!built_in) GTEST_SKIP() << "built without Siconos";
  ProblemSet set;
  set.name = "s";
  const BoxMLCP lcp = BoxMLCP::LCP(DenseMatrix::Identity(2, 2) * 2.0, Vector::Constant(2, -1.0));
  set.problems.push_back(MakeLibraryProblem("s/lcp", "handmade", lcp));
  BenchRequest request;
  request.solvers = {"siconos-lcp-lemke", "siconos-relay-lemke", "siconos-mlcp-lemke"};
  // relay-lemke does not apply to an LCP; mlcp_lcp_lemke aborts on an MLCP without equality rows.
  request.settings = {"siconos-mlcp-lemke.allow_known_crashes=1"};
  request.repetitions = 2;
  request.quick = true;
  ReplayResults results = RunSet(set, request);
  ASSERT_EQ(results.records.size(), 3u);
  EXPECT_EQ(results.records[0].status, SolveStatus::kSolved);
  EXPECT_FALSE(results.records[0].timed_in_worker);
  EXPECT_EQ(results.records[1].status, SolveStatus::kNotApplicable);  // no Siconos call at all
  EXPECT_FALSE(results.records[1].timed_in_worker);
  EXPECT_EQ(results.records[2].status, SolveStatus::kNumericalFailure) << results.records[2].message;
  EXPECT_TRUE(results.records[2].timed_in_worker);
  // isolate=always: every timed solve goes through the worker.
  request.settings = {"siconos-lcp-lemke.isolate=always"};
  request.solvers = {"siconos-lcp-lemke"};
  results = RunSet(set, request);
  ASSERT_EQ(results.records.size(), 1u);
  EXPECT_EQ(results.records[0].status, SolveStatus::kSolved);
  EXPECT_TRUE(results.records[0].timed_in_worker);
}

// results.json keeps every verdict and the numbers behind it; NaN (not defined) reads back as NaN.
TEST(Bench, ResultsJsonRoundTripsEveryVerdictAndTheNewNumbers) {
  BenchResults results;
  results.command = "test";
  SuiteResults suite;
  suite.suite = "s";
  suite.description = "d";
  for (Verdict v : {Verdict::kSolved, Verdict::kCorrectlyRefused, Verdict::kFailed, Verdict::kWronglyClaimed,
                    Verdict::kInaccurate, Verdict::kWronglyRefused}) {
    ReplayRecord r;
    r.suite = "s";
    r.problem = "p" + std::to_string(static_cast<int>(v));
    r.solver = "x";
    r.verdict = v;
    r.residual_scaled = 0.1 + static_cast<int>(v);  // not exactly representable: a round trip must keep all bits
    r.forward_error = v == Verdict::kFailed ? kNaN : 1.0 / 3.0;
    r.forward_error_rel = r.forward_error / 7.0;
    r.forward_allowance = 2e-9;
    r.certificate = v == Verdict::kFailed ? "none found" : "unique";
    r.timed_in_worker = v == Verdict::kInaccurate;
    suite.replay.records.push_back(r);
  }
  results.suites.push_back(suite);
  const BenchResults back = BenchResultsFromJson(nlohmann::json::parse(ToJson(results, {}).dump()));
  ASSERT_EQ(back.suites.size(), 1u);
  ASSERT_EQ(back.suites[0].replay.records.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    const ReplayRecord& a = suite.replay.records[i];
    const ReplayRecord& b = back.suites[0].replay.records[i];
    EXPECT_EQ(b.verdict, a.verdict);
    EXPECT_EQ(b.residual_scaled, a.residual_scaled);
    EXPECT_EQ(std::isnan(b.forward_error), std::isnan(a.forward_error));
    if (!std::isnan(a.forward_error)) {
      EXPECT_EQ(b.forward_error, a.forward_error);
      EXPECT_EQ(b.forward_error_rel, a.forward_error_rel);
    }
    EXPECT_EQ(b.forward_allowance, a.forward_allowance);
    EXPECT_EQ(b.certificate, a.certificate);
    EXPECT_EQ(b.timed_in_worker, a.timed_in_worker);
  }
  // A results.json from before these fields still reads: the new numbers are NaN, the certificate "none".
  auto old = ToJson(results, {});
  for (auto& rec : old["suites"][0]["records"]) {
    for (const char* key :
         {"residual_scaled", "forward_error", "forward_error_rel", "forward_allowance", "certificate"}) {
      rec.erase(key);
    }
  }
  const BenchResults older = BenchResultsFromJson(old);
  EXPECT_TRUE(std::isnan(older.suites[0].replay.records[0].residual_scaled));
  EXPECT_EQ(older.suites[0].replay.records[0].certificate, "none");
  // Without timed_in_worker (before Siconos was timed in process after its probe), a siconos-* record was timed
  // through its isolation worker, any other in this process.
  auto before_probe = ToJson(results, {});
  before_probe["suites"][0]["records"][1]["solver"] = "siconos-lcp-lemke";
  for (auto& rec : before_probe["suites"][0]["records"]) rec.erase("timed_in_worker");
  const BenchResults before = BenchResultsFromJson(before_probe);
  EXPECT_FALSE(before.suites[0].replay.records[0].timed_in_worker);
  EXPECT_TRUE(before.suites[0].replay.records[1].timed_in_worker);
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

// Names and options are checked before any suite is built or any folder made, so a typo costs a second.
TEST(Bench, ChecksSuitesAndOptionsBeforeAnyWork) {
  const fs::path out = fs::temp_directory_path() / ("smcbench-bench-early-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto start = std::chrono::steady_clock::now();
  // The paper suite comes first and is slow to capture: the unknown second suite must fail before it.
  CliRun r = RunSmcbench({"bench", "--suite", "paper", "--suite", "papr", "--out", out.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("unknown suite 'papr'"));
  r = RunSmcbench({"bench", "--suite", "paper", "--set", "psor.omega=abc", "--out", out.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--set psor.omega=abc"));
  r = RunSmcbench({"bench", "--suite", "paper", "--set", "psor-omega", "--out", out.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("BACKEND.OPTION=VALUE"));
  r = RunSmcbench({"bench", "--suite", "siconos", "--siconos-dir", "/nonexistent", "--out", out.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--siconos-dir '/nonexistent' is not a folder"));
  // Numbers are checked as the flags are parsed (exit status 2, as every command's), naming flag and value.
  for (const std::vector<std::string>& flag : std::vector<std::vector<std::string>>{
           {"--time-limit", "-1"}, {"--time-limit", "nan"}, {"--repetitions", "0"}, {"--backend-budget", "-1"},
           {"--tol", "0"}, {"--repetitions", "2.5"}}) {
    r = RunSmcbench({"bench", "--suite", "paper", flag[0], flag[1], "--out", out.string()});
    EXPECT_EQ(r.code, 2) << flag[0] << " " << flag[1];
    EXPECT_THAT(r.err, HasSubstr(flag[0])) << r.err;
    EXPECT_THAT(r.err, HasSubstr("'" + flag[1] + "'")) << r.err;
  }
  r = RunSmcbench({"bench", "--suite", "paper", "--stepper", "--no-stepper", "--out", out.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--stepper or --no-stepper"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_FALSE(fs::exists(out)) << "no folder is made for a request that fails its checks";
}

// A problem-set file that cannot be read, or holds no problem, fails before the output folder exists.
TEST(Bench, AnUnreadableOrEmptySuiteFileLeavesNoFolder) {
  const fs::path scratch = fs::temp_directory_path() / ("smcbench-bench-empty-" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  const fs::path empty = scratch / "empty.smcps", garbage = scratch / "garbage.smcps", out = scratch / "b1";
  std::ofstream(empty).close();
  std::ofstream(garbage) << "not a problem set\n";
  for (const fs::path& file : {empty, garbage}) {
    const CliRun r = RunSmcbench({"bench", "--suite", file.string(), "--no-stepper", "--solver", "lemke", "--out",
                                  out.string()});
    EXPECT_EQ(r.code, 1) << file;
    EXPECT_THAT(r.err, HasSubstr(file.filename().string())) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "bench made " << out << " for " << file;
  }
  fs::remove_all(scratch);
}

// The time-stepper studies run the paper's scenes, so a run of other suites (a user's problem-set file)
// has none unless --stepper asks for them.
TEST(Bench, StepperStudiesOnlyForSceneSuitesOrWhenAsked) {
  const fs::path scratch = fs::temp_directory_path() / ("smcbench-bench-stepper-" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  const fs::path suite = scratch / "mine.smcps";
  WriteProblemSetFile(TinySuite(), suite.string());
  CliRun r = RunSmcbench({"bench", "--suite", suite.string(), "--solver", "lemke", "--list-jobs"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, Not(HasSubstr("stepper")));
  r = RunSmcbench({"bench", "--suite", suite.string(), "--solver", "lemke", "--list-jobs", "--stepper"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\tstepper\tstepper\n# ")) << "the last job: " << r.out;
  // A run of the file: no stepper section in results.json, and the manifest says so.
  const fs::path out = scratch / "run";
  r = RunSmcbench({"bench", "--suite", suite.string(), "--solver", "lemke", "--quick", "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, Not(HasSubstr("time-stepper")));
  EXPECT_FALSE(ReadBenchResults(out.string()).has_stepper);
  EXPECT_EQ(nlohmann::json::parse(ReadText(out / "manifest.json"))["options"]["stepper"], false);
  fs::remove_all(scratch);
}

// Runs `bench` on the tiny suite (4 planted-solution P-matrix problems and one infeasible LCP) into dir.
CliRun BenchTiny(const fs::path& dir, std::vector<std::string> extra) {
  std::vector<std::string> args{"bench", "--suite", "tiny", "--quick", "--no-stepper", "--solver", "lemke",
                                "--solver", "enum", "--out", dir.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return RunSmcbench(args);
}

TEST(Bench, EndsWithASummaryTableAndKeepsEarlierResults) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-table-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  CliRun r = BenchTiny(dir, {});
  ASSERT_EQ(r.code, 0) << r.err;
  // Both exact backends solve the four P-matrix problems and refuse the infeasible LCP (TinySuite's construction).
  EXPECT_THAT(r.out, HasSubstr("| suite | backend | problems | solved | refused | failed | wrongly claimed | "
                               "inaccurate | wrongly refused | SGM time |"));
  EXPECT_THAT(r.out, HasSubstr("| tiny | lemke | 5 | 4 | 1 | 0 | 0 | 0 | 0 | "));
  EXPECT_THAT(r.out, HasSubstr("| tiny | enum | 5 | 4 | 1 | 0 | 0 | 0 | 0 | "));
  const auto results = nlohmann::json::parse(ReadText(dir / "results.json"));
  // Only our backends ran: no Siconos version is claimed.
  EXPECT_FALSE(results["environment"]["libraries"].contains("siconos_numerics"));

  r = BenchTiny(dir, {});  // the same folder again: refused, the earlier results kept
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("already holds results.json"));
  EXPECT_THAT(r.err, HasSubstr("--overwrite"));
  EXPECT_EQ(nlohmann::json::parse(ReadText(dir / "results.json"))["environment"]["date"],
            results["environment"]["date"]);
  r = BenchTiny(dir, {"--overwrite"});
  EXPECT_EQ(r.code, 0) << r.err;
  fs::remove_all(dir);
}

TEST(Bench, WithoutOutWritesAFreshFolder) {
  const fs::path cwd = fs::current_path();
  const fs::path scratch = fs::temp_directory_path() / ("smcbench-bench-default-" + std::to_string(::getpid()));
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  fs::current_path(scratch);
  const CliRun a = RunSmcbench({"bench", "--suite", "tiny", "--quick", "--no-stepper", "--solver", "lemke"});
  const CliRun b = RunSmcbench({"bench", "--suite", "tiny", "--quick", "--no-stepper", "--solver", "lemke"});
  fs::current_path(cwd);
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  std::vector<std::string> folders;
  for (const auto& entry : fs::directory_iterator(scratch)) {
    folders.push_back(entry.path().filename().string());
    EXPECT_TRUE(fs::exists(entry.path() / "results.json")) << entry.path();
  }
  ASSERT_EQ(folders.size(), 2u) << "two runs, two folders";
  for (const std::string& name : folders) {
    EXPECT_EQ(name.rfind("smcbench-bench-", 0), 0u) << name;
    EXPECT_THAT(a.out + b.out, HasSubstr(name + "/results.json"));
  }
  fs::remove_all(scratch);
}

// A backend past its per-suite budget is not run on the suite's remaining problems: they are recorded as time
// limit with a message, and one line on stderr says so. Progress lines appear when stderr is not a terminal.
TEST(Bench, BackendBudgetSkipsTheRestAndProgressLinesAreWritten) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-budget-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const CliRun r = BenchTiny(dir, {"--backend-budget", "1e-9", "--progress-every", "1e-9"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("bench: lemke skipped 4 of 5 problems of suite tiny after spending its budget"));
  EXPECT_THAT(r.err, HasSubstr("bench: enum skipped 4 of 5 problems"));
  EXPECT_THAT(r.err, HasSubstr("bench: 1/31 (3%) after "));  // 10 cold jobs, 5 floor jobs, 16 of the ladder
  // Skipped jobs are cut: no verdict, in no column of the summary, counted on a line of their own.
  EXPECT_THAT(r.out, HasSubstr("| tiny | lemke | 1 | 1 | 0 | 0 | 0 | 0 | 0 | "));
  EXPECT_THAT(r.out, HasSubstr("8 jobs cut by a time budget"));
  const auto j = nlohmann::json::parse(ReadText(dir / "results.json"));
  const auto& records = j["suites"][0]["records"];
  ASSERT_EQ(records.size(), 10u);
  int skipped = 0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    // The job list's order: problem by problem, lemke then enum.
    EXPECT_EQ(records[k]["solver"], k % 2 == 0 ? "lemke" : "enum") << k;
    if (records[k]["message"].get<std::string>().find("not run: ") == 0) {
      ++skipped;
      EXPECT_EQ(records[k]["status"], "not_run") << records[k].dump();
      EXPECT_EQ(records[k]["mode"], "cut") << records[k].dump();
      EXPECT_EQ(records[k]["samples"], 0);
    }
  }
  EXPECT_EQ(skipped, 8);
  EXPECT_EQ(records[0]["problem"], records[1]["problem"]);
  EXPECT_EQ(records[0]["status"], "solved");  // the first problem ran before the budget was spent
  fs::remove_all(dir);
}

// With Siconos in the build, results.json names the version its backends came from (the Debian package's).
TEST(Bench, RecordsTheSiconosVersionWhenItsBackendsRan) {
  std::string siconos;
  for (auto name : SolverNames()) {
    if (std::string(name).rfind("siconos-lcp-", 0) == 0 && siconos.empty()) siconos = std::string(name);
  }
  if (siconos.empty()) GTEST_SKIP() << "this build has no siconos-* backends";
  std::string package;
  if (FILE* pipe = ::popen("dpkg-query -W -f='${Version}' libsiconos-numerics-dev 2>/dev/null", "r")) {
    char buffer[128] = {};
    if (std::fgets(buffer, sizeof buffer, pipe)) package = buffer;
    ::pclose(pipe);
  }
  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-siconos-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const CliRun r = RunSmcbench({"bench", "--suite", "tiny", "--quick", "--no-stepper", "--solver", siconos, "--out",
                                dir.string(), "--allow-wrong", "siconos-*"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(ReadText(dir / "results.json"));
  ASSERT_TRUE(j["environment"]["libraries"].contains("siconos_numerics")) << j["environment"].dump();
  const std::string version = j["environment"]["libraries"]["siconos_numerics"];
  EXPECT_FALSE(version.empty());
  if (!package.empty()) {
    EXPECT_EQ(package.rfind(version, 0), 0u) << package << " vs " << version;
  }
  fs::remove_all(dir);
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
  // Residuals and forward errors: the worst is taken over the solved records only, the forward error only where
  // defined (p2 has no reference).
  s.replay.records[0].residual_scaled = 3e-12;
  s.replay.records[0].forward_error = 5e-13;
  s.replay.records[1].residual_scaled = 4e-11;
  s.replay.records[1].forward_error = 1e-14;
  s.replay.records[3].residual_scaled = 2e-11;
  s.replay.records[5].residual_scaled = 1.0;  // wrongly claimed: not in the worst of the solved
  s.replay.records[5].forward_error = 0.5;
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
  EXPECT_EQ(summary[1].wrong(), 1);
  EXPECT_EQ(summary[0].wrong(), 0);
  EXPECT_EQ(summary[0].worst_residual_scaled, 3e-12);
  EXPECT_EQ(summary[0].worst_forward_error, 5e-13);
  EXPECT_EQ(summary[1].worst_residual_scaled, 4e-11);
  EXPECT_EQ(summary[1].worst_forward_error, 1e-14);
  EXPECT_EQ(summary[1].forward_error_defined, 1);
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

// The headline "our best against Siconos' best" compares in-process times; Siconos records timed through the
// isolation worker (timed_in_worker) are a labelled footnote, never mixed into it.
TEST(Report, SiconosHeadlineIsInProcessAndWorkerTimesAreAFootnote) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-report-siconos-" + std::to_string(::getpid()));
  BenchResults results;
  results.command = "test";
  SuiteResults suite;
  suite.suite = "paper";
  suite.description = "d";
  suite.replay.records = {Rec("p1", "enum", Verdict::kSolved, 100e-9),
                          Rec("p1", "siconos-lcp-lemke", Verdict::kSolved, 250e-9),
                          Rec("p1", "siconos-relay-lemke", Verdict::kSolved, 7300e-9),
                          Rec("p2", "enum", Verdict::kSolved, 200e-9),
                          Rec("p2", "siconos-lcp-lemke", Verdict::kSolved, 300e-9)};
  suite.replay.records[2].timed_in_worker = true;  // e.g. isolate=always: 7 µs of IPC in its time
  results.suites.push_back(suite);
  WriteBenchResults(results, dir.string());
  const std::string md = WriteBenchReport(dir.string(), /*plots=*/false);
  EXPECT_THAT(md, HasSubstr("both timed in process"));
  // In process: p1 250/100 = 2.5, p2 300/200 = 1.5 (the worker-timed 7.3 µs is not Siconos' best of p1).
  EXPECT_THAT(md, HasSubstr("| 1 | 2 | 2.5× | 1.5× | 2.5× |"));
  EXPECT_THAT(md, HasSubstr("Footnote: Siconos records timed through the isolation worker"));
  EXPECT_THAT(md, HasSubstr("| 1 | 1 | 73× | 73× | 73× |"));
  fs::remove_all(dir);
}

// The two new wrong verdicts are counted in their own columns and in wrong(), never as solved.
TEST(Report, InaccurateAndWronglyRefusedAreCountedAsWrong) {
  SuiteResults s;
  s.suite = "s";
  s.replay.records = {Rec("p1", "a", Verdict::kInaccurate, 1e-6), Rec("p2", "a", Verdict::kWronglyRefused, 1e-6),
                      Rec("p3", "a", Verdict::kSolved, 1e-6)};
  s.replay.records[0].forward_error = 0.25;
  const auto summary = SummarizeSuite(s);
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary[0].inaccurate, 1);
  EXPECT_EQ(summary[0].wrongly_refused, 1);
  EXPECT_EQ(summary[0].solved, 1);
  EXPECT_EQ(summary[0].wrong(), 2);
  EXPECT_NEAR(summary[0].success_rate, 1.0 / 3.0, 1e-15);
  EXPECT_TRUE(std::isnan(summary[0].worst_forward_error));  // the inaccurate one is not a solved answer
}


// ------------------------------------------------------------------------------------------------------------
// Sharded runs, merge, resume, frozen suites.

// A record of results.json without what depends on the clock or the machine (times, sample counts, host, how many
// jobs shared it): what a sharded run must reproduce exactly.
nlohmann::json WithoutTimes(nlohmann::json record) {
  for (const char* key : {"time_median", "time_min", "time_max", "time_mad", "samples", "solves_per_sample", "host",
                          "concurrent_jobs"}) {
    record.erase(key);
  }
  return record;
}

// Every suite's records and sweep of a results.json, without times, in file order.
std::vector<nlohmann::json> TimelessRecords(const fs::path& dir) {
  const auto j = nlohmann::json::parse(ReadText(dir / "results.json"));
  std::vector<nlohmann::json> out;
  for (const auto& suite : j["suites"]) {
    out.push_back({{"suite", suite["suite"]}, {"problems", suite["problems"]}, {"checksum", suite["checksum"]}});
    for (const char* part : {"records", "sweep"}) {
      for (const auto& r : suite[part]) out.push_back(WithoutTimes(r));
    }
  }
  return out;
}

// lemke, psor and enum (each gets the tolerance sweep), tiny suite, no stepper study.
std::vector<std::string> ShardArgs(const std::vector<std::string>& extra) {
  std::vector<std::string> args{"bench", "--suite", "tiny", "--quick", "--no-stepper", "--solver", "lemke",
                                "--solver", "psor", "--solver", "enum"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(Shards, ThreeShardsMergedEqualTheSingleRunAndAKilledShardResumes) {
  const fs::path root = fs::temp_directory_path() / ("smcbench-shards-" + std::to_string(::getpid()));
  fs::remove_all(root);
  CliRun single = RunSmcbench(ShardArgs({"--out", (root / "single").string()}));
  ASSERT_EQ(single.code, 0) << single.err;

  // --list-jobs: 5 problems × 3 backends cold + 5 floor jobs + 2 problems × 3 backends × 4 tolerances = 44 jobs,
  // each in one shard.
  const CliRun listed = RunSmcbench(ShardArgs({"--list-jobs"}));
  ASSERT_EQ(listed.code, 0) << listed.err;
  EXPECT_THAT(listed.out, HasSubstr("# 44 of 44 jobs"));
  std::set<std::string> in_shards;
  std::size_t listed_in_shards = 0;
  for (int k = 1; k <= 3; ++k) {
    const std::string shard = std::to_string(k) + "/3";
    const CliRun part = RunSmcbench(ShardArgs({"--list-jobs", "--shard", shard}));
    ASSERT_EQ(part.code, 0) << part.err;
    for (const std::string& line : Lines(part.out)) {
      if (line.empty() || line[0] == '#') continue;
      EXPECT_THAT(line, HasSubstr("\t" + shard + "\t"));
      in_shards.insert(line.substr(line.rfind('\t') + 1));
      ++listed_in_shards;
    }
    // The shards are the same in every process; the estimated seconds are this machine's measured costs, so they
    // are left out of the comparison.
    const auto jobs_of = [](const std::string& listing) {
      std::vector<std::string> jobs;
      for (const std::string& line : Lines(listing)) {
        if (line.empty() || line[0] == '#') continue;
        const auto shard_end = line.find('\t', line.find('\t') + 1);
        jobs.push_back(line.substr(0, shard_end) + line.substr(line.find('\t', shard_end + 1)));
      }
      return jobs;
    };
    EXPECT_EQ(jobs_of(RunSmcbench(ShardArgs({"--list-jobs", "--shard", shard})).out), jobs_of(part.out))
        << "deterministic";
  }
  EXPECT_EQ(listed_in_shards, 44u);
  EXPECT_EQ(in_shards.size(), 44u) << "every job in exactly one shard";

  std::vector<std::string> dirs;
  for (int k = 1; k <= 3; ++k) {
    dirs.push_back((root / ("shard-" + std::to_string(k))).string());
    const CliRun r = RunSmcbench(ShardArgs({"--shard", std::to_string(k) + "/3", "--out", dirs.back()}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::is_regular_file(fs::path(dirs.back()) / "records.jsonl"));
  }
  std::vector<std::string> merge{"merge", (root / "merged").string()};
  merge.insert(merge.end(), dirs.begin(), dirs.end());
  CliRun merged = RunSmcbench(merge);
  ASSERT_EQ(merged.code, 0) << merged.err;
  EXPECT_EQ(merged.err, "");  // nothing missing, nothing duplicated
  const std::vector<nlohmann::json> expected = TimelessRecords(root / "single");
  ASSERT_EQ(expected.size(), 1u + 15u + 24u);
  EXPECT_EQ(TimelessRecords(root / "merged"), expected);
  const CliRun report = RunSmcbench({"report", (root / "merged").string(), "--no-plots"});
  EXPECT_EQ(report.code, 0) << report.err;

  // Shard 2 killed half-way: half its lines kept, the next one cut in the middle, no results.json. Resumed, it
  // runs only the missing jobs, and the merge is the same.
  const fs::path killed = fs::path(dirs[1]) / "records.jsonl";
  const std::vector<std::string> lines = Lines(ReadText(killed));
  ASSERT_GE(lines.size(), 4u);
  const std::size_t kept = lines.size() / 2;
  {
    std::ofstream cut(killed, std::ios::trunc);
    for (std::size_t i = 0; i < kept; ++i) cut << lines[i] << "\n";
    cut << lines[kept].substr(0, lines[kept].size() / 2);
  }
  fs::remove(fs::path(dirs[1]) / "results.json");
  const CliRun resumed = RunSmcbench(ShardArgs({"--shard", "2/3", "--resume", dirs[1]}));
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr("resuming " + dirs[1] + ": " + std::to_string(kept) + " jobs done, " +
                                     std::to_string(lines.size() - kept) + " to run"));
  EXPECT_EQ(Lines(ReadText(killed)).size(), lines.size());
  merge[1] = (root / "merged-after-resume").string();
  merged = RunSmcbench(merge);
  ASSERT_EQ(merged.code, 0) << merged.err;
  EXPECT_EQ(TimelessRecords(root / "merged-after-resume"), expected);

  // Resuming with other options is refused (the folder's run is another).
  const CliRun other = RunSmcbench({"bench", "--suite", "tiny", "--quick", "--no-stepper", "--solver", "lemke",
                                    "--shard", "2/3", "--resume", dirs[1]});
  EXPECT_EQ(other.code, 1);
  EXPECT_THAT(other.err, HasSubstr("not the same run: other options (options.solvers"));

  // A shard missing: listed, refused (exit 2) unless --partial.
  const CliRun missing = RunSmcbench({"merge", (root / "two").string(), dirs[0], dirs[2]});
  EXPECT_EQ(missing.code, 2);
  EXPECT_THAT(missing.err, HasSubstr("jobs missing: "));
  // The same folder twice: its jobs are listed as duplicated, the first kept.
  const CliRun twice = RunSmcbench({"merge", (root / "twice").string(), dirs[0], dirs[1], dirs[2], dirs[2]});
  EXPECT_EQ(twice.code, 0) << twice.err;
  EXPECT_THAT(twice.err, HasSubstr("jobs finished more than once (the first kept): "));
  EXPECT_EQ(TimelessRecords(root / "twice"), expected);
  fs::remove_all(root);
}

// Every number of results.csv reads back to the double results.json holds.
TEST(Shards, ResultsCsvNumbersRoundTrip) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-csv-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  ASSERT_EQ(RunSmcbench(ShardArgs({"--out", dir.string()})).code, 0);
  const auto j = nlohmann::json::parse(ReadText(dir / "results.json"));
  std::vector<nlohmann::json> records;
  for (const char* part : {"records", "sweep"}) {
    for (const auto& r : j["suites"][0][part]) records.push_back(r);
  }
  const std::vector<std::string> rows = Lines(ReadText(dir / "results.csv"));
  ASSERT_EQ(rows.size(), records.size() + 1);
  std::vector<std::string> header;
  {
    std::istringstream in(rows[0]);
    for (std::string cell; std::getline(in, cell, ',');) header.push_back(cell);
  }
  int compared = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    std::vector<std::string> cells;
    std::istringstream in(rows[i + 1]);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    if (!rows[i + 1].empty() && rows[i + 1].back() == ',') cells.emplace_back();  // an empty last field (start)
    ASSERT_EQ(cells.size(), header.size()) << rows[i + 1];
    for (std::size_t c = 0; c < header.size(); ++c) {
      const auto& value = records[i][header[c]];
      if (!value.is_number_float()) continue;
      const double read = std::strtod(cells[c].c_str(), nullptr);
      EXPECT_EQ(read, value.get<double>()) << header[c] << " " << cells[c];
      ++compared;
    }
  }
  EXPECT_GT(compared, 100);
  fs::remove_all(dir);
}

// merge's OUT naming a file: refused before a shard is read (exit 1, OUT named), nothing written.
TEST(Shards, MergeRefusesAFileAsOutBeforeReadingTheShards) {
  const fs::path file = fs::temp_directory_path() / ("smcbench-merge-out-" + std::to_string(::getpid()) + ".txt");
  std::ofstream(file) << "x\n";
  const CliRun r = RunSmcbench({"merge", file.string(), "/nonexistent/shard"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("OUT: '" + file.string() + "' is a file; a folder is expected here"));
  EXPECT_EQ(ReadText(file), "x\n");
  fs::remove(file);
}

// Frozen inputs: a suite written by `library --write-suite` runs with the built-in suite's checksum; shards of
// different problems, or of another build, are not merged (one line, exit status 2).
TEST(Shards, FrozenSuitesKeepTheirChecksumAndMergeRefusesOtherSuitesOrBuilds) {
  const fs::path root = fs::temp_directory_path() / ("smcbench-frozen-" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  const std::string frozen = (root / "tiny.smcps").string();
  const CliRun written = RunSmcbench({"library", "--write-suite", "tiny", frozen});
  ASSERT_EQ(written.code, 0) << written.err;
  ASSERT_THAT(written.out, HasSubstr("wrote suite tiny (5 problems, checksum "));
  const std::string checksum = written.out.substr(written.out.find("checksum ") + 9, 16);

  const std::vector<std::string> run{"bench", "--quick", "--no-stepper", "--solver", "lemke", "--shard", "1/2"};
  const auto bench = [&](const std::string& suite, const std::string& dir) {
    std::vector<std::string> args = run;
    args.insert(args.end(), {"--suite", suite, "--out", (root / dir).string()});
    return RunSmcbench(args);
  };
  ASSERT_EQ(bench("tiny", "built").code, 0);
  ASSERT_EQ(bench(frozen, "frozen").code, 0);
  for (const char* dir : {"built", "frozen"}) {
    const auto j = nlohmann::json::parse(ReadText(root / dir / "results.json"));
    EXPECT_EQ(j["suites"][0]["checksum"], checksum) << dir;
    EXPECT_FALSE(j["environment"]["build_revision"].get<std::string>().empty());
  }

  // The same suite with one number changed: another checksum, and merge refuses it.
  ProblemSet changed = ReadProblemSetFile(frozen);
  Vector q = changed.problems[0].problem.q();
  q[0] += 1e-3;
  const BoxMLCP& p = changed.problems[0].problem;
  LibraryProblem edited = MakeLibraryProblem(changed.problems[0].id, changed.problems[0].source,
                                             BoxMLCP(p.dense_matrix(), q, p.l(), p.u()));
  edited.expected = changed.problems[0].expected;
  changed.problems[0] = std::move(edited);
  const std::string other = (root / "tiny-changed.smcps").string();
  WriteProblemSetFile(changed, other);
  ASSERT_EQ(bench(other, "changed").code, 0);
  const CliRun suites = RunSmcbench({"merge", (root / "m1").string(), (root / "built").string(),
                                     (root / "changed").string()});
  EXPECT_EQ(suites.code, 2);
  EXPECT_THAT(suites.err, HasSubstr("other problems in suite tiny (checksum " + checksum + " vs "));
  EXPECT_EQ(Lines(suites.err).size(), 1u) << suites.err;
  EXPECT_FALSE(fs::exists(root / "m1" / "results.json"));

  // Another build: the same shard with the build revision of its manifest changed.
  fs::copy(root / "frozen", root / "rebuilt");
  auto manifest = nlohmann::json::parse(ReadText(root / "rebuilt" / "manifest.json"));
  manifest["environment"]["build_revision"] = "0123456789ab";
  std::ofstream(root / "rebuilt" / "manifest.json") << manifest.dump(1);
  const CliRun builds = RunSmcbench({"merge", (root / "m2").string(), (root / "built").string(),
                                     (root / "rebuilt").string()});
  EXPECT_EQ(builds.code, 2);
  EXPECT_THAT(builds.err, HasSubstr("another build (build.build_revision: "));
  EXPECT_THAT(builds.err, HasSubstr("vs '\"0123456789ab\"'"));
  EXPECT_EQ(Lines(builds.err).size(), 1u) << builds.err;
  fs::remove_all(root);
}

// Shards: each job in exactly one, the same every time, and balanced: no shard's estimated work exceeds another's
// by more than the largest job (the greedy bound), checked on 200 jobs of uneven cost.
TEST(Shards, AssignmentIsDeterministicCompleteAndBalanced) {
  std::vector<BenchJob> jobs(200);
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    jobs[i].index = i;
    jobs[i].id = "suite|p" + std::to_string(i) + "|lemke|cold|1e-10";
    jobs[i].cost = 1e-3 * static_cast<double>((i * 7919) % 97 + 1);
  }
  for (int shards : {1, 3, 7}) {
    const std::vector<int> a = AssignShards(jobs, shards);
    EXPECT_EQ(AssignShards(jobs, shards), a);
    std::vector<double> load(shards, 0.0);
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      ASSERT_GE(a[i], 0);
      ASSERT_LT(a[i], shards);
      load[a[i]] += jobs[i].cost;
    }
    EXPECT_LE(*std::max_element(load.begin(), load.end()) - *std::min_element(load.begin(), load.end()), 0.097 + 1e-12);
  }
  EXPECT_EQ(ParseShard("2/3"), (std::pair<int, int>{1, 3}));
  for (const char* bad : {"0/3", "4/3", "3", "1/0", "a/b", "1/3x"}) {
    EXPECT_THROW(ParseShard(bad), InvalidInputError) << bad;
  }
  const CliRun r = RunSmcbench({"bench", "--suite", "tiny", "--shard", "4/3"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--shard expects K/N with 1 <= K <= N, got '4/3'"));
}

TEST(Report, WarnsWhenComparedTimesComeFromSharedHosts) {
  BenchResults results;
  SuiteResults s;
  s.suite = "s";
  for (int i = 0; i < 2; ++i) {
    ReplayRecord r = Rec("p", i ? "enum" : "lemke", Verdict::kSolved, 1e-6);
    r.samples = 3;
    r.host = "node1";
    r.concurrent_jobs = 1;
    s.replay.records.push_back(r);
  }
  results.suites.push_back(s);
  EXPECT_EQ(SharedHostWarning(results), "");
  results.suites[0].replay.records[1].concurrent_jobs = 2;
  EXPECT_THAT(SharedHostWarning(results), HasSubstr("1 of 2 timed records were measured while other"));
  results.suites[0].replay.records[1].concurrent_jobs = 1;
  results.suites[0].replay.records[1].host = "node2";
  EXPECT_THAT(SharedHostWarning(results), HasSubstr("The times come from 2 hosts"));
}

// An MCP suite's records are problem × start: a backend's failure on one start of a problem is penalized at 10×
// the slowest correct time on that same start, and the profile compares times per start.
TEST(Report, McpSuiteIsSummarizedPerProblemAndStart) {
  SuiteResults s;
  s.suite = "mcp";
  const auto at = [](ReplayRecord r, const std::string& start) {
    r.start = start;
    return r;
  };
  s.replay.records = {at(Rec("p", "a", Verdict::kSolved, 1e-6), "s1"), at(Rec("p", "b", Verdict::kSolved, 2e-6), "s1"),
                      at(Rec("p", "a", Verdict::kFailed, 1.0), "s2"), at(Rec("p", "b", Verdict::kSolved, 5e-6), "s2")};
  EXPECT_TRUE(IsMcpSuite(s));
  const auto summary = SummarizeSuite(s);
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(summary[0].problems, 2);
  EXPECT_EQ(summary[0].solved, 1);
  EXPECT_EQ(summary[0].failed, 1);
  // a: 1e-6 on s1, and on s2 10 × b's 5e-6 (not b's 2e-6 of the other start); shift 1e-6.
  EXPECT_NEAR(summary[0].shifted_geomean, std::sqrt(2e-6 * 51e-6) - 1e-6, 1e-18);
  EXPECT_NEAR(summary[1].shifted_geomean, std::sqrt(3e-6 * 6e-6) - 1e-6, 1e-18);
  const auto ratios = PerformanceRatios(s);
  EXPECT_THAT(ratios[0].second, ::testing::ElementsAre(1.0, std::numeric_limits<double>::infinity()));
  EXPECT_THAT(ratios[1].second, ::testing::ElementsAre(1.0, 2.0));  // s2: b is the best; s1: 2e-6 / 1e-6
  SuiteResults box = s;
  for (auto& r : box.replay.records) r.start.clear();
  EXPECT_FALSE(IsMcpSuite(box));
  // A recorded kind decides, whatever the records or the name: the AVI and MCP sections by kind alone.
  box.kind = "mcp";
  EXPECT_TRUE(IsMcpSuite(box));
  s.kind = "box";
  EXPECT_FALSE(IsMcpSuite(s));
  s.suite = "avi";
  EXPECT_FALSE(IsAviSuite(s));
  box.suite = "mine";
  box.kind = "avi";
  EXPECT_TRUE(IsAviSuite(box));
  EXPECT_FALSE(IsMcpSuite(box));
}

TEST(Report, McpSectionNamesSuccessPerStartAndWhoFailsWhere) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-report-mcp-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  BenchResults results;
  results.command = "smcbench bench --suite mcp";
  SuiteResults box;
  box.suite = "tiny";
  box.description = "box";
  box.replay.records = {Rec("q", "lemke", Verdict::kSolved, 1e-6)};
  SuiteResults mcp;
  mcp.suite = "mcp";
  mcp.description = "nonlinear MCPs";
  mcp.problems = 2;
  const auto at = [](ReplayRecord r, const std::string& problem, const std::string& start) {
    r.suite = "mcp";
    r.problem = problem;
    r.start = start;
    r.samples = 3;
    r.certificate = "unique";
    return r;
  };
  ReplayRecord failed = at(Rec("", "newton", Verdict::kFailed, 1e-3), "mcp/classic/josephy", "start2");
  failed.status = SolveStatus::kIterationLimit;
  failed.message = "line search | stalled";
  ReplayRecord inaccurate = at(Rec("", "other", Verdict::kInaccurate, 2e-5), "mcp/classic/josephy", "start1");
  inaccurate.status = SolveStatus::kSolved;
  inaccurate.forward_error = 0.5;
  ReplayRecord solved = at(Rec("", "newton", Verdict::kSolved, 1e-5), "mcp/classic/josephy", "start1");
  solved.forward_error = 1e-15;
  mcp.replay.records = {solved, inaccurate, failed,
                        at(Rec("", "other", Verdict::kSolved, 3e-5), "mcp/classic/josephy", "start2"),
                        at(Rec("", "newton", Verdict::kCorrectlyRefused, 1e-5), "mcp/hard/none", "start1"),
                        at(Rec("", "other", Verdict::kCorrectlyRefused, 1e-5), "mcp/hard/none", "start1")};
  results.suites = {box, mcp};
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const std::string md = WriteBenchReport(dir.string(), false);
  EXPECT_THAT(md, HasSubstr("## Suite `tiny`"));  // the box suite keeps its section
  EXPECT_THAT(md, HasSubstr("## MCP suite `mcp`: nonlinear MCPs"));
  EXPECT_THAT(md, HasSubstr("2 nonlinear MCPs, 3 problem × start"));
  // Backend table: newton 1 solved, 1 correctly refused, 1 failed; other 1 solved, 1 refused, 1 inaccurate.
  EXPECT_THAT(md, HasSubstr("| newton | 1 | 1 | 1 | 0 | 0 | 0 | 66.7% |"));
  EXPECT_THAT(md, HasSubstr("| other | 1 | 1 | 0 | 0 | **1** | 0 | 66.7% |"));
  // Per start: start1 has josephy and none, start2 josephy only.
  EXPECT_THAT(md, HasSubstr("| backend | `start1` | `start2` | "));
  EXPECT_THAT(md, HasSubstr("| newton | 2/2 | 0/1 | "));
  EXPECT_THAT(md, HasSubstr("| other | 1/2 | 1/1 | "));
  // Who fails where: the wrong answer first, then the failure with its status and message (no stray '|').
  const auto wrong_at = md.find("| mcp/classic/josephy | start1 | other | **INACCURATE** | solved |");
  const auto failed_at = md.find("| mcp/classic/josephy | start2 | newton | failed | iteration_limit | "
                                 "line search / stalled |");
  ASSERT_NE(wrong_at, std::string::npos) << md;
  ASSERT_NE(failed_at, std::string::npos) << md;
  EXPECT_LT(wrong_at, failed_at);
  EXPECT_THAT(md, HasSubstr("Where the backends fail (2 problem × start × backend"));
  if (GnuplotAvailable()) {
    WriteBenchReport(dir.string(), true);
    EXPECT_TRUE(fs::exists(dir / "speed-forward-error-mcp.png"));
    EXPECT_TRUE(fs::exists(dir / "profile-mcp.png"));
    const std::string data = ReadText(dir / "speed-forward-error-mcp.dat");
    EXPECT_THAT(data, HasSubstr("# newton"));
    EXPECT_THAT(data, HasSubstr("# other"));
  }
  fs::remove_all(dir);
}

// Two MCPs of the quick suite for the tests of the MCP plumbing (jobs, runs, shards, merge, budget): a 1-unknown
// problem with three solutions (three starts) and a degenerate 2-unknown one (two starts), whose references take a
// few quick solves (about 0.1 s each to list in release, where mcp/hard/no-solution takes 0.9 s of the whole quick
// suite's 2.0 s: backends run long on it). The whole suite's references (every backend from every start) take
// 40-76 s under ASan, and these tests built them once per run; the suite's content is mcp_library_test's.
const std::vector<std::string> kMcpPlumbingProblems{"--problem", "mcp/hard/three-solutions", "--problem",
                                                    "mcp/hard/degen*"};
constexpr std::size_t kMcpPlumbingStarts = 3 + 2;

std::vector<std::string> McpPlumbingArgs(std::vector<std::string> args) {
  args.insert(args.end(), kMcpPlumbingProblems.begin(), kMcpPlumbingProblems.end());
  return args;
}

// `bench --suite mcp`: MCP jobs only on the backends that solve MCPs, one per problem × start; the run's summary
// gets an mcp row and the report its MCP section.
TEST(Bench, McpSuiteJobsAndRun) {
  CliRun r = RunSmcbench(McpPlumbingArgs({"bench", "--suite", "mcp", "--quick", "--no-stepper", "--solver", "lemke",
                                          "--solver", "newton", "--list-jobs"}));
  ASSERT_EQ(r.code, 0) << r.err;
  std::size_t jobs = 0, floors = 0;
  for (const std::string& line : Lines(r.out)) {
    if (line.empty() || line[0] == '#') continue;
    EXPECT_THAT(line, HasSubstr("@"));
    if (line.find("\tfloor\t") != std::string::npos) {  // the floor of each problem × start, after its MCP job
      EXPECT_THAT(line, HasSubstr("|floor|floor|"));
      ++floors;
      continue;
    }
    ++jobs;
    EXPECT_THAT(line, HasSubstr("\tmcp\tmcp|mcp/hard/"));  // only the problems --problem names
    EXPECT_THAT(line, HasSubstr("|newton|cold|"));  // lemke does not solve MCPs: no job
  }
  EXPECT_EQ(jobs, kMcpPlumbingStarts);
  EXPECT_EQ(floors, kMcpPlumbingStarts);

  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-mcp-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  r = RunSmcbench(McpPlumbingArgs({"bench", "--suite", "mcp", "--quick", "--no-stepper", "--solver", "lemke",
                                   "--solver", "newton", "--out", dir.string(), "--report", "--no-plots"}));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| mcp | newton | " + std::to_string(jobs) + " | "));
  EXPECT_THAT(r.out, Not(HasSubstr("| mcp | lemke |")));
  const std::string md = ReadText(dir / "report.md");
  EXPECT_THAT(md, HasSubstr("## MCP suite `mcp`"));
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  EXPECT_EQ(back.suites[0].replay.records.size(), jobs);
  for (const ReplayRecord& rec : back.suites[0].replay.records) EXPECT_FALSE(rec.start.empty());

  // Only box backends chosen: said on stderr, no MCP record, and the report says why the suite is empty.
  r = RunSmcbench(McpPlumbingArgs({"bench", "--suite", "mcp", "--quick", "--no-stepper", "--solver", "lemke",
                                   "--out", dir.string(), "--overwrite", "--report", "--no-plots"}));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("no chosen backend solves MCPs"));
  EXPECT_THAT(r.out, Not(HasSubstr("| mcp |")));
  EXPECT_THAT(ReadText(dir / "report.md"), HasSubstr("No records: no chosen backend ran on it"));
  fs::remove_all(dir);
}

// `--problem 'families/warm/*'` alone runs the families' warm sequences (no cold problem matches): the report's
// section of the suite is its warm track.
TEST(BenchCommand, AGlobForTheWarmSequencesAloneRunsThem) {
  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-warm-only-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const CliRun r = RunSmcbench({"bench", "--suite", "families", "--quick", "--problem", "families/warm/*",
                                "--solver", "lemke", "--out", dir.string(), "--report", "--no-plots"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warm track of suite families: 2 sequences"));
  EXPECT_THAT(r.out, HasSubstr("| families warm | lemke | 2 | 2 | 0 | 0 | 0 | 0 | 0 | "));
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  EXPECT_TRUE(back.suites[0].replay.records.empty());
  ASSERT_EQ(back.suites[0].warm.size(), 2u);
  for (const WarmRecord& w : back.suites[0].warm) EXPECT_EQ(w.record.verdict, Verdict::kSolved) << w.record.problem;
  const std::string md = ReadText(dir / "report.md");
  EXPECT_THAT(md, HasSubstr("### Warm track of suite `families`"));
  EXPECT_THAT(md, Not(HasSubstr("No records")));
  fs::remove_all(dir);
}

// The MCP suite's jobs shard, merge and resume like the box's: two shards merged are the single run, and a backend
// past its budget gets its remaining problem × start recorded as not run, start label kept.
TEST(Shards, McpJobsMergeToTheSingleRunAndRespectTheBudget) {
  const fs::path root = fs::temp_directory_path() / ("smcbench-mcp-shards-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const auto args = [](std::vector<std::string> extra) {
    std::vector<std::string> a =
        McpPlumbingArgs({"bench", "--suite", "mcp", "--quick", "--no-stepper", "--solver", "newton"});
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(RunSmcbench(args({"--out", (root / "single").string()})).code, 0);
  std::vector<std::string> merge{"merge", (root / "merged").string()};
  for (int k = 1; k <= 2; ++k) {
    merge.push_back((root / ("shard-" + std::to_string(k))).string());
    const CliRun r = RunSmcbench(args({"--shard", std::to_string(k) + "/2", "--out", merge.back()}));
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const CliRun merged = RunSmcbench(merge);
  ASSERT_EQ(merged.code, 0) << merged.err;
  const std::vector<nlohmann::json> expected = TimelessRecords(root / "single");
  ASSERT_EQ(expected.size(), 1u + kMcpPlumbingStarts);  // the suite, then one record per problem × start
  EXPECT_EQ(expected[0]["suite"], "mcp");
  EXPECT_EQ(expected[0]["problems"], 2);
  EXPECT_EQ(expected[0]["checksum"].get<std::string>().size(), 16u);
  EXPECT_EQ(TimelessRecords(root / "merged"), expected);

  const CliRun budget = RunSmcbench(args({"--backend-budget", "1e-9", "--out", (root / "budget").string()}));
  ASSERT_EQ(budget.code, 0) << budget.err;
  const std::vector<nlohmann::json> cut = TimelessRecords(root / "budget");
  ASSERT_EQ(cut.size(), expected.size());
  for (std::size_t i = 2; i < cut.size(); ++i) {  // the first job spends the budget, every later one is cut
    EXPECT_EQ(cut[i]["status"], "not_run");
    EXPECT_EQ(cut[i]["mode"], "cut");
    EXPECT_THAT(cut[i]["message"].get<std::string>(), HasSubstr("--backend-budget"));
    EXPECT_EQ(cut[i]["start"], expected[i]["start"]);
  }
  EXPECT_EQ(cut[2]["start"], "z0=2");  // the second start of mcp/hard/degenerate: a cut record keeps its label
  EXPECT_THAT(budget.err, HasSubstr("problem x start of suite mcp"));
  fs::remove_all(root);
}

// `bench --problem GLOB`: only the matching problems run, in box and MCP suites alike; the globs are in the
// manifest, so --resume with other globs is refused and compare shows them among the settings; --list-jobs and
// --shard list only their jobs; a glob that matches nothing is an error naming the flag and the glob.
TEST(Bench, ProblemFilterRunsOnlyTheMatchingProblemsAndIsRecorded) {
  const fs::path root = fs::temp_directory_path() / ("smcbench-bench-problem-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const auto args = [](std::vector<std::string> extra, const std::string& mcp_glob = "mcp/hard/degen*") {
    std::vector<std::string> a{"bench", "--suite", "tiny", "--suite", "mcp", "--quick", "--no-stepper",
                               "--repetitions", "1", "--solver", "lemke", "--solver", "newton",
                               "--allow-wrong", "newton", "--problem", "tiny/infeasible*", "--problem", mcp_glob};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const CliRun run = RunSmcbench(args({"--out", (root / "filtered").string()}));
  ASSERT_EQ(run.code, 0) << run.err;
  const BenchResults results = ReadBenchResults((root / "filtered").string());
  ASSERT_EQ(results.suites.size(), 2u);
  EXPECT_EQ(results.suites[0].suite, "tiny");
  EXPECT_EQ(results.suites[0].problems, 1);
  EXPECT_EQ(results.suites[0].replay.records.size(), 2u);  // tiny/infeasible-lcp on lemke and newton
  EXPECT_EQ(results.suites[1].suite, "mcp");
  EXPECT_EQ(results.suites[1].problems, 1);
  EXPECT_EQ(results.suites[1].replay.records.size(), 2u);  // mcp/hard/degenerate from its two starts, newton
  for (const SuiteResults& suite : results.suites) {
    for (const auto* records : {&suite.replay.records, &suite.replay.sweep, &suite.replay.floor}) {
      for (const ReplayRecord& r : *records) {
        EXPECT_TRUE(r.problem == "tiny/infeasible-lcp" || r.problem == "mcp/hard/degenerate") << r.problem;
      }
    }
  }
  const auto manifest = nlohmann::json::parse(ReadText(root / "filtered" / "manifest.json"));
  EXPECT_EQ(manifest["options"]["problems"], nlohmann::json({"tiny/infeasible*", "mcp/hard/degen*"}));

  // The same command resumes (nothing left to run); other globs are another run.
  const CliRun resumed = RunSmcbench(args({"--resume", (root / "filtered").string()}));
  EXPECT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr(" 0 to run"));
  const CliRun refused = RunSmcbench(args({"--resume", (root / "filtered").string()}, "mcp/hard/three-*"));
  EXPECT_EQ(refused.code, 1);
  EXPECT_THAT(refused.err, HasSubstr("not the same run: other options (options.problems"));

  // --list-jobs with --shard: each shard lists only jobs of the kept problems, and the shards together all of them.
  std::size_t listed = 0;
  for (int k = 1; k <= 2; ++k) {
    const CliRun jobs = RunSmcbench(args({"--list-jobs", "--shard", std::to_string(k) + "/2"}));
    ASSERT_EQ(jobs.code, 0) << jobs.err;
    for (const std::string& line : Lines(jobs.out)) {
      if (line.empty() || line[0] == '#') continue;
      ++listed;
      EXPECT_TRUE(line.find("|tiny/infeasible-lcp|") != std::string::npos ||
                  line.find("|mcp/hard/degenerate@") != std::string::npos)
          << line;
    }
  }
  const RunManifest written = ReadRunManifest((root / "filtered").string());
  EXPECT_EQ(listed, written.jobs.size());

  // compare: other problems are not comparable (the suites' checksums differ); the same problems chosen by other
  // globs are, and the globs are among the settings that differ.
  const auto tiny_run = [&](const std::string& glob, const std::string& out) {
    std::vector<std::string> a{"bench", "--suite", "tiny", "--quick", "--no-stepper", "--repetitions", "1",
                               "--solver", "lemke", "--out", (root / out).string()};
    if (!glob.empty()) a.insert(a.end(), {"--problem", glob});
    return RunSmcbench(a).code;
  };
  ASSERT_EQ(tiny_run("", "all"), 0);
  ASSERT_EQ(tiny_run("tiny/infeasible*", "glob"), 0);
  ASSERT_EQ(tiny_run("tiny/infeasible-lcp", "exact"), 0);
  const CliRun other_problems = RunSmcbench({"compare", (root / "all").string(), (root / "glob").string()});
  EXPECT_EQ(other_problems.code, kExitCompareRefused);
  EXPECT_THAT(other_problems.err, HasSubstr("other problems in suite tiny"));
  const CliRun same_problems = RunSmcbench({"compare", (root / "glob").string(), (root / "exact").string(),
                                            "--out", (root / "compared").string(), "--no-plots"});
  EXPECT_NE(same_problems.code, kExitCompareRefused) << same_problems.err;  // 0, or 1 if timing noise flags it
  EXPECT_THAT(same_problems.out, HasSubstr("problems [\"tiny/infeasible*\"] vs [\"tiny/infeasible-lcp\"]"));

  // A glob that matches nothing: an error naming the flag and the glob, before any folder is made.
  const CliRun none = RunSmcbench({"bench", "--suite", "tiny", "--quick", "--solver", "lemke", "--problem",
                                   "tiny/*", "--problem", "tiny/nope*", "--out", (root / "none").string()});
  EXPECT_EQ(none.code, 1);
  EXPECT_THAT(none.err, HasSubstr("--problem 'tiny/nope*' matches no problem of the suites tiny (ids look like "
                                  "'tiny/"));
  EXPECT_FALSE(fs::exists(root / "none"));
  fs::remove_all(root);
}

// `bench --suite avi`: one job per AVI × box backend; the run writes records of suite avi that no backend got
// wrongly claimed, the summary an avi row per backend and the report its AVI section.
TEST(Bench, AviSuiteJobsAndRun) {
  CliRun r = RunSmcbench({"bench", "--suite", "avi", "--quick", "--no-stepper", "--solver", "lemke", "--solver",
                          "newton", "--list-jobs"});
  ASSERT_EQ(r.code, 0) << r.err;
  std::size_t jobs = 0;
  for (const std::string& line : Lines(r.out)) {
    if (line.empty() || line[0] == '#') continue;
    if (line.find("\tfloor\tavi|avi/") != std::string::npos) continue;  // the floor of each AVI, after its jobs
    ++jobs;
    EXPECT_THAT(line, HasSubstr("\tavi\tavi|avi/"));
  }
  EXPECT_EQ(jobs % 2, 0u);
  EXPECT_GE(jobs / 2, 20u);  // every AVI on both backends

  const fs::path dir = fs::temp_directory_path() / ("smcbench-bench-avi-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  r = RunSmcbench({"bench", "--suite", "avi", "--quick", "--no-stepper", "--solver", "lemke", "--solver", "newton",
                   "--out", dir.string(), "--report", "--no-plots"});
  ASSERT_EQ(r.code, 0) << r.err;  // 3 would mean a wrong answer
  EXPECT_THAT(r.out, HasSubstr("| avi | lemke | " + std::to_string(jobs / 2) + " | "));
  EXPECT_THAT(r.out, HasSubstr("| avi | newton | " + std::to_string(jobs / 2) + " | "));
  const std::string md = ReadText(dir / "report.md");
  EXPECT_THAT(md, HasSubstr("## AVI suite `avi`"));
  EXPECT_THAT(md, HasSubstr("| backend | twisting | planted | degenerate | halfspaces | cone | infeasible |"));
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  EXPECT_EQ(back.suites[0].suite, "avi");
  EXPECT_EQ(back.suites[0].checksum.size(), 16u);
  EXPECT_EQ(back.suites[0].replay.records.size(), jobs);
  int refused = 0;
  for (const ReplayRecord& rec : back.suites[0].replay.records) {
    EXPECT_EQ(rec.suite, "avi");
    EXPECT_NE(rec.verdict, Verdict::kWronglyClaimed) << rec.solver << " on " << rec.problem;
    refused += rec.expected == ExpectedOutcome::kInfeasible && rec.verdict == Verdict::kCorrectlyRefused;
  }
  EXPECT_EQ(refused, 6);  // the 3 AVIs with no solution, by both backends
  fs::remove_all(dir);
}

// The AVI suite's jobs shard and merge like the others: two shards merged are the single run.
TEST(Shards, AviJobsMergeToTheSingleRun) {
  const fs::path root = fs::temp_directory_path() / ("smcbench-avi-shards-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const auto args = [](std::vector<std::string> extra) {
    std::vector<std::string> a{"bench", "--suite", "avi", "--quick", "--no-stepper", "--solver", "lemke"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(RunSmcbench(args({"--out", (root / "single").string()})).code, 0);
  std::vector<std::string> merge{"merge", (root / "merged").string()};
  for (int k = 1; k <= 2; ++k) {
    merge.push_back((root / ("shard-" + std::to_string(k))).string());
    const CliRun r = RunSmcbench(args({"--shard", std::to_string(k) + "/2", "--out", merge.back()}));
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const CliRun merged = RunSmcbench(merge);
  ASSERT_EQ(merged.code, 0) << merged.err;
  const std::vector<nlohmann::json> expected = TimelessRecords(root / "single");
  ASSERT_GE(expected.size(), 20u);
  EXPECT_EQ(expected[0]["suite"], "avi");
  EXPECT_EQ(TimelessRecords(root / "merged"), expected);

  // A backend past its budget: its remaining AVIs are recorded as not run, said on stderr.
  const CliRun budget = RunSmcbench(args({"--backend-budget", "1e-9", "--out", (root / "budget").string()}));
  ASSERT_EQ(budget.code, 0) << budget.err;
  const std::vector<nlohmann::json> cut = TimelessRecords(root / "budget");
  ASSERT_EQ(cut.size(), expected.size());
  EXPECT_EQ(cut[2]["status"], "not_run");
  EXPECT_EQ(cut[2]["mode"], "cut");
  EXPECT_THAT(cut[2]["message"].get<std::string>(), HasSubstr("--backend-budget"));
  EXPECT_THAT(budget.err, HasSubstr("problems of suite avi"));
  fs::remove_all(root);
}

}  // namespace
}  // namespace smcbench
