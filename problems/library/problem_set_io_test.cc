// The .smcps format: bit-exact round trips (±∞ bounds, −0.0, subnormals, dense and sparse, every metadata
// field), one shared matrix stored once, the streaming writer, one test per kind of damaged or hostile file
// (hostile sizes must not allocate), the Siconos relay export and the matrix-class tags; sets of AVIs (version 4)
// with the same discipline, and the committed files re-written byte for byte.
#include "problems/library/problem_set_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "problems/avi_library/avi_library.h"
#include "problems/io/siconos_format.h"
#include "problems/library/matrix_tags.h"
#include "problems/library/siconos_export.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

constexpr double kDenorm = std::numeric_limits<double>::denorm_min();
constexpr double kMax = std::numeric_limits<double>::max();
const char kFile[] = "test.smcps";

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSameBits(const Vector& a, const Vector& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index i = 0; i < a.size(); ++i) EXPECT_TRUE(SameBits(a[i], b[i])) << what << "[" << i << "]";
}

void ExpectSameMatrix(const BoxMLCP& a, const BoxMLCP& b) {
  ASSERT_EQ(a.is_sparse(), b.is_sparse());
  ASSERT_EQ(a.size(), b.size());
  if (!a.is_sparse()) {
    EXPECT_EQ(std::memcmp(a.dense_matrix().data(), b.dense_matrix().data(),
                          sizeof(double) * static_cast<std::size_t>(a.dense_matrix().size())),
              0);
    return;
  }
  const SparseMatrix &x = a.sparse_matrix(), &y = b.sparse_matrix();
  ASSERT_EQ(x.nonZeros(), y.nonZeros());
  for (int j = 0; j <= a.size(); ++j) EXPECT_EQ(x.outerIndexPtr()[j], y.outerIndexPtr()[j]);
  for (int k = 0; k < x.nonZeros(); ++k) {
    EXPECT_EQ(x.innerIndexPtr()[k], y.innerIndexPtr()[k]);
    EXPECT_TRUE(SameBits(x.valuePtr()[k], y.valuePtr()[k])) << "value " << k;
  }
}

void ExpectSameProblem(const LibraryProblem& a, const LibraryProblem& b) {
  SCOPED_TRACE(a.id);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.problem.name(), b.problem.name());
  ExpectSameMatrix(a.problem, b.problem);
  ExpectSameBits(a.problem.q(), b.problem.q(), "q");
  ExpectSameBits(a.problem.l(), b.problem.l(), "l");
  ExpectSameBits(a.problem.u(), b.problem.u(), "u");
  EXPECT_EQ(a.matrix.symmetric, b.matrix.symmetric);
  EXPECT_EQ(a.matrix.positive_definite, b.matrix.positive_definite);
  EXPECT_EQ(a.matrix.p_matrix, b.matrix.p_matrix);
  EXPECT_EQ(a.tags, b.tags);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.expected, b.expected);
  ExpectSameBits(a.solution, b.solution, "solution");
  EXPECT_EQ(a.metadata, b.metadata);
  EXPECT_EQ(a.reference.certificate, b.reference.certificate);
  EXPECT_TRUE(SameBits(a.reference.condition, b.reference.condition)) << a.reference.condition;
  ExpectSameBits(a.reference.z, b.reference.z, "reference z");
}

Vector Vec(std::initializer_list<double> values) {
  Vector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

DenseMatrix Dense3() {
  DenseMatrix M(3, 3);
  M << 4.0, -0.0, kDenorm,  //
      1e300, 3.0, -1.0,     //
      0.5, 1e-310, -kMax;
  return M;
}

SparseMatrix Sparse4() {
  // Column 1 empty; an explicitly stored −0.0; a subnormal.
  std::vector<Eigen::Triplet<double, int>> t = {{0, 0, 2.0}, {3, 0, -0.0}, {1, 2, kDenorm}, {2, 2, 5.0},
                                                {0, 3, -1.5}, {3, 3, 7.0}};
  SparseMatrix S(4, 4);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

LibraryProblem Problem(std::string id, BoxMLCP box) {
  return LibraryProblem{std::move(id), "", std::move(box), {}, {}, std::nullopt, ExpectedOutcome::kUnknown, {}, {}, {}};
}

// Every field set, every special value in every vector.
ProblemSet SampleSet() {
  ProblemSet set;
  set.name = "sample";
  set.description = "every field, every special double";
  LibraryProblem a = Problem("lib/dense/a", BoxMLCP(Dense3(), Vec({-0.0, kDenorm, -3.25}), Vec({-kInf, -0.0, -1.0}),
                                                    Vec({kInf, kInf, kDenorm}), "named"));
  a.source = "generated:test";
  a.matrix = {Tristate::kYes, Tristate::kNo, Tristate::kUnknown};
  a.tags = {"degenerate", "murty", ""};
  a.seed = 0xffffffffffffffffULL;
  a.expected = ExpectedOutcome::kSolvable;
  a.solution = Vec({1.5, -0.0, kDenorm});
  a.metadata = {{"h", "0.1"}, {"scene", "sign"}, {"empty", ""}, {"unicode", "θ → ∞"}};
  a.reference.certificate = Certificate::kUnique;
  a.reference.condition = 2.5;
  a.reference.z = Vec({1.5, -0.0, kDenorm});
  set.problems.push_back(a);

  LibraryProblem b = Problem("lib/sparse/b", BoxMLCP(Sparse4(), Vec({1, 2, 3, 4}), Vec({0, -1, -kInf, 0}),
                                                     Vec({kInf, 1, 2, 0})));
  b.expected = ExpectedOutcome::kInfeasible;
  b.seed = 0;
  b.matrix = {Tristate::kNo, Tristate::kUnknown, Tristate::kYes};
  b.reference.certificate = Certificate::kNoneFound;  // no z*, a condition all the same (kept bit for bit)
  b.reference.condition = kDenorm;
  set.problems.push_back(b);

  // Same M as a (stored once), different q; id with non-ASCII characters; named by its id (not stored twice).
  LibraryProblem c = Problem("lib/dense/c/ü", BoxMLCP(Dense3(), Vec({1, 2, 3}), Vec({-1, -1, -1}), Vec({1, 1, 1}),
                                                      "lib/dense/c/ü"));
  c.source = "capture:sign";
  c.reference.certificate = Certificate::kNonUnique;  // verified through a singular block: μ = +∞
  c.reference.condition = kInf;
  c.reference.z = Vec({-kMax, 0.0, 1e-300});
  set.problems.push_back(c);
  return set;
}

std::string Serialize(const ProblemSet& set) {
  std::ostringstream out;
  WriteProblemSet(set, out);
  return out.str();
}

ProblemSet Parse(const std::string& bytes) { return ReadProblemSetBytes(bytes, kFile); }

// Expects an InvalidInputError naming the file and containing every needle.
std::string ExpectRejected(const std::string& bytes, const std::vector<std::string>& needles) {
  try {
    Parse(bytes);
    ADD_FAILURE() << "accepted a damaged file";
  } catch (const InvalidInputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(kFile), std::string::npos) << "does not name the file: " << message;
    for (const std::string& needle : needles) {
      EXPECT_NE(message.find(needle), std::string::npos) << "'" << needle << "' missing from: " << message;
    }
    return message;
  }
  return {};
}

// The records of a file image: kind, offset of the record, offset and length of its body.
struct Record {
  std::uint8_t kind;
  std::size_t at, body;
  std::uint64_t length;
};

std::uint64_t Load(const std::string& s, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(s[at + i])) << (8 * i);
  return v;
}

void Store(std::string* s, std::size_t at, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) (*s)[at + i] = static_cast<char>((v >> (8 * i)) & 0xff);
}

void StoreDouble(std::string* s, std::size_t at, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, 8);
  Store(s, at, bits, 8);
}

double BitsOf(const std::string& s, std::size_t at) {
  const std::uint64_t bits = Load(s, at, 8);
  double v;
  std::memcpy(&v, &bits, 8);
  return v;
}

std::vector<Record> Records(const std::string& s) {
  std::vector<Record> out;
  std::size_t pos = 16;
  while (pos < s.size()) {
    Record r{static_cast<std::uint8_t>(s[pos]), pos, pos + 9, Load(s, pos + 1, 8)};
    out.push_back(r);
    pos = r.body + r.length;
  }
  return out;
}

Record Nth(const std::vector<Record>& records, std::uint8_t kind, int n = 0) {
  for (const Record& r : records) {
    if (r.kind == kind && n-- == 0) return r;
  }
  throw std::logic_error("no such record");
}

constexpr std::uint8_t kSet = 1, kMatrix = 2, kProblem = 3, kEnd = 4, kBounds = 5, kAviRecord = 6;

// A one-problem file with a 2×2 M: problem id "p", empty source and name, so its body offsets are fixed:
// id 0, source 5, flags 9, name 10, matrix index 14, n 22, q 30, l 46, u 62, tristates 78, expected 81, tag count
// 82, metadata 86 (count, then "a" "1" "b" "2": 24 bytes), certificate 110 (0, none), condition 111; 119 bytes.
constexpr std::size_t kSmallCertificate = 110, kSmallCondition = 111, kSmallBodyLength = 119;
std::string SmallFile(bool sparse = false) {
  ProblemSet set;
  set.name = "s";
  DenseMatrix M(2, 2);
  M << 2, 1, 1, 3;
  if (sparse) {
    set.problems.push_back(Problem("p", BoxMLCP(SparseMatrix(M.sparseView()), Vec({1, -1}), Vec({-1, -1}),
                                                Vec({1, 1}))));
  } else {
    set.problems.push_back(Problem("p", BoxMLCP::Relay(M, Vec({1, -1}))));
  }
  set.problems[0].metadata = {{"a", "1"}, {"b", "2"}};
  return Serialize(set);
}

// Largest single allocation while fn runs (tests/support/malloc_counter.h; 0 under AddressSanitizer).
template <typename Fn>
std::size_t LargestAllocation(Fn&& fn) {
  return test_support::LargestMalloc(std::forward<Fn>(fn));
}

// Patches a valid file, fixes its checksum, and expects a rejection that allocated less than 1 MiB.
void ExpectHostileRejected(std::string bytes, const std::vector<std::string>& needles) {
  FixProblemSetChecksum(&bytes);
  const std::size_t largest = LargestAllocation([&] { ExpectRejected(bytes, needles); });
  EXPECT_LT(largest, std::size_t{1} << 20) << "a hostile size field made the reader allocate " << largest << " bytes";
}

// ------------------------------------------------------------------------------------------------------------
// Round trips

TEST(ProblemSetIo, RoundTripIsBitExact) {
  const ProblemSet set = SampleSet();
  const ProblemSet back = Parse(Serialize(set));
  EXPECT_EQ(back.name, set.name);
  EXPECT_EQ(back.description, set.description);
  ASSERT_EQ(back.problems.size(), set.problems.size());
  for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameProblem(set.problems[i], back.problems[i]);
  // And the bytes are a fixed point: writing what was read gives the same file.
  EXPECT_EQ(Serialize(back), Serialize(set));
}

// ------------------------------------------------------------------------------------------------------------
// Version 1 (before references): still read, every problem with Certificate::kNone

// The version-1 image of a set whose references are all unverified: the same records without the 9 trailing
// bytes (certificate, condition) of each problem body, header version 1, lengths and checksum fixed. Built from
// the specification's version-1 layout, independently of the reader.
std::string VersionOneImage(const std::string& v2) {
  std::string v1 = v2.substr(0, 16);
  Store(&v1, 8, 1, 4);
  for (const Record& r : Records(v2)) {
    const std::uint64_t length = r.kind == kProblem ? r.length - 9 : r.length;
    std::string record = v2.substr(r.at, 9 + length);
    Store(&record, 1, length, 8);
    v1 += record;
  }
  FixProblemSetChecksum(&v1);
  return v1;
}

TEST(ProblemSetIoVersion1, HandBuiltVersionOneImageIsReadWithoutReferences) {
  ProblemSet set = SampleSet();
  for (LibraryProblem& p : set.problems) p.reference = {};
  const std::string v2 = Serialize(set);
  const std::string v1 = VersionOneImage(v2);
  EXPECT_EQ(v1.size(), v2.size() - 9 * set.problems.size());
  ProblemSetFileInfo info;
  const fs::path path = fs::temp_directory_path() / ("library-v1-" + std::to_string(::getpid()) + ".smcps");
  {
    std::ofstream out(path, std::ios::binary);
    out << v1;
  }
  const ProblemSet back = ReadProblemSetFile(path.string(), &info);
  fs::remove(path);
  EXPECT_EQ(info.version, 1u);
  ASSERT_EQ(back.problems.size(), set.problems.size());
  for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameProblem(set.problems[i], back.problems[i]);
  // Written again, it is the version-2 file.
  EXPECT_EQ(Serialize(back), v2);
  // The version decides the layout: version-2 bodies under a version-1 header have 9 bytes too many.
  std::string mislabeled = v2;
  Store(&mislabeled, 8, 1, 4);
  FixProblemSetChecksum(&mislabeled);
  ExpectRejected(mislabeled, {"problem #0", "9 unexpected trailing byte(s) inside the record"});
}

// A file written by the version-1 writer (a copy of tests/fuzz/seeds/library/sign.smcps, `smcbench simulate sign
// --T 0.05 --record`, committed before version 2 existed).
TEST(ProblemSetIoVersion1, FileWrittenByTheVersionOneWriterIsRead) {
  ProblemSetFileInfo info;
  const ProblemSet set =
      ReadProblemSetFile(std::string(SMCBENCH_SOURCE_DIR) + "/problems/library/testdata/format-v1-sign.smcps", &info);
  EXPECT_EQ(info.version, 1u);
  EXPECT_EQ(set.name, "capture");
  ASSERT_GT(set.problems.size(), 0u);
  for (const LibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    EXPECT_EQ(p.id.rfind("capture/sign/", 0), 0u);
    EXPECT_EQ(p.reference.certificate, Certificate::kNone);
    EXPECT_EQ(p.reference.z.size(), 0);
    // The captured z is what the run used, and it solves the problem (the bytes were read as meant).
    ASSERT_EQ(p.solution.size(), p.size());
    Vector w(p.size());  // sized: GCC 12 -Warray-bounds misreads the inlined small-size path on an empty w
    EXPECT_LE(p.problem.NaturalResidual(p.solution, &w).rel, 1e-10);
  }
  // Round trip through version 2: same problems.
  const ProblemSet again = Parse(Serialize(set));
  ASSERT_EQ(again.problems.size(), set.problems.size());
  for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameProblem(set.problems[i], again.problems[i]);
}

TEST(ProblemSetIo, EmptySetRoundTrips) {
  ProblemSet set;
  const ProblemSet back = Parse(Serialize(set));
  EXPECT_EQ(back.name, "");
  EXPECT_TRUE(back.problems.empty());
}

TEST(ProblemSetIo, FileRoundTripAndInfo) {
  const fs::path path = fs::temp_directory_path() / ("library-test-" + std::to_string(::getpid()) + ".smcps");
  const ProblemSet set = SampleSet();
  WriteProblemSetFile(set, path.string());
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
  ProblemSetFileInfo info;
  const ProblemSet back = ReadProblemSetFile(path.string(), &info);
  EXPECT_EQ(info.version, kProblemSetFormatVersion);
  EXPECT_EQ(info.problems, 3u);
  EXPECT_EQ(info.matrices, 2u);  // a and c share M
  EXPECT_EQ(info.bytes, fs::file_size(path));
  for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameProblem(set.problems[i], back.problems[i]);
  fs::remove(path);
  try {
    ReadProblemSetFile(path.string());
    ADD_FAILURE() << "read a missing file";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(ProblemSetIo, SharedMatrixIsStoredOnce) {
  constexpr int kN = 20, kCount = 50;
  const DenseMatrix M = DenseMatrix::Identity(kN, kN) * 3.0 + DenseMatrix::Constant(kN, kN, 0.25);
  ProblemSet shared, distinct;
  for (int k = 0; k < kCount; ++k) {
    const Vector q = Vector::Constant(kN, static_cast<double>(k));
    shared.problems.push_back(Problem("p" + std::to_string(k), BoxMLCP::Relay(M, q)));
    DenseMatrix Mk = M;
    Mk(0, 0) += k;
    distinct.problems.push_back(Problem("p" + std::to_string(k), BoxMLCP::Relay(Mk, q)));
  }
  const std::string a = Serialize(shared), b = Serialize(distinct);
  int matrices_a = 0, matrices_b = 0;
  for (const Record& r : Records(a)) matrices_a += r.kind == kMatrix;
  for (const Record& r : Records(b)) matrices_b += r.kind == kMatrix;
  EXPECT_EQ(matrices_a, 1);
  EXPECT_EQ(matrices_b, kCount);
  // 49 dense 20×20 matrices (8 bytes an entry plus a 9-byte body header and 9-byte record header) saved.
  EXPECT_EQ(b.size() - a.size(), static_cast<std::size_t>((kCount - 1) * (kN * kN * 8 + 18)));
  const ProblemSet back = Parse(a);
  for (int k = 0; k < kCount; ++k) ExpectSameProblem(shared.problems[k], back.problems[k]);
}

TEST(ProblemSetIo, MatricesEqualInValueButNotInBitsAreNotMerged) {
  DenseMatrix M(1, 1), N(1, 1);
  M << 0.0;
  N << -0.0;
  ProblemSet set;
  set.problems.push_back(Problem("zero", BoxMLCP::Relay(M, Vec({1}))));
  set.problems.push_back(Problem("minus-zero", BoxMLCP::Relay(N, Vec({1}))));
  const ProblemSet back = Parse(Serialize(set));
  EXPECT_TRUE(std::signbit(back.problems[1].problem.dense_matrix()(0, 0)));
  EXPECT_FALSE(std::signbit(back.problems[0].problem.dense_matrix()(0, 0)));
}

TEST(ProblemSetIo, StreamingWriterWritesTheSameBytes) {
  const ProblemSet set = SampleSet();
  std::ostringstream out;
  ProblemSetWriter writer(out, "stream", set.name, set.description);
  for (const LibraryProblem& p : set.problems) writer.Add(p);
  writer.Close();
  EXPECT_TRUE(writer.closed());
  EXPECT_EQ(writer.problems_written(), 3u);
  EXPECT_EQ(writer.matrices_written(), 2u);
  EXPECT_EQ(writer.bytes_written(), out.str().size());
  EXPECT_EQ(out.str(), Serialize(set));
}

TEST(ProblemSetIo, StreamingWriterDedupeCache) {
  DenseMatrix A(2, 2), B(2, 2);
  A << 2, 0, 0, 2;
  B << 3, 1, 1, 3;
  const auto count_matrices = [&](const std::vector<const DenseMatrix*>& sequence, std::size_t budget) {
    std::ostringstream out;
    ProblemSetWriter writer(out, "stream", "s", "", ProblemSetWriterOptions{budget});
    int k = 0;
    for (const DenseMatrix* M : sequence) {
      writer.Add(Problem("p" + std::to_string(k++), BoxMLCP::Relay(*M, Vec({1, 2}))));
    }
    writer.Close();
    const ProblemSet back = Parse(out.str());
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      EXPECT_EQ(back.problems[i].problem.dense_matrix(), *sequence[i]);
    }
    return writer.matrices_written();
  };
  // Consecutive repeats are merged even with no cache budget at all.
  EXPECT_EQ(count_matrices({&A, &A, &A, &B, &B}, 0), 2u);
  EXPECT_EQ(count_matrices({&A, &B, &A, &B}, 0), 4u);
  EXPECT_EQ(count_matrices({&A, &B, &A, &B}, 1 << 20), 2u);
}

TEST(ProblemSetIo, FileWriterPublishesOnlyOnClose) {
  const fs::path path = fs::temp_directory_path() / ("library-writer-" + std::to_string(::getpid()) + ".smcps");
  const ProblemSet set = SampleSet();
  {
    ProblemSetWriter writer(path.string(), "s", "d");
    writer.Add(set.problems[0]);
    EXPECT_FALSE(fs::exists(path));
    EXPECT_TRUE(fs::exists(path.string() + ".partial"));
  }  // never closed
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
  {
    ProblemSetWriter writer(path.string(), "s", "d");
    for (const LibraryProblem& p : set.problems) writer.Add(p);
    writer.Close();
  }
  const ProblemSet back = ReadProblemSetFile(path.string());
  ASSERT_EQ(back.problems.size(), 3u);
  EXPECT_EQ(back.name, "s");
  EXPECT_EQ(back.description, "d");
  fs::remove(path);
  EXPECT_THROW(ProblemSetWriter("/nonexistent-dir/x.smcps", "s", ""), InvalidInputError);
}

TEST(ProblemSetIo, WriterRejectsWhatTheReaderWouldRefuse) {
  ProblemSet set = SampleSet();
  set.problems[2].id = set.problems[0].id;
  EXPECT_THROW(Serialize(set), InvalidInputError);

  set = SampleSet();
  set.problems[0].solution[1] = std::nan("");
  try {
    Serialize(set);
    ADD_FAILURE();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("solution[1] is not finite"), std::string::npos) << e.what();
  }

  set = SampleSet();
  set.problems[0].expected = static_cast<ExpectedOutcome>(7);
  EXPECT_THROW(Serialize(set), InvalidInputError);

  // References: what the certificate promises must be there, and nothing else.
  const auto expect_refused = [](const ProblemSet& bad, const std::string& needle) {
    try {
      Serialize(bad);
      ADD_FAILURE() << "wrote " << needle;
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  set = SampleSet();
  set.problems[0].reference.certificate = static_cast<Certificate>(9);
  expect_refused(set, "reference certificate with the invalid value 9");
  set = SampleSet();
  set.problems[0].reference.z = Vec({1.0});
  expect_refused(set, "z* of size 1 but n = 3");
  set = SampleSet();
  set.problems[1].reference.z = Vec({1, 2, 3, 4});  // none found, yet a z*
  expect_refused(set, "z* of size 4");
  set = SampleSet();
  set.problems[0].reference.condition = -1.0;
  expect_refused(set, "reference condition");
  set = SampleSet();
  set.problems[0].reference.condition = std::nan("");
  expect_refused(set, "reference condition");
  set = SampleSet();
  set.problems[2].reference.z[1] = std::nan("");
  std::ostringstream out_of_validate;  // Validate passes (sizes match): the writer's own check refuses it
  try {
    ProblemSetWriter w(out_of_validate, "stream", "s", "");
    w.Add(set.problems[2]);
    ADD_FAILURE();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("reference z[1] is not finite"), std::string::npos) << e.what();
  }

  std::ostringstream out;
  ProblemSetWriter writer(out, "stream", "s", "");
  writer.Add(SampleSet().problems[0]);
  EXPECT_THROW(writer.Add(SampleSet().problems[0]), InvalidInputError);  // duplicate id
  writer.Close();
  EXPECT_THROW(writer.Add(SampleSet().problems[1]), InvalidInputError);  // after Close
}

// ------------------------------------------------------------------------------------------------------------
// Damaged files: one test per defect

TEST(ProblemSetIoDefects, EmptyFile) { ExpectRejected("", {"empty file"}); }

TEST(ProblemSetIoDefects, NotAProblemSetFile) {
  ExpectRejected("15\n0\n15 15\n1 2 3\n", {"not a smcbench problem-set file", "magic"});
}

TEST(ProblemSetIoDefects, TruncatedHeader) { ExpectRejected(SmallFile().substr(0, 11), {"truncated", "header"}); }

TEST(ProblemSetIoDefects, VersionMismatch) {
  std::string bytes = SmallFile();
  Store(&bytes, 8, 5, 4);
  ExpectRejected(bytes, {"format version 5 is not supported", "reads versions 1 to 4", "newer"});
  Store(&bytes, 8, 0, 4);
  ExpectRejected(bytes, {"format version 0 is not supported", "byte 8"});
}

TEST(ProblemSetIoDefects, ReservedHeaderField) {
  std::string bytes = SmallFile();
  Store(&bytes, 12, 1, 4);
  ExpectRejected(bytes, {"reserved header field", "byte 12"});
}

TEST(ProblemSetIoDefects, EveryTruncationIsRejected) {
  const std::string bytes = SmallFile();
  for (std::size_t size = 1; size < bytes.size(); ++size) {
    SCOPED_TRACE("truncated to " + std::to_string(size) + " bytes");
    ExpectRejected(bytes.substr(0, size), {"truncated"});
  }
}

TEST(ProblemSetIoDefects, EveryFlippedByteIsRejected) {
  const std::string bytes = SmallFile(true);
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    for (unsigned char mask : {0x01, 0x80, 0xff}) {
      std::string damaged = bytes;
      damaged[at] = static_cast<char>(damaged[at] ^ mask);
      EXPECT_THROW(Parse(damaged), InvalidInputError) << "byte " << at << " xor " << int{mask};
    }
  }
}

TEST(ProblemSetIoDefects, ChecksumMismatch) {
  std::string bytes = SmallFile();
  const Record& p = Nth(Records(bytes), kProblem);
  StoreDouble(&bytes, p.body + 30, 1.5);  // q[0]: a plausible value, only the checksum can tell
  ExpectRejected(bytes, {"checksum mismatch", "corrupt"});
}

TEST(ProblemSetIoDefects, TrailingBytesAfterTheEndRecord) {
  ExpectRejected(SmallFile() + "x", {"1 unexpected byte(s) after the end record"});
}

TEST(ProblemSetIoDefects, MissingEndRecord) {
  std::string bytes = SmallFile();
  ExpectRejected(bytes.substr(0, Nth(Records(bytes), kEnd).at), {"truncated", "without an end record"});
}

TEST(ProblemSetIoDefects, UnknownRecordKind) {
  std::string bytes = SmallFile();
  bytes[Nth(Records(bytes), kProblem).at] = 9;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"unknown record kind 9"});
}

TEST(ProblemSetIoDefects, MatrixIndexOutOfRange) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kProblem).body + 14, 7, 8);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #0 ('p') matrix index", "refers to matrix 7"});
}

TEST(ProblemSetIoDefects, SizeDisagreesWithTheMatrix) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kProblem).body + 22, 1, 8);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"n = 1 but matrix 0 is 2x2"});
}

TEST(ProblemSetIoDefects, NaNInQ) {
  std::string bytes = SmallFile();
  const std::size_t at = Nth(Records(bytes), kProblem).body + 38;
  StoreDouble(&bytes, at, std::nan(""));
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"q[1] at byte " + std::to_string(at), "is NaN"});
}

TEST(ProblemSetIoDefects, InfinityInQ) {
  std::string bytes = SmallFile();
  StoreDouble(&bytes, Nth(Records(bytes), kProblem).body + 30, -kInf);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"q[0]", "is infinite"});
}

TEST(ProblemSetIoDefects, NaNBound) {
  std::string bytes = SmallFile();
  StoreDouble(&bytes, Nth(Records(bytes), kProblem).body + 46, std::nan(""));
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"l[0]", "is NaN"});
}

TEST(ProblemSetIoDefects, LowerBoundAboveUpperBound) {
  std::string bytes = SmallFile();
  StoreDouble(&bytes, Nth(Records(bytes), kProblem).body + 54, 2.0);  // l[1] = 2 > u[1] = 1
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #0 ('p')", "l[1] = 2 > u[1] = 1"});
}

TEST(ProblemSetIoDefects, InvalidTristate) {
  std::string bytes = SmallFile();
  bytes[Nth(Records(bytes), kProblem).body + 79] = 7;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"positive_definite", "value 7"});
}

TEST(ProblemSetIoDefects, InvalidExpectedOutcome) {
  std::string bytes = SmallFile();
  bytes[Nth(Records(bytes), kProblem).body + 81] = 3;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"expected", "value 3"});
}

TEST(ProblemSetIoDefects, UnknownCertificate) {
  std::string bytes = SmallFile();
  const Record& p = Nth(Records(bytes), kProblem);
  ASSERT_EQ(p.length, kSmallBodyLength);
  const std::size_t at = p.body + kSmallCertificate;
  ASSERT_EQ(bytes[at], 0);
  bytes[at] = 6;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #0 ('p') certificate at byte " + std::to_string(at),
                         "value 6 is not a known certificate (0 none, 1 unique, 2 degenerate, 3 non-unique, "
                         "4 none found, 5 isolated)"});
  bytes[at] = static_cast<char>(0xff);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"certificate at byte " + std::to_string(at), "value 255"});
}

TEST(ProblemSetIoDefects, VerifiedCertificateWithoutItsSolution) {
  // Certificate 1 (unique) promises z*: 2 doubles, but the record ends after the condition.
  std::string bytes = SmallFile();
  const Record& p = Nth(Records(bytes), kProblem);
  bytes[p.body + kSmallCertificate] = 1;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #0 ('p') reference z at byte " + std::to_string(p.body + kSmallBodyLength),
                         "declares 2 value(s) of 8 byte(s) but only 0 byte(s) remain"});
}

TEST(ProblemSetIoDefects, BadCondition) {
  std::string bytes = SmallFile();
  const std::size_t at = Nth(Records(bytes), kProblem).body + kSmallCondition;
  StoreDouble(&bytes, at, std::nan(""));
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"condition at byte " + std::to_string(at), "is NaN"});
  StoreDouble(&bytes, at, -1.0);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"condition at byte " + std::to_string(at), "is negative"});
}

TEST(ProblemSetIoDefects, NonFiniteReferenceSolution) {
  ProblemSet set;
  DenseMatrix M(1, 1);
  M << 2;
  set.problems.push_back(Problem("p", BoxMLCP::Relay(M, Vec({1}))));
  set.problems[0].reference = ReferenceSolution{Certificate::kUnique, Vec({-0.5}), 0.5};
  std::string bytes = Serialize(set);
  const Record& p = Nth(Records(bytes), kProblem);
  const std::size_t at = p.body + p.length - 8;  // z*[0], the record's last field
  StoreDouble(&bytes, at, kInf);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"reference z[0] at byte " + std::to_string(at), "is infinite"});
}

TEST(ProblemSetIoDefects, UnknownFlagBits) {
  std::string bytes = SmallFile();
  bytes[Nth(Records(bytes), kProblem).body + 9] = 0x40;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"flags", "unknown flag bits 0x0000000000000040"});
  // Bits 3 and 4 exist from version 3 on.
  Store(&bytes, 8, 2, 4);
  bytes[Nth(Records(bytes), kProblem).body + 9] = 0x08;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"flags", "unknown flag bits 0x0000000000000008"});
}

TEST(ProblemSetIoDefects, RepeatedMetadataKey) {
  std::string bytes = SmallFile();
  const Record& p = Nth(Records(bytes), kProblem);
  // Metadata: u32 count, then "a" "1" "b" "2" as 5-byte strings, then the reference (certificate 0 and the
  // condition: 9 bytes): the second key's character is 6 + 9 bytes from the end.
  ASSERT_EQ(bytes[p.body + p.length - 15], 'b');
  bytes[p.body + p.length - 15] = 'a';
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"metadata key[1]", "key repeated"});
}

TEST(ProblemSetIoDefects, DuplicateIds) {
  ProblemSet set = SampleSet();
  set.problems[2].id = "lib/dense/X";  // same length as "lib/dense/a"
  std::string bytes = Serialize(set);
  const Record& c = Nth(Records(bytes), kProblem, 2);
  bytes[c.body + 4 + 10] = 'a';
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"duplicate problem id 'lib/dense/a'"});
}

// Found by library_fuzzer: an id holding a newline (ids come from the file) made the error message span two lines.
TEST(ProblemSetIoFuzzRegression, IdWithANewlineGivesAOneLineError) {
  ProblemSet set = SampleSet();
  set.problems[1].id = "x\ny";
  set.problems[2].id = "x\nz";
  std::string bytes = Serialize(set);
  const Record& c = Nth(Records(bytes), kProblem, 2);
  bytes[c.body + 4 + 2] = 'y';
  FixProblemSetChecksum(&bytes);
  const std::string message = ExpectRejected(bytes, {"duplicate problem id 'x\\x0ay'"});
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(ProblemSetQuote, EscapesControlAndNonAsciiBytesAndCuts) {
  EXPECT_EQ(QuoteForMessage("paper/sign/k1"), "paper/sign/k1");
  EXPECT_EQ(QuoteForMessage(std::string("a\r\n\x00\xff", 5)), "a\\x0d\\x0a\\x00\\xff");
  EXPECT_EQ(QuoteForMessage(std::string(300, 'i'), 4), "iiii...");
}

TEST(ProblemSetIoDefects, EndRecordCountsDisagree) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kEnd).body + 8, 5, 8);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"end record counts 1 matrices and 5 problems", "holds 1 and 1"});
}

TEST(ProblemSetIoDefects, TrailingBytesInsideARecord) {
  std::string bytes = SmallFile();
  const Record p = Nth(Records(bytes), kProblem);
  bytes.insert(p.body + p.length, 1, '\0');
  Store(&bytes, p.at + 1, p.length + 1, 8);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #0 ('p')", "1 unexpected trailing byte(s) inside the record"});
}

TEST(ProblemSetIoDefects, RecordBeforeTheSetRecord) {
  std::string bytes = SmallFile();
  bytes[Nth(Records(bytes), kSet).at] = kMatrix;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"before the set record"});
}

TEST(ProblemSetIoDefects, NonFiniteMatrixEntry) {
  std::string bytes = SmallFile();
  StoreDouble(&bytes, Nth(Records(bytes), kMatrix).body + 9 + 8, kInf);  // M(1,0)
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"matrix #0 M(1,0)", "is infinite"});
}

TEST(ProblemSetIoDefects, UnknownStorage) {
  std::string bytes = SmallFile();
  bytes[Nth(Records(bytes), kMatrix).body] = 5;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"storage", "unknown storage 5"});
}

TEST(ProblemSetIoDefects, SparseRowIndicesOutOfOrder) {
  std::string bytes = SmallFile(true);
  // Column 0 holds rows 0, 1: make them 1, 1.
  const Record& m = Nth(Records(bytes), kMatrix);
  const std::size_t rows = m.body + 17 + 4 * 3;
  ASSERT_EQ(Load(bytes, rows, 4), 0u);
  Store(&bytes, rows, 1, 4);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"row index[1]", "not above the previous row index"});
}

TEST(ProblemSetIoDefects, SparseRowIndexOutOfRange) {
  std::string bytes = SmallFile(true);
  Store(&bytes, Nth(Records(bytes), kMatrix).body + 17 + 4 * 3 + 4, 2, 4);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"row index[1]", "is >= n = 2"});
}

TEST(ProblemSetIoDefects, SparseColumnPointersDecrease) {
  std::string bytes = SmallFile(true);
  Store(&bytes, Nth(Records(bytes), kMatrix).body + 17 + 4, 5, 4);  // p[1] = 5 > nnz = 4
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"column pointer[1]", "value 5"});
}

// ------------------------------------------------------------------------------------------------------------
// Hostile size fields: rejected before any large allocation

TEST(ProblemSetIoHostile, AllocationTrackerSeesLargeAllocations) {
if (!test_support::CanCountMallocs()) GTEST_SKIP() << "AddressSanitizer owns malloc: allocation sizes are not observed";
  const std::size_t largest = LargestAllocation([] {
    std::vector<char> v(std::size_t{3} << 20);
    v[v.size() / 2] = 1;
    EXPECT_EQ(v[v.size() / 2], 1);
  });
  EXPECT_GE(largest, std::size_t{3} << 20);
}

TEST(ProblemSetIoHostile, HugeDimension) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kMatrix).body + 1, std::uint64_t{1} << 40, 8);
  ExpectHostileRejected(bytes, {"matrix #0 n", "n = 1099511627776 is outside [1, 2147483647]"});
}

TEST(ProblemSetIoHostile, DenseDimensionLargerThanTheData) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kMatrix).body + 1, 2147483647, 8);
  ExpectHostileRejected(bytes, {"dense 2147483647x2147483647 matrix needs more than", "corrupt size field"});
}

TEST(ProblemSetIoHostile, SparseDimensionLargerThanTheData) {
  std::string bytes = SmallFile(true);
  Store(&bytes, Nth(Records(bytes), kMatrix).body + 1, 2147483647, 8);
  ExpectHostileRejected(bytes, {"column pointers", "declares 2147483648 value(s)"});
}

TEST(ProblemSetIoHostile, HugeNonZeroCount) {
  std::string bytes = SmallFile(true);
  const Record& m = Nth(Records(bytes), kMatrix);
  Store(&bytes, m.body + 9, 2147483647, 8);
  // Keep the column pointers consistent with the claim, so the size check on the entries is what fires.
  Store(&bytes, m.body + 17 + 8, 2147483647, 4);
  ExpectHostileRejected(bytes, {"row indices and values", "declares 2147483647 value(s)"});
}

TEST(ProblemSetIoHostile, HugeStringLength) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kProblem).body, 0xffffffff, 4);
  ExpectHostileRejected(bytes, {"problem #0 id", "declares 4294967295 value(s) of 1 byte(s)"});
}

TEST(ProblemSetIoHostile, HugeTagCount) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kProblem).body + 82, 0xffffffff, 4);
  ExpectHostileRejected(bytes, {"tags", "declares 4294967295"});
}

TEST(ProblemSetIoHostile, HugeRecordLength) {
  std::string bytes = SmallFile();
  Store(&bytes, Nth(Records(bytes), kProblem).at + 1, std::uint64_t{1} << 62, 8);
  const std::size_t largest = LargestAllocation([&] {
    ExpectRejected(bytes, {"problem record #2 declares 4611686018427387904 byte(s)", "truncated or corrupt"});
  });
  EXPECT_LT(largest, std::size_t{1} << 20);
}

// ------------------------------------------------------------------------------------------------------------
// Siconos relay export

TEST(SiconosExport, RelayProblemRoundTripsBitExact) {
  ProblemSet set = SampleSet();
  const LibraryProblem& c = set.problems[2];
  std::ostringstream out;
  ExportSiconosRelay(c, out);
  std::istringstream in(out.str());
  const BoxMLCP back = ReadSiconosStream(in, SiconosKind::kRelay, "export");
  ExpectSameMatrix(c.problem, back);
  ExpectSameBits(c.problem.q(), back.q(), "q");
  ExpectSameBits(c.problem.l(), back.l(), "l");
  ExpectSameBits(c.problem.u(), back.u(), "u");
}

TEST(SiconosExport, SparseBoxProblemIsWrittenDensely) {
  LibraryProblem p = Problem("sparse", BoxMLCP(Sparse4(), Vec({1, 2, 3, 4}), Vec({-1, -1, -2, 0}), Vec({1, 1, 2, 0})));
  std::ostringstream out;
  ExportSiconosRelay(p, out);
  std::istringstream in(out.str());
  const BoxMLCP back = ReadSiconosStream(in, SiconosKind::kRelay, "export");
  EXPECT_FALSE(back.is_sparse());
  EXPECT_EQ(back.dense_matrix(), p.problem.ToDense());
}

TEST(SiconosExport, InfiniteBoundsAreRefusedWithTheRow) {
  const ProblemSet set = SampleSet();
  std::string why;
  EXPECT_FALSE(CanExportSiconosRelay(set.problems[0], &why));
  EXPECT_EQ(why, "row 0 has l = -inf, u = inf (a free row)");
  EXPECT_FALSE(CanExportSiconosRelay(set.problems[1], &why));
  EXPECT_EQ(why, "row 0 has l = 0, u = inf (an LCP row)");
  std::ostringstream out;
  try {
    ExportSiconosRelay(set.problems[1], out);
    ADD_FAILURE();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("problem 'lib/sparse/b': cannot be written in Siconos relay format: row 0"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(out.str().empty());
}

TEST(SiconosExport, FileNamesFromIds) {
  EXPECT_EQ(SiconosRelayFileName("paper/sign/implicit/h0.01/k12"), "paper_sign_implicit_h0.01_k12.dat");
  EXPECT_EQ(SiconosRelayFileName("../etc/passwd"), "_._etc_passwd.dat");
  EXPECT_EQ(SiconosRelayFileName("a b\\c:d"), "a_b_c_d.dat");
  EXPECT_EQ(SiconosRelayFileName(""), "_.dat");
  const std::string long_name = SiconosRelayFileName(std::string(400, 'x'));
  EXPECT_LE(long_name.size(), 200u);
  EXPECT_NE(long_name, SiconosRelayFileName(std::string(401, 'x')));
}

// ------------------------------------------------------------------------------------------------------------
// Matrix-class tags

MatrixTags Classify(const DenseMatrix& M) { return ClassifyMatrix(BoxMLCP::LCP(M, Vector::Zero(M.rows()))); }

TEST(MatrixTags, SymmetricPositiveDefinite) {
  DenseMatrix M(3, 3);
  M << 4, 1, 0, 1, 3, 1, 0, 1, 2;
  const MatrixTags t = Classify(M);
  EXPECT_EQ(t.symmetric, Tristate::kYes);
  EXPECT_EQ(t.positive_definite, Tristate::kYes);
  EXPECT_EQ(t.p_matrix, Tristate::kYes);
  // Same verdicts through the sparse path.
  const MatrixTags s = ClassifyMatrix(BoxMLCP(SparseMatrix(M.sparseView()), Vector::Zero(3), Vector::Zero(3),
                                              Vector::Constant(3, kInf)));
  EXPECT_EQ(s.positive_definite, Tristate::kYes);
  EXPECT_EQ(s.p_matrix, Tristate::kYes);
}

TEST(MatrixTags, PMatrixWithoutPositiveDefiniteSymmetricPart) {
  // Upper triangular, 1 on the diagonal, 3 above (Murty's construction with a larger entry): every principal
  // minor is 1, but the symmetric part, 1 on the diagonal and 1.5 elsewhere, has the eigenvalue −0.5.
  const int n = 6;
  DenseMatrix M = DenseMatrix::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) M(i, j) = 3;
  }
  const MatrixTags t = Classify(M);
  EXPECT_EQ(t.symmetric, Tristate::kNo);
  EXPECT_EQ(t.positive_definite, Tristate::kNo);
  EXPECT_EQ(t.p_matrix, Tristate::kYes);
  // Above the minors limit nothing is claimed.
  EXPECT_EQ(ClassifyMatrix(BoxMLCP::LCP(M, Vector::Zero(n)), ClassifyOptions{500, 4}).p_matrix, Tristate::kUnknown);
}

TEST(MatrixTags, IndefiniteAndSingular) {
  DenseMatrix M(2, 2);
  M << 1, 3, 3, 1;  // det = −8
  MatrixTags t = Classify(M);
  EXPECT_EQ(t.symmetric, Tristate::kYes);
  EXPECT_EQ(t.positive_definite, Tristate::kNo);
  EXPECT_EQ(t.p_matrix, Tristate::kNo);
  M << 1, 1, 1, 1;  // PSD, singular: det = 0 is not > 0, but not clearly < 0 either
  t = Classify(M);
  EXPECT_EQ(t.positive_definite, Tristate::kUnknown);
  EXPECT_EQ(t.p_matrix, Tristate::kUnknown);
  M << 0, 1, -1, 0;  // skew: zero diagonal
  t = Classify(M);
  EXPECT_EQ(t.positive_definite, Tristate::kNo);
  EXPECT_EQ(t.p_matrix, Tristate::kNo);
}

TEST(MatrixTags, OneByOne) {
  DenseMatrix M(1, 1);
  M << 1e-9;  // the h → 0 one-step matrix: tiny but positive
  EXPECT_EQ(Classify(M).p_matrix, Tristate::kYes);
  EXPECT_EQ(Classify(M).positive_definite, Tristate::kYes);
  M << -2;
  EXPECT_EQ(Classify(M).p_matrix, Tristate::kNo);
  EXPECT_EQ(Classify(M).positive_definite, Tristate::kNo);
}

// ------------------------------------------------------------------------------------------------------------
// Version 3 (captures of long runs): the bounds table, and problems that continue the previous one's source, tags
// and metadata.
// Offsets below come from the specification (problems/library/README.md), not from the reader.

// count problems of a capture: same M (2×2), source, tags and bounds [−1, 1]; metadata differing in "step" only.
ProblemSet CaptureLikeSet(int count) {
  ProblemSet set;
  set.name = "capture";
  DenseMatrix M(2, 2);
  M << 2, 1, 1, 3;
  for (int k = 1; k <= count; ++k) {
    const std::string id = "capture/s/implicit/h0.1/k" + std::to_string(k);
    LibraryProblem p = Problem(id, BoxMLCP::Relay(M, Vec({1.0 * k, -1.0}), -1.0, 1.0, id));
    p.source = "capture:s";
    p.tags = {"capture"};
    p.metadata = {{"scene", "s"}, {"method", "implicit"}, {"status", "solved"}, {"step", std::to_string(k)}};
    p.solution = Vec({0.5, -0.5});
    set.problems.push_back(p);
  }
  return set;
}

// The stored flags byte of a problem record (after the id and source strings).
std::uint8_t StoredFlags(const std::string& bytes, const Record& r) {
  const std::size_t id = Load(bytes, r.body, 4);
  const std::size_t source = Load(bytes, r.body + 4 + id, 4);
  return static_cast<std::uint8_t>(bytes[r.body + 8 + id + source]);
}

TEST(ProblemSetIoVersion3, RepeatedBoundsAreStoredOnceAndMetadataAsChanges) {
  const ProblemSet set = CaptureLikeSet(5);
  const std::string bytes = Serialize(set);
  EXPECT_EQ(Load(bytes, 8, 4), 3u);
  const std::vector<Record> records = Records(bytes);
  int bounds = 0;
  for (const Record& r : records) bounds += r.kind == kBounds;
  EXPECT_EQ(bounds, 1);
  // The first problem is laid out as in version 2 (inline l, u; its own source, tags, metadata).
  EXPECT_EQ(StoredFlags(bytes, Nth(records, kProblem, 0)), 0x02 | 0x04);  // solution, name = id
  // The bounds record comes before the second problem, which refers to it and continues the first.
  EXPECT_LT(Nth(records, kBounds).at, Nth(records, kProblem, 1).at);
  EXPECT_GT(Nth(records, kBounds).at, Nth(records, kProblem, 0).at);
  for (int i = 1; i < 5; ++i) {
    const Record& r = Nth(records, kProblem, i);
    EXPECT_EQ(StoredFlags(bytes, r), 0x02 | 0x04 | 0x08 | 0x10) << i;
    const std::size_t id = Load(bytes, r.body, 4);
    EXPECT_EQ(Load(bytes, r.body + 4 + id, 4), 0u) << "stored source is empty";
    // id, source, flags, matrix, n, q (2), bounds index, tristates, expected, solution (2), tag count 0, metadata
    // count 1 and "step" = "k" (4 + 4 + 4 + 1), certificate and condition.
    EXPECT_EQ(r.length, 4 + id + 4 + 1 + 8 + 8 + 16 + 8 + 3 + 1 + 16 + 4 + 4 + 13 + 9) << i;
  }
  const ProblemSet back = Parse(bytes);
  ASSERT_EQ(back.problems.size(), set.problems.size());
  for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameProblem(set.problems[i], back.problems[i]);
  EXPECT_EQ(Serialize(back), bytes);  // a fixed point
  // The streaming writer writes the same bytes.
  std::ostringstream out;
  ProblemSetWriter writer(out, "stream", set.name, set.description);
  for (const LibraryProblem& p : set.problems) writer.Add(p);
  writer.Close();
  EXPECT_EQ(out.str(), bytes);
}

// A problem continues the previous one only when its source and tags are the same and it keeps every key; new keys
// and changed values are stored. Otherwise it is stored in full.
TEST(ProblemSetIoVersion3, OnlyWhatCanBeContinuedIs) {
  ProblemSet set = CaptureLikeSet(5);
  set.problems[1].metadata["iteration"] = "2";   // a new key: continued, the key stored
  set.problems[2].metadata.erase("status");      // a dropped key: stored in full
  set.problems[3].source = "capture:other";      // another source: in full
  set.problems[4].problem = BoxMLCP(set.problems[4].problem.dense_matrix(), Vec({1, 2}), Vec({0, 0}),
                                    Vec({kInf, kInf}), set.problems[4].id);  // other bounds: inline
  const std::string bytes = Serialize(set);
  const std::vector<Record> records = Records(bytes);
  EXPECT_EQ(StoredFlags(bytes, Nth(records, kProblem, 1)) & 0x18, 0x18);
  EXPECT_EQ(StoredFlags(bytes, Nth(records, kProblem, 2)) & 0x10, 0);
  EXPECT_EQ(StoredFlags(bytes, Nth(records, kProblem, 3)) & 0x10, 0);
  EXPECT_EQ(StoredFlags(bytes, Nth(records, kProblem, 4)) & 0x08, 0);
  const ProblemSet back = Parse(bytes);
  for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameProblem(set.problems[i], back.problems[i]);
  EXPECT_EQ(Serialize(back), bytes);
}

// The committed fuzz seeds of versions 1 and 2 (tests/fuzz/seeds/library) are still read, and written as version 3
// they give the same problems.
TEST(ProblemSetIoVersion3, EarlierVersionsAreStillRead) {
  const std::string dir = std::string(SMCBENCH_SOURCE_DIR) + "/tests/fuzz/seeds/library/";
  int versions_seen[4] = {0, 0, 0, 0};
  for (const char* name : {"sign.smcps", "zoh-mimo.smcps", "arctan-newton.smcps", "zoh-mimo-v2.smcps"}) {
    SCOPED_TRACE(name);
    ProblemSetFileInfo info;
    const ProblemSet set = ReadProblemSetFile(dir + name, &info);
    ASSERT_LE(info.version, 2u);
    ++versions_seen[info.version];
    ASSERT_FALSE(set.problems.empty());
    const std::string v3 = Serialize(set);
    EXPECT_LT(v3.size(), info.bytes);  // the captures' bounds and metadata repeat
    const ProblemSet again = Parse(v3);
    ASSERT_EQ(again.problems.size(), set.problems.size());
    for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameProblem(set.problems[i], again.problems[i]);
  }
  EXPECT_GT(versions_seen[1], 0);
  EXPECT_GT(versions_seen[2], 0);
}

TEST(ProblemSetIoVersion3, BoundsIndexOutOfRangeOrOfAnotherSize) {
  std::string bytes = Serialize(CaptureLikeSet(2));
  const Record& p = Nth(Records(bytes), kProblem, 1);
  // Problem #1: id, empty source, flags, matrix index, n, q (2 doubles), then the bounds index.
  const std::size_t at = p.body + 4 + Load(bytes, p.body, 4) + 4 + 1 + 8 + 8 + 16;
  ASSERT_EQ(Load(bytes, at, 8), 0u);
  Store(&bytes, at, 7, 8);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #1", "bounds index at byte " + std::to_string(at), "refers to bounds 7"});

  // Two sizes, each with repeated bounds: bounds #0 has 2 rows, #1 has 3; point a 2-row problem at #1.
  ProblemSet set = CaptureLikeSet(2);
  for (int k = 0; k < 2; ++k) {
    set.problems.push_back(
        Problem("three/" + std::to_string(k), BoxMLCP::Relay(DenseMatrix::Identity(3, 3), Vec({1, 2, 3}))));
  }
  set.problems.push_back(set.problems[0]);
  set.problems.back().id = "two/again";
  set.problems.back().problem.set_name("two/again");
  bytes = Serialize(set);
  const Record& last = Nth(Records(bytes), kProblem, 4);
  const std::size_t id_length = Load(bytes, last.body, 4);
  const std::size_t source_length = Load(bytes, last.body + 4 + id_length, 4);  // "capture:s": stored in full
  const std::size_t index_at = last.body + 4 + id_length + 4 + source_length + 1 + 8 + 8 + 16;
  ASSERT_EQ(Load(bytes, index_at, 8), 0u);
  Store(&bytes, index_at, 1, 8);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #4", "bounds 1 have 3 rows but n = 2"});
}

TEST(ProblemSetIoVersion3, ContinuingWhatCannotBeContinued) {
  // Bit 4 on the first problem.
  std::string bytes = SmallFile();
  bytes[Nth(Records(bytes), kProblem).body + 9] |= 0x10;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #0", "flags", "on the first problem"});

  // Bit 4 on a problem that stores a source, or tags.
  ProblemSet set = CaptureLikeSet(2);
  set.problems[1].source = "capture:t";  // stored in full
  bytes = Serialize(set);
  Record p = Nth(Records(bytes), kProblem, 1);
  std::size_t flags_at = p.body + 4 + Load(bytes, p.body, 4) + 4 + Load(bytes, p.body + 4 + Load(bytes, p.body, 4), 4);
  ASSERT_EQ(bytes[flags_at] & 0x10, 0);
  bytes[flags_at] |= 0x10;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #1", "source", "must be empty when flag bit 4"});

  set = CaptureLikeSet(2);
  for (LibraryProblem& q : set.problems) q.source.clear();
  set.problems[1].tags = {"other"};  // stored in full, with an empty source
  bytes = Serialize(set);
  p = Nth(Records(bytes), kProblem, 1);
  flags_at = p.body + 4 + Load(bytes, p.body, 4) + 4;
  ASSERT_EQ(bytes[flags_at] & 0x10, 0);
  bytes[flags_at] |= 0x10;
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"problem #1", "tag count", "must be 0 when flag bit 4"});
}

TEST(ProblemSetIoVersion3, BoundsRecordDefects) {
  std::string good = Serialize(CaptureLikeSet(2));
  const Record b = Nth(Records(good), kBounds);
  ASSERT_EQ(b.length, 8u + 32u);
  // A bounds record in a version-2 file.
  std::string bytes = good;
  Store(&bytes, 8, 2, 4);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"unknown record kind 5 in a version-2 file", "version 3"});
  // NaN, +inf as a lower bound, u < l.
  bytes = good;
  StoreDouble(&bytes, b.body + 8, std::nan(""));
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"bounds #0 l[0] at byte " + std::to_string(b.body + 8), "is NaN"});
  bytes = good;
  StoreDouble(&bytes, b.body + 16, kInf);
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"bounds #0 l[1]", "is +inf"});
  bytes = good;
  StoreDouble(&bytes, b.body + 24, -2.0);  // u[0] = −2 < l[0] = −1
  FixProblemSetChecksum(&bytes);
  ExpectRejected(bytes, {"bounds #0 u[0]", "u = -2 < l = -1"});
  // A hostile row count.
  bytes = good;
  Store(&bytes, b.body, std::uint64_t{1} << 30, 8);
  ExpectHostileRejected(bytes, {"bounds #0 l, u", "declares 1073741824 value(s) of 16 byte(s)"});
}


// ------------------------------------------------------------------------------------------------------------
// Sets of AVIs (version 4, set kind 1)

std::shared_ptr<const AffineVI> SharedAvi(AffineVI avi) { return std::make_shared<const AffineVI>(std::move(avi)); }

DenseMatrix UnitBox2() {  // H of [0, 1]²
  DenseMatrix H(4, 2);
  H << 1, 0, -1, 0, 0, 1, 0, -1;
  return H;
}

// Three AVIs: an equality block with a certified reference, a second one sharing its M and H (named apart from its
// id, awkward doubles), and one with no solution (unbounded P, no reference).
AviProblemSet SmallAviSet() {
  AviProblemSet set;
  set.name = "avi-small";
  set.description = "hand-made AVIs of every shape";
  DenseMatrix E(1, 2);
  E << 1, 1;
  // The projection of c = (0.7, 0.1) onto [0, 1]² ∩ {λ₁ + λ₂ = 1} is (0.8, 0.2).
  AviLibraryProblem segment;
  segment.id = "a/segment";
  segment.source = "hand-made:segment";
  segment.problem = SharedAvi(AffineVI(DenseMatrix::Identity(2, 2), Vec({-0.7, -0.1}), UnitBox2(),
                                       Vec({0, -1, 0, -1}), E, Vec({1}), "a/segment"));
  segment.tags = {"hand-made", "equality"};
  segment.expected = ExpectedOutcome::kSolvable;
  segment.reference = CertifyAvi(*segment.problem, {AviSolution{Vec({0.8, 0.2}), {}, {}}});
  segment.metadata = {{"why", "an equality row"}};
  set.problems.push_back(segment);

  AviLibraryProblem box;
  box.id = "a/box";
  box.source = "hand-made:box";
  box.problem = SharedAvi(AffineVI(DenseMatrix::Identity(2, 2), Vec({-0.0, kDenorm}), UnitBox2(),
                                   Vec({0, -1, -0.0, -1}), "named apart"));
  box.expected = ExpectedOutcome::kSolvable;
  box.reference = CertifyAvi(*box.problem, {AviSolution{Vec({0, 0}), {}, {}}});
  set.problems.push_back(box);

  // λ ≥ 0 with M = 0, q = −1: 0 ∈ −1 + N_P(λ) has no solution (N_P(λ) ⊂ (−∞, 0]).
  AviLibraryProblem none;
  none.id = "a/none";
  none.source = "hand-made:no solution";
  none.problem = SharedAvi(AffineVI(DenseMatrix::Zero(1, 1), Vec({-1}), DenseMatrix::Identity(1, 1), Vec({0}),
                                    "a/none"));
  none.expected = ExpectedOutcome::kInfeasible;
  none.tags = {"infeasible"};
  set.problems.push_back(none);
  return set;
}

std::string SerializeAvis(const AviProblemSet& set) {
  std::ostringstream out;
  WriteAviProblemSet(set, out);
  return out.str();
}

AviProblemSet ParseAvis(const std::string& bytes) { return ReadAviProblemSetBytes(bytes, kFile); }

void ExpectSameDense(const DenseMatrix& a, const DenseMatrix& b, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  if (a.size() == 0) return;  // data() may be null, which memcmp must not see
  EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())), 0) << what;
}

void ExpectSameAvi(const AviLibraryProblem& a, const AviLibraryProblem& b) {
  SCOPED_TRACE(a.id);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.problem->name(), b.problem->name());
  ExpectSameDense(a.problem->M(), b.problem->M(), "M");
  ExpectSameBits(a.problem->q(), b.problem->q(), "q");
  ExpectSameDense(a.problem->H(), b.problem->H(), "H");
  ExpectSameBits(a.problem->K(), b.problem->K(), "K");
  ExpectSameDense(a.problem->E(), b.problem->E(), "E");
  ExpectSameBits(a.problem->f(), b.problem->f(), "f");
  EXPECT_EQ(a.tags, b.tags);
  EXPECT_EQ(a.expected, b.expected);
  EXPECT_EQ(a.metadata, b.metadata);
  const AviReference &r = a.reference, &s = b.reference;
  EXPECT_EQ(r.strictly_monotone, s.strictly_monotone);
  EXPECT_EQ(r.lambda_unique, s.lambda_unique);
  EXPECT_EQ(r.reduced.certificate, s.reduced.certificate);
  EXPECT_TRUE(SameBits(r.reduced.condition, s.reduced.condition)) << r.reduced.condition;
  ExpectSameBits(r.reduced.z, s.reduced.z, "reference z");
  ExpectSameBits(r.solution.lambda, s.solution.lambda, "reference lambda");
  ExpectSameBits(r.solution.mu, s.solution.mu, "reference mu");
  ExpectSameBits(r.solution.nu, s.solution.nu, "reference nu");
}

TEST(AviProblemSetIo, RoundTripIsBitExactAndMatricesAreShared) {
  const AviProblemSet set = SmallAviSet();
  ASSERT_TRUE(set.problems[0].reference.verified());
  ASSERT_TRUE(set.problems[1].reference.verified());
  const std::string bytes = SerializeAvis(set);
  EXPECT_EQ(Load(bytes, 8, 4), 4u);  // version 4
  EXPECT_EQ(Load(bytes, 12, 4), 1u);  // set kind 1, AVIs
  int matrices = 0;
  for (const Record& r : Records(bytes)) matrices += r.kind == kMatrix;
  // I₂ and the unit box's H once for the first two AVIs, E, and the last one's M = 0 and H = 1.
  EXPECT_EQ(matrices, 5);
  const AviProblemSet back = ParseAvis(bytes);
  EXPECT_EQ(back.name, set.name);
  EXPECT_EQ(back.description, set.description);
  ASSERT_EQ(back.problems.size(), set.problems.size());
  for (std::size_t i = 0; i < set.problems.size(); ++i) ExpectSameAvi(set.problems[i], back.problems[i]);
  EXPECT_EQ(SerializeAvis(back), bytes);  // a fixed point

  const fs::path path = fs::temp_directory_path() / ("library-avi-" + std::to_string(::getpid()) + ".smcps");
  WriteAviProblemSetFile(set, path.string());
  ProblemSetFileInfo info;
  EXPECT_EQ(ReadAviProblemSetFile(path.string(), &info).problems.size(), 3u);
  EXPECT_EQ(info.version, 4u);
  EXPECT_EQ(info.kind, ProblemSetKind::kAvi);
  EXPECT_EQ(info.matrices, 5u);
  EXPECT_EQ(info.problems, 3u);
  EXPECT_EQ(ReadProblemSetKind(path.string()), ProblemSetKind::kAvi);
  fs::remove(path);
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
}

TEST(AviProblemSetIo, BoxSetsAreStillWrittenAsVersion3) {
  const std::string bytes = Serialize(SampleSet());
  EXPECT_EQ(Load(bytes, 8, 4), 3u);
  EXPECT_EQ(Load(bytes, 12, 4), 0u);
}

// Files committed under problems/library/testdata and tests/fuzz/seeds/library that this build writes in their
// own version (3 for box-MLCPs, 4 for AVIs): read and written again, byte for byte the same. A change to either
// writer's bytes shows here.
TEST(AviProblemSetIo, CommittedFilesAreRewrittenByteForByte) {
  const std::string root = std::string(SMCBENCH_SOURCE_DIR);
  for (const std::string& name : {root + "/tests/fuzz/seeds/library/zoh-mimo-v3.smcps",
                                 root + "/problems/library/testdata/avi-small-v4.smcps"}) {
    SCOPED_TRACE(name);
    std::ifstream in(name, std::ios::binary);
    ASSERT_TRUE(in) << "missing";
    std::ostringstream file;
    file << in.rdbuf();
    const std::string bytes = file.str();
    if (ReadProblemSetKind(name) == ProblemSetKind::kAvi) {
      const AviProblemSet set = ReadAviProblemSetFile(name);
      EXPECT_EQ(set.problems.size(), 3u);
      EXPECT_EQ(SerializeAvis(set), bytes);
    } else {
      const ProblemSet set = ReadProblemSetFile(name);
      EXPECT_FALSE(set.problems.empty());
      EXPECT_EQ(Serialize(set), bytes);
    }
  }
}

TEST(AviProblemSetIo, EachReaderRefusesTheOtherKind) {
  ExpectRejected(SerializeAvis(SmallAviSet()), {"a set of AVIs (set kind 1), not of box-MLCPs", "at byte 12"});
  try {
    ParseAvis(Serialize(SampleSet()));
    ADD_FAILURE() << "an AVI reader accepted a set of box-MLCPs";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("a set of box-MLCPs (set kind 0) (format version 3), not of AVIs"),
              std::string::npos)
        << e.what();
  }
}

// Expects the AVI reader to refuse bytes with an InvalidInputError naming the file and containing every needle.
void ExpectAvisRejected(const std::string& bytes, const std::vector<std::string>& needles) {
  try {
    ParseAvis(bytes);
    ADD_FAILURE() << "accepted a damaged set of AVIs";
  } catch (const InvalidInputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(kFile), std::string::npos) << "does not name the file: " << message;
    for (const std::string& needle : needles) {
      EXPECT_NE(message.find(needle), std::string::npos) << "'" << needle << "' missing from: " << message;
    }
  }
}

TEST(AviProblemSetIo, EveryTruncationIsRejected) {
  const std::string bytes = SerializeAvis(SmallAviSet());
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    SCOPED_TRACE("truncated to " + std::to_string(size) + " bytes");
    ExpectAvisRejected(bytes.substr(0, size), {size == 0 ? "empty file" : "truncated"});
  }
}

TEST(AviProblemSetIo, EveryFlippedByteIsRejectedAndAPayloadByteByTheChecksum) {
  const std::string bytes = SerializeAvis(SmallAviSet());
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x01);
    EXPECT_THROW(ParseAvis(damaged), InvalidInputError) << "byte " << at;
  }
  // A bit of the first AVI's q (its body: id, source, flags, n, M index, then q).
  const Record avi = Nth(Records(bytes), kAviRecord);
  const std::size_t q_at = avi.body + 4 + 9 + 4 + 17 + 1 + 8 + 8;
  ASSERT_TRUE(SameBits(BitsOf(bytes, q_at), -0.7));
  std::string damaged = bytes;
  damaged[q_at] = static_cast<char>(damaged[q_at] ^ 0x01);
  ExpectAvisRejected(damaged, {"checksum mismatch", "the file is corrupt"});
}

TEST(AviProblemSetIo, DamagedFieldsAreNamedWithTheirOffset) {
  const std::string good = SerializeAvis(SmallAviSet());
  const std::vector<Record> records = Records(good);
  const Record avi = Nth(records, kAviRecord);  // "a/segment": id, source "hand-made:segment", flags, n, ...
  const std::size_t flags_at = avi.body + 4 + 9 + 4 + 17, n_at = flags_at + 1, m_index_at = n_at + 8,
                    q_at = m_index_at + 8, m_at = q_at + 16, h_index_at = m_at + 8, k_at = h_index_at + 8,
                    p_at = k_at + 32, expected_at = p_at + 8 + 8 + 8;
  const auto patched = [&](std::size_t at, std::uint64_t value, int size) {
    std::string bytes = good;
    Store(&bytes, at, value, size);
    FixProblemSetChecksum(&bytes);
    return bytes;
  };
  ExpectAvisRejected(patched(8, 5, 4), {"format version 5 is not supported", "reads versions 1 to 4"});
  ExpectAvisRejected(patched(12, 2, 4), {"set kind 2 is unknown", "at byte 12"});
  ExpectAvisRejected(patched(Nth(records, kMatrix).body, 0, 1), {"matrix #0 storage", "storage 0 in a set of AVIs"});
  ExpectAvisRejected(patched(flags_at, 0x05, 1), {"AVI #0 ('a/segment') flags at byte " + std::to_string(flags_at),
                                                  "unknown flag bits 0x0000000000000004"});
  ExpectAvisRejected(patched(m_index_at, 9, 8), {"M index", "refers to matrix 9 but only"});
  ExpectAvisRejected(patched(m_index_at, 1, 8), {"M index", "matrix 1 is 4x2 but the AVI needs 2x2"});
  ExpectAvisRejected(patched(h_index_at, 0, 8), {"H index", "matrix 0 is 2x2 but the AVI needs 4x2"});
  std::uint64_t nan_bits;
  const double not_a_number = std::nan("");
  std::memcpy(&nan_bits, &not_a_number, 8);
  ExpectAvisRejected(patched(q_at + 8, nan_bits, 8), {"q[1] at byte " + std::to_string(q_at + 8), "is NaN"});
  ExpectAvisRejected(patched(expected_at, 7, 1), {"expected", "value 7 is not 0 (unknown)"});
  // P = [0, 1]² ∩ {λ₁ + λ₂ = 1} is bounded: "infeasible" contradicts Hartman–Stampacchia, and the verified reference.
  ExpectAvisRejected(patched(expected_at, 2, 1), {"expected", "is infeasible but the reference is a verified"});
  // The third AVI has no verified reference: bit 1 (λ* unique) is refused there.
  const Record none = Nth(records, kAviRecord, 2);
  const std::size_t none_flags_at = none.body + 4 + 6 + 4 + 21;
  ExpectAvisRejected(patched(none_flags_at, 0x03, 1), {"AVI #2 ('a/none') flags", "bit 1 (lambda* unique) without"});
  // A constraint the AffineVI refuses: K = (0, 5, 0, −1) makes P empty (λ₁ ≥ 0 and −λ₁ ≥ 5).
  std::uint64_t five_bits;
  const double five = 5.0;
  std::memcpy(&five_bits, &five, 8);
  ExpectAvisRejected(patched(k_at + 8, five_bits, 8), {"AVI #0 ('a/segment')", "is empty"});
  // A box problem's record kind inside a set of AVIs.
  ExpectAvisRejected(patched(avi.at, kProblem, 1), {"record kind 3 in a set of AVIs"});
  // End-record counts.
  ExpectAvisRejected(patched(Nth(records, kEnd).body + 8, 4, 8), {"end record counts", "4 AVIs", "holds 5 and 3"});
  // A hostile matrix size: refused before any allocation.
  std::string hostile = good;
  Store(&hostile, Nth(records, kMatrix).body + 1, std::uint64_t{1} << 30, 8);
  FixProblemSetChecksum(&hostile);
  const std::size_t largest =
      LargestAllocation([&] { ExpectAvisRejected(hostile, {"matrix #0 values", "corrupt size"}); });
  EXPECT_LT(largest, std::size_t{1} << 20);
}

TEST(AviProblemSetIo, TheWriterRefusesWhatTheReaderWould) {
  const auto message = [](const AviProblemSet& set) {
    try {
      SerializeAvis(set);
    } catch (const InvalidInputError& e) {
      return std::string(e.what());
    }
    return std::string("(written)");
  };
  AviProblemSet set = SmallAviSet();
  set.problems[0].reference.solution.lambda[0] = 0.5;  // no longer the head of z*
  EXPECT_NE(message(set).find("AVI 'a/segment': reference lambda is not the first n entries of z*"),
            std::string::npos)
      << message(set);
  set = SmallAviSet();
  set.problems[0].reference.solution.mu.resize(1);
  EXPECT_NE(message(set).find("reference mu must have m and nu p finite entries"), std::string::npos);
  set = SmallAviSet();
  set.problems[2].reference.lambda_unique = true;
  EXPECT_NE(message(set).find("AVI 'a/none': reference lambda_unique without a verified solution"),
            std::string::npos);
  set = SmallAviSet();
  set.problems[1].reference = {};
  set.problems[1].expected = ExpectedOutcome::kInfeasible;
  EXPECT_NE(message(set).find("AVI 'a/box': expected infeasible, but P is bounded"), std::string::npos);
  set = SmallAviSet();
  set.problems[2].id = "a/box";
  EXPECT_NE(message(set).find("id is a duplicate"), std::string::npos);  // AviProblemSet::Validate
}

}  // namespace
}  // namespace smcbench
