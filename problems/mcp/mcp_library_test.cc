// The built-in MCPs: formulas at the published solutions, Jacobians against finite differences, sparse against
// dense, quad against double, the captured steps against the stepper's own one-step MCP, the suite's ids, its
// validation and the certificate every classic problem earns.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "problems/mcp/builtin_entry.h"
#include "problems/mcp/classic_mcps.h"
#include "problems/mcp/mcp_families.h"
#include "problems/mcp/mcp_suite.h"
#include "problems/mcp/scalar_math.h"
#include "problems/mcp/scene_step_mcps.h"
#include "problems/stepper/nonlinear_scenes.h"

namespace smcbench {
namespace {

double Abs(Quad x) { return static_cast<double>(x < 0 ? -x : x); }

// McpScaledResidual with the Jacobian at z: the MCP verdict's measure, computed here.
double ScaledResidual(const MCP& p, const Vector& z) {
  Vector F(p.size()), d;
  p.Evaluate(z, &F);
  DenseMatrix J;
  p.JacobianDense(z, &J);
  McpRowScales(J, p.variable_scale(), &d);
  return McpScaledResidual(z, F, p.l(), p.u(), d, p.variable_scale());
}

// A point strictly inside the box: l + U(0.05, 2)(1 + |l|) for a lower bound only, uniform between two bounds.
Vector RandomInside(const MCP& p, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> unit(0.05, 0.95), wide(0.05, 2.0), free(-2.0, 2.0);
  Vector z(p.size());
  for (int i = 0; i < p.size(); ++i) {
    const double l = p.l()[i], u = p.u()[i];
    if (l == u)
      z[i] = l;
    else if (l > -kInf && u < kInf)
      z[i] = l + unit(*rng) * (u - l);
    else if (l > -kInf)
      z[i] = l + wide(*rng) * (1 + std::abs(l));
    else if (u < kInf)
      z[i] = u - wide(*rng) * (1 + std::abs(u));
    else
      z[i] = free(*rng);
  }
  return z;
}

std::vector<std::string> AllQuickIds() { return McpSuiteIds(true); }

TEST(McpLibraryTest, IdsAreStable) {
  // The scene steps: S9 arrives on x = 0 at step 9 (x0 = 1.5, h = 0.1: t* = ln 2.5 ≈ 0.92), S10 at step 92
  // (t* = 14/3, h = 0.05); each is captured at its first step and the steps before, at and after the arrival.
  const std::vector<std::string> expected{
      "mcp/classic/kojshin",        "mcp/classic/josephy",       "mcp/classic/mathiesen",
      "mcp/classic/nash5",          "mcp/classic/nash10",        "mcp/classic/exchange",
      "mcp/classic/billups",        "mcp/hard/degenerate",       "mcp/hard/three-solutions",
      "mcp/hard/no-solution",       "mcp/hard/undefined-outside", "mcp/obstacle1d/n32",
      "mcp/obstacle2d/m8",          "mcp/bratu1d/n32",           "mcp/bratu2d/m8",
      "mcp/scene/hypomonotone/k0",  "mcp/scene/hypomonotone/k8", "mcp/scene/hypomonotone/k9",
      "mcp/scene/hypomonotone/k10", "mcp/scene/arctan/k0",       "mcp/scene/arctan/k91",
      "mcp/scene/arctan/k92",       "mcp/scene/arctan/k93"};
  EXPECT_EQ(McpSuiteIds(true), expected);
  const std::vector<std::string> full = McpSuiteIds(false);
  EXPECT_EQ(full.size(), expected.size() + 7);
  for (const std::string& id : full) {
    EXPECT_EQ(MakeBuiltinMcpProblem(id).id, id);
  }
}

TEST(McpLibraryTest, UnknownIdsAreErrorsNamingCloseIds) {
  try {
    MakeBuiltinMcp("mcp/classic/kojshn");
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("mcp/classic/kojshin"), std::string::npos) << e.what();
  }
  EXPECT_THROW(MakeBuiltinMcp("mcp/obstacle1d/n0"), InvalidInputError);
  EXPECT_THROW(MakeBuiltinMcp("mcp/obstacle2d/mabc"), InvalidInputError);
  EXPECT_THROW(MakeBuiltinMcp("mcp/scene/arctan/k100000"), InvalidInputError);
  EXPECT_EQ(MakeBuiltinMcp("mcp/obstacle2d/m3")->size(), 9);
}

// The published (exact) solutions satisfy complementarity to rounding; the Cournot game's published 5 digits to
// that accuracy.
TEST(McpLibraryTest, PublishedSolutionsSatisfyComplementarity) {
  const std::map<std::string, double> tolerance{{"mcp/classic/nash5", 1e-4}};
  int checked = 0;
  for (const std::string& id : AllQuickIds()) {
    if (id.rfind("mcp/scene/", 0) == 0) continue;
    BuiltinMcpEntry entry;
    ASSERT_TRUE(MakeClassicMcp(id, &entry) || MakeFamilyMcp(id, &entry)) << id;
    const auto it = tolerance.find(id);
    for (const Vector& z : entry.known_solutions) {
      EXPECT_LE(ScaledResidual(*entry.problem.problem, z), it == tolerance.end() ? 1e-15 : it->second) << id;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 12);
}

TEST(McpLibraryTest, JacobiansMatchCentralDifferencesAndQuadMatchesDouble) {
  std::mt19937_64 rng(20261126);
  std::vector<std::string> ids = AllQuickIds();
  ids.push_back("mcp/obstacle2d/m3");
  for (const std::string& id : ids) {
    SCOPED_TRACE(id);
    const std::shared_ptr<const MCP> p = MakeBuiltinMcp(id);
    const auto* quad = dynamic_cast<const ExtendedPrecisionMCP*>(p.get());
    ASSERT_NE(quad, nullptr);
    const int n = p->size();
    for (int trial = 0; trial < 3; ++trial) {
      const Vector z = RandomInside(*p, &rng);
      DenseMatrix J;
      p->JacobianDense(z, &J);
      Vector Fp(n), Fm(n), F(n);
      p->Evaluate(z, &F);
      for (int j = 0; j < n; ++j) {
        const double step = 1e-6 * (1 + std::abs(z[j]));
        Vector zp = z, zm = z;
        zp[j] += step, zm[j] -= step;
        p->Evaluate(zp, &Fp);
        p->Evaluate(zm, &Fm);
        for (int i = 0; i < n; ++i) {
          const double fd = (Fp[i] - Fm[i]) / (2 * step);
          EXPECT_NEAR(J(i, j), fd, 1e-5 * (1 + std::abs(J(i, j)) + std::abs(F[i]))) << i << "," << j;
        }
      }
      std::vector<Quad> zq(z.data(), z.data() + n), Fq(n), Jq(static_cast<std::size_t>(n) * n);
      quad->EvaluateQuad(zq.data(), Fq.data());
      quad->JacobianQuad(zq.data(), Jq.data());
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(static_cast<double>(Fq[i]), F[i], 1e-13 * (1 + std::abs(F[i]))) << i;
        for (int j = 0; j < n; ++j)
          EXPECT_NEAR(static_cast<double>(Jq[i + j * n]), J(i, j), 1e-13 * (1 + std::abs(J(i, j))));
      }
    }
  }
}

TEST(McpLibraryTest, FamiliesSparseJacobianEqualsDenseAndKeepsItsPattern) {
  std::mt19937_64 rng(7);
  for (const char* id :
       {"mcp/obstacle1d/n32", "mcp/obstacle2d/m8", "mcp/bratu1d/n32", "mcp/bratu2d/m8", "mcp/obstacle2d/m100"}) {
    SCOPED_TRACE(id);
    const std::shared_ptr<const MCP> p = MakeBuiltinMcp(id);
    EXPECT_EQ(p->jacobian_kind(), MCP::JacobianKind::kSparse);
    SparseMatrix S;
    p->JacobianSparse(RandomInside(*p, &rng), &S);
    const Eigen::Index nnz = S.nonZeros();
    const Vector z = RandomInside(*p, &rng);
    p->JacobianSparse(z, &S);
    EXPECT_EQ(S.nonZeros(), nnz);
    if (p->size() <= 1024) {
      DenseMatrix D;
      p->JacobianDense(z, &D);
      EXPECT_EQ((DenseMatrix(S) - D).cwiseAbs().maxCoeff(), 0.0);
    }
  }
  EXPECT_EQ(MakeBuiltinMcp("mcp/obstacle2d/m100")->size(), 10000);
  EXPECT_EQ(MakeBuiltinMcp("mcp/obstacle1d/n10000")->size(), 10000);
}

// The captured steps are the stepper's own OneStepMCP at (t_k, x_k): the same F and J.
TEST(McpLibraryTest, SceneStepsEqualTheStepperOneStepMcp) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(-3, 3), s(-1, 1);
  int checked = 0;
  for (const std::string& id : SceneStepMcpIds()) {
    SCOPED_TRACE(id);
    BuiltinMcpEntry entry;
    ASSERT_TRUE(MakeSceneStepMcp(id, &entry));
    const NonlinearScene scene = id.find("hypomonotone") != std::string::npos ? HypomonotoneScene() : ArctanScene();
    OneStepMCP reference(scene.system, scene.scheme);
    const double x_k = entry.problem.starts[0][0];
    reference.SetStep(0.0, Vector::Constant(1, x_k));
    for (int trial = 0; trial < 5; ++trial) {
      const Vector z = (Vector(2) << x(rng), s(rng)).finished();
      Vector F1(2), F2(2);
      DenseMatrix J1, J2(2, 2);
      entry.problem.problem->Evaluate(z, &F1);
      reference.Evaluate(z, &F2);
      entry.problem.problem->JacobianDense(z, &J1);
      reference.JacobianDense(z, &J2);
      EXPECT_NEAR((F1 - F2).cwiseAbs().maxCoeff(), 0.0, 1e-15);
      EXPECT_NEAR((J1 - J2).cwiseAbs().maxCoeff(), 0.0, 1e-15);
    }
    // The run's next state solves the captured MCP.
    EXPECT_LE(ScaledResidual(*entry.problem.problem, entry.known_solutions[0]), 1e-12);
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

TEST(McpLibraryTest, QuadElementaryFunctions) {
  using namespace mcp_math;
  const Quad two = 2;
  EXPECT_LT(Abs(Sqrt(two) * Sqrt(two) - 2), 1e-33);
  EXPECT_LT(Abs(Exp(Log(Quad(12345.678))) - Quad(12345.678)), 1e-28);
  EXPECT_LT(Abs(Log(Exp(Quad(-3.25))) + Quad(3.25)), 1e-32);
  EXPECT_LT(Abs(Pow(two, Quad(10)) - 1024), 1e-29);
  EXPECT_LT(Abs(Log(Quad(8)) - 3 * Ln2()), 1e-33);
  // Machin: π/4 = 4 atan(1/5) − atan(1/239).
  EXPECT_LT(Abs(Atan(Quad(1)) - (4 * Atan(Quad(1) / 5) - Atan(Quad(1) / 239))), 1e-33);
  EXPECT_NEAR(static_cast<double>(4 * Atan(Quad(1))), 3.14159265358979323846, 1e-15);
  EXPECT_TRUE(IsNan(Sqrt(Quad(-1))));
  EXPECT_TRUE(IsNan(Log(Quad(-1))));
}

TEST(McpLibraryTest, ValidateNamesTheFault) {
  McpProblemSet set;
  set.name = "t";
  set.problems.push_back(MakeBuiltinMcpProblem("mcp/classic/billups"));
  EXPECT_NO_THROW(set.Validate());
  set.problems.push_back(set.problems[0]);
  EXPECT_THROW(set.Validate(), InvalidInputError);
  set.problems[1].id = "other";
  set.problems[1].starts[0] = Vector::Zero(3);
  try {
    set.Validate();
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("starts[0] has size 3"), std::string::npos) << e.what();
  }
  set.problems[1].starts.clear();
  set.problems[1].start_labels.clear();
  EXPECT_THROW(set.Validate(), InvalidInputError);
}

// The quick suite: it validates, every reference solves its problem to rounding, and the certificate each classic
// and hard problem earns is the one its theory predicts.
TEST(McpLibraryTest, QuickSuiteValidatesWithCertifiedReferences) {
  const McpProblemSet suite = BuildMcpSuite(true);
  EXPECT_NO_THROW(suite.Validate());
  const std::map<std::string, std::vector<Certificate>> expected{
      {"mcp/classic/kojshin", {Certificate::kNonUnique, Certificate::kNonUnique}},
      {"mcp/classic/josephy", {Certificate::kIsolated}},
      {"mcp/classic/mathiesen", {Certificate::kUnique}},
      {"mcp/classic/nash5", {Certificate::kUnique}},
      {"mcp/classic/nash10", {Certificate::kUnique}},
      {"mcp/classic/exchange", {Certificate::kUnique}},
      {"mcp/classic/billups", {Certificate::kUnique}},
      {"mcp/hard/degenerate", {Certificate::kDegenerate}},
      {"mcp/hard/three-solutions", {Certificate::kNonUnique, Certificate::kNonUnique, Certificate::kNonUnique}},
      {"mcp/hard/no-solution", {}},
      {"mcp/hard/undefined-outside", {Certificate::kUnique}},
      {"mcp/obstacle1d/n32", {Certificate::kUnique}},
      {"mcp/obstacle2d/m8", {Certificate::kUnique}},
      {"mcp/bratu1d/n32", {Certificate::kUnique}},
      {"mcp/bratu2d/m8", {Certificate::kUnique}},
  };
  for (const McpLibraryProblem& p : suite.problems) {
    SCOPED_TRACE(p.id);
    for (const ReferenceSolution& r : p.references) {
      EXPECT_TRUE(r.verified());
      EXPECT_LE(ScaledResidual(*p.problem, r.z), 1e-15);
    }
    const auto it = expected.find(p.id);
    if (it == expected.end()) {
      EXPECT_FALSE(p.references.empty()) << "scene step without a reference";
      continue;
    }
    std::vector<Certificate> got;
    for (const ReferenceSolution& r : p.references) got.push_back(r.certificate);
    EXPECT_EQ(got, it->second);
    EXPECT_EQ(p.references_complete, p.id != "mcp/classic/josephy") << p.metadata.at("certificates");
  }
  // The Cournot games' references agree with the published digits.
  for (const McpLibraryProblem& p : suite.problems) {
    if (p.id != "mcp/classic/nash5") continue;
    const double published[5] = {36.933, 41.818, 43.707, 42.659, 39.179};
    ASSERT_EQ(p.references.size(), 1u);
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(p.references[0].z[i], published[i], 1e-3);
  }
}

// A large family size gets its reference through the certifier's banded path (tridiagonal here).
TEST(McpLibraryTest, LargeSparseFamilyGetsABandedReference) {
  McpLibraryProblem p = MakeBuiltinMcpProblem("mcp/obstacle1d/n1000");
  AttachMcpReferences(&p);
  ASSERT_EQ(p.references.size(), 1u);
  EXPECT_EQ(p.references[0].certificate, Certificate::kUnique);
  EXPECT_TRUE(p.references_complete);
  EXPECT_LE(ScaledResidual(*p.problem, p.references[0].z), 1e-15);
}

}  // namespace
}  // namespace smcbench
