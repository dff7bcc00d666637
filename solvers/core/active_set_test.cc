// The active-set kernel (active_set.h) on problems with a planted solution: dense and sparse, infinite bounds, a
// wrong set caught by the sign check at a stated margin, a singular block reported, and no allocation on repeats.
#include "solvers/core/active_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "solvers/core/polish.h"
#include "solvers/core/problem.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

constexpr signed char kLow = static_cast<signed char>(RowState::kLower);
constexpr signed char kFree = static_cast<signed char>(RowState::kFree);
constexpr signed char kUp = static_cast<signed char>(RowState::kUpper);
constexpr signed char kFix = static_cast<signed char>(RowState::kFixed);

// A planted box-MLCP: z* and w* chosen first (w* > 0 at a lower bound, < 0 at an upper one, 0 on free rows and
// any value on a fixed row), q = w* − M z*.
struct Planted {
  DenseMatrix M;
  Vector q, l, u, z, w;
  std::vector<signed char> state;
};

// A nonsymmetric diagonally dominant M (every principal block nonsingular) on n rows; rows cycle through lower,
// free, upper and (with fixed) fixed.
Planted MakePlanted(int n, unsigned seed, bool with_fixed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Planted p;
  p.M = DenseMatrix(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) p.M(i, j) = uniform(rng);
  }
  for (int i = 0; i < n; ++i) p.M(i, i) = n + 1.0;
  p.l = Vector::Constant(n, -1.0);
  p.u = Vector::Constant(n, 2.0);
  p.z = Vector(n);
  p.w = Vector(n);
  p.state.resize(n);
  const int kinds = with_fixed ? 4 : 3;
  for (int i = 0; i < n; ++i) {
    switch (i % kinds) {
      case 0: p.state[i] = kLow, p.z[i] = p.l[i], p.w[i] = 0.5 + 0.1 * i; break;
      case 1: p.state[i] = kFree, p.z[i] = 0.3 * uniform(rng), p.w[i] = 0.0; break;
      case 2: p.state[i] = kUp, p.z[i] = p.u[i], p.w[i] = -0.7 - 0.1 * i; break;
      default: p.state[i] = kFix, p.l[i] = p.u[i] = 0.25, p.z[i] = 0.25, p.w[i] = uniform(rng); break;
    }
  }
  p.q = p.w - p.M * p.z;
  return p;
}

double MaxAbs(const Vector& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

TEST(ActiveSet, DenseSolveFindsThePlantedSolution) {
  for (int n : {1, 3, 7, 20}) {
    for (bool with_fixed : {false, true}) {
      const Planted p = MakePlanted(n, 17u + n, with_fixed);
      ActiveSetWorkspace workspace;
      ActiveSetScratch s = workspace.For(n);
      Vector z(n);
      int nf = -1;
      const ActiveSetOutcome outcome = active_set::SolveDense(p.M.data(), n, p.q.data(), p.l.data(), p.u.data(),
                                                              p.state.data(), 0.0, s, z.data(), &nf);
      ASSERT_EQ(outcome, ActiveSetOutcome::kSolved) << "n = " << n;
      int expected_free = 0;
      for (signed char st : p.state) expected_free += st == kFree;
      EXPECT_EQ(nf, expected_free);
      EXPECT_LE(MaxAbs(z - p.z), 1e-13) << "n = " << n;
      // Bound rows exactly at their bound (placed, not solved).
      for (int i = 0; i < n; ++i) {
        if (p.state[i] != kFree) {
          EXPECT_EQ(z[i], p.z[i]) << "row " << i;
        }
      }
      const Vector w = p.M * z + p.q;
      EXPECT_TRUE(active_set::BoundRowSignsHold(n, p.state.data(), w.data(), p.l.data(), p.u.data(), 0.0));
      // The factor-once path (a session's reused set) gives the same bits as the one-shot solve.
      ActiveSetFactors factors;
      factors.Resize(n);
      ASSERT_TRUE(factors.Factor(p.M, p.state.data()));
      Vector z2(n);
      ASSERT_TRUE(factors.Solve<0>(p.M, p.q.data(), p.l.data(), p.u.data(), z2.data()));
      for (int i = 0; i < n; ++i) EXPECT_EQ(z2[i], z[i]) << "row " << i;
    }
  }
}

// Its affine map z = A q + c reproduces the solve for every q (checked on two q of the same active set).
TEST(ActiveSet, AffineMapMatchesTheSolve) {
  const int n = 4;
  const Planted p = MakePlanted(n, 5u, false);
  ActiveSetFactors factors;
  factors.Resize(n);
  ASSERT_TRUE(factors.Factor(p.M, p.state.data()));
  DenseMatrix A(n, n);
  Vector c(n);
  int free_row = -2;
  factors.AffineMap(p.M, p.l.data(), p.u.data(), A.data(), c.data(), &free_row);
  EXPECT_EQ(free_row, 1);  // rows 0..3 are lower, free, upper, lower: one free row
  for (double shift : {0.0, 1e-3}) {
    const Vector q = p.q + Vector::Constant(n, shift);
    Vector z(n);
    factors.Solve<0>(p.M, q.data(), p.l.data(), p.u.data(), z.data());
    EXPECT_LE(MaxAbs(A * q + c - z), 1e-14);
  }
}

// Free rows with both bounds infinite and one-sided rows: z_F from M_FF z_F = −(q_F + M_FB z_B), checked against
// Eigen's LU of the same block (an independent solve).
TEST(ActiveSet, InfiniteBounds) {
  const double inf = std::numeric_limits<double>::infinity();
  DenseMatrix M(4, 4);
  M << 4, 1, 0, 1,  //
      1, 5, 2, 0,   //
      0, 1, 6, 1,   //
      2, 0, 1, 3;
  const Vector q = (Vector(4) << 1.0, -2.0, 3.0, 0.5).finished();
  const Vector l = (Vector(4) << -inf, -inf, 0.0, -inf).finished();
  const Vector u = (Vector(4) << inf, inf, inf, 1.0).finished();
  const std::vector<signed char> state = {kFree, kFree, kLow, kUp};
  ActiveSetWorkspace workspace;
  Vector z(4);
  int nf = 0;
  ASSERT_EQ(active_set::SolveDense(M.data(), 4, q.data(), l.data(), u.data(), state.data(), 0.0, workspace.For(4),
                                   z.data(), &nf),
            ActiveSetOutcome::kSolved);
  EXPECT_EQ(nf, 2);
  EXPECT_EQ(z[2], 0.0);
  EXPECT_EQ(z[3], 1.0);
  const Vector rhs = -(q.head(2) + M.topRightCorner(2, 2) * z.tail(2));
  const Vector expected = M.topLeftCorner(2, 2).partialPivLu().solve(rhs);
  EXPECT_LE(MaxAbs(z.head(2) - expected), 1e-15);
  // The row at its finite lower bound of [0, ∞) and the row at its upper bound of (−∞, 1]: signs judged on w.
  const Vector w = M * z + q;
  EXPECT_EQ(active_set::BoundRowSignsHold(4, state.data(), w.data(), l.data(), u.data(), 0.0),
            w[2] >= 0.0 && w[3] <= 0.0);
}

// A wrong active set: the 1×1 problem 2 z − 1 ⊥ z ∈ [0, 1] has z* = 0.5 (free). Claiming z at its lower bound gives
// z = 0 and w = −1 (pushing into the box): rejected by the exact test and by any margin below |w| = 1, accepted by a
// margin above it. Margins are absolute, in the units of w.
TEST(ActiveSet, WrongSetIsRejectedByTheSignCheckWithItsMargin) {
  DenseMatrix M(1, 1);
  M << 2.0;
  const Vector q = Vector::Constant(1, -1.0), l = Vector::Zero(1), u = Vector::Ones(1);
  const signed char wrong[1] = {kLow};
  ActiveSetWorkspace workspace;
  Vector z(1);
  int nf = 0;
  ASSERT_EQ(active_set::SolveDense(M.data(), 1, q.data(), l.data(), u.data(), wrong, 0.0, workspace.For(1),
                                   z.data(), &nf),
            ActiveSetOutcome::kSolved);  // a bound row only: nothing to solve, the box holds
  EXPECT_EQ(z[0], 0.0);
  const Vector w = M * z + q;
  EXPECT_EQ(w[0], -1.0);
  EXPECT_FALSE(active_set::BoundRowSignsHold(1, wrong, w.data(), l.data(), u.data(), 0.0));
  EXPECT_FALSE(active_set::BoundRowSignsHold(1, wrong, w.data(), l.data(), u.data(), 0.999));
  EXPECT_TRUE(active_set::BoundRowSignsHold(1, wrong, w.data(), l.data(), u.data(), 1.001));
  // At the upper bound instead: z = 1, w = +1 pushes into the box too.
  const signed char upper[1] = {kUp};
  active_set::SolveDense(M.data(), 1, q.data(), l.data(), u.data(), upper, 0.0, workspace.For(1), z.data(), &nf);
  const Vector w_up = M * z + q;
  EXPECT_EQ(w_up[0], 1.0);
  EXPECT_FALSE(active_set::BoundRowSignsHold(1, upper, w_up.data(), l.data(), u.data(), 0.0));
  // The right set solves exactly.
  const signed char right[1] = {kFree};
  EXPECT_EQ(active_set::SolveDense(M.data(), 1, q.data(), l.data(), u.data(), right, 0.0, workspace.For(1),
                                   z.data(), &nf),
            ActiveSetOutcome::kSolved);
  EXPECT_EQ(z[0], 0.5);
  // A row with l = u takes any w: never a sign failure.
  const Vector fixed_l = Vector::Constant(1, 0.3), fixed_u = Vector::Constant(1, 0.3);
  EXPECT_TRUE(active_set::BoundRowSignsHold(1, wrong, w.data(), fixed_l.data(), fixed_u.data(), 0.0));
  const signed char pinned[1] = {kFix};
  EXPECT_TRUE(active_set::BoundRowSignsHold(1, pinned, w.data(), l.data(), u.data(), 0.0));
}

// A free row whose solution leaves its box: reported, with the unclipped value in z for the caller's policy.
TEST(ActiveSet, FreeRowOutsideItsBoxIsReported) {
  DenseMatrix M(1, 1);
  M << 1.0;
  const Vector q = Vector::Constant(1, -3.0), l = Vector::Zero(1), u = Vector::Ones(1);
  const signed char free_row[1] = {kFree};
  ActiveSetWorkspace workspace;
  Vector z(1);
  int nf = 0;
  EXPECT_EQ(active_set::SolveDense(M.data(), 1, q.data(), l.data(), u.data(), free_row, 0.0, workspace.For(1),
                                   z.data(), &nf),
            ActiveSetOutcome::kOutsideBox);
  EXPECT_EQ(z[0], 3.0);
}

TEST(ActiveSet, SingularReducedBlockIsReportedNotACrash) {
  DenseMatrix M(3, 3);
  M << 1, 1, 0,  //
      1, 1, 0,   //
      0, 0, 2;
  const Vector q = Vector::Ones(3), l = Vector::Constant(3, -5.0), u = Vector::Constant(3, 5.0);
  const std::vector<signed char> state = {kFree, kFree, kLow};
  ActiveSetWorkspace workspace;
  Vector z(3);
  int nf = 0;
  EXPECT_EQ(active_set::SolveDense(M.data(), 3, q.data(), l.data(), u.data(), state.data(), 0.0, workspace.For(3),
                                   z.data(), &nf),
            ActiveSetOutcome::kSingular);
  ActiveSetFactors factors;
  factors.Resize(3);
  EXPECT_FALSE(factors.Factor(M, state.data()));
  EXPECT_FALSE(factors.valid());
  // A relative threshold: the nearly singular block 1, 1; 1, 1 + 1e-12 passes at 0 and fails at 1e-10.
  M(1, 1) = 1.0 + 1e-12;
  EXPECT_NE(active_set::SolveDense(M.data(), 3, q.data(), l.data(), u.data(), state.data(), 0.0, workspace.For(3),
                                   z.data(), &nf),
            ActiveSetOutcome::kSingular);
  EXPECT_EQ(active_set::SolveDense(M.data(), 3, q.data(), l.data(), u.data(), state.data(), 1e-10,
                                   workspace.For(3), z.data(), &nf),
            ActiveSetOutcome::kSingular);
  // Sparse: the same exactly singular block, and a structurally singular one (an empty column).
  M(1, 1) = 1.0;
  const SparseMatrix S = M.sparseView();
  const int both[2] = {0, 1};
  SparseFreeBlock block;
  EXPECT_FALSE(block.Factor(S, both, 2));
  DenseMatrix E = DenseMatrix::Identity(2, 2);
  E(1, 1) = 0.0;
  const SparseMatrix empty_column = E.sparseView();
  EXPECT_FALSE(block.Factor(empty_column, both, 2));
  EXPECT_EQ(block.block().rows(), 2);  // kept for a caller's fallback
}

// RobustFreeBlock (ipopt's polish): a nonsingular block is solved like the kernel's LU; a singular but consistent
// PSD block gets the minimum-norm solution (dense: the complete orthogonal decomposition; sparse: SparseQR after
// SparseLU refuses), which the test computes independently as the projection onto the range.
TEST(ActiveSet, RobustFreeBlockSolvesNonsingularAndSingularBlocks) {
  DenseMatrix M(3, 3);
  M << 4, 1, 0,  //
      1, 3, 1,   //
      0, 1, 2;
  const Vector q = Vector::Zero(3), l = Vector::Constant(3, -5.0), u = Vector::Constant(3, 5.0);
  const int rows[2] = {0, 2};
  const Vector b = (Vector(2) << 1.0, -2.0).finished();
  // M_FF = [[4, 0], [0, 2]]: x = (1/4, −1).
  for (const bool sparse : {false, true}) {
    const BoxMLCP problem = sparse ? BoxMLCP(SparseMatrix(M.sparseView()), q, l, u) : BoxMLCP(M, q, l, u);
    RobustFreeBlock block;
    ASSERT_TRUE(block.Factor(problem, rows, 2)) << (sparse ? "sparse" : "dense");
    Vector x;
    block.Solve(b, &x);
    ASSERT_EQ(x.size(), 2);
    EXPECT_NEAR(x[0], 0.25, 1e-15);
    EXPECT_NEAR(x[1], -1.0, 1e-15);
  }
  // M_FF = [[1, 1], [1, 1]] (rank 1) with b = (2, 2) in its range: the solutions are x₀ + x₁ = 2, the
  // minimum-norm one is (1, 1). Partial-pivoting LU would return garbage or infinities here.
  DenseMatrix S(3, 3);
  S << 1, 1, 0,  //
      1, 1, 0,   //
      0, 0, 2;
  const int both[2] = {0, 1};
  const Vector consistent = (Vector(2) << 2.0, 2.0).finished();
  for (const bool sparse : {false, true}) {
    const BoxMLCP problem = sparse ? BoxMLCP(SparseMatrix(S.sparseView()), q, l, u) : BoxMLCP(S, q, l, u);
    RobustFreeBlock block;
    ASSERT_TRUE(block.Factor(problem, both, 2)) << (sparse ? "sparse" : "dense");
    Vector x;
    block.Solve(consistent, &x);
    ASSERT_EQ(x.size(), 2);
    EXPECT_NEAR(x[0] + x[1], 2.0, 1e-12) << (sparse ? "sparse" : "dense");
    if (!sparse) {  // SparseQR gives a least-squares solution, not necessarily the minimum-norm one
      EXPECT_NEAR(x[0], 1.0, 1e-12);
      EXPECT_NEAR(x[1], 1.0, 1e-12);
    }
  }
}

TEST(ActiveSet, BadInputNamesTheField) {
  ActiveSetFactors factors;
  factors.Resize(3);
  const DenseMatrix M = DenseMatrix::Identity(2, 2);
  const signed char state[3] = {kFree, kFree, kFree};
  EXPECT_THROW(factors.Factor(M, state), InvalidInputError);
  SparseFreeBlock block;
  const SparseMatrix S = DenseMatrix(DenseMatrix::Identity(3, 3)).sparseView();
  const int unordered[2] = {2, 1};
  try {
    block.Factor(S, unordered, 2);
    ADD_FAILURE() << "an unordered free_rows list was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("free_rows"), std::string::npos) << e.what();
  }
  const int out_of_range[1] = {3};
  EXPECT_THROW(block.Factor(S, out_of_range, 1), InvalidInputError);
}

// A sparse planted problem (tridiagonal, n = 60): the kernel's sparse block, and the base's sparse polish from a
// perturbed point, both land on z*.
TEST(ActiveSet, SparseSolveFindsThePlantedSolution) {
  const int n = 60;
  std::vector<Eigen::Triplet<double, int>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 4.0);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.5);
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(entries.begin(), entries.end());
  Vector z_star(n), w_star(n);
  std::vector<signed char> state(n);
  const Vector l = Vector::Zero(n), u = Vector::Constant(n, 1.0);
  for (int i = 0; i < n; ++i) {
    switch (i % 3) {
      case 0: state[i] = kLow, z_star[i] = 0.0, w_star[i] = 1.0; break;
      case 1: state[i] = kFree, z_star[i] = 0.5, w_star[i] = 0.0; break;
      default: state[i] = kUp, z_star[i] = 1.0, w_star[i] = -2.0; break;
    }
  }
  const Vector q = w_star - M * z_star;
  Vector z(n);
  std::vector<int> free_rows(n);
  const int nf = active_set::PlaceBoundRows(n, state.data(), l.data(), u.data(), z.data(), free_rows.data());
  ASSERT_EQ(nf, n / 3);
  const Vector r = M * z + q;
  Vector rhs(nf);
  for (int k = 0; k < nf; ++k) rhs[k] = -r[free_rows[k]];
  SparseFreeBlock block;
  ASSERT_TRUE(block.Factor(M, free_rows.data(), nf));
  Vector x;
  ASSERT_TRUE(block.Solve(rhs, &x));
  EXPECT_EQ(active_set::ScatterFreeRows(x.data(), free_rows.data(), nf, l.data(), u.data(), z.data()),
            FreeRowsFit::kInside);
  EXPECT_LE(MaxAbs(z - z_star), 1e-14);
  const Vector w = M * z + q;
  EXPECT_TRUE(active_set::BoundRowSignsHold(n, state.data(), w.data(), l.data(), u.data(), 0.0));

  const BoxMLCP problem(M, q, l, u, "tridiagonal");
  Vector start = z_star;
  for (int i = 0; i < n; ++i) start[i] += 1e-6 * ((i % 5) - 2);
  Vector polished;
  ASSERT_TRUE(PolishSparse(problem, start, &polished));
  EXPECT_LE(MaxAbs(polished - z_star), 1e-14);
}

// The blocked entry point (k ≤ 4 unrolled) gives the same bits as the run-time LU it stands for.
TEST(ActiveSet, BlockedEntryPointMatchesTheRunTimeLu) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int k = 1; k <= 6; ++k) {
    const int ld = k + 1;
    std::vector<double> a(static_cast<size_t>(ld) * k), b(k);
    for (double& v : a) v = uniform(rng);
    for (double& v : b) v = uniform(rng);
    std::vector<double> a2 = a, b2 = b;
    std::vector<int> piv(k), piv2(k);
    ASSERT_TRUE(active_set::SolveBlock(a.data(), ld, k, b.data(), piv.data(), 0.0));
    ASSERT_TRUE(dense_lu::Factor(a2.data(), ld, k, piv2.data(), 0.0));
    dense_lu::Solve(a2.data(), ld, k, piv2.data(), b2.data());
    for (int i = 0; i < k; ++i) EXPECT_EQ(b[i], b2[i]) << "k = " << k << ", row " << i;
    const active_set::BlockPivots pivots = active_set::FactoredPivots(a.data(), ld, k, piv.data());
    double smallest = std::numeric_limits<double>::infinity();
    for (int j = 0; j < k; ++j) smallest = std::min(smallest, std::abs(a2[j + static_cast<size_t>(j) * ld]));
    EXPECT_EQ(pivots.smallest, smallest);
  }
}

// The hot path: after the workspace is sized, repeated solves of the same size (one-shot and factor-once, with a
// change of active set) allocate nothing.
TEST(ActiveSet, RepeatedSolvesDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  const int n = 12;
  const Planted p = MakePlanted(n, 9u, true);
  std::vector<signed char> other = p.state;
  other[1] = kLow;
  ActiveSetWorkspace workspace;
  ActiveSetFactors factors;
  factors.Resize(n);
  Vector z(n), w(n);
  workspace.For(n);
  int nf = 0;
  bool all_ok = true;
  const long allocations = test_support::CountMallocs([&] {
    for (int k = 0; k < 10; ++k) {
      const signed char* state = k % 2 == 0 ? p.state.data() : other.data();
      all_ok &= active_set::SolveDense(p.M.data(), n, p.q.data(), p.l.data(), p.u.data(), state, 0.0,
                                       workspace.For(n), z.data(), &nf) != ActiveSetOutcome::kSingular;
      all_ok &= factors.Factor(p.M, state);
      factors.Solve<0>(p.M, p.q.data(), p.l.data(), p.u.data(), z.data());
      w.noalias() = p.M * z;
      active_set::BoundRowSignsHold(n, state, w.data(), p.l.data(), p.u.data(), 0.0);
    }
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(all_ok);
}

}  // namespace
}  // namespace smcbench
