// End-to-end tests of `smcbench library`, run in-process: the summary of a problem-set file, --list, the Siconos
// relay export (bit-exact files, colliding names, an index, infinite bounds refused with exit status 1), --certify
// on sets of box-MLCPs and of AVIs, and one-line errors for damaged or missing files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "problems/avi_library/avi_library.h"
#include "problems/io/siconos_format.h"
#include "problems/library/problem_set_io.h"
#include "problems/suites/catalogue.h"
#include "solvers/avi/avi_verdict.h"
#include "tools/smcbench/cli_test_runner.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

using test_support::CliRun;
using test_support::RunSmcbench;

LibraryProblem Problem(std::string id, BoxMLCP box, ExpectedOutcome expected) {
  return LibraryProblem{std::move(id), "generated:test", std::move(box), {}, {"handmade"},
                        std::uint64_t{7},  expected,   {}, {}, {}};
}

// Two relay problems whose ids sanitize to the same file name, a sparse box problem and an LCP.
ProblemSet MixedSet() {
  ProblemSet set;
  set.name = "mixed";
  set.description = "relay, sparse box and LCP rows";
  DenseMatrix M(2, 2);
  M << 2, -1, -1, 2;
  Vector q(2);
  q << 0.5, -1.0 / 3.0;
  set.problems.push_back(Problem("a/b", BoxMLCP::Relay(M, q), ExpectedOutcome::kSolvable));
  set.problems.push_back(Problem("a_b", BoxMLCP::Relay(M, -q, -2.0, 0.5), ExpectedOutcome::kSolvable));
  set.problems.push_back(Problem("sparse/box", BoxMLCP(SparseMatrix(M.sparseView()), q, Vector::Constant(2, -1e-300),
                                                       Vector::Constant(2, 3.0)),
                                 ExpectedOutcome::kUnknown));
  set.problems.push_back(Problem("lcp/one", BoxMLCP::LCP(M, q), ExpectedOutcome::kInfeasible));
  set.problems[0].matrix = {Tristate::kYes, Tristate::kYes, Tristate::kYes};
  return set;
}

class LibraryCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(testing::TempDir()) / ("library_command_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

TEST_F(LibraryCommandTest, SummaryAndList) {
  const std::string file = Path("mixed.smcps");
  WriteProblemSetFile(MixedSet(), file);
  CliRun r = RunSmcbench({"library", file});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_THAT(r.out, HasSubstr("set mixed: relay, sparse box and LCP rows\n"));
  EXPECT_THAT(r.out, HasSubstr("format version " + std::to_string(kProblemSetFormatVersion) +
                               ", 2 distinct matrices for 4 problems"));
  EXPECT_THAT(r.out, HasSubstr("problems: 4 (dense 3, sparse 1)\n"));
  EXPECT_THAT(r.out, HasSubstr("sizes: n=2 x4\n"));
  EXPECT_THAT(r.out, HasSubstr("bounds: relay/box 3, lcp 1\n"));
  EXPECT_THAT(r.out, HasSubstr("expected: solvable 2, infeasible 1, unknown 1\n"));
  EXPECT_THAT(r.out, HasSubstr("references: none 4\n"));
  EXPECT_THAT(r.out, HasSubstr("  P-matrix           1 / 0 / 3\n"));
  EXPECT_THAT(r.out, HasSubstr("sources: generated 4\n"));
  EXPECT_THAT(r.out, HasSubstr("labels: handmade 4\n"));
  EXPECT_THAT(r.out, HasSubstr("seeded: 4, with a known solution: 0\n"));
  EXPECT_THAT(r.out, Not(HasSubstr("a/b |")));

  r = RunSmcbench({"library", file, "--list"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("a/b | 2 | dense | solvable | yyy | none | -\n"));
  EXPECT_THAT(r.out, HasSubstr("sparse/box | 2 | sparse | unknown | ??? | none | -\n"));
}

TEST_F(LibraryCommandTest, ExportRelayWritesBitExactFilesAndRefusesInfiniteBounds) {
  const std::string file = Path("mixed.smcps"), out = Path("relay");
  const ProblemSet set = MixedSet();
  WriteProblemSetFile(set, file);
  const CliRun r = RunSmcbench({"library", file, "--export-relay", out});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.out, HasSubstr("exported 3 of 4 problem(s) to " + out));
  EXPECT_THAT(r.err, HasSubstr("lcp/one: row 0 has l = 0, u = inf (an LCP row)\n"));
  EXPECT_THAT(r.err, HasSubstr("1 problem(s) cannot be written in Siconos relay format"));
  // Colliding names get a suffix; the index maps files back to ids.
  const std::vector<std::pair<std::string, int>> files = {{"a_b.dat", 0}, {"a_b-2.dat", 1}, {"sparse_box.dat", 2}};
  for (const auto& [name, index] : files) {
    SCOPED_TRACE(name);
    const BoxMLCP back = ReadSiconosFile((fs::path(out) / name).string(), SiconosKind::kRelay);
    const BoxMLCP& original = set.problems[static_cast<std::size_t>(index)].problem;
    const DenseMatrix M = original.ToDense();
    EXPECT_EQ(std::memcmp(back.dense_matrix().data(), M.data(), sizeof(double) * 4), 0);
    EXPECT_EQ(std::memcmp(back.q().data(), original.q().data(), sizeof(double) * 2), 0);
    EXPECT_EQ(std::memcmp(back.l().data(), original.l().data(), sizeof(double) * 2), 0);
    EXPECT_EQ(std::memcmp(back.u().data(), original.u().data(), sizeof(double) * 2), 0);
  }
  EXPECT_FALSE(fs::exists(fs::path(out) / "lcp_one.dat"));
  std::ifstream in(fs::path(out) / "index.csv");
  const std::string index((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(index,
            "file,id,n,expected\na_b.dat,a/b,2,solvable\na_b-2.dat,a_b,2,solvable\nsparse_box.dat,sparse/box,2,unknown\n");
}

TEST_F(LibraryCommandTest, RecordedRunExportsEveryStep) {
  const std::string file = Path("lyapunov.smcps"), out = Path("steps");
  CliRun r = RunSmcbench({"simulate", "lyapunov", "--record", file});
  ASSERT_EQ(r.code, 0) << r.err;
  r = RunSmcbench({"library", file, "--export-relay", out});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("set capture: one-step problems of smcbench simulate lyapunov"));
  EXPECT_THAT(r.out, HasSubstr("1 distinct matrix for 100 problems"));
  EXPECT_THAT(r.out, HasSubstr("expected: solvable 100\n"));
  EXPECT_THAT(r.out, HasSubstr("exported 100 of 100 problem(s)"));
  EXPECT_TRUE(fs::exists(fs::path(out) / "capture_lyapunov_implicit_h0.1_k100.dat"));
  // Every exported file is a relay problem the Siconos reader accepts.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(out)) {
    if (entry.path().extension() != ".dat") continue;
    EXPECT_NO_THROW(ReadSiconosFile(entry.path().string(), SiconosKind::kRelay)) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 100);
}

// M = [[2, −1], [−1, 2]], q = (½, −⅓), relay: z = −M⁻¹q = −(1/3)[[2, 1], [1, 2]] q = (−2/9, 1/18), both rows
// inside [−1, 1], so w = 0 and the solution is unique (M is SPD). Row scales 2: D⁻¹M = [[1, −½], [−½, 1]], whose
// inverse (4/3)[[1, ½], [½, 1]] has ∞-norm 2 = μ. A 5×5 problem above --certify-max-size 4, and an LCP with
// w = −z − 1 < 0 for every z ≥ 0 (no solution).
// Output paths are checked before any work: building and certifying a suite takes seconds, so a file where a folder
// is needed (or the other way round) fails at once, naming the flag, and nothing is written.
TEST_F(LibraryCommandTest, OutputPathsAreRefusedBeforeAnyWork) {
  const std::string file = Path("a-file.txt");
  std::ofstream(file) << "not a folder\n";
  const auto expect_refused = [&](std::initializer_list<std::string> args, std::initializer_list<const char*> parts) {
    const CliRun r = RunSmcbench(args);
    EXPECT_EQ(r.code, 1) << r.out << r.err;
    EXPECT_EQ(r.out, "");  // no summary, no "certified ..." line: it stopped before reading or building anything
    for (const char* part : parts) EXPECT_THAT(r.err, HasSubstr(part));
  };
  // avi to a folder: a file is refused before the suite is built (and certified).
  expect_refused({"library", "--write-suite", "avi", file}, {"--write-suite", "a-file.txt", "is a file"});
  expect_refused({"library", "--write-suite", "tiny", Path("missing/tiny.smcps")},
                 {"--write-suite", "its folder", "does not exist"});
  expect_refused({"library", "--write-suite", "tiny", dir_.string()}, {"--write-suite", "is a folder"});
  expect_refused({"library", file, "--certify", dir_.string()}, {"--certify", "is a folder"});
  expect_refused({"library", file, "--export-relay", file}, {"--export-relay", "is a file"});
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir_)) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"a-file.txt"});
}

TEST_F(LibraryCommandTest, CertifyAttachesReferencesAndWritesTheSet) {
  ProblemSet set;
  set.name = "certify";
  DenseMatrix M(2, 2);
  M << 2, -1, -1, 2;
  Vector q(2);
  q << 0.5, -1.0 / 3.0;
  set.problems.push_back(Problem("relay/two", BoxMLCP::Relay(M, q), ExpectedOutcome::kSolvable));
  set.problems.push_back(Problem("lcp/none", BoxMLCP::LCP(DenseMatrix::Constant(1, 1, -1.0), Vector::Constant(1, -1.0)),
                                 ExpectedOutcome::kInfeasible));
  set.problems.push_back(Problem("relay/five", BoxMLCP::Relay(DenseMatrix::Identity(5, 5), Vector::Constant(5, 0.5)),
                                 ExpectedOutcome::kSolvable));
  const std::string file = Path("in.smcps"), certified = Path("certified.smcps");
  WriteProblemSetFile(set, file);
  CliRun r = RunSmcbench({"library", file, "--certify", certified, "--certify-max-size", "4", "--list"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("references: none 3\n"));  // the summary of the file as read
  EXPECT_THAT(r.out, HasSubstr("certified 2 problem(s) in "));
  EXPECT_THAT(r.out, HasSubstr("(kept 0 existing reference(s); 1 above 4 rows left without)\n"));
  EXPECT_THAT(r.out, HasSubstr("references: none 1, none found 1, unique 1\n"));
  EXPECT_THAT(r.out, HasSubstr("wrote " + certified + " (format version " +
                               std::to_string(kProblemSetFormatVersion) + ")\n"));
  EXPECT_THAT(r.out, HasSubstr("relay/two | 2 | dense | solvable | ??? | unique | 2\n"));
  EXPECT_THAT(r.out, HasSubstr("lcp/none | 1 | dense | infeasible | ??? | none found | -\n"));
  EXPECT_THAT(r.out, HasSubstr("relay/five | 5 | dense | solvable | ??? | none | -\n"));

  ProblemSetFileInfo info;
  const ProblemSet back = ReadProblemSetFile(certified, &info);
  EXPECT_EQ(info.version, kProblemSetFormatVersion);
  ASSERT_EQ(back.problems.size(), 3u);
  const ReferenceSolution& two = back.problems[0].reference;
  ASSERT_EQ(two.certificate, Certificate::kUnique);
  EXPECT_NEAR(two.z[0], -2.0 / 9.0, 1e-16);
  EXPECT_NEAR(two.z[1], 1.0 / 18.0, 1e-16);
  EXPECT_NEAR(two.condition, 2.0, 1e-15);
  EXPECT_EQ(back.problems[1].reference.certificate, Certificate::kNoneFound);
  EXPECT_EQ(back.problems[2].reference.certificate, Certificate::kNone);

  // Certifying the certified file again keeps what is there and, with the default limit, adds the 5×5 one.
  r = RunSmcbench({"library", certified, "--certify", certified});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("certified 1 problem(s) in "));
  EXPECT_THAT(r.out, HasSubstr("(kept 2 existing reference(s); 0 above 64 rows left without)\n"));
  EXPECT_EQ(ReadProblemSetFile(certified).problems[2].reference.certificate, Certificate::kUnique);

  EXPECT_EQ(RunSmcbench({"library", file, "--certify", certified, "--certify-max-size", "0"}).code, 2);
}

// A version-1 file (written before references existed) is read, certified, and written in the current version.
TEST_F(LibraryCommandTest, CertifyUpgradesAVersionOneFile) {
  const std::string v1 = std::string(SMCBENCH_SOURCE_DIR) + "/problems/library/testdata/format-v1-sign.smcps";
  const std::string out = Path("sign-certified.smcps");
  const CliRun r = RunSmcbench({"library", v1, "--certify", out});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("format version 1,"));
  ProblemSetFileInfo info;
  const ProblemSet set = ReadProblemSetFile(out, &info);
  EXPECT_EQ(info.version, kProblemSetFormatVersion);
  for (const LibraryProblem& p : set.problems) {
    // S1's one-step problems: 1×1, M = h > 0, relay bounds: a unique solution, which the run's z approximates.
    EXPECT_TRUE(p.reference.unique()) << p.id;
    EXPECT_LE(std::abs(p.reference.z[0] - p.solution[0]), ForwardErrorAllowance(p.reference, 1e-10)) << p.id;
  }
}

// The file says "infeasible" but a solution is verified: the file is wrong; one line, exit 1, nothing written.
TEST_F(LibraryCommandTest, CertifyRefusesAnInfeasibleProblemWithASolution) {
  const std::string file = Path("mixed.smcps"), out = Path("never.smcps");
  WriteProblemSetFile(MixedSet(), file);  // "lcp/one" is an SPD LCP (it has a solution) marked infeasible
  const CliRun r = RunSmcbench({"library", file, "--certify", out});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("smcbench: --certify: problem 'lcp/one' is expected infeasible"));
  EXPECT_THAT(r.err, HasSubstr("nothing was written"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(LibraryCommandTest, DamagedOrMissingFilesAreOneLineErrors) {
  const std::string file = Path("mixed.smcps");
  WriteProblemSetFile(MixedSet(), file);
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x7f');
  }
  CliRun r = RunSmcbench({"library", file});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("problem set '" + file + "'"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;

  r = RunSmcbench({"library", Path("missing.smcps")});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("cannot open"));

  std::ofstream(Path("text.smcps")) << "not a problem set\n";
  r = RunSmcbench({"library", Path("text.smcps")});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("not a smcbench problem-set file"));

  EXPECT_EQ(RunSmcbench({"library"}).code, 2);  // FILE is required
}

// A 2-D AVI on the unit box 0 <= λ <= 1 (with M = I: the projection of -q onto it), with equalities E, f if given.
std::shared_ptr<const AffineVI> UnitBoxAvi(const std::string& id, double q0, double q1, DenseMatrix E = {},
                                           Vector f = {}) {
  DenseMatrix H(4, 2);
  H << 1, 0, -1, 0, 0, 1, 0, -1;
  const Vector K = (Vector(4) << 0, -1, 0, -1).finished();
  if (E.size() == 0) E = DenseMatrix(0, 2);
  return std::make_shared<const AffineVI>(DenseMatrix::Identity(2, 2), (Vector(2) << q0, q1).finished(), H, K, E,
                                          f, id);
}

AviLibraryProblem AviEntry(const std::string& id, std::shared_ptr<const AffineVI> avi, ExpectedOutcome expected) {
  AviLibraryProblem p;
  p.id = id;
  p.source = "hand-made:test";
  p.problem = std::move(avi);
  p.expected = expected;
  return p;
}

// `library FILE.smcps --certify OUT` on a set of AVIs: references for the AVIs that have none, within the limit on
// the reduction's rows n + m + p; existing ones kept; written as a set of AVIs that reads back.
TEST_F(LibraryCommandTest, CertifyAttachesReferencesToASetOfAvis) {
  AviProblemSet set;
  set.name = "avis";
  // n + m + p = 7 rows: above the limit 6 below. The projection of (0.7, 0.1) onto the box ∩ {λ₁ + λ₂ = 1}.
  set.problems.push_back(AviEntry("avi/segment", UnitBoxAvi("avi/segment", -0.7, -0.1, DenseMatrix::Ones(1, 2),
                                                            Vector::Ones(1)),
                                  ExpectedOutcome::kSolvable));
  // 6 rows: the projection of (2, 3) onto the box is the corner (1, 1).
  set.problems.push_back(AviEntry("avi/corner", UnitBoxAvi("avi/corner", -2, -3), ExpectedOutcome::kSolvable));
  set.problems[1].metadata = {{"certificate", "none"}, {"lambda_unique", "no"}, {"why", "a corner"}};
  // Already certified: kept as it is (its condition marked).
  set.problems.push_back(AviEntry("avi/kept", UnitBoxAvi("avi/kept", -0.5, -0.25), ExpectedOutcome::kSolvable));
  set.problems[2].reference =
      CertifyAvi(*set.problems[2].problem, {AviSolution{(Vector(2) << 0.5, 0.25).finished(), {}, {}}});
  ASSERT_TRUE(set.problems[2].reference.verified());
  set.problems[2].reference.reduced.condition = 77.0;
  // λ >= 0, M = 0, q = -1: no solution, nothing to verify.
  set.problems.push_back(AviEntry("avi/none",
                                  std::make_shared<const AffineVI>(DenseMatrix::Zero(1, 1), Vector::Constant(1, -1.0),
                                                                   DenseMatrix::Identity(1, 1), Vector::Zero(1),
                                                                   "avi/none"),
                                  ExpectedOutcome::kInfeasible));
  const std::string file = Path("avis.smcps"), certified = Path("avis-certified.smcps");
  WriteAviProblemSetFile(set, file);
  CliRun r = RunSmcbench({"library", file, "--certify", certified, "--certify-max-size", "6", "--list"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("certified 2 AVI(s) in "));
  EXPECT_THAT(r.out, HasSubstr("(kept 1 existing reference(s); 1 with more than 6 rows n + m + p left without)\n"));
  EXPECT_THAT(r.out, HasSubstr("wrote " + certified + " (format version " +
                               std::to_string(kAviProblemSetFormatVersion) + ")\n"));
  EXPECT_THAT(r.out, HasSubstr("\navi/segment | 2 | 4 | 1 | solvable | none | -\n"));  // --list shows the new set
  EXPECT_THAT(r.out, HasSubstr("\navi/none | 1 | 1 | 0 | infeasible | none found | -\n"));

  ProblemSetFileInfo info;
  AviProblemSet back = ReadAviProblemSetFile(certified, &info);
  EXPECT_EQ(info.version, kAviProblemSetFormatVersion);
  ASSERT_EQ(back.problems.size(), 4u);
  EXPECT_EQ(back.problems[0].reference.reduced.certificate, Certificate::kNone);
  const AviReference& corner = back.problems[1].reference;
  ASSERT_TRUE(corner.verified());
  EXPECT_TRUE(corner.lambda_unique);  // M = I: strictly monotone
  EXPECT_EQ(corner.solution.lambda, (Vector(2) << 1, 1).finished());
  // μ recomputed here: Mλ + q = Hᵀμ at λ = (1, 1) with the upper rows active gives μ = (0, 1, 0, 2).
  EXPECT_LE((corner.solution.mu - (Vector(4) << 0, 1, 0, 2).finished()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(back.problems[1].metadata.at("certificate"), std::string(ToString(corner.reduced.certificate)));
  EXPECT_EQ(back.problems[1].metadata.at("lambda_unique"), "yes");
  EXPECT_EQ(back.problems[1].metadata.at("why"), "a corner");
  EXPECT_EQ(back.problems[2].reference.reduced.condition, 77.0);
  EXPECT_TRUE(back.problems[2].reference.solution.lambda == set.problems[2].reference.solution.lambda);
  EXPECT_EQ(back.problems[3].reference.reduced.certificate, Certificate::kNoneFound);

  // Certifying the certified file in place with the default limit adds the segment.
  r = RunSmcbench({"library", certified, "--certify", certified});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("certified 1 AVI(s) in "));
  EXPECT_THAT(r.out, HasSubstr("(kept 3 existing reference(s); 0 with more than 64 rows n + m + p left without)\n"));
  back = ReadAviProblemSetFile(certified);
  const AviReference& segment = back.problems[0].reference;
  ASSERT_TRUE(segment.verified());
  EXPECT_LE((segment.solution.lambda - (Vector(2) << 0.8, 0.2).finished()).cwiseAbs().maxCoeff(), 1e-15);
}

// An AVI the set says has no solution, but which has one (λ = 1 on λ >= 0 with M = 1, q = -1): the set is wrong;
// one line, exit 1, nothing written.
TEST_F(LibraryCommandTest, CertifyRefusesAnAviExpectedInfeasibleThatHasASolution) {
  AviProblemSet set;
  set.name = "wrong";
  set.problems.push_back(AviEntry("avi/wrong",
                                  std::make_shared<const AffineVI>(DenseMatrix::Ones(1, 1), Vector::Constant(1, -1.0),
                                                                   DenseMatrix::Identity(1, 1), Vector::Zero(1),
                                                                   "avi/wrong"),
                                  ExpectedOutcome::kInfeasible));
  const std::string file = Path("wrong.smcps"), out = Path("never.smcps");
  WriteAviProblemSetFile(set, file);
  const CliRun r = RunSmcbench({"library", file, "--certify", out});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("smcbench: --certify: AVI 'avi/wrong' is expected infeasible, but CertifyAvi "
                               "verified a solution"));
  EXPECT_THAT(r.err, HasSubstr("nothing was written"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(out + ".partial"));
}

// `library --write-suite NAME FILE`: the built-in suite frozen to a file, bit for bit the problems BuildSuite makes,
// with their certified references; an unknown suite name is a one-line error.
TEST_F(LibraryCommandTest, WriteSuiteFreezesABuiltInSuite) {
  const std::string file = Path("tiny.smcps");
  CliRun r = RunSmcbench({"library", "--write-suite", "tiny", file});
  ASSERT_EQ(r.code, 0) << r.err;
  const ProblemSet built = BuildSuite("tiny", SuiteRequest{});
  EXPECT_EQ(r.out, "wrote suite tiny (5 problems, checksum " + ProblemSetContentChecksum(built) + ") to " + file +
                       "\n");
  const ProblemSet read = ReadProblemSetFile(file);
  EXPECT_EQ(read.name, "tiny");
  ASSERT_EQ(read.problems.size(), built.problems.size());
  for (std::size_t i = 0; i < read.problems.size(); ++i) {
    EXPECT_EQ(read.problems[i].id, built.problems[i].id);
    EXPECT_EQ(read.problems[i].problem.q(), built.problems[i].problem.q());
    EXPECT_EQ(read.problems[i].reference.certificate, built.problems[i].reference.certificate);
  }
  EXPECT_NE(read.problems[0].reference.certificate, Certificate::kNone);  // references attached
  EXPECT_EQ(ProblemSetContentChecksum(read), ProblemSetContentChecksum(built));

  r = RunSmcbench({"library", "--write-suite", "nope", Path("nope.smcps")});
  EXPECT_EQ(r.code, 1);
  EXPECT_THAT(r.err, HasSubstr("unknown suite 'nope'"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  EXPECT_FALSE(fs::exists(Path("nope.smcps")));
}

}  // namespace
}  // namespace smcbench
