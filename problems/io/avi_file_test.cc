// The AVI file: a bit-for-bit round trip of random AVIs full of awkward doubles, every error path of the reader
// (each message names the file and the field), the hand-written example of docs/formats.md read and solved, and
// the regressions of hostile inputs (a key with a control byte, deep nesting, rows that claim a huge matrix).
#include "problems/io/avi_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "solvers/avi/avi_solver.h"
#include "solvers/generators/seeded_random.h"
#include "solvers/registry/registry.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kExample = std::string(SMCBENCH_SOURCE_DIR) + "/problems/io/testdata/twisting-projection.avi.json";

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::uint64_t Bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Equal bit for bit (so -0.0 differs from 0.0), entry by entry.
void ExpectSameBits(const DenseMatrix& a, const DenseMatrix& b, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    for (Eigen::Index j = 0; j < a.cols(); ++j) {
      EXPECT_EQ(Bits(a(i, j)), Bits(b(i, j))) << what << "(" << i << "," << j << "): " << a(i, j) << " vs " << b(i, j);
    }
  }
}

// Doubles whose text is easy to get wrong: signed zero, subnormals, the extremes, values with no short decimal,
// integers past 2^53, and full-mantissa random values across many decades.
double Awkward(SeededRandom& rng) {
  static const double kSpecial[] = {-0.0,   0.1,     1.0 / 3.0, -2.0 / 3.0, 5e-324, -4.9406564584124654e-324,
                                    DBL_MIN, DBL_MAX, -DBL_MAX,  1e23,       9007199254740993.0, 1e21,
                                    1e-7,   123456789012345678.0, 0.30000000000000004, -1e-300};
  if (rng.Index(3) == 0) return kSpecial[rng.Index(static_cast<int>(std::size(kSpecial)))];
  return rng.Uniform(-1.0, 1.0) * std::pow(10.0, rng.Index(40) - 20);
}

// A random AVI with awkward numbers everywhere; P contains the box [-1, 1]ⁿ ∩ {Eλ = 0} (each row of H has K_i ≤
// −‖H_i‖₁ − 1), so it is never empty.
AffineVI RandomAwkwardAvi(int n, int m, int p, std::uint64_t seed) {
  SeededRandom rng(seed);
  DenseMatrix M(n, n);
  Vector q(n);
  for (int i = 0; i < n; ++i) {
    q[i] = Awkward(rng);
    for (int j = 0; j < n; ++j) M(i, j) = Awkward(rng);
  }
  DenseMatrix H(m, n);
  Vector K(m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < n; ++j) H(i, j) = rng.Uniform(-1.0, 1.0) * std::pow(10.0, rng.Index(6) - 3);
    H(i, i % n) = i % 2 == 0 ? 0.1 : -1.0 / 3.0;  // never a zero row
    K[i] = -H.row(i).cwiseAbs().sum() - 1.0 - rng.Uniform();
  }
  DenseMatrix E(p, n);
  Vector f(p);
  for (int j = 0; j < p; ++j) {
    for (int k = 0; k < n; ++k) E(j, k) = rng.Uniform(-1.0, 1.0);
    E(j, j % n) = 1.0 / 3.0;
    f[j] = j % 2 == 0 ? -0.0 : 0.0;
  }
  return AffineVI(M, q, H, K, E, f, "awkward-" + std::to_string(seed) + " \"quoted\" \\ λ");
}

TEST(AviFile, RandomAwkwardAvisRoundTripBitForBit) {
  const fs::path dir = fs::temp_directory_path() / ("avi_file_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  int count = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const int n = 1 + static_cast<int>(seed % 5), m = static_cast<int>(seed % 4) * 2;
    const AffineVI avi = RandomAwkwardAvi(n, m, seed % 3 == 0 ? 1 : 0, seed);
    const std::string path = (dir / ("a" + std::to_string(seed) + ".avi.json")).string();
    WriteAviFile(avi, path);
    const AviFile back = ReadAviFile(path);
    EXPECT_EQ(back.avi.name(), avi.name());
    ExpectSameBits(back.avi.M(), avi.M(), "M");
    ExpectSameBits(back.avi.q(), avi.q(), "q");
    ExpectSameBits(back.avi.H(), avi.H(), "H");
    ExpectSameBits(back.avi.K(), avi.K(), "K");
    ExpectSameBits(back.avi.E(), avi.E(), "E");
    ExpectSameBits(back.avi.f(), avi.f(), "f");
    EXPECT_EQ(back.solution.size(), 0);
    // Writing what was read gives the same text: the format is a fixed point.
    EXPECT_EQ(AviFileText(back.avi), ReadAll(path));
    ++count;
  }
  EXPECT_EQ(count, 12);
  fs::remove_all(dir);
}

TEST(AviFile, ASolutionRoundTripsAndIsChecked) {
  // The projection of c onto P = [0, 1]² ∩ {λ₁ + λ₂ = 1} (M = I, q = −c): an equality block, and a solution.
  DenseMatrix H(4, 2);
  H << 1, 0, -1, 0, 0, 1, 0, -1;
  const Vector K = (Vector(4) << 0, -1, 0, -1).finished();
  DenseMatrix E(1, 2);
  E << 1, 1;
  const Vector f = Vector::Constant(1, 1.0);
  // c = (0.7, 0.1): its projection onto the segment λ₁ + λ₂ = 1 in [0, 1]² is (0.8, 0.2).
  const AffineVI avi(DenseMatrix::Identity(2, 2), -(Vector(2) << 0.7, 0.1).finished(), H, K, E, f, "segment");
  const Vector solution = (Vector(2) << 0.8, 0.2).finished();
  const std::string text = AviFileText(avi, solution);
  const AviFile back = ParseAviText(text, "segment.avi.json");
  ExpectSameBits(back.solution, solution, "solution");
  ExpectSameBits(back.avi.E(), E, "E");
  EXPECT_EQ(AviFileText(back.avi, back.solution), text);

  // A wrong reference is refused, naming the field and what failed.
  const std::string wrong = AviFileText(avi, (Vector(2) << 0.5, 0.5).finished());
  try {
    ParseAviText(wrong, "segment.avi.json");
    FAIL() << "a wrong solution was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("AVI file 'segment.avi.json': \"solution\": does not solve the AVI"));
  }
  EXPECT_THROW(AviFileText(avi, Vector::Zero(3)), InvalidInputError);
  EXPECT_THROW(AviFileText(avi, (Vector(2) << 0.8, kNaN).finished()), InvalidInputError);
}

// The example's text with one edit: `from` replaced by `to` (which must occur).
std::string Edited(const std::string& from, const std::string& to) {
  std::string text = ReadAll(kExample);
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseAviText(text, "bad.avi.json");
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(AviFile, EveryDefectNamesTheFileAndTheField) {
  struct Case {
    std::string from, to, message;
  };
  const Case cases[] = {
      // the kind
      {"\"format\": \"smcbench-avi\",", "", "\"format\": missing"},
      {"smcbench-avi", "siconos-avi", "\"format\": expected \"smcbench-avi\", got string \"siconos-avi\""},
      {"\"version\": 1,", "", "\"version\": missing"},
      {"\"version\": 1", "\"version\": 2", "\"version\": unsupported version number 2"},
      {"\"version\": 1", "\"version\": \"1\"", "\"version\": unsupported version string \"1\""},
      // keys
      {"\"name\"", "\"nmae\"",
       "\"nmae\": unknown key (known: format, version, name, M, q, H, K, E, f, solution, expected)"},
      {"\"q\": [-2, -3],", "", "\"q\": missing"},
      {"\"K\": [-1, -1, -1, -1],", "", "\"K\": missing"},
      {"\"K\"", "\"E\": [[1, 1]], \"K\"", "\"f\": missing: E and f come together (E is given)"},
      {"\"K\"", "\"f\": [1], \"K\"", "\"E\": missing: E and f come together (f is given)"},
      // types and values
      {"\"name\": \"twisting-projection\"", "\"name\": 3", "\"name\": expected a string, got number 3"},
      {"[-2, -3]", "[-2, \"nan\"]", "\"q[1]\": expected a number, got string \"nan\""},
      {"[-2, -3]", "[-2, null]", "\"q[1]\": expected a number, got null"},
      {"[-2, -3]", "[-2, true]", "\"q[1]\": expected a number, got boolean true"},
      {"[-2, -3]", "[-2, 1e400]", "not valid JSON: [json.exception.out_of_range.406] number overflow parsing '1e400'"},
      {"[-2, -3]", "{\"a\": 1}", "\"q\": expected an array, got object"},
      {"[0, 1]\n  ]", "[0, \"Infinity\"]\n  ]", "\"M[1][1]\": expected a number, got string \"Infinity\""},
      // sizes
      {"[-2, -3]", "[]", "\"q\": is empty"},
      {"[-2, -3]", "[-2, -3, 4]", "\"M\": has 2 rows, expected 3"},
      {"[0, 1]\n  ]", "[0, 1, 2]\n  ]", "\"M[1]\": has 3 entries, expected 2 (n = the size of q): a ragged matrix"},
      {"[0.05, -1]", "[0.05]", "\"H[3]\": has 1 entries, expected 2"},
      {"[-1, -1, -1, -1]", "[-1, -1, -1]", "\"K\": has 3 entries, expected 4 (one per row of H)"},
      {"\"solution\": [1, 1.05]", "\"solution\": [1]", "\"solution\": has 1 entries, expected 2"},
      // the AffineVI's own checks, with the file named
      {"[0.05, -1]", "[0, 0]", "H row 3 is zero"},
      {"\"K\": [-1, -1, -1, -1]", "\"K\": [-1, 2, -1, -1]", "is empty"},
      // the expected outcome
      {"\"solution\": [1, 1.05]", "\"expected\": \"maybe\"",
       "\"expected\": expected \"solvable\", \"infeasible\" or \"unknown\", got string \"maybe\""},
      {"\"solution\": [1, 1.05]", "\"solution\": [1, 1.05], \"expected\": \"infeasible\"",
       "\"expected\": \"infeasible\" contradicts the \"solution\""},
      {"\"solution\": [1, 1.05]", "\"expected\": \"infeasible\"", "\"expected\": \"infeasible\", but P is bounded"},
      {"\"K\": [-1, -1, -1, -1]", "\"K\": [-1, -1, -1, -1], \"q\": [1, 2]", "\"q\": given twice"},
      // not JSON at all
      {"\"version\": 1,", "\"version\": 1,,", "not valid JSON"},
  };
  for (const Case& c : cases) {
    const std::string message = ErrorOf(Edited(c.from, c.to));
    EXPECT_THAT(message, HasSubstr("AVI file 'bad.avi.json': ")) << c.message;
    EXPECT_THAT(message, HasSubstr(c.message)) << "edit " << c.from << " -> " << c.to;
  }
  EXPECT_THAT(ErrorOf("[1, 2]"), HasSubstr("expected a JSON object, got array"));
  // ReadAviFile names the path it was given.
  try {
    ReadAviFile("/nonexistent/x.avi.json");
    FAIL() << "no error for a missing file";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("AVI file '/nonexistent/x.avi.json': cannot open"));
  }
}

TEST(AviFile, TheDocsExampleIsThisFileAndSolves) {
  const std::string text = ReadAll(kExample);
  // docs/formats.md prints this file verbatim, so the example a reader copies is the one tested here.
  const std::string docs = ReadAll(std::string(SMCBENCH_SOURCE_DIR) + "/docs/formats.md");
  EXPECT_NE(docs.find("```json\n" + text + "```"), std::string::npos) << "docs/formats.md no longer shows " << kExample;

  const AviFile file = ReadAviFile(kExample);
  EXPECT_EQ(file.avi.name(), "twisting-projection");
  EXPECT_EQ(file.avi.size(), 2);
  EXPECT_EQ(file.avi.inequality_count(), 4);
  EXPECT_EQ(file.avi.equality_count(), 0);
  EXPECT_EQ(AviFileText(file.avi, file.solution), text);  // hand-written in the writer's own layout
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  const AviResult r = SolveAvi(file.avi, *lemke);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(r.judgement.verdict, Verdict::kSolved);
  // By hand: λ = (1, 1.05) on rows 1 and 3 (λ₁ ≤ 1, λ₂ − 0.05λ₁ ≤ 1), and λ − c = (−1, −1.95) = Hᵀμ with
  // μ₃ = 1.95 (second coordinate) and μ₁ = 1 + 0.05·1.95 = 1.0975 (first).
  EXPECT_NEAR(r.solution.lambda[0], 1.0, 1e-12);
  EXPECT_NEAR(r.solution.lambda[1], 1.05, 1e-12);
  EXPECT_NEAR(r.solution.mu[1], 1.0975, 1e-12);
  EXPECT_NEAR(r.solution.mu[3], 1.95, 1e-12);
  EXPECT_NEAR((r.solution.lambda - file.solution).cwiseAbs().maxCoeff(), 0.0, 1e-12);
}

TEST(AviFile, TheExpectedOutcomeIsTheFilesOrTheBoundednessRule) {
  // λ ≥ 0 with M = 0, q = −1 has no solution; P is unbounded, so only the file can say "infeasible".
  const AffineVI none(DenseMatrix::Zero(1, 1), Vector::Constant(1, -1.0), DenseMatrix::Identity(1, 1),
                      Vector::Zero(1), "no-solution");
  const std::string stated = AviFileText(none, {}, ExpectedOutcome::kInfeasible);
  EXPECT_THAT(stated, HasSubstr("\"expected\": \"infeasible\""));
  const AviFile back = ParseAviText(stated, "none.avi.json");
  EXPECT_EQ(back.expected, ExpectedOutcome::kInfeasible);
  EXPECT_EQ(AviFileText(back.avi, back.solution, back.expected), stated);
  EXPECT_EQ(ParseAviText(AviFileText(none), "none.avi.json").expected, ExpectedOutcome::kUnknown);  // unbounded P
  EXPECT_EQ(ReadAviFile(kExample).expected, ExpectedOutcome::kSolvable);                           // bounded P
}

TEST(AviFile, ExtensionAndDefaultName) {
  EXPECT_TRUE(HasAviFileExtension("a/b.avi.json"));
  EXPECT_TRUE(HasAviFileExtension("B.AVI.JSON"));
  EXPECT_FALSE(HasAviFileExtension("scene.json"));
  EXPECT_FALSE(HasAviFileExtension(".avi.json"));
  // Without "name", the file's stem names the AVI.
  const fs::path dir = fs::temp_directory_path() / ("avi_file_name_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "my-problem.avi.json").string();
  std::ofstream(path) << Edited("\"name\": \"twisting-projection\",", "");
  EXPECT_EQ(ReadAviFile(path).avi.name(), "my-problem");
  fs::remove_all(dir);
}


// ------------------------------------------------------------------------------------------------------------
// Regressions: the first found by tests/fuzz/avi_fuzzer.cc, the other two while writing it (their inputs are
// larger than the fuzzer's 4 KB)

TEST(AviFileFuzzRegression, AKeyWithAControlByteGivesAOneLineError) {
  const std::string message = ErrorOf(R"({"format": "smcbench-avi", "version": 1, "a\nb": 1})");
  EXPECT_THAT(message, HasSubstr("\"a\\x0ab\": unknown key"));
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(AviFileRegression, DeeplyNestedArraysAreAnErrorNotAStackOverflow) {
  const std::size_t depth = 1000000;
  const std::string text = R"({"format": "smcbench-avi", "version": 1, "M": [[1]], "H": [], "K": [], "q": [)" +
                           std::string(depth, '[') + std::string(depth, ']') + "]}";
  EXPECT_THAT(ErrorOf(text), HasSubstr("\"q[0]\": expected a number, got array of 1 entries"));
}

TEST(AviFileRegression, RowsOfEmptyBracketsAreRefusedBeforeTheMatrixIsAllocated) {
  const int n = 4000;  // M would take 128 MB
  std::string zeros, empty_rows;
  for (int i = 0; i < n; ++i) {
    zeros += i ? ", 0" : "0";
    empty_rows += i ? ", []" : "[]";
  }
  const std::string text = R"({"format": "smcbench-avi", "version": 1, "H": [], "K": [], "q": [)" + zeros +
                           "], \"M\": [" + empty_rows + "]}";
  std::string message;
  const unsigned long largest = test_support::LargestMalloc([&] { message = ErrorOf(text); });
  EXPECT_THAT(message, HasSubstr("\"M[0]\": has 0 entries, expected 4000"));
  EXPECT_LT(largest, 1ul << 20) << "the reader allocated " << largest << " bytes before checking the rows";
}


// Found by tests/fuzz/library_fuzzer.cc in a set of AVIs, which builds each AVI as this reader does: a row whose
// ratio b/a overflows to +inf (K = 1e305 over a coefficient 1e-6) was compared with the initial +inf and read the
// basis at index -1 in the phase-1 simplex that checks P is not empty (caught by UBSan in the ASan build).
TEST(AviFileFuzzRegression, AnOverflowingRatioInThePhaseOneSimplexIsHandled) {
  const AviFile file = ParseAviText(R"({"format": "smcbench-avi", "version": 1, "M": [[1, 0], [0, 1]],
      "q": [0, 0], "H": [[1e-6, 1], [1, 0]], "K": [1e305, 0]})",
                                    "overflow.avi.json");
  // P = {1e-6 λ₁ + λ₂ ≥ 1e305, λ₁ ≥ 0} is not empty and not bounded: no solution is promised.
  EXPECT_GE(file.avi.H().row(0).dot(file.avi.feasible_point()), 1e305 * (1 - 1e-9));
  EXPECT_GE(file.avi.feasible_point()[0], 0.0);
  EXPECT_EQ(file.expected, ExpectedOutcome::kUnknown);
}

}  // namespace
}  // namespace smcbench
