// Tests of the semismooth Newton backend: problems with a known solution built by picking z* first, residuals
// recomputed here from M, q, l, u (never trusting the solver's status alone).
#include "solvers/newton/semismooth_newton_solver.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "solvers/core/verdict.h"
#include "tests/support/malloc_counter.h"
#include "tests/support/small_h_relay.h"
#include "solvers/newton/fischer_burmeister.h"
#include "tests/support/small_mcps.h"

namespace smcbench {
namespace {

enum class RowKind { kFree, kLower, kUpper, kBox };
enum class RowState { kAtLower, kAtUpper, kInterior, kDegenerateLower, kDegenerateUpper };

// A box-MLCP with known solution z*: M, z*, bounds and F* = M z* + q are chosen, q derived.
struct Known {
  DenseMatrix M;
  Vector q, l, u, z_star;
};

DenseMatrix RandomMatrix(int n, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  DenseMatrix B(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) B(i, j) = normal(*rng);
  }
  return B;
}

// Symmetric positive definite: BᵀB/n + 0.5 I.
DenseMatrix RandomSpd(int n, std::mt19937* rng) {
  const DenseMatrix B = RandomMatrix(n, rng);
  DenseMatrix M = B.transpose() * B / n;
  M.diagonal().array() += 0.5;
  return M;
}

// Nonsymmetric with positive definite symmetric part (hence a P-matrix): SPD + skew.
DenseMatrix RandomNonsymmetricPd(int n, std::mt19937* rng) {
  const DenseMatrix K = RandomMatrix(n, rng);
  return RandomSpd(n, rng) + (K - K.transpose()) * 0.5;
}

// Picks bounds of the given kinds (cycled through `kinds`) and a solution state per row, then q.
Known MakeKnown(DenseMatrix M, const std::vector<RowKind>& kinds, double degenerate_fraction, std::mt19937* rng) {
  const int n = static_cast<int>(M.rows());
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  Known k;
  k.M = std::move(M);
  k.l.resize(n);
  k.u.resize(n);
  k.z_star.resize(n);
  Vector F(n);
  for (int i = 0; i < n; ++i) {
    const RowKind kind = kinds[i % kinds.size()];
    const double lo = -1.0 - unif(*rng), hi = 1.0 + unif(*rng);
    k.l[i] = (kind == RowKind::kLower || kind == RowKind::kBox) ? lo : -kInf;
    k.u[i] = (kind == RowKind::kUpper || kind == RowKind::kBox) ? hi : kInf;
    const bool degenerate = unif(*rng) < degenerate_fraction;
    const double pick = unif(*rng);
    RowState state = RowState::kInterior;
    if (kind == RowKind::kLower) {
      state = pick < 0.5 ? (degenerate ? RowState::kDegenerateLower : RowState::kAtLower) : RowState::kInterior;
    } else if (kind == RowKind::kUpper) {
      state = pick < 0.5 ? (degenerate ? RowState::kDegenerateUpper : RowState::kAtUpper) : RowState::kInterior;
    } else if (kind == RowKind::kBox) {
      if (pick < 0.35) {
        state = degenerate ? RowState::kDegenerateLower : RowState::kAtLower;
      } else if (pick < 0.7) {
        state = degenerate ? RowState::kDegenerateUpper : RowState::kAtUpper;
      }
    }
    switch (state) {
      case RowState::kAtLower:
        k.z_star[i] = k.l[i];
        F[i] = 0.1 + unif(*rng);
        break;
      case RowState::kAtUpper:
        k.z_star[i] = k.u[i];
        F[i] = -0.1 - unif(*rng);
        break;
      case RowState::kDegenerateLower:
        k.z_star[i] = k.l[i];
        F[i] = 0.0;
        break;
      case RowState::kDegenerateUpper:
        k.z_star[i] = k.u[i];
        F[i] = 0.0;
        break;
      case RowState::kInterior: {
        const double a = std::isfinite(k.l[i]) ? k.l[i] : -2.0, b = std::isfinite(k.u[i]) ? k.u[i] : 2.0;
        k.z_star[i] = a + (b - a) * (0.1 + 0.8 * unif(*rng));
        F[i] = 0.0;
        break;
      }
    }
  }
  k.q = F - k.M * k.z_star;
  return k;
}

SparseMatrix ToSparse(const DenseMatrix& M) { return M.sparseView(); }

// The merit function, recomputed here from the data.
double RelativeResidual(const BoxMLCP& p, const Vector& z) {
  Vector w(p.size());
  p.Affine(z, &w);
  return NaturalResidualNorm(z, w, p.l(), p.u()) / (1.0 + p.q().cwiseAbs().maxCoeff());
}

void ExpectSolved(const BoxMLCP& p, const SolveResult& r, const Vector& z_star, double z_tol) {
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(RelativeResidual(p, r.z), 1e-10);
  EXPECT_LE((r.z - z_star).cwiseAbs().maxCoeff(), z_tol);
  for (int i = 0; i < p.size(); ++i) {  // the returned point is feasible
    EXPECT_GE(r.z[i], p.l()[i]);
    EXPECT_LE(r.z[i], p.u()[i]);
  }
}

// ---------------------------------------------------------------- the complementarity function

TEST(FischerBurmeister, ZeroSetAndStableEvaluation) {
  EXPECT_EQ(fb::Phi(0.0, 3.0), 0.0);
  EXPECT_EQ(fb::Phi(2.0, 0.0), 0.0);
  EXPECT_GT(fb::Phi(-1.0, 2.0), 0.0);
  EXPECT_LT(fb::Phi(1.0, 1.0), 0.0);
  // a, b > 0 with ab tiny: −2ab/(r + a + b) keeps full relative accuracy where r − a − b would cancel.
  EXPECT_NEAR(fb::Phi(1e-12, 1.0) / -1e-12, 1.0, 1e-10);
  EXPECT_NEAR(fb::Phi(1e8, 1e8), (std::sqrt(2.0) - 2.0) * 1e8, 1e-6);
  // Box: zero exactly on the three solution branches.
  EXPECT_EQ(fb::BoxPhi(-1.0, 2.0, -1.0, 1.0), 0.0);          // at l, F > 0
  EXPECT_EQ(fb::BoxPhi(1.0, -2.0, -1.0, 1.0), 0.0);          // at u, F < 0
  EXPECT_NEAR(fb::BoxPhi(0.3, 0.0, -1.0, 1.0), 0.0, 1e-16);  // interior, F = 0
  EXPECT_NE(fb::BoxPhi(0.3, 0.1, -1.0, 1.0), 0.0);
  EXPECT_NE(fb::BoxPhi(-1.0, -0.1, -1.0, 1.0), 0.0);  // at l with F < 0 is not a solution
  EXPECT_NE(fb::BoxPhi(1.0, 0.1, -1.0, 1.0), 0.0);    // at u with F > 0 is not a solution
  EXPECT_EQ(fb::BoxPhi(7.0, -2.5, -kInf, kInf), -2.5);
}

TEST(FischerBurmeister, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unif(-2.0, 2.0);
  const double bounds[4][2] = {{-kInf, kInf}, {-1.0, kInf}, {-kInf, 1.0}, {-1.0, 1.0}};
  for (int trial = 0; trial < 400; ++trial) {
    const double z = unif(rng), F = unif(rng);
    const double l = bounds[trial % 4][0], u = bounds[trial % 4][1];
    double value;
    fb::RowDerivative rd;
    ASSERT_FALSE(fb::BoxPhiDerivative(z, F, l, u, 1.0, 0.0, &value, &rd));
    EXPECT_NEAR(value, fb::BoxPhi(z, F, l, u), 1e-14);
    const double h = 1e-7;
    const double dz = (fb::BoxPhi(z + h, F, l, u) - fb::BoxPhi(z - h, F, l, u)) / (2 * h);
    const double dF = (fb::BoxPhi(z, F + h, l, u) - fb::BoxPhi(z, F - h, l, u)) / (2 * h);
    EXPECT_NEAR(rd.da, dz, 1e-6) << "z=" << z << " F=" << F << " l=" << l << " u=" << u;
    EXPECT_NEAR(rd.db, dF, 1e-6);
    if (std::isfinite(l) || std::isfinite(u)) {  // sign convention used by the reduced system
      EXPECT_LE(rd.da, 0.0);
      EXPECT_LE(rd.db, 0.0);
    }
  }
}

TEST(FischerBurmeister, KinkUsesDirectionalLimit) {
  // Lower bound, z = l, F = 0: limit along (dz, dF) = (1, 2) is (1/√5 − 1, 2/√5 − 1).
  double value;
  fb::RowDerivative rd;
  EXPECT_TRUE(fb::BoxPhiDerivative(0.0, 0.0, 0.0, kInf, 1.0, 2.0, &value, &rd));
  EXPECT_EQ(value, 0.0);
  EXPECT_NEAR(rd.da, 1.0 / std::sqrt(5.0) - 1.0, 1e-15);
  EXPECT_NEAR(rd.db, 2.0 / std::sqrt(5.0) - 1.0, 1e-15);
  // It is the one-sided derivative along the path: (Phi(t, 2t) − 0)/t.
  const double t = 1e-6;
  EXPECT_NEAR(fb::BoxPhi(t, 2 * t, 0.0, kInf) / t, rd.da + 2.0 * rd.db, 1e-9);  // phi is homogeneous
  // Box, z = l, F = 0 (outer kink) and z = u, F = 0 (inner kink): same check along (1, dF).
  for (double zk : {-1.0, 1.0}) {
    EXPECT_TRUE(fb::BoxPhiDerivative(zk, 0.0, -1.0, 1.0, 1.0, -0.5, &value, &rd));
    const double path = fb::BoxPhi(zk + t, -0.5 * t, -1.0, 1.0) / t;
    EXPECT_NEAR(path, rd.da - 0.5 * rd.db, 1e-5) << "z=" << zk;
  }
}

// ---------------------------------------------------------------- box-MLCPs with known solutions

TEST(NewtonSolver, InfoAndOptions) {
  SemismoothNewtonSolver solver;
  EXPECT_EQ(solver.info().name, "newton");
  EXPECT_TRUE(solver.info().mcp);
  EXPECT_TRUE(solver.info().dense);
  EXPECT_TRUE(solver.info().sparse);
  std::string error;
  EXPECT_TRUE(solver.SetOption("nonmonotone_memory", "5", &error)) << error;
  EXPECT_EQ(solver.options().nonmonotone_memory, 5);
  EXPECT_FALSE(solver.SetOption("nonmonotone_memory", "0", &error));
  EXPECT_FALSE(solver.SetOption("no_such_option", "1", &error));
  EXPECT_TRUE(solver.SetOption("mcp_stagnation_window", "7", &error)) << error;
  EXPECT_EQ(solver.options().mcp_stagnation_window, 7);
  EXPECT_FALSE(solver.SetOption("mcp_stagnation_window", "0", &error));
  EXPECT_NE(error.find("mcp_stagnation_window"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("mcp_proximal_lambda", "-1", &error));
  EXPECT_NE(error.find("mcp_proximal_lambda"), std::string::npos) << error;
  NewtonOptions bad;
  bad.armijo_sigma = 0.7;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("armijo_sigma"), std::string::npos);
  SemismoothNewtonSolver bad_solver(bad);
  const BoxMLCP p = BoxMLCP::LCP(DenseMatrix::Identity(2, 2), Vector::Constant(2, -1.0));
  EXPECT_EQ(bad_solver.Solve(p).status, SolveStatus::kInvalidOptions);
}

TEST(NewtonSolver, LcpSpd) {
  std::mt19937 rng(1);
  for (int n : {1, 2, 5, 40, 120}) {
    const Known k = MakeKnown(RandomSpd(n, &rng), {RowKind::kLower}, 0.0, &rng);
    const BoxMLCP p(k.M, k.q, k.l, k.u);
    SemismoothNewtonSolver solver;
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r, k.z_star, 1e-8);
    EXPECT_LE(r.iterations, 30) << "n=" << n;
  }
}

TEST(NewtonSolver, LcpNonsymmetricWithDegenerateRows) {
  std::mt19937 rng(2);
  for (int n : {10, 60, 150}) {
    const Known k = MakeKnown(RandomNonsymmetricPd(n, &rng), {RowKind::kLower}, 0.4, &rng);
    const BoxMLCP p(k.M, k.q, k.l, k.u);
    SemismoothNewtonSolver solver;
    ExpectSolved(p, solver.Solve(p), k.z_star, 1e-7);
  }
}

TEST(NewtonSolver, RelayNonsymmetric) {
  std::mt19937 rng(3);
  for (int n : {3, 30, 100}) {
    const Known k = MakeKnown(RandomNonsymmetricPd(n, &rng), {RowKind::kBox}, 0.2, &rng);
    const BoxMLCP p(k.M, k.q, k.l, k.u);
    SemismoothNewtonSolver solver;
    ExpectSolved(p, solver.Solve(p), k.z_star, 1e-7);
  }
}

TEST(NewtonSolver, MixedBoundsDenseAndSparseAgree) {
  std::mt19937 rng(4);
  const std::vector<RowKind> kinds = {RowKind::kFree, RowKind::kLower, RowKind::kUpper, RowKind::kBox};
  for (int n : {8, 50, 130}) {
    const Known k = MakeKnown(RandomNonsymmetricPd(n, &rng), kinds, 0.3, &rng);
    const BoxMLCP dense(k.M, k.q, k.l, k.u);
    const BoxMLCP sparse(ToSparse(k.M), k.q, k.l, k.u);
    for (NewtonOptions::LinearSolver linear_solver :
         {NewtonOptions::kAutoLinearSolver, NewtonOptions::kDenseLinearSolver, NewtonOptions::kSparseLinearSolver}) {
      NewtonOptions o;
      o.linear_solver = linear_solver;
      SemismoothNewtonSolver solver(o);
      ExpectSolved(dense, solver.Solve(dense), k.z_star, 1e-7);
      ExpectSolved(sparse, solver.Solve(sparse), k.z_star, 1e-7);
    }
  }
}

TEST(NewtonSolver, ExactNewtonAndNonmonotoneVariants) {
  std::mt19937 rng(5);
  const std::vector<RowKind> kinds = {RowKind::kLower, RowKind::kBox, RowKind::kFree};
  const Known k = MakeKnown(RandomNonsymmetricPd(80, &rng), kinds, 0.25, &rng);
  const BoxMLCP p(k.M, k.q, k.l, k.u);
  NewtonOptions exact;
  exact.reduction_threshold = 0.0;
  NewtonOptions nonmonotone;
  nonmonotone.nonmonotone_memory = 8;
  NewtonOptions no_safeguard;
  no_safeguard.proximal_safeguard = false;
  for (const NewtonOptions& o : {exact, nonmonotone, no_safeguard}) {
    SemismoothNewtonSolver solver(o);
    ExpectSolved(p, solver.Solve(p), k.z_star, 1e-7);
  }
}

TEST(NewtonSolver, SymmetricWithAndWithoutCholesky) {
  std::mt19937 rng(12);
  const Known k = MakeKnown(RandomSpd(90, &rng), {RowKind::kBox, RowKind::kLower, RowKind::kFree}, 0.2, &rng);
  const BoxMLCP p(k.M, k.q, k.l, k.u);
  for (bool cholesky : {true, false}) {
    NewtonOptions o;
    o.use_cholesky = cholesky;
    SemismoothNewtonSolver solver(o);
    ExpectSolved(p, solver.Solve(p), k.z_star, 1e-7);
  }
}

// Monotone LCPs with a rank-deficient M: solutions are not isolated and the Newton matrix is singular near
// them; the regularized Newton step must still reach the tolerance (z* is not unique, so only the residual
// is checked). Without the regularization such problems crawl along gradient steps.
TEST(NewtonSolver, MonotoneRankDeficientLcp) {
  for (int seed = 0; seed < 10; ++seed) {
    std::mt19937 rng(100 + seed);
    const int n = 30;
    const DenseMatrix C = RandomMatrix(n / 2, &rng).leftCols(n / 2);
    DenseMatrix B = DenseMatrix::Zero(n / 2, n);
    B.leftCols(n / 2) = C;
    B.rightCols(n / 2) = RandomMatrix(n / 2, &rng);
    const DenseMatrix M = B.transpose() * B / n;  // PSD, rank n/2
    const Known k = MakeKnown(M, {RowKind::kLower, RowKind::kBox}, 0.3, &rng);
    const BoxMLCP p(k.M, k.q, k.l, k.u);
    SemismoothNewtonSolver solver;
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "seed " << seed << ": " << r.message;
    EXPECT_LE(RelativeResidual(p, r.z), 1e-10);
  }
}

TEST(NewtonSolver, KinkAtTheStartingPoint) {
  // At z = 0 row 0 has z_0 = 0 = F_0: the DFK rule must give a usable Jacobian element.
  DenseMatrix M(2, 2);
  M << 2, 1, 1, 2;
  Vector q(2);
  q << 0, -3;
  const BoxMLCP p = BoxMLCP::LCP(M, q);
  SemismoothNewtonSolver solver;
  Vector z_star(2);
  z_star << 0, 1.5;
  ExpectSolved(p, solver.Solve(p), z_star, 1e-9);
  // Fully degenerate: q = 0, the start z = 0 is the solution.
  const BoxMLCP zero = BoxMLCP::LCP(M, Vector::Zero(2));
  const SolveResult r = solver.Solve(zero);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.iterations, 0);
}

TEST(NewtonSolver, WarmStartAtSolutionTakesNoIteration) {
  std::mt19937 rng(6);
  const Known k = MakeKnown(RandomSpd(30, &rng), {RowKind::kBox, RowKind::kLower}, 0.0, &rng);
  const BoxMLCP p(k.M, k.q, k.l, k.u);
  SemismoothNewtonSolver solver;
  SolverOptions options;
  options.warm_start = solver.Solve(p).z;
  const SolveResult r = solver.Solve(p, options);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.iterations, 0);
}

// Tridiagonal, diagonally dominant, nonsymmetric; mixed bounds; stored sparse.
TEST(NewtonSolver, LargeSparseTridiagonal) {
  const int n = 20000;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0 + unif(rng));
    if (i > 0) t.emplace_back(i, i - 1, -1.0 - 0.5 * unif(rng));
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0 + 0.5 * unif(rng));
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(t.begin(), t.end());
  Vector l(n), u(n), z_star(n), F(n);
  for (int i = 0; i < n; ++i) {
    switch (i % 4) {
      case 0:
        l[i] = 0;
        u[i] = kInf;
        break;
      case 1:
        l[i] = -1;
        u[i] = 1;
        break;
      case 2:
        l[i] = -kInf;
        u[i] = kInf;
        break;
      default:
        l[i] = -kInf;
        u[i] = 0.5;
        break;
    }
    const double pick = unif(rng);
    if (std::isfinite(l[i]) && pick < 0.4) {
      z_star[i] = l[i];
      F[i] = pick < 0.1 ? 0.0 : unif(rng) + 0.1;
    } else if (std::isfinite(u[i]) && pick > 0.6) {
      z_star[i] = u[i];
      F[i] = -unif(rng) - 0.1;
    } else {
      z_star[i] = std::isfinite(l[i]) ? l[i] + 0.3 : (std::isfinite(u[i]) ? u[i] - 0.3 : unif(rng) - 0.5);
      F[i] = 0.0;
    }
  }
  const Vector q = F - M * z_star;
  const BoxMLCP p(M, q, l, u);
  SemismoothNewtonSolver solver;
  const auto start = std::chrono::steady_clock::now();
  const SolveResult r = solver.Solve(p);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ExpectSolved(p, r, z_star, 1e-8);
  EXPECT_LT(seconds, 5.0);  // generous for sanitizer builds; Release takes a few hundredths
  std::printf("[ info ] m = %d sparse tridiagonal: %d iterations, %.3f s\n", n, r.iterations, seconds);
}

TEST(NewtonSolver, RepeatedSolvesDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc is owned by the sanitizer runtime";
  std::mt19937 rng(9);
  const std::vector<RowKind> kinds = {RowKind::kFree, RowKind::kLower, RowKind::kBox};
  const Known k = MakeKnown(RandomNonsymmetricPd(60, &rng), kinds, 0.2, &rng);
  const BoxMLCP dense(k.M, k.q, k.l, k.u);
  const BoxMLCP sparse(ToSparse(k.M), k.q, k.l, k.u);
  NewtonOptions sparse_options;
  sparse_options.linear_solver = NewtonOptions::kSparseLinearSolver;
  // Newton's own path: above BoxMLCP::kSmallSize the base's generic polish allocates by design (polish.h).
  SolverOptions raw;
  raw.polish = false;
  for (const BoxMLCP* p : {&dense, &sparse}) {
    SemismoothNewtonSolver solver(p->is_sparse() ? sparse_options : NewtonOptions{});
    SolveResult result;
    solver.Solve(*p, raw, &result);  // sizes the workspace and the result
    ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
    test_support::StartCountingMallocs();
    for (int rep = 0; rep < 3; ++rep) solver.Solve(*p, raw, &result);
    const long mallocs = test_support::StopCountingMallocs();
    // Dense: nothing at all. Sparse: UMFPACK's factorization mallocs its own memory (C, out of our hands); our
    // code's allocations all go through operator new, and there are none.
    if (!p->is_sparse()) {
      EXPECT_EQ(mallocs, 0) << "dense";
    }
    EXPECT_EQ(test_support::OperatorNewCalls(), 0) << (p->is_sparse() ? "sparse" : "dense");
    EXPECT_EQ(result.status, SolveStatus::kSolved);
  }
  // The whole of Solve, polish included, on the small-solve path (n ≤ BoxMLCP::kSmallSize).
  const Known small = MakeKnown(RandomNonsymmetricPd(3, &rng), {RowKind::kBox}, 0.0, &rng);
  const BoxMLCP small_problem(small.M, small.q, small.l, small.u);
  SemismoothNewtonSolver solver;
  SolveResult result;
  solver.Solve(small_problem, SolverOptions{}, &result);
  ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
  test_support::StartCountingMallocs();
  for (int rep = 0; rep < 3; ++rep) solver.Solve(small_problem, SolverOptions{}, &result);
  EXPECT_EQ(test_support::StopCountingMallocs(), 0) << "n = 3 with the polish";
}

// ---------------------------------------------------------------- failures are statuses

TEST(NewtonSolver, InfeasibleMonotoneLcpIsNotSolved) {
  // M skew-symmetric (monotone, singular part), q = (−1, −1): w_2 = −z_1 − 1 < 0 for every z ≥ 0.
  DenseMatrix M(2, 2);
  M << 0, 1, -1, 0;
  const BoxMLCP p = BoxMLCP::LCP(M, Vector::Constant(2, -1.0));
  SemismoothNewtonSolver solver;
  const SolveResult r = solver.Solve(p);
  EXPECT_NE(r.status, SolveStatus::kSolved);
  EXPECT_NE(r.status, SolveStatus::kInaccurate);
  EXPECT_FALSE(r.message.empty());
  EXPECT_GT(RelativeResidual(p, r.z), 1e-3);
}

TEST(NewtonSolver, SingularSystemWithoutDirection) {
  // Free rows with M = 0, q ≠ 0: H = 0 and ∇Psi = 0, no direction exists.
  const BoxMLCP p(DenseMatrix::Zero(3, 3), Vector::Constant(3, 1.0), Vector::Constant(3, -kInf),
                  Vector::Constant(3, kInf));
  SemismoothNewtonSolver solver;
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSingular) << r.message;
  EXPECT_NE(r.message.find("residual"), std::string::npos);
}

TEST(NewtonSolver, WithoutGradientFallbackASingularSystemIsReported) {
  const BoxMLCP p(DenseMatrix::Zero(2, 2), Vector::Constant(2, 1.0), Vector::Constant(2, -kInf),
                  Vector::Constant(2, kInf));
  NewtonOptions o;
  o.gradient_fallback = false;
  o.proximal_safeguard = false;
  SemismoothNewtonSolver solver(o);
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSingular) << r.message;
  EXPECT_EQ(r.iterations, 1);
}

TEST(NewtonSolver, TimeLimit) {
  std::mt19937 rng(13);
  const Known k = MakeKnown(RandomNonsymmetricPd(40, &rng), {RowKind::kBox}, 0.0, &rng);
  const BoxMLCP p(k.M, k.q, k.l, k.u);
  SemismoothNewtonSolver solver;
  SolverOptions options;
  options.time_limit_seconds = 1e-12;
  const SolveResult r = solver.Solve(p, options);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit) << r.message;
}

TEST(NewtonSolver, IterationLimit) {
  std::mt19937 rng(10);
  const Known k = MakeKnown(RandomNonsymmetricPd(50, &rng), {RowKind::kBox}, 0.0, &rng);
  const BoxMLCP p(k.M, k.q, k.l, k.u);
  SemismoothNewtonSolver solver;
  SolverOptions options;
  options.max_iterations = 1;
  const SolveResult r = solver.Solve(p, options);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit);
  EXPECT_EQ(r.iterations, 1);
}

// ---------------------------------------------------------------- nonlinear MCPs

// Billups' example (tests/support/small_mcps.h): the merit function's local minimizer outside the box.
TEST(NewtonSolverMcp, BillupsWithoutSafeguardStallsHonestly) {
  const FunctionMCP mcp = BillupsMcp();
  NewtonOptions o;
  o.proximal_safeguard = false;
  SemismoothNewtonSolver solver(o);
  const SolveResult r = solver.Solve(mcp);
  EXPECT_TRUE(r.status == SolveStatus::kStalled || r.status == SolveStatus::kIterationLimit)
      << ToString(r.status) << ": " << r.message;
  EXPECT_NE(r.message.find("residual"), std::string::npos);
  EXPECT_LT(std::abs(r.z[0] - (1.0 - std::sqrt(1.01))), 0.01) << "expected: trapped at the merit minimizer";
}

TEST(NewtonSolverMcp, BillupsSolvedByProximalPerturbation) {
  const FunctionMCP mcp = BillupsMcp();
  SemismoothNewtonSolver solver;
  const SolveResult r = solver.Solve(mcp);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_NEAR(r.z[0], 1.0 + std::sqrt(1.01), 1e-9);
  EXPECT_GE(r.GetDetail("proximal_rounds"), 1.0);
}

// Josephy's NCP (MCPLIB "josephy"): nondegenerate solution (√6/2, 0, 0, 1/2).
TEST(NewtonSolverMcp, Josephy) {
  const FunctionMCP mcp = JosephyMcp();
  SemismoothNewtonSolver solver;
  const SolveResult r = solver.Solve(mcp);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  Vector expected(4);
  expected << std::sqrt(6.0) / 2, 0, 0, 0.5;
  EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-8);
}

// A nonlinear box MCP built from z*: F(z) = A z + c∘z³ + b with A nonsymmetric PD, c ≥ 0 (strongly monotone),
// b derived from a chosen F(z*) that is complementary to z* within mixed bounds. Dense and sparse Jacobians.
class CubicMcp final : public MCP {
 public:
  CubicMcp(const Known& k, Vector c, bool sparse_jacobian)
      : MCP(k.l, k.u, "cubic"), A_(k.M), A_sparse_(k.M.sparseView()), c_(std::move(c)), sparse_(sparse_jacobian) {
    // F(z*) = F* ⇒ b = F* − A z* − c∘z*³, where F* = M z* + q from the known LCP.
    b_ = (k.M * k.z_star + k.q) - A_ * k.z_star - (c_.array() * k.z_star.array().cube()).matrix();
  }
  void Evaluate(const Vector& z, Vector* F) const override {
    F->noalias() = A_ * z;
    F->array() += c_.array() * z.array().cube() + b_.array();
  }
  JacobianKind jacobian_kind() const override { return sparse_ ? JacobianKind::kSparse : JacobianKind::kDense; }
  void JacobianDense(const Vector& z, DenseMatrix* J) const override {
    *J = A_;
    J->diagonal().array() += 3.0 * c_.array() * z.array().square();
  }
  void JacobianSparse(const Vector& z, SparseMatrix* J) const override {
    *J = A_sparse_;  // A's pattern includes its (nonzero) diagonal
    for (int i = 0; i < size(); ++i) J->coeffRef(i, i) += 3.0 * c_[i] * z[i] * z[i];
  }

 private:
  DenseMatrix A_;
  SparseMatrix A_sparse_;
  Vector c_, b_;
  bool sparse_;
};

TEST(NewtonSolverMcp, ConstructedCubicMcpDenseAndSparse) {
  std::mt19937 rng(11);
  const std::vector<RowKind> kinds = {RowKind::kLower, RowKind::kBox, RowKind::kFree, RowKind::kUpper};
  const Known k = MakeKnown(RandomNonsymmetricPd(40, &rng), kinds, 0.2, &rng);
  const Vector c = Vector::Constant(40, 0.5);
  for (bool sparse : {false, true}) {
    for (NewtonOptions::LinearSolver linear_solver : {NewtonOptions::kDenseLinearSolver, NewtonOptions::kSparseLinearSolver}) {
      const CubicMcp mcp(k, c, sparse);
      NewtonOptions o;
      o.linear_solver = linear_solver;
      SemismoothNewtonSolver solver(o);
      const SolveResult r = solver.Solve(mcp);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      Vector F(40);
      mcp.Evaluate(r.z, &F);
      EXPECT_LE(NaturalResidualNorm(r.z, F, k.l, k.u), 1e-9);
      EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-7);
    }
  }
}

TEST(NewtonSolverMcp, RepeatedSolvesDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc is owned by the sanitizer runtime";
  std::mt19937 rng(14);
  const Known k = MakeKnown(RandomNonsymmetricPd(30, &rng), {RowKind::kLower, RowKind::kBox}, 0.2, &rng);
  const CubicMcp mcp(k, Vector::Constant(30, 0.3), /*sparse_jacobian=*/false);
  SemismoothNewtonSolver solver;
  SolveResult result;
  solver.Solve(mcp, SolverOptions{}, &result);
  ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
  test_support::StartCountingMallocs();
  for (int rep = 0; rep < 3; ++rep) solver.Solve(mcp, SolverOptions{}, &result);
  EXPECT_EQ(test_support::StopCountingMallocs(), 0);
  EXPECT_EQ(result.status, SolveStatus::kSolved);
}

TEST(NewtonSolverMcp, NanInFIsNumericalFailure) {
  // F is NaN everywhere.
  const FunctionMCP always_nan(
      Vector::Zero(2), Vector::Constant(2, kInf), [](const Vector&, Vector* F) { F->setConstant(std::nan("")); },
      [](const Vector&, DenseMatrix* J) { J->setIdentity(); }, "nan");
  SemismoothNewtonSolver solver;
  SolveResult r = solver.Solve(always_nan);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_FALSE(r.message.empty());
  // F finite at the start but NaN at every point the Newton step can reach (x ≠ 0).
  const FunctionMCP nan_away(
      Vector::Constant(1, -kInf), Vector::Constant(1, kInf),
      [](const Vector& x, Vector* F) { (*F)[0] = x[0] == 0.0 ? 1.0 : std::nan(""); },
      [](const Vector&, DenseMatrix* J) { (*J)(0, 0) = 1.0; }, "nan_away");
  r = solver.Solve(nan_away);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
}

// ---- MCPs whose F is huge at Π(0) but modest near the solution -------------------------------------------------
// A stopping test relative to 1 + ‖F(Π(0))‖∞ stopped such problems far from their solution and called it solved.
// Newton now stops on the base's scale-free residual: every "solved" must be the known solution.

// A Cobb–Douglas exchange economy (Scarf's general-equilibrium setting): household h owns e_h and spends the share
// α_hi of its income p·e_h on good i. F_i(p) = E_i − Σ_h α_hi (p·e_h)/p_i is excess supply, prices p_i ≥ 1e-8 (F is
// undefined at 0), good 0 the numéraire (l = u = 1). At Π(0) the demand for every other good is ~1e8 times its
// supply. The equilibrium solves the linear system p_i E_i = Σ_j B_ij p_j, B = Σ_h α_h e_hᵀ (computed here
// independently).
class CobbDouglasEconomy final : public MCP {
 public:
  CobbDouglasEconomy(DenseMatrix alpha, DenseMatrix endowment)
      : MCP(Bounds(endowment.cols(), true), Bounds(endowment.cols(), false), "cobb-douglas"),
        alpha_(std::move(alpha)), e_(std::move(endowment)), supply_(e_.colwise().sum().transpose()),
        income_(e_.rows()) {}
  void Evaluate(const Vector& p, Vector* F) const override {
    income_.noalias() = e_ * p;
    for (int i = 0; i < size(); ++i) (*F)[i] = supply_[i] - alpha_.col(i).dot(income_) / p[i];
  }
  void JacobianDense(const Vector& p, DenseMatrix* J) const override {
    income_.noalias() = e_ * p;
    for (int i = 0; i < size(); ++i) {
      for (int j = 0; j < size(); ++j) (*J)(i, j) = -alpha_.col(i).dot(e_.col(j)) / p[i];
      (*J)(i, i) += alpha_.col(i).dot(income_) / (p[i] * p[i]);
    }
  }
  // The equilibrium with p_0 = 1: rows 1..n−1 of (diag(E) − B) p = 0.
  Vector Equilibrium() const {
    const int n = size();
    const DenseMatrix B = alpha_.transpose() * e_;
    DenseMatrix A = -B;
    A.diagonal() += supply_;
    Vector p(n);
    p[0] = 1.0;
    p.tail(n - 1) = A.bottomRightCorner(n - 1, n - 1).fullPivLu().solve(-A.bottomLeftCorner(n - 1, 1));
    return p;
  }

 private:
  static Vector Bounds(Eigen::Index n, bool lower) {
    Vector b = Vector::Constant(n, lower ? 1e-8 : kInf);
    b[0] = 1.0;
    return b;
  }
  DenseMatrix alpha_, e_;
  Vector supply_;
  mutable Vector income_;  // workspace: F and J allocate nothing
};

CobbDouglasEconomy Economy() {
  DenseMatrix alpha(3, 4), e(3, 4);
  alpha << 0.1, 0.2, 0.3, 0.4,  //
      0.5, 0.3, 0.1, 0.1,        //
      0.05, 0.05, 0.1, 0.8;
  e << 2.0, 0.0, 30.0, 0.001,  //
      0.5, 40.0, 0.0, 0.0,      //
      0.0, 0.3, 1.0, 100.0;
  return CobbDouglasEconomy(alpha, e);
}

// Murphy–Sherali–Soyster (1982) Cournot–Nash oligopoly: inverse demand P(Q) = 5000^{1/γ} Q^{−1/γ}, firm i's cost
// c_i q + β_i/(β_i + 1) L_i^{1/β_i} q^{(β_i+1)/β_i}, outputs q_i ≥ 1e-8 (P is undefined at Q = 0). F_i is firm i's
// marginal profit with a minus sign: c_i + (L_i q_i)^{1/β_i} − P(Q) − q_i P'(Q). At Π(0), Q = n·1e-8 and P ~ 1e9.
class CournotGame final : public MCP {
 public:
  CournotGame(Vector c, Vector L, Vector beta, double gamma)
      : MCP(Vector::Constant(c.size(), 1e-8), Vector::Constant(c.size(), kInf), "cournot"), c_(std::move(c)),
        L_(std::move(L)), beta_(std::move(beta)), gamma_(gamma) {}
  void Evaluate(const Vector& q, Vector* F) const override {
    const double Q = q.sum(), P = Price(Q);
    for (int i = 0; i < size(); ++i) {
      (*F)[i] = c_[i] + std::pow(L_[i] * q[i], 1.0 / beta_[i]) - P + q[i] * P / (gamma_ * Q);
    }
  }
  void JacobianDense(const Vector& q, DenseMatrix* J) const override {
    const double Q = q.sum(), P = Price(Q);
    for (int i = 0; i < size(); ++i) {
      const double row = P / (gamma_ * Q) - q[i] * (1.0 + 1.0 / gamma_) * P / (gamma_ * Q * Q);
      J->row(i).setConstant(row);
      (*J)(i, i) += L_[i] * std::pow(L_[i] * q[i], 1.0 / beta_[i] - 1.0) / beta_[i] + P / (gamma_ * Q);
    }
  }
  // The equilibrium by nested bisection in long double: for a total Q each firm's condition is increasing in q_i
  // (its root, or the bound, is q_i(Q)), and Σ q_i(Q) − Q is decreasing in Q. Independent of any MCP solver.
  Vector Equilibrium() const {
    using Real = long double;
    const auto firm_output = [&](int i, Real Q) {
      const Real P = std::pow(Real(5000) / Q, 1 / Real(gamma_));
      const auto g = [&](Real q) { return c_[i] + std::pow(L_[i] * q, 1 / Real(beta_[i])) - P + q * P / (gamma_ * Q); };
      Real lo = 1e-8L, hi = gamma_ * Q;
      if (g(lo) >= 0) return lo;
      for (int k = 0; k < 100; ++k) (g((lo + hi) / 2) < 0 ? lo : hi) = (lo + hi) / 2;
      return (lo + hi) / 2;
    };
    const auto excess = [&](Real Q) {
      Real sum = 0;
      for (int i = 0; i < size(); ++i) sum += firm_output(i, Q);
      return sum - Q;
    };
    Real lo = 1e-6L, hi = 1e6L;
    for (int k = 0; k < 100; ++k) (excess(std::sqrt(lo * hi)) > 0 ? lo : hi) = std::sqrt(lo * hi);
    const Real Q = std::sqrt(lo * hi);
    Vector q(size());
    for (int i = 0; i < size(); ++i) q[i] = static_cast<double>(firm_output(i, Q));
    return q;
  }

 private:
  double Price(double Q) const { return std::pow(5000.0 / Q, 1.0 / gamma_); }
  Vector c_, L_, beta_;
  double gamma_;
};

CournotGame FiveFirms() {
  return CournotGame((Vector(5) << 10, 8, 6, 4, 2).finished(), Vector::Constant(5, 5.0),
                     (Vector(5) << 1.2, 1.1, 1.0, 0.9, 0.8).finished(), 1.1);
}

CournotGame TenFirms() {
  return CournotGame((Vector(10) << 5, 3, 8, 5, 1, 3, 7, 4, 6, 3).finished(), Vector::Constant(10, 10.0),
                     (Vector(10) << 1.2, 1, 0.9, 0.6, 1.5, 1, 0.7, 1.1, 0.95, 0.75).finished(), 1.1);
}

// Every start: solved to forward error ≤ 1e-8·max(1, ‖z*‖∞), or an honest non-solved status; never "solved" away
// from z*. Returns how many starts were solved.
int ExpectNeverSolvedFarAway(const MCP& mcp, const Vector& z_star, const std::vector<Vector>& starts) {
  int solved = 0;
  for (const Vector& start : starts) {
    SemismoothNewtonSolver solver;
    SolverOptions options;
    options.warm_start = start;
    const SolveResult r = solver.Solve(mcp, options);
    const Judgement j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, {}, false, r.status, r.z, options.tolerance);
    const double error = (r.z - z_star).cwiseAbs().maxCoeff();
    if (r.solved()) {
      ++solved;
      EXPECT_EQ(j.verdict, Verdict::kSolved) << mcp.name() << " from " << start.transpose();
      EXPECT_LE(error, 1e-8 * std::max(1.0, z_star.cwiseAbs().maxCoeff()))
          << mcp.name() << " from " << start.transpose() << ": residual_rel " << r.residual_rel << ", scaled "
          << r.residual_scaled;
    }
    EXPECT_EQ(r.residual_scaled, j.residual.scaled) << "the base and the verdict measure the same thing";
  }
  return solved;
}

TEST(NewtonSolverMcp, GeneralEquilibriumIsNeverSolvedFarFromItsPrices) {
  const CobbDouglasEconomy economy = Economy();
  const Vector p_star = economy.Equilibrium();
  ASSERT_TRUE((p_star.array() > 1e-3).all()) << p_star.transpose();
  Vector F(4);
  economy.Evaluate(p_star, &F);
  ASSERT_LE(F.cwiseAbs().maxCoeff(), 1e-10 * 150) << "the independent equilibrium solves the MCP";
  Vector cold(4);
  ProjectZeroOntoBox(economy.l(), economy.u(), &cold);
  economy.Evaluate(cold, &F);
  EXPECT_GT(F.cwiseAbs().maxCoeff(), 1e7) << "F at Π(0) is huge";
  const std::vector<Vector> starts = {cold, Vector::Ones(4), (Vector(4) << 1, 10, 0.1, 5).finished(),
                                      (Vector(4) << 1, 1e-3, 1e-3, 1e-3).finished()};
  EXPECT_GE(ExpectNeverSolvedFarAway(economy, p_star, starts), 3);
}

TEST(NewtonSolverMcp, CournotNashIsNeverSolvedFarFromItsEquilibrium) {
  const CournotGame five = FiveFirms();
  const Vector q5 = five.Equilibrium();
  // The published equilibrium (Murphy, Sherali, Soyster 1982; Harker 1988), 4 decimals.
  const Vector published = (Vector(5) << 15.4293, 12.4986, 9.6635, 7.1651, 5.1326).finished();
  EXPECT_LE((q5 - published).cwiseAbs().maxCoeff(), 1e-4) << q5.transpose();
  EXPECT_EQ(ExpectNeverSolvedFarAway(five, q5, {Vector::Constant(5, 1e-8), Vector::Ones(5), Vector::Constant(5, 10.0)}),
            3);
  const CournotGame ten = TenFirms();
  const Vector q10 = ten.Equilibrium();
  Vector F(10);
  ten.Evaluate(Vector::Constant(10, 1e-8), &F);
  EXPECT_GT(F.cwiseAbs().maxCoeff(), 1e8) << "F at Π(0) is huge";
  EXPECT_EQ(
      ExpectNeverSolvedFarAway(ten, q10, {Vector::Constant(10, 1e-8), Vector::Ones(10), Vector::Constant(10, 10.0)}),
      3);
}

// Newton stops on the base's own verdict: at its last iterate the base accepts, and one iteration less is an
// iteration limit whose best point the base does not accept (Newton did not run on past an acceptable point).
TEST(NewtonSolverMcp, StopsAtTheFirstIterateTheBaseAccepts) {
  const CournotGame ten = TenFirms();
  for (const Vector& start : std::vector<Vector>{Vector::Constant(10, 1e-8), Vector::Ones(10),
                                                 Vector::Constant(10, 10.0)}) {
    SemismoothNewtonSolver solver;
    SolverOptions options;
    options.warm_start = start;
    const SolveResult r = solver.Solve(ten, options);
    ASSERT_TRUE(r.solved()) << r.message;
    if (r.iterations < 2) continue;  // max_iterations = 0 means the default budget
    options.max_iterations = r.iterations - 1;
    const SolveResult shorter = solver.Solve(ten, options);
    EXPECT_EQ(shorter.status, SolveStatus::kIterationLimit) << shorter.message;
    EXPECT_GT(shorter.residual_scaled, options.tolerance);
  }
}

// ---- Small h: relay W = h·G with a planted s* -----------------------------------------------------------------
// The fixture (G, s*, the reference with μ) and the check are tests/support/small_h_relay.h.

TEST(NewtonSolver, SolvedWithWrongSAtSmallH) {
  // On relay problems W = h·G, a residual within tol·(1 + ‖q‖∞) alone passes |s − s*|∞ up to 0.2 as "solved"
  // at h = 1e-4 … 1e-8, since q = O(h); this pins the forward-error check.
  // Without the polish, Newton's own stopping test is in units of z, so it still solves within the allowance.
  SemismoothNewtonSolver solver;
  test_support::ExpectSolvedWithinAllowanceAtSmallH(solver);
}

}  // namespace
}  // namespace smcbench
