// `smcbench solve FILE.avi.json` and `solve SET.smcps` on a set of AVIs, run in-process: the answer checked against
// the KKT conditions recomputed here from the file's data, the verdict and the certified reference (the set's own
// where it has one), the ways the kind is recognised, the selection by id, and the refusals.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/replay/avi_replay.h"
#include "bench/kinds/avi_kind.h"
#include "bench/run/bench_plan.h"
#include "problems/avi_library/avi_suite.h"
#include "problems/io/avi_file.h"
#include "problems/library/problem_set_io.h"
#include "solvers/avi/avi_verdict.h"
#include "tools/smcbench/avi_export.h"
#include "tools/smcbench/cli_test_runner.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using test_support::CliRun;
using test_support::RunSmcbench;

const std::string kExample = std::string(SMCBENCH_SOURCE_DIR) + "/problems/io/testdata/twisting-projection.avi.json";

Vector FromJson(const nlohmann::json& array) {
  Vector v(static_cast<Eigen::Index>(array.size()));
  for (std::size_t i = 0; i < array.size(); ++i) v[static_cast<Eigen::Index>(i)] = array[i].get<double>();
  return v;
}

// A scratch folder removed at the end of the test.
struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("avi_solve_test_" + std::to_string(::getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() { fs::remove_all(path); }
  std::string File(const std::string& name) const { return (path / name).string(); }
};

TEST(SolveAviCli, AnswerSatisfiesTheKktConditionsRecomputedFromTheFile) {
  const CliRun r = RunSmcbench({"solve", kExample, "--solver", "lemke", "enum", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 2u);
  const AffineVI avi = ReadAviFile(kExample).avi;
  for (const auto& row : j) {
    SCOPED_TRACE(row.dump());
    EXPECT_EQ(row["problem"], "twisting-projection");
    EXPECT_EQ(row["status"], "solved");
    EXPECT_EQ(row["verdict"], "solved");
    for (const char* key : {"residual_rel", "residual_scaled", "primal_infeasibility", "complementarity"}) {
      ASSERT_TRUE(row[key].is_number()) << key;
      EXPECT_LE(row[key].get<double>(), 1e-10) << key;
    }
    EXPECT_TRUE(row["forward_error"].is_null());  // not judged against a reference without --reference
    EXPECT_TRUE(row["reduced"].contains("status"));
    const Vector lambda = FromJson(row["lambda"]), mu = FromJson(row["mu"]);
    ASSERT_EQ(lambda.size(), 2);
    ASSERT_EQ(mu.size(), 4);
    EXPECT_TRUE(row["nu"].empty());
    // KKT recomputed here: Mλ + q − Hᵀμ = 0, μ ≥ 0, Hλ − K ≥ 0, μᵢ(Hλ − K)ᵢ = 0.
    EXPECT_LE((avi.M() * lambda + avi.q() - avi.H().transpose() * mu).cwiseAbs().maxCoeff(), 1e-12);
    const Vector slack = avi.H() * lambda - avi.K();
    EXPECT_GE(mu.minCoeff(), 0.0);
    EXPECT_GE(slack.minCoeff(), -1e-12);
    EXPECT_LE(mu.cwiseProduct(slack).cwiseAbs().maxCoeff(), 1e-12);
    // The projection of (2, 3) onto the parallelogram, worked by hand in docs/formats.md's example.
    EXPECT_NEAR(lambda[0], 1.0, 1e-12);
    EXPECT_NEAR(lambda[1], 1.05, 1e-12);
  }
}

TEST(SolveAviCli, TextShowsTheProblemTheVerdictAndTheMultipliers) {
  const CliRun r = RunSmcbench({"solve", kExample, "--solver", "lemke", "--repeat", "3"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("twisting-projection (AVI: n = 2, m = 4, p = 0, P bounded, expected solvable)"));
  EXPECT_THAT(r.out, HasSubstr("lemke    solved"));
  EXPECT_THAT(r.out, HasSubstr("verdict solved"));
  // λ and μ as numbers that read back to the answer's doubles: by hand, λ = (1, 1.05), μ = (0, 1.0975, 0, 1.95).
  const std::size_t at = r.out.find("    lambda ");
  ASSERT_NE(at, std::string::npos);
  std::istringstream lines(r.out.substr(at));
  std::string word;
  double l0 = 0, l1 = 0, m0 = -1, m1 = 0, m2 = -1, m3 = 0;
  lines >> word >> l0 >> l1 >> word >> m0 >> m1 >> m2 >> m3;
  EXPECT_NEAR(l0, 1.0, 1e-12);
  EXPECT_NEAR(l1, 1.05, 1e-12);
  EXPECT_NEAR(m0, 0.0, 1e-12);
  EXPECT_NEAR(m1, 1.0975, 1e-12);
  EXPECT_NEAR(m2, 0.0, 1e-12);
  EXPECT_NEAR(m3, 1.95, 1e-12);
  EXPECT_THAT(r.out, HasSubstr("    nu     (none)"));
}

TEST(SolveAviCli, ReferenceJudgesTheForwardError) {
  const CliRun r = RunSmcbench({"solve", kExample, "--solver", "lemke", "--json", "--reference", "--repeat", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("reference"));
  EXPECT_TRUE(j["reference"]["lambda_unique"].get<bool>());  // M = I: strictly monotone
  EXPECT_NE(j["reference"]["certificate"], "none");
  const Vector reference = FromJson(j["reference"]["lambda"]);
  ASSERT_EQ(reference.size(), 2);
  EXPECT_NEAR(reference[1], 1.05, 1e-15);
  const auto& row = j["results"].at(0);
  EXPECT_EQ(row["repeats"], 2);
  EXPECT_EQ(row["verdict"], "solved");
  ASSERT_TRUE(row["forward_error"].is_number());
  EXPECT_LE(row["forward_error"].get<double>(), row["forward_allowance"].get<double>());

  const CliRun text = RunSmcbench({"solve", kExample, "--solver", "lemke", "--reference"});
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("reference: certificate"));
  EXPECT_THAT(text.out, HasSubstr("fwd err"));
}

TEST(SolveAviCli, TheKindIsChosenGuessedByExtensionOrByContent) {
  const ScratchDir dir;
  std::ifstream in(kExample);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string plain = dir.File("problem.txt");
  std::ofstream(plain) << text;
  // By content: the JSON says "format": "smcbench-avi".
  CliRun r = RunSmcbench({"solve", plain, "--solver", "lemke", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).at(0)["verdict"], "solved");
  // Chosen: --format avi.
  r = RunSmcbench({"solve", plain, "--format", "avi", "--solver", "lemke"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("verdict solved"));
  // A Siconos file read as an AVI because the user said so: the reader's error, unchanged.
  const std::string lcp = dir.File("lcp.dat");
  std::ofstream(lcp) << "1\n1\n-1\n";
  r = RunSmcbench({"solve", lcp, "--format", "avi"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("AVI file '" + lcp + "': not valid JSON"));
}

TEST(SolveAviCli, DefectsAndUnsupportedCombinationsAreClearErrors) {
  const ScratchDir dir;
  // A defective file under a guessed kind: the field, then why it was read as an AVI.
  const std::string bad = dir.File("bad.avi.json");
  std::ofstream(bad) << R"({"format": "smcbench-avi", "version": 1, "M": [[1]], "H": [], "K": []})";
  CliRun r = RunSmcbench({"solve", bad});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("AVI file '" + bad + "': \"q\": missing"));
  EXPECT_THAT(r.err, HasSubstr("read as an AVI file, guessed from the extension '.avi.json'"));

  r = RunSmcbench({"solve", kExample, "--id", "x"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--id selects problems of a .smcps set; '" + kExample + "' is an AVI file"));
  r = RunSmcbench({"solve", kExample, "--warm"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--warm is not supported for AVI files"));
  r = RunSmcbench({"convert", kExample, dir.File("out.mtx")});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("is an AVI file, not a box problem: only `smcbench solve` reads it"));
  EXPECT_FALSE(fs::exists(dir.File("out.mtx")));
}

TEST(SolveAviCli, AnAviWithNoSolutionIsNeverClaimedSolved) {
  // λ ≥ 0 with M = 0, q = −1: (x − λ)ᵀ(−1) ≥ 0 for every x ≥ 0 is impossible, P is unbounded.
  const ScratchDir dir;
  const std::string path = dir.File("no-solution.avi.json");
  WriteAviFile(AffineVI(DenseMatrix::Zero(1, 1), Vector::Constant(1, -1.0), DenseMatrix::Identity(1, 1),
                        Vector::Zero(1), "no-solution"),
               path);
  const CliRun r = RunSmcbench({"solve", path, "--solver", "all", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_FALSE(j.empty());
  for (const auto& row : j) {
    EXPECT_NE(row["status"], "solved") << row["solver"];
    EXPECT_THAT(std::string(row["verdict"]), ::testing::AnyOf("failed", "correctly refused")) << row["solver"];
  }
  const CliRun text = RunSmcbench({"solve", path, "--solver", "lemke"});
  EXPECT_THAT(text.out, HasSubstr("P unbounded, expected unknown"));
}

TEST(SolveAviCli, TheAviSuiteWrittenAsFilesReadsBackBitForBitAndSolves) {
  const ScratchDir dir;
  const std::string folder = dir.File("avi-suite");
  CliRun r = RunSmcbench({"library", "--write-suite", "avi", folder, "--quick"});
  ASSERT_EQ(r.code, 0) << r.err;
  const AviProblemSet suite = BuildAviSuite(/*quick=*/true);
  EXPECT_THAT(r.out, HasSubstr("wrote suite avi (" + std::to_string(suite.problems.size()) + " AVI files"));
  std::ifstream index(folder + "/index.csv");
  std::string line;
  int rows = -1;  // the header
  while (std::getline(index, line)) ++rows;
  EXPECT_EQ(rows, static_cast<int>(suite.problems.size()));
  bool saw_infeasible = false;
  for (const AviLibraryProblem& p : suite.problems) {
    SCOPED_TRACE(p.id);
    const AviFile file = ReadAviFile(folder + "/" + AviExportFileName(p.id));  // its solution checked on reading
    EXPECT_EQ(file.avi.name(), p.id);
    EXPECT_EQ(file.expected, p.expected);
    EXPECT_TRUE(file.avi.M() == p.problem->M() && file.avi.q() == p.problem->q() && file.avi.H() == p.problem->H() &&
                file.avi.K() == p.problem->K() && file.avi.E() == p.problem->E() && file.avi.f() == p.problem->f());
    if (p.reference.verified()) {
      EXPECT_TRUE(file.solution == p.reference.solution.lambda);
    }
    if (p.expected != ExpectedOutcome::kInfeasible || saw_infeasible) continue;
    // An AVI with no solution, judged from its file: a refusal is correct, never "failed" for want of the
    // expected outcome.
    saw_infeasible = true;
    r = RunSmcbench({"solve", folder + "/" + AviExportFileName(p.id), "--solver", "lemke", "--json"});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto row = nlohmann::json::parse(r.out).at(0);
    EXPECT_NE(row["status"], "solved");
    EXPECT_EQ(row["verdict"], "correctly refused");
  }
  EXPECT_TRUE(saw_infeasible);
}


TEST(SolveAviCli, TheAviSuiteWrittenAsOneSetReadsBackAndIsListed) {
  const ScratchDir dir;
  const std::string file = dir.File("avi.smcps");
  const CliRun r = RunSmcbench({"library", "--write-suite", "avi", file, "--quick"});
  ASSERT_EQ(r.code, 0) << r.err;
  const AviProblemSet suite = BuildAviSuite(/*quick=*/true);
  EXPECT_THAT(r.out, HasSubstr("wrote suite avi (" + std::to_string(suite.problems.size()) +
                                   " AVIs, format version 4) to " + file));
  ProblemSetFileInfo info;
  const AviProblemSet back = ReadAviProblemSetFile(file, &info);
  EXPECT_EQ(info.kind, ProblemSetKind::kAvi);
  ASSERT_EQ(back.problems.size(), suite.problems.size());
  for (std::size_t i = 0; i < suite.problems.size(); ++i) {
    const AviLibraryProblem &a = suite.problems[i], &b = back.problems[i];
    SCOPED_TRACE(a.id);
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.expected, a.expected);
    EXPECT_TRUE(b.problem->M() == a.problem->M() && b.problem->q() == a.problem->q() &&
                b.problem->H() == a.problem->H() && b.problem->K() == a.problem->K());
    EXPECT_TRUE(b.reference.solution.lambda == a.reference.solution.lambda);
  }
  const CliRun listed = RunSmcbench({"library", file, "--list"});
  ASSERT_EQ(listed.code, 0) << listed.err;
  EXPECT_THAT(listed.out, HasSubstr("format version 4 (a set of AVIs)"));
  EXPECT_THAT(listed.out, HasSubstr("AVIs: " + std::to_string(suite.problems.size()) + "\n"));
  EXPECT_THAT(listed.out, HasSubstr("\n" + suite.problems[0].id + " | " + std::to_string(suite.problems[0].size()) +
                                    " | "));
  const CliRun relay = RunSmcbench({"library", file, "--export-relay", dir.File("relay")});
  EXPECT_EQ(relay.code, 1);
  EXPECT_THAT(relay.err, HasSubstr("--export-relay takes a set of box-MLCPs"));
  EXPECT_FALSE(fs::exists(dir.File("relay")));
  // `bench --suite FILE.smcps` plans the AVI suite read from the file: the same problems, by their checksum.
  BenchRequest request;
  request.suites = {file};
  request.solvers = {"lemke"};
  request.quick = true;
  const BenchPlan plan = MakeBenchPlan(request);
  ASSERT_EQ(plan.suites.size(), 1u);
  EXPECT_EQ(plan.suites[0]->kind(), "avi");
  EXPECT_EQ(AviProblemSetChecksum(AviSet(*plan.suites[0])), AviProblemSetChecksum(suite));
  // `solve FILE.smcps --id` solves the AVI of the set as its .avi.json file is solved: same answer, bit for bit.
  const AviLibraryProblem& first = suite.problems[0];
  const CliRun from_set = RunSmcbench({"solve", file, "--id", first.id, "--solver", "lemke", "--json"});
  ASSERT_EQ(from_set.code, 0) << from_set.err;
  const std::string single = dir.File("first.avi.json");
  WriteAviFile(*first.problem, single, Vector(), first.expected);
  const CliRun from_file = RunSmcbench({"solve", single, "--solver", "lemke", "--json"});
  ASSERT_EQ(from_file.code, 0) << from_file.err;
  const nlohmann::json set_row = nlohmann::json::parse(from_set.out).at(0)["results"].at(0);
  const nlohmann::json file_row = nlohmann::json::parse(from_file.out).at(0);
  EXPECT_EQ(set_row["problem"], first.id);
  for (const char* key : {"status", "verdict", "lambda", "mu", "nu", "residual_rel", "complementarity"}) {
    EXPECT_EQ(set_row[key], file_row[key]) << key;
  }
  // A box command refuses it, saying what reads it.
  const CliRun convert = RunSmcbench({"convert", file, dir.File("out.mtx"), "--id", first.id});
  EXPECT_EQ(convert.code, 1);
  EXPECT_THAT(convert.err, HasSubstr("is a set of AVIs (.smcps format version 4), not of box problems: "
                                     "`smcbench solve`"));
}

// A set of AVIs by hand: λ of (0.8, 0.2) on a segment (p = 1) with a stored reference, the corner (1, 1) of the
// unit box without one, and an AVI with no solution. Returns the path it was written to.
std::string WriteHandMadeAviSet(const ScratchDir& dir, AviReference* stored) {
  DenseMatrix box(4, 2);
  box << 1, 0, -1, 0, 0, 1, 0, -1;  // 0 <= λ <= 1
  const Vector box_k = (Vector(4) << 0, -1, 0, -1).finished();
  AviProblemSet set;
  set.name = "hand-made";
  AviLibraryProblem segment;
  segment.id = "hand/segment";
  segment.source = "hand-made:segment";
  // The projection of c = (0.7, 0.1) onto [0, 1]² ∩ {λ₁ + λ₂ = 1} is (0.8, 0.2).
  segment.problem =
      std::make_shared<const AffineVI>(DenseMatrix::Identity(2, 2), (Vector(2) << -0.7, -0.1).finished(), box, box_k,
                                       DenseMatrix::Ones(1, 2), Vector::Ones(1), "hand/segment");
  segment.expected = ExpectedOutcome::kSolvable;
  segment.reference = CertifyAvi(*segment.problem, {AviSolution{(Vector(2) << 0.8, 0.2).finished(), {}, {}}});
  // A condition no certification of this AVI gives (it is 1 or so): the mark that the set's own reference is used.
  segment.reference.reduced.condition = 123.0;
  *stored = segment.reference;
  set.problems.push_back(segment);
  AviLibraryProblem corner;
  corner.id = "hand/corner";
  corner.source = "hand-made:corner";
  // The projection of (2, 3) onto the unit box.
  corner.problem = std::make_shared<const AffineVI>(DenseMatrix::Identity(2, 2), (Vector(2) << -2, -3).finished(),
                                                    box, box_k, "hand/corner");
  corner.expected = ExpectedOutcome::kSolvable;
  set.problems.push_back(corner);
  AviLibraryProblem none;
  none.id = "other/none";
  none.source = "hand-made:no solution";
  // λ >= 0, M = 0, q = -1: 0 ∈ -1 + N_P(λ) has no solution.
  none.problem = std::make_shared<const AffineVI>(DenseMatrix::Zero(1, 1), Vector::Constant(1, -1.0),
                                                  DenseMatrix::Identity(1, 1), Vector::Zero(1), "other/none");
  none.expected = ExpectedOutcome::kInfeasible;
  set.problems.push_back(none);
  const std::string path = dir.File("hand.smcps");
  WriteAviProblemSetFile(set, path);
  return path;
}

TEST(SolveAviCli, ASetOfAvisIsSolvedByIdAndItsAnswersMeetTheKktConditions) {
  const ScratchDir dir;
  AviReference stored;
  const std::string file = WriteHandMadeAviSet(dir, &stored);
  const AviProblemSet set = ReadAviProblemSetFile(file);
  CliRun r = RunSmcbench({"solve", file, "--id", "hand/*", "--solver", "lemke", "enum", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 2u);
  const Vector expected_lambda[2] = {(Vector(2) << 0.8, 0.2).finished(), (Vector(2) << 1, 1).finished()};
  for (std::size_t k = 0; k < 2; ++k) {
    const AffineVI& avi = *set.problems[k].problem;
    EXPECT_EQ(j[k]["problem"], set.problems[k].id);
    EXPECT_EQ(j[k]["n"], 2);
    EXPECT_EQ(j[k]["m"], 4);
    EXPECT_EQ(j[k]["p"], avi.equality_count());
    EXPECT_EQ(j[k]["expected"], "solvable");
    EXPECT_FALSE(j[k].contains("reference"));
    ASSERT_EQ(j[k]["results"].size(), 2u);
    for (const auto& row : j[k]["results"]) {
      SCOPED_TRACE(row.dump());
      EXPECT_EQ(row["problem"], set.problems[k].id);
      EXPECT_EQ(row["verdict"], "solved");
      const Vector lambda = FromJson(row["lambda"]), mu = FromJson(row["mu"]), nu = FromJson(row["nu"]);
      ASSERT_EQ(lambda.size(), 2);
      ASSERT_EQ(mu.size(), 4);
      ASSERT_EQ(nu.size(), avi.equality_count());
      // KKT recomputed from the set's data: Mλ + q − Hᵀμ − Eᵀν = 0, μ ≥ 0, Hλ ≥ K, μᵢ(Hλ − K)ᵢ = 0, Eλ = f.
      EXPECT_LE((avi.M() * lambda + avi.q() - avi.H().transpose() * mu - avi.E().transpose() * nu)
                    .cwiseAbs()
                    .maxCoeff(),
                1e-12);
      const Vector slack = avi.H() * lambda - avi.K();
      EXPECT_GE(mu.minCoeff(), 0.0);
      EXPECT_GE(slack.minCoeff(), -1e-12);
      EXPECT_LE(mu.cwiseProduct(slack).cwiseAbs().maxCoeff(), 1e-12);
      if (avi.equality_count() > 0) {
        EXPECT_LE((avi.E() * lambda - avi.f()).cwiseAbs().maxCoeff(), 1e-12);
      }
      EXPECT_LE((lambda - expected_lambda[k]).cwiseAbs().maxCoeff(), 1e-12);
    }
  }

  // --reference: the set's own reference where it has one (its marked condition), certified here where not.
  r = RunSmcbench({"solve", file, "--id", "hand/segment", "hand/corner", "--solver", "lemke", "--json",
                   "--reference", "--repeat", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json ref = nlohmann::json::parse(r.out);
  ASSERT_EQ(ref.size(), 2u);
  EXPECT_EQ(ref[0]["reference"]["condition"], 123.0);
  EXPECT_EQ(ref[0]["reference"]["certificate"], std::string(ToString(stored.reduced.certificate)));
  EXPECT_TRUE(FromJson(ref[0]["reference"]["lambda"]) == stored.solution.lambda);
  EXPECT_THAT(std::string(ref[1]["reference"]["certificate"]), ::testing::AnyOf("unique", "isolated"));
  EXPECT_TRUE(ref[1]["reference"]["lambda_unique"].get<bool>());  // M = I: strictly monotone
  EXPECT_TRUE(FromJson(ref[1]["reference"]["lambda"]) == expected_lambda[1]);
  for (const auto& entry : ref) {
    const auto& row = entry["results"].at(0);
    EXPECT_EQ(row["repeats"], 2);
    EXPECT_EQ(row["verdict"], "solved");
    ASSERT_TRUE(row["forward_error"].is_number()) << row.dump();
    EXPECT_LE(row["forward_error"].get<double>(), row["forward_allowance"].get<double>());
  }

  // The set's expected outcome judges: a refusal of the AVI with no solution is correct.
  r = RunSmcbench({"solve", file, "--id", "other/none", "--solver", "lemke", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto none = nlohmann::json::parse(r.out).at(0);
  EXPECT_EQ(none["expected"], "infeasible");
  EXPECT_NE(none["results"].at(0)["status"], "solved");
  EXPECT_EQ(none["results"].at(0)["verdict"], "correctly refused");

  // Text: the file's layout, one block per AVI titled by its id.
  r = RunSmcbench({"solve", file, "--solver", "lemke", "--reference"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("hand/segment (AVI: n = 2, m = 4, p = 1, P bounded, expected solvable)\n"
                               "reference: certificate "));
  EXPECT_THAT(r.out, HasSubstr("condition 123,"));
  EXPECT_THAT(r.out, HasSubstr("hand/corner (AVI: n = 2, m = 4, p = 0, P bounded, expected solvable)\n"));
  EXPECT_THAT(r.out, HasSubstr("other/none (AVI: n = 1, m = 1, p = 0, P unbounded, expected infeasible)\n"));
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 3 * 6);  // title, reference, record, λ, μ, ν

  // An unknown id lists what exists; --warm is refused as for an AVI file.
  r = RunSmcbench({"solve", file, "--id", "hand/nope"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--id hand/nope: no such problem in '" + file +
                               "' (3 problems, e.g. hand/segment, hand/corner, other/none; `smcbench library " + file +
                               "` lists them"));
  r = RunSmcbench({"solve", file, "--warm"});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("--warm is not supported for a set of AVIs"));
}

}  // namespace
}  // namespace smcbench
