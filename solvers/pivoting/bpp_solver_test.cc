// Tests of the block principal pivoting backend. Answers are checked against hand solutions, the generators'
// planted z* (unique: every family is a P-matrix) and the exact backends (enum, lemke), with the natural residual
// recomputed here; never against bpp's own status alone.
#include "solvers/pivoting/bpp_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "solvers/enumerative/enumerative_solver.h"
#include "solvers/generators/random_problems.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/pivoting/prefix_cholesky.h"
#include "solvers/pivoting/updated_free_block.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

// A generated problem with its planted solution.
GeneratedProblem Planted(MatrixFamily family, BoundKind bounds, int size, std::uint64_t seed) {
  GeneratorOptions g;
  g.family = family;
  g.bounds = bounds;
  g.size = size;
  g.seed = seed;
  return GenerateProblem(g);
}

// ‖z − Π_[l,u](z − (Mz+q))‖∞, recomputed from scratch (dense or sparse M).
double NaturalResidual(const BoxMLCP& problem, const Vector& z) {
  const Vector w = problem.is_sparse() ? Vector(problem.sparse_matrix() * z + problem.q())
                                       : Vector(problem.dense_matrix() * z + problem.q());
  double r = 0.0;
  for (int i = 0; i < problem.size(); ++i) {
    if (!std::isfinite(z[i])) return kInf;
    r = std::max(r, std::abs(z[i] - std::clamp(z[i] - w[i], problem.l()[i], problem.u()[i])));
  }
  return r;
}

double ForwardError(const Vector& z, const Vector& reference) {
  return (z - reference).cwiseAbs().maxCoeff() / (1.0 + reference.cwiseAbs().maxCoeff());
}

DenseMatrix Dense(int rows, std::initializer_list<double> column_major) {
  DenseMatrix M(rows, rows);
  std::copy(column_major.begin(), column_major.end(), M.data());
  return M;
}

Vector Vec(std::initializer_list<double> values) {
  Vector v(static_cast<int>(values.size()));
  std::copy(values.begin(), values.end(), v.data());
  return v;
}

TEST(BppSolver, InfoAndOptions) {
  BppSolver solver;
  EXPECT_EQ(solver.info().name, "bpp");
  EXPECT_TRUE(solver.info().dense);
  EXPECT_TRUE(solver.info().sparse);
  EXPECT_TRUE(solver.info().solves_every_p_matrix);
  EXPECT_TRUE(solver.info().allocation_free);
  std::string error;
  EXPECT_TRUE(solver.SetOption("block_steps_without_progress", "5", &error)) << error;
  EXPECT_EQ(solver.options().block_steps_without_progress, 5);
  EXPECT_FALSE(solver.SetOption("pivot_tolerance", "2", &error));
  EXPECT_NE(error.find("pivot_tolerance"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("omega", "1", &error));
}

TEST(BppSolver, InvalidOptionsNameTheField) {
  BppOptions bad;
  bad.block_steps_without_progress = -1;
  BppSolver solver(bad);
  const SolveResult r = solver.Solve(BoxMLCP::LCP(Dense(1, {2.0}), Vec({-4.0})));
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("block_steps_without_progress"), std::string::npos) << r.message;
}

TEST(BppSolver, OneByOneByHand) {
  BppSolver solver;
  // 2z − 4 = 0 inside z ≥ 0; 2z + 3 > 0 keeps z at 0; relay M = 1, q = −5: z = 1 with w = −4 ≤ 0.
  SolveResult r = solver.Solve(BoxMLCP::LCP(Dense(1, {2.0}), Vec({-4.0})));
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_DOUBLE_EQ(r.z[0], 2.0);
  EXPECT_EQ(r.iterations, 1);  // the Jacobi-scaled first guess is the answer's set
  r = solver.Solve(BoxMLCP::LCP(Dense(1, {2.0}), Vec({3.0})));
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(r.z[0], 0.0);
  r = solver.Solve(BoxMLCP::Relay(Dense(1, {1.0}), Vec({-5.0})));
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(r.z[0], 1.0);
}

TEST(BppSolver, TwoByTwoByHand) {
  BppSolver solver;
  const DenseMatrix M = Dense(2, {2.0, 1.0, 1.0, 2.0});
  // Both free: z = M⁻¹(5, 6) = (4/3, 7/3).
  SolveResult r = solver.Solve(BoxMLCP::LCP(M, Vec({-5.0, -6.0})));
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_NEAR(r.z[0], 4.0 / 3.0, 1e-14);
  EXPECT_NEAR(r.z[1], 7.0 / 3.0, 1e-14);
  // z = (1/2, 0) with w_2 = 1/2 + 3 > 0.
  r = solver.Solve(BoxMLCP::LCP(M, Vec({-1.0, 3.0})));
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_NEAR(r.z[0], 0.5, 1e-15);
  EXPECT_EQ(r.z[1], 0.0);
  // Relay: z_1 at its upper bound (w_1 = 2 − 0.75 − 5 < 0), z_2 = −(0.5 + 1)/2 = −0.75 free.
  r = solver.Solve(BoxMLCP::Relay(M, Vec({-5.0, 0.5})));
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_NEAR(r.z[1], -0.75, 1e-15);
}

// Every generated family (SPD, SPD + skew, diagonally dominant), every bound kind, with and without the base's
// polish: bpp's z against the planted z*, which is unique (P-matrix), and against lemke's answer.
TEST(BppSolver, GeneratedProblemsAgreeWithPlantedSolutionAndLemke) {
  BppSolver solver;
  LemkeSolver lemke;
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix,
                              MatrixFamily::kDiagonallyDominant}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
      for (int size : {3, 12, 60}) {
        for (std::uint64_t seed : {1u, 2u}) {
          const GeneratedProblem gen = Planted(family, bounds, size, seed);
          for (bool polish : {true, false}) {
            SolverOptions options;
            options.polish = polish;
            const SolveResult r = solver.Solve(gen.problem, options);
            ASSERT_TRUE(r.solved()) << gen.problem.name() << ": " << r.message;
            EXPECT_LE(NaturalResidual(gen.problem, r.z), 1e-9) << gen.problem.name();
            EXPECT_LE(ForwardError(r.z, gen.z_star), 1e-8) << gen.problem.name() << " polish " << polish;
          }
          const SolveResult by_lemke = lemke.Solve(gen.problem);
          ASSERT_TRUE(by_lemke.solved()) << gen.problem.name();
          EXPECT_LE(ForwardError(solver.Solve(gen.problem).z, by_lemke.z), 1e-8) << gen.problem.name();
        }
      }
    }
  }
}

// Degenerate rows (z* at a bound with w* = 0) against the exact enumeration.
TEST(BppSolver, DegenerateProblemsAgreeWithEnum) {
  BppSolver solver;
  EnumerativeSolver reference;
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      GeneratorOptions g;
      g.family = MatrixFamily::kNonsymmetricPMatrix;
      g.bounds = bounds;
      g.size = 8;
      g.seed = seed;
      g.degenerate_fraction = 0.25;
      const GeneratedProblem gen = GenerateProblem(g);
      const SolveResult exact = reference.Solve(gen.problem);
      ASSERT_TRUE(exact.solved()) << gen.problem.name();
      const SolveResult r = solver.Solve(gen.problem);
      ASSERT_TRUE(r.solved()) << gen.problem.name() << ": " << r.message;
      EXPECT_LE(ForwardError(r.z, exact.z), 1e-8) << gen.problem.name();
    }
  }
}

// Free blocks above 64 rows take the blocked LU; the answers must not change in kind.
TEST(BppSolver, LargeFreeBlocksTakeTheBlockedFactorization) {
  BppSolver solver;
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay}) {
      const GeneratedProblem gen = Planted(family, bounds, 300, 3);
      SolverOptions options;
      options.polish = false;
      const SolveResult r = solver.Solve(gen.problem, options);
      ASSERT_TRUE(r.solved()) << gen.problem.name() << ": " << r.message;
      EXPECT_LE(NaturalResidual(gen.problem, r.z), 1e-9) << gen.problem.name();
      EXPECT_LE(ForwardError(r.z, gen.z_star), 1e-8) << gen.problem.name();
    }
  }
}

TEST(BppSolver, SparseProblemsUseTheSparseFreeBlock) {
  BppSolver solver;
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
    GeneratorOptions g;
    g.family = MatrixFamily::kNonsymmetricPMatrix;
    g.bounds = bounds;
    g.size = 200;
    g.sparse = true;
    const GeneratedProblem gen = GenerateProblem(g);
    ASSERT_TRUE(gen.problem.is_sparse());
    const SolveResult r = solver.Solve(gen.problem);
    ASSERT_TRUE(r.solved()) << gen.problem.name() << ": " << r.message;
    EXPECT_FALSE(r.GetDetail("densified") == 1.0) << "solved on the sparse path";
    EXPECT_LE(ForwardError(r.z, gen.z_star), 1e-8) << gen.problem.name();
  }
}

// A 3×3 P-matrix LCP on which the plain block exchange (every infeasible row changes at every step) cycles through
// the free sets {1} → {0,1,2} → {2} → {1} with 2 infeasible rows each time (found by a search over small integer
// P-matrices; that the full exchange can cycle on P-matrices is why Júdice & Pires 1994 add Murty's single pivots).
// The solution is z = (0, 1/2, 1/2), w = (3/2, 0, 0).
TEST(BppSolver, CyclingBlockExchangeNeedsMurtysFallback) {
  // Rows (2, −3, −2), (−1, 2, 4), (1, −3, 1), stored by columns.
  const BoxMLCP problem = BoxMLCP::LCP(Dense(3, {2.0, -1.0, 1.0, -3.0, 2.0, -3.0, -2.0, 4.0, 1.0}),
                                       Vec({4.0, -3.0, 1.0}), "block-exchange-cycles");
  SolverOptions options;
  options.max_iterations = 60;
  options.polish = false;  // the base's polish alone would not find the set either, but keep the method bare
  BppOptions never_fall_back;
  never_fall_back.block_steps_without_progress = 1000;
  BppSolver plain(never_fall_back);
  const SolveResult cycled = plain.Solve(problem, options);
  EXPECT_EQ(cycled.status, SolveStatus::kIterationLimit) << cycled.message;
  EXPECT_EQ(cycled.iterations, 60);

  BppSolver solver;
  const SolveResult r = solver.Solve(problem, options);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_GT(r.GetDetail("single_pivots"), 0.0);
  EXPECT_NEAR(r.z[0], 0.0, 1e-15);
  EXPECT_NEAR(r.z[1], 0.5, 1e-14);
  EXPECT_NEAR(r.z[2], 0.5, 1e-14);
}

TEST(BppSolver, MaxSinglePivotsHandsOverAsIterationLimit) {
  // The cycling example above needs single pivots: with none allowed bpp stops at the first one, naming the option.
  const BoxMLCP problem = BoxMLCP::LCP(Dense(3, {2.0, -1.0, 1.0, -3.0, 2.0, -3.0, -2.0, 4.0, 1.0}),
                                       Vec({4.0, -3.0, 1.0}), "block-exchange-cycles");
  SolverOptions options;
  options.polish = false;
  BppOptions capped;
  capped.max_single_pivots = 0;
  BppSolver solver(capped);
  const SolveResult r = solver.Solve(problem, options);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_NE(r.message.find("max_single_pivots"), std::string::npos) << r.message;
  EXPECT_EQ(r.GetDetail("single_pivots"), 0.0);
  // A limit above what the problem needs changes nothing.
  std::string error;
  ASSERT_TRUE(solver.SetOption("max_single_pivots", "100", &error)) << error;
  const SolveResult solved = solver.Solve(problem, options);
  ASSERT_TRUE(solved.solved()) << solved.message;
  EXPECT_NEAR(solved.z[1], 0.5, 1e-14);
  EXPECT_FALSE(solver.SetOption("max_single_pivots", "-2", &error));
  EXPECT_NE(error.find("max_single_pivots"), std::string::npos) << error;
}

// The safeguard in proportion to the problem (what auto sets): max(4, ⌈c·n⌉) single pivots, then a hand-over
// naming the option; on the strongly nonsymmetric relay that needs hundreds of single pivots at m = 64.
TEST(BppSolver, SinglePivotsPerRowCapsTheSinglePivotPhase) {
  const GeneratedProblem gen = Planted(MatrixFamily::kSkewPMatrix, BoundKind::kRelay, 64, 1);
  BppSolver uncapped;
  const SolveResult full = uncapped.Solve(gen.problem);
  ASSERT_GT(full.GetDetail("single_pivots"), 16.0) << "the case needs a long single-pivot phase";
  BppOptions per_row;
  per_row.single_pivots_per_row = 0.25;
  BppSolver capped(per_row);
  const SolveResult r = capped.Solve(gen.problem);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_EQ(r.GetDetail("single_pivots"), 16.0) << "max(4, ceil(0.25 * 64))";
  EXPECT_NE(r.message.find("single_pivots_per_row"), std::string::npos) << r.message;
  // A tiny problem still gets 4; max_single_pivots, when set, wins.
  std::string error;
  ASSERT_TRUE(capped.SetOption("max_single_pivots", "2", &error)) << error;
  EXPECT_EQ(capped.Solve(gen.problem).GetDetail("single_pivots"), 2.0);
  EXPECT_FALSE(capped.SetOption("single_pivots_per_row", "0", &error));
  EXPECT_NE(error.find("single_pivots_per_row"), std::string::npos) << error;
}

// A warm start at the solution gives its active set: one set solved, whatever the family or bounds.
TEST(BppSolver, WarmStartFromTheSolutionSolvesInOneIteration) {
  BppSolver solver;
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
    const GeneratedProblem gen = Planted(MatrixFamily::kNonsymmetricPMatrix, bounds, 40, 7);
    const SolveResult cold = solver.Solve(gen.problem);
    ASSERT_TRUE(cold.solved()) << gen.problem.name();
    SolverOptions options;
    options.warm_start = cold.z;
    const SolveResult warm = solver.Solve(gen.problem, options);
    ASSERT_TRUE(warm.solved()) << gen.problem.name() << ": " << warm.message;
    EXPECT_EQ(warm.iterations, 1) << gen.problem.name();
    EXPECT_LE(ForwardError(warm.z, gen.z_star), 1e-8) << gen.problem.name();
  }
}

// In a session whose reused active set is off, every call reaches bpp; the previous answer as warm start is its
// first set, so a repeated q costs one set and a nearby q few.
TEST(BppSolver, SessionWarmStartsGiveTheFirstActiveSet) {
  BppSolver solver;
  const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 50, 4);
  SessionOptions no_reuse;
  no_reuse.reuse_active_set = false;
  SolveSession session = solver.Prepare(gen.problem, SolverOptions{}, no_reuse);
  SolveResult result;
  session.Solve(gen.problem.q(), &result);
  ASSERT_TRUE(result.solved()) << result.message;
  const Vector first = result.z;
  session.Solve(gen.problem.q(), &result, &first);
  ASSERT_TRUE(result.solved()) << result.message;
  EXPECT_EQ(result.iterations, 1);
  EXPECT_EQ(SessionPathOf(result), SessionPath::kBackend);
  EXPECT_LE(ForwardError(result.z, gen.z_star), 1e-8);
}

// Outside the P-matrices: M = 0, q = −1 has no solution; the one free block is singular. A status, no crash.
TEST(BppSolver, SingularFreeBlockIsAStatus) {
  BppSolver solver;
  const SolveResult r = solver.Solve(BoxMLCP::LCP(Dense(1, {0.0}), Vec({-1.0})));
  EXPECT_EQ(r.status, SolveStatus::kSingular) << r.message;
  EXPECT_NE(r.message.find("singular"), std::string::npos) << r.message;
}

// A singular block reached by a block pivot is stepped back from: M = [[1, 1], [1, 1]] (positive semidefinite),
// q = (−1, −1): the first guess (both free) is singular, so the method restarts at z = 0; its block pivot makes
// both rows free again, and the single pivot from z = 0 finds z = (1, 0). (Without the sweeps, which on this
// symmetric M would pick a nonsingular first set.)
TEST(BppSolver, SingularBlockAfterABlockPivotFallsBackToSinglePivots) {
  BppOptions no_sweeps;
  no_sweeps.guess_sweeps = 0;
  BppSolver solver(no_sweeps);
  const BoxMLCP problem = BoxMLCP::LCP(Dense(2, {1.0, 1.0, 1.0, 1.0}), Vec({-1.0, -1.0}));
  const SolveResult r = solver.Solve(problem);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_LE(NaturalResidual(problem, r.z), 1e-14);
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_EQ(r.z[1], 0.0);
  EXPECT_EQ(r.GetDetail("singular_blocks"), 2.0);
  EXPECT_EQ(r.GetDetail("single_pivots"), 1.0);
}

TEST(BppSolver, RepeatedSolvesAreIdentical) {
  BppSolver solver;
  GeneratorOptions g;
  g.family = MatrixFamily::kSymmetricPositiveDefinite;
  g.bounds = BoundKind::kRelay;
  g.size = 30;
  const GeneratedProblem gen = GenerateProblem(g);
  const SolveResult first = solver.Solve(gen.problem);
  const SolveResult second = solver.Solve(gen.problem);
  ASSERT_TRUE(first.solved());
  EXPECT_EQ(first.iterations, second.iterations);
  EXPECT_EQ((first.z - second.z).cwiseAbs().maxCoeff(), 0.0);
}

// ---- Factor updates (updated_free_block.h) ----

// A random nonsymmetric n×n matrix with a dominant diagonal (every principal block nonsingular and well
// conditioned), column-major.
DenseMatrix RandomDominant(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  DenseMatrix M(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) M(i, j) = entry(rng) / n;
  }
  for (int i = 0; i < n; ++i) M(i, i) += 1.0 + 0.5 * std::abs(entry(rng));
  return M;
}

// z on the free rows of a set solved by a fresh dense LU (Eigen), with the bound rows placed as given.
Vector FreshSolve(const DenseMatrix& M, const Vector& q, const std::vector<int>& free_rows, Vector z) {
  const int nf = static_cast<int>(free_rows.size());
  DenseMatrix block(nf, nf);
  Vector rhs(nf);
  for (int r = 0; r < nf; ++r) {
    rhs[r] = -q[free_rows[r]];
    for (int j = 0; j < M.cols(); ++j) rhs[r] -= M(free_rows[r], j) * z[j];
    for (int c = 0; c < nf; ++c) block(r, c) = M(free_rows[r], free_rows[c]);
  }
  const Vector x = block.partialPivLu().solve(rhs);
  for (int r = 0; r < nf; ++r) z[free_rows[r]] = x[r];
  return z;
}

// A walk of free sets, each a few rows away from the last (rows enter, leave, and come back): every set's z from
// the update agrees with a fresh factorization, and only the first set and the sets beyond MaxRank are factored.
TEST(UpdatedFreeBlock, UpdatedSetsAgreeWithFreshFactorizations) {
  const int n = 80;
  const DenseMatrix M = RandomDominant(n, 5);
  Vector q(n);
  for (int i = 0; i < n; ++i) q[i] = std::sin(1.3 * i) - 0.2;
  std::mt19937_64 rng(9);
  std::vector<char> free(n, 0);
  for (int i = 0; i < n; i += 2) free[i] = 1;  // 40 free rows: MaxRank(40) = 10
  UpdatedFreeBlock block;
  block.Resize(n);
  int fresh_expected = 0, rank_since_factor = 0;
  std::vector<char> reference = free;
  for (int set = 0; set < 40; ++set) {
    if (set > 0) {
      const int flips = 1 + static_cast<int>(rng() % 3);
      for (int f = 0; f < flips; ++f) {
        const int i = static_cast<int>(rng() % n);
        free[i] = !free[i];
      }
    }
    std::vector<int> free_rows;
    Vector z(n);
    for (int i = 0; i < n; ++i) {
      z[i] = free[i] ? 0.0 : (i % 3 == 0 ? -1.0 : 1.0);
      if (free[i]) free_rows.push_back(i);
    }
    const Vector placed = z;
    int nf0 = 0;
    rank_since_factor = 0;
    for (int i = 0; i < n; ++i) {
      nf0 += reference[i];
      rank_since_factor += reference[i] != free[i];
    }
    const bool fresh = set == 0 || rank_since_factor > UpdatedFreeBlock::MaxRank(nf0);
    if (fresh) {
      ++fresh_expected;
      reference = free;
    }
    ASSERT_TRUE(block.Solve(M.data(), n, q.data(), free_rows.data(), static_cast<int>(free_rows.size()), 1e-14,
                            z.data()));
    EXPECT_EQ(block.last_path(), fresh ? UpdatedFreeBlock::Path::kFactored : UpdatedFreeBlock::Path::kUpdated)
        << "set " << set;
    const Vector expected = FreshSolve(M, q, free_rows, placed);
    EXPECT_LE((z - expected).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + expected.cwiseAbs().maxCoeff())) << "set " << set;
  }
  EXPECT_EQ(block.factorizations(), fresh_expected);
  EXPECT_EQ(block.updates(), 40 - fresh_expected);
  EXPECT_GE(block.updates(), 20);  // most sets of the walk were updates
}

// A set whose block is singular though the reference is not (column 20 equals column 1 on the rows of F): the
// Schur complement's LU rejects it, the set is factored afresh, and that factorization reports the singularity.
TEST(UpdatedFreeBlock, ASingularSetIsJudgedByAFreshFactorization) {
  const int n = 21;
  DenseMatrix M = RandomDominant(n, 3);
  for (int i = 0; i < n; ++i) M(i, 20) = M(i, 1);  // F = {1..20}: two equal columns
  const Vector q = Vector::Constant(n, -1.0);
  UpdatedFreeBlock block;
  block.Resize(n);
  std::vector<int> f0(20), f1(20);
  for (int k = 0; k < 20; ++k) f0[k] = k, f1[k] = k + 1;
  Vector z = Vector::Zero(n);
  z[20] = 1.0;
  ASSERT_TRUE(block.Solve(M.data(), n, q.data(), f0.data(), 20, 1e-14, z.data()));
  z.setZero();
  z[0] = 1.0;
  EXPECT_FALSE(block.Solve(M.data(), n, q.data(), f1.data(), 20, 1e-14, z.data()));
  EXPECT_EQ(block.factorizations(), 2);
  EXPECT_EQ(block.updates(), 0);
}

// bpp with and without updates on every generated family and bound kind: same verdict, both at the planted z*
// (unique), and with updates fewer factorizations than sets once a problem needs several sets.
TEST(BppSolver, FactorUpdatesGiveTheAnswersOfFreshFactorizations) {
  BppOptions fresh_options;
  fresh_options.factor_updates = false;
  BppSolver updated, fresh(fresh_options);
  int sets = 0, factorizations = 0, updated_sets = 0;
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix,
                              MatrixFamily::kDiagonallyDominant, MatrixFamily::kSkewPMatrix}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
      for (int size : {20, 70, 150}) {
        // The strongly nonsymmetric relay of 150 rows exhausts bpp's budget in Murty's phase (no finiteness proof
        // on the box), with or without updates.
        if (family == MatrixFamily::kSkewPMatrix && size > 100) continue;
        const GeneratedProblem gen = Planted(family, bounds, size, 2);
        SolverOptions options;
        options.polish = false;
        const SolveResult a = updated.Solve(gen.problem, options);
        const SolveResult b = fresh.Solve(gen.problem, options);
        ASSERT_TRUE(b.solved()) << gen.problem.name() << ": " << b.message;
        ASSERT_TRUE(a.solved()) << gen.problem.name() << ": " << a.message;
        EXPECT_LE(NaturalResidual(gen.problem, a.z), 1e-9) << gen.problem.name();
        EXPECT_LE(ForwardError(a.z, gen.z_star), 1e-8) << gen.problem.name();
        EXPECT_EQ(b.GetDetail("updated_sets"), 0.0);
        EXPECT_EQ(a.GetDetail("factorizations") + a.GetDetail("updated_sets"),
                  a.iterations - a.GetDetail("singular_blocks"))
            << gen.problem.name() << ": every set solved is either factored or updated";
        sets += a.iterations;
        factorizations += static_cast<int>(a.GetDetail("factorizations"));
        updated_sets += static_cast<int>(a.GetDetail("updated_sets"));
      }
    }
  }
  EXPECT_GT(updated_sets, 0);
  EXPECT_LT(factorizations, sets);
}

// The strongly nonsymmetric class runs Murty's single pivots: each changes one row, so with updates the sets are
// rank-1 changes of a factored block, and bpp refactors a small fraction of them.
TEST(BppSolver, SinglePivotsAreSolvedByUpdates) {
  const GeneratedProblem gen = Planted(MatrixFamily::kSkewPMatrix, BoundKind::kRelay, 64, 1);
  BppSolver solver;
  const SolveResult r = solver.Solve(gen.problem);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_LE(ForwardError(r.z, gen.z_star), 1e-8);
  LemkeSolver lemke;
  const SolveResult by_lemke = lemke.Solve(gen.problem);
  ASSERT_TRUE(by_lemke.solved());
  EXPECT_LE(ForwardError(r.z, by_lemke.z), 1e-8);
  ASSERT_GT(r.GetDetail("single_pivots"), 10.0) << "the problem should need Murty's phase";
  EXPECT_LE(r.GetDetail("factorizations") * 4, r.iterations)
      << r.GetDetail("factorizations") << " factorizations for " << r.iterations << " sets";
}

// From 5 to 31 rows the sweeps choose the first set on a box whose M is neither symmetric nor strictly diagonally
// dominant (kMinBoxSweptRows): every nonsymmetric class with relay bounds is solved to its planted answer, which enum
// (exact, its own search) finds too, never swept where M is dominant, always on the nonsymmetric P-matrices; a
// symmetric box of those sizes, a skew-dominant one, an LCP, mixed bounds, a problem of 4 rows, one of 40 (symmetric
// M only from 32) and guess_sweeps = 0 keep the natural map at Π(0).
TEST(BppSolver, NonsymmetricSmallBoxesAreSweptAndKeepTheAnswer) {
  BppSolver bpp;
  EnumerativeSolver enumerative;
  for (MatrixFamily family : {MatrixFamily::kNonsymmetricPMatrix, MatrixFamily::kDiagonallyDominant,
                              MatrixFamily::kSkewPMatrix, MatrixFamily::kScaledPMatrix}) {
    for (int size : {5, 8, 12, 20, 31}) {
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const GeneratedProblem gen = Planted(family, BoundKind::kRelay, size, seed);
        const SolveResult r = bpp.Solve(gen.problem);
        ASSERT_TRUE(r.solved()) << gen.problem.name() << ": " << r.message;
        // Never where M is strictly diagonally dominant by rows (recomputed here; the base's row scaling does not
        // change dominance by rows); always on the nonsymmetric P-matrices, whose skew part is about as large as
        // their symmetric part (the skew-dominant test is on the row-scaled M, so the other classes are not pinned).
        const DenseMatrix& M = gen.problem.dense_matrix();
        bool dominant = true;
        for (int i = 0; i < size; ++i) dominant &= M(i, i) > M.row(i).cwiseAbs().sum() - std::abs(M(i, i));
        if (dominant || family == MatrixFamily::kNonsymmetricPMatrix) {
          EXPECT_EQ(r.GetDetail("swept_guess") == 1.0, !dominant) << gen.problem.name();
        }
        if (family == MatrixFamily::kDiagonallyDominant) {
          EXPECT_TRUE(dominant) << gen.problem.name();
        }
        if (family == MatrixFamily::kNonsymmetricPMatrix && size >= 8) {
          EXPECT_FALSE(dominant) << gen.problem.name();
        }
        EXPECT_LE(ForwardError(r.z, gen.z_star), 1e-8) << gen.problem.name();
        if (size <= 12) {
          const SolveResult e = enumerative.Solve(gen.problem);
          ASSERT_TRUE(e.solved()) << gen.problem.name() << ": " << e.message;
          EXPECT_LE(ForwardError(r.z, e.z), 1e-8) << gen.problem.name();
        }
      }
    }
  }
  const auto swept = [&](BppSolver& solver, MatrixFamily family, BoundKind bounds, int size) {
    return solver.Solve(Planted(family, bounds, size, 1).problem).GetDetail("swept_guess") == 1.0;
  };
  EXPECT_FALSE(swept(bpp, MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 8));
  EXPECT_FALSE(swept(bpp, MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 8));
  EXPECT_FALSE(swept(bpp, MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 8));
  EXPECT_FALSE(swept(bpp, MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 4));
  EXPECT_FALSE(swept(bpp, MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 40));  // symmetric only from 32
  // The strongly nonsymmetric class (skew part about 2.9 times the symmetric part at m = 8): not swept.
  EXPECT_FALSE(swept(bpp, MatrixFamily::kSkewPMatrix, BoundKind::kRelay, 8));
  BppOptions off;
  off.guess_sweeps = 0;
  BppSolver unswept(off);
  EXPECT_FALSE(swept(unswept, MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 8));
}

// A few projected Gauss–Seidel sweeps choose the first set; the answer does not depend on it.
TEST(BppSolver, SweptGuessesKeepTheAnswer) {
  for (int sweeps : {0, 1, 3}) {
    BppOptions o;
    o.guess_sweeps = sweeps;
    BppSolver solver(o);
    for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix}) {
      for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
        const GeneratedProblem gen = Planted(family, bounds, 90, 4);
        const SolveResult r = solver.Solve(gen.problem);
        ASSERT_TRUE(r.solved()) << gen.problem.name() << " sweeps " << sweeps << ": " << r.message;
        EXPECT_LE(ForwardError(r.z, gen.z_star), 1e-8) << gen.problem.name() << " sweeps " << sweeps;
      }
    }
  }
  // The sweeps run on symmetric M only (the base hands bpp the row-scaled M, symmetric up to that scaling).
  GeneratorOptions g;
  g.size = 40;
  g.bounds = BoundKind::kRelay;
  g.family = MatrixFamily::kSymmetricPositiveDefinite;
  BppSolver solver;
  EXPECT_EQ(solver.Solve(GenerateProblem(g).problem).GetDetail("swept_guess"), 1.0);
  g.family = MatrixFamily::kNonsymmetricPMatrix;
  EXPECT_FALSE(solver.Solve(GenerateProblem(g).problem).GetDetail("swept_guess") == 1.0);
  std::string error;
  EXPECT_FALSE(solver.SetOption("guess_sweeps", "-1", &error));
  EXPECT_NE(error.find("guess_sweeps"), std::string::npos) << error;
}

// ---- Cholesky of the free block on symmetric M ----

// z with the set read off a known solution (rows strictly inside their box free, the others at the bound they
// touch) solved directly on the user's M by Eigen's full-pivoting LU: independent of bpp's kernels, scaling and
// pivoting.
Vector DirectSolveOnKnownSet(const BoxMLCP& problem, const Vector& known) {
  const DenseMatrix& M = problem.dense_matrix();
  const int n = problem.size();
  std::vector<int> free_rows;
  Vector z(n);
  for (int i = 0; i < n; ++i) {
    const double l = problem.l()[i], u = problem.u()[i], gap = 1e-9 * (1.0 + std::abs(known[i]));
    if (known[i] <= l + gap) {
      z[i] = l;
    } else if (known[i] >= u - gap) {
      z[i] = u;
    } else {
      z[i] = 0.0;
      free_rows.push_back(i);
    }
  }
  const int nf = static_cast<int>(free_rows.size());
  DenseMatrix block(nf, nf);
  Vector rhs(nf);
  for (int r = 0; r < nf; ++r) {
    rhs[r] = -problem.q()[free_rows[r]] - M.row(free_rows[r]).dot(z);
    for (int c = 0; c < nf; ++c) block(r, c) = M(free_rows[r], free_rows[c]);
  }
  const Vector x = block.fullPivLu().solve(rhs);
  for (int r = 0; r < nf; ++r) z[free_rows[r]] = x[r];
  return z;
}

// SPD problems (every bound kind, sizes from the update's 16 rows to the blocked factorization's) are factored by
// Cholesky only, and the answer is the planted z* and the direct solve of its set to rounding, with and without
// the base's polish; the LU path (cholesky = false) gives the same verdict and point.
TEST(BppSolver, SymmetricPositiveDefiniteBlocksAreFactoredByCholesky) {
  BppOptions lu_only;
  lu_only.cholesky = false;
  BppSolver cholesky, lu(lu_only);
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
    for (int size : {16, 20, 50, 150}) {
      for (bool polish : {true, false}) {
        const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, bounds, size, 6);
        SolverOptions options;
        options.polish = polish;
        const SolveResult a = cholesky.Solve(gen.problem, options);
        const SolveResult b = lu.Solve(gen.problem, options);
        const std::string where = gen.problem.name() + (polish ? " polished" : " raw");
        ASSERT_TRUE(a.solved()) << where << ": " << a.message;
        ASSERT_TRUE(b.solved()) << where << ": " << b.message;
        EXPECT_GT(a.GetDetail("factorizations"), 0.0) << where;
        EXPECT_EQ(a.GetDetail("cholesky_factorizations"), a.GetDetail("factorizations")) << where;
        EXPECT_TRUE(std::isnan(b.GetDetail("cholesky_factorizations"))) << where;
        const Vector direct = DirectSolveOnKnownSet(gen.problem, gen.z_star);
        EXPECT_LE(ForwardError(a.z, direct), 1e-12) << where;
        EXPECT_LE(ForwardError(a.z, gen.z_star), 1e-10) << where;
        EXPECT_LE(ForwardError(a.z, b.z), 1e-12) << where;
        EXPECT_LE(NaturalResidual(gen.problem, a.z), 1e-11 * (1.0 + gen.problem.q().cwiseAbs().maxCoeff())) << where;
      }
    }
  }
  // Small enough for enum (3^16 sets would not be: 2 free choices on 16 LCP rows are 65536): a 16-row LCP.
  const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 16, 7);
  const SolveResult a = cholesky.Solve(gen.problem);
  ASSERT_TRUE(a.solved()) << a.message;
  EXPECT_EQ(a.GetDetail("cholesky_factorizations"), a.GetDetail("factorizations"));
  EnumerativeSolver enumerative;
  const SolveResult e = enumerative.Solve(gen.problem);
  ASSERT_TRUE(e.solved()) << e.message;
  EXPECT_LE(ForwardError(a.z, e.z), 1e-12);
}

// A symmetric M given with its rows scaled (M = D S, D positive diagonal, not symmetric as stored) is symmetric
// after the base's row equilibration up to that scaling: still factored by Cholesky, same answer.
TEST(BppSolver, RowScaledSymmetricMatricesTakeTheCholeskyPath) {
  const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 60, 8);
  const int n = gen.problem.size();
  Vector d(n);
  for (int i = 0; i < n; ++i) d[i] = std::exp(std::sin(3.0 * i) * 4.0);  // 0.02 … 55
  const DenseMatrix scaled = d.asDiagonal() * gen.problem.dense_matrix();
  const BoxMLCP problem =
      BoxMLCP(scaled, d.cwiseProduct(gen.problem.q()), gen.problem.l(), gen.problem.u(), "row-scaled-spd");
  ASSERT_FALSE(problem.IsSymmetric());
  BppSolver solver;
  SolverOptions options;
  options.polish = false;
  const SolveResult r = solver.Solve(problem, options);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_GT(r.GetDetail("cholesky_factorizations"), 0.0);
  EXPECT_EQ(r.GetDetail("cholesky_factorizations"), r.GetDetail("factorizations"));
  EXPECT_LE(ForwardError(r.z, DirectSolveOnKnownSet(problem, gen.z_star)), 1e-12);
}

// A symmetric indefinite M (a 2×2 principal block [1 2; 2 1] with eigenvalue −1 in an otherwise dominant
// diagonal): the problem's answer z* has every row free, the Cholesky of that block fails, the LU takes over and
// solves it, and the answer is the direct solve. On PrefixCholesky's small blocks (12, 14 rows) and the updated
// ones, below and above the sweeps' 32 rows.
TEST(BppSolver, SymmetricIndefiniteBlocksFallBackToTheLu) {
  for (int n : {12, 14, 20, 48}) {
    DenseMatrix M = DenseMatrix::Zero(n, n);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> entry(-1.0, 1.0);
    for (int j = 0; j < n; ++j) {
      for (int i = j + 1; i < n; ++i) M(i, j) = M(j, i) = 0.05 * entry(rng) / n;
      M(j, j) = 1.0 + 0.5 * std::abs(entry(rng));
    }
    M(0, 0) = M(1, 1) = 1.0;
    M(0, 1) = M(1, 0) = 2.0;
    Vector z_star(n);
    for (int i = 0; i < n; ++i) z_star[i] = 0.1 * std::sin(1.7 * i + 0.3);
    const Vector q = -M * z_star;
    const BoxMLCP problem(M, q, Vector::Constant(n, -1.0), Vector::Constant(n, 1.0), "symmetric-indefinite");
    ASSERT_TRUE(problem.IsSymmetric());
    ASSERT_LT(Eigen::SelfAdjointEigenSolver<DenseMatrix>(M).eigenvalues().minCoeff(), -0.5);
    // From the Jacobi-scaled guess every row starts free (|q_i| < M_ii), so the first block is all of M.
    BppOptions guess, lu_only;
    guess.guess_sweeps = 0;
    lu_only.guess_sweeps = 0;
    lu_only.cholesky = false;
    BppSolver solver(guess), lu(lu_only), swept;
    for (bool polish : {true, false}) {
      SolverOptions options;
      options.polish = polish;
      const SolveResult r = solver.Solve(problem, options);
      const SolveResult b = lu.Solve(problem, options);
      ASSERT_TRUE(r.solved()) << n << ": " << r.message;
      ASSERT_TRUE(b.solved()) << n << ": " << b.message;
      EXPECT_EQ(r.iterations, 1) << n;
      EXPECT_EQ(r.GetDetail("factorizations"), 1.0) << n;
      EXPECT_TRUE(std::isnan(r.GetDetail("cholesky_factorizations"))) << n << ": the LU took over";
      EXPECT_LE(ForwardError(r.z, z_star), 1e-13) << n;
      EXPECT_LE(ForwardError(r.z, DirectSolveOnKnownSet(problem, z_star)), 1e-13) << n;
      EXPECT_LE(ForwardError(r.z, b.z), 1e-13) << n;
      // With the default sweeps (from 32 rows) the first set differs; M is not a P-matrix, so the answer may be
      // another solution: solved, and one by the natural residual recomputed here.
      const SolveResult c = swept.Solve(problem, options);
      ASSERT_TRUE(c.solved()) << n << ": " << c.message;
      EXPECT_LE(NaturalResidual(problem, c.z), 1e-13) << n;
    }
  }
}

// Nonsymmetric M never takes the Cholesky: with the option on or off, bpp's path and answer are the same bits.
TEST(BppSolver, NonsymmetricProblemsAreUnchangedByTheCholeskyOption) {
  BppOptions lu_only;
  lu_only.cholesky = false;
  BppSolver with, without(lu_only);
  for (MatrixFamily family : {MatrixFamily::kNonsymmetricPMatrix, MatrixFamily::kDiagonallyDominant,
                              MatrixFamily::kSkewPMatrix}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
      const GeneratedProblem gen = Planted(family, bounds, 40, 3);
      ASSERT_FALSE(gen.problem.IsSymmetric());
      const SolveResult a = with.Solve(gen.problem);
      const SolveResult b = without.Solve(gen.problem);
      ASSERT_TRUE(a.solved()) << gen.problem.name() << ": " << a.message;
      EXPECT_TRUE(std::isnan(a.GetDetail("cholesky_factorizations"))) << gen.problem.name();
      EXPECT_EQ(a.iterations, b.iterations) << gen.problem.name();
      EXPECT_EQ(a.GetDetail("factorizations"), b.GetDetail("factorizations")) << gen.problem.name();
      EXPECT_EQ(a.z, b.z) << gen.problem.name();
      EXPECT_LE(ForwardError(a.z, gen.z_star), 1e-8) << gen.problem.name();
    }
  }
}

// An answer whose set was factored afresh, unclipped, and is the set the base's polish reads off it is not polished
// again (the polish would factor the same block once more): the point is bpp's own, bit for bit as with the polish
// off, and exact to rounding.
TEST(BppSolver, AFreshlyFactoredAnswerIsNotFactoredAgainByThePolish) {
  const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 64, 1);
  BppSolver solver;
  SolverOptions raw;
  raw.polish = false;
  const SolveResult polished = solver.Solve(gen.problem);
  const SolveResult unpolished = solver.Solve(gen.problem, raw);
  ASSERT_TRUE(polished.solved()) << polished.message;
  ASSERT_EQ(polished.GetDetail("updated_sets"), 0.0) << "a set factored afresh is the point of this test";
  EXPECT_TRUE(std::isnan(polished.GetDetail("polished")));
  EXPECT_EQ(polished.z, unpolished.z);
  EXPECT_LE(ForwardError(polished.z, DirectSolveOnKnownSet(gen.problem, gen.z_star)), 1e-13);
  EXPECT_LE(polished.residual_scaled, 1e-13);
}

// The update path allocates nothing after the first solve of a size (free blocks of 16–64 rows and updates, LU
// and Cholesky).
TEST(BppSolver, UpdatedSolvesDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  // The symmetric problem twice: unpolished, its block pivots are updates of a Cholesky; polished, they are fresh
  // Cholesky factorizations (bpp_solver.h).
  for (const auto& [family, polish] : {std::pair{MatrixFamily::kNonsymmetricPMatrix, true},
                                       std::pair{MatrixFamily::kSymmetricPositiveDefinite, false},
                                       std::pair{MatrixFamily::kSymmetricPositiveDefinite, true}}) {
    const GeneratedProblem gen = Planted(family, BoundKind::kRelay, 96, 3);
    BppOptions no_sweeps;  // from the Jacobi-scaled guess these need several sets, hence updates
    no_sweeps.guess_sweeps = 0;
    BppSolver solver(no_sweeps);
    SolverOptions options;
    options.polish = polish;
    SolveResult result;
    solver.Solve(gen.problem, options, &result);
    ASSERT_TRUE(result.solved()) << result.message;
    if (family == MatrixFamily::kSymmetricPositiveDefinite) {
      ASSERT_GT(result.GetDetail("cholesky_factorizations"), 0.0) << gen.problem.name();
    }
    if (!(family == MatrixFamily::kSymmetricPositiveDefinite && polish)) {
      ASSERT_GT(result.GetDetail("updated_sets"), 0.0) << gen.problem.name();
    }
    const long allocations = test_support::CountMallocs([&] {
      for (int k = 0; k < 3; ++k) solver.Solve(gen.problem, options, &result);
    });
    EXPECT_EQ(allocations, 0) << gen.problem.name();
    EXPECT_TRUE(result.solved());
  }
}

// M = R·S (S symmetric positive definite, R a positive diagonal) and a sequence of free sets: each PrefixCholesky
// solve gives M_FF⁻¹ b_F (an LU of the block, computed here), keeps the leading rows of the last order that are
// still free, and a row that leaves truncates the factor at its place.
TEST(PrefixCholesky, SolvesAgreeWithAnLuOfTheBlockAndKeepTheLeadingRows) {
  const int n = 12;
  const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kBox, n, 5);
  Vector ratio(n), inv_ratio(n);
  for (int i = 0; i < n; ++i) {
    ratio[i] = std::exp(2.0 * std::sin(1.3 * i));
    inv_ratio[i] = 1.0 / ratio[i];
  }
  const DenseMatrix M = ratio.asDiagonal() * gen.problem.dense_matrix();
  const Vector q = ratio.cwiseProduct(gen.problem.q());
  PrefixCholesky factor;
  factor.Resize(n);
  struct Step {
    std::vector<int> free;
    int reused;  // rows of L kept from the set before
  };
  const std::vector<Step> steps = {{{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, 0},
                                   {{0, 1, 2, 3, 4, 5, 6, 7, 10, 11}, 8},   // 8, 9 leave at the end, 10, 11 enter
                                   {{1, 2, 3, 4, 5, 6, 7, 10, 11}, 0},      // row 0 leaves: nothing is kept
                                   {{1, 2, 3, 4, 5, 6, 7, 10, 11}, 9},      // the same set: all kept
                                   {{1, 2, 3, 4, 5, 6, 8, 9, 10, 11}, 6},   // 7 leaves: 1..6 kept
                                   {{}, 0},
                                   {{3, 4}, 0}};
  int reused = 0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const std::vector<int>& f = steps[k].free;
    const int nf = static_cast<int>(f.size());
    Vector z(n);
    std::vector<char> in(n, 0);
    for (int i : f) in[i] = 1;
    for (int i = 0; i < n; ++i) z[i] = in[i] ? 0.0 : (i % 2 ? gen.problem.l()[i] : gen.problem.u()[i]);
    if (nf == 0) continue;  // bpp does not call it with no free row
    ASSERT_EQ(factor.Solve(M.data(), n, q.data(), ratio.data(), inv_ratio.data(), f.data(), nf, 1e-14, z.data()),
              PrefixCholesky::Outcome::kSolved)
        << k;
    reused += steps[k].reused;
    EXPECT_EQ(factor.reused_rows(), reused) << k;
    DenseMatrix block(nf, nf);
    Vector rhs(nf);
    for (int r = 0; r < nf; ++r) {
      rhs[r] = -q[f[r]];
      for (int j = 0; j < n; ++j) {
        if (!in[j]) rhs[r] -= M(f[r], j) * z[j];
      }
      for (int c = 0; c < nf; ++c) block(r, c) = M(f[r], f[c]);
    }
    const Vector x = block.partialPivLu().solve(rhs);
    for (int r = 0; r < nf; ++r) EXPECT_NEAR(z[f[r]], x[r], 1e-12 * (1.0 + x.cwiseAbs().maxCoeff())) << k;
  }
}

// A set whose block is not positive definite ends the factorization (kNotPositive) and drops it: the next set is
// factored from its first row and solved right.
TEST(PrefixCholesky, ABlockThatIsNotPositiveDefiniteDropsTheFactor) {
  const int n = 6;
  DenseMatrix M = DenseMatrix::Identity(n, n) * 2.0;
  M(2, 3) = M(3, 2) = 3.0;  // [2 3; 3 2]: eigenvalue −1
  M(0, 1) = M(1, 0) = 0.5;
  const Vector q = Vector::LinSpaced(n, -1.0, 1.0);
  const Vector ones = Vector::Ones(n);
  PrefixCholesky factor;
  factor.Resize(n);
  Vector z = Vector::Zero(n);
  const std::vector<int> bad = {0, 1, 2, 3}, good = {0, 1, 4, 5};
  EXPECT_EQ(factor.Solve(M.data(), n, q.data(), ones.data(), ones.data(), bad.data(), 4, 1e-14, z.data()),
            PrefixCholesky::Outcome::kNotPositive);
  z.setZero();
  ASSERT_EQ(factor.Solve(M.data(), n, q.data(), ones.data(), ones.data(), good.data(), 4, 1e-14, z.data()),
            PrefixCholesky::Outcome::kSolved);
  EXPECT_EQ(factor.reused_rows(), 0);
  // Rows 0, 1: [2 0.5; 0.5 2] z = −q; rows 4, 5 decoupled: z = −q / 2 (rows 2, 3 at 0).
  const double det = 2.0 * 2.0 - 0.25;
  EXPECT_NEAR(z[0], (-q[0] * 2.0 + 0.5 * q[1]) / det, 1e-15);
  EXPECT_NEAR(z[1], (-q[1] * 2.0 + 0.5 * q[0]) / det, 1e-15);
  EXPECT_NEAR(z[4], -q[4] / 2.0, 1e-15);
  EXPECT_NEAR(z[5], -q[5] / 2.0, 1e-15);
}

// A relay whose entries span 8 decades (the shape of Siconos' relay1.dat: a graded symmetric positive definite M,
// bounds far below q's scale).
BoxMLCP GradedRelay() {
  const int n = 15;
  DenseMatrix M(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) M(i, j) = std::pow(10.0, 7.0 - 0.25 * (i + j)) / (1.0 + i + j);  // Hilbert, graded
  }
  M.diagonal() *= 2.0;
  return BoxMLCP::Relay(M, Vector::Constant(n, -13.3), -0.1, 0.1, "graded-relay");
}

// An SPD relay of condition 1e6 (U diag(1 … 1e-6) Uᵀ, U a random rotation; m = 15, q of the bounds' scale): bpp goes
// through many sets, more than the two it factors by LU before PrefixCholesky.
BoxMLCP IllConditionedRelay() {
  const int n = 15;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  DenseMatrix A(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
  }
  const DenseMatrix U = Eigen::HouseholderQR<DenseMatrix>(A).householderQ();
  Vector spectrum(n), q(n);
  for (int i = 0; i < n; ++i) spectrum[i] = std::pow(10.0, -6.0 * i / (n - 1));
  for (int i = 0; i < n; ++i) q[i] = 2e-3 * normal(rng);
  const DenseMatrix M = U * spectrum.asDiagonal() * U.transpose();
  const DenseMatrix S = 0.5 * (M + M.transpose());
  return BoxMLCP::Relay(S, q, -1.0, 1.0, "ill-conditioned-relay");
}

// Below UpdatedFreeBlock::kMinRows, a symmetric M's sets after the second are solved by PrefixCholesky (the first
// two by the inline LU): the same answers as the LU (cholesky = false), the planted solution, enum's (LCPs) or
// lemke's, and an answer the polish would only solve again is not polished (the point is the raw one, bit for bit).
TEST(BppSolver, SmallSymmetricBlocksTakeThePrefixCholesky) {
  BppOptions lu_only;
  lu_only.cholesky = false;
  BppSolver cholesky, lu(lu_only);
  EnumerativeSolver enumerative;
  LemkeSolver lemke;
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
    for (int size : {12, 13, 15}) {
      for (std::uint64_t seed : {1, 2, 3}) {
        const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, bounds, size, seed);
        const std::string where = gen.problem.name();
        SolverOptions raw;
        raw.polish = false;
        const SolveResult a = cholesky.Solve(gen.problem);
        const SolveResult r = cholesky.Solve(gen.problem, raw);
        const SolveResult b = lu.Solve(gen.problem);
        ASSERT_TRUE(a.solved()) << where << ": " << a.message;
        ASSERT_TRUE(b.solved()) << where << ": " << b.message;
        const double factorizations = a.GetDetail("factorizations");  // 0 when the first set has every row bound
        if (factorizations > 2.0) {
          EXPECT_EQ(a.GetDetail("cholesky_factorizations"), factorizations - 2.0) << where;
        } else {
          EXPECT_TRUE(std::isnan(a.GetDetail("cholesky_factorizations"))) << where << ": the two LU sets";
        }
        EXPECT_TRUE(std::isnan(b.GetDetail("cholesky_factorizations"))) << where;
        EXPECT_LE(ForwardError(a.z, DirectSolveOnKnownSet(gen.problem, gen.z_star)), 1e-12) << where;
        EXPECT_LE(ForwardError(a.z, b.z), 1e-12) << where;
        EXPECT_LE(NaturalResidual(gen.problem, a.z), 1e-11 * (1.0 + gen.problem.q().cwiseAbs().maxCoeff())) << where;
        if (std::isnan(a.GetDetail("polished"))) {
          EXPECT_EQ(a.z, r.z) << where;
        }
        const SolveResult e = bounds == BoundKind::kLCP ? enumerative.Solve(gen.problem) : lemke.Solve(gen.problem);
        ASSERT_TRUE(e.solved()) << where << ": " << e.message;
        EXPECT_LE(ForwardError(a.z, e.z), 1e-10) << where;
      }
    }
  }
  // The graded relay, and one of many sets: the answers are lemke's; on the second, the prefix keeps rows between
  // its sets after the first two.
  for (const BoxMLCP& relay : {GradedRelay(), IllConditionedRelay()}) {
    ASSERT_TRUE(relay.IsSymmetric());
    const SolveResult a = cholesky.Solve(relay);
    ASSERT_TRUE(a.solved()) << relay.name() << ": " << a.message;
    const SolveResult e = lemke.Solve(relay);
    ASSERT_TRUE(e.solved()) << e.message;
    EXPECT_LE(ForwardError(a.z, e.z), 1e-8) << relay.name();
    EXPECT_LE(a.residual_scaled, 1e-10) << relay.name();
  }
  const SolveResult many = cholesky.Solve(IllConditionedRelay());
  ASSERT_GT(many.GetDetail("factorizations"), 3.0);
  EXPECT_EQ(many.GetDetail("cholesky_factorizations"), many.GetDetail("factorizations") - 2.0);
  EXPECT_GT(many.GetDetail("reused_cholesky_rows"), 0.0);
}

TEST(BppSolver, SmallSymmetricBlocksOfAFewSetsStayWithTheLu) {
  // At most two sets (most solves at these sizes): the inline LU alone, the same bits as with cholesky = false.
  BppOptions lu_only;
  lu_only.cholesky = false;
  BppSolver cholesky, lu(lu_only);
  int checked = 0;
  for (std::uint64_t seed : {1, 2, 3, 4, 5}) {
    const GeneratedProblem gen = Planted(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 14, seed);
    const SolveResult a = cholesky.Solve(gen.problem);
    if (!(a.GetDetail("factorizations") <= 2.0)) continue;
    ++checked;
    const SolveResult b = lu.Solve(gen.problem);
    EXPECT_EQ(a.z, b.z) << gen.problem.name();
    EXPECT_EQ(a.iterations, b.iterations) << gen.problem.name();
    EXPECT_TRUE(std::isnan(a.GetDetail("cholesky_factorizations"))) << gen.problem.name();
  }
  EXPECT_GT(checked, 0);
}

// The small Cholesky path allocates nothing after the first solve of a size, polished or not.
TEST(BppSolver, SmallCholeskySolvesDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  const BoxMLCP relay = IllConditionedRelay();  // more sets than the two the LU factors first
  for (bool polish : {true, false}) {
    BppSolver solver;
    SolverOptions options;
    options.polish = polish;
    SolveResult result;
    solver.Solve(relay, options, &result);
    ASSERT_TRUE(result.solved()) << result.message;
    ASSERT_GT(result.GetDetail("cholesky_factorizations"), 0.0);
    const long allocations = test_support::CountMallocs([&] {
      for (int k = 0; k < 3; ++k) solver.Solve(relay, options, &result);
    });
    EXPECT_EQ(allocations, 0) << polish;
    EXPECT_TRUE(result.solved());
  }
}

}  // namespace
}  // namespace smcbench
