// Pins down problem validation (every error names field and index) and the natural-map merit function.
#include "solvers/core/problem.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace smcbench {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::function<void()>& build) {
  try {
    build();
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "(no error)";
}

DenseMatrix Identity(int n) { return DenseMatrix::Identity(n, n); }

TEST(BoxMLCPValidation, RejectsNaNAndInfInMatrixWithIndex) {
  DenseMatrix M = Identity(3);
  M(2, 1) = std::nan("");
  EXPECT_THAT(ErrorOf([&] { BoxMLCP::LCP(M, Vector::Zero(3)); }), HasSubstr("M(2,1) is NaN"));
  M(2, 1) = kInf;
  EXPECT_THAT(ErrorOf([&] { BoxMLCP::LCP(M, Vector::Zero(3)); }), HasSubstr("M(2,1) is infinite"));
}

TEST(BoxMLCPValidation, RejectsNaNInQWithIndex) {
  Vector q = Vector::Zero(3);
  q[1] = std::nan("");
  EXPECT_THAT(ErrorOf([&] { BoxMLCP::LCP(Identity(3), q); }), HasSubstr("q[1] is NaN"));
  q[1] = -kInf;
  EXPECT_THAT(ErrorOf([&] { BoxMLCP::LCP(Identity(3), q); }), HasSubstr("q[1] is infinite"));
}

TEST(BoxMLCPValidation, RejectsSizeMismatches) {
  EXPECT_THAT(ErrorOf([&] { BoxMLCP::LCP(DenseMatrix::Ones(2, 3), Vector::Zero(2)); }),
              HasSubstr("M is 2x3 but must be square"));
  EXPECT_THAT(ErrorOf([&] { BoxMLCP::LCP(Identity(3), Vector::Zero(2)); }), HasSubstr("q has size 2"));
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(Identity(2), Vector::Zero(2), Vector::Zero(3), Vector::Ones(2)); }),
              HasSubstr("l has size 3"));
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(Identity(2), Vector::Zero(2), Vector::Zero(2), Vector::Ones(1)); }),
              HasSubstr("u has size 1"));
}

TEST(BoxMLCPValidation, RejectsEmptyProblem) {
  EXPECT_THAT(ErrorOf([&] { BoxMLCP::LCP(DenseMatrix(0, 0), Vector(0)); }), HasSubstr("empty problem"));
}

TEST(BoxMLCPValidation, RejectsBadBoundsWithIndex) {
  Vector l = Vector::Zero(3), u = Vector::Ones(3);
  l[2] = 2.0;
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(Identity(3), Vector::Zero(3), l, u); }), HasSubstr("l[2] = 2 > u[2] = 1"));
  l[2] = std::nan("");
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(Identity(3), Vector::Zero(3), l, u); }), HasSubstr("l[2] is NaN"));
  l[2] = 0;
  u[0] = std::nan("");
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(Identity(3), Vector::Zero(3), l, u); }), HasSubstr("u[0] is NaN"));
  u[0] = -kInf;
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(Identity(3), Vector::Zero(3), l, u); }), HasSubstr("u[0] is -inf"));
  u[0] = 1;
  l[1] = kInf;
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(Identity(3), Vector::Zero(3), l, u); }), HasSubstr("l[1] is +inf"));
}

TEST(BoxMLCPValidation, SparseMatrixEntriesAreChecked) {
  SparseMatrix M(2, 2);
  M.insert(0, 0) = 1.0;
  M.insert(1, 0) = std::nan("");
  M.insert(1, 1) = 1.0;
  EXPECT_THAT(ErrorOf([&] { BoxMLCP(M, Vector::Zero(2), Vector::Zero(2), Vector::Constant(2, kInf)); }),
              HasSubstr("M(1,0) is NaN"));
}

TEST(BoxMLCPValidation, AcceptsInfiniteBoundsOfEveryKind) {
  Vector l(4), u(4);
  l << -kInf, 0.0, -kInf, -1.0;
  u << kInf, kInf, 3.0, 1.0;
  const BoxMLCP p(Identity(4), Vector::Ones(4), l, u, "mixed");
  EXPECT_EQ(p.size(), 4);
  EXPECT_EQ(p.name(), "mixed");
  EXPECT_FALSE(p.is_sparse());
  EXPECT_THROW(p.sparse_matrix(), std::logic_error);
}

TEST(NaturalResidual, IsZeroExactlyAtTheSolution) {
  // LCP with M = I, q = (-1, 2): z = (1, 0), w = (0, 2).
  Vector q(2);
  q << -1.0, 2.0;
  const BoxMLCP p = BoxMLCP::LCP(Identity(2), q);
  Vector z(2), w;
  z << 1.0, 0.0;
  Residual r = p.NaturalResidual(z, &w);
  EXPECT_EQ(r.abs, 0.0);
  EXPECT_EQ(w, Vector((Vector(2) << 0.0, 2.0).finished()));
  z << 0.5, 0.25;
  r = p.NaturalResidual(z, &w);
  // z − Π(z − w): row 0: 0.5 − Π(0.5 − (−0.5)) = −0.5; row 1: 0.25 − Π(0.25 − 2.25) = 0.25.
  EXPECT_DOUBLE_EQ(r.abs, 0.5);
  EXPECT_DOUBLE_EQ(r.rel, 0.5 / 3.0);  // 1 + ‖q‖∞ = 3
}

TEST(NaturalResidual, RelayAndFreeRows) {
  Vector l(2), u(2), q(2);
  l << -1.0, -kInf;
  u << 1.0, kInf;
  q << 5.0, -2.0;
  const BoxMLCP p(Identity(2), q, l, u);
  Vector z(2), w;
  z << -1.0, 2.0;  // row 0 at lower bound with w = 4 ≥ 0; free row w = 0.
  EXPECT_EQ(p.NaturalResidual(z, &w).abs, 0.0);
  z << -1.0, 1.0;  // free row off by 1.
  EXPECT_DOUBLE_EQ(p.NaturalResidual(z, &w).abs, 1.0);
}

TEST(NaturalResidual, HugeIteratesDoNotCancelToZero) {
  // M = 0, q = 1, so w = 1 at z = 1e16: z − Π(z − w) = 1e16 − (1e16 − 1) rounds to 0 in floating point,
  // but the residual is really 1.
  const DenseMatrix zero = DenseMatrix::Zero(1, 1);
  const BoxMLCP free_row(zero, Vector::Ones(1), Vector::Constant(1, -kInf), Vector::Constant(1, kInf));
  Vector z = Vector::Constant(1, 1e16), w;
  EXPECT_EQ(free_row.NaturalResidual(z, &w).abs, 1.0);
  const BoxMLCP lcp = BoxMLCP::LCP(zero, Vector::Ones(1));
  EXPECT_EQ(lcp.NaturalResidual(z, &w).abs, 1.0);
}

TEST(NaturalResidual, InfeasibleIteratesAreMeasured) {
  // z outside the box: z − Π(z − w) with z = 3 > u = 1, w = 0 → 3 − 1 = 2.
  const BoxMLCP p = BoxMLCP::Relay(Identity(1), Vector::Constant(1, -3.0));
  Vector z = Vector::Constant(1, 3.0), w;
  EXPECT_EQ(p.NaturalResidual(z, &w).abs, 2.0);
}

TEST(NaturalResidual, NaNIteratesNeverPass) {
  const BoxMLCP p = BoxMLCP::LCP(Identity(1), Vector::Ones(1));
  Vector z(1), w;
  z[0] = std::nan("");
  EXPECT_EQ(p.NaturalResidual(z, &w).abs, kInf);
}

TEST(BoxMLCP, DenseAndSparseAgree) {
  DenseMatrix M(2, 2);
  M << 2.0, -1.0, 0.5, 3.0;
  const SparseMatrix S = M.sparseView();
  Vector q(2);
  q << 1.0, -1.0;
  const BoxMLCP d = BoxMLCP::LCP(M, q);
  const BoxMLCP s(S, q, Vector::Zero(2), Vector::Constant(2, kInf));
  Vector z(2), wd(2), ws(2);
  z << 0.3, 0.7;
  d.Affine(z, &wd);
  s.Affine(z, &ws);
  EXPECT_EQ(wd, ws);
  Vector unsized;  // the small-size path resizes like Eigen's assignment does
  d.Affine(z, &unsized);
  EXPECT_EQ(unsized, wd);
  EXPECT_FALSE(d.IsSymmetric());
  EXPECT_FALSE(s.IsSymmetric());
  EXPECT_DOUBLE_EQ(d.MatrixInfNorm(), 3.5);
  EXPECT_DOUBLE_EQ(s.MatrixInfNorm(), 3.5);
  EXPECT_TRUE(BoxMLCP::LCP(Identity(3), Vector::Zero(3)).IsSymmetric());
}

TEST(BoxMLCP, SetQReplacesInPlaceAndValidates) {
  BoxMLCP p = BoxMLCP::Relay(Identity(2), Vector::Zero(2));
  Vector q(2);
  q << 3.0, -4.0;
  p.set_q(q);
  EXPECT_EQ(p.q(), q);
  EXPECT_DOUBLE_EQ(p.residual_scale(), 5.0);
  q[1] = std::nan("");
  EXPECT_THAT(ErrorOf([&] { p.set_q(q); }), HasSubstr("q[1] is NaN"));
  EXPECT_THAT(ErrorOf([&] { p.set_q(Vector::Zero(3)); }), HasSubstr("set_q: q has size 3"));
  EXPECT_DOUBLE_EQ(p.residual_scale(), 5.0);  // unchanged after a rejected update
}

TEST(BoxMLCP, SetQFixedSizeOverloadMatchesTheDynamicOne) {
  BoxMLCP p = BoxMLCP::Relay(Identity(2), Vector::Zero(2));
  Eigen::Vector2d q(3.0, -4.0);
  p.set_q(q);
  EXPECT_EQ(p.q(), Vector(q));
  EXPECT_DOUBLE_EQ(p.residual_scale(), 5.0);
  q[0] = -kInf;
  EXPECT_THAT(ErrorOf([&] { p.set_q(q); }), HasSubstr("q[0] is infinite"));
  EXPECT_THAT(ErrorOf([&] { p.set_q(Eigen::Vector3d::Zero().eval()); }), HasSubstr("set_q: q has size 3"));
  EXPECT_DOUBLE_EQ(p.q()[0], 3.0);  // unchanged after a rejected update
  EXPECT_DOUBLE_EQ(p.residual_scale(), 5.0);
}

TEST(BoxMLCP, MatrixIdIsNewForEveryMatrixAndSharedByCopies) {
  BoxMLCP a = BoxMLCP::LCP(Identity(2), Vector::Zero(2));
  const BoxMLCP b = BoxMLCP::LCP(Identity(2), Vector::Zero(2));
  EXPECT_NE(a.matrix_id(), 0u);
  EXPECT_NE(a.matrix_id(), b.matrix_id());  // equal contents, but ids are never compared by value
  const BoxMLCP copy = a;
  EXPECT_EQ(copy.matrix_id(), a.matrix_id());
  const auto before = a.matrix_id();
  a.set_q((Vector(2) << 1.0, 2.0).finished());
  EXPECT_EQ(a.matrix_id(), before);  // q does not touch M
  a.set_M(2.0 * Identity(2));
  EXPECT_NE(a.matrix_id(), before);
  EXPECT_EQ(a.dense_matrix(), 2.0 * Identity(2));
  EXPECT_EQ(copy.dense_matrix(), Identity(2));
}

TEST(BoxMLCP, SetMValidatesAndKeepsTheOldMatrixOnError) {
  BoxMLCP d = BoxMLCP::LCP(Identity(2), Vector::Zero(2));
  DenseMatrix bad = Identity(2);
  bad(1, 0) = std::nan("");
  EXPECT_THAT(ErrorOf([&] { d.set_M(bad); }), HasSubstr("M(1,0) is NaN"));
  EXPECT_EQ(d.dense_matrix(), Identity(2));
  EXPECT_THAT(ErrorOf([&] { d.set_M(Identity(3)); }), HasSubstr("set_M: M is 3x3"));
  EXPECT_THAT(ErrorOf([&] { d.set_M(SparseMatrix(2, 2)); }), HasSubstr("stores M dense"));
  BoxMLCP s(SparseMatrix(Identity(2).sparseView()), Vector::Zero(2), Vector::Zero(2), Vector::Constant(2, kInf));
  const auto before = s.matrix_id();
  s.set_M(SparseMatrix((3.0 * Identity(2)).sparseView()));
  EXPECT_NE(s.matrix_id(), before);
  EXPECT_EQ(s.ToDense(), 3.0 * Identity(2));
  EXPECT_THAT(ErrorOf([&] { s.set_M(Identity(2)); }), HasSubstr("stores M sparse"));
}

TEST(BoxMLCP, SmallDenseMeritFunctionMatchesTheGenericFormula) {
  // The inline m ≤ 4 path against NaturalResidualNorm(M z + q) on random data, NaN and infinite bounds.
  for (int n = 1; n <= 5; ++n) {
    DenseMatrix M = DenseMatrix::Random(n, n);
    Vector q = Vector::Random(n), l = -Vector::Ones(n), u = Vector::Ones(n);
    u[0] = kInf;
    const BoxMLCP p(M, q, l, u);
    for (int trial = 0; trial < 3; ++trial) {
      Vector z = 2.0 * Vector::Random(n), w;
      if (trial == 2) z[n - 1] = std::nan("");
      const Residual r = p.NaturalResidual(z, &w);
      const Vector w_ref = M * z + q;
      EXPECT_TRUE(w.isApprox(w_ref) || trial == 2) << n;
      const double ref = NaturalResidualNorm(z, w_ref, l, u);
      EXPECT_EQ(r.abs, ref) << n << " " << trial;
      EXPECT_EQ(r.rel, ref / p.residual_scale());
    }
  }
}

TEST(MCPValidation, BoundsAreChecked) {
  Vector l(1), u(1);
  l << 1.0;
  u << 0.0;
  auto F = [](const Vector& z, Vector* f) { *f = z; };
  auto J = [](const Vector&, DenseMatrix* j) { j->setIdentity(1, 1); };
  EXPECT_THAT(ErrorOf([&] { FunctionMCP(l, u, F, J); }), HasSubstr("l[0] = 1 > u[0] = 0"));
  EXPECT_THAT(ErrorOf([&] { FunctionMCP(Vector(0), Vector(0), F, J); }), HasSubstr("empty problem"));
  EXPECT_THAT(ErrorOf([&] { FunctionMCP(u, l, nullptr, J); }), HasSubstr("F is empty"));
}

// ---- The MCP's scale-free residual (McpScaledResidual, McpRowScales, MCP::variable_scale) ----

// With units 1 and F = M z + q it is the box's Residual::scaled, to rounding (the box multiplies by 1/d_i, the MCP
// divides by d_i).
TEST(McpScaledResidual, IsTheBoxResidualScaledForAnAffineF) {
  DenseMatrix M(3, 3);
  M << 2e-6, 1e-6, 0, -1e-6, 2e-6, 0, 0, 3.0, 4e3;
  Vector q(3), l(3), u(3), z(3);
  q << -1e-6, 2e-6, -5.0;
  l << -1.0, 0.0, -kInf;
  u << 1.0, kInf, kInf;
  z << 0.3, 0.7, -2.0;
  const BoxMLCP p(M, q, l, u);
  Vector w;
  const double box = p.NaturalResidual(z, &w).scaled;
  Vector d;
  McpRowScales(M, Vector(), &d);
  EXPECT_EQ(d, p.row_scale());
  EXPECT_NEAR(McpScaledResidual(z, w, l, u, d, Vector()), box, 1e-15 * box);
  McpRowScales(SparseMatrix(M.sparseView()), Vector(), &d);
  EXPECT_EQ(d, p.row_scale());
}

// Row i of F scaled by r_i > 0 scales row i of J by r_i, so F_i/d_i is unchanged: the residual is the same (to
// rounding) for r_i = 1e±8. A change of units z = S y stated through c = S⁻¹·c0 gives the same residual in y.
TEST(McpScaledResidual, IsInvariantUnderRowScalingAndUnderAStatedChangeOfUnits) {
  DenseMatrix J(2, 2);
  J << 4.0, -1.0, 0.5, 3.0;
  Vector z(2), F(2), l(2), u(2);
  z << 1.5, 1e-3;
  F << 2e-7, 0.25;
  l << 0.0, 0.0;
  u << kInf, kInf;
  Vector d;
  McpRowScales(J, Vector(), &d);
  const double reference = McpScaledResidual(z, F, l, u, d, Vector());
  EXPECT_GT(reference, 0.0);
  const Vector r = (Vector(2) << 1e8, 1e-8).finished();
  McpRowScales(r.asDiagonal() * J, Vector(), &d);
  EXPECT_NEAR(McpScaledResidual(z, r.asDiagonal() * F, l, u, d, Vector()), reference, 1e-14 * reference);
  // y = S⁻¹ z: F_y(y) = F(S y), J_y = J S, bounds S⁻¹l, S⁻¹u, units c = S⁻¹ (z's unit was 1).
  const Vector S = (Vector(2) << 1e4, 1e-4).finished();
  const Vector c = S.cwiseInverse();
  McpRowScales(J * S.asDiagonal(), c, &d);
  EXPECT_NEAR(McpScaledResidual(S.cwiseInverse().asDiagonal() * z, F, l, u, d, c), reference, 1e-14 * reference);
}

TEST(McpRowScales, ZeroRowsTakeTheLargestAndNonFiniteEntriesAreNotTrusted) {
  DenseMatrix J(3, 3);
  J << 0, 0, 0, 2, -7, 0, 0, 0, 0.5;
  Vector d;
  McpRowScales(J, Vector(), &d);
  EXPECT_EQ(d, (Vector(3) << 7.0, 7.0, 0.5).finished());
  McpRowScales(DenseMatrix::Zero(2, 2), Vector(), &d);
  EXPECT_EQ(d, Vector::Ones(2));
  J(2, 0) = std::nan("");
  McpRowScales(J, Vector(), &d);
  EXPECT_EQ(d[2], kInf);
  const Vector z = Vector::Ones(3), F = Vector::Zero(3), l = Vector::Zero(3), u = Vector::Constant(3, kInf);
  EXPECT_EQ(McpScaledResidual(z, F, l, u, d, Vector()), kInf) << "a residual that cannot be trusted never passes";
}

TEST(MCPValidation, VariableScaleMustBePositiveFiniteAndOfTheProblemsSize) {
  FunctionMCP mcp(
      Vector::Zero(2), Vector::Constant(2, kInf), [](const Vector& z, Vector* F) { *F = z; },
      [](const Vector&, DenseMatrix* J) { J->setIdentity(); });
  EXPECT_THAT(ErrorOf([&] { mcp.set_variable_scale(Vector::Ones(3)); }), HasSubstr("variable_scale has size 3"));
  EXPECT_THAT(ErrorOf([&] { mcp.set_variable_scale((Vector(2) << 1.0, 0.0).finished()); }),
              HasSubstr("variable_scale[1] = 0"));
  EXPECT_THAT(ErrorOf([&] { mcp.set_variable_scale((Vector(2) << kInf, 1.0).finished()); }),
              HasSubstr("variable_scale[0]"));
  mcp.set_variable_scale((Vector(2) << 2.0, 1e-3).finished());
  EXPECT_EQ(mcp.variable_scale()[1], 1e-3);
  mcp.set_variable_scale(Vector());
  EXPECT_EQ(mcp.variable_scale().size(), 0);
}

}  // namespace
}  // namespace smcbench
