// The Siconos MCP adapters (siconos_mcp_solver.h), built only with Siconos: known solutions through the exact
// rewriting (every kind of row, a nonlinear F, a literature problem), every status the adapter maps, and the
// registry listing them as MCP backends. Answers are judged by our scale-free residual, recomputed here.
#include "solvers/siconos/siconos_mcp_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "solvers/registry/registry.h"
#include "solvers/siconos/planted_mcp_test_util.h"
#include "tests/support/small_mcps.h"

namespace smcbench {
namespace {

using test_support::EveryRowKind;
using test_support::Planted;
using test_support::PlantedMcp;

constexpr double kTol = 1e-10;
constexpr SiconosMcpMethod kMethods[] = {SiconosMcpMethod::kNewtonFb, SiconosMcpMethod::kNewtonMin};

double ScaledResidual(const MCP& p, const Vector& z) {
  Vector F(p.size()), d;
  p.Evaluate(z, &F);
  DenseMatrix J(p.size(), p.size());
  if (p.jacobian_kind() == MCP::JacobianKind::kSparse) {
    SparseMatrix Js;
    p.JacobianSparse(z, &Js);
    J = DenseMatrix(Js);
  } else {
    p.JacobianDense(z, &J);
  }
  McpRowScales(J, p.variable_scale(), &d);
  return McpScaledResidual(z, F, p.l(), p.u(), d, p.variable_scale());
}

TEST(SiconosMcp, RegistryListsBothAsExternalMcpBackends) {
  for (const char* name : {"siconos-mcp-newton-fb", "siconos-mcp-newton-min"}) {
    const auto solver = CreateSolver(name);
    ASSERT_NE(solver, nullptr);
    EXPECT_EQ(solver->info().name, name);
    EXPECT_TRUE(solver->info().mcp);
    EXPECT_TRUE(solver->info().external);
    EXPECT_FALSE(solver->info().equilibrate);
    EXPECT_TRUE(IsExternalBackend(name));
  }
}

TEST(SiconosMcp, PlantedSolutionWithEveryRowKindThroughTheRewriting) {
  const Planted k = EveryRowKind();
  for (const SiconosMcpMethod method : kMethods) {
    for (const bool sparse : {false, true}) {
      const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, sparse);
      SiconosMcpSolver solver(method);
      const SolveResult r = solver.Solve(mcp);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << solver.info().name << ": " << r.message;
      EXPECT_LE(ScaledResidual(mcp, r.z), kTol);
      EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-8) << solver.info().name;
      EXPECT_EQ(r.GetDetail("standard_size"), 11.0);  // 8 rows that are not fixed + 3 box multipliers
    }
  }
}

// Josephy's NCP (MCPLIB "josephy"): unique nondegenerate solution (√6/2, 0, 0, 1/2), from MCPLIB's start
// (1, 1, 1, 1).
TEST(SiconosMcp, JosephyFromThePublishedStart) {
  const FunctionMCP mcp = JosephyMcp();
  const Vector expected = JosephySolution();
  for (const SiconosMcpMethod method : kMethods) {
    SiconosMcpSolver solver(method);
    SolverOptions o;
    o.warm_start = Vector::Ones(4);
    const SolveResult r = solver.Solve(mcp, o);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << solver.info().name << ": " << r.message;
    EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-8) << solver.info().name;
  }
}

TEST(SiconosMcp, BoxMlcpIsRefused) {
  const BoxMLCP box = BoxMLCP::LCP(DenseMatrix::Identity(2, 2), -Vector::Ones(2));
  SiconosMcpSolver solver(SiconosMcpMethod::kNewtonFb);
  EXPECT_EQ(solver.Solve(box).status, SolveStatus::kNotApplicable);
}

TEST(SiconosMcp, NanInFAtTheStartIsANumericalFailureBeforeSiconosRuns) {
  const FunctionMCP mcp(
      Vector::Zero(2), Vector::Constant(2, kInf),
      [](const Vector& z, Vector* F) {
        (*F)[0] = z[0] - 1.0;
        (*F)[1] = std::log(z[1]) + 1.0;
      },
      [](const Vector& z, DenseMatrix* J) { *J << 1.0, 0.0, 0.0, 1.0 / z[1]; }, "log");
  for (const SiconosMcpMethod method : kMethods) {
    SiconosMcpSolver solver(method);
    const SolveResult r = solver.Solve(mcp);
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
    EXPECT_NE(r.message.find("F[1]"), std::string::npos) << r.message;
    EXPECT_TRUE(std::isnan(r.GetDetail("siconos_info")));  // never called
    EXPECT_EQ(r.backend_code, std::nullopt);
  }
}

TEST(SiconosMcp, WrongSizeJacobianIsANumericalFailureNamingTheSize) {
  const FunctionMCP mcp(
      Vector::Zero(2), Vector::Constant(2, kInf), [](const Vector& z, Vector* F) { *F = z.array() - 1.0; },
      [](const Vector&, DenseMatrix* J) { *J = DenseMatrix::Identity(3, 2); }, "wrong-jacobian");
  SiconosMcpSolver solver(SiconosMcpMethod::kNewtonMin);
  const SolveResult r = solver.Solve(mcp);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_NE(r.message.find("3x2"), std::string::npos) << r.message;
}

// An exception from F inside Siconos' iterations never crosses its C frames; it reaches the caller afterwards.
// An evaluation error of F inside Siconos' callback (a std::runtime_error) is carried past Siconos' C code and ends the
// solve with numerical_failure and its message (Solver::Solve's policy); the instance solves the next problem.
TEST(SiconosMcp, ExceptionFromFIsAStatusAfterSiconosReturns) {
  int calls = 0;
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [&calls](const Vector& x, Vector* F) {
        if (++calls > 3) throw std::runtime_error("F failed");
        (*F)[0] = x[0] * x[0] - 1.0;
      },
      [](const Vector& x, DenseMatrix* J) { (*J)(0, 0) = 2.0 * x[0]; }, "throws");
  for (const SiconosMcpMethod method : kMethods) {
    calls = 0;
    SiconosMcpSolver solver(method);
    SolverOptions o;
    o.warm_start = Vector::Constant(1, 3.0);
    const SolveResult failed = solver.Solve(mcp, o);
    EXPECT_EQ(failed.status, SolveStatus::kNumericalFailure);
    EXPECT_NE(failed.message.find("F failed"), std::string::npos) << failed.message;
    calls = -1000;
    const SolveResult r = solver.Solve(mcp, o);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_NEAR(r.z[0], 1.0, 1e-10);
  }
}

TEST(SiconosMcp, IterationLimitAtTheBudget) {
  const Planted k = EveryRowKind();
  const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, false);
  SiconosMcpSolver solver(SiconosMcpMethod::kNewtonFb);
  SolverOptions o;
  o.max_iterations = 1;
  const SolveResult r = solver.Solve(mcp, o);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_EQ(r.GetDetail("siconos_info"), 1.0);
  EXPECT_EQ(r.backend_code, std::optional<int>(1));  // Siconos' info as it is
}

TEST(SiconosMcp, TimeLimitPassedBeforeTheCall) {
  const Planted k = EveryRowKind();
  const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, false);
  SiconosMcpSolver solver(SiconosMcpMethod::kNewtonFb);
  SolverOptions o;
  o.time_limit_seconds = 1e-9;
  const SolveResult r = solver.Solve(mcp, o);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit) << r.message;
}

TEST(SiconosMcp, SizeLimitIsAStatus) {
  const Planted k = EveryRowKind();
  const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, false);
  SiconosMcpSolver solver(SiconosMcpMethod::kNewtonFb);
  solver.mutable_options().max_size = 4;
  const SolveResult r = solver.Solve(mcp);
  EXPECT_EQ(r.status, SolveStatus::kSizeLimit);
  EXPECT_NE(r.message.find("max_size"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace smcbench
