// Why: pins down the registry's named constructions that are not plain `CreateSolver(name)` calls (the benchmark's
// generic sparse path), so that the one place defining them keeps saying what bench's reports claim.
#include "solvers/registry/registry.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <vector>

#include "solvers/newton/semismooth_newton_solver.h"

namespace smcbench {
namespace {

TEST(RegistryGenericSparsePath, IsNewtonWithItsSparseLuForcedAtEverySize) {
  const std::unique_ptr<Solver> solver = CreateGenericSparsePathSolver();
  ASSERT_NE(solver, nullptr);
  EXPECT_EQ(solver->info().name, "newton");
  const auto* newton = dynamic_cast<const SemismoothNewtonSolver*>(solver.get());
  ASSERT_NE(newton, nullptr);
  EXPECT_EQ(newton->options().linear_solver, NewtonOptions::kSparseLinearSolver);
  // The registry's own newton keeps its automatic choice (dense LU for small sparse data).
  const std::unique_ptr<Solver> plain = CreateSolver("newton");
  EXPECT_EQ(dynamic_cast<const SemismoothNewtonSolver&>(*plain).options().linear_solver,
            NewtonOptions::kAutoLinearSolver);
}

TEST(RegistryGenericSparsePath, SolvesASmallSparseProblemToItsPlantedSolution) {
  // Tridiagonal M (a P-matrix), n = 5, below newton's dense_max_size: only the forced option sends it to UMFPACK.
  // Planted z* = (0.5, 0, 0.25, 1, 0) with w* = M z* + q: w_i = 0 where 0 < z_i < u_i, w_i ≥ 0 where z_i = l_i = 0,
  // w_i ≤ 0 where z_i = u_i = 1.
  const int n = 5;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 4.0);
    if (i + 1 < n) {
      entries.emplace_back(i, i + 1, -1.0);
      entries.emplace_back(i + 1, i, -1.0);
    }
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(entries.begin(), entries.end());
  Vector z_star(n), l = Vector::Zero(n), u = Vector::Ones(n);
  z_star << 0.5, 0.0, 0.25, 1.0, 0.0;
  Vector w_star(n);
  w_star << 0.0, 2.0, 0.0, -1.0, 3.0;  // the sign each bound requires
  const Vector q = w_star - M * z_star;
  const BoxMLCP problem(M, q, l, u, "tridiagonal-5");
  SolverOptions options;
  options.polish = false;  // the path's own answer, as bench times it
  const SolveResult r = CreateGenericSparsePathSolver()->Solve(problem, options);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_LE((r.z - z_star).cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
}  // namespace smcbench
