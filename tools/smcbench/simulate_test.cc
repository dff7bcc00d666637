// End-to-end tests of `smcbench simulate` and `smcbench scenes`, run in-process: the CSV and summary formats
// scripts rely on, the paper's S1 and S2 claims through the command line, one-line errors with exit status 1.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/figures/gnuplot_figure.h"
#include "problems/library/capture.h"
#include "problems/library/problem_set_io.h"
#include "problems/scenes/linear_scene.h"
#include "problems/scenes/reference_run.h"
#include "problems/scenes/registry.h"
#include "problems/scenes/run_summary.h"
#include "solvers/registry/registry.h"
#include "tests/support/malloc_counter.h"
#include "tools/smcbench/cli_test_runner.h"
#include "tools/smcbench/simulate.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

using test_support::CliRun;
using test_support::RunSmcbench;

std::vector<std::string> ReadLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<double> SplitNumbers(const std::string& line) {
  std::vector<double> values;
  std::stringstream ss(line);
  for (std::string item; std::getline(ss, item, ',');) values.push_back(std::stod(item));
  return values;
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

class Simulate : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(testing::TempDir()) / ("simulate_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  // Expects exit 1 and a one-line error containing every part.
  static void ExpectOneLineError(const CliRun& r, std::initializer_list<const char*> parts) {
    EXPECT_EQ(r.code, 1) << r.out << r.err;
    for (const char* part : parts) EXPECT_THAT(r.err, HasSubstr(part));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }

  fs::path dir_;
};

// S1 with h = 0.01: CSV header and row 0, summary keys, exact arrival at k0+1 (k0 = ⌈1.01/0.01⌉ − 1 = 100) or
// k0+2, the errors against the exact solution.
TEST_F(Simulate, SignSceneWritesCsvAndSummary) {
  const std::string csv = Path("sign.csv"), summary = Path("sign.json");
  const CliRun r = RunSmcbench({"simulate", "sign", "--h", "0.01", "--out", csv, "--summary", summary});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("sign: implicit"));
  EXPECT_EQ(r.err, "");

  const auto lines = ReadLines(csv);
  ASSERT_EQ(lines.size(), 1u + 201u);  // header + rows k = 0..200 (T = 2)
  EXPECT_EQ(lines[0].rfind("t,x1,s1", 0), 0u) << lines[0];
  EXPECT_EQ(lines[0], "t,x1,s1,y1,iterations,residual,u1");  // S1 is a controller: u = −s
  const auto row0 = SplitNumbers(lines[1]);
  ASSERT_GE(row0.size(), 3u);
  EXPECT_EQ(row0[0], 0.0);
  EXPECT_EQ(row0[1], 1.01);
  EXPECT_EQ(row0[2], 0.0);  // no step produced x_0
  const auto row1 = SplitNumbers(lines[2]);
  EXPECT_DOUBLE_EQ(row1[0], 0.01);
  EXPECT_EQ(row1[2], 1.0);  // s_1 = Π(x_0/h) = 1

  const auto j = ReadJson(summary);
  for (const char* key : {"steps", "x_final", "reaching_step", "max_abs_y_after_reaching", "sign_changes_after_reaching",
                          "total_variation_after_reaching", "max_residual", "errors", "scene", "method", "solver",
                          "failed_steps", "surfaces", "s_error_max", "y_error_max", "reference_skipped",
                          "reference"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["steps"], 200);
  ASSERT_EQ(j["x_final"].size(), 1u);
  // Lemma (yahoo): x = 0 exactly after the arrival, with the default backend (the base's exact polish gives
  // s = fl(x_k/h), and the stepper zeroes the rounding residue of x_k − h·s).
  EXPECT_EQ(j["x_final"][0].get<double>(), 0.0);
  const int k0 = 100;
  const auto reaching = j["reaching_step"].get<int>();
  EXPECT_TRUE(reaching == k0 + 1 || reaching == k0 + 2) << reaching;
  EXPECT_LE(j["max_abs_y_after_reaching"].get<double>(), 1e-15);
  EXPECT_EQ(j["sign_changes_after_reaching"], 0);
  EXPECT_LE(j["max_residual"].get<double>(), 1e-10);
  EXPECT_EQ(j["failed_steps"], 0);
  for (const char* part : {"x", "s"}) {
    for (const char* norm : {"l1", "l2", "max"}) EXPECT_TRUE(j["errors"][part].contains(norm)) << part << norm;
  }
  EXPECT_LE(j["errors"]["x"]["max"].get<double>(), 0.011);
  EXPECT_LE(j["errors"]["s"]["l1"].get<double>(), 0.02);
}

// Lemma (yahoo) through the command line with the reported example (x0 = 1.7771, h = 0.021, T = 8), where x was
// seen at 1.7e-18 (lemke) and 1e-10 (newton) after the arrival: with every backend at its default settings x is exactly
// 0 from k0+1 (or k0+2) to the end, k0 the first step with |x_k| ≤ h.
TEST_F(Simulate, LemmaYahooIssueExampleIsExactlyZeroWithEveryBackend) {
  for (const char* solver : {"", "lemke", "psor", "newton", "enum", "ipopt"}) {
    SCOPED_TRACE(*solver ? solver : "default backend");
    const std::string csv = Path("yahoo.csv");
    std::vector<std::string> args{"simulate", "sign", "--x0", "1.7771", "--h", "0.021", "--T", "8", "--out", csv};
    if (*solver) args.insert(args.end(), {"--solver", solver});
    const CliRun r = RunSmcbench(args);
    ASSERT_EQ(r.code, 0) << r.err;
    const auto lines = ReadLines(csv);
    ASSERT_EQ(lines.size(), 1u + 382u);  // header + k = 0..381 (T/h = 380.95)
    std::vector<double> x;
    for (std::size_t k = 1; k < lines.size(); ++k) x.push_back(SplitNumbers(lines[k])[1]);
    std::size_t k0 = 0;
    while (std::abs(x[k0]) > 0.021) ++k0;
    std::size_t arrival = k0 + 1;
    while (arrival < x.size() && x[arrival] != 0.0) ++arrival;
    EXPECT_TRUE(arrival == k0 + 1 || arrival == k0 + 2) << "arrival " << arrival << ", k0 " << k0;
    for (std::size_t k = arrival; k < x.size(); ++k) ASSERT_EQ(x[k], 0.0) << "step " << k;
  }
}

// Accuracy in the units users read: s_error_max and y_error_max against a run stepped with certified
// solves. enum solves each one-step problem exactly, so it matches the reference to rounding. PSOR without the
// polish at tolerance 1e-4 may stop early: the summary gives its answers' own error in x_{k+1} (step_x_error_max,
// refined_steps: the step verdict), and the run goes on from the exact step on PSOR's active set (docs/verdict.md), so its s and y
// are the certified run's to rounding.
TEST_F(Simulate, SummaryReportsTheErrorInSAndYAgainstACertifiedReferenceRun) {
  for (const char* scene : {"sign", "multi-surface"}) {
    SCOPED_TRACE(scene);
    const std::string exact = Path("exact.json"), loose = Path("loose.json");
    CliRun r = RunSmcbench({"simulate", scene, "--solver", "enum", "--summary", exact});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("against the certified reference run"));
    const auto e = ReadJson(exact);
    ASSERT_TRUE(e["s_error_max"].is_number()) << e["reference_skipped"];
    EXPECT_LE(e["s_error_max"].get<double>(), 1e-12);
    EXPECT_LE(e["y_error_max"].get<double>(), 1e-12);
    EXPECT_TRUE(e["reference_skipped"].is_null());
    EXPECT_EQ(e["reference"]["solver"], "reference");
    EXPECT_EQ(e["reference"]["steps"], e["steps"]);
    EXPECT_EQ(e["reference"]["steps_compared"], e["steps"]);
    EXPECT_EQ(e["reference"]["completed"], true);
    EXPECT_GE(e["reference"]["wall_seconds"].get<double>(), 0.0);

    r = RunSmcbench({"simulate", scene, "--solver", "psor", "--no-polish", "--tol", "1e-4", "--summary", loose});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto l = ReadJson(loose);
    ASSERT_TRUE(l["s_error_max"].is_number()) << l["reference_skipped"];
    // PSOR's answers themselves: within the step verdict's allowance in x (these one- and two-row steps converge
    // far past the loose tolerance), so none was refined.
    EXPECT_LE(l["step_x_error_max"].get<double>(), 1e-4);
    EXPECT_EQ(l["refined_steps"].get<std::int64_t>(), 0);
    EXPECT_LE(l["s_error_max"].get<double>(), 1e-12);
    EXPECT_LE(l["y_error_max"].get<double>(), 1e-12);
    EXPECT_EQ(e["refined_steps"].get<std::int64_t>(), 0);  // enum's answers are exact
    EXPECT_LE(e["step_x_error_max"].get<double>(), 1e-12);
  }
  // No one-step problem, no reference: the keys are null and say why.
  const std::string ex = Path("explicit.json");
  ASSERT_EQ(RunSmcbench({"simulate", "sign", "--method", "explicit", "--summary", ex}).code, 0);
  const auto x = ReadJson(ex);
  EXPECT_TRUE(x["s_error_max"].is_null());
  EXPECT_TRUE(x["y_error_max"].is_null());
  EXPECT_TRUE(x["reference"].is_null());
  EXPECT_THAT(x["reference_skipped"].get<std::string>(), HasSubstr("solves no one-step problem"));
}

TEST_F(Simulate, ReferenceRunIsSkippedAboveAMillionSteps) {
  const auto scene = LoadScene("sign");
  SimulationSettings settings = scene->defaults();
  Trajectory run;  // only its size matters: the limit is checked before anything runs
  run.n = run.m = 1;
  run.recorded = true;
  run.num_steps = kMaxReferenceSteps + 1;
  const ReferenceComparison c = CompareWithReferenceRun(*scene, settings, run);
  EXPECT_FALSE(c.errors.has_value());
  EXPECT_FALSE(c.ran);
  EXPECT_THAT(c.skipped, HasSubstr("1000001 steps > 1000000"));
  const auto enumerative = CreateSolver("enum");
  ASSERT_NE(scene->linear_plant(), nullptr);
  LinearStepper stepper(scene->linear_plant()->Discretization(settings));
  const Trajectory three_steps = stepper.Run(settings.x0, 3, enumerative.get(), StepperOptions{});
  const nlohmann::json j = SimulationSummary(*scene, settings, "enum", three_steps, 1e-9, 0.0, &c);
  EXPECT_TRUE(j["s_error_max"].is_null());
  EXPECT_THAT(j["reference_skipped"].get<std::string>(), HasSubstr("> 1000000"));
}

// S2 at h = 0.3: explicit Euler ends on a period-2 orbit around the sliding line; implicit Euler reaches it and
// stays with |Cx| at rounding level and s without sign changes (Lemma oups, CB = 1).
TEST_F(Simulate, GaliasYuExplicitChattersImplicitDoesNot) {
  const std::string ecsv = Path("explicit.csv"), ejs = Path("explicit.json"), ijs = Path("implicit.json");
  CliRun r = RunSmcbench({"simulate", "galias-yu-2007", "--method", "explicit", "--h", "0.3", "--T", "30", "--out",
                          ecsv, "--summary", ejs});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto e = ReadJson(ejs);
  EXPECT_EQ(e["theta"], 0.0);        // explicit without --theta: the classical explicit Euler scheme
  EXPECT_TRUE(e["solver"].is_null());  // no one-step problem
  EXPECT_EQ(e["reaching_step"], -1);
  EXPECT_GE(e["sign_changes_total"].get<int>(), 50);
  // The orbit: x_{k+2} = x_k, x_{k+1} ≠ x_k, on both sides of the line (s alternates).
  const auto lines = ReadLines(ecsv);
  const auto a = SplitNumbers(lines[lines.size() - 3]), b = SplitNumbers(lines[lines.size() - 2]),
             c = SplitNumbers(lines[lines.size() - 1]);
  for (int i = 1; i <= 2; ++i) EXPECT_NEAR(a[i], c[i], 1e-9) << "x" << i;
  EXPECT_GT(std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]), 1e-3);
  EXPECT_EQ(b[3], -c[3]);  // s1 alternates
  EXPECT_NE(b[3], 0.0);

  r = RunSmcbench({"simulate", "galias-yu-2007", "--method", "implicit", "--h", "0.3", "--T", "30", "--summary", ijs});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto i = ReadJson(ijs);
  EXPECT_GE(i["reaching_step"].get<int>(), 1);
  EXPECT_LE(i["reaching_step"].get<int>(), 20);
  EXPECT_LE(i["max_abs_y_after_reaching"].get<double>(), 1e-12);
  EXPECT_EQ(i["sign_changes_after_reaching"], 0);
  EXPECT_EQ(i["failed_steps"], 0);
}

// S9/S10 by name: --algorithm picks Algorithm 1 (mcp, default backend newton) or 2 (newton-mlcp, any backend);
// both land on the same final state; the summary names the algorithm.
TEST_F(Simulate, NonlinearScenesRunBothAlgorithms) {
  const std::string a1 = Path("mcp.json"), a2 = Path("mlcp.json");
  CliRun r = RunSmcbench({"simulate", "arctan", "--algorithm", "mcp", "--summary", a1});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("backend newton"));
  r = RunSmcbench({"simulate", "arctan", "--algorithm", "newton-mlcp", "--solver", "psor", "--newton-tol", "1e-11",
                   "--newton-max-iter", "20", "--summary", a2});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j1 = ReadJson(a1), j2 = ReadJson(a2);
  EXPECT_EQ(j1["algorithm"], "mcp");
  EXPECT_EQ(j2["algorithm"], "newton-mlcp");
  EXPECT_EQ(j2["newton_tolerance"], 1e-11);
  EXPECT_EQ(j2["newton_max_iterations"], 20);
  EXPECT_EQ(j1["reaching_step"], j2["reaching_step"]);
  EXPECT_EQ(j1["sign_changes_after_reaching"], 0);
  EXPECT_NEAR(j1["x_final"][0].get<double>(), j2["x_final"][0].get<double>(), 1e-12);
  // The rho-shift of S9 is a scene parameter.
  r = RunSmcbench({"simulate", "hypomonotone", "--param", "rho=2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("rho=2"));

  ExpectOneLineError(RunSmcbench({"simulate", "arctan", "--algorithm", "mcp", "--solver", "lemke"}),
                     {"--algorithm mcp needs a backend that solves nonlinear MCPs"});
  ExpectOneLineError(RunSmcbench({"simulate", "arctan", "--algorithm", "newton"}), {"unknown algorithm 'newton'"});
  ExpectOneLineError(RunSmcbench({"simulate", "arctan", "--newton-max-iter", "0"}), {"newton iteration limit"});
  ExpectOneLineError(RunSmcbench({"simulate", "arctan", "--method", "zoh"}), {"ZOH"});
  r = RunSmcbench({"simulate", "sign", "--algorithm", "mcp"});
  EXPECT_EQ(r.code, 0);
  EXPECT_THAT(r.err, HasSubstr("apply to nonlinear scenes only"));
}

TEST_F(Simulate, UnknownSceneListsTheKnownNames) {
  const CliRun r = RunSmcbench({"simulate", "sine"});
  ExpectOneLineError(r, {"unknown scene 'sine'", "sign", "galias-yu-2007", "multi-surface", "filippov", "zoh-siso",
                         "zoh-mimo", "lyapunov", "observer", "parasitic"});
}

TEST_F(Simulate, BadSettingsAreOneLineErrorsWithExitOne) {
  // Numbers out of range name the flag and the value.
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--h", "0"}), {"simulate sign", "--h must be", "got 0"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--h", "-0.5"}), {"--h must be", "-0.5"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--T", "-1"}), {"--T must be", "-1"});
  ExpectOneLineError(RunSmcbench({"simulate", "observer", "--theta", "1.5"}), {"--theta must lie in [0, 1]", "1.5"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--theta", "2"}), {"--theta must lie in [0, 1], got 2"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--max-iter", "-1"}),
                     {"--max-iter must be an integer >= 0", "got -1"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--tol", "0"}),
                     {"--tol must be a positive finite number, got 0"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--gamma", "2"}), {"gamma must lie in [0, 1]"});
  ExpectOneLineError(RunSmcbench({"simulate", "galias-yu-2007", "--x0", "1,2,3"}), {"x0 has 3 entries", "n = 2"});
  ExpectOneLineError(RunSmcbench({"simulate", "galias-yu-2007", "--x0", "1,abc"}), {"--x0", "'abc' is not a number"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--method", "rk4"}), {"unknown method 'rk4'"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--method", "zoh"}), {"needs a ZOH plant"});
  // A ZOH scene with a polytope law refuses the explicit ZOH for its law, not for its plant.
  ExpectOneLineError(RunSmcbench({"simulate", "twisting", "--method", "zoh-explicit"}),
                     {"scene 'twisting'", "polytope law", "use an implicit method"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--solver", "simplex"}), {"unknown solver 'simplex'", "lemke"});
  ExpectOneLineError(RunSmcbench({"simulate", "observer", "--param", "tao=1"}), {"no parameter 'tao'", "tau"});
  ExpectOneLineError(RunSmcbench({"simulate", "observer", "--param", "tau"}), {"--param expects NAME=VALUE"});
  ExpectOneLineError(RunSmcbench({"simulate", "observer", "--param", "tau=0"}), {"system.E", "not finite"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--solver", "lemke", "--set", "psor.omega=1"}),
                     {"names backend 'psor'", "uses 'lemke'"});
}

// Every output path before the run: a folder given as a file, a file in a missing folder; nothing is written.
TEST_F(Simulate, OutputPathsAreRefusedBeforeTheRun) {
  const std::string missing = Path("missing/x.csv");
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--out", dir_.string()}), {"--out", "is a folder"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--summary", missing}), {"--summary", "does not exist"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--plot", dir_.string()}), {"--plot", "is a folder"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--record", missing}), {"--record", "does not exist"});
  // The summary is written after the run: its path refused before it, the run's --out is not written either.
  const CliRun r = RunSmcbench({"simulate", "sign", "--out", Path("t.csv"), "--summary", dir_.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(fs::is_empty(dir_));
}

// A run that stops on a failed step (--on-failure stop, the default) writes what it has, says so on stderr and
// exits with status 3; with --on-failure continue it runs to T and exits 0 with a warning.
TEST_F(Simulate, RunStoppedOnAFailedStepExitsNonZero) {
  // One PSOR sweep without polishing at tol 1e-14: step 497 of filippov is the first one it does not solve.
  const std::vector<std::string> failing{"--solver", "psor", "--no-polish", "--max-iter", "1", "--tol", "1e-14"};
  const std::string csv = Path("stopped.csv");
  std::vector<std::string> args{"simulate", "filippov", "--out", csv};
  args.insert(args.end(), failing.begin(), failing.end());
  const CliRun stopped = RunSmcbench(args);
  EXPECT_EQ(stopped.code, kStoppedEarlyExitStatus) << stopped.out << stopped.err;
  EXPECT_THAT(stopped.err, HasSubstr("error: step 497: iteration_limit"));
  EXPECT_THAT(stopped.err, HasSubstr("the run stopped there (497 of 750 steps; exit status 3)\n"));
  EXPECT_THAT(stopped.out, HasSubstr("497 of 750 steps"));
  // The CSV holds the steps taken: a header, the initial state and 497 rows.
  std::ifstream in(csv);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 1 + 1 + 497);
  args = {"simulate", "filippov", "--on-failure", "continue"};
  args.insert(args.end(), failing.begin(), failing.end());
  const CliRun continued = RunSmcbench(args);
  EXPECT_EQ(continued.code, 0) << continued.err;
  EXPECT_THAT(continued.err, HasSubstr("warning: step 497: iteration_limit"));
  EXPECT_THAT(continued.err, Not(HasSubstr("stopped")));
  EXPECT_THAT(continued.out, HasSubstr("750 of 750 steps"));
}

TEST_F(Simulate, WithoutOutputFilesNothingIsRecordedOrWritten) {
  const CliRun r = RunSmcbench({"simulate", "filippov"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("750 of 750 steps"));
  EXPECT_THAT(r.out, Not(HasSubstr("recording")));
  EXPECT_TRUE(fs::is_empty(dir_));
}

// The outcome is on stdout whatever the outputs: the reaching step and, after it, the σ band and the input's
// chattering, the numbers the summary holds.
TEST_F(Simulate, PrintsTheOutcomeWithoutOutputFiles) {
  const CliRun bare = RunSmcbench({"simulate", "sign", "--x0", "0.505", "--h", "0.01"});
  ASSERT_EQ(bare.code, 0) << bare.err;
  const std::string summary = Path("sign.json");
  const CliRun with_summary = RunSmcbench({"simulate", "sign", "--x0", "0.505", "--h", "0.01", "--summary", summary});
  ASSERT_EQ(with_summary.code, 0) << with_summary.err;
  const auto j = ReadJson(summary);
  const std::int64_t reaching = j["reaching_step"].get<std::int64_t>();
  EXPECT_EQ(reaching, 51);  // x0/h = 50.5: x = 0 exactly from step 51 on (Lemma yahoo)
  EXPECT_THAT(bare.out, HasSubstr("surfaces reached at step " + std::to_string(reaching) + " (t = 0.51; |y| <= "));
  EXPECT_THAT(bare.out, HasSubstr("sign changes of the switching part " +
                                  std::to_string(j["chattering"]["switching_sign_changes"].get<std::int64_t>())));
  EXPECT_THAT(bare.out, HasSubstr("sigma band 0"));
  // The same lines with and without files, but the wall time and the summary's reference run.
  const auto without_wall = [](const std::string& text) {
    std::string kept;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      if (line.find("  wall ") != 0 && line.find("  against the certified reference") != 0) kept += line + "\n";
    }
    return kept;
  };
  EXPECT_EQ(without_wall(bare.out), without_wall(with_summary.out));
}

TEST_F(Simulate, ParametersMethodsAndScenePathsFromTheCommandLine) {
  // S8 with τ = 0.5, θ = 1/2 (the report's comparison), any backend.
  const std::string js = Path("observer.json");
  CliRun r = RunSmcbench({"simulate", "observer", "--param", "tau=0.5", "--theta", "0.5", "--solver", "enum",
                          "--summary", js});
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = ReadJson(js);
  EXPECT_EQ(j["parameters"]["tau"], 0.5);
  EXPECT_EQ(j["theta"], 0.5);
  EXPECT_EQ(j["solver"], "enum");
  EXPECT_EQ(j["steps"], 100);
  // S5 runs ZOH by default, and the Euler discretization of its closed loop on request.
  r = RunSmcbench({"simulate", "zoh-siso", "--summary", js});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(ReadJson(js)["method"], "zoh");
  EXPECT_FALSE(ReadJson(js).contains("theta"));
  r = RunSmcbench({"simulate", "zoh-siso", "--method", "zoh-explicit", "--summary", js});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(ReadJson(js)["reaching_step"], -1);  // explicit ZOH chatters
  // A scene file given by path, with its x0 overridden.
  r = RunSmcbench({"simulate", ScenesDirectory() + "/sign.json", "--x0", "-0.5", "--T", "1", "--summary", js});
  ASSERT_EQ(r.code, 0) << r.err;
  j = ReadJson(js);
  EXPECT_EQ(j["x0"][0], -0.5);
  EXPECT_LE(std::abs(j["x_final"][0].get<double>()), 1e-15);
  EXPECT_LE(j["errors"]["x"]["max"].get<double>(), 0.011);
  // γ has no effect on a linear scene: accepted with a note.
  r = RunSmcbench({"simulate", "sign", "--gamma", "0.5"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--gamma has no effect"));
}

TEST_F(Simulate, PlotWritesAPng) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  for (const char* scene : {"sign", "zoh-mimo"}) {
    const std::string png = Path(std::string(scene) + ".png");
    const CliRun r = RunSmcbench({"simulate", scene, "--plot", png});
    ASSERT_EQ(r.code, 0) << r.err;
    std::ifstream in(png, std::ios::binary);
    char magic[8] = {};
    in.read(magic, 8);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG") << scene;
    EXPECT_GT(fs::file_size(png), 5000u) << scene;
  }
  // The temporary data file is gone when --out was not given.
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path())) {
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr("smcbench-trajectory-" + std::to_string(::getpid()))));
  }
}

TEST_F(Simulate, PlotWithoutGnuplotIsAClearError) {
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", "/nonexistent", 1);
  const CliRun r = RunSmcbench({"simulate", "sign", "--plot", Path("x.png")});
  ::setenv("PATH", saved.c_str(), 1);
  ExpectOneLineError(r, {"--plot needs gnuplot", "gnuplot-nox"});
  EXPECT_FALSE(fs::exists(Path("x.png")));
}

TEST_F(Simulate, ScenesListsEveryRegisteredScene) {
  const CliRun r = RunSmcbench({"scenes"});
  ASSERT_EQ(r.code, 0) << r.err;
  for (auto name : SceneNames()) EXPECT_THAT(r.out, HasSubstr(std::string(name) + " ")) << name;
  EXPECT_EQ(static_cast<std::size_t>(std::count(r.out.begin(), r.out.end(), '\n')), SceneNames().size());
  EXPECT_THAT(r.out, HasSubstr("n=4 m=1"));  // observer
}


// --record: every one-step problem of the run in a problem-set file (M stored once), with the z the run used, which
// solves it; Algorithm 2's inner problems carry their Newton iteration; nothing to record is an error.
TEST_F(Simulate, RecordWritesEveryOneStepProblem) {
  const std::string file = Path("sign.smcps"), summary = Path("sign.json");
  CliRun r = RunSmcbench({"simulate", "sign", "--record", file, "--summary", summary});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("recorded 200 one-step problem(s), 1 distinct matrix, to " + file));
  ProblemSetFileInfo info;
  const ProblemSet set = ReadProblemSetFile(file, &info);
  EXPECT_EQ(info.matrices, 1u);
  ASSERT_EQ(set.problems.size(), 200u);
  EXPECT_EQ(set.name, "capture");
  const LibraryProblem& p = set.problems[11];
  EXPECT_EQ(p.id, "capture/sign/implicit/h0.01/k12");
  EXPECT_EQ(p.source, "capture:sign");
  EXPECT_EQ(p.metadata.at("theta"), "1");
  EXPECT_EQ(p.metadata.at("step"), "12");
  EXPECT_EQ(p.metadata.at("backend"), "auto");  // the default backend
  for (const LibraryProblem& q : set.problems) {
    EXPECT_EQ(q.expected, ExpectedOutcome::kSolvable) << q.id;
    EXPECT_EQ(Judge(q, SolveStatus::kSolved, q.solution, 1e-10).verdict, Verdict::kSolved) << q.id;
  }
  // The last problem's solution is the run's final s.
  const nlohmann::json j = ReadJson(summary);
  EXPECT_EQ(set.problems.back().solution[0], j["s_final"][0].get<double>());

  const std::string nonlinear = Path("arctan.smcps");
  r = RunSmcbench({"simulate", "arctan", "--T", "1", "--record", nonlinear});
  ASSERT_EQ(r.code, 0) << r.err;
  const ProblemSet newton = ReadProblemSetFile(nonlinear);
  ASSERT_FALSE(newton.problems.empty());
  for (const LibraryProblem& q : newton.problems) {
    EXPECT_EQ(q.id, "capture/arctan/implicit/h0.05/k" + q.metadata.at("step") + "/it" + q.metadata.at("iteration"));
    EXPECT_EQ(q.metadata.at("algorithm"), "newton-mlcp");
  }

  const std::string none = Path("none.smcps");
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--method", "explicit", "--record", none}),
                     {"--record: method 'explicit' solves no one-step problem"});
  ExpectOneLineError(RunSmcbench({"simulate", "arctan", "--algorithm", "mcp", "--record", none}),
                     {"--record captures box-MLCPs", "--algorithm newton-mlcp"});
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--record", Path("no/such/dir/x.smcps")}),
                     {"--record", "cannot be written: its folder", "does not exist"});
  EXPECT_FALSE(fs::exists(none));
}

// ------------------------------------------------------------------------------------------------------------
// Streaming: the outputs are computed while the run goes, in memory independent of its length.

// The summary `simulate` computes on the fly against the whole-trajectory computation of the same run (recorded
// trajectory, ComputeMetrics, ComputeErrors, CompareWithReference after a recorded reference run: the path that
// keeps the whole trajectory, kept in SimulationSummary's recorded overload). Every key must be equal;
// doubles compare exactly (the accumulators add the same terms in the same order, and the JSON text round-trips
// doubles), except wall_seconds, steps_per_second and reference.wall_seconds, which are timings.
TEST_F(Simulate, StreamedSummaryEqualsTheWholeTrajectoryComputation) {
  struct Case {
    std::vector<std::string> args;                     // after "simulate SCENE"
    std::function<void(SimulationSettings*)> settings;  // what those arguments set
    std::string solver;
    double tol = 1e-10;
  };
  const auto none = [](SimulationSettings*) {};
  const std::vector<std::pair<std::string, Case>> cases = {
      // S1: errors against its exact solution, the reference run, Lemma (yahoo).
      {"sign", {{"--solver", "enum"}, none, "enum"}},
      // Explicit S2: no reference, never reached, chattering (sign changes, variation).
      {"galias-yu-2007",
       {{"--method", "explicit", "--h", "0.3", "--T", "30"},
        [](SimulationSettings* s) {
          s->method = Method::kExplicit, s->h = 0.3, s->T = 30, s->theta = 0.0, s->gamma = 0.0;
        },
        ""}},
      // S3, m = 2, a loose backend: nonzero s and y errors against the reference.
      {"multi-surface",
       {{"--solver", "psor", "--no-polish", "--tol", "1e-4"},
        [](SimulationSettings* s) { s->stepper.solver.polish = false; },
        "psor",
        1e-4}},
      // ZOH, m = 2, 4001 rows (two streamed blocks).
      {"zoh-mimo",
       {{"--solver", "lemke", "--T", "40"}, [](SimulationSettings* s) { s->T = 40; }, "lemke"}},
      // Forced (S7), and S8 with a parameter and θ = 1/2.
      {"lyapunov", {{"--solver", "enum"}, none, "enum"}},
      {"observer",
       {{"--solver", "enum", "--param", "tau=0.5", "--theta", "0.5"},
        [](SimulationSettings* s) { s->parameters["tau"] = 0.5, s->theta = 0.5; },
        "enum"}},
      // The default backend ("auto") on S11's nearly singular steps.
      {"parasitic", {{}, none, "auto"}},
      // Nonlinear S10 (Algorithm 2) and S9 (Algorithm 1).
      {"arctan", {{"--solver", "enum"}, none, "enum"}},
      {"hypomonotone",
       {{"--algorithm", "mcp"}, [](SimulationSettings* s) { s->algorithm = NonlinearAlgorithm::kMcp; }, "newton"}},
      // Failed steps, kept going past (first_failure, failed_steps, max_residual), and a run that stops at one.
      {"filippov",
       {{"--solver", "psor", "--no-polish", "--max-iter", "2", "--tol", "1e-14", "--on-failure", "continue"},
        [](SimulationSettings* s) {
          s->stepper.solver.polish = false, s->stepper.solver.max_iterations = 2;
          s->stepper.on_failure = FailurePolicy::kContinue;
        },
        "psor",
        1e-14}},
      {"filippov",
       {{"--solver", "psor", "--no-polish", "--max-iter", "1", "--tol", "1e-14"},
        [](SimulationSettings* s) { s->stepper.solver.polish = false, s->stepper.solver.max_iterations = 1; },
        "psor",
        1e-14}},
  };
  int with_reference = 0, with_failures = 0, stopped = 0;
  for (const auto& [scene_name, c] : cases) {
    SCOPED_TRACE(scene_name + " " + ::testing::PrintToString(c.args));
    const std::string file = Path("streamed.json");
    std::vector<std::string> args{"simulate", scene_name, "--summary", file};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliRun r = RunSmcbench(args);
    ASSERT_TRUE(r.code == 0 || r.code == kStoppedEarlyExitStatus) << r.err;
    const nlohmann::json streamed = ReadJson(file);

    const auto scene = LoadScene(scene_name);
    SimulationSettings settings = scene->defaults();
    c.settings(&settings);
    settings.stepper.solver.tolerance = c.tol;
    settings.stepper.record = true;
    std::unique_ptr<Solver> solver = c.solver.empty() ? nullptr : CreateSolver(c.solver);
    Trajectory tr;
    scene->Run(settings, solver.get(), &tr);
    const ReferenceComparison reference = CompareWithReferenceRun(*scene, settings, tr);
    const nlohmann::json whole = SimulationSummary(*scene, settings, c.solver, tr, 10 * c.tol, 0.0, &reference);

    with_reference += streamed["s_error_max"].is_number() ? 1 : 0;
    with_failures += tr.failed_steps > 0 ? 1 : 0;
    stopped += tr.stopped_early ? 1 : 0;
    EXPECT_EQ(r.code, tr.stopped_early ? kStoppedEarlyExitStatus : 0);
    EXPECT_EQ(streamed["steps"], tr.steps_taken);
    for (const auto& [key, value] : whole.items()) {
      if (key == "wall_seconds" || key == "steps_per_second") continue;
      ASSERT_TRUE(streamed.contains(key)) << key;
      if (key == "reference" && value.is_object()) {
        nlohmann::json a = value, b = streamed[key];
        a.erase("wall_seconds"), b.erase("wall_seconds");
        EXPECT_EQ(b, a) << key;
      } else {
        EXPECT_EQ(streamed[key], value) << key << ": streamed " << streamed[key].dump() << ", whole "
                                        << value.dump();
      }
    }
    EXPECT_EQ(streamed.size(), whole.size());
  }
  // The cases exercise what they are meant to.
  EXPECT_GE(with_reference, 6);
  EXPECT_GE(with_failures, 2);
  EXPECT_GE(stopped, 1);
}

// Every output at once (--summary with its reference run, --out, --record) for N and 10 N steps: the heap the run
// adds to the process must not grow with N. Measured at the malloc level (tests/support/malloc_counter.h: live
// bytes, whatever allocates them, Eigen included), not through /proc (VmHWM does not see the heap on every kernel this runs on).
// Holding the whole trajectory (the run's and the reference run's rows) and the --record ids at once would grow
// the peak by megabytes per 10⁵ steps of S2; here the peak of the 10 N run may exceed the N run's by at most 1 MB.
TEST_F(Simulate, OutputsStreamInMemoryIndependentOfTheNumberOfSteps) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "the allocator is not ours to observe (sanitizer build)";
  const auto peak_bytes = [&](const char* T) {
    const std::string out = Path("run.csv"), summary = Path("run.json"), record = Path("run.smcps");
    test_support::ResetHeapPeak();
    const CliRun r = RunSmcbench({"simulate", "galias-yu-2007", "--solver", "enum", "--h", "1e-3", "--T", T, "--out",
                                  out, "--summary", summary, "--record", record});
    const long peak = test_support::HeapPeakAboveReset();
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(ReadJson(summary)["s_error_max"].is_number()) << "the reference run was made";
    return peak;
  };
  const long small = peak_bytes("10");   // N = 10⁴ steps
  const long large = peak_bytes("100");  // 10 N
  std::printf("[ info     ] peak heap above the start of the run: %ld kB for 10^4 steps, %ld kB for 10^5 steps\n",
              small / 1024, large / 1024);
  EXPECT_GT(small, 0) << "the counter sees the run's allocations";
  EXPECT_LT(large - small, 1 << 20);
}

// --record writes version 3: l and u stored once (like M), and each problem after the first stores only the
// metadata that changed. The problems read back equal the in-memory capture of the same run.
TEST_F(Simulate, RecordSharesBoundsAndMetadataAcrossSteps) {
  const std::string file = Path("galias.smcps");
  const CliRun r = RunSmcbench({"simulate", "galias-yu-2007", "--solver", "enum", "--h", "0.01", "--T", "20",
                                "--record", file});
  ASSERT_EQ(r.code, 0) << r.err;
  ProblemSetFileInfo info;
  const ProblemSet set = ReadProblemSetFile(file, &info);
  EXPECT_EQ(info.version, 3u);
  ASSERT_EQ(set.problems.size(), 2000u);
  // Version 2 took ≈ 300 bytes a step here (id 49, source 26, tags 15, metadata 137, l and u 16, ...).
  const double per_step = static_cast<double>(info.bytes) / 2000.0;
  std::printf("[ info     ] --record: %.1f bytes per step (S2, m = 1)\n", per_step);
  EXPECT_LT(per_step, 160.0);

  const auto scene = LoadScene("galias-yu-2007");
  SimulationSettings settings = scene->defaults();
  settings.h = 0.01, settings.T = 20;
  const auto solver = CreateSolver("enum");
  Trajectory tr;
  const std::vector<LibraryProblem> captured =
      CaptureSceneRun(*scene, settings, solver.get(), MakeCaptureContext("capture", *scene, settings, "enum"), &tr);
  ASSERT_EQ(captured.size(), set.problems.size());
  for (std::size_t i = 0; i < captured.size(); ++i) {
    const LibraryProblem &a = captured[i], &b = set.problems[i];
    ASSERT_EQ(a.id, b.id);
    EXPECT_EQ(a.source, b.source) << a.id;
    EXPECT_EQ(a.tags, b.tags) << a.id;
    EXPECT_EQ(a.metadata, b.metadata) << a.id;
    EXPECT_EQ(a.problem.q(), b.problem.q()) << a.id;
    EXPECT_EQ(a.problem.l(), b.problem.l()) << a.id;
    EXPECT_EQ(a.problem.u(), b.problem.u()) << a.id;
    EXPECT_EQ(a.solution, b.solution) << a.id;
    EXPECT_EQ(a.reference.certificate, b.reference.certificate) << a.id;
  }
}

// The default zeroes a state component that underflows below 2.2e-308 after an implicit step, so S2 sliding to
// the origin ends exactly there; --ieee-subnormals keeps plain IEEE arithmetic, whose state parks on subnormals.
TEST_F(Simulate, SubnormalStatesAreZeroByDefaultAndKeptWithIeeeSubnormals) {
  const std::string zeroed = Path("zeroed.json"), ieee = Path("ieee.json");
  const std::vector<std::string> run{"simulate", "galias-yu-2007", "--solver", "enum", "--h", "0.3", "--T", "1200",
                                     "--x0", "0,2.21"};
  std::vector<std::string> args = run;
  args.insert(args.end(), {"--summary", zeroed});
  ASSERT_EQ(RunSmcbench(args).code, 0);
  args = run;
  args.insert(args.end(), {"--ieee-subnormals", "--summary", ieee});
  ASSERT_EQ(RunSmcbench(args).code, 0);
  const auto z = ReadJson(zeroed)["x_final"], i = ReadJson(ieee)["x_final"];
  EXPECT_EQ(z[0].get<double>(), 0.0);
  EXPECT_EQ(z[1].get<double>(), 0.0);
  const double largest = std::max(std::abs(i[0].get<double>()), std::abs(i[1].get<double>()));
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(largest, std::numeric_limits<double>::min());
  ExpectOneLineError(RunSmcbench({"simulate", "sign", "--flush-subnormals", "--ieee-subnormals"}),
                     {"--flush-subnormals and --ieee-subnormals exclude each other"});
}

// A ZOH scene's CSV carries u1..um, each row's u consistent with the next state (x_{k+1} − e^{Fh} x_k =
// Ψ G u_k with e^{Fh}, Ψ by a Taylor series here: F = 0 for smc-disturbed, so e^{Fh} = I, Ψ = hI, plus the
// disturbance ∫ G d = G·(0.5/50)(cos 50t_k − cos 50t_{k+1})), and the summary's chattering keys.
TEST_F(Simulate, ZohSceneWritesItsInputAndChatteringKeys) {
  const std::string scene = ScenesDirectory() + "/smc-disturbed.json";
  for (const char* method : {"zoh", "zoh-explicit"}) {
    SCOPED_TRACE(method);
    const std::string csv = Path(std::string(method) + ".csv"), summary = Path(std::string(method) + ".json");
    const CliRun r = RunSmcbench({"simulate", scene, "--method", method, "--out", csv, "--summary", summary});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto lines = ReadLines(csv);
    ASSERT_EQ(lines.size(), 1u + 201u);
    EXPECT_EQ(lines[0], "t,x1,x2,s1,y1,iterations,residual,u1");
    EXPECT_EQ(lines.back().substr(lines.back().rfind(',') + 1), "nan");  // no step applies the last row's input
    double worst = 0.0;
    for (std::size_t k = 1; k + 1 < lines.size(); ++k) {
      const auto row = SplitNumbers(lines[k]), next = SplitNumbers(lines[k + 1]);
      const double t = row[0], t_next = next[0], u = row[7];
      const double disturbance = 2.0 * 0.5 / 50.0 * (std::cos(50.0 * t) - std::cos(50.0 * t_next));
      worst = std::max(worst, std::abs(next[2] - row[2] - (0.01 * 2.0 * u + disturbance)));
      EXPECT_EQ(next[1], row[1]);  // x1' = 0
    }
    EXPECT_LE(worst, 1e-14);
    const auto j = ReadJson(summary);
    ASSERT_TRUE(j["chattering"].is_object());
    for (const char* key : {"has_input", "from_step", "from_time", "sigma_band", "u_total_variation", "u_max_jump",
                            "u_max_abs", "switching_sign_changes", "rows"}) {
      EXPECT_TRUE(j["chattering"].contains(key)) << key;
    }
    EXPECT_TRUE(j["chattering"]["has_input"].get<bool>());
    EXPECT_GT(j["chattering"]["from_step"].get<int>(), 0);
    // The explicit scheme's switching part jumps by 2α = 2; the implicit one follows d (|Δd| ≤ 0.01·50·0.5).
    const double jump = j["chattering"]["u_max_jump"].get<double>();
    if (std::string(method) == "zoh") {
      EXPECT_LE(jump, 0.3);
    } else {
      EXPECT_GE(jump, 1.5);
    }
  }
  // A class-(2) scene without control_input: no u column, null input keys.
  const std::string summary = Path("gy.json"), csv = Path("gy.csv");
  const CliRun r = RunSmcbench({"simulate", "galias-yu-2007", "--out", csv, "--summary", summary});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(ReadLines(csv)[0], "t,x1,x2,s1,y1,iterations,residual");
  EXPECT_TRUE(ReadJson(summary)["chattering"]["u_total_variation"].is_null());
}

// The plant between samples. A ZOH plant with F ≠ 0, Siconos' θ = 0.5 controller and a matched
// disturbance 0.1 + 0.5 sin(20 t + 0.3), plant_substeps 4 in the file: the CSV has 4N + 1 rows, the sample rows are
// those of the samples-only run (--plant-substeps 1 overrides the file) text for text, and every point between
// samples, those of the last interval included, matches a fine RK4 written here of x' = F x + G (u_k + d(t)) from
// the sample row's x_k and u_k to 1e-10; the summary's metrics stay on the samples.
constexpr const char* kSampledPlantScene = R"({
  "format": "smcbench-scene/1", "name": "sampled", "description": "ZOH plant between samples",
  "system": {"type": "zoh", "F": [[0, 1], [2, -2]], "G": [[0], [1]], "C": [[1, 1]], "alpha": 1,
             "equivalent_control": {"theta": 0.5},
             "disturbance": {"constant": [0.1], "sinusoids": [{"amplitude": [0.5], "omega": 20, "phase": 0.3}]}},
  "simulation": {"method": "zoh", "h": 0.05, "T": 1, "x0": [1, -0.5], "plant_substeps": 4}
})";

// x(t + tau) of x' = F x + G (u + d(t)) for kSampledPlantScene, by `fine` classical RK4 steps.
std::vector<double> SampledSceneRk4(std::vector<double> x, double u, double t, double tau, int fine) {
  const auto rate = [u](const std::vector<double>& v, double time) {
    const double input = u + 0.1 + 0.5 * std::sin(20.0 * time + 0.3);
    return std::vector<double>{v[1], 2.0 * v[0] - 2.0 * v[1] + input};
  };
  const auto axpy = [](const std::vector<double>& v, double a, const std::vector<double>& w) {
    return std::vector<double>{v[0] + a * w[0], v[1] + a * w[1]};
  };
  const double dt = tau / fine;
  for (int i = 0; i < fine; ++i) {
    const double ti = t + i * dt;
    const auto k1 = rate(x, ti), k2 = rate(axpy(x, 0.5 * dt, k1), ti + 0.5 * dt);
    const auto k3 = rate(axpy(x, 0.5 * dt, k2), ti + 0.5 * dt), k4 = rate(axpy(x, dt, k3), ti + dt);
    for (int c = 0; c < 2; ++c) x[c] += dt / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
  }
  return x;
}

TEST_F(Simulate, PlantSubstepsReportTheContinuousPlantBetweenSamples) {
  const std::string scene = Path("sampled.json");
  std::ofstream(scene) << kSampledPlantScene;
  const std::string csv = Path("plant.csv"), samples_csv = Path("samples.csv");
  const std::string summary = Path("plant.json"), samples_summary = Path("samples.json");
  CliRun r = RunSmcbench({"simulate", scene, "--out", csv, "--summary", summary});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("plant between samples: 3 point(s) per interval in the trajectory (81 rows)"));
  r = RunSmcbench({"simulate", scene, "--plant-substeps", "1", "--out", samples_csv, "--summary", samples_summary});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto plant = ReadLines(csv), samples = ReadLines(samples_csv);
  ASSERT_EQ(samples.size(), 1u + 21u);
  ASSERT_EQ(plant.size(), 1u + 4u * 20u + 1u);
  EXPECT_EQ(plant[0], samples[0]);
  double worst = 0.0;
  for (std::size_t k = 0; k < 21; ++k) {
    EXPECT_EQ(plant[1 + 4 * k], samples[1 + k]) << "sample " << k;
    if (k == 20) break;
    const auto row = SplitNumbers(samples[1 + k]), next = SplitNumbers(samples[2 + k]);
    // Columns t, x1, x2, s1, y1, iterations, residual, u1.
    std::vector<double> x{row[1], row[2]};
    for (int j = 1; j <= 4; ++j) {
      x = SampledSceneRk4(x, row[7], row[0] + (j - 1) * 0.05 / 4, 0.05 / 4, 500);
      if (j == 4) {  // the next sample: the ZOH step and the disturbance's are exact
        worst = std::max({worst, std::abs(x[0] - next[1]), std::abs(x[1] - next[2])});
        break;
      }
      const auto point = SplitNumbers(plant[1 + 4 * k + static_cast<std::size_t>(j)]);
      EXPECT_NEAR(point[0], row[0] + j * 0.05 / 4, 1e-15) << k << "," << j;
      worst = std::max({worst, std::abs(point[1] - x[0]), std::abs(point[2] - x[1])});
      EXPECT_EQ(point[3], next[3]) << "s_{k+1}, the multiplier held over the interval";
      EXPECT_NEAR(point[4], point[1] + point[2], 1e-15) << "y = C x";
      EXPECT_EQ(point[5], 0.0);
      EXPECT_EQ(point[7], row[7]) << "the u applied over the interval";
    }
  }
  EXPECT_LE(worst, 1e-10);
  // Metrics on the controller's samples: the same summary, plus the plant_substeps key.
  auto with = ReadJson(summary), without = ReadJson(samples_summary);
  EXPECT_EQ(with["plant_substeps"], 4);
  EXPECT_FALSE(without.contains("plant_substeps"));
  for (const char* key : {"steps", "x_final", "reaching_step", "chattering", "s_error_max", "y_error_max"}) {
    EXPECT_EQ(with[key], without[key]) << key;
  }
}

// The default is today's output: a ZOH scene without plant_substeps and with --plant-substeps 1 write the same bytes.
TEST_F(Simulate, PlantSubstepsOneIsTheDefaultOutput) {
  const std::string a = Path("default.csv"), b = Path("one.csv");
  ASSERT_EQ(RunSmcbench({"simulate", "zoh-mimo", "--out", a}).code, 0);
  ASSERT_EQ(RunSmcbench({"simulate", "zoh-mimo", "--plant-substeps", "1", "--out", b}).code, 0);
  EXPECT_EQ(ReadLines(a), ReadLines(b));
  EXPECT_GT(ReadLines(a).size(), 2u);
}

TEST_F(Simulate, PlantSubstepsBadValuesAreOneLineErrors) {
  const std::string scene = Path("sampled.json");
  std::ofstream(scene) << kSampledPlantScene;
  ExpectOneLineError(RunSmcbench({"simulate", scene, "--plant-substeps", "0"}),
                     {"--plant-substeps must be an integer >= 1, got 0"});
  ExpectOneLineError(RunSmcbench({"simulate", "zoh-siso", "--method", "implicit", "--plant-substeps", "3"}),
                     {"--plant-substeps 3 needs method zoh or zoh-explicit"});
  // The file's value with an Euler method: a note, and the samples alone.
  const std::string csv = Path("euler.csv");
  const CliRun r = RunSmcbench({"simulate", scene, "--method", "implicit", "--out", csv});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("plant_substeps applies to methods zoh and zoh-explicit only"));
  EXPECT_EQ(ReadLines(csv).size(), 1u + 21u);
  const std::string text = kSampledPlantScene;
  const auto with_value = [&](const std::string& value) {
    std::string edited = text;
    edited.replace(edited.find("\"plant_substeps\": 4"), 19, "\"plant_substeps\": " + value);
    const std::string path = Path("bad.json");
    std::ofstream(path) << edited;
    return RunSmcbench({"simulate", path});
  };
  ExpectOneLineError(with_value("2.5"), {"simulation.plant_substeps", "must be an integer in [1, 1000000], got 2.5"});
  ExpectOneLineError(with_value("0"), {"simulation.plant_substeps", "got 0"});
  ExpectOneLineError(with_value("\"4\""), {"simulation.plant_substeps", "expected a number"});
}

}  // namespace
}  // namespace smcbench
