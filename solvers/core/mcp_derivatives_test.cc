// MCPs without a hand-written Jacobian: automatic differentiation (autodiff_mcp.h) and central differences
// (mcp_derivatives.h) against the analytic Jacobian of Josephy's NCP, a Newton solve through each reaching the
// problem's known solution, and the derivative check flagging a deliberately wrong J.
#include "solvers/core/mcp_derivatives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "solvers/core/autodiff_mcp.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// Josephy (1979), MCPLIB `josephy`: an NCP in R⁴ whose unique solution is (√6/2, 0, 0, 1/2).
template <class T>
void JosephyF(const T* x, T* F) {
  F[0] = 3.0 * x[0] * x[0] + 2.0 * x[0] * x[1] + 2.0 * x[1] * x[1] + x[2] + 3.0 * x[3] - 6.0;
  F[1] = 2.0 * x[0] * x[0] + x[0] + x[1] * x[1] + 3.0 * x[2] + 2.0 * x[3] - 2.0;
  F[2] = 3.0 * x[0] * x[0] + x[0] * x[1] + 2.0 * x[1] * x[1] + 2.0 * x[2] + 3.0 * x[3] - 1.0;
  F[3] = x[0] * x[0] + 3.0 * x[1] * x[1] + 2.0 * x[2] + 3.0 * x[3] - 3.0;
}

DenseMatrix JosephyJ(const Vector& x) {
  DenseMatrix J(4, 4);
  J << 6 * x[0] + 2 * x[1], 2 * x[0] + 4 * x[1], 1, 3,  //
      4 * x[0] + 1, 2 * x[1], 3, 2,                    //
      6 * x[0] + x[1], x[0] + 4 * x[1], 2, 3,          //
      2 * x[0], 6 * x[1], 2, 3;
  return J;
}

const Vector kLower = Vector::Zero(4);
const Vector kUpper = Vector::Constant(4, kInf);

FunctionMCP Analytic(double wrong_entry = 0.0) {
  return FunctionMCP(
      kLower, kUpper, [](const Vector& z, Vector* F) { JosephyF(z.data(), F->data()); },
      [wrong_entry](const Vector& z, DenseMatrix* J) {
        *J = JosephyJ(z);
        (*J)(1, 2) += wrong_entry;  // a slip in one entry: 3 written as 3 + wrong_entry
      },
      "josephy");
}

const auto kJosephy = [](const auto* z, auto* F) { JosephyF(z, F); };

TEST(AutoDiffMcp, JacobianIsTheAnalyticOneToRounding) {
  const auto mcp = MakeAutoDiffMcp(kLower, kUpper, kJosephy);
  const auto fixed = MakeAutoDiffMcp<4>(kLower, kUpper, kJosephy);
  for (const Vector& z : {Vector::Zero(4).eval(), (Vector(4) << 1.2, 0.3, 2.0, 0.5).finished(),
                          (Vector(4) << 100, 100, 100, 100).finished()}) {
    DenseMatrix J(4, 4), Jf(4, 4);
    mcp.JacobianDense(z, &J);
    fixed.JacobianDense(z, &Jf);
    const DenseMatrix expected = JosephyJ(z);
    EXPECT_LE((J - expected).cwiseAbs().maxCoeff(), 1e-14 * (1 + expected.cwiseAbs().maxCoeff())) << z.transpose();
    EXPECT_EQ(J, Jf);
    Vector F(4), Fa(4);
    mcp.Evaluate(z, &F);
    JosephyF(z.data(), Fa.data());
    EXPECT_EQ(F, Fa);
  }
}

TEST(AutoDiffMcp, ConstantRowsAndWrongTemplateSize) {
  // F_1 = 7: the AutoDiff scalar keeps no derivatives for it; its row must read as zeros.
  const auto mcp = MakeAutoDiffMcp(Vector::Zero(2), Vector::Ones(2), [](const auto* z, auto* F) {
    F[0] = z[0] * z[1];
    F[1] = 7.0;
  });
  DenseMatrix J(2, 2);
  mcp.JacobianDense((Vector(2) << 0.5, 0.25).finished(), &J);
  EXPECT_EQ(J(0, 0), 0.25);
  EXPECT_EQ(J(0, 1), 0.5);
  EXPECT_EQ(J(1, 0), 0.0);
  EXPECT_EQ(J(1, 1), 0.0);
  EXPECT_THROW(MakeAutoDiffMcp<3>(kLower, kUpper, kJosephy), InvalidInputError);
}

TEST(McpDerivatives, CentralDifferencesMatchTheAnalyticJacobian) {
  const FunctionMCP mcp = Analytic();
  for (const Vector& z : {Vector::Zero(4).eval(), (Vector(4) << 1.2, 0.3, 2.0, 0.5).finished(),
                          (Vector(4) << 100, 100, 100, 100).finished()}) {
    DenseMatrix D;
    CentralDifferenceJacobian(mcp, z, &D);
    const DenseMatrix expected = JosephyJ(z);
    // F is quadratic: the central difference has no truncation error, only rounding of order ε^{2/3}·|F|.
    EXPECT_LE(((D - expected).array().abs() / expected.array().abs().max(1.0)).maxCoeff(), 1e-7) << z.transpose();
  }
}

TEST(McpDerivatives, DifferencesStayInTheBox) {
  // F is undefined below 0 and above 1: at the bounds the step must go inward.
  const FunctionMCP mcp(
      Vector::Zero(2), Vector::Ones(2),
      [](const Vector& z, Vector* F) {
        if ((z.array() < 0.0).any() || (z.array() > 1.0).any()) throw std::domain_error("F outside the box");
        (*F)[0] = std::sqrt(z[0] + 1.0) + z[1];
        (*F)[1] = z[0] * z[1];
      },
      [](const Vector& z, DenseMatrix* J) {
        *J << 0.5 / std::sqrt(z[0] + 1.0), 1.0, z[1], z[0];
      });
  const Vector z = (Vector(2) << 0.0, 1.0).finished();
  DenseMatrix D, J(2, 2);
  CentralDifferenceJacobian(mcp, z, &D);
  mcp.JacobianDense(z, &J);
  EXPECT_LE((D - J).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_TRUE(CheckMcpJacobian(mcp, z).ok);
}

TEST(McpDerivatives, CheckPassesARightJacobianAndFlagsAWrongOne) {
  const Vector z0 = Vector::Ones(4);
  const JacobianCheck right = CheckMcpJacobian(Analytic(), z0);
  EXPECT_TRUE(right.ok) << right.message;
  EXPECT_EQ(right.message, "");
  EXPECT_LT(right.max_error, 1e-7);

  const JacobianCheck wrong = CheckMcpJacobian(Analytic(0.5), z0);
  EXPECT_FALSE(wrong.ok);
  EXPECT_EQ(wrong.row, 1);
  EXPECT_EQ(wrong.col, 2);
  EXPECT_EQ(wrong.wrong_entries, 1);
  EXPECT_NEAR(wrong.analytic, 3.5, 1e-15);
  EXPECT_NEAR(wrong.finite_difference, 3.0, 1e-7);
  EXPECT_NE(wrong.message.find("J[1, 2] = 3.5"), std::string::npos) << wrong.message;
  EXPECT_NE(wrong.message.find("1 of 16 entries"), std::string::npos) << wrong.message;

  // A slip below the tolerance passes; a tighter tolerance catches it.
  EXPECT_TRUE(CheckMcpJacobian(Analytic(1e-6), z0).ok);
  EXPECT_FALSE(CheckMcpJacobian(Analytic(1e-6), z0, {1e-7}).ok);
  EXPECT_THROW(CheckMcpJacobian(Analytic(), z0, {0.0}), InvalidInputError);
  EXPECT_THROW(CheckMcpJacobian(Analytic(), Vector::Ones(3)), InvalidInputError);
}

// Newton on the AutoDiff MCP and on the analytic one: the same answer, Josephy's solution.
TEST(AutoDiffMcp, NewtonSolvesJosephyAsWithTheAnalyticJacobian) {
  const Vector solution = (Vector(4) << std::sqrt(6.0) / 2.0, 0.0, 0.0, 0.5).finished();
  auto newton = CreateSolver("newton");
  SolverOptions options;
  options.warm_start = Vector::Ones(4);
  const auto autodiff = MakeAutoDiffMcp(kLower, kUpper, kJosephy);
  const SolveResult by_autodiff = newton->Solve(autodiff, options);
  const SolveResult by_hand = newton->Solve(Analytic(), options);
  ASSERT_TRUE(by_autodiff.solved()) << by_autodiff.message;
  ASSERT_TRUE(by_hand.solved()) << by_hand.message;
  EXPECT_LE((by_autodiff.z - solution).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((by_autodiff.z - by_hand.z).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace smcbench
