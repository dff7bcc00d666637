// Matrix Market problem files: bit-for-bit round trips against the original numbers (infinite bounds, subnormals,
// -0, explicit zeros), Eigen's own MarketIO reading what we write and writing what we read, hand-written files
// with known entries, and one test per kind of bad file (the message names the file and what is wrong).
#include "problems/io/matrix_market.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unsupported/Eigen/SparseExtra>
#include <vector>

#include <unistd.h>

namespace smcbench {
namespace {

namespace fs = std::filesystem;
constexpr double kInf = std::numeric_limits<double>::infinity();

class MatrixMarketTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("smcbench-mtx-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  void Write(const std::string& name, const std::string& text) const { std::ofstream(Path(name)) << text; }
  // Expects the read of P.mtx to fail with a message holding every needle.
  void ExpectRejected(const std::string& matrix, const std::vector<std::string>& needles) const {
    try {
      ReadMatrixMarketProblem(Path(matrix));
      ADD_FAILURE() << "accepted " << matrix;
    } catch (const InvalidInputError& e) {
      for (const std::string& needle : needles) EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
          << "message: " << e.what() << "\nmissing: " << needle;
    }
  }
  fs::path dir_;
};

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSameBits(const Vector& a, const Vector& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index i = 0; i < a.size(); ++i) EXPECT_TRUE(SameBits(a[i], b[i])) << what << "[" << i << "]";
}

TEST_F(MatrixMarketTest, DenseRoundTripIsBitForBitWithInfiniteBounds) {
  DenseMatrix M(3, 3);
  M << 0.1, 1.0 / 3.0, -0.0,  //
      4.9e-324, 1e308, -2.5,  //
      0.0, 7.0, std::nextafter(1.0, 2.0);
  Vector q(3), l(3), u(3);
  q << -1.0 / 7.0, 0.0, 3e-310;
  l << -kInf, 0.0, -1.0;
  u << kInf, kInf, 1.0;
  const BoxMLCP original(M, q, l, u, "dense3");
  WriteMatrixMarketProblem(original, Path("p.mtx"));
  for (const char* file : {"p.mtx", "p_q.mtx", "p_l.mtx", "p_u.mtx"}) EXPECT_TRUE(fs::exists(Path(file))) << file;

  const BoxMLCP read = ReadMatrixMarketProblem(Path("p.mtx"));
  ASSERT_FALSE(read.is_sparse());
  EXPECT_EQ(read.name(), "p");
  for (Eigen::Index j = 0; j < 3; ++j) {
    for (Eigen::Index i = 0; i < 3; ++i) EXPECT_TRUE(SameBits(read.dense_matrix()(i, j), M(i, j))) << i << "," << j;
  }
  ExpectSameBits(read.q(), q, "q");
  ExpectSameBits(read.l(), l, "l");
  ExpectSameBits(read.u(), u, "u");
  EXPECT_EQ(read.l()[0], -kInf);
  EXPECT_EQ(read.u()[1], kInf);
}

TEST_F(MatrixMarketTest, SparseRoundTripKeepsStructureAndExplicitZeros) {
  std::vector<Eigen::Triplet<double, int>> entries{{0, 0, 2.0}, {3, 0, -1e-17}, {1, 1, 0.0}, {2, 2, 5.5},
                                                   {0, 3, 0.3}, {3, 3, 1.0 / 9.0}};
  SparseMatrix M(4, 4);
  M.setFromTriplets(entries.begin(), entries.end());
  M.makeCompressed();
  Vector q(4), l(4), u(4);
  q << 1.0, -2.0, 0.125, 1e-5;
  l << -1.0, -kInf, 0.0, -kInf;
  u << 1.0, kInf, kInf, 2.0;
  const BoxMLCP original(M, q, l, u, "sparse4");
  WriteMatrixMarketProblem(original, Path("s.mtx"));
  const BoxMLCP read = ReadMatrixMarketProblem(Path("s.mtx"));
  ASSERT_TRUE(read.is_sparse());
  const SparseMatrix& R = read.sparse_matrix();
  ASSERT_EQ(R.nonZeros(), 6);  // the explicit zero at (1,1) is kept
  for (int j = 0; j < 4; ++j) {
    SparseMatrix::InnerIterator a(M, j), b(R, j);
    for (; a && b; ++a, ++b) {
      EXPECT_EQ(a.row(), b.row());
      EXPECT_TRUE(SameBits(a.value(), b.value())) << a.row() << "," << j;
    }
    EXPECT_FALSE(a || b) << "column " << j << " differs in length";
  }
  ExpectSameBits(read.q(), q, "q");
  ExpectSameBits(read.l(), l, "l");
  ExpectSameBits(read.u(), u, "u");
}

// Eigen's MarketIO is an independent implementation of the format: it reads what we write, we read what it writes.
TEST_F(MatrixMarketTest, EigenMarketIOReadsOurFilesAndWeReadItsFiles) {
  std::vector<Eigen::Triplet<double, int>> entries{{0, 0, 4.0}, {1, 0, -1.0 / 3.0}, {1, 1, 4.0}, {2, 1, 0.7},
                                                   {2, 2, 1e-200}};
  SparseMatrix M(3, 3);
  M.setFromTriplets(entries.begin(), entries.end());
  Vector q(3);
  q << -1.0, 0.1, 2.0 / 3.0;
  WriteMatrixMarketProblem(BoxMLCP(M, q, Vector::Zero(3), Vector::Constant(3, kInf), "lcp"), Path("ours.mtx"));
  SparseMatrix by_eigen;
  ASSERT_TRUE(Eigen::loadMarket(by_eigen, Path("ours.mtx")));
  ASSERT_EQ(by_eigen.nonZeros(), M.nonZeros());
  EXPECT_EQ(DenseMatrix(by_eigen), DenseMatrix(M));
  Vector q_by_eigen;
  ASSERT_TRUE(Eigen::loadMarketVector(q_by_eigen, Path("ours_q.mtx")));
  EXPECT_EQ(q_by_eigen, q);

  ASSERT_TRUE(Eigen::saveMarket(M, Path("theirs.mtx")));
  ASSERT_TRUE(Eigen::saveMarketVector(q, Path("theirs_q.mtx")));
  const BoxMLCP read = ReadMatrixMarketProblem(Path("theirs.mtx"));  // no _l/_u files: an LCP
  ASSERT_TRUE(read.is_sparse());
  EXPECT_EQ(DenseMatrix(read.sparse_matrix()), DenseMatrix(M));
  EXPECT_EQ(read.q(), q);
  EXPECT_EQ(read.l(), Vector::Zero(3));
  EXPECT_EQ(read.u(), Vector::Constant(3, kInf));
}

TEST_F(MatrixMarketTest, HandWrittenSymmetricFileIsMirrored) {
  Write("h.mtx", "%%MatrixMarket matrix coordinate integer symmetric\n% a comment\n\n2 2 3\n1 1 4\n2 1 -1\n2 2 3\n");
  Write("h_q.mtx", "%%MatrixMarket matrix array real general\n2 1\n+1.5\n-inf\n");
  ExpectRejected("h.mtx", {"h_q.mtx", "q[1] = -inf", "q must be finite"});
  Write("h_q.mtx", "%%MatrixMarket matrix array real general\n2 1\n+1.5 -2e0\n");
  Write("h_u.mtx", "%%MatrixMarket matrix array real general\n2 1\n1\ninf\n");
  const BoxMLCP read = ReadMatrixMarketProblem(Path("h.mtx"));
  const DenseMatrix M = read.ToDense();
  EXPECT_EQ(M(0, 0), 4.0);
  EXPECT_EQ(M(0, 1), -1.0);
  EXPECT_EQ(M(1, 0), -1.0);
  EXPECT_EQ(M(1, 1), 3.0);
  EXPECT_EQ(read.q()[0], 1.5);
  EXPECT_EQ(read.q()[1], -2.0);
  EXPECT_EQ(read.l(), Vector::Zero(2));  // no h_l.mtx
  EXPECT_EQ(read.u()[0], 1.0);
  EXPECT_EQ(read.u()[1], kInf);
}

// SciPy 1.10's scipy.io.mmwrite of the symmetric dense M below writes 'array real symmetric': the lower triangle,
// column by column (the text is its output, byte for byte). Read, it is the full matrix.
TEST_F(MatrixMarketTest, ArraySymmetricAsSciPyWritesItIsTheFullMatrix) {
  Write("s.mtx",
        "%%MatrixMarket matrix array real symmetric\n%\n3 3\n4.0000000000000000e+00\n-1.0000000000000000e+00\n"
        "5.0000000000000000e-01\n3.0000000000000000e+00\n2.0000000000000000e+00\n5.0000000000000000e+00\n");
  Write("s_q.mtx", "%%MatrixMarket matrix array real general\n3 1\n1\n2\n3\n");
  const BoxMLCP read = ReadMatrixMarketProblem(Path("s.mtx"));
  DenseMatrix expected(3, 3);
  expected << 4.0, -1.0, 0.5, -1.0, 3.0, 2.0, 0.5, 2.0, 5.0;
  EXPECT_FALSE(read.is_sparse());
  EXPECT_EQ(read.ToDense(), expected);
  // A short or long lower triangle names the count it expected.
  Write("t.mtx", "%%MatrixMarket matrix array real symmetric\n3 3\n1\n2\n3\n4\n5\n");
  Write("t_q.mtx", "%%MatrixMarket matrix array real general\n3 1\n1\n2\n3\n");
  ExpectRejected("t.mtx", {"t.mtx", "only 5 of the 6 entries", "lower triangle"});
  Write("t.mtx", "%%MatrixMarket matrix array real symmetric\n2 2\n1\n2\n3\n4\n");
  Write("t_q.mtx", "%%MatrixMarket matrix array real general\n2 1\n1\n2\n");
  ExpectRejected("t.mtx", {"t.mtx", "line 6", "trailing data '4' after the last entry"});
}

TEST_F(MatrixMarketTest, BadFilesAreClearErrorsNamingTheFile) {
  const std::string vector_q = "%%MatrixMarket matrix array real general\n2 1\n1\n2\n";
  Write("a.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1\n");
  ExpectRejected("a.mtx", {"a_q.mtx", "missing", "required"});
  Write("a_q.mtx", vector_q);
  EXPECT_NO_THROW(ReadMatrixMarketProblem(Path("a.mtx")));

  Write("b.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n1 1 2\n");
  Write("b_q.mtx", vector_q);
  ExpectRejected("b.mtx", {"b.mtx", "M(1,1) is given twice (lines 3 and 4)"});
  Write("c.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n");
  ExpectRejected("c.mtx", {"c.mtx", "line 3", "above the diagonal"});
  Write("d.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2 2 x\n");
  ExpectRejected("d.mtx", {"d.mtx", "line 4", "M(2,2): expected a number, got 'x'"});
  Write("e.mtx", "%%MatrixMarket matrix coordinate real general\n2 3 1\n1 1 1\n");
  ExpectRejected("e.mtx", {"e.mtx", "2 x 3", "square"});
  Write("f.mtx", "%%MatrixMarket matrix coordinate complex general\n2 2 1\n1 1 1 0\n");
  ExpectRejected("f.mtx", {"f.mtx", "line 1", "'complex' is not supported"});
  Write("g.mtx", "%%MatrixMarket matrix array real general\n2 2\n1 2 3\n");
  ExpectRejected("g.mtx", {"g.mtx", "only 3 of the 4 entries"});
  Write("i.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1\n");
  ExpectRejected("i.mtx", {"i.mtx", "line 3", "row = 3 is outside 1 ... 2"});
  Write("j.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 1\n1 1 1\n");
  Write("j_q.mtx", vector_q);
  ExpectRejected("j.mtx", {"j_q.mtx", "q has 2 entries but M is 3 x 3"});
  Write("k.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1\n");
  Write("k_q.mtx", vector_q);
  Write("k_l.mtx", "%%MatrixMarket matrix array real general\n2 1\ninf\n0\n");
  ExpectRejected("k.mtx", {"k_l.mtx", "l[0] = inf", "no feasible point"});
  Write("k_l.mtx", "%%MatrixMarket matrix array real general\n2 1\n0\n3\n");
  Write("k_u.mtx", "%%MatrixMarket matrix array real general\n2 1\n1\n2\n");
  ExpectRejected("k.mtx", {"k_l.mtx", "l[1] = 3 > u[1] = 2", "k_u.mtx"});
  Write("m.mtx", "1 1 1\n");
  ExpectRejected("m.mtx", {"m.mtx", "line 1", "expected the banner"});
  ExpectRejected("absent.mtx", {"absent.mtx", "cannot open"});
  EXPECT_THROW(ReadMatrixMarketProblem(Path("p.txt")), InvalidInputError);
  EXPECT_THROW(WriteMatrixMarketProblem(BoxMLCP::LCP(DenseMatrix::Identity(1, 1), Vector::Ones(1)),
                                        (dir_ / "no-such-dir" / "x.mtx").string()),
               InvalidInputError);
}

}  // namespace
}  // namespace smcbench
