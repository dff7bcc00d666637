// The shared small LU (dense_lu.h) against Eigen's LU and hand-made facts: planted solutions, the exact inverse norm.
#include "solvers/core/dense_lu.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include <Eigen/LU>

namespace smcbench {
namespace {

DenseMatrix RandomMatrix(int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  DenseMatrix A(k, k);
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) A(i, j) = uniform(rng);
  }
  return A;
}

// Copies A into a column-major block with leading dimension ld (padding filled with NaN: must never be read).
std::vector<double> Block(const DenseMatrix& A, int ld) {
  std::vector<double> a(static_cast<size_t>(ld) * A.cols(), std::numeric_limits<double>::quiet_NaN());
  for (int j = 0; j < A.cols(); ++j) {
    for (int i = 0; i < A.rows(); ++i) a[i + static_cast<size_t>(j) * ld] = A(i, j);
  }
  return a;
}

TEST(DenseLu, SolvesPlantedSystemsOfEverySmallSize) {
  for (int k = 1; k <= 9; ++k) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
      const DenseMatrix A = RandomMatrix(k, 100 * k + seed);
      const Vector x_true = RandomMatrix(k, 7 * seed + k).col(0);
      const Vector b = A * x_true;
      const int ld = k + 2;
      std::vector<double> a = Block(A, ld);
      std::vector<int> piv(k);
      ASSERT_TRUE(dense_lu::Factor(a.data(), ld, k, piv.data(), 0.0));
      Vector x = b;
      dense_lu::Solve(a.data(), ld, k, piv.data(), x.data());
      // Forward error bound of a backward-stable solve: a modest multiple of κ∞(A)·ε·‖x‖∞.
      const double cond =
          A.lu().inverse().cwiseAbs().rowwise().sum().maxCoeff() * A.cwiseAbs().rowwise().sum().maxCoeff();
      const double bound = 1e3 * cond * std::numeric_limits<double>::epsilon() * x_true.cwiseAbs().maxCoeff();
      EXPECT_LE((x - x_true).cwiseAbs().maxCoeff(), bound) << "k = " << k;
    }
  }
}

TEST(DenseLu, FixedSizeInstantiationsMatchTheRunTimeOneBitForBit) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const DenseMatrix A = RandomMatrix(4, seed);
    std::vector<double> a4 = Block(A, 4), a0 = Block(A, 4);
    int p4[4], p0[4];
    ASSERT_TRUE(dense_lu::Factor<4>(a4.data(), 4, 4, p4, 0.0));
    ASSERT_TRUE(dense_lu::Factor(a0.data(), 4, 4, p0, 0.0));
    EXPECT_EQ(a4, a0);
    double b4[4] = {1, -2, 3, -4}, b0[4] = {1, -2, 3, -4};
    dense_lu::Solve<4>(a4.data(), 4, 4, p4, b4);
    dense_lu::Solve(a0.data(), 4, 4, p0, b0);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(b4[i], b0[i]);
  }
}

TEST(DenseLu, PivotsLikeEigenAndRefusesSingularBlocks) {
  DenseMatrix A(3, 3);
  A << 1, 2, 3, 4, 5, 6, 7, 8, 10;  // det = −3
  std::vector<double> a = Block(A, 3);
  int piv[3];
  ASSERT_TRUE(dense_lu::Factor(a.data(), 3, 3, piv, 0.0));
  EXPECT_EQ(piv[0], 2);  // |7| is the largest entry of column 0
  double det = 1.0;
  for (int j = 0; j < 3; ++j) det *= (piv[j] != j ? -1.0 : 1.0) * a[j + 3 * j];
  EXPECT_NEAR(det, -3.0, 1e-13);

  DenseMatrix S(3, 3);
  S << 1, 2, 3, 2, 4, 6, 1, 0, 1;  // row 2 = 2 · row 1
  std::vector<double> s = Block(S, 3);
  EXPECT_FALSE(dense_lu::FactorRelative(s.data(), 3, 3, piv));
  std::vector<double> zero(4, 0.0);
  EXPECT_FALSE(dense_lu::FactorRelative(zero.data(), 2, 2, piv));
}

TEST(DenseLu, RowMajorRightHandSidesAndTransposedSolve) {
  const int k = 5, m = 3;
  const DenseMatrix A = RandomMatrix(k, 42);
  const DenseMatrix X = RandomMatrix(k, 43).leftCols(m);
  const DenseMatrix B = A * X;
  std::vector<double> a = Block(A, k);
  std::vector<int> piv(k);
  ASSERT_TRUE(dense_lu::FactorRelative(a.data(), k, k, piv.data()));
  std::vector<double> rows(static_cast<size_t>(k) * m);  // row-major k×m
  for (int i = 0; i < k; ++i) {
    for (int c = 0; c < m; ++c) rows[static_cast<size_t>(i) * m + c] = B(i, c);
  }
  dense_lu::SolveRows(a.data(), k, k, piv.data(), rows.data(), m);
  for (int i = 0; i < k; ++i) {
    for (int c = 0; c < m; ++c) EXPECT_NEAR(rows[static_cast<size_t>(i) * m + c], X(i, c), 1e-11);
  }
  const Vector y_true = X.col(0);
  Vector y = A.transpose() * y_true;
  dense_lu::SolveTransposed(a.data(), k, k, piv.data(), y.data());
  EXPECT_LE((y - y_true).cwiseAbs().maxCoeff(), 1e-11);
}

TEST(DenseLu, HagerEstimateIsALowerBoundWithinAFactorOfTheExactNorm) {
  for (int k : {1, 2, 5, 12}) {
    const DenseMatrix A = RandomMatrix(k, 300 + k) + 0.5 * DenseMatrix::Identity(k, k);
    const double exact = A.lu().inverse().cwiseAbs().colwise().sum().maxCoeff();  // ‖A⁻¹‖₁
    std::vector<double> a = Block(A, k), x(k), y(k);
    std::vector<int> piv(k);
    ASSERT_TRUE(dense_lu::FactorRelative(a.data(), k, k, piv.data()));
    const double estimate = dense_lu::InverseNorm1Estimate(a.data(), k, k, piv.data(), x.data(), y.data());
    EXPECT_LE(estimate, exact * (1.0 + 1e-12)) << "k = " << k;
    EXPECT_GE(estimate, exact / 10.0) << "k = " << k;
  }
}

// The multipliers are quotients, not products with a reciprocal: a 2×2 block gives the bits of elimination by hand
// (m = a10 / a00, u11 = a11 − m·a01, back substitution by division), which the exact polish, a session's stored
// active set and the enumerative fast path all rely on to agree bit for bit.
TEST(DenseLu, TwoByTwoIsEliminationByHandBitForBit) {
  for (unsigned seed = 0; seed < 200; ++seed) {
    const DenseMatrix A = RandomMatrix(2, seed);
    std::vector<double> a = Block(A, 2);
    int piv[2];
    ASSERT_TRUE(dense_lu::Factor(a.data(), 2, 2, piv, 0.0));
    const bool swap = std::abs(A(1, 0)) > std::abs(A(0, 0));
    const double a00 = swap ? A(1, 0) : A(0, 0), a10 = swap ? A(0, 0) : A(1, 0);
    const double a01 = swap ? A(1, 1) : A(0, 1), a11 = swap ? A(0, 1) : A(1, 1);
    const double m = a10 / a00, u11 = a11 - m * a01;
    EXPECT_EQ(piv[0], swap ? 1 : 0);
    EXPECT_EQ(a[1], m) << seed;
    EXPECT_EQ(a[3], u11) << seed;
    const double b0 = 0.25 + seed, b1 = -1.5;
    double b[2] = {b0, b1};
    dense_lu::Solve(a.data(), 2, 2, piv, b);
    const double r0 = swap ? b1 : b0, r1 = swap ? b0 : b1;
    const double x1 = (r1 - m * r0) / u11;
    EXPECT_EQ(b[1], x1) << seed;
    EXPECT_EQ(b[0], (r0 - a01 * x1) / a00) << seed;
  }
}

}  // namespace
}  // namespace smcbench
