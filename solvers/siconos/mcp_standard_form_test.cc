// The box MCP → Siconos MCP rewriting (mcp_standard_form.h), both ways: a known solution of the box MCP maps to a
// solution of the rewritten problem, and the rewritten problem solved by our own newton maps back to the known
// solution; its Jacobian agrees with finite differences of its F. Built without Siconos.
#include "solvers/siconos/mcp_standard_form.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solvers/newton/semismooth_newton_solver.h"
#include "solvers/siconos/planted_mcp_test_util.h"

namespace smcbench {
namespace {

using test_support::EveryRowKind;
using test_support::Planted;
using test_support::PlantedMcp;

double NaturalResidual(const MCP& p, const Vector& z) {
  Vector F(p.size());
  p.Evaluate(z, &F);
  return NaturalResidualNorm(z, F, p.l(), p.u());
}

TEST(McpStandardForm, LayoutCountsEquationsAndDoublesBoxRows) {
  const Planted k = EveryRowKind();
  const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, false);
  const McpStandardForm form(mcp);
  EXPECT_EQ(form.num_equations(), 1);         // the free row
  EXPECT_EQ(form.num_complementarity(), 10);  // 2 lower + 2 upper + 3 box + 3 box multipliers; fixed eliminated
  EXPECT_TRUE(std::isinf(form.l()[0]) && form.l()[0] < 0);
  for (int a = 1; a < form.size(); ++a) EXPECT_EQ(form.l()[a], 0.0);
}

TEST(McpStandardForm, KnownSolutionMapsToASolutionAndBack) {
  const Planted k = EveryRowKind();
  for (const bool sparse : {false, true}) {
    const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, sparse);
    ASSERT_LE(NaturalResidual(mcp, k.z_star), 1e-14);
    const McpStandardForm form(mcp);
    Vector x, z;
    form.FromOriginal(k.z_star, &x);
    EXPECT_LE(NaturalResidual(form, x), 1e-14) << "sparse " << sparse;
    EXPECT_GE(x.tail(form.num_complementarity()).minCoeff(), 0.0);
    form.ToOriginal(x, &z);
    EXPECT_LE((z - k.z_star).cwiseAbs().maxCoeff(), 1e-15);  // z = u − (u − z*) rounds
  }
}

TEST(McpStandardForm, RewrittenProblemSolvedByNewtonMapsBackToTheSolution) {
  const Planted k = EveryRowKind();
  for (const bool sparse : {false, true}) {
    const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, sparse);
    const McpStandardForm form(mcp);
    SemismoothNewtonSolver newton;
    const SolveResult r = newton.Solve(form);
    ASSERT_TRUE(r.solved()) << r.message;
    Vector z;
    form.ToOriginal(r.z, &z);
    EXPECT_LE(NaturalResidual(mcp, z), 1e-9);
    EXPECT_LE((z - k.z_star).cwiseAbs().maxCoeff(), 1e-8) << "sparse " << sparse;
  }
}

TEST(McpStandardForm, JacobianMatchesFiniteDifferences) {
  const Planted k = EveryRowKind();
  const PlantedMcp mcp(k.l, k.u, k.z_star, k.F_star, false);
  const McpStandardForm form(mcp);
  Vector x;
  form.FromOriginal(k.z_star, &x);
  x.array() += 0.1;
  DenseMatrix J;
  form.JacobianDense(x, &J);
  const int N = form.size();
  Vector Fp(N), Fm(N);
  const double h = 1e-6;
  for (int b = 0; b < N; ++b) {
    Vector xp = x, xm = x;
    xp[b] += h;
    xm[b] -= h;
    form.Evaluate(xp, &Fp);
    form.Evaluate(xm, &Fm);
    EXPECT_LE(((Fp - Fm) / (2 * h) - J.col(b)).cwiseAbs().maxCoeff(), 1e-7) << "column " << b;
  }
}

TEST(McpStandardForm, WrongSizeJacobianIsReportedNotCrashed) {
  const FunctionMCP bad(
      Vector::Zero(2), Vector::Constant(2, kInf), [](const Vector& z, Vector* F) { *F = z; },
      [](const Vector&, DenseMatrix* J) { *J = DenseMatrix::Identity(3, 3); }, "bad");
  const McpStandardForm form(bad);
  DenseMatrix J;
  form.JacobianDense(Vector::Zero(2), &J);
  EXPECT_NE(form.jacobian_error().find("3x3"), std::string::npos) << form.jacobian_error();
  EXPECT_TRUE(J.array().isNaN().all());
}

}  // namespace
}  // namespace smcbench
