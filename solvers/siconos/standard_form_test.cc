// The box-MLCP ↔ relay / standard-MLCP rewriting used by the Siconos adapters: exact in both directions, checked
// against problems with a known solution and by solving the rewritten problem with our own exact backend.
#include "solvers/siconos/standard_form.h"

#include <gtest/gtest.h>

#include "solvers/enumerative/enumerative_solver.h"
#include "solvers/generators/random_problems.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

constexpr double kInfinity = kInf;

// A 6-row problem with one row of each kind (free, lower, upper, box, fixed) plus a second box row.
BoxMLCP EveryRowKind() {
  DenseMatrix M(6, 6);
  M << 4, 1, 0, 0.5, 0, 0.2,  //
      1, 5, 1, 0, 0.3, 0,     //
      0, 1, 6, 1, 0, 0.1,     //
      0.5, 0, 1, 5, 1, 0,     //
      0, 0.3, 0, 1, 4, 1,     //
      0.2, 0, 0.1, 0, 1, 3;
  Vector q(6);
  q << 1, -2, 3, -4, 0.5, 2;
  Vector l(6), u(6);
  l << -kInfinity, 0, -kInfinity, -1, 0.25, -2;
  u << kInfinity, kInfinity, 1, 1, 0.25, 3;
  return BoxMLCP(M, q, l, u, "every-row-kind");
}

// ‖standard-MLCP violation‖∞ of x: equality rows |w|, complementarity rows min(x, w) (natural map of the LCP).
double StandardViolation(const StandardForm& f, const Vector& x) {
  const Vector w = f.M() * x + f.q();
  double r = 0.0;
  for (int i = 0; i < f.size(); ++i) {
    r = std::max(r, i < f.num_equalities() ? std::abs(w[i]) : std::abs(std::min(x[i], w[i])));
  }
  return r;
}

TEST(StandardForm, CountsRowKinds) {
  const BoxMLCP p = EveryRowKind();
  const StandardForm::RowCounts c = StandardForm::Count(p.l(), p.u());
  EXPECT_EQ(c.free, 1);
  EXPECT_EQ(c.lower, 1);
  EXPECT_EQ(c.upper, 1);
  EXPECT_EQ(c.box, 2);
  EXPECT_EQ(c.fixed, 1);
  EXPECT_EQ(c.unbounded(), 3);
}

TEST(StandardForm, MixedFormPutsFreeRowsFirstAndDoublesBoxRows) {
  const BoxMLCP p = EveryRowKind();
  StandardForm f;
  f.Build(p, StandardForm::Kind::kMixed);
  EXPECT_EQ(f.num_equalities(), 1);
  // 5 non-fixed rows + one multiplier per box row.
  EXPECT_EQ(f.size(), 7);
  EXPECT_EQ(f.num_complementarity(), 6);
  // Multiplier rows: [−1 on its box row's variable], q = u − l.
  EXPECT_DOUBLE_EQ(f.q()[5], 2.0);  // row 3: u − l = 1 − (−1)
  EXPECT_DOUBLE_EQ(f.q()[6], 5.0);  // row 5: 3 − (−2)
  EXPECT_DOUBLE_EQ(f.M()(5, 3), -1.0);
  EXPECT_DOUBLE_EQ(f.M()(3, 5), 1.0);
  // The upper-only row (row 2, variable 2) is negated on both sides: its diagonal keeps its sign.
  EXPECT_DOUBLE_EQ(f.M()(2, 2), 6.0);
  EXPECT_DOUBLE_EQ(f.M()(2, 1), -1.0);
}

TEST(StandardForm, KnownSolutionsMapToSolutionsAndBack) {
  int checked = 0;
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      GeneratorOptions g;
      g.size = 9;
      g.family = MatrixFamily::kNonsymmetricPMatrix;
      g.bounds = bounds;
      g.seed = seed;
      g.degenerate_fraction = 0.2;
      const GeneratedProblem gen = GenerateProblem(g);
      SCOPED_TRACE(gen.problem.name());
      for (StandardForm::Kind kind : {StandardForm::Kind::kMixed, StandardForm::Kind::kBox}) {
        if (kind == StandardForm::Kind::kBox &&
            StandardForm::Count(gen.problem.l(), gen.problem.u()).unbounded() > 0) {
          continue;
        }
        StandardForm f;
        f.Build(gen.problem, kind);
        Vector x, z;
        f.FromBox(gen.problem, gen.z_star, &x);
        f.ToBox(gen.problem, x, &z);
        EXPECT_LE((z - gen.z_star).cwiseAbs().maxCoeff(), 1e-14);
        if (kind == StandardForm::Kind::kMixed) {
          EXPECT_LE(StandardViolation(f, x), 1e-12) << "z* does not map to a solution of the standard MLCP";
        } else {
          // Box form: the same problem without fixed rows; its natural residual at x is the original one.
          const BoxMLCP reduced(f.M(), f.q(), f.lower(), f.upper());
          Vector w;
          EXPECT_LE(reduced.NaturalResidual(x, &w).abs, 1e-12);
        }
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 12 + 6);  // mixed for all, box for the relay and box families
}

TEST(StandardForm, SolutionsOfTheRewrittenProblemSolveTheOriginal) {
  // The other direction: solve the standard MLCP with our exact backend (as a box-MLCP with l = 0 or free rows)
  // and map back; every row kind, including fixed rows that the rewriting eliminates.
  const BoxMLCP p = EveryRowKind();
  StandardForm f;
  f.Build(p, StandardForm::Kind::kMixed);
  Vector l = Vector::Zero(f.size()), u = Vector::Constant(f.size(), kInfinity);
  for (int i = 0; i < f.num_equalities(); ++i) l[i] = -kInfinity;
  const BoxMLCP standard(f.M(), f.q(), l, u, "standard");
  EnumerativeSolver exact;
  SolverOptions options;
  options.tolerance = 1e-12;
  const SolveResult s = exact.Solve(standard, options);
  ASSERT_TRUE(s.solved()) << s.message;
  Vector z;
  f.ToBox(p, s.z, &z);
  Vector w;
  EXPECT_LE(p.NaturalResidual(z, &w).rel, 1e-11);
  EXPECT_DOUBLE_EQ(z[4], 0.25);  // the fixed row
  const SolveResult direct = exact.Solve(p, options);
  ASSERT_TRUE(direct.solved());
  EXPECT_LE((direct.z - z).cwiseAbs().maxCoeff(), 1e-9);  // positive definite M: the solution is unique
}

TEST(StandardForm, BoxFormRejectsUnboundedRowsAndDropsFixedOnes) {
  const BoxMLCP p = EveryRowKind();
  StandardForm f;
  EXPECT_THROW(f.Build(p, StandardForm::Kind::kBox), std::logic_error);
  DenseMatrix M(3, 3);
  M << 2, 1, 0, 1, 2, 1, 0, 1, 2;
  Vector q(3), l(3), u(3);
  q << 1, -1, 2;
  l << -1, 0.5, -1;
  u << 1, 0.5, 1;
  const BoxMLCP relay(M, q, l, u);
  f.Build(relay, StandardForm::Kind::kBox);
  ASSERT_EQ(f.size(), 2);
  // q̂ = q + M z̄ with z̄ = (0, 0.5, 0): the fixed row's contribution moves into q.
  EXPECT_DOUBLE_EQ(f.q()[0], 1.0 + 0.5);
  EXPECT_DOUBLE_EQ(f.q()[1], 2.0 + 0.5);
  EXPECT_DOUBLE_EQ(f.M()(1, 0), 0.0);
  EXPECT_DOUBLE_EQ(f.lower()[1], -1.0);
}

TEST(StandardForm, AllRowsFixedGivesAnEmptyProblem) {
  const BoxMLCP p(DenseMatrix::Identity(2, 2), Vector::Ones(2), Vector::Constant(2, 0.5), Vector::Constant(2, 0.5));
  StandardForm f;
  f.Build(p, StandardForm::Kind::kMixed);
  EXPECT_EQ(f.size(), 0);
  Vector z;
  f.ToBox(p, Vector(), &z);
  EXPECT_EQ(z, Vector::Constant(2, 0.5));
}

TEST(StandardForm, RebuildingTheSameShapeDoesNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  const BoxMLCP p = EveryRowKind();
  StandardForm f;
  Vector x, z;
  f.Build(p, StandardForm::Kind::kMixed);
  f.FromBox(p, Vector::Zero(6), &x);
  f.ToBox(p, x, &z);
  const long count = test_support::CountMallocs([&] {
    for (int k = 0; k < 5; ++k) {
      f.Build(p, StandardForm::Kind::kMixed);
      f.FromBox(p, z, &x);
      f.ToBox(p, x, &z);
    }
  });
  EXPECT_EQ(count, 0);
}

}  // namespace
}  // namespace smcbench
