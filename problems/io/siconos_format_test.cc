// Reader and writer of the Siconos text formats: every peer file, values checked by hand against the files,
// the sparse-block twins, bit-exact round trips, and one test per kind of malformed input.
#include "problems/io/siconos_format.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "solvers/generators/random_problems.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
const fs::path kSiconos = fs::path(SMCBENCH_PEER_DATA_DIR) / "siconos";

fs::path PeerFile(const char* folder, const char* file) { return kSiconos / folder / file; }

BoxMLCP ReadText(const std::string& text, SiconosKind kind) {
  std::istringstream in(text);
  return ReadSiconosStream(in, kind, "test-input");
}

// Expects InvalidInputError whose message contains every one of `needles`.
void ExpectRejected(const std::string& text, SiconosKind kind, std::vector<std::string> needles) {
  try {
    ReadText(text, kind);
    ADD_FAILURE() << "accepted malformed input:\n" << text;
  } catch (const InvalidInputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("test-input"), std::string::npos) << "message does not name the input: " << message;
    for (const std::string& needle : needles) {
      EXPECT_NE(message.find(needle), std::string::npos) << "'" << needle << "' missing from: " << message;
    }
  }
}

// A string literal with embedded NUL bytes kept.
template <std::size_t N>
std::string Bytes(const char (&s)[N]) {
  return std::string(s, N - 1);
}

bool BitEqual(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

void ExpectBitEqual(const BoxMLCP& a, const BoxMLCP& b) {
  ASSERT_EQ(a.size(), b.size());
  const DenseMatrix Ma = a.ToDense();
  const DenseMatrix Mb = b.ToDense();
  for (int j = 0; j < a.size(); ++j) {
    for (int i = 0; i < a.size(); ++i) EXPECT_TRUE(BitEqual(Ma(i, j), Mb(i, j))) << "M(" << i << "," << j << ")";
  }
  for (int i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(BitEqual(a.q()[i], b.q()[i])) << "q[" << i << "]";
    EXPECT_TRUE(BitEqual(a.l()[i], b.l()[i])) << "l[" << i << "]";
    EXPECT_TRUE(BitEqual(a.u()[i], b.u()[i])) << "u[" << i << "]";
  }
}

// ---------------------------------------------------------------------------------------------------------------
// The peer collection.

// Sizes from each file's header (n for LCP/relay, n + m for MLCP) and, for MLCP, the equality-row count n.
struct Expected {
  int size;
  int equality_rows;
};

const std::map<std::string, Expected>& ExpectedSizes() {
  static const std::map<std::string, Expected> sizes = {
      {"lcp/lcp_CPS_1", {2, 0}},        {"lcp/lcp_CPS_2", {3, 0}},
      {"lcp/lcp_CPS_3", {4, 0}},        {"lcp/lcp_CPS_4", {4, 0}},
      {"lcp/lcp_CPS_4bis", {4, 0}},     {"lcp/lcp_CPS_5", {2, 0}},
      {"lcp/lcp_Pang_isolated_sol", {3, 0}}, {"lcp/lcp_Pang_isolated_sol_perturbed", {3, 0}},
      {"lcp/lcp_deudeu", {2, 0}},       {"lcp/lcp_deudeu_block", {2, 0}},
      {"lcp/lcp_enum_fails", {9, 0}},   {"lcp/lcp_exp_murty", {6, 0}},
      {"lcp/lcp_exp_murty2", {6, 0}},   {"lcp/lcp_inf_sol_perturbed", {3, 0}},
      {"lcp/lcp_mmc", {26, 0}},         {"lcp/lcp_ortiz", {4, 0}},
      {"lcp/lcp_ortiz_block", {4, 0}},  {"lcp/lcp_tobenna", {40, 0}},
      {"lcp/lcp_trivial", {9, 0}},      {"lcp/lcp_trivial_block", {9, 0}},
      {"relay/relay1", {15, 0}},        {"relay/relay_2x2", {2, 0}},
      {"relay/relay_4x4", {4, 0}},      {"relay/relay_simple2", {2, 0}},
      {"relay/step_1x1", {1, 0}},       {"relay/step_2x2", {2, 0}},
      {"relay/step_4x4", {4, 0}},       {"mlcp/Buck2_mlcp", {32, 20}},
      {"mlcp/BuckConverter_mlcp", {32, 20}}, {"mlcp/BuckFirstStep_mlcp", {32, 20}},
      {"mlcp/PDSym_mlcp", {7, 3}},      {"mlcp/PD_mlcp", {7, 3}},
      {"mlcp/RCD_mlcp", {3, 2}},        {"mlcp/RLCD_mlcp", {8, 6}},
      {"mlcp/deltasigma2_mlcp", {221, 65}}, {"mlcp/deltasigma_mlcp", {221, 65}},
      {"mlcp/deudeu_mlcp", {2, 1}},     {"mlcp/diodeBridge20_mlcp", {31, 11}},
      {"mlcp/diodeBridge40_mlcp", {61, 21}}, {"mlcp/diodeBridge_mlcp", {7, 3}},
      {"mlcp/m2n1_mlcp", {3, 1}},       {"mlcp/m3n2_mlcp", {5, 2}},
      {"mlcp/relay2_mlcp", {6, 4}},     {"mlcp/relay3_mlcp", {6, 4}},
  };
  return sizes;
}

TEST(SiconosPeerFiles, EveryFileIsReadWithTheRightSizeAndBounds) {
  int files = 0;
  for (const char* folder : {"lcp", "relay", "mlcp"}) {
    for (const auto& entry : fs::directory_iterator(kSiconos / folder)) {
      if (entry.path().extension() != ".dat") continue;
      ++files;
      const std::string key = std::string(folder) + "/" + entry.path().stem().string();
      SCOPED_TRACE(key);
      if (key == "mlcp/Rectangular_mlcp") continue;  // rejected on purpose: see the next test
      const auto expected = ExpectedSizes().find(key);
      ASSERT_NE(expected, ExpectedSizes().end()) << "new file in the collection: add it to ExpectedSizes";
      const BoxMLCP p = ReadSiconosFile(entry.path().string());
      EXPECT_EQ(p.name(), entry.path().stem().string());
      EXPECT_EQ(p.size(), expected->second.size);
      const std::string kind = folder;
      for (int i = 0; i < p.size(); ++i) {
        if (kind == "lcp") {
          EXPECT_EQ(p.l()[i], 0.0);
          EXPECT_EQ(p.u()[i], kInf);
        } else if (kind == "mlcp") {
          const bool equality = i < expected->second.equality_rows;  // every peer MLCP puts them first
          EXPECT_EQ(p.l()[i], equality ? -kInf : 0.0) << i;
          EXPECT_EQ(p.u()[i], kInf) << i;
        } else {
          EXPECT_TRUE(std::isfinite(p.l()[i]) && std::isfinite(p.u()[i]) && p.l()[i] <= p.u()[i]);
        }
      }
    }
  }
  EXPECT_EQ(files, 45);
}

// Rectangular_mlcp.dat declares n = m = 1 but its type-1 M is 3x2 (with a 2-vector q), and its type-2 data
// ([A C; D B] = [1 -1; 1 1], b = -1) agrees with neither M's second row nor q[1] = 1. The two storages
// contradict each other and Siconos' own test collection leaves the file out; we reject it with a message.
TEST(SiconosPeerFiles, RectangularMlcpIsRejectedWithAClearMessage) {
  const std::string path = PeerFile("mlcp", "Rectangular_mlcp.dat").string();
  try {
    ReadSiconosFile(path);
    FAIL() << "Rectangular_mlcp.dat was accepted";
  } catch (const InvalidInputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("Rectangular_mlcp.dat"), std::string::npos) << message;
    EXPECT_NE(message.find("3x2"), std::string::npos) << message;
    EXPECT_NE(message.find("rectangular"), std::string::npos) << message;
  }
}

TEST(SiconosPeerFiles, LcpMmcValuesMatchTheFile) {
  const BoxMLCP p = ReadSiconosFile(PeerFile("lcp", "lcp_mmc.dat").string());
  ASSERT_EQ(p.size(), 26);
  ASSERT_FALSE(p.is_sparse());
  const DenseMatrix& M = p.dense_matrix();
  // First line of the matrix block = column 0; its second number is M(1,0).
  EXPECT_EQ(M(0, 0), 1.488865599999999976716936e+05);
  EXPECT_EQ(M(1, 0), -9.278025599999999394640326e+04);
  EXPECT_EQ(M(25, 0), 1.927852300000000127511157e+02);
  EXPECT_EQ(M(0, 25), 1.927852300000000127511157e+02);  // the matrix is symmetric
  EXPECT_EQ(p.q()[0], -4.356652999999999664737516e+00);
  EXPECT_EQ(p.q()[25], 6.053916799999999875936396e-01);
}

TEST(SiconosPeerFiles, DenseStorageIsColumnMajor) {
  // lcp_CPS_2.dat writes "0 2 -1 / -1 0 1 / 2 -2 0": the lines are columns, so M = [0 -1 2; 2 0 -2; -1 1 0].
  const BoxMLCP p = ReadSiconosFile(PeerFile("lcp", "lcp_CPS_2.dat").string());
  DenseMatrix expected(3, 3);
  expected << 0, -1, 2, 2, 0, -2, -1, 1, 0;
  EXPECT_EQ(p.dense_matrix(), expected);
  EXPECT_EQ(p.q(), (Vector(3) << -3, 6, -1).finished());

  const BoxMLCP ortiz = ReadSiconosFile(PeerFile("lcp", "lcp_ortiz.dat").string());
  DenseMatrix ortiz_M(4, 4);
  ortiz_M << 3, 1, 0, -1, -1, 2, 1, 1, 0, 1, 3, -1, 0, 0, 1, 2;
  EXPECT_EQ(ortiz.dense_matrix(), ortiz_M);
}

TEST(SiconosPeerFiles, RelayValuesMatchTheFile) {
  const BoxMLCP p = ReadSiconosFile(PeerFile("relay", "relay_2x2.dat").string());
  ASSERT_EQ(p.size(), 2);
  EXPECT_EQ(p.dense_matrix(), DenseMatrix::Identity(2, 2));
  EXPECT_EQ(p.q(), (Vector(2) << -0.5, 0.5).finished());
  EXPECT_EQ(p.l(), Vector::Constant(2, -1.0));
  EXPECT_EQ(p.u(), Vector::Constant(2, 1.0));

  const BoxMLCP step = ReadSiconosFile(PeerFile("relay", "step_1x1.dat").string());
  EXPECT_EQ(step.dense_matrix()(0, 0), 1.0);
  EXPECT_EQ(step.q()[0], 0.5);
  EXPECT_EQ(step.l()[0], 0.0);
  EXPECT_EQ(step.u()[0], 1.0);
}

TEST(SiconosPeerFiles, MlcpValuesMatchBothStorages) {
  // m2n1_mlcp.dat: type 1 M (column-major) = [1 2 0; 0 1 1.3333; 0 0 1], q = (-1, 1, -3); type 2 writes
  // A = 1, B = [1 1.3333; 0 1] row by row, C = [2 0], D = [0; 0], a = -1, b = (1, -3): the same problem.
  const BoxMLCP p = ReadSiconosFile(PeerFile("mlcp", "m2n1_mlcp.dat").string());
  ASSERT_EQ(p.size(), 3);
  const double c = 1.333299999999999929656269e+00;
  DenseMatrix expected(3, 3);
  expected << 1, 2, 0, 0, 1, c, 0, 0, 1;
  EXPECT_EQ(p.dense_matrix(), expected);
  EXPECT_EQ(p.q(), (Vector(3) << -1, 1, -3).finished());
  EXPECT_EQ(p.l()[0], -kInf);
  EXPECT_EQ(p.l()[1], 0.0);
  EXPECT_EQ(p.l()[2], 0.0);
  EXPECT_EQ(p.u(), Vector::Constant(3, kInf));
}

TEST(SiconosPeerFiles, FileKindIsInferredFromFolderThenName) {
  // relay2_mlcp.dat contains "relay" but is an MLCP; outside the standard folders the name decides.
  const fs::path dir = fs::temp_directory_path() / ("smcbench_siconos_kind_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(PeerFile("mlcp", "relay2_mlcp.dat"), dir / "relay2_mlcp.dat", fs::copy_options::overwrite_existing);
  fs::copy_file(PeerFile("relay", "relay_2x2.dat"), dir / "relay_2x2.dat", fs::copy_options::overwrite_existing);
  fs::copy_file(PeerFile("lcp", "lcp_ortiz.dat"), dir / "ortiz.dat", fs::copy_options::overwrite_existing);
  EXPECT_EQ(ReadSiconosFile((dir / "relay2_mlcp.dat").string()).size(), 6);
  EXPECT_EQ(ReadSiconosFile((dir / "relay_2x2.dat").string()).l()[0], -1.0);
  EXPECT_EQ(ReadSiconosFile((dir / "ortiz.dat").string()).u()[0], kInf);
  fs::remove_all(dir);
}

TEST(SiconosPeerFiles, SparseBlockTwinsEqualTheirDenseFiles) {
  for (const char* stem : {"lcp_trivial", "lcp_ortiz", "lcp_deudeu"}) {
    SCOPED_TRACE(stem);
    const BoxMLCP dense = ReadSiconosFile((kSiconos / "lcp" / (std::string(stem) + ".dat")).string());
    const BoxMLCP block = ReadSiconosFile((kSiconos / "lcp" / (std::string(stem) + "_block.dat")).string());
    EXPECT_FALSE(dense.is_sparse());
    EXPECT_TRUE(block.is_sparse());
    ASSERT_EQ(block.size(), dense.size());
    EXPECT_EQ(block.ToDense(), dense.dense_matrix());
    EXPECT_EQ(block.q(), dense.q());
  }
  // lcp_trivial_block stores nine 1x1 diagonal blocks: only 9 entries.
  EXPECT_EQ(ReadSiconosFile(PeerFile("lcp", "lcp_trivial_block.dat").string()).sparse_matrix().nonZeros(), 9);
}

// ---------------------------------------------------------------------------------------------------------------
// Writer.

TEST(SiconosWriter, RoundTripIsBitExactIncludingInfiniteBounds) {
  for (BoundKind bounds : {BoundKind::kMixed, BoundKind::kBox, BoundKind::kLCP}) {
    for (bool sparse : {false, true}) {
      GeneratorOptions g;
      g.size = 17;
      g.bounds = bounds;
      g.family = MatrixFamily::kNonsymmetricPMatrix;
      g.sparse = sparse;
      g.seed = 5;
      const GeneratedProblem gen = GenerateProblem(g);
      std::ostringstream out;
      WriteSiconosRelay(gen.problem, out);
      const BoxMLCP back = ReadText(out.str(), SiconosKind::kRelay);
      ExpectBitEqual(gen.problem, back);
    }
  }
  // Awkward values: subnormal, negative zero, extremes, infinities on both sides.
  DenseMatrix M(2, 2);
  M << 4.9406564584124654e-324, -0.0, 1.7976931348623157e308, 0.1;
  const BoxMLCP p(M, (Vector(2) << 1.0 / 3.0, -2.2250738585072014e-308).finished(),
                  (Vector(2) << -kInf, -1e-300).finished(), (Vector(2) << kInf, 5.0).finished(), "awkward");
  std::ostringstream out;
  WriteSiconosRelay(p, out);
  EXPECT_NE(out.str().find("-inf"), std::string::npos);
  ExpectBitEqual(p, ReadText(out.str(), SiconosKind::kRelay));
}

TEST(SiconosWriter, PeerFilesRoundTripThroughTheRelayFormat) {
  for (const char* f : {"lcp/lcp_mmc.dat", "lcp/lcp_ortiz_block.dat", "relay/relay1.dat", "mlcp/Buck2_mlcp.dat"}) {
    SCOPED_TRACE(f);
    const BoxMLCP p = ReadSiconosFile((kSiconos / f).string());
    std::ostringstream out;
    WriteSiconosRelay(p, out);
    ExpectBitEqual(p, ReadText(out.str(), SiconosKind::kRelay));
  }
}

TEST(SiconosWriter, FileRoundTripAndUnwritablePath) {
  GeneratorOptions g;
  g.size = 6;
  g.bounds = BoundKind::kRelay;
  const GeneratedProblem gen = GenerateProblem(g);
  const fs::path path = fs::temp_directory_path() / ("smcbench_relay_" + std::to_string(::getpid()) + ".dat");
  WriteSiconosRelayFile(gen.problem, path.string());
  const BoxMLCP back = ReadSiconosFile(path.string(), SiconosKind::kRelay);
  ExpectBitEqual(gen.problem, back);
  EXPECT_EQ(back.name(), path.stem().string());
  fs::remove(path);
  EXPECT_THROW(WriteSiconosRelayFile(gen.problem, "/nonexistent-dir/x/relay.dat"), InvalidInputError);
  std::ostringstream failed;
  failed.setstate(std::ios::badbit);
  EXPECT_THROW(WriteSiconosRelay(gen.problem, failed), InvalidInputError);
}

// ---------------------------------------------------------------------------------------------------------------
// Malformed input: each case names the field (and index) in the message.

constexpr SiconosKind kLCP = SiconosKind::kLCP;
constexpr SiconosKind kRelay = SiconosKind::kRelay;
constexpr SiconosKind kMLCP = SiconosKind::kMLCP;

const char* const kGoodLcp = "2\n0\n2\n2\n2 2\n1 0\n0 1\n-1 -1\n";
const char* const kGoodRelay = "2\n0\n2\n2\n2 2\n1 0\n0 1\n-1 1\n-1 -1\n1 1\n";
// n = 1, m = 1, both storages: M = [2 1; -1 3] (column-major "2 -1 1 3"), q = (1, -2).
const char* const kGoodMlcp = "1 1 1 1\n0 1 2\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n2\n3\n1\n-1\n1\n-2\n";

TEST(SiconosMalformed, GoodInputsParse) {
  EXPECT_EQ(ReadText(kGoodLcp, kLCP).size(), 2);
  EXPECT_EQ(ReadText(kGoodRelay, kRelay).size(), 2);
  const BoxMLCP p = ReadText(kGoodMlcp, kMLCP);
  EXPECT_EQ(p.dense_matrix(), (DenseMatrix(2, 2) << 2, 1, -1, 3).finished());
  EXPECT_EQ(p.l()[0], -kInf);
  EXPECT_EQ(p.l()[1], 0.0);
  // Type 1 only and type 2 only give the same problem.
  const BoxMLCP only1 = ReadText("1 0 1 1\n0 1 2\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n", kMLCP);
  const BoxMLCP only2 = ReadText("0 1 1 1\n2\n3\n1\n-1\n1\n-2\n", kMLCP);
  ExpectBitEqual(p, only1);
  ExpectBitEqual(p, only2);
}

TEST(SiconosMalformed, UnreadableFile) {
  try {
    ReadSiconosFile("/nonexistent/lcp/missing.dat");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/lcp/missing.dat"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadSiconosFile(kSiconos.string(), kLCP), InvalidInputError);  // a directory
}

TEST(SiconosMalformed, EmptyInput) { ExpectRejected("", kLCP, {"n", "end of file"}); }

TEST(SiconosMalformed, TruncatedMatrix) {
  ExpectRejected("2 0 2 2 2 2\n1 0 0\n", kLCP, {"M(1,1)", "end of file"});
  ExpectRejected("2 0 2 2 2 2\n1 0\n", kLCP, {"M", "bytes remain"});
}

TEST(SiconosMalformed, TruncatedQ) {
  ExpectRejected("2 0 2 2 2 2\n1 0 0 1\n-1\n", kLCP, {"q[1]", "end of file"});
  ExpectRejected("2 0 2 2 2 2\n1 0 0 1\n", kLCP, {"q", "bytes remain"});
  ExpectRejected("2 0 2 2 2 2\n1 0 0 1\n-1 ", kLCP, {"q[1]", "end of file"});
}

TEST(SiconosMalformed, TruncatedBounds) {
  ExpectRejected("2 0 2 2 2 2\n1 0 0 1\n-1 1\n-1 -1\n1\n", kRelay, {"ub[1]"});
  ExpectRejected("1 0 1 1 1 1\n1\n-1\n-1\n", kRelay, {"ub[0]", "end of file"});
}

TEST(SiconosMalformed, NonNumericTokens) {
  ExpectRejected("two 0 2 2 2 2 1 0 0 1 -1 -1", kLCP, {"n", "'two'", "integer"});
  ExpectRejected("2 0 2 2 2 2\n1 x\n0 1\n-1 -1\n", kLCP, {"M(1,0)", "'x'", "line 2"});
  ExpectRejected("2 0 2 2 2 2\n1 0 0 1\n-1 1.5.2\n", kLCP, {"q[1]", "'1.5.2'"});
  ExpectRejected("2 0 2 2 2 2\n1 0 0 1\n-1 1\n-1 -1\nup 1\n", kRelay, {"ub[0]", "'up'"});
  ExpectRejected("2 0 2.0 2 2 2 1 0 0 1 -1 -1", kLCP, {"M size0", "'2.0'"});
  ExpectRejected(Bytes("2 0 2 2 2 2 1 \x01\xff 0 1 -1 -1"), kLCP, {"M(1,0)", "\\x01\\xff"});
  ExpectRejected(Bytes("2 0 2 2 2 2 1 0\0 0 1 -1 -1"), kLCP, {"M(1,0)", "\\x00"});
}

TEST(SiconosMalformed, UnknownStorageType) {
  ExpectRejected("2 7 2 2 2 2 1 0 0 1 -1 -1", kLCP, {"M storage type", "unknown storage type 7"});
  ExpectRejected("2 -1 2 2 2 2 1 0 0 1 -1 -1", kLCP, {"M storage type", "unknown storage type -1"});
  ExpectRejected("2 2 2 2 4 4 0 0 1 1 0 1 1 0 1 1 -1 -1", kLCP, {"M storage type", "storage type 2", "not supported"});
  ExpectRejected("2 1 1 2 2 2 1 0 0 1 -1 -1", kMLCP, {"isStorageType1", "out of range"});
  ExpectRejected("0 0 1 1", kMLCP, {"isStorageType2", "neither"});
}

TEST(SiconosMalformed, BadSizes) {
  ExpectRejected("0 0 0 0 0 0", kLCP, {"n", "out of range"});
  ExpectRejected("-3 0 2 2 2 2", kLCP, {"n", "out of range"});
  ExpectRejected("99999999999999999999999 0", kLCP, {"n", "out of range"});
  ExpectRejected("3 0 2 2 2 2 1 0 0 1 -1 -1", kLCP, {"M", "2x2", "3x3"});
  ExpectRejected("2 0 2 3 2 3 1 0 0 1 0 0 -1 -1", kLCP, {"M", "2x3"});
  ExpectRejected("2 0 2 2 2 3 1 0 0 1 -1 -1", kLCP, {"M size1 (repeated)"});
  ExpectRejected("1 1 -1 2", kMLCP, {"n", "out of range"});
  ExpectRejected("1 1 0 0", kMLCP, {"m", "n + m = 0"});
}

TEST(SiconosMalformed, HugeSizesFailBeforeAllocating) {
  // 2^28 x 2^28 doubles would be 512 PiB; the reader compares the count with the bytes left first.
  ExpectRejected("268435456 0 268435456 268435456 268435456 268435456 1 2 3", kLCP, {"M", "bytes remain"});
  ExpectRejected("268435457 0", kLCP, {"n", "out of range"});
  ExpectRejected("1 1 0 100000000 0 100000000", kMLCP, {"n + m", "bytes remain"});
  std::string many_ones;
  for (int k = 0; k < 150; ++k) many_ones += "1 ";
  ExpectRejected("0 1 100 1 " + many_ones, kMLCP, {"A", "bytes remain"});
  ExpectRejected("100000 1 100000 100000 99999 1 1 100000 100000 2 99999", kLCP, {"M nbblocks", "block grid"});
  ExpectRejected("100000 1 100000 100000 1 1 1 100000 100000 2 1 0 1 0 0 1", kLCP, {"M block", "bytes remain"});
}

TEST(SiconosMalformed, NanAndInfInMatrixOrQ) {
  ExpectRejected("2 0 2 2 2 2 1 nan 0 1 -1 -1", kLCP, {"M(1,0)", "NaN"});
  ExpectRejected("2 0 2 2 2 2 1 0 inf 1 -1 -1", kLCP, {"M(0,1)", "infinite"});
  ExpectRejected("2 0 2 2 2 2 1 0 0 1e999 -1 -1", kLCP, {"M(1,1)", "infinite"});
  ExpectRejected("2 0 2 2 2 2 1 0 0 1 -1 -inf", kLCP, {"q[1]", "infinite"});
  ExpectRejected("2 0 2 2 2 2 1 0 0 1 NaN -1", kLCP, {"q[0]", "NaN"});
  ExpectRejected("1 1 1 1\n0 1 2\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n2\n3\n1\n-1\nnan\n-2\n", kMLCP, {"a[0]", "NaN"});
  // Underflow below the subnormals reads as zero, as strtod does.
  EXPECT_EQ(ReadText("1 0 1 1 1 1 1e-400 -1", kLCP).dense_matrix()(0, 0), 0.0);
}

TEST(SiconosMalformed, BadBounds) {
  ExpectRejected("2 0 2 2 2 2 1 0 0 1 -1 1  2 -1  1 1", kRelay, {"lb[0]", "> ub[0]"});
  ExpectRejected("2 0 2 2 2 2 1 0 0 1 -1 1  -1 nan  1 1", kRelay, {"lb[1]", "NaN"});
  ExpectRejected("2 0 2 2 2 2 1 0 0 1 -1 1  -1 -1  1 nan", kRelay, {"ub[1]", "NaN"});
  ExpectRejected("2 0 2 2 2 2 1 0 0 1 -1 1  inf -1  inf 1", kRelay, {"lb[0]", "inf"});
  ExpectRejected("2 0 2 2 2 2 1 0 0 1 -1 1  -inf -1  -inf 1", kRelay, {"ub[0]", "-inf"});
  const BoxMLCP p = ReadText("2 0 2 2 2 2 1 0 0 1 -1 1  -inf 0  inf 0", kRelay);  // infinite and equal bounds
  EXPECT_EQ(p.l()[0], -kInf);
  EXPECT_EQ(p.u()[0], kInf);
  EXPECT_EQ(p.l()[1], p.u()[1]);
}

TEST(SiconosMalformed, TrailingGarbage) {
  ExpectRejected(std::string(kGoodLcp) + "7\n", kLCP, {"trailing data", "'7'", "after q"});
  ExpectRejected(std::string(kGoodRelay) + "1\n", kRelay, {"trailing data", "after ub"});
  ExpectRejected("2 0 2 2 2 2\n1 0\n0 1\n-1 -1 oops\n", kLCP, {"trailing data", "'oops'", "line 4"});
  ExpectRejected(std::string(kGoodLcp) + "Remark without an empty line before it\n", kLCP, {"trailing data"});
  // Allowed: '#' comments anywhere, and free-text notes after an empty line (lcp_CPS_*.dat have them).
  EXPECT_EQ(ReadText(std::string(kGoodLcp) + "# a comment\n#another\n", kLCP).size(), 2);
  EXPECT_EQ(ReadText("2 # size\n0 2 2 2 2\n1 0\n0 1\n-1 -1\n", kLCP).size(), 2);
  EXPECT_EQ(ReadText(std::string(kGoodLcp) + "\nRemark 4.1: 1 2 3\n", kLCP).size(), 2);
  EXPECT_EQ(ReadText(std::string(kGoodLcp) + "\r\n\r\nExample\r\n", kLCP).size(), 2);
}

TEST(SiconosMalformed, MlcpTrailingReferenceSolutionIsBounded) {
  // Up to 2(n + m) trailing numbers are a reference solution that Siconos' reader ignores; more is an error.
  EXPECT_EQ(ReadText(std::string(kGoodMlcp) + "0.5 0 0 1\n", kMLCP).size(), 2);
  ExpectRejected(std::string(kGoodMlcp) + "0.5 0 0 1 9\n", kMLCP, {"trailing data", "'9'", "after b"});
}

TEST(SiconosMalformed, MlcpBlocks) {
  ExpectRejected("1 0 1 1\n1 2\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n", kMLCP, {"blocksRows[0]"});
  ExpectRejected("1 0 1 1\n0 1 1 2\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n", kMLCP, {"blocksRows[2]"});
  ExpectRejected("1 0 1 1\n0 1 3\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n", kMLCP, {"blocksRows[2]"});
  ExpectRejected("1 0 1 1\n0 1 2\n0 2\n0 2 2 2 2\n2 -1 1 3\n1 -2\n", kMLCP, {"blocksIsComp[1]"});
  ExpectRejected("1 0 1 1\n0 1 2\n1 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n", kMLCP, {"blocksIsComp", "0 equality rows"});
  // Type-1 blocks with the complementarity row first contradict the type-2 layout.
  ExpectRejected("1 1 1 1\n0 1 2\n1 0\n0 2 2 2 2\n2 -1 1 3\n1 -2\n2\n3\n1\n-1\n1\n-2\n", kMLCP,
                 {"blocksIsComp", "type-2 layout"});
  // Without type 2, any block order is honoured.
  const BoxMLCP p = ReadText("1 0 1 1\n0 1 2\n1 0\n0 2 2 2 2\n2 -1 1 3\n1 -2\n", kMLCP);
  EXPECT_EQ(p.l()[0], 0.0);
  EXPECT_EQ(p.l()[1], -kInf);
}

TEST(SiconosMalformed, MlcpStoragesDisagree) {
  // C = 5 in type 2 but M(0,1) = 1 in type 1.
  ExpectRejected("1 1 1 1\n0 1 2\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n2\n3\n5\n-1\n1\n-2\n", kMLCP,
                 {"M(0,1)", "disagree", "C(0,0)"});
  ExpectRejected("1 1 1 1\n0 1 2\n0 1\n0 2 2 2 2\n2 -1 1 3\n1 -2\n2\n3\n1\n-1\n1\n2\n", kMLCP,
                 {"q[1]", "disagree", "b[0]"});
  ExpectRejected("1 1 1 1\n0 1 2\n0 1\n0 3 2 3 2\n2 -1 1 3 0 0\n1 -2\n2\n3\n1\n-1\n1\n-2\n", kMLCP,
                 {"M", "3x2", "rectangular"});
}

TEST(SiconosMalformed, SparseBlockStructure) {
  // The 2x2 lcp_deudeu_block layout: one 2x2 block.
  const std::string head = "2\n1\n2\n2\n";
  EXPECT_EQ(ReadText(head + "1 1 1 2 2 2 1 0 1 0 0 2 1 1 2 -5 -6", kLCP).size(), 2);
  ExpectRejected(head + "1 1 1 3 2 2 1 0 1 0 0 2 1 1 2 -5 -6", kLCP, {"M blocksize0[0]"});
  ExpectRejected(head + "1 1 1 1 2 2 1 0 1 0 0 2 1 1 2 -5 -6", kLCP, {"M blocksize0[0]", "end at 1"});
  ExpectRejected(head + "1 1 1 2 2 3 1 0 1 0 0 2 1 1 2 -5 -6", kLCP, {"M filled1"});
  ExpectRejected(head + "1 1 1 2 2 2 2 0 1 0 0 2 1 1 2 -5 -6", kLCP, {"M filled2"});
  ExpectRejected(head + "1 1 1 2 2 2 1 1 1 0 0 2 1 1 2 -5 -6", kLCP, {"M index1_data[0]"});
  ExpectRejected(head + "1 1 1 2 2 2 1 0 0 0 0 2 1 1 2 -5 -6", kLCP, {"M index1_data[1]", "end at 0"});
  ExpectRejected(head + "1 1 1 2 2 2 1 0 1 1 0 2 1 1 2 -5 -6", kLCP, {"M index2_data[0]"});
  ExpectRejected(head + "1 1 1 2 2 2 1 0 1 0 3 2 1 1 2 -5 -6", kLCP, {"M block number[0]"});
  ExpectRejected(head + "1 1 1 2 2 2 1 0 1 0 0 2 nan 1 2 -5 -6", kLCP, {"M(1,0)", "NaN"});
  ExpectRejected(head + "5 1 1 2 2 2 1 0 1 0 0 2 1 1 2 -5 -6", kLCP, {"M nbblocks", "block grid"});
  // One block row holding the same block column twice.
  ExpectRejected(head + "2 1 2 2 1 2 2 2 0 2 0 0", kLCP, {"M index2_data[1]"});
  // Two 1x2 block rows: M = [1 1; 1 2]; then block-row pointers that decrease.
  const BoxMLCP two = ReadText(head + "2 2 1 1 2 2 3 2 0 1 2 0 0 0 1 1 1 1 2 -5 -6", kLCP);
  EXPECT_EQ(two.ToDense(), (DenseMatrix(2, 2) << 1, 1, 1, 2).finished());
  ExpectRejected(head + "2 2 1 1 2 2 3 2 0 2 1 0 0 0 1 1 1 1 2 -5 -6", kLCP, {"M index1_data[2]"});
  // nbblocks = 0: Siconos' all-zero matrix.
  const BoxMLCP zero = ReadText(head + "0 -5 -6", kLCP);
  EXPECT_EQ(zero.sparse_matrix().nonZeros(), 0);
}

// Never crash: every truncation and many single-byte corruptions of valid inputs parse or throw
// InvalidInputError (run under ASan/UBSan in the sanitizer build).
TEST(SiconosMalformed, MutatedInputsNeverCrash) {
  const std::string block = "2\n1\n2\n2\n1 1 1 2 2 2 1 0 1 0 0 2 1 1 2 -5 -6\n";
  const std::vector<std::pair<std::string, SiconosKind>> seeds = {
      {kGoodLcp, kLCP}, {kGoodRelay, kRelay}, {kGoodMlcp, kMLCP}, {block, kLCP}};
  const std::string replacements = Bytes("0-1+9e.# \n\0x");
  std::uint64_t state = 12345;
  const auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return state >> 33;
  };
  int accepted = 0;
  int rejected = 0;
  const auto attempt = [&](const std::string& text, SiconosKind kind) {
    try {
      ReadText(text, kind);
      ++accepted;
    } catch (const InvalidInputError&) {
      ++rejected;
    }
  };
  for (const auto& [text, kind] : seeds) {
    for (std::size_t cut = 0; cut < text.size(); ++cut) attempt(text.substr(0, cut), kind);
    for (int trial = 0; trial < 400; ++trial) {
      std::string mutated = text;
      const int edits = 1 + static_cast<int>(next() % 3);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = next() % mutated.size();
        const char c = replacements[next() % replacements.size()];
        switch (next() % 3) {
          case 0:
            mutated[at] = c;
            break;
          case 1:
            mutated.insert(mutated.begin() + static_cast<std::ptrdiff_t>(at), c);
            break;
          default:
            if (mutated.size() > 1) mutated.erase(at, 1);
        }
      }
      attempt(mutated, kind);
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace smcbench
