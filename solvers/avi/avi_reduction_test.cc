// The reduction AVI ↔ box-MLCP tested both ways: its blocks against the formula, planted AVI solutions as
// solutions of the reduced problem (residual ≈ 0, both scalings), the exhaustive backend's solutions of the reduced
// problem as AVI solutions (KKT conditions recomputed here), and box-MLCPs written as AVIs against the box
// backends' answers.
#include "solvers/avi/avi_reduction.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solvers/avi/avi_solver.h"
#include "solvers/avi/planted_avi_test_util.h"
#include "solvers/generators/random_problems.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// The KKT conditions of the AVI at (λ, μ, ν), computed here from the stated data: stationarity
// ‖Mλ + q − Hᵀμ − Eᵀν‖∞, and the worst of μ⁻, (K − Hλ)⁺, |μ_i·(H_iλ − K_i)|, |Eλ − f|.
struct Kkt {
  double stationarity;
  double complementarity;
};
Kkt KktOf(const AffineVI& avi, const AviSolution& s) {
  const Vector r = avi.M() * s.lambda + avi.q() - avi.H().transpose() * s.mu - avi.E().transpose() * s.nu;
  double c = 0.0;
  for (int i = 0; i < avi.inequality_count(); ++i) {
    const double slack = avi.H().row(i).dot(s.lambda) - avi.K()[i];
    c = std::max({c, -s.mu[i], -slack, std::abs(s.mu[i] * slack)});
  }
  for (int j = 0; j < avi.equality_count(); ++j) c = std::max(c, std::abs(avi.E().row(j).dot(s.lambda) - avi.f()[j]));
  return {r.size() ? r.cwiseAbs().maxCoeff() : 0.0, c};
}

TEST(AviReduction, BlocksAreTheStatedFormula) {
  DenseMatrix M(2, 2), H(3, 2), E(1, 2);
  M << 2, 1, -1, 3;
  H << 1, 0, 0, 4, -1, -1;
  E << 1, -2;
  const Vector q = Vector::LinSpaced(2, 1, 2), K = Vector::LinSpaced(3, -3, -1), f = Vector::Constant(1, 0.5);
  const AffineVI avi(M, q, H, K, E, f, "small");
  const AviReduction r = ReduceToBoxMlcp(avi, AviReductionScaling::kAsStated);
  ASSERT_EQ(r.problem.size(), 6);
  const DenseMatrix& R = r.problem.dense_matrix();
  EXPECT_EQ(R.topLeftCorner(2, 2), M);
  EXPECT_EQ(R.block(0, 2, 2, 3), -H.transpose());
  EXPECT_EQ(R.block(0, 5, 2, 1), -E.transpose());
  EXPECT_EQ(R.block(2, 0, 3, 2), H);
  EXPECT_EQ(R.block(5, 0, 1, 2), E);
  EXPECT_EQ(R.bottomRightCorner(4, 4), DenseMatrix::Zero(4, 4));
  EXPECT_EQ(r.problem.q().head(2), q);
  EXPECT_EQ(r.problem.q().segment(2, 3), -K);
  EXPECT_EQ(r.problem.q()[5], -0.5);
  for (int i : {0, 1, 5}) EXPECT_EQ(r.problem.l()[i], -kInf);
  for (int i : {2, 3, 4}) EXPECT_EQ(r.problem.l()[i], 0.0);
  EXPECT_TRUE((r.problem.u().array() == kInf).all());
  EXPECT_EQ(r.problem.name(), "small/reduced");

  // Normalized: σ = max|M_ij| = 3, h = (1, 4, 1), e = 2.
  const AviReduction s = ReduceToBoxMlcp(avi, AviReductionScaling::kNormalized);
  EXPECT_EQ(s.sigma, 3.0);
  Vector h(3);
  h << 1, 4, 1;
  EXPECT_EQ(s.inequality_scale, h);
  EXPECT_EQ(s.equality_scale[0], 2.0);
  EXPECT_EQ(s.problem.dense_matrix()(3, 1), 1.0);   // H(1,1)/4
  EXPECT_EQ(s.problem.dense_matrix()(1, 3), -1.0);  // −H(1,1)/4
  EXPECT_EQ(s.problem.q()[0], 1.0 / 3.0);
  EXPECT_EQ(ToString(AviReductionScaling::kNormalized), "normalized");
}

TEST(AviReduction, PlantedSolutionsSolveTheReduction) {
  for (const AviReductionScaling scaling : {AviReductionScaling::kAsStated, AviReductionScaling::kNormalized}) {
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      const PlantedAvi planted = MakePlantedAvi(5, 6, 3, 1, seed);
      const AviReduction r = ReduceToBoxMlcp(planted.avi, scaling);
      const Vector z = JoinReducedSolution(r, planted.solution);
      Vector w(r.problem.size());
      const Residual res = r.problem.NaturalResidual(z, &w);
      EXPECT_LE(res.rel, 1e-13) << planted.avi.name();
      EXPECT_LE(res.scaled, 1e-13) << planted.avi.name();
      // And back: the same (λ, μ, ν).
      const AviSolution back = SplitReducedSolution(r, z);
      EXPECT_LE((back.lambda - planted.solution.lambda).cwiseAbs().maxCoeff(), 1e-15);
      EXPECT_LE((back.mu - planted.solution.mu).cwiseAbs().maxCoeff(), 1e-14);
      EXPECT_LE((back.nu - planted.solution.nu).cwiseAbs().maxCoeff(), 1e-14);
    }
  }
}

TEST(AviReduction, SolutionsOfTheReductionSolveTheAvi) {
  // The exhaustive backend on the reduction, unscaled and normalized: every answer satisfies the AVI's KKT
  // conditions, and equals the planted λ* (unique: M + Mᵀ positive definite).
  const std::unique_ptr<Solver> solver = CreateSolver("enum");
  for (const AviReductionScaling scaling : {AviReductionScaling::kAsStated, AviReductionScaling::kNormalized}) {
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      const PlantedAvi planted = MakePlantedAvi(3, 4, 2, static_cast<int>(seed % 2), seed);
      const AviReduction r = ReduceToBoxMlcp(planted.avi, scaling);
      const SolveResult result = solver->Solve(r.problem);
      ASSERT_TRUE(result.solved()) << planted.avi.name() << ": " << result.message;
      const AviSolution s = SplitReducedSolution(r, result.z);
      const Kkt kkt = KktOf(planted.avi, s);
      EXPECT_LE(kkt.stationarity, 1e-9) << planted.avi.name();
      EXPECT_LE(kkt.complementarity, 1e-9) << planted.avi.name();
      EXPECT_LE((s.lambda - planted.solution.lambda).cwiseAbs().maxCoeff(), 1e-9) << planted.avi.name();
    }
  }
}

TEST(AviReduction, SizeErrorsNameTheField) {
  const PlantedAvi planted = MakePlantedAvi(2, 1, 1, 0, 3);
  const AviReduction r = ReduceToBoxMlcp(planted.avi);
  EXPECT_THROW(SplitReducedSolution(r, Vector::Zero(3)), InvalidInputError);
  try {
    JoinReducedSolution(r, {Vector::Zero(2), Vector::Zero(2), {}});
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("mu has size 2 but the AVI has 5"));
  }
  // Empty multipliers are zeros.
  const Vector z = JoinReducedSolution(r, {planted.solution.lambda, {}, {}});
  EXPECT_EQ(z.tail(5), Vector::Zero(5));
}

TEST(AviFromBox, RowsOfTheBoxAndBack) {
  DenseMatrix M(3, 3);
  M << 4, 1, 0, 1, 4, 1, 0, 1, 4;
  Vector q(3), l(3), u(3);
  q << -1, 2, 0.5;
  l << 0, -kInf, 2;
  u << kInf, 1, 2;  // LCP row, upper-only row, fixed row
  const BoxMLCP box(M, q, l, u, "mixed");
  const AffineVI avi = AviFromBox(box);
  ASSERT_EQ(avi.inequality_count(), 2);
  ASSERT_EQ(avi.equality_count(), 1);
  EXPECT_EQ(avi.H().row(0), Vector::Unit(3, 0).transpose());
  EXPECT_EQ(avi.K()[0], 0.0);
  EXPECT_EQ(avi.H().row(1), -Vector::Unit(3, 1).transpose());
  EXPECT_EQ(avi.K()[1], -1.0);
  EXPECT_EQ(avi.E().row(0), Vector::Unit(3, 2).transpose());
  EXPECT_EQ(avi.f()[0], 2.0);
  EXPECT_EQ(avi.name(), "mixed");
  SparseMatrix sparse = M.sparseView();
  EXPECT_THROW(AviFromBox(BoxMLCP(sparse, q, l, u)), InvalidInputError);
}

TEST(AviFromBox, BoxSolversAgreeWithTheAvi) {
  // P-matrix box-MLCPs with a planted unique z*: solved as boxes by lemke, and as AVIs (H = [I; −I]) by lemke and
  // enum through the reduction. λ = z*, and Hᵀμ + Eᵀν = Mz + q (the AVI's multipliers are the box's w split by
  // sign).
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  const std::unique_ptr<Solver> enumerative = CreateSolver("enum");
  for (const BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      GeneratorOptions g;
      g.size = 4;
      g.family = MatrixFamily::kNonsymmetricPMatrix;
      g.bounds = bounds;
      g.seed = seed;
      const GeneratedProblem generated = GenerateProblem(g);
      const BoxMLCP& box = generated.problem;
      const SolveResult direct = lemke->Solve(box);
      ASSERT_TRUE(direct.solved()) << box.name();
      const AffineVI avi = AviFromBox(box);
      for (Solver* solver : {lemke.get(), enumerative.get()}) {
        const AviResult result = SolveAvi(avi, *solver);
        ASSERT_TRUE(result.solved()) << box.name() << " " << result.solver << ": " << result.message;
        EXPECT_EQ(result.judgement.verdict, Verdict::kSolved) << box.name();
        EXPECT_LE((result.solution.lambda - generated.z_star).cwiseAbs().maxCoeff(), 1e-9) << box.name();
        EXPECT_LE((result.solution.lambda - direct.z).cwiseAbs().maxCoeff(), 1e-9) << box.name();
        const Vector w = box.dense_matrix() * result.solution.lambda + box.q();
        const Vector multipliers =
            avi.H().transpose() * result.solution.mu + avi.E().transpose() * result.solution.nu;
        EXPECT_LE((multipliers - w).cwiseAbs().maxCoeff(), 1e-9 * (1 + w.cwiseAbs().maxCoeff())) << box.name();
      }
    }
  }
}

}  // namespace
}  // namespace smcbench
