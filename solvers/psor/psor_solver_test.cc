// Tests of the PSOR backend. Problems are feasible by construction (pick z*, a complementary w − v, derive q);
// success is judged by a natural residual recomputed here, never by the solver's status alone.
#include "solvers/psor/psor_solver.h"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "solvers/core/verdict.h"
#include "tests/support/malloc_counter.h"
#include "tests/support/small_h_relay.h"

namespace smcbench {
namespace {

// True if text contains part; prints the text otherwise.
::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

// Relative natural residual ‖z − Π(z − (Mz+q))‖∞ / (1 + ‖q‖∞), computed independently of the library.
double MyResidual(const BoxMLCP& p, const Vector& z) {
  const DenseMatrix M = p.ToDense();
  const Vector w = M * z + p.q();
  double r = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    const double proj = std::min(std::max(z[i] - w[i], p.l()[i]), p.u()[i]);
    const double e = std::abs(z[i] - proj);
    if (!std::isfinite(e)) return kInf;
    r = std::max(r, e);
  }
  return r / (1.0 + p.q().cwiseAbs().maxCoeff());
}

// Symmetric positive definite: B Bᵀ / n + shift·I.
DenseMatrix RandomSpd(int n, std::mt19937_64& rng, double shift = 0.5) {
  std::normal_distribution<double> normal;
  DenseMatrix B(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) B(i, j) = normal(rng);
  DenseMatrix M = B * B.transpose() / n;
  M.diagonal().array() += shift;
  return M;
}

// Picks z* in [l,u] (at a finite lower bound, at a finite upper bound, or strictly inside) and a complementary
// residual r = w − v: r > 0 at l, r < 0 at u, r = 0 inside. Then q = r − M z*.
void PlantSolution(const DenseMatrix& M, const Vector& l, const Vector& u, std::mt19937_64& rng, Vector* zstar,
                   Vector* q) {
  const int n = static_cast<int>(l.size());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 2);
  Vector r(n);
  zstar->resize(n);
  for (int i = 0; i < n; ++i) {
    int kind = pick(rng);
    if (kind == 0 && !std::isfinite(l[i])) kind = 2;
    if (kind == 1 && !std::isfinite(u[i])) kind = 2;
    if (kind == 0) {
      (*zstar)[i] = l[i];
      r[i] = 0.1 + unit(rng);
    } else if (kind == 1) {
      (*zstar)[i] = u[i];
      r[i] = -0.1 - unit(rng);
    } else {
      const double lo = std::isfinite(l[i]) ? l[i] : -2.0;
      const double hi = std::isfinite(u[i]) ? u[i] : lo + 4.0;
      (*zstar)[i] = lo + (0.1 + 0.8 * unit(rng)) * (hi - lo);
      r[i] = 0.0;
    }
  }
  *q = r - M * (*zstar);
}

struct Planted {
  BoxMLCP problem;
  Vector zstar;
};

Planted SpdLcp(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  DenseMatrix M = RandomSpd(n, rng);
  const Vector l = Vector::Zero(n), u = Vector::Constant(n, kInf);
  Vector zstar, q;
  PlantSolution(M, l, u, rng, &zstar, &q);
  return {BoxMLCP::LCP(std::move(M), std::move(q), "spd_lcp"), zstar};
}

Planted SpdRelay(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  DenseMatrix M = RandomSpd(n, rng);
  const Vector l = Vector::Constant(n, -1.0), u = Vector::Constant(n, 1.0);
  Vector zstar, q;
  PlantSolution(M, l, u, rng, &zstar, &q);
  return {BoxMLCP::Relay(std::move(M), std::move(q), -1.0, 1.0, "spd_relay"), zstar};
}

// Sparse banded SPD (strictly diagonally dominant) with mixed rows: LCP, relay, free and half-bounded.
struct SparseDensePair {
  BoxMLCP sparse;
  BoxMLCP dense;
  Vector zstar;
};

SparseDensePair BandedMixed(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> off(-1.0, 1.0);
  DenseMatrix M = DenseMatrix::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int k = 1; k <= 3 && i + k < n; ++k) {
      const double v = off(rng);
      M(i, i + k) = v;
      M(i + k, i) = v;
    }
  }
  for (int i = 0; i < n; ++i) M(i, i) = M.row(i).cwiseAbs().sum() + 0.5;
  Vector l(n), u(n);
  for (int i = 0; i < n; ++i) {
    switch (i % 4) {
      case 0: l[i] = 0.0, u[i] = kInf; break;
      case 1: l[i] = -1.0, u[i] = 1.0; break;
      case 2: l[i] = -kInf, u[i] = kInf; break;
      default: l[i] = -kInf, u[i] = 2.0; break;
    }
  }
  Vector zstar, q;
  PlantSolution(M, l, u, rng, &zstar, &q);
  SparseMatrix S = M.sparseView();
  return {BoxMLCP(std::move(S), q, l, u, "banded_sparse"), BoxMLCP(M, q, l, u, "banded_dense"), zstar};
}

SolverOptions Tight() {
  SolverOptions o;
  o.tolerance = 1e-10;
  return o;
}

// ---- Correctness on the convergence classes of CPS §5.2 ------------------------------------------------------

TEST(PsorSolver, InfoDescribesAnIterativeDenseAndSparseBackend) {
  PsorSolver solver;
  EXPECT_EQ(solver.info().name, "psor");
  EXPECT_TRUE(solver.info().dense);
  EXPECT_TRUE(solver.info().sparse);
  EXPECT_FALSE(solver.info().exact);
  EXPECT_FALSE(solver.info().symmetric_only);
}

TEST(PsorSolver, OptionsChangedBetweenSolvesAreValidatedAgain) {
  // ValidateBackendOptions remembers the last valid value; a changed one is checked afresh, whichever way it came.
  const Planted p = SpdLcp(2, 5);
  PsorSolver solver;
  SolveResult r;
  solver.Solve(p.problem, Tight(), &r);
  ASSERT_TRUE(r.solved()) << r.message;
  PsorOptions o = solver.options();
  o.omega = 2.5;
  solver.set_options(o);
  solver.Solve(p.problem, Tight(), &r);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("omega"), std::string::npos) << r.message;
  o.omega = 1.0;
  solver.set_options(o);
  solver.Solve(p.problem, Tight(), &r);
  EXPECT_TRUE(r.solved()) << r.message;
  o.stall_factor = std::nan("");
  solver.set_options(o);
  solver.Solve(p.problem, Tight(), &r);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
}

TEST(PsorSolver, SolvesRandomSpdLcpOfEverySize) {
  // 1..4 run the fixed-size kernels, the rest the dynamic one.
  for (int n : {1, 2, 3, 4, 5, 16, 64, 200}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      SCOPED_TRACE("n=" + std::to_string(n) + " seed=" + std::to_string(seed));
      const Planted p = SpdLcp(n, 100 * n + seed);
      PsorSolver solver;
      const SolveResult r = solver.Solve(p.problem, Tight());
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      EXPECT_LE(MyResidual(p.problem, r.z), 1e-10);
      EXPECT_NEAR(r.residual_rel, MyResidual(p.problem, r.z), 1e-13);
      // SPD ⇒ unique solution; the error is bounded by ‖M⁻¹‖·residual, and λ_min(M) ≥ 0.5 here.
      EXPECT_LE((r.z - p.zstar).lpNorm<Eigen::Infinity>(), 1e-7 * (1.0 + p.zstar.lpNorm<Eigen::Infinity>()));
      // Zero sweeps only when the cold start Π(0) = 0 already solves it.
      if (MyResidual(p.problem, Vector::Zero(n)) > 1e-10) {
        EXPECT_GE(r.iterations, 1);
      }
      for (int i = 0; i < n; ++i) EXPECT_GE(r.z[i], 0.0);
    }
  }
}

TEST(PsorSolver, SolvesRandomSpdRelay) {
  for (int n : {2, 4, 16, 50}) {
    SCOPED_TRACE("n=" + std::to_string(n));
    const Planted p = SpdRelay(n, 7 + n);
    PsorSolver solver;
    const SolveResult r = solver.Solve(p.problem, Tight());
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_LE(MyResidual(p.problem, r.z), 1e-10);
    EXPECT_LE((r.z - p.zstar).lpNorm<Eigen::Infinity>(), 1e-7);
    EXPECT_LE(r.z.maxCoeff(), 1.0);
    EXPECT_GE(r.z.minCoeff(), -1.0);
  }
}

TEST(PsorSolver, SparseAndDenseGiveTheSameSolution) {
  const SparseDensePair p = BandedMixed(120, 42);
  ASSERT_TRUE(p.sparse.is_sparse());
  PsorSolver sparse_solver, dense_solver;
  const SolveResult rs = sparse_solver.Solve(p.sparse, Tight());
  const SolveResult rd = dense_solver.Solve(p.dense, Tight());
  ASSERT_EQ(rs.status, SolveStatus::kSolved) << rs.message;
  ASSERT_EQ(rd.status, SolveStatus::kSolved) << rd.message;
  EXPECT_LE(MyResidual(p.sparse, rs.z), 1e-10);
  EXPECT_LE(MyResidual(p.dense, rd.z), 1e-10);
  // Same sweep order and the same floating-point updates (dense adds exact zeros): equal up to rounding.
  EXPECT_LE((rs.z - rd.z).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_LE(std::abs(rs.iterations - rd.iterations), 1);
  EXPECT_LE((rs.z - p.zstar).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(PsorSolver, ConvergesForOmegaAcrossTheInterval) {
  const Planted p = SpdLcp(30, 5);
  int gauss_seidel_sweeps = 0;
  for (double omega : {0.3, 0.8, 1.0, 1.2, 1.5, 1.9}) {
    SCOPED_TRACE("omega=" + std::to_string(omega));
    PsorOptions o;
    o.omega = omega;
    PsorSolver solver(o);
    const SolveResult r = solver.Solve(p.problem, Tight());
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_LE(MyResidual(p.problem, r.z), 1e-10);
    EXPECT_LE((r.z - p.zstar).lpNorm<Eigen::Infinity>(), 1e-7);
    if (omega == 1.0) gauss_seidel_sweeps = r.iterations;
  }
  EXPECT_GT(gauss_seidel_sweeps, 0);
}

TEST(PsorSolver, OmegaSetFromTextIsUsed) {
  const Planted p = SpdRelay(20, 9);
  PsorSolver solver;
  std::string error;
  ASSERT_TRUE(solver.SetOption("omega", "1.4", &error)) << error;
  EXPECT_DOUBLE_EQ(solver.options().omega, 1.4);
  const SolveResult r = solver.Solve(p.problem, Tight());
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(MyResidual(p.problem, r.z), 1e-10);
  const SolveResult gauss_seidel = PsorSolver().Solve(p.problem, Tight());
  ASSERT_EQ(gauss_seidel.status, SolveStatus::kSolved) << gauss_seidel.message;
  EXPECT_NE(r.GetDetail("column_updates"), gauss_seidel.GetDetail("column_updates"));  // omega was used
}

// ---- Sweep order ------------------------------------------------------------------------------------------------

PsorSolver SweepingIn(PsorOptions::SweepOrder order) {
  PsorOptions o;
  o.sweep = order;
  return PsorSolver(o);
}

// Triangular M (upper or lower) with a positive diagonal, a mixed box (LCP, relay, free and half-bounded rows)
// and its one solution by substitution, computed here: z_i = Π_[l_i,u_i](−(q_i + Σ_{j≠i} M_ij z_j) / M_ii) in
// the order in which the z_j it needs are known.
struct Triangular {
  BoxMLCP problem;
  Vector z;
};

Triangular TriangularMixed(int n, bool upper) {
  DenseMatrix M = DenseMatrix::Zero(n, n);
  Vector q(n), l(n), u(n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0 + 0.1 * i;
    for (int j = 0; j < n; ++j) {
      if (upper ? j > i : j < i) M(i, j) = std::sin(1.0 + i * n + j);
    }
    q[i] = 2.0 * std::cos(3.0 * i);
    l[i] = i % 4 == 2 ? -kInf : (i % 4 == 1 ? -0.5 : 0.0);
    u[i] = i % 4 == 1 ? 0.5 : (i % 4 == 3 ? 1.0 : kInf);
  }
  Vector z = Vector::Zero(n);
  for (int k = 0; k < n; ++k) {
    const int i = upper ? n - 1 - k : k;
    const double free_value = -(q[i] + M.row(i).dot(z)) / M(i, i);  // z_i is still 0 here
    z[i] = std::min(std::max(free_value, l[i]), u[i]);
  }
  return {BoxMLCP(std::move(M), std::move(q), std::move(l), std::move(u), upper ? "upper" : "lower"), z};
}

// Upper triangular M: one backward sweep is the back substitution (solved after at most two sweeps, the second
// confirming), where the forward sweep needs about one sweep per row.
TEST(PsorSolver, BackwardSweepIsTheBackSubstitutionOnUpperTriangularM) {
  const Triangular t = TriangularMixed(20, /*upper=*/true);
  const SolveResult backward = SweepingIn(PsorOptions::kBackwardSweep).Solve(t.problem, Tight());
  ASSERT_EQ(backward.status, SolveStatus::kSolved) << backward.message;
  EXPECT_LE((backward.z - t.z).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + t.z.cwiseAbs().maxCoeff()));
  EXPECT_LE(backward.iterations, 2);
  const SolveResult forward = PsorSolver().Solve(t.problem, Tight());
  ASSERT_EQ(forward.status, SolveStatus::kSolved) << forward.message;
  EXPECT_LE((forward.z - t.z).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + t.z.cwiseAbs().maxCoeff()));
  EXPECT_GT(forward.iterations, backward.iterations);
}

// Lower triangular M: the forward sweep is the substitution; backward and symmetric sweeps reach the same one
// solution (the row order changes the path, not the answer). Murty's LCP (1 on the diagonal, 2 below, z* = 2ⁿe₁)
// and the mixed box.
TEST(PsorSolver, EverySweepOrderSolvesLowerTriangularM) {
  const int n = 12;
  DenseMatrix M = DenseMatrix::Zero(n, n);
  Vector q(n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    for (int j = 0; j < i; ++j) M(i, j) = 2.0;
    q[i] = -(2.0 * std::ldexp(1.0, n) - std::ldexp(1.0, n - i));
  }
  const BoxMLCP murty = BoxMLCP::LCP(std::move(M), std::move(q), "murty12");
  Vector murty_z = Vector::Zero(n);
  murty_z[0] = std::ldexp(1.0, n);
  const Triangular mixed = TriangularMixed(20, /*upper=*/false);
  for (const auto order : {PsorOptions::kForwardSweep, PsorOptions::kBackwardSweep, PsorOptions::kSymmetricSweep}) {
    SCOPED_TRACE("sweep " + std::to_string(static_cast<int>(order)));
    const SolveResult r = SweepingIn(order).Solve(murty, Tight());
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_LE((r.z - murty_z).cwiseAbs().maxCoeff(), 1e-10 * murty_z[0]);
    const SolveResult rm = SweepingIn(order).Solve(mixed.problem, Tight());
    ASSERT_EQ(rm.status, SolveStatus::kSolved) << rm.message;
    EXPECT_LE((rm.z - mixed.z).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + mixed.z.cwiseAbs().maxCoeff()));
    if (order != PsorOptions::kBackwardSweep) {
      EXPECT_LE(r.iterations, 2);
    }
  }
}

// Symmetric positive definite M (dense LCP and relay, sparse and dense banded mixed box): the symmetric sweep
// (projected SSOR) and the backward sweep converge to the planted solution, as the forward one does, also with
// over-relaxation.
TEST(PsorSolver, SymmetricAndBackwardSweepsSolveSpdProblems) {
  const Planted lcp = SpdLcp(30, 5);
  const Planted relay = SpdRelay(20, 9);
  const SparseDensePair banded = BandedMixed(120, 42);
  const struct {
    const BoxMLCP* problem;
    const Vector* zstar;
  } cases[] = {{&lcp.problem, &lcp.zstar}, {&relay.problem, &relay.zstar}, {&banded.sparse, &banded.zstar},
               {&banded.dense, &banded.zstar}};
  for (const auto order : {PsorOptions::kBackwardSweep, PsorOptions::kSymmetricSweep}) {
    for (const double omega : {1.0, 1.4}) {
      for (const auto& c : cases) {
        SCOPED_TRACE(c.problem->name() + " sweep " + std::to_string(static_cast<int>(order)) + " omega " +
                     std::to_string(omega));
        PsorOptions o;
        o.sweep = order;
        o.omega = omega;
        const SolveResult r = PsorSolver(o).Solve(*c.problem, Tight());
        ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
        EXPECT_LE(MyResidual(*c.problem, r.z), 1e-10);
        EXPECT_LE((r.z - *c.zstar).lpNorm<Eigen::Infinity>(), 1e-7 * (1.0 + c.zstar->lpNorm<Eigen::Infinity>()));
      }
    }
  }
}

TEST(PsorSolver, SweepIsSetByNameAndListed) {
  PsorSolver solver;
  std::string error;
  ASSERT_TRUE(solver.SetOption("sweep", "backward", &error)) << error;
  EXPECT_EQ(solver.options().sweep, PsorOptions::kBackwardSweep);
  ASSERT_TRUE(solver.SetOption("sweep", "symmetric", &error)) << error;
  EXPECT_EQ(solver.options().sweep, PsorOptions::kSymmetricSweep);
  EXPECT_FALSE(solver.SetOption("sweep", "sideways", &error));
  EXPECT_TRUE(Contains(error, "sweep"));
  EXPECT_TRUE(Contains(error, "forward"));
  EXPECT_TRUE(Contains(PsorSolver().OptionsHelp(), "sweep"));
  EXPECT_TRUE(Contains(PsorSolver().OptionsHelp(), "forward"));
}

TEST(PsorSolver, CheckIntervalAndRefreshIntervalDoNotChangeTheAnswer) {
  const Planted p = SpdLcp(40, 77);
  PsorOptions o;
  o.check_interval = 7;
  o.refresh_interval = 1;
  PsorSolver solver(o);
  const SolveResult r = solver.Solve(p.problem, Tight());
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(MyResidual(p.problem, r.z), 1e-10);
  EXPECT_EQ(r.iterations % 7, 0);  // success is only seen at a check
  EXPECT_GE(r.GetDetail("w_refreshes"), r.iterations);  // refreshed after every sweep
}

// ---- Warm start -----------------------------------------------------------------------------------------------

TEST(PsorSolver, WarmStartFromTheSolutionTakesAtMostOneSweep) {
  const Planted p = SpdLcp(25, 11);
  PsorSolver solver;
  SolveResult cold = solver.Solve(p.problem, Tight());
  ASSERT_EQ(cold.status, SolveStatus::kSolved) << cold.message;
  ASSERT_GT(cold.iterations, 1);

  SolverOptions warm = Tight();
  warm.warm_start = cold.z;
  const SolveResult again = solver.Solve(p.problem, warm);
  ASSERT_EQ(again.status, SolveStatus::kSolved) << again.message;
  EXPECT_EQ(again.iterations, 0);
  EXPECT_LE(MyResidual(p.problem, again.z), 1e-10);

  warm.warm_start = p.zstar;  // the planted solution: exact up to the rounding in q
  const SolveResult planted = solver.Solve(p.problem, warm);
  ASSERT_EQ(planted.status, SolveStatus::kSolved) << planted.message;
  EXPECT_LE(planted.iterations, 1);
}

TEST(PsorSolver, WarmStartOutsideTheBoxIsProjectedFirst) {
  const Planted p = SpdRelay(10, 3);
  SolverOptions o = Tight();
  o.warm_start = Vector::Constant(10, 50.0);
  PsorSolver solver;
  const SolveResult r = solver.Solve(p.problem, o);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(MyResidual(p.problem, r.z), 1e-10);
}

// ---- Safeguards -----------------------------------------------------------------------------------------------

TEST(PsorSolver, ZeroDiagonalIsNotApplicableAndNamesTheRow) {
  DenseMatrix M = DenseMatrix::Identity(4, 4);
  M(2, 2) = 0.0;
  M(2, 3) = 1.0;
  const BoxMLCP problem = BoxMLCP::LCP(M, Vector::Constant(4, -1.0));
  PsorSolver solver;
  const SolveResult r = solver.Solve(problem, Tight());
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_TRUE(Contains(r.message, "M(2,2)"));
  EXPECT_EQ(r.iterations, 0);
}

TEST(PsorSolver, NegativeAndTinyDiagonalsAreRefused) {
  {
    DenseMatrix M = DenseMatrix::Identity(3, 3);
    M(1, 1) = -2.0;
    const SolveResult r = PsorSolver().Solve(BoxMLCP::Relay(M, Vector::Ones(3)), Tight());
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
    EXPECT_TRUE(Contains(r.message, "M(1,1)"));
  }
  {
    DenseMatrix M = DenseMatrix::Identity(3, 3);
    M(0, 0) = 1e-20;
    M(0, 1) = M(1, 0) = 0.5;
    const SolveResult r = PsorSolver().Solve(BoxMLCP::LCP(M, -Vector::Ones(3)), Tight());
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
    EXPECT_TRUE(Contains(r.message, "M(0,0)"));
  }
}

TEST(PsorSolver, StructurallyMissingSparseDiagonalIsRefused) {
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 2.0}, {1, 2, 1.0}, {2, 1, 1.0}, {2, 2, 3.0}};
  SparseMatrix S(3, 3);
  S.setFromTriplets(t.begin(), t.end());
  const BoxMLCP problem(S, Vector::Constant(3, -1.0), Vector::Zero(3), Vector::Constant(3, kInf));
  const SolveResult r = PsorSolver().Solve(problem, Tight());
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_TRUE(Contains(r.message, "M(1,1)"));
}

TEST(PsorSolver, ZeroDiagonalOnAFixedRowIsHarmless) {
  // l_2 = u_2: the projection fixes z_2, so M_22 is never divided by.
  DenseMatrix M = 2.0 * DenseMatrix::Identity(3, 3);
  M(2, 2) = 0.0;
  M(0, 2) = M(2, 0) = 0.5;
  Vector l(3), u(3);
  l << 0.0, -1.0, 0.25;
  u << kInf, 1.0, 0.25;
  const BoxMLCP problem(M, Vector(Vector::Constant(3, -1.0)), l, u);
  const SolveResult r = PsorSolver().Solve(problem, Tight());
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(MyResidual(problem, r.z), 1e-10);
  EXPECT_DOUBLE_EQ(r.z[2], 0.25);
}

// M = [1 3; −3 1] is positive definite but nonsymmetric and far from dominant: Gauss–Seidel's iteration matrix
// has spectral radius 9. With z* = (1,1) in the interior, projected GS cycles (4,10) → (0,0) → (4,10) ...
TEST(PsorSolver, NonconvergentNonsymmetricLcpIsNeverReportedSolved) {
  DenseMatrix M(2, 2);
  M << 1, 3, -3, 1;
  const Vector zstar = Vector::Ones(2);
  const BoxMLCP problem = BoxMLCP::LCP(M, -M * zstar);
  PsorSolver solver;
  const SolveResult r = solver.Solve(problem, Tight());
  EXPECT_NE(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.status, SolveStatus::kStalled) << r.message;
  EXPECT_TRUE(Contains(r.message, "residual"));
  EXPECT_GT(MyResidual(problem, r.z), 1e-3);
  EXPECT_NEAR(r.residual_rel, MyResidual(problem, r.z), 1e-12);

  // Larger relative of the same matrix on a relay box: bounded iterates, still never "solved".
  DenseMatrix big = DenseMatrix::Identity(6, 6);
  for (int i = 0; i + 1 < 6; ++i) {
    big(i, i + 1) = 3.0;
    big(i + 1, i) = -3.0;
  }
  const BoxMLCP relay = BoxMLCP::Relay(big, -big * Vector::Constant(6, 0.3));
  for (double omega : {0.5, 1.0, 1.5}) {
    PsorOptions o;
    o.omega = omega;
    const SolveResult rr = PsorSolver(o).Solve(relay, Tight());
    if (rr.status == SolveStatus::kSolved) {
      EXPECT_LE(MyResidual(relay, rr.z), 1e-10);  // allowed only if it really converged
    } else {
      EXPECT_TRUE(Contains(rr.message, "residual"));
      EXPECT_TRUE(rr.status == SolveStatus::kStalled || rr.status == SolveStatus::kIterationLimit ||
                  rr.status == SolveStatus::kDiverged)
          << ToString(rr.status);
    }
  }
}

TEST(PsorSolver, DivergingFreeRowsAreReportedDiverged) {
  // Free rows: PSOR is plain SOR on M z = −q, whose iteration matrix for [1 3; −3 1] has spectral radius 9.
  DenseMatrix M(2, 2);
  M << 1, 3, -3, 1;
  const Vector l = Vector::Constant(2, -kInf), u = Vector::Constant(2, kInf);
  const BoxMLCP problem(M, Vector(-M * Vector::Ones(2)), l, u);
  SolverOptions raw = Tight();
  raw.polish = false;  // PSOR's own outcome (the base's polish solves the free block exactly from any iterate)
  const SolveResult r = PsorSolver().Solve(problem, raw);
  EXPECT_EQ(r.status, SolveStatus::kDiverged) << r.message;
  EXPECT_TRUE(Contains(r.message, "diverged"));
  EXPECT_LT(r.iterations, 100);
}

TEST(PsorSolver, IterationLimitReportsTheResidualReached) {
  const Planted p = SpdLcp(60, 21);
  SolverOptions o = Tight();
  o.max_iterations = 2;
  o.polish = false;  // the raw sweeps (the polish would finish the job: Polish.AVerifiedAnswerOutranks...)
  const SolveResult r = PsorSolver().Solve(p.problem, o);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit);
  EXPECT_EQ(r.iterations, 2);
  EXPECT_TRUE(Contains(r.message, "residual"));
  EXPECT_GT(MyResidual(p.problem, r.z), 1e-10);
}

TEST(PsorSolver, TimeLimitStopsTheSweeps) {
  const Planted p = SpdLcp(60, 22);
  SolverOptions o = Tight();
  o.time_limit_seconds = 1e-12;
  o.polish = false;  // the raw sweeps
  const SolveResult r = PsorSolver().Solve(p.problem, o);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit) << r.message;
  EXPECT_TRUE(Contains(r.message, "residual"));
}

TEST(PsorSolver, UnattainableToleranceStallsInsteadOfSpinning) {
  // Large diagonals (~1e6) with z* of order 1: once |w_i| / M_ii drops below half an ulp of z_i no coordinate
  // moves, although |w_i| itself (the residual) is still ~1e-10.
  Planted p = SpdLcp(20, 31);
  p.problem = BoxMLCP::LCP(1e6 * p.problem.dense_matrix(), 1e6 * p.problem.q());
  SolverOptions o;
  o.tolerance = 1e-300;
  const SolveResult r = PsorSolver().Solve(p.problem, o);
  EXPECT_EQ(r.status, SolveStatus::kStalled) << r.message;
  EXPECT_TRUE(Contains(r.message, "tolerance"));
  EXPECT_LT(r.iterations, PsorSolver::kDefaultMaxSweeps);
  EXPECT_LE(MyResidual(p.problem, r.z), 1e-12);  // it did get as close as rounding allows
}

TEST(PsorSolver, VerbosityControlsStderr) {
  const Planted p = SpdLcp(8, 4);
  SolverOptions o = Tight();
  ::testing::internal::CaptureStderr();
  PsorSolver().Solve(p.problem, o);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  o.verbosity = 2;
  ::testing::internal::CaptureStderr();
  const SolveResult r = PsorSolver().Solve(p.problem, o);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(Contains(printed, "psor: sweep"));
  EXPECT_TRUE(Contains(printed, "psor: solved after"));
  EXPECT_EQ(r.status, SolveStatus::kSolved);
}

// ---- Options --------------------------------------------------------------------------------------------------

TEST(PsorOptions, ValidationNamesTheField) {
  std::string why;
  EXPECT_TRUE(PsorOptions{}.IsValid(&why));
  const auto invalid = [](auto mutate, const char* field) {
    PsorOptions o;
    mutate(o);
    std::string message;
    EXPECT_FALSE(o.IsValid(&message)) << field;
    EXPECT_TRUE(Contains(message, field));
  };
  invalid([](PsorOptions& o) { o.omega = 0.0; }, "omega");
  invalid([](PsorOptions& o) { o.omega = 2.0; }, "omega");
  invalid([](PsorOptions& o) { o.omega = std::nan(""); }, "omega");
  invalid([](PsorOptions& o) { o.sweep = static_cast<PsorOptions::SweepOrder>(7); }, "sweep");
  invalid([](PsorOptions& o) { o.check_interval = 0; }, "check_interval");
  invalid([](PsorOptions& o) { o.refresh_interval = 0; }, "refresh_interval");
  invalid([](PsorOptions& o) { o.divergence_threshold = 0.5; }, "divergence_threshold");
  invalid([](PsorOptions& o) { o.stall_sweeps = -1; }, "stall_sweeps");
  invalid([](PsorOptions& o) { o.stall_factor = 1.0; }, "stall_factor");
  invalid([](PsorOptions& o) { o.min_diagonal = -1.0; }, "min_diagonal");
}

TEST(PsorSolver, InvalidOmegaIsAStatusNotAnException) {
  const Planted p = SpdLcp(5, 1);
  PsorOptions o;
  o.omega = 3.0;
  PsorSolver solver(o);
  const SolveResult r = solver.Solve(p.problem, Tight());
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_TRUE(Contains(r.message, "omega"));
  EXPECT_EQ(r.iterations, 0);
}

TEST(PsorSolver, SetOptionRejectsBadValuesWithAMessage) {
  PsorSolver solver;
  std::string error;
  EXPECT_FALSE(solver.SetOption("omega", "3", &error));
  EXPECT_TRUE(Contains(error, "omega"));
  solver.set_options(PsorOptions{});  // the core leaves a rejected value in place; start clean
  error.clear();
  EXPECT_FALSE(solver.SetOption("omega", "fast", &error));
  EXPECT_TRUE(Contains(error, "omega"));
  error.clear();
  EXPECT_FALSE(solver.SetOption("relaxation", "1.2", &error));
  EXPECT_TRUE(Contains(error, "unknown option"));
  EXPECT_TRUE(solver.SetOption("stall_sweeps", "0", &error)) << error;
  EXPECT_EQ(solver.options().stall_sweeps, 0);
  EXPECT_TRUE(Contains(solver.OptionsHelp(), "omega"));
}

// ---- Hot path -------------------------------------------------------------------------------------------------

TEST(PsorSolver, RepeatedSolvesDoNotTouchTheHeap) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc is owned by the sanitizer runtime";
  {  // the counter itself must see Eigen's and operator new's allocations, or the test below proves nothing
    test_support::StartCountingMallocs();
    Vector probe = Vector::Ones(100);
    std::string text(200, 'x');
    EXPECT_GE(test_support::StopCountingMallocs(), 2) << probe.sum() << text.size();
  }
  const Planted small = SpdLcp(2, 8);
  const Planted mid = SpdRelay(16, 8);
  const SparseDensePair banded = BandedMixed(64, 8);
  const BoxMLCP* problems[] = {&small.problem, &mid.problem, &banded.sparse, &banded.dense};
  for (const BoxMLCP* problem : problems) {
    for (const auto order :
         {PsorOptions::kForwardSweep, PsorOptions::kBackwardSweep, PsorOptions::kSymmetricSweep}) {
      PsorSolver solver = SweepingIn(order);
      SolveResult result;
      SolverOptions options = Tight();
      // PSOR's own path, and the whole of Solve on the small-solve path (n ≤ BoxMLCP::kSmallSize, where the base's
      // polish is fixed-size). Above that the base's generic polish allocates by design (polish.h), so it is off.
      options.polish = problem->size() <= BoxMLCP::kSmallSize;
      solver.Solve(*problem, options, &result);  // sizes the workspace
      ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
      test_support::StartCountingMallocs();
      for (int k = 0; k < 5; ++k) solver.Solve(*problem, options, &result);
      EXPECT_EQ(test_support::StopCountingMallocs(), 0) << problem->name() << " sweep " << order;
      EXPECT_EQ(result.status, SolveStatus::kSolved);
    }
  }
}

// ---- The subspace step (psor_solver.h) ------------------------------------------------------------------------

// An SPD relay of condition number cond (M = Q diag(1 … 1/cond) Qᵀ): PSOR's rate is about 1 − 1/cond, so plain
// sweeps take thousands, while the active set is read off after a few.
Planted IllConditionedSpdRelay(int n, double cond, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  DenseMatrix B(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) B(i, j) = normal(rng);
  const Eigen::HouseholderQR<DenseMatrix> qr(B);
  const DenseMatrix Q = qr.householderQ();
  Vector eigenvalues(n);
  for (int i = 0; i < n; ++i) eigenvalues[i] = std::pow(cond, -static_cast<double>(i) / (n - 1));
  DenseMatrix M = Q * eigenvalues.asDiagonal() * Q.transpose();
  M = (0.5 * (M + M.transpose())).eval();
  const Vector l = Vector::Constant(n, -1.0), u = Vector::Constant(n, 1.0);
  Vector zstar, q;
  PlantSolution(M, l, u, rng, &zstar, &q);
  return {BoxMLCP::Relay(std::move(M), std::move(q), -1.0, 1.0, "ill_conditioned_relay"), zstar};
}

TEST(PsorSubspaceStep, SolvesAnIllConditionedRelayInAFewSweeps) {
  PsorOptions plain;
  plain.subspace_sweeps = 0;
  int hard = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const Planted p = IllConditionedSpdRelay(8, 1e6, seed);
    const SolveResult fast = PsorSolver().Solve(p.problem, Tight());
    const SolveResult slow = PsorSolver(plain).Solve(p.problem, Tight());
    ASSERT_EQ(fast.status, SolveStatus::kSolved) << fast.message;
    ASSERT_EQ(slow.status, SolveStatus::kSolved) << slow.message;
    EXPECT_EQ(slow.GetDetail("subspace_tries"), 0.0);
    EXPECT_LE(fast.iterations, slow.iterations);
    // The exact answer of the planted set, independently of the polish: the planted z*.
    EXPECT_LE((fast.z - p.zstar).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + p.zstar.cwiseAbs().maxCoeff()))
        << "seed " << seed;
    EXPECT_LE(MyResidual(p.problem, fast.z), 1e-10);
    if (slow.iterations < 200) continue;  // every row settles at a bound within a few sweeps: nothing to gain
    ++hard;
    EXPECT_EQ(fast.GetDetail("subspace_steps"), 1.0) << "seed " << seed;
    EXPECT_LE(fast.iterations, 40) << "seed " << seed << " (plain PSOR: " << slow.iterations << " sweeps; tries "
                                   << fast.GetDetail("subspace_tries") << ")";
  }
  EXPECT_GE(hard, 3) << "too few seeds where plain PSOR is slow: the test shows nothing";
}

TEST(PsorSubspaceStep, FastConvergenceNeverTriesIt) {
  // Strictly diagonally dominant: the residual falls by more than half per sweep, so the pattern is not even
  // tracked, and the answer is bit for bit the plain one.
  const SparseDensePair banded = BandedMixed(64, 3);
  PsorOptions plain;
  plain.subspace_sweeps = 0;
  const SolveResult with = PsorSolver().Solve(banded.dense, Tight());
  const SolveResult without = PsorSolver(plain).Solve(banded.dense, Tight());
  ASSERT_EQ(with.status, SolveStatus::kSolved) << with.message;
  EXPECT_EQ(with.GetDetail("subspace_tries"), 0.0);
  EXPECT_EQ(with.iterations, without.iterations);
  EXPECT_EQ(with.z, without.z);
}

TEST(PsorSubspaceStep, NeverChangesTheVerdict) {
  // Random SPD problems of every bound kind, well and badly conditioned: the same status with and without the step,
  // and answers that agree to the tolerance (the step's answer passes the sweeps' own stopping test).
  PsorOptions plain;
  plain.subspace_sweeps = 0;
  int tried = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    for (const Planted& p : {SpdLcp(12, seed), SpdRelay(20, seed), IllConditionedSpdRelay(16, 1e4, seed)}) {
      const SolveResult with = PsorSolver().Solve(p.problem, Tight());
      const SolveResult without = PsorSolver(plain).Solve(p.problem, Tight());
      EXPECT_EQ(with.status, without.status) << p.problem.name() << " seed " << seed;
      EXPECT_LE(with.iterations, without.iterations);
      if (with.status == SolveStatus::kSolved) {
        EXPECT_LE((with.z - without.z).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + p.zstar.cwiseAbs().maxCoeff()));
      }
      tried += with.GetDetail("subspace_tries") > 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(tried, 0) << "no problem exercised the step";
}

TEST(PsorSubspaceStep, RepeatedSolvesDoNotTouchTheHeap) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc is owned by the sanitizer runtime";
  const Planted p = IllConditionedSpdRelay(8, 1e6, 1);
  PsorSolver solver;
  SolveResult result;
  SolverOptions options = Tight();
  options.polish = false;  // the base's generic polish allocates by design above kSmallSize (polish.h)
  solver.Solve(p.problem, options, &result);
  ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
  ASSERT_EQ(result.GetDetail("subspace_steps"), 1.0);
  test_support::StartCountingMallocs();
  for (int k = 0; k < 5; ++k) solver.Solve(p.problem, options, &result);
  EXPECT_EQ(test_support::StopCountingMallocs(), 0);
  EXPECT_EQ(result.GetDetail("subspace_steps"), 1.0);
}

TEST(PsorSubspaceStep, NegativeSweepsAreRefusedWithTheField) {
  PsorOptions o;
  o.subspace_sweeps = -1;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_TRUE(Contains(why, "subspace_sweeps must be >= 0"));
}

// ---- Small h: relay W = h·G with a planted s* -----------------------------------------------------------------
// The fixture (G, s*, the reference with μ) and the check are tests/support/small_h_relay.h.

TEST(PsorSolver, SolvedWithWrongSAtSmallH) {
  // On relay problems W = h·G, a residual within tol·(1 + ‖q‖∞) alone passes |s − s*|∞ up to 0.2 as "solved"
  // at h = 1e-4 … 1e-8, since q = O(h); this pins the forward-error check.
  // Without the polish: G is an H-matrix (dominant rows), where PSOR contracts, so its own stopping test, in
  // units of z, ends within the allowance too.
  PsorSolver solver;
  test_support::ExpectSolvedWithinAllowanceAtSmallH(solver);
}

}  // namespace
}  // namespace smcbench
