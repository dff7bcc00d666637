// End-to-end tests of the smcbench command line, run in-process: output formats scripts rely on, exit codes,
// one-line errors on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "solvers/auto/auto_solver.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/cli_test_runner.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;

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

TEST(Cli, SolveJsonHasTheStableKeys) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--solver", "all", "--json", "--repeat", "3"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), SolverNames().size());  // every registered backend (5 + the siconos-* when built)
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
// chosen, an index into AutoCandidateName): relay_2x2 has two rows with a choice, so enum.
TEST(Cli, SolveDefaultsToAutoAndRecordsTheChoice) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 1u) << j.dump();
  EXPECT_EQ(j[0]["solver"], "auto");
  EXPECT_EQ(j[0]["status"], "solved") << j[0].dump();
  ASSERT_TRUE(j[0]["details"].contains("chosen")) << j[0].dump();
  EXPECT_EQ(AutoCandidateName(j[0]["details"]["chosen"].get<int>()), "enum") << j[0].dump();
  EXPECT_EQ(j[0]["details"]["fallbacks"].get<int>(), 0);
  const CliRun help = RunSmcbench({"solve", "--help"});
  EXPECT_THAT(help.out, HasSubstr("default: auto"));
}

// --set BACKEND.OPTION reaches auto's own instance of that backend: with enum limited to 1 row with a choice,
// relay_2x2 goes elsewhere. A bad option of a backend that is not selected is still an error.
TEST(Cli, SetReachesAutosInstanceOfTheBackend) {
  const CliRun r = RunSmcbench({"solve", kPeer + "/relay/relay_2x2.dat", "--json", "--set", "enum.size_limit=1"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["status"], "solved") << j[0].dump();
  EXPECT_NE(AutoCandidateName(j[0]["details"]["chosen"].get<int>()), "enum") << j[0].dump();
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
  EXPECT_EQ(nlohmann::json::parse(jin).size(), SolverNames().size());
}

}  // namespace
}  // namespace smcbench
