// The matrix-class module against matrices whose class is known by hand: P-matrices without a positive definite
// symmetric part, a negative principal minor, singular PSD matrices, near-symmetry on both sides of the margin,
// size limits and non-finite input.
#include "solvers/core/matrix_class.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

constexpr auto kYes = MatrixClassAnswer::kYes;
constexpr auto kNo = MatrixClassAnswer::kNo;
constexpr auto kNotDecided = MatrixClassAnswer::kNotDecided;

DenseMatrix Matrix2(double a, double b, double c, double d) {
  DenseMatrix M(2, 2);
  M << a, b, c, d;
  return M;
}

const PMatrixOptions kHadamard{10, PrincipalMinorTest::kDeterminantVsHadamard, 16.0};
const DefinitenessOptions kEigen{DefinitenessTest::kEigenvalues, 8.0};

TEST(MatrixClass, PMatrixWhoseSymmetricPartIsIndefinite) {
  // Minors 1, 1, 1 (upper triangular); (M + Mᵀ)/2 = [1 −1.5; −1.5 1] has eigenvalues −0.5 and 2.5.
  const DenseMatrix M = Matrix2(1, -3, 0, 1);
  for (const PMatrixOptions& options : {PMatrixOptions{}, kHadamard}) {
    const PMatrixResult p = ClassifyPMatrix(M, options);
    EXPECT_EQ(p.answer, kYes);
    EXPECT_FALSE(p.too_large);
    EXPECT_DOUBLE_EQ(p.minor, 1.0);  // the smallest principal minor
  }
  EXPECT_EQ(ClassifySymmetricPartPositiveDefinite(M).answer, kNo);
  const DefinitenessResult eig = ClassifySymmetricPartPositiveDefinite(M, kEigen);
  EXPECT_EQ(eig.answer, kNo);
  EXPECT_NEAR(eig.certificate, -0.5, 1e-14);
  // A 3×3 cyclic P-matrix (minors 1, 1 and det = 1 + 27 = 28) whose symmetric part has eigenvalues −0.5, −0.5, 4.
  DenseMatrix C(3, 3);
  C << 1, 3, 0, 0, 1, 3, 3, 0, 1;
  EXPECT_EQ(ClassifyPMatrix(C).answer, kYes);
  EXPECT_EQ(ClassifyPMatrix(C, kHadamard).answer, kYes);
  EXPECT_EQ(ClassifySymmetricPartPositiveDefinite(C).answer, kNo);
  EXPECT_NEAR(ClassifySymmetricPartPositiveDefinite(C, kEigen).certificate, -0.5, 1e-14);
}

TEST(MatrixClass, NegativePrincipalMinorIsTheCertificate) {
  // Positive diagonal, det = 1 − 6 = −5.
  for (const PMatrixOptions& options : {PMatrixOptions{}, kHadamard}) {
    const PMatrixResult p = ClassifyPMatrix(Matrix2(1, 2, 3, 1), options);
    EXPECT_EQ(p.answer, kNo);
    EXPECT_EQ(p.minor_rows, (std::vector<int>{0, 1}));
    EXPECT_NEAR(p.minor, -5.0, 1e-14);
  }
  // A negative diagonal entry is a 1×1 minor.
  const PMatrixResult d = ClassifyPMatrix(Matrix2(2, 0, 0, -1));
  EXPECT_EQ(d.answer, kNo);
  EXPECT_EQ(d.minor_rows, std::vector<int>{1});
  EXPECT_EQ(d.minor, -1.0);
}

TEST(MatrixClass, PMatrixAgreesWithDeterminantsComputedIndependently) {
  // Random 6×6 matrices with a shifted diagonal: some are P-matrices, some not; the answer must match the signs
  // of all 63 determinants by full-pivoting LU (every minor here is far from zero).
  int yes = 0, no = 0;
  for (int seed = 1; seed <= 40; ++seed) {
    std::srand(static_cast<unsigned>(seed));
    DenseMatrix M = DenseMatrix::Random(6, 6);
    M.diagonal().array() += 1.2;
    bool all_positive = true;
    double smallest = kInf;
    for (unsigned mask = 1; mask < 64u; ++mask) {
      std::vector<int> rows;
      for (int i = 0; i < 6; ++i) {
        if (mask >> i & 1u) rows.push_back(i);
      }
      DenseMatrix A(rows.size(), rows.size());
      for (std::size_t c = 0; c < rows.size(); ++c) {
        for (std::size_t r = 0; r < rows.size(); ++r) A(r, c) = M(rows[r], rows[c]);
      }
      const double det = Eigen::FullPivLU<DenseMatrix>(A).determinant();
      all_positive = all_positive && det > 0.0;
      smallest = std::min(smallest, std::abs(det));
    }
    if (smallest < 1e-6) continue;  // too close to call for an independent check
    for (const PMatrixOptions& options : {PMatrixOptions{}, kHadamard}) {
      const PMatrixResult p = ClassifyPMatrix(M, options);
      EXPECT_EQ(p.answer, all_positive ? kYes : kNo) << "seed " << seed;
    }
    (all_positive ? yes : no) += 1;
  }
  EXPECT_GT(yes, 0);
  EXPECT_GT(no, 0);
}

TEST(MatrixClass, SingularPositiveSemidefinite) {
  const DenseMatrix M = Matrix2(1, 1, 1, 1);  // eigenvalues 0 and 2
  Eigen::LLT<DenseMatrix> factor;
  const SemidefinitenessResult psd = ClassifySymmetricPartPositiveSemidefinite(M, 1e-9, &factor);
  EXPECT_EQ(psd.answer, kYes);
  EXPECT_DOUBLE_EQ(psd.shift, 2e-9);  // 1e-9 · ‖M‖∞
  const SparseMatrix S = M.sparseView();
  EXPECT_EQ(ClassifySymmetricPartPositiveSemidefinite(S, 1e-9).answer, kYes);
  // λ_min = 0 sits inside every margin: positive definiteness is not decided, whichever test.
  EXPECT_EQ(ClassifySymmetricPartPositiveDefinite(M).answer, kNotDecided);
  const DefinitenessResult eig = ClassifySymmetricPartPositiveDefinite(M, kEigen);
  EXPECT_EQ(eig.answer, kNotDecided);
  EXPECT_NEAR(eig.certificate, 0.0, 1e-15);
  // Neither is a zero principal minor decided.
  EXPECT_EQ(ClassifyPMatrix(M).answer, kNotDecided);
  EXPECT_EQ(ClassifyPMatrix(M, kHadamard).answer, kNotDecided);
  EXPECT_EQ(ClassifyPMatrix(M).minor_rows, (std::vector<int>{0, 1}));
  // Indefinite: eigenvalues −1 and 3.
  const DenseMatrix N = Matrix2(1, 2, 2, 1);
  EXPECT_EQ(ClassifySymmetricPartPositiveSemidefinite(N, 1e-9, &factor).answer, kNo);
  EXPECT_EQ(ClassifySymmetricPartPositiveSemidefinite(SparseMatrix(N.sparseView()), 1e-9).answer, kNo);
  // The zero matrix is PSD (and not PD).
  EXPECT_EQ(ClassifySymmetricPartPositiveSemidefinite(DenseMatrix::Zero(3, 3), 0.0, &factor).answer, kYes);
  EXPECT_EQ(ClassifySymmetricPartPositiveDefinite(DenseMatrix::Zero(3, 3), kEigen).answer, kNo);
}

TEST(MatrixClass, PositiveDefiniteWithKnownSmallestEigenvalue) {
  // Q diag(0.5, 2, 3) Qᵀ: λ_min = 0.5 by construction.
  std::srand(7);
  const DenseMatrix Q = Eigen::HouseholderQR<DenseMatrix>(DenseMatrix::Random(3, 3)).householderQ();
  const DenseMatrix M = Q * Eigen::Vector3d(0.5, 2.0, 3.0).asDiagonal() * Q.transpose();
  const DefinitenessResult eig = ClassifySymmetricPartPositiveDefinite(M, kEigen);
  EXPECT_EQ(eig.answer, kYes);
  EXPECT_NEAR(eig.certificate, 0.5, 1e-13);
  const DefinitenessResult chol = ClassifySymmetricPartPositiveDefinite(M);
  EXPECT_EQ(chol.answer, kYes);
  EXPECT_GT(chol.certificate, 0.0);
  // Every pivot L_kk² of a Cholesky factor lies between λ_min and λ_max.
  EXPECT_GE(chol.certificate, 0.5 - 1e-12);
  EXPECT_LE(chol.certificate, 3.0 + 1e-12);
}

TEST(MatrixClass, NearlySymmetricWithinAndOutsideTheMargin) {
  // max|M| = 2, so the default margin 1e-12 allows an asymmetry up to 2e-12.
  const DenseMatrix inside = Matrix2(2, 1, 1 + 1e-13, 2);
  const DenseMatrix outside = Matrix2(2, 1, 1 + 1e-11, 2);
  const SymmetryResult a = ClassifySymmetry(inside);
  EXPECT_EQ(a.answer, kYes);
  EXPECT_EQ(a.max_entry, 2.0);
  EXPECT_GT(a.max_asymmetry, 0.0);
  const SymmetryResult b = ClassifySymmetry(outside);
  EXPECT_EQ(b.answer, kNo);
  EXPECT_EQ(b.row, 1);  // the offending pair
  EXPECT_EQ(b.col, 0);
  EXPECT_NEAR(b.max_asymmetry, 1e-11, 1e-15);
  EXPECT_EQ(ClassifySymmetry(outside, SymmetryOptions{1e-10}).answer, kYes);
  EXPECT_EQ(ClassifySymmetry(SparseMatrix(inside.sparseView())).answer, kYes);
  const SymmetryResult s = ClassifySymmetry(SparseMatrix(outside.sparseView()));
  EXPECT_EQ(s.answer, kNo);
  EXPECT_EQ(s.max_asymmetry, b.max_asymmetry);
  // Exactly symmetric: no offending pair.
  EXPECT_EQ(ClassifySymmetry(Matrix2(1, 3, 3, 1)).row, -1);
  // A sparse entry without its transpose partner is asymmetric by its full size.
  SparseMatrix lower(3, 3);
  lower.insert(2, 0) = 0.5;
  lower.insert(1, 1) = 1.0;
  const SymmetryResult l = ClassifySymmetry(lower);
  EXPECT_EQ(l.answer, kNo);
  EXPECT_EQ(l.max_asymmetry, 0.5);
  EXPECT_EQ(l.row, 2);
  // Row weights: diag(1, 2) [4 2; 1 3] = [4 2; 2 6] is symmetric, [4 2; 1 3] itself is not.
  const DenseMatrix scaled = Matrix2(4, 2, 1, 3);
  const Vector weights = Eigen::Vector2d(1.0, 2.0);
  EXPECT_EQ(ClassifySymmetry(scaled).answer, kNo);
  EXPECT_EQ(ClassifySymmetry(scaled, {}, &weights).answer, kYes);
  EXPECT_EQ(ClassifySymmetry(SparseMatrix(scaled.sparseView()), {}, &weights).answer, kYes);
  EXPECT_EQ(ClassifySymmetry(scaled, {}, &weights).max_entry, 6.0);
}

TEST(MatrixClass, SymmetricAndSkewPartNormsHaveTheirHandComputedValues) {
  // Symmetric: M + Mᵀ = [4 2; 2 6] → 16 + 4 + 4 + 36 = 60; no skew part at all.
  const SymmetricSkewNorms symmetric = SymmetricAndSkewPartNorms(Matrix2(2, 1, 1, 3));
  EXPECT_EQ(symmetric.symmetric_squared, 60.0);
  EXPECT_EQ(symmetric.skew_squared, 0.0);
  EXPECT_FALSE(symmetric.SkewOutweighsSymmetric(0.0));
  // Pure skew: M + Mᵀ = 0, M − Mᵀ = [0 4; −4 0] → 32; outweighs a symmetric part of nothing at any ratio.
  const SymmetricSkewNorms skew = SymmetricAndSkewPartNorms(Matrix2(0, 2, -2, 0));
  EXPECT_EQ(skew.symmetric_squared, 0.0);
  EXPECT_EQ(skew.skew_squared, 32.0);
  EXPECT_TRUE(skew.SkewOutweighsSymmetric(1e6));
  // [1 3; 1 2]: M + Mᵀ = [2 4; 4 4] → 52, M − Mᵀ = [0 2; −2 0] → 8.
  const SymmetricSkewNorms mixed = SymmetricAndSkewPartNorms(Matrix2(1, 3, 1, 2));
  EXPECT_EQ(mixed.symmetric_squared, 52.0);
  EXPECT_EQ(mixed.skew_squared, 8.0);
  EXPECT_TRUE(mixed.SkewOutweighsSymmetric(0.3));   // 8 > 0.09 · 52
  EXPECT_FALSE(mixed.SkewOutweighsSymmetric(0.5));  // 8 ≤ 0.25 · 52
  // 3×3: M + Mᵀ has diagonal 2, 2, 4 and pairs 2, −1, 3 → 24 + 2·14 = 52; M − Mᵀ has pairs 2, 1, 3 → 2·14 = 28.
  DenseMatrix M3(3, 3);
  M3 << 1, 2, 0, 0, 1, 3, -1, 0, 2;
  const SymmetricSkewNorms three = SymmetricAndSkewPartNorms(M3);
  EXPECT_EQ(three.symmetric_squared, 52.0);
  EXPECT_EQ(three.skew_squared, 28.0);
  EXPECT_EQ(three.symmetric_squared, (M3 + M3.transpose()).squaredNorm());
  EXPECT_EQ(three.skew_squared, (M3 - M3.transpose()).squaredNorm());
  // The limit is strict: [a b; −b a] has 8a² and 8b², so b = 2a is exactly ratio 2 (bpp's limit: still swept) and
  // b = 4a exactly ratio 4 (auto's limit: not skew-dominant).
  EXPECT_FALSE(SymmetricAndSkewPartNorms(Matrix2(1, 2, -2, 1)).SkewOutweighsSymmetric(2.0));
  EXPECT_TRUE(SymmetricAndSkewPartNorms(Matrix2(1, 2, -2, 1)).SkewOutweighsSymmetric(1.99));
  EXPECT_FALSE(SymmetricAndSkewPartNorms(Matrix2(1, 4, -4, 1)).SkewOutweighsSymmetric(4.0));
  EXPECT_TRUE(SymmetricAndSkewPartNorms(Matrix2(1, 4.01, -4.01, 1)).SkewOutweighsSymmetric(4.0));
  // Nothing at all: neither part, and nothing outweighs nothing.
  const SymmetricSkewNorms zero = SymmetricAndSkewPartNorms(DenseMatrix::Zero(3, 3));
  EXPECT_EQ(zero.symmetric_squared, 0.0);
  EXPECT_FALSE(zero.SkewOutweighsSymmetric(4.0));
}

TEST(MatrixClass, TooLargeIsNotDecidedNotNo) {
  const DenseMatrix I = DenseMatrix::Identity(13, 13);  // certainly a P-matrix, but above the default size 12
  const PMatrixResult p = ClassifyPMatrix(I);
  EXPECT_EQ(p.answer, kNotDecided);
  EXPECT_TRUE(p.too_large);
  EXPECT_TRUE(p.minor_rows.empty());
  EXPECT_EQ(ClassifyPMatrix(I, PMatrixOptions{13}).answer, kYes);
  EXPECT_THROW(ClassifyPMatrix(I, PMatrixOptions{kMaxPMatrixTestSize + 1}), InvalidInputError);
  EXPECT_THROW(ClassifyPMatrix(I, PMatrixOptions{-1}), InvalidInputError);
}

TEST(MatrixClass, NonFiniteOrNonSquareInputIsAnErrorNamingTheEntry) {
  DenseMatrix M = DenseMatrix::Identity(2, 2);
  M(1, 0) = kNaN;
  const auto expect_names_entry = [](auto&& call) {
    try {
      call();
      ADD_FAILURE() << "no InvalidInputError";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find("M(1, 0)"), std::string::npos) << e.what();
    }
  };
  Eigen::LLT<DenseMatrix> factor;
  expect_names_entry([&] { ClassifySymmetry(M); });
  expect_names_entry([&] { ClassifySymmetry(SparseMatrix(M.sparseView(0.0, 0.0))); });
  expect_names_entry([&] { ClassifySymmetricPartPositiveDefinite(M); });
  expect_names_entry([&] { ClassifySymmetricPartPositiveDefinite(M, kEigen); });
  expect_names_entry([&] { ClassifySymmetricPartPositiveSemidefinite(M, 1e-9, &factor); });
  expect_names_entry([&] { ClassifyPMatrix(M); });
  M(1, 0) = kInf;
  expect_names_entry([&] { ClassifyPMatrix(M, kHadamard); });
  EXPECT_THROW(ClassifySymmetry(DenseMatrix(2, 3)), InvalidInputError);
  EXPECT_THROW(ClassifySymmetricPartPositiveSemidefinite(DenseMatrix::Identity(2, 2), -1.0, &factor),
               InvalidInputError);
  const Vector wrong_size = Vector::Ones(3);
  EXPECT_THROW(ClassifySymmetry(DenseMatrix::Identity(2, 2), {}, &wrong_size), InvalidInputError);
  EXPECT_EQ(ToString(kNotDecided), "not decided");
}

}  // namespace
}  // namespace smcbench
