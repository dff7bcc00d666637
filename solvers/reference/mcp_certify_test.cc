// CertifyMCP: solutions known in closed form recovered to quad accuracy, and the certificate each case earns.
#include "solvers/reference/mcp_certify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <utility>

namespace smcbench {
namespace {

Quad QuadSqrt(Quad x) {
  Quad r = std::sqrt(static_cast<double>(x));
  for (int i = 0; i < 3; ++i) r = (r + x / r) / 2;
  return r;
}
double QuadAbs(Quad x) { return static_cast<double>(x < 0 ? -x : x); }

// A test MCP from a polynomial F given once on quad (double evaluation converts through it).
class PolyMcp final : public ExtendedPrecisionMCP {
 public:
  using QuadF = std::function<void(const Quad*, Quad*)>;
  using QuadJ = std::function<void(const Quad*, Quad*)>;
  PolyMcp(Vector l, Vector u, QuadF F, QuadJ J, SolutionSetProperty property = SolutionSetProperty::kNone)
      : ExtendedPrecisionMCP(std::move(l), std::move(u), "poly"),
        F_(std::move(F)),
        J_(std::move(J)),
        property_(property) {}
  void Evaluate(const Vector& z, Vector* F) const override {
    std::vector<Quad> zq(z.data(), z.data() + z.size()), Fq(z.size());
    F_(zq.data(), Fq.data());
    for (int i = 0; i < size(); ++i) (*F)[i] = static_cast<double>(Fq[i]);
  }
  void JacobianDense(const Vector& z, DenseMatrix* J) const override {
    std::vector<Quad> zq(z.data(), z.data() + z.size()), Jq(z.size() * z.size());
    J_(zq.data(), Jq.data());
    J->resize(size(), size());
    for (int k = 0; k < size() * size(); ++k) J->data()[k] = static_cast<double>(Jq[k]);
  }
  void EvaluateQuad(const Quad* z, Quad* F) const override { F_(z, F); }
  void JacobianQuad(const Quad* z, Quad* J) const override { J_(z, J); }
  SolutionSetProperty solution_set_property() const override { return property_; }

 private:
  QuadF F_;
  QuadJ J_;
  SolutionSetProperty property_;
};

Vector Vec(std::initializer_list<double> v) {
  Vector out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

// Kojima–Shindo (MCPLIB kojshin): two solutions, (1, 0, 3, 0) and (√6/2, 0, 0, 1/2) (degenerate in row 3).
PolyMcp KojimaShindo() {
  return PolyMcp(
      Vector::Zero(4), Vector::Constant(4, kInf),
      [](const Quad* x, Quad* F) {
        F[0] = 3 * x[0] * x[0] + 2 * x[0] * x[1] + 2 * x[1] * x[1] + x[2] + 3 * x[3] - 6;
        F[1] = 2 * x[0] * x[0] + x[0] + x[1] * x[1] + 10 * x[2] + 2 * x[3] - 2;
        F[2] = 3 * x[0] * x[0] + x[0] * x[1] + 2 * x[1] * x[1] + 2 * x[2] + 9 * x[3] - 9;
        F[3] = x[0] * x[0] + 3 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 3;
      },
      [](const Quad* x, Quad* J) {  // column-major
        const Quad rows[4][4] = {{6 * x[0] + 2 * x[1], 2 * x[0] + 4 * x[1], 1, 3},
                                 {4 * x[0] + 1, 2 * x[1], 10, 2},
                                 {6 * x[0] + x[1], x[0] + 4 * x[1], 2, 9},
                                 {2 * x[0], 6 * x[1], 2, 3}};
        for (int i = 0; i < 4; ++i) {
          for (int j = 0; j < 4; ++j) J[i + 4 * j] = rows[i][j];
        }
      });
}

TEST(McpCertifyTest, KojimaShindoBothSolutionsRecoveredToQuadAccuracy) {
  const PolyMcp p = KojimaShindo();
  // Rough candidates, as a backend stopping at 1e-6 would return them.
  const std::vector<Vector> candidates{Vec({1 + 1e-6, 0, 3 - 2e-6, 1e-7}), Vec({1.2247, 1e-7, 0, 0.5001})};
  const std::vector<McpCertifiedSolution> found = CertifyMCPSolutions(p, candidates);
  ASSERT_EQ(found.size(), 2u);
  const Quad exact[2][4] = {{1, 0, 3, 0}, {QuadSqrt(6) / 2, 0, 0, Quad(1) / 2}};
  for (int s = 0; s < 2; ++s) {
    SCOPED_TRACE(s);
    EXPECT_EQ(found[s].reference.certificate, Certificate::kNonUnique);
    for (int i = 0; i < 4; ++i) EXPECT_LT(QuadAbs(found[s].z[i] - exact[s][i]), 1e-30) << i;
    EXPECT_LE(found[s].margin, 1e-28);
    // The second has x3 = 0 with F3 = 3·(3/2) + 9·(1/2) − 9 = 0: degenerate.
    EXPECT_EQ(found[s].degenerate, s == 1);
    EXPECT_GT(found[s].reference.condition, 0.0);
  }
  EXPECT_EQ(CertifyMCP(p, candidates).certificate, Certificate::kNonUnique);
}

TEST(McpCertifyTest, OneSolutionWithoutAGlobalClaimIsIsolated) {
  const PolyMcp p = KojimaShindo();
  const ReferenceSolution r = CertifyMCP(p, {Vec({1.2, 0, 0, 0.5})});
  EXPECT_EQ(r.certificate, Certificate::kIsolated);
  EXPECT_NEAR(r.z[0], std::sqrt(6.0) / 2, 1e-15);
  EXPECT_EQ(r.z[1], 0.0);
}

// F(x) = x + x³ − 2 on x ≥ 0, declared a P-function (F' > 0): unique solution 1.
TEST(McpCertifyTest, DeclaredPFunctionWithStrictComplementarityIsUnique) {
  const PolyMcp p(
      Vector::Zero(1), Vector::Constant(1, kInf), [](const Quad* x, Quad* F) { F[0] = x[0] + x[0] * x[0] * x[0] - 2; },
      [](const Quad* x, Quad* J) { J[0] = 1 + 3 * x[0] * x[0]; }, SolutionSetProperty::kPFunction);
  const ReferenceSolution r = CertifyMCP(p, {Vec({5.0})});
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  EXPECT_EQ(r.z[0], 1.0);
  // One free row: μ = |F'/d| ⁻¹ = 1 (d = |F'| at z*).
  EXPECT_DOUBLE_EQ(r.condition, 1.0);
}

// F1 = x1 + x1³ − 2, F2 = x2 + x1² − 1 on x ≥ 0 (P-function): the solution (1, 0) has x2 = 0 and F2 = 0.
TEST(McpCertifyTest, DegenerateSolutionOfAPFunctionIsDegenerate) {
  const PolyMcp p(
      Vector::Zero(2), Vector::Constant(2, kInf),
      [](const Quad* x, Quad* F) {
        F[0] = x[0] + x[0] * x[0] * x[0] - 2;
        F[1] = x[1] + x[0] * x[0] - 1;
      },
      [](const Quad* x, Quad* J) { J[0] = 1 + 3 * x[0] * x[0], J[1] = 2 * x[0], J[2] = 0, J[3] = 1; },
      SolutionSetProperty::kPFunction);
  for (const Vector& candidate : {Vec({1.0, 0.0}), Vec({0.9, 1e-3}), Vec({1.1, 0.0})}) {
    const std::vector<McpCertifiedSolution> found = CertifyMCPSolutions(p, {candidate});
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].reference.certificate, Certificate::kDegenerate);
    EXPECT_TRUE(found[0].degenerate);
    EXPECT_LT(QuadAbs(found[0].z[0] - 1), 1e-32);
    EXPECT_LT(QuadAbs(found[0].z[1]), 1e-32);
  }
}

// F = M z + q with every row free (l = −∞, u = ∞): μ = ‖(D⁻¹M)⁻¹‖∞, D = diag(max_j |M_ij|). M = [[2, 1], [1, 3]]:
// D⁻¹M = [[1, 1/2], [1/3, 1]], inverse 6/5 [[1, −1/2], [−1/3, 1]], row sums 9/5 and 8/5.
TEST(McpCertifyTest, ConditionIsTheScaledReducedInverseNorm) {
  const PolyMcp p(
      Vector::Constant(2, -kInf), Vector::Constant(2, kInf),
      [](const Quad* z, Quad* F) {
        F[0] = 2 * z[0] + z[1] - 3;
        F[1] = z[0] + 3 * z[1] - 4;
      },
      [](const Quad*, Quad* J) { J[0] = 2, J[1] = 1, J[2] = 1, J[3] = 3; });
  const ReferenceSolution r = CertifyMCP(p, {Vec({0.0, 0.0})});
  EXPECT_EQ(r.certificate, Certificate::kIsolated);
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_EQ(r.z[1], 1.0);
  EXPECT_NEAR(r.condition, 1.8, 1e-15);
}

// A change of units z = S y stated through variable_scale leaves the certificate and μ unchanged and scales z*.
TEST(McpCertifyTest, VariableUnitsScaleTheAnswerAndKeepTheCondition) {
  const double s0 = 1e4, s1 = 1e-3;
  PolyMcp p(
      Vector::Constant(2, -kInf), Vector::Constant(2, kInf),
      [&](const Quad* z, Quad* F) {
        F[0] = 2 * (z[0] / s0) + z[1] / s1 - 3;
        F[1] = z[0] / s0 + 3 * (z[1] / s1) - 4;
      },
      [&](const Quad*, Quad* J) {
        J[0] = 2 / Quad(s0), J[1] = 1 / Quad(s0), J[2] = 1 / Quad(s1), J[3] = 3 / Quad(s1);
      });
  p.set_variable_scale(Vec({s0, s1}));
  const ReferenceSolution r = CertifyMCP(p, {Vec({0.0, 0.0})});
  EXPECT_EQ(r.certificate, Certificate::kIsolated);
  EXPECT_NEAR(r.z[0], s0, 1e-12 * s0);
  EXPECT_NEAR(r.z[1], s1, 1e-12 * s1);
  EXPECT_NEAR(r.condition, 1.8, 1e-14);
}

// Rows of F scaled by 1e8 and 1e-8: the same solutions, certificates and μ (the row scales absorb the factors).
TEST(McpCertifyTest, RowScalingOfFChangesNothing) {
  const Quad s[4] = {1e8, 1e-8, 1e8, 1e-8};
  const PolyMcp plain = KojimaShindo();
  const PolyMcp scaled(
      Vector::Zero(4), Vector::Constant(4, kInf),
      [&](const Quad* x, Quad* F) {
        KojimaShindo().EvaluateQuad(x, F);
        for (int i = 0; i < 4; ++i) F[i] *= s[i];
      },
      [&](const Quad* x, Quad* J) {
        KojimaShindo().JacobianQuad(x, J);
        for (int j = 0; j < 4; ++j) {
          for (int i = 0; i < 4; ++i) J[i + 4 * j] *= s[i];
        }
      });
  const std::vector<Vector> candidates{Vec({1, 0, 3, 0}), Vec({1.2247, 0, 0, 0.5})};
  const std::vector<McpCertifiedSolution> a = CertifyMCPSolutions(plain, candidates);
  const std::vector<McpCertifiedSolution> b = CertifyMCPSolutions(scaled, candidates);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(a[k].reference.certificate, b[k].reference.certificate);
    EXPECT_NEAR(a[k].reference.condition, b[k].reference.condition, 1e-12 * a[k].reference.condition);
    for (int i = 0; i < 4; ++i) EXPECT_LT(QuadAbs(a[k].z[i] - b[k].z[i]), 1e-30);
  }
}

// F2 = −1 − z1² − z2² < 0 on z ≥ 0: no solution; nothing verifies, wrong-size and NaN candidates are skipped.
TEST(McpCertifyTest, NoSolutionGivesNoneFound) {
  const PolyMcp p(
      Vector::Zero(2), Vector::Constant(2, kInf),
      [](const Quad* z, Quad* F) {
        F[0] = z[0] - z[1];
        F[1] = -1 - z[0] * z[0] - z[1] * z[1];
      },
      [](const Quad* z, Quad* J) { J[0] = 1, J[1] = -2 * z[0], J[2] = -1, J[3] = -2 * z[1]; });
  const ReferenceSolution r = CertifyMCP(p, {Vec({0, 0}), Vec({1, 1}), Vec({1e6, 1e6}), Vec({1}), Vec({kNaN, 0})});
  EXPECT_EQ(r.certificate, Certificate::kNoneFound);
  EXPECT_EQ(r.z.size(), 0);
  EXPECT_FALSE(r.verified());
}

// A sparse 1-D obstacle problem, −u″ + u³ = −10 above ψ, rows times h² (strongly monotone; tridiagonal J).
class SparseObstacle final : public ExtendedPrecisionMCP {
 public:
  explicit SparseObstacle(int n) : ExtendedPrecisionMCP(Obstacle(n), Vector::Constant(n, kInf), "obstacle") {}
  static Vector Obstacle(int n) {
    Vector psi(n);
    for (int i = 0; i < n; ++i) {
      const double x = (i + 1.0) / (n + 1.0) - 0.5;
      psi[i] = -0.05 - 0.5 * x * x;
    }
    return psi;
  }
  JacobianKind jacobian_kind() const override { return JacobianKind::kSparse; }
  SolutionSetProperty solution_set_property() const override { return SolutionSetProperty::kStronglyMonotone; }
  void Evaluate(const Vector& z, Vector* F) const override {
    std::vector<Quad> zq(z.data(), z.data() + z.size()), Fq(z.size());
    EvaluateQuad(zq.data(), Fq.data());
    for (int i = 0; i < size(); ++i) (*F)[i] = static_cast<double>(Fq[i]);
  }
  void EvaluateQuad(const Quad* z, Quad* F) const override {
    const int n = size();
    const Quad h2 = Quad(1) / ((n + 1) * (n + 1));
    for (int i = 0; i < n; ++i) {
      F[i] = 2 * z[i] + h2 * (z[i] * z[i] * z[i] + 10);
      if (i > 0) F[i] -= z[i - 1];
      if (i + 1 < n) F[i] -= z[i + 1];
    }
  }
  void JacobianQuad(const Quad* z, Quad* J) const override {
    const int n = size();
    const Quad h2 = Quad(1) / ((n + 1) * (n + 1));
    for (int k = 0; k < n * n; ++k) J[k] = 0;
    for (int i = 0; i < n; ++i) {
      J[i + i * n] = 2 + 3 * h2 * z[i] * z[i];
      if (i > 0) J[i + (i - 1) * n] = -1;
      if (i + 1 < n) J[i + (i + 1) * n] = -1;
    }
  }
};

// The banded path (n above max_size) certifies the same solution, certificate and μ as the dense path: for this
// M-matrix reduced Jacobian ‖A⁻¹‖∞ = ‖A⁻¹e‖∞.
TEST(McpCertifyTest, BandedPathAgreesWithTheDensePath) {
  const SparseObstacle p(100);
  const std::vector<Vector> candidates{p.l()};
  McpCertifyOptions dense;
  dense.max_size = 100;
  const std::vector<McpCertifiedSolution> a = CertifyMCPSolutions(p, candidates, dense);
  const std::vector<McpCertifiedSolution> b = CertifyMCPSolutions(p, candidates);
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(a[0].reference.certificate, Certificate::kUnique);
  EXPECT_EQ(b[0].reference.certificate, Certificate::kUnique);
  EXPECT_NEAR(a[0].reference.condition, b[0].reference.condition, 1e-20 * a[0].reference.condition);
  EXPECT_GT(a[0].reference.condition, 1.0);
  for (int i = 0; i < 100; ++i) EXPECT_LT(QuadAbs(a[0].z[i] - b[0].z[i]), 1e-30) << i;
  // Some rows touch the obstacle, some do not.
  int contact = 0;
  for (int i = 0; i < 100; ++i) contact += b[0].reference.z[i] == p.l()[i];
  EXPECT_GT(contact, 0);
  EXPECT_LT(contact, 100);
}

TEST(McpCertifyTest, LargerThanMaxSizeIsNotAttempted) {
  const PolyMcp p(
      Vector::Zero(1), Vector::Constant(1, kInf), [](const Quad* x, Quad* F) { F[0] = x[0] - 1; },
      [](const Quad*, Quad* J) { J[0] = 1; });
  McpCertifyOptions options;
  options.max_size = 0;
  EXPECT_EQ(CertifyMCP(p, {Vec({1.0})}, options).certificate, Certificate::kNone);
}

}  // namespace
}  // namespace smcbench
