// End-to-end tests of the smcbench command line, run in-process: output formats scripts rely on, exit codes,
// one-line errors on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "problems/io/matrix_market.h"
#include "problems/io/siconos_format.h"
#include "problems/library/problem_set_io.h"
#include "smcbench/version.h"
#include "solvers/auto/auto_solver.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/cli_test_runner.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

using test_support::CliRun;
using test_support::RunSmcbench;

const std::string kPeer = SMCBENCH_PEER_DATA_DIR "/siconos";

TEST(Cli, ListNamesEveryBackendWithReference) {
  const CliRun r = RunSmcbench({"list"});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* name : {"lemke", "psor", "newton", "enum", "ipopt"}) EXPECT_THAT(r.out, HasSubstr(name));
  EXPECT_THAT(r.out, HasSubstr("reference:"));
  EXPECT_THAT(r.out, HasSubstr("size limit:"));
}

// The backends `--solver all` names for a box-MLCP file: every registered one that solves box-MLCPs.
std::size_t BoxBackendCount() {
  std::size_t count = 0;
  for (auto name : SolverNames()) count += CreateSolver(name)->info().box;
  return count;
}

TEST(Cli, SolveJsonHasTheStableKeys) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--solver", "all", "--json", "--repeat", "3"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), BoxBackendCount());  // every registered backend that solves box-MLCPs
  for (const auto& row : j) {
    for (const char* key : {"solver", "status", "iterations", "residual_abs", "residual_rel", "residual_scaled",
                            "time_ns_median", "z"}) {
      EXPECT_TRUE(row.contains(key)) << key;
    }
    EXPECT_FALSE(row.contains("forward_error")) << "only with --reference";
    EXPECT_EQ(row["z"].size(), 2u);
    if (row["status"] == "solved") {
      EXPECT_LE(row["residual_rel"].get<double>(), 1e-10);
      EXPECT_LE(row["residual_scaled"].get<double>(), 1e-10);  // solved needs both
    }
  }
  EXPECT_EQ(j[0]["status"], "solved") << j[0].dump();  // Lemke solves this relay problem
}

// With no --solver, `solve` runs the default backend, auto, and its JSON row says which backend answered (detail
// chosen, by name): relay_2x2 has two rows with a choice, so enum.
TEST(Cli, SolveDefaultsToAutoAndRecordsTheChoice) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 1u) << j.dump();
  EXPECT_EQ(j[0]["solver"], "auto");
  EXPECT_EQ(j[0]["status"], "solved") << j[0].dump();
  ASSERT_TRUE(j[0]["details"].contains("chosen")) << j[0].dump();
  EXPECT_EQ(j[0]["details"]["chosen"], "enum") << j[0].dump();
  EXPECT_EQ(j[0]["chosen"], "enum") << j[0].dump();
  EXPECT_EQ(j[0]["details"]["fallbacks"].get<int>(), 0);
  // Codes by name, measurements as numbers: a cold solve answered by the backend's algorithm.
  EXPECT_EQ(j[0]["details"]["path"], "backend") << j[0].dump();
  const CliRun help = RunSmcbench({"solve", "--help"});
  EXPECT_THAT(help.out, HasSubstr("default: auto"));
}

// CLI11's own usage errors (an unknown flag, a missing argument) read like ours: one line on stderr with the
// `smcbench:` prefix and where to look, exit status 2; --help still prints the help and exits 0.
TEST(Cli, UsageErrorsAreOneLinePrefixedAndExitTwo) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{{"solve", "--bogus"}, {"solve"}}) {
    const CliRun r = RunSmcbench(args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_THAT(r.err, ::testing::StartsWith("smcbench: "));
    EXPECT_THAT(r.err, HasSubstr("(see 'smcbench solve --help')"));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const CliRun help = RunSmcbench({"solve", "--help"});
  EXPECT_EQ(help.code, 0);
  EXPECT_THAT(help.out, HasSubstr("--repeat"));
}

// A mistyped flag is named, with the nearest flag of that command; the order of the words is the user's.
TEST(Cli, UnknownFlagIsNamedWithTheNearestFlag) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--solvr", "lemke"});
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown flag '--solvr' (did you mean '--solver'?)")) << r.err;
  const CliRun far = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--completely-different"});
  EXPECT_EQ(far.code, 2);
  EXPECT_THAT(far.err, HasSubstr("unknown flag '--completely-different'")) << far.err;
  EXPECT_THAT(far.err, Not(HasSubstr("did you mean"))) << far.err;
}

// Invalid numbers name the flag and the value instead of being accepted.
TEST(Cli, NegativeBudgetsAreRejectedNamingTheFlag) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--max-iter", "-1"}, {"--time-limit", "-1"}, {"--max-iter", "2.5"}}) {
    const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", args[0], args[1]});
    EXPECT_EQ(r.code, 2) << args[0] << " " << args[1];
    EXPECT_THAT(r.err, HasSubstr(args[0])) << r.err;
    EXPECT_THAT(r.err, HasSubstr(args[1])) << r.err;
  }
}

// convert says what it wrote.
TEST(Cli, ConvertSaysWhatItWrote) {
  const std::string out = (std::filesystem::temp_directory_path() / "smcbench_cli_convert.smcps").string();
  const CliRun r = RunSmcbench({"convert", kPeer + "/relay/relay_2x2.dat", out});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("convert: wrote '"));
  EXPECT_THAT(r.out, HasSubstr("(m = 2, dense) to " + out));
  std::filesystem::remove(out);
}

// convert A B C --out SET.smcps gathers the three files' problems into one set that reads back with their data; a
// clash of ids names both files, and an --out that is not a .smcps is refused before anything is read.
TEST(Cli, ConvertGathersFilesIntoOneSet) {
  const std::string out = testing::TempDir() + "/gathered.smcps";
  const std::vector<std::string> files = {kPeer + "/relay/relay_2x2.dat", kPeer + "/relay/relay_4x4.dat",
                                          kPeer + "/relay/step_1x1.dat"};
  CliRun r = RunSmcbench({"convert", files[0], files[1], files[2], "--out", out});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("convert: wrote 3 problems from 3 file(s) to " + out));
  const ProblemSet set = ReadProblemSetFile(out);
  EXPECT_EQ(set.name, "gathered");
  ASSERT_EQ(set.problems.size(), 3u);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const BoxMLCP original = ReadSiconosFile(files[i]);
    EXPECT_EQ(set.problems[i].size(), original.size()) << files[i];
    EXPECT_EQ(set.problems[i].problem.q(), original.q()) << files[i];
    EXPECT_EQ(set.problems[i].problem.dense_matrix(), original.dense_matrix()) << files[i];
  }
  r = RunSmcbench({"convert", files[0], files[0], "--out", out});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("is also in '" + files[0] + "'"));
  r = RunSmcbench({"convert", files[0], files[1], "--out", testing::TempDir() + "/gathered.mtx"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("must name a problem set file ending in .smcps"));
  r = RunSmcbench({"convert", files[0], files[1], files[2]});
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.err, HasSubstr("give INPUT OUTPUT, or INPUT... --out SET.smcps"));
  std::filesystem::remove(out);
}

// --version is an option of the program like --help: listed by --help, printed on stdout with the revision the
// build recorded, exit 0 (also from an out-of-tree program's main calling RunCli).
TEST(Cli, VersionIsListedByHelpAndPrintsTheBuildsRevision) {
  const CliRun help = RunSmcbench({"--help"});
  EXPECT_EQ(help.code, 0);
  EXPECT_THAT(help.out, HasSubstr("--version"));
  const CliRun version = RunSmcbench({"--version"});
  EXPECT_EQ(version.code, 0) << version.err;
  EXPECT_EQ(version.out, "smcbench " + std::string(Version()) + " (git " + std::string(GitRevision()) + ")\n");
  EXPECT_FALSE(std::string(GitRevision()).empty());
}

// --set BACKEND.OPTION reaches auto's own instance of that backend: with enum limited to 1 row with a choice,
// relay_2x2 goes elsewhere. A bad option of a backend that is not selected is still an error.
TEST(Cli, SetReachesAutosInstanceOfTheBackend) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--json", "--set", "enum.size_limit=1"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["status"], "solved") << j[0].dump();
  EXPECT_NE(j[0]["details"]["chosen"], "enum") << j[0].dump();
  EXPECT_TRUE(j[0]["details"]["chosen"].is_string()) << j[0].dump();
  const CliRun bad = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--set", "psor.omega=3"});
  EXPECT_EQ(bad.code, 1);
  EXPECT_THAT(bad.err, HasSubstr("omega"));
}

// lcp_trivial: M = diag(1, …, 9), q = −1, so z*_i = 1/i (every row free), the only solution (M is a P-matrix).
TEST(Cli, SolveReferenceGivesEachBackendsForwardErrorAgainstTheCertifiedSolution) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/lcp/lcp_trivial.dat", "--solver", "lemke", "psor", "newton",
                                "--json", "--reference"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_object());
  const auto& reference = j["reference"];
  EXPECT_EQ(reference["certificate"], "unique");
  ASSERT_EQ(reference["z"].size(), 9u);
  for (int i = 0; i < 9; ++i) EXPECT_DOUBLE_EQ(reference["z"][i].get<double>(), 1.0 / (i + 1)) << i;
  EXPECT_DOUBLE_EQ(reference["condition"].get<double>(), 1.0);  // (D⁻¹M)_FF = I
  ASSERT_EQ(j["results"].size(), 3u);
  for (const auto& row : j["results"]) {
    ASSERT_EQ(row["z"].size(), 9u) << row.dump();
    double error = 0.0;
    for (int i = 0; i < 9; ++i) error = std::max(error, std::abs(row["z"][i].get<double>() - 1.0 / (i + 1)));
    EXPECT_DOUBLE_EQ(row["forward_error"].get<double>(), error) << row["solver"];
    EXPECT_DOUBLE_EQ(row["forward_error_rel"].get<double>(), error) << "‖z*‖∞ = 1";
    // 10 · max(1, μ) · tol · (1 + ‖z*‖∞) with μ = 1, tol = 1e-10.
    EXPECT_DOUBLE_EQ(row["forward_allowance"].get<double>(), 2e-9);
    EXPECT_TRUE(row.contains("residual_scaled"));
    EXPECT_EQ(row["verdict"], "solved") << row.dump();
  }

  // The same as text: the certificate on one line, each backend's forward error on its line.
  const CliRun text = RunSmcbench({"solve", kPeer + "/lcp/lcp_trivial.dat", "--solver", "lemke", "--reference"});
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("reference: certificate unique"));
  EXPECT_THAT(text.out, HasSubstr("fwd err 0.00e+00"));
}

// M = [[1, 1], [1, 1]], q = (−1, −1): every z ≥ 0 with z₁ + z₂ = 1 solves it, so no forward error is defined.
TEST(Cli, SolveReferenceOnANonUniqueProblemDefinesNoForwardError) {
  const std::string path = testing::TempDir() + "/lcp_nonunique.dat";
  std::ofstream(path) << "2\n0\n2\n2\n2\t2\n1 1\n1 1\n-1 -1\n";
  const CliRun r = RunSmcbench({"solve", path, "--solver", "lemke", "--json", "--reference"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["reference"]["certificate"], "non-unique") << j.dump();
  const auto& row = j["results"][0];
  EXPECT_EQ(row["status"], "solved");
  EXPECT_TRUE(row["forward_error"].is_null()) << row.dump();
  EXPECT_EQ(row["verdict"], "solved");
}

// --no-polish reaches SolverOptions::polish: psor stopped after 2 sweeps on lcp_mmc is polished by default (detail
// "polished"), and returned raw with the flag.
TEST(Cli, NoPolishReturnsTheRawAlgorithmsAnswer) {
  const std::vector<std::string> base = {"solve", kPeer + "/lcp/lcp_mmc.dat", "--solver", "psor", "--max-iter", "2",
                                         "--json"};
  const CliRun polished = RunSmcbench(base);
  std::vector<std::string> args = base;
  args.push_back("--no-polish");
  const CliRun raw = RunSmcbench(args);
  ASSERT_EQ(polished.code, 0) << polished.err;
  ASSERT_EQ(raw.code, 0) << raw.err;
  const auto p = nlohmann::json::parse(polished.out)[0], q = nlohmann::json::parse(raw.out)[0];
  EXPECT_EQ(p["details"].value("polished", 0.0), 1.0) << p.dump();
  EXPECT_FALSE(q["details"].contains("polished")) << q.dump();
  EXPECT_GE(q["residual_scaled"].get<double>(), p["residual_scaled"].get<double>());
}

TEST(Cli, SolveTextHasOneLinePerBackend) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/lcp/lcp_trivial.dat", "--solver", "lemke", "enum"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("lemke"));
  EXPECT_THAT(r.out, HasSubstr("enum"));
  EXPECT_THAT(r.out, HasSubstr("solved"));
}

TEST(Cli, UnreadableFileIsAOneLineErrorAndExitOne) {
  const CliRun r = RunSmcbench({"solve", "/nonexistent/problem.dat"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("/nonexistent/problem.dat"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
}

TEST(Cli, UnknownSolverAndBadOptionsAreErrors) {
  CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--solver", "simplex"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("unknown solver 'simplex'"));
  r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--solver", "psor", "--set", "psor.omega=3"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("omega"));
  r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--set", "psor.nosuchoption=1"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("unknown option"));
  r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--tol", "-1"});
  EXPECT_EQ(r.code, 2);
  r = RunSmcbench({"frobnicate"});
  EXPECT_EQ(r.code, 2);
}

TEST(Cli, MalformedFileIsAnErrorNamingTheFile) {
  const std::string path = testing::TempDir() + "/truncated_lcp.dat";
  std::ofstream(path) << "3\n0 3 3 3 3\n1 2 3\n";
  const CliRun r = RunSmcbench({"solve", path});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("truncated_lcp"));
}

TEST(Cli, ConvertWritesARelayFileThatSolvesTheSame) {
  const std::string out = testing::TempDir() + "/converted_relay.dat";
  CliRun r = RunSmcbench({"convert", kPeer + "/lcp/lcp_mmc.dat", out});
  ASSERT_EQ(r.code, 0) << r.err;
  const CliRun a = RunSmcbench({"solve", kPeer + "/lcp/lcp_mmc.dat", "--solver", "lemke", "--json"});
  const CliRun b = RunSmcbench({"solve", out, "--solver", "lemke", "--json"});
  ASSERT_EQ(a.code, 0);
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(nlohmann::json::parse(a.out)[0]["z"], nlohmann::json::parse(b.out)[0]["z"]);
}

TEST(Cli, CollectionWritesTableAndJson) {
  const std::string dir = testing::TempDir() + "/mini_collection";
  std::filesystem::create_directories(dir + "/relay");
  std::filesystem::copy_file(kPeer + "/relay/relay_2x2.dat", dir + "/relay/relay_2x2.dat",
                             std::filesystem::copy_options::overwrite_existing);
  const std::string md = dir + "/table.md", js = dir + "/records.json";
  const CliRun r = RunSmcbench({"collection", dir, "--markdown", md, "--json", js, "--repeat", "1"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("relay/relay_2x2.dat"));
  std::ifstream in(md);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_THAT(text, HasSubstr("Generated by `smcbench collection"));
  std::ifstream jin(js);
  EXPECT_EQ(nlohmann::json::parse(jin).size(), BoxBackendCount());
}

// A fresh folder per test under the test temp dir.
std::string FreshDir(const std::string& name) {
  const std::string dir = testing::TempDir() + "/cli-formats-" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// relay_2x2 is M = I, q = (-0.5, 0.5), l = -1, u = 1: z = -q = (0.5, -0.5), read off the file by hand.
void ExpectRelay2x2Answer(const CliRun& r) {
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 1u) << r.out;
  EXPECT_EQ(j[0]["status"], "solved");
  ASSERT_EQ(j[0]["z"].size(), 2u);
  EXPECT_NEAR(j[0]["z"][0].get<double>(), 0.5, 1e-12);
  EXPECT_NEAR(j[0]["z"][1].get<double>(), -0.5, 1e-12);
}

// A relay file outside a folder named relay/ must not be read as an LCP (which fails with "trailing data"): a
// name that says nothing lets the content decide, and a misleading folder gives an error that says what was
// assumed, why, and the --format that reads it.
TEST(CliFormats, RelayFileWithANeutralNameIsReadByItsContent) {
  const std::string dir = FreshDir("neutral");
  std::filesystem::copy_file(kPeer + "/relay/relay_2x2.dat", dir + "/two.dat");
  ExpectRelay2x2Answer(RunSmcbench({"solve", dir + "/two.dat", "--solver", "lemke", "--json"}));
  const CliRun text = RunSmcbench({"solve", dir + "/two.dat", "--solver", "lemke"});
  EXPECT_THAT(text.out, HasSubstr("two (n = 2)"));
}

TEST(CliFormats, RelayFileInAnLcpFolderSaysWhatWasAssumedAndHowToChoose) {
  const std::string dir = FreshDir("misfiled");
  std::filesystem::create_directories(dir + "/lcp");
  const std::string path = dir + "/lcp/two.dat";
  std::filesystem::copy_file(kPeer + "/relay/relay_2x2.dat", path);
  const CliRun r = RunSmcbench({"solve", path, "--solver", "lemke"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("trailing data"));
  EXPECT_THAT(r.err, HasSubstr("read as a Siconos LCP, guessed from the folder name 'lcp/'"));
  EXPECT_THAT(r.err, HasSubstr("it reads as a Siconos relay problem: choose that with --format relay"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  ExpectRelay2x2Answer(RunSmcbench({"solve", path, "--format", "relay", "--solver", "lemke", "--json"}));

  // The user's choice is not second-guessed: no hint, the reader's own message.
  const CliRun forced = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--format", "lcp"});
  EXPECT_EQ(forced.code, 1);
  EXPECT_THAT(forced.err, HasSubstr("Siconos LCP"));
  EXPECT_THAT(forced.err, Not(HasSubstr("guessed")));
  const CliRun bad = RunSmcbench({"solve", path, "--format", "hdf5"});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--format"));

  // collection --format applies to every file of the folder.
  const CliRun all = RunSmcbench({"collection", dir, "--format", "relay", "--solver", "lemke", "--repeat", "1"});
  ASSERT_EQ(all.code, 0) << all.err;
  EXPECT_THAT(all.out, HasSubstr("| lcp/two.dat | 2 | solved"));
  const CliRun guessed = RunSmcbench({"collection", dir, "--solver", "lemke", "--repeat", "1"});
  EXPECT_THAT(guessed.out, HasSubstr("rejected by the reader"));
  EXPECT_THAT(guessed.out, HasSubstr("--format relay"));
}

// A .smcps set with three problems whose solutions are known by construction: M = diag(d), q = -d·z*, l = 0,
// u = inf with z* > 0, so z = z*.
std::string WriteThreeProblemSet(const std::string& dir) {
  ProblemSet set{"three", "cli test", {}};
  const double diagonal[3] = {2.0, 4.0, 8.0};
  const char* ids[3] = {"t/a", "t/b1", "t/b2"};
  for (int k = 0; k < 3; ++k) {
    DenseMatrix M = DenseMatrix::Identity(2, 2) * diagonal[k];
    Vector z(2);
    z << 1.0 + k, 0.5;
    set.problems.push_back(MakeLibraryProblem(ids[k], "generated:test", BoxMLCP::LCP(M, -(M * z), ids[k])));
    set.problems.back().solution = z;
  }
  const std::string path = dir + "/three.smcps";
  WriteProblemSetFile(set, path);
  return path;
}

TEST(CliFormats, SolveReadsAProblemSetAndSelectsById) {
  const std::string path = WriteThreeProblemSet(FreshDir("smcps"));
  CliRun r = RunSmcbench({"solve", path, "--id", "t/a", "t/b2", "--solver", "lemke", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 2u) << r.out;
  EXPECT_EQ(j[0]["problem"], "t/a");
  EXPECT_EQ(j[1]["problem"], "t/b2");
  EXPECT_EQ(j[1]["n"], 2);
  EXPECT_EQ(j[0]["results"][0]["status"], "solved");
  EXPECT_NEAR(j[0]["results"][0]["z"][0].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(j[1]["results"][0]["z"][0].get<double>(), 3.0, 1e-12);
  EXPECT_NEAR(j[1]["results"][0]["z"][1].get<double>(), 0.5, 1e-12);

  r = RunSmcbench({"solve", path, "--id", "t/b*", "--solver", "lemke"});  // prefix: b1 and b2, text output
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("t/b1 (n = 2)"));
  EXPECT_THAT(r.out, HasSubstr("t/b2 (n = 2)"));
  EXPECT_THAT(r.out, Not(HasSubstr("t/a ")));
  r = RunSmcbench({"solve", path, "--solver", "lemke", "--json"});  // all three
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).size(), 3u);

  // A set renamed without its extension is still recognized by its magic bytes.
  std::filesystem::copy_file(path, path + ".bin");
  r = RunSmcbench({"solve", path + ".bin", "--id", "t/a", "--solver", "lemke", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)[0]["problem"], "t/a");

  r = RunSmcbench({"solve", path, "--id", "t/zzz"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--id t/zzz: no such problem in"));
  EXPECT_THAT(r.err, HasSubstr("3 problems, e.g. t/a, t/b1, t/b2"));
  EXPECT_THAT(r.err, Not(HasSubstr("--format"))) << "an unknown id is not a question of the file's kind";
  r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--id", "x"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--id selects problems of a .smcps set"));
  r = RunSmcbench({"convert", path, FreshDir("smcps-out") + "/x.dat"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("gives 3: choose one with --id"));
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// convert to Matrix Market and back: the numbers equal the Siconos file's, bit for bit, infinite bounds included
// (an MLCP's free rows: l = -inf, u = +inf), and `solve` reads the .mtx by extension or --format.
TEST(CliFormats, ConvertToMatrixMarketRoundTripsEveryNumber) {
  const std::string dir = FreshDir("mtx");
  for (const std::string& source : {kPeer + "/mlcp/deltasigma_mlcp.dat", kPeer + "/relay/relay_2x2.dat",
                                   kPeer + "/lcp/lcp_mmc.dat"}) {
    SCOPED_TRACE(source);
    ASSERT_TRUE(std::filesystem::exists(source));
    const BoxMLCP original = ReadSiconosFile(source);
    const std::string out = dir + "/" + std::filesystem::path(source).stem().string() + ".mtx";
    const CliRun r = RunSmcbench({"convert", source, out});
    ASSERT_EQ(r.code, 0) << r.err;
    const BoxMLCP back = ReadMatrixMarketProblem(out);
    ASSERT_EQ(back.size(), original.size());
    EXPECT_EQ(back.is_sparse(), original.is_sparse());
    const DenseMatrix a = original.ToDense(), b = back.ToDense();
    for (Eigen::Index i = 0; i < a.size(); ++i) EXPECT_TRUE(SameBits(a.data()[i], b.data()[i])) << "M entry " << i;
    for (Eigen::Index i = 0; i < original.size(); ++i) {
      EXPECT_TRUE(SameBits(original.q()[i], back.q()[i])) << "q " << i;
      EXPECT_TRUE(SameBits(original.l()[i], back.l()[i])) << "l " << i;
      EXPECT_TRUE(SameBits(original.u()[i], back.u()[i])) << "u " << i;
    }
  }
  // relay_2x2's bounds are ±1; the vector file holds them as text a person can read.
  EXPECT_EQ(ReadText(dir + "/relay_2x2_l.mtx").find("%%MatrixMarket matrix array real general"), 0u);
  EXPECT_THAT(ReadText(dir + "/relay_2x2_l.mtx"), HasSubstr("\n2 1\n-1\n-1\n"));
  ExpectRelay2x2Answer(RunSmcbench({"solve", dir + "/relay_2x2.mtx", "--solver", "lemke", "--json"}));
  std::filesystem::copy_file(dir + "/relay_2x2.mtx", dir + "/other.txt");
  const CliRun wrong_name = RunSmcbench({"solve", dir + "/other.txt", "--format", "mtx"});
  EXPECT_EQ(wrong_name.code, 1);
  EXPECT_THAT(wrong_name.err, HasSubstr("must end in .mtx"));
  std::filesystem::remove(dir + "/relay_2x2_q.mtx");
  const CliRun missing = RunSmcbench({"solve", dir + "/relay_2x2.mtx"});
  EXPECT_EQ(missing.code, 1);
  EXPECT_THAT(missing.err, HasSubstr("relay_2x2_q.mtx': missing"));
  EXPECT_THAT(missing.err, HasSubstr("guessed from the extension '.mtx'"));
}

}  // namespace
}  // namespace smcbench
