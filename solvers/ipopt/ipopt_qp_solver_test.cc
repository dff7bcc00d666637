// Tests of the Ipopt backend. Problems are generated with a known solution (z* first, then complementary w*, v*,
// then q = w* - v* - M z*), and every check recomputes the natural residual here instead of trusting the solver.
#include "solvers/ipopt/ipopt_qp_solver.h"

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/core/verdict.h"
#include "solvers/ipopt/ipopt_details.h"
#include "tests/support/small_h_relay.h"

namespace smcbench {
namespace {

constexpr double kTol = 1e-10;

// Relative natural residual of z, computed independently of the solver.
double Residual(const BoxMLCP& p, const Vector& z) {
  const Vector w = p.is_sparse() ? Vector(p.sparse_matrix() * z + p.q()) : Vector(p.dense_matrix() * z + p.q());
  double r = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    const double proj = std::min(std::max(z[i] - w[i], p.l()[i]), p.u()[i]);
    r = std::max(r, std::abs(z[i] - proj));
  }
  return r / (1.0 + p.q().cwiseAbs().maxCoeff());
}

// A row picks "at lower", "at upper" or "strictly between" among what its bounds allow; q follows from z*.
struct Generated {
  Vector q, z_star;
};

Generated MakeSolution(const DenseMatrix& M, const Vector& l, const Vector& u, std::mt19937* rng) {
  std::uniform_real_distribution<double> mult(0.5, 2.0), unit(0.0, 1.0), any(-2.0, 2.0);
  const int n = static_cast<int>(l.size());
  Generated g;
  g.z_star.resize(n);
  Vector w = Vector::Zero(n), v = Vector::Zero(n);
  for (int i = 0; i < n; ++i) {
    const bool lf = std::isfinite(l[i]), uf = std::isfinite(u[i]);
    if (l[i] == u[i]) {
      g.z_star[i] = l[i];
      (unit(*rng) < 0.5 ? w[i] : v[i]) = mult(*rng);
      continue;
    }
    const double pick = unit(*rng);
    if (lf && pick < 0.35) {
      g.z_star[i] = l[i];
      w[i] = mult(*rng);
    } else if (uf && pick > 0.65) {
      g.z_star[i] = u[i];
      v[i] = mult(*rng);
    } else if (lf && uf) {
      g.z_star[i] = l[i] + (0.1 + 0.8 * unit(*rng)) * (u[i] - l[i]);
    } else if (lf) {
      g.z_star[i] = l[i] + mult(*rng);
    } else if (uf) {
      g.z_star[i] = u[i] - mult(*rng);
    } else {
      g.z_star[i] = any(*rng);
    }
  }
  g.q = w - v - M * g.z_star;
  return g;
}

DenseMatrix RandomMatrix(int rows, int cols, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  DenseMatrix A(rows, cols);
  for (int j = 0; j < cols; ++j) {
    for (int i = 0; i < rows; ++i) A(i, j) = normal(*rng);
  }
  return A;
}

DenseMatrix Spd(int n, std::mt19937* rng) {
  const DenseMatrix B = RandomMatrix(n, n, rng);
  return B * B.transpose() / n + 0.5 * DenseMatrix::Identity(n, n);
}

// Upper triangular with positive diagonal after a symmetric permutation: every principal minor is a product of
// diagonal entries (a P-matrix), while the large off-diagonal entries make (M+M')/2 indefinite.
DenseMatrix NonsymmetricP(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> diag(1.0, 2.0), off(-3.0, 3.0);
  DenseMatrix T = DenseMatrix::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    T(i, i) = diag(*rng);
    for (int j = i + 1; j < n; ++j) T(i, j) = off(*rng);
  }
  Eigen::PermutationMatrix<Eigen::Dynamic> P(n);
  P.setIdentity();
  std::shuffle(P.indices().data(), P.indices().data() + n, *rng);
  return P * T * P.transpose();
}

bool IsPsd(const DenseMatrix& M) {
  const DenseMatrix S = 0.5 * (M + M.transpose());
  return Eigen::SelfAdjointEigenSolver<DenseMatrix>(S).eigenvalues().minCoeff() >= -1e-12;
}

TEST(IpoptQpSolverTest, InfoAndDefaults) {
  IpoptQpSolver solver;
  EXPECT_EQ(solver.info().name, "ipopt");
  EXPECT_TRUE(solver.info().dense);
  EXPECT_TRUE(solver.info().sparse);
  EXPECT_FALSE(solver.info().exact);
  std::string why;
  EXPECT_TRUE(solver.options().IsValid(&why)) << why;
}

// The codes print by name (what JSON and Python show), each value with its own name.
TEST(IpoptQpSolverTest, CodeDetailsPrintByName) {
  std::mt19937 rng(7);
  const DenseMatrix M = Spd(6, &rng);
  const Vector l = Vector::Zero(6), u = Vector::Constant(6, kInf);
  const Generated g = MakeSolution(M, l, u, &rng);
  IpoptQpSolver solver;
  const SolveResult r = solver.Solve(BoxMLCP(M, g.q, l, u));
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  bool found = false;
  for (int i = 0; i < r.num_details; ++i) {
    if (std::string_view(r.details[i].name) == "formulation") {
      EXPECT_EQ(SolveResult::CodeText(r.details[i]), "convex-qp");
      found = true;
    }
  }
  EXPECT_TRUE(found);
  std::set<std::string_view> names;
  for (int v = 0; v < 4; ++v) names.insert(ToString(static_cast<IpoptFormulation>(v)));
  for (int v = 0; v < 4; ++v) names.insert(ToString(static_cast<IpoptEarlyStop>(v)));
  EXPECT_EQ(names.size(), 7u);  // "none" is shared by the two codes' value 0
  std::set<std::string_view> mcp;
  for (int v = 0; v < 5; ++v) mcp.insert(ToString(static_cast<IpoptMcpEarlyStop>(v)));
  EXPECT_EQ(mcp.size(), 5u);
  EXPECT_EQ(ToString(IpoptOptions::kLimitedMemory), "limited-memory");
  EXPECT_FALSE(kIpoptFormulationDetail.FromNumber(4.0).has_value());
}

TEST(IpoptQpSolverTest, SpdLcpSolvedToTolAfterPolish) {
  IpoptQpSolver solver;
  for (int seed = 0; seed < 5; ++seed) {
    std::mt19937 rng(100 + seed);
    const int n = 5 + 7 * seed;
    const DenseMatrix M = Spd(n, &rng);
    const Vector l = Vector::Zero(n), u = Vector::Constant(n, kInf);
    const Generated g = MakeSolution(M, l, u, &rng);
    const BoxMLCP p(M, g.q, l, u, "spd_lcp");
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "seed " << seed << ": " << r.message;
    EXPECT_LE(Residual(p, r.z), kTol);
    EXPECT_LE((r.z - g.z_star).cwiseAbs().maxCoeff(), 1e-8);  // unique: M is positive definite
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kConvexQp);
    EXPECT_EQ(r.GetDetail("symmetric_psd"), 1.0);
    EXPECT_GT(r.iterations, 0);
    EXPECT_FALSE(std::isnan(r.GetDetail("ipopt_residual")));
  }
}

TEST(IpoptQpSolverTest, SpdRelaySolved) {
  IpoptQpSolver solver;
  for (int seed = 0; seed < 4; ++seed) {
    std::mt19937 rng(200 + seed);
    const int n = 8 + 10 * seed;
    const DenseMatrix M = Spd(n, &rng);
    const Vector l = Vector::Constant(n, -1.0), u = Vector::Constant(n, 1.0);
    const Generated g = MakeSolution(M, l, u, &rng);
    const BoxMLCP p = BoxMLCP::Relay(M, g.q);
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_LE(Residual(p, r.z), kTol);
    EXPECT_LE((r.z - g.z_star).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kConvexQp);
  }
}

TEST(IpoptQpSolverTest, PolishReportsBothResiduals) {
  std::mt19937 rng(7);
  const int n = 30;
  const DenseMatrix M = Spd(n, &rng);
  const Generated g = MakeSolution(M, Vector::Zero(n), Vector::Constant(n, kInf), &rng);
  const BoxMLCP p = BoxMLCP::LCP(M, g.q);

  IpoptQpSolver plain;
  plain.mutable_options().polish = false;
  plain.mutable_options().tol = 1e-6;  // a loose Ipopt tolerance: the interior-point point alone is not accurate
  SolverOptions strict;
  const SolveResult a = plain.Solve(p, strict);
  EXPECT_TRUE(std::isnan(a.GetDetail("polished_residual")));
  EXPECT_NEAR(a.residual_rel, Residual(p, a.z), 1e-14);

  IpoptQpSolver polished;
  polished.mutable_options().tol = 1e-6;
  polished.mutable_options().early_polish = false;
  const SolveResult b = polished.Solve(p, strict);
  ASSERT_EQ(b.status, SolveStatus::kSolved) << b.message;
  EXPECT_LE(Residual(p, b.z), kTol);
  EXPECT_GT(b.GetDetail("ipopt_residual"), kTol);
  EXPECT_LE(b.GetDetail("polished_residual"), kTol);
  EXPECT_EQ(b.GetDetail("polish_accepted"), 1.0);
}

TEST(IpoptQpSolverTest, PsdSingularLcpSolved) {
  IpoptQpSolver solver;
  for (int seed = 0; seed < 4; ++seed) {
    std::mt19937 rng(300 + seed);
    const int n = 12 + 6 * seed;
    const DenseMatrix B = RandomMatrix(n, n / 2, &rng);
    const DenseMatrix M = B * B.transpose();  // rank n/2: PSD, singular, solutions not unique
    const Vector l = Vector::Zero(n), u = Vector::Constant(n, kInf);
    const Generated g = MakeSolution(M, l, u, &rng);
    const BoxMLCP p(M, g.q, l, u);
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "seed " << seed << ": " << r.message;
    EXPECT_LE(Residual(p, r.z), kTol);
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kConvexQp);
    EXPECT_EQ(r.GetDetail("symmetric_psd"), 1.0);
  }
}

TEST(IpoptQpSolverTest, NonsymmetricPMatrixLcpViaGapFormulation) {
  IpoptQpSolver solver;
  for (int seed = 0; seed < 5; ++seed) {
    std::mt19937 rng(400 + seed);
    const int n = 4 + 4 * seed;
    const DenseMatrix M = NonsymmetricP(n, &rng);
    ASSERT_FALSE(IsPsd(M));
    const Vector l = Vector::Zero(n), u = Vector::Constant(n, kInf);
    const Generated g = MakeSolution(M, l, u, &rng);
    const BoxMLCP p(M, g.q, l, u);
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "seed " << seed << ": " << r.message;
    EXPECT_LE(Residual(p, r.z), kTol);
    EXPECT_LE((r.z - g.z_star).cwiseAbs().maxCoeff(), 1e-7);  // P-matrix: unique solution
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kGapNlp);
    EXPECT_EQ(r.GetDetail("symmetric_psd"), 0.0);
  }
}

TEST(IpoptQpSolverTest, NonsymmetricPMatrixRelayViaGapFormulation) {
  IpoptQpSolver solver;
  for (int seed = 0; seed < 4; ++seed) {
    std::mt19937 rng(500 + seed);
    const int n = 3 + 5 * seed;
    const DenseMatrix M = NonsymmetricP(n, &rng);
    const Vector l = Vector::Constant(n, -1.0), u = Vector::Constant(n, 1.0);
    const Generated g = MakeSolution(M, l, u, &rng);
    const BoxMLCP p(M, g.q, l, u);
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "seed " << seed << ": " << r.message;
    EXPECT_LE(Residual(p, r.z), kTol);
    EXPECT_LE((r.z - g.z_star).cwiseAbs().maxCoeff(), 1e-7);
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kGapNlp);
  }
}

TEST(IpoptQpSolverTest, GapFormulationForcedOnSpdProblem) {
  std::mt19937 rng(550);
  const int n = 15;
  const DenseMatrix M = Spd(n, &rng);
  const Vector l = Vector::Constant(n, -0.5), u = Vector::Constant(n, 2.0);
  const Generated g = MakeSolution(M, l, u, &rng);
  const BoxMLCP p(M, g.q, l, u);
  IpoptQpSolver solver;
  ASSERT_TRUE(solver.SetOption("formulation", "2", nullptr));
  const SolveResult r = solver.Solve(p);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(Residual(p, r.z), kTol);
  EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kGapNlp);
}

// Symmetric PSD but singular, and w1 + w2 = -2 < 0 for every z: no solution. The QP is unbounded below along
// z1 = z2 -> inf, where z - Pi(z - w) rounds to exactly 0 once |z| > 2^53: the backend must not call that solved.
TEST(IpoptQpSolverTest, LcpWithoutSolutionPsdIsNotSolved) {
  DenseMatrix M(2, 2);
  M << 1, -1, -1, 1;
  const BoxMLCP p = BoxMLCP::LCP(M, Vector::Constant(2, -1.0));
  IpoptQpSolver solver;
  SolverOptions options;
  options.max_iterations = 200;
  const SolveResult r = solver.Solve(p, options);
  EXPECT_NE(r.status, SolveStatus::kSolved);
  EXPECT_TRUE(r.status == SolveStatus::kDiverged || r.status == SolveStatus::kIterationLimit) << r.message;
  EXPECT_FALSE(r.message.empty());
  EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kConvexQp);
  // Where the residual is still meaningful it is large.
  if (r.z.cwiseAbs().maxCoeff() < 1e6) {
    EXPECT_GT(Residual(p, r.z), kTol);
  }
}

// w = -z - 1 < 0 for every z >= 0: the gap NLP's constraints are infeasible.
TEST(IpoptQpSolverTest, LcpWithoutSolutionNonPsdIsInfeasible) {
  DenseMatrix M(2, 2);
  M << -1, 0.5, 0.3, -1;
  const BoxMLCP p = BoxMLCP::LCP(M, Vector::Constant(2, -1.0));
  IpoptQpSolver solver;
  const SolveResult r = solver.Solve(p);
  EXPECT_NE(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  // Only with a certificate checked by the backend: a claim of no solution is a verdict too, and must be earned.
  EXPECT_NE(r.message.find("Farkas certificate"), std::string::npos) << r.message;
  EXPECT_GT(Residual(p, r.z), kTol);
  EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kGapNlp);
}

Vector MixedLower(int n) {
  Vector l(n);
  for (int i = 0; i < n; ++i) {
    switch (i % 5) {
      case 0: l[i] = 0.0; break;      // LCP row
      case 1: l[i] = -kInf; break;    // free row
      case 2: l[i] = -1.0; break;     // relay row
      case 3: l[i] = -kInf; break;    // upper bound only
      default: l[i] = 0.25; break;    // fixed row
    }
  }
  return l;
}

Vector MixedUpper(int n) {
  Vector u(n);
  for (int i = 0; i < n; ++i) {
    switch (i % 5) {
      case 0: u[i] = kInf; break;
      case 1: u[i] = kInf; break;
      case 2: u[i] = 1.0; break;
      case 3: u[i] = 3.0; break;
      default: u[i] = 0.25; break;
    }
  }
  return u;
}

TEST(IpoptQpSolverTest, MixedBoundsWithFreeRows) {
  IpoptQpSolver solver;
  for (int seed = 0; seed < 3; ++seed) {
    std::mt19937 rng(600 + seed);
    const int n = 10 + 10 * seed;
    const Vector l = MixedLower(n), u = MixedUpper(n);
    {
      const DenseMatrix M = Spd(n, &rng);
      const Generated g = MakeSolution(M, l, u, &rng);
      const BoxMLCP p(M, g.q, l, u);
      const SolveResult r = solver.Solve(p);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      EXPECT_LE(Residual(p, r.z), kTol);
      EXPECT_LE((r.z - g.z_star).cwiseAbs().maxCoeff(), 1e-8);
      EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kConvexQp);
    }
    {
      const DenseMatrix M = NonsymmetricP(n, &rng);
      const Generated g = MakeSolution(M, l, u, &rng);
      const BoxMLCP p(M, g.q, l, u);
      const SolveResult r = solver.Solve(p);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      EXPECT_LE(Residual(p, r.z), kTol);
      EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kGapNlp);
    }
  }
}

TEST(IpoptQpSolverTest, SparseProblems) {
  IpoptQpSolver solver;
  const int n = 60;
  std::mt19937 rng(700);
  // Tridiagonal SPD (1-D Laplacian + shift), and the same with a nonsymmetric, non-PSD upwind coupling.
  for (int variant = 0; variant < 2; ++variant) {
    std::vector<Eigen::Triplet<double, int>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, 2.5);
      if (i > 0) t.emplace_back(i, i - 1, variant == 0 ? -1.0 : -2.4);
      if (i + 1 < n) t.emplace_back(i, i + 1, variant == 0 ? -1.0 : 0.1);
    }
    SparseMatrix M(n, n);
    M.setFromTriplets(t.begin(), t.end());
    const Vector l = MixedLower(n), u = MixedUpper(n);
    const Generated g = MakeSolution(DenseMatrix(M), l, u, &rng);
    const BoxMLCP p(M, g.q, l, u);
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "variant " << variant << ": " << r.message;
    EXPECT_LE(Residual(p, r.z), kTol);
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), variant == 0 ? IpoptFormulation::kConvexQp : IpoptFormulation::kGapNlp);
  }
}

// The backend receives the row-equilibrated problem D⁻¹M (Solver's base), which is not symmetric even for a
// symmetric M, and a user may scale rows too (R M). Both are symmetric up to a positive row scaling, which keeps
// the solutions: the convex QP must still be chosen (not the nonconvex gap program), dense and sparse.
TEST(IpoptQpSolverTest, RowScaledSymmetricProblemKeepsTheConvexQp) {
  std::mt19937 rng(760);
  std::uniform_real_distribution<double> exponent(-4.0, 4.0);
  for (int variant = 0; variant < 2; ++variant) {
    const int n = 12;
    const DenseMatrix M = Spd(n, &rng);
    const Vector l = MixedLower(n), u = MixedUpper(n);
    const Generated g = MakeSolution(M, l, u, &rng);
    Vector factors(n);
    for (int i = 0; i < n; ++i) factors[i] = std::pow(10.0, exponent(rng));
    const DenseMatrix RM = factors.asDiagonal() * M;
    const Vector Rq = factors.cwiseProduct(g.q);
    const BoxMLCP p = variant == 0 ? BoxMLCP(RM, Rq, l, u) : BoxMLCP(SparseMatrix(RM.sparseView()), Rq, l, u);
    IpoptQpSolver solver;
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << (variant == 0 ? "dense: " : "sparse: ") << r.message;
    EXPECT_LE((r.z - g.z_star).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kConvexQp);
    EXPECT_EQ(r.GetDetail("symmetric_psd"), 1.0);
  }
  // A sign pattern no positive row scaling can symmetrize (M_01 > 0 > M_10) stays with the gap program.
  DenseMatrix skew(2, 2);
  skew << 2.0, 1.0, -1.0, 2.0;
  const BoxMLCP p = BoxMLCP::LCP(skew, Vector::Constant(2, -1.0));
  const SolveResult r = IpoptQpSolver().Solve(p);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kGapNlp);
}

// Block diagonal with [1 -1; -1 1] blocks plus a rank-one coupling: PSD and singular, so the polish meets
// singular free blocks (SparseLU fails, SparseQR takes over).
TEST(IpoptQpSolverTest, SparsePsdSingular) {
  const int n = 40;
  std::mt19937 rng(750);
  std::vector<Eigen::Triplet<double, int>> t;
  for (int b = 0; b + 1 < n; b += 2) {
    t.emplace_back(b, b, 1.0);
    t.emplace_back(b + 1, b + 1, 1.0);
    t.emplace_back(b, b + 1, -1.0);
    t.emplace_back(b + 1, b, -1.0);
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(t.begin(), t.end());
  for (int variant = 0; variant < 2; ++variant) {
    const Vector l = variant == 0 ? Vector::Zero(n) : Vector::Constant(n, -1.0);
    const Vector u = variant == 0 ? Vector::Constant(n, kInf) : Vector::Constant(n, 1.0);
    const Generated g = MakeSolution(DenseMatrix(M), l, u, &rng);
    const BoxMLCP p(M, g.q, l, u);
    IpoptQpSolver solver;
    const SolveResult r = solver.Solve(p);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "variant " << variant << ": " << r.message;
    EXPECT_LE(Residual(p, r.z), kTol);
    EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kConvexQp);
  }
}

TEST(IpoptQpSolverTest, InvalidOptions) {
  std::mt19937 rng(800);
  const DenseMatrix M = Spd(4, &rng);
  const BoxMLCP p = BoxMLCP::LCP(M, Vector::Constant(4, -1.0));
  IpoptQpSolver solver;
  std::string error;
  EXPECT_FALSE(solver.SetOption("tol", "-1", &error));
  EXPECT_NE(error.find("tol"), std::string::npos);
  EXPECT_FALSE(solver.SetOption("no_such_option", "1", &error));
  EXPECT_FALSE(solver.SetOption("mu_strategy", "7", &error));
  // Rejected values are not kept.
  EXPECT_EQ(solver.options().tol, IpoptOptions().tol);
  EXPECT_EQ(solver.options().mu_strategy, IpoptOptions().mu_strategy);
  SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;

  solver.set_options(IpoptOptions());
  solver.mutable_options().psd_tolerance = -1.0;
  r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("psd_tolerance"), std::string::npos);
  solver.set_options(IpoptOptions());
  solver.mutable_options().linear_solver = static_cast<IpoptOptions::LinearSolver>(42);
  r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  solver.mutable_options().formulation = static_cast<IpoptOptions::Formulation>(5);
  EXPECT_EQ(solver.Solve(p).status, SolveStatus::kInvalidOptions);

  // A valid code for a linear solver this Ipopt cannot load (HSL is not in Debian) is a status, not a crash.
  solver.set_options(IpoptOptions());
  solver.mutable_options().linear_solver = IpoptOptions::kMa27;
  r = solver.Solve(p);
  if (r.status != SolveStatus::kSolved) {
    EXPECT_EQ(r.status, SolveStatus::kInvalidOptions) << r.message;
    EXPECT_NE(r.message.find("libhsl.so"), std::string::npos) << r.message;
  }

  // The instance is usable again once the options are fixed.
  solver.set_options(IpoptOptions());
  r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;
}

TEST(IpoptQpSolverTest, RepeatedSolvesOnOneInstance) {
  IpoptQpSolver solver;
  std::mt19937 rng(900);
  std::vector<BoxMLCP> problems;
  for (int k = 0; k < 6; ++k) {
    const int n = 6 + 3 * (k % 3);
    const DenseMatrix M = (k % 2 == 0) ? Spd(n, &rng) : NonsymmetricP(n, &rng);
    const Vector l = Vector::Constant(n, -1.0), u = Vector::Constant(n, 1.0);
    const Generated g = MakeSolution(M, l, u, &rng);
    problems.emplace_back(M, g.q, l, u);
  }
  SolveResult r;
  for (int pass = 0; pass < 3; ++pass) {
    for (const BoxMLCP& p : problems) {
      solver.Solve(p, SolverOptions(), &r);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      EXPECT_LE(Residual(p, r.z), kTol);
    }
  }
}

TEST(IpoptQpSolverTest, WarmStartFromSolutionNeedsNoIterations) {
  std::mt19937 rng(1000);
  const int n = 12;
  const DenseMatrix M = Spd(n, &rng);
  const Generated g = MakeSolution(M, Vector::Zero(n), Vector::Constant(n, kInf), &rng);
  const BoxMLCP p = BoxMLCP::LCP(M, g.q);
  IpoptQpSolver solver;
  const SolveResult cold = solver.Solve(p);
  ASSERT_EQ(cold.status, SolveStatus::kSolved) << cold.message;
  SolverOptions warm;
  warm.warm_start = cold.z;
  const SolveResult again = solver.Solve(p, warm);
  EXPECT_EQ(again.status, SolveStatus::kSolved);
  EXPECT_EQ(again.iterations, 0);
  EXPECT_LE(Residual(p, again.z), kTol);

  // A nearby warm start still converges (Ipopt pushes it into the interior), and with the warm-start polish
  // a slightly perturbed problem is solved without Ipopt.
  warm.warm_start = cold.z + Vector::Constant(n, 1e-3);
  const SolveResult near = solver.Solve(p, warm);
  EXPECT_EQ(near.status, SolveStatus::kSolved) << near.message;
  solver.mutable_options().polish_warm_start = true;
  const SolveResult polished = solver.Solve(p, warm);
  EXPECT_EQ(polished.status, SolveStatus::kSolved) << polished.message;
  EXPECT_EQ(polished.iterations, 0);
  EXPECT_EQ(kIpoptEarlyStopDetail.Get(polished), IpoptEarlyStop::kWarmPolish);
}

TEST(IpoptQpSolverTest, LimitsAreStatuses) {
  std::mt19937 rng(1100);
  const int n = 25;
  const DenseMatrix M = NonsymmetricP(n, &rng);
  const Generated g = MakeSolution(M, Vector::Zero(n), Vector::Constant(n, kInf), &rng);
  const BoxMLCP p = BoxMLCP::LCP(M, g.q);
  IpoptQpSolver solver;
  solver.mutable_options().polish = false;
  SolverOptions options;
  options.max_iterations = 1;
  SolveResult r = solver.Solve(p, options);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_EQ(r.GetDetail("ipopt_status"), -1.0);  // Maximum_Iterations_Exceeded

  options.max_iterations = 0;
  options.time_limit_seconds = 1e-9;
  r = solver.Solve(p, options);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit) << r.message;
}

TEST(IpoptQpSolverTest, SilentUnlessVerbose) {
  std::mt19937 rng(1200);
  const int n = 10;
  const DenseMatrix M = NonsymmetricP(n, &rng);
  const Generated g = MakeSolution(M, Vector::Zero(n), Vector::Constant(n, kInf), &rng);
  const BoxMLCP p = BoxMLCP::LCP(M, g.q);
  IpoptQpSolver solver;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const SolveResult r = solver.Solve(p);
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");

  SolverOptions verbose;
  verbose.verbosity = 1;
  testing::internal::CaptureStderr();
  solver.Solve(p, verbose);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("ipopt:"), std::string::npos);
  // Back to silence on the same instance.
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  solver.Solve(p);
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(IpoptQpSolverTest, ForcedQpOnSymmetricIndefiniteRelay) {
  // On a bounded box a symmetric indefinite QP has a minimizer, and any KKT point solves the MLCP.
  std::mt19937 rng(1300);
  const int n = 10;
  DenseMatrix M = RandomMatrix(n, n, &rng);
  M = (0.5 * (M + M.transpose())).eval();
  ASSERT_FALSE(IsPsd(M));
  const BoxMLCP p = BoxMLCP::Relay(M, RandomMatrix(n, 1, &rng).col(0));
  IpoptQpSolver solver;
  solver.mutable_options().formulation = IpoptOptions::kQp;
  const SolveResult r = solver.Solve(p);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(Residual(p, r.z), kTol);
  EXPECT_EQ(kIpoptFormulationDetail.Get(r), IpoptFormulation::kForcedQp);

  // formulation=qp is refused for nonsymmetric M.
  const BoxMLCP q = BoxMLCP::LCP(NonsymmetricP(4, &rng), Vector::Constant(4, -1.0));
  EXPECT_EQ(solver.Solve(q).status, SolveStatus::kNotApplicable);
}

// Found by solver_option_fuzzer: linear_solver = 5 (ma97) without libhsl.so made Ipopt 3.11 call exit() from its
// MA97 interface, ending the whole program. Every HSL/Pardiso code is now checked for its library first.
TEST(IpoptFuzzRegression, Ma97WithoutHslIsAnInvalidOptionNotAProcessExit) {
  if (void* hsl = ::dlopen("libhsl.so", RTLD_LAZY | RTLD_LOCAL)) {
    ::dlclose(hsl);
    GTEST_SKIP() << "libhsl.so is installed here: ma97 is a real choice";
  }
  IpoptQpSolver solver;
  std::string error;
  EXPECT_FALSE(solver.SetOption("linear_solver", "5", &error));
  EXPECT_NE(error.find("libhsl.so"), std::string::npos) << error;
  solver.mutable_options().linear_solver = IpoptOptions::kMa97;  // set directly: Solve must still refuse it
  const BoxMLCP p = BoxMLCP::LCP((DenseMatrix(2, 2) << 2, 1, 1, 2).finished(), (Vector(2) << -1, -1).finished());
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("ma97"), std::string::npos) << r.message;
}

// ---- Small h: relay W = h·G with a planted s* -----------------------------------------------------------------
// The fixture (G, s*, the reference with μ) and the check are tests/support/small_h_relay.h.

TEST(IpoptQpSolverTest, SolvedWithWrongSAtSmallH) {
  // On relay problems W = h·G, a residual within tol·(1 + ‖q‖∞) alone passes |s − s*|∞ up to 0.2 as "solved"
  // at h = 1e-4 … 1e-8, since q = O(h); this pins the forward-error check.
  // Without the base's polish, Ipopt's own active-set polish stays on and ends within the allowance.
  IpoptQpSolver solver;
  test_support::ExpectSolvedWithinAllowanceAtSmallH(solver);
}

}  // namespace
}  // namespace smcbench
