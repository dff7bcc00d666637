// Why: pins down the registry's named constructions that are not plain `CreateSolver(name)` calls (the benchmark's
// generic sparse path), so that the one place defining them keeps saying what bench's reports claim.
#include "solvers/registry/registry.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solvers/auto/auto_solver.h"
#include "solvers/newton/semismooth_newton_solver.h"
#include "solvers/siconos/external_backends.h"
#include "tests/support/small_mcps.h"

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

// The MCP backends are found by capability: ipopt and newton always, the Siconos MCP adapters where Siconos is built
// in, newton-min once it is registered; every one of them really solves a small nonlinear MCP (Josephy's NCP,
// unique solution (√6/2, 0, 0, 1/2), from MCPLIB's start).
TEST(RegistryMcp, McpBackendsAreListedWithInfoMcpAndSolveJosephy) {
  std::vector<std::string> mcp_names;
  for (std::string_view name : SolverNames()) {
    if (CreateSolver(name)->info().mcp) mcp_names.emplace_back(name);
  }
  const auto listed = [&](const char* name) {
    return std::find(mcp_names.begin(), mcp_names.end(), name) != mcp_names.end();
  };
  EXPECT_TRUE(listed("newton"));
  EXPECT_TRUE(listed("ipopt"));
  EXPECT_TRUE(listed("auto"));
  EXPECT_EQ(listed("siconos-mcp-newton-fb"), IsExternalBackend("siconos-mcp-newton-fb"));
  EXPECT_EQ(listed("siconos-mcp-newton-min"), IsExternalBackend("siconos-mcp-newton-min"));
  EXPECT_FALSE(listed("lemke"));
  const FunctionMCP josephy = JosephyMcp();
  const Vector expected = JosephySolution();
  SolverOptions o;
  o.warm_start = Vector::Ones(4);
  for (const std::string& name : mcp_names) {
    const SolveResult r = CreateSolver(name)->Solve(josephy, o);
    ASSERT_TRUE(r.solved()) << name << ": " << r.message;
    EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-8) << name;
  }
}

// auto's MCP chain from the registry: newton, then newton-min where registered, then ipopt.
TEST(RegistryMcp, AutoFromTheRegistryChainsTheRegisteredMcpBackends) {
  const std::unique_ptr<Solver> solver = CreateSolver("auto");
  auto* automatic = dynamic_cast<AutoSolver*>(solver.get());
  ASSERT_NE(automatic, nullptr);
  const AutoChoice chain = automatic->McpChoice();
  const std::vector<std::string_view> names = SolverNames();
  const bool has_newton_min = std::find(names.begin(), names.end(), "newton-min") != names.end();
  ASSERT_EQ(chain.count, has_newton_min ? 3 : 2);
  EXPECT_EQ(chain.order[0], AutoCandidate::kNewton);
  if (has_newton_min) {
    EXPECT_EQ(chain.order[1], AutoCandidate::kNewtonMin);
  }
  EXPECT_EQ(chain.order[chain.count - 1], AutoCandidate::kIpopt);
  EXPECT_EQ(automatic->candidate(AutoCandidate::kIpopt).info().name, "ipopt");
}

// One rule for starts outside [l, u] (docs/problem.md, "Starts outside the box"): the Solver base projects the start
// before any backend runs and says so in the result. F below is NaN outside the box (log(1 + z1) for z1 < −1), so a
// backend that started from the given point could not even evaluate F there. F1 = log(1 + z1) − 1/2 has its root
// e^{1/2} − 1 inside [0, 10]; F2 = z2 + 1 ≥ 1 > 0 on the box puts z2 at its lower bound 0: the unique
// solution (e^{1/2} − 1, 0). The start (−3, 20) lies below the box in z1 (by 3) and above it in z2 (by 10).
FunctionMCP LogMcpOnABox() {
  return FunctionMCP(
      Vector::Zero(2), Vector::Constant(2, 10.0),
      [](const Vector& z, Vector* F) {
        (*F)[0] = std::log(1 + z[0]) - 0.5;
        (*F)[1] = z[1] + 1;
      },
      [](const Vector& z, DenseMatrix* J) { *J << 1 / (1 + z[0]), 0, 0, 1; }, "log-box");
}

TEST(SolverBaseStartOutsideTheBox, EveryMcpBackendStartsFromTheProjectionAndSaysSo) {
  const FunctionMCP problem = LogMcpOnABox();
  Vector expected(2);
  expected << std::exp(0.5) - 1, 0.0;
  SolverOptions o;
  o.warm_start = Vector(2);
  o.warm_start << -3.0, 20.0;
  int checked = 0;
  for (std::string_view name : SolverNames()) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    if (!solver->info().mcp) continue;
    ++checked;
    const SolveResult r = solver->Solve(problem, o);
    ASSERT_TRUE(r.solved()) << name << ": " << r.message;
    EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-8) << name;
    EXPECT_TRUE((r.z.array() >= problem.l().array()).all() && (r.z.array() <= problem.u().array()).all())
        << name << ": z = " << r.z.transpose();
    EXPECT_EQ(r.GetDetail("start_projected"), 2.0) << name;
    EXPECT_EQ(r.GetDetail("start_projection_distance"), 10.0) << name;
  }
  EXPECT_GE(checked, 3);  // newton, ipopt, auto at least
  // A start inside the box leaves no trace.
  o.warm_start << 0.5, 1.0;
  const SolveResult inside = CreateSolver("newton")->Solve(problem, o);
  ASSERT_TRUE(inside.solved()) << inside.message;
  EXPECT_TRUE(std::isnan(inside.GetDetail("start_projected")));
}

// The same rule for every box backend, warm start outside [l, u]: a relay (box [−1, 1]²) with an SPD M (every box
// backend applies) and the planted solution z* = (0.5, −1): row 1 free (w1 = 0), row 2 at its lower bound (w2 > 0).
TEST(SolverBaseStartOutsideTheBox, EveryBoxBackendStartsFromTheProjectionAndSaysSo) {
  DenseMatrix M(2, 2);
  M << 4, 1, 1, 3;
  Vector z_star(2), w_star(2);
  z_star << 0.5, -1.0;
  w_star << 0.0, 2.0;
  const Vector q = w_star - M * z_star;
  const BoxMLCP problem(M, q, Vector::Constant(2, -1.0), Vector::Ones(2), "relay-2");
  SolverOptions o;
  o.warm_start = Vector(2);
  o.warm_start << 3.0, -1.5;  // above the box by 2 in z1, below it by 0.5 in z2
  int checked = 0;
  for (std::string_view name : SolverNames()) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    if (!solver->info().box) continue;
    ++checked;
    const SolveResult r = solver->Solve(problem, o);
    if (r.status == SolveStatus::kNotApplicable || r.status == SolveStatus::kSizeLimit) continue;
    ASSERT_TRUE(r.solved()) << name << ": " << r.message;
    EXPECT_LE((r.z - z_star).cwiseAbs().maxCoeff(), 1e-8) << name;
    EXPECT_EQ(r.GetDetail("start_projected"), 2.0) << name;
    EXPECT_EQ(r.GetDetail("start_projection_distance"), 2.0) << name;
  }
  EXPECT_GE(checked, 5);
}

}  // namespace
}  // namespace smcbench
