// Tests of the interval proof against solutions known exactly: integer matrices whose solution is a dyadic
// rational (exact in double), so the true distance of a perturbed point from z* is known here, hand-solved 2×2
// problems, the wrong active sets and degenerate rows it must refuse, and Certify's references it must prove.
#include "solvers/reference/enclosure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "solvers/generators/random_problems.h"
#include "solvers/reference/certify.h"
#include "tests/support/eigen_literals.h"

namespace smcbench {
namespace {

using test_support::Mat;
using test_support::Vec;

constexpr double kInf = std::numeric_limits<double>::infinity();

// An n×n integer matrix with a dominant diagonal (a P-matrix, nonsymmetric), and a solution z* whose entries are
// multiples of 1/8, free on the even rows and at a bound of [−1, 1] on the odd ones (w*_i = ±(1 + i)): q = w* − M z*
// is exact in double, so z* is the problem's exact (and only) solution.
struct Dyadic {
  BoxMLCP problem;
  Vector z_star;
};
Dyadic DyadicProblem(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> entry(-3, 3), eighths(-7, 7);
  DenseMatrix M(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) M(i, j) = i == j ? 4.0 * n : entry(rng);
  }
  Vector z(n), w(n);
  for (int i = 0; i < n; ++i) {
    const bool free_row = i % 2 == 0;
    const bool at_upper = i % 4 == 1;
    z[i] = free_row ? eighths(rng) / 8.0 : (at_upper ? 1.0 : -1.0);
    w[i] = free_row ? 0.0 : (at_upper ? -(1.0 + i) : 1.0 + i);
  }
  const Vector q = w - M * z;  // integers and eighths times small integers: exact
  return {BoxMLCP::Relay(M, q), z};
}

TEST(EncloseSolution, ProvesTheExactSolutionWithRadiusZeroOrTiny) {
  const Dyadic d = DyadicProblem(9, 1);
  const SolutionEnclosure e = EncloseSolution(d.problem, d.z_star);
  ASSERT_TRUE(e.proved) << e.why_not;
  EXPECT_GE(e.radius, 0.0);
  // z* is exact: only the a-priori bound of the quad sum's rounding (≈ 1e-32 relative) remains.
  EXPECT_LE(e.radius, 1e-28);
}

TEST(EncloseSolution, ItsRadiusCoversTheTrueDistanceOfAPerturbedPoint) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Dyadic d = DyadicProblem(4 + static_cast<int>(seed % 13), seed);
    Vector z = d.z_star;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> noise(-1e-7, 1e-7);
    for (int i = 0; i < z.size(); i += 2) z[i] += noise(rng);  // free rows only: the active set is kept
    const double distance = (z - d.z_star).lpNorm<Eigen::Infinity>();  // exact: z* is dyadic, z − z* too
    const SolutionEnclosure e = EncloseSolution(d.problem, z);
    ASSERT_TRUE(e.proved) << "seed " << seed << ": " << e.why_not;
    EXPECT_GE(e.radius, distance) << "seed " << seed;
    EXPECT_LE(e.radius, 10 * distance) << "seed " << seed;  // and not a vacuous bound
  }
}

TEST(EncloseSolution, ProvesAHandSolvedInteriorLcpSolution) {
  // M z = (1, 1): z* = (2/5, 1/5), not representable in double.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 3}}), Vec({-1, -1}));
  const Vector z = Vec({0.4, 0.2});
  const SolutionEnclosure e = EncloseSolution(p, z);
  ASSERT_TRUE(e.proved) << e.why_not;
  // |0.4 − 2/5| and |0.2 − 1/5| in long double (exact to far below the double rounding being measured).
  const long double d0 = std::abs(static_cast<long double>(0.4) - 2.0L / 5.0L);
  const long double d1 = std::abs(static_cast<long double>(0.2) - 1.0L / 5.0L);
  EXPECT_GE(static_cast<long double>(e.radius), std::max(d0, d1));
  EXPECT_LE(e.radius, 1e-15);
}

TEST(EncloseSolution, RefusesAPointOnTheWrongActiveSet) {
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 3}}), Vec({-1, -1}));
  const SolutionEnclosure e = EncloseSolution(p, Vec({0, 0}));  // w = q < 0 at the lower bound
  EXPECT_FALSE(e.proved);
  EXPECT_NE(e.why_not.find("row 0: at its lower bound"), std::string::npos) << e.why_not;
  // With u₀ = 0.3 the solution is (0.3, 7/30): row 0 at its upper bound (w₀ = −1/6), row 1 free. From the point
  // (0.3, 0.2), on that active set but 1/30 off in the free row, the enclosure still proves it, with a radius that
  // covers the 1/30; a point outside [l, u] is refused.
  const BoxMLCP boxed(Mat({{2, 1}, {1, 3}}), Vec({-1, -1}), Vec({0, 0}), Vec({0.3, kInf}));
  const SolutionEnclosure moved = EncloseSolution(boxed, Vec({0.3, 0.2}));
  ASSERT_TRUE(moved.proved) << moved.why_not;  // the solution (0.3, 7/30) is 1/30 away: inside the enclosure
  EXPECT_GE(moved.radius, 1.0 / 30 - 1e-15);
  EXPECT_FALSE(EncloseSolution(boxed, Vec({0.4, 0.2})).proved);  // outside [l, u]
}

TEST(EncloseSolution, ProvesAnExactDegenerateRowButNotAnInexactOne) {
  // w = z exactly at z = 0: degenerate (w = 0 at the bound), and exact, so proved.
  const BoxMLCP identity = BoxMLCP::LCP(Mat({{1, 0}, {0, 1}}), Vec({0, 0}));
  const SolutionEnclosure exact = EncloseSolution(identity, Vec({0, 0}));
  ASSERT_TRUE(exact.proved) << exact.why_not;
  EXPECT_EQ(exact.radius, 0.0);
  // z = (1, 0) solves M = [[2, 1], [1, 2]], q = (−2, −1) with w = (0, 0): row 1 is degenerate, and the free row's
  // enclosure (nonzero, however small) puts w₁ = 0 ± ε, whose sign cannot be proved.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 2}}), Vec({-2, -1}));
  const SolutionEnclosure e = EncloseSolution(p, Vec({1, 0}));
  EXPECT_FALSE(e.proved);
  EXPECT_NE(e.why_not.find("degenerate"), std::string::npos) << e.why_not;
}

TEST(EncloseSolution, RefusesASingularOrIllConditionedFreeBlock) {
  const BoxMLCP singular = BoxMLCP::LCP(Mat({{1, 1}, {1, 1}}), Vec({-1, -1}));
  const SolutionEnclosure s = EncloseSolution(singular, Vec({0.5, 0.5}));
  EXPECT_FALSE(s.proved);
  // Hilbert 13×13: condition ≈ 1e18, beyond double.
  const int n = 13;
  DenseMatrix H(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) H(i, j) = 1.0 / (i + j + 1);
  }
  const Vector z = Vector::Constant(n, 0.5);
  const BoxMLCP hilbert(H, -H * z, Vector::Constant(n, -kInf), Vector::Constant(n, kInf));
  const SolutionEnclosure h = EncloseSolution(hilbert, z);
  EXPECT_FALSE(h.proved);
  EXPECT_NE(h.why_not.find("free block"), std::string::npos) << h.why_not;
}

TEST(EncloseSolution, RefusesPointsItCannotUse) {
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 3}}), Vec({-1, -1}));
  EXPECT_FALSE(EncloseSolution(p, Vec({0.4})).proved);
  EXPECT_FALSE(EncloseSolution(p, Vec({std::nan(""), 0.2})).proved);
  const SolutionEnclosure outside = EncloseSolution(p, Vec({-0.1, 0.2}));
  EXPECT_FALSE(outside.proved);
  EXPECT_NE(outside.why_not.find("outside [l, u]"), std::string::npos) << outside.why_not;
  const int n = kMaxEnclosureSize + 1;
  const BoxMLCP large = BoxMLCP::LCP(DenseMatrix::Identity(n, n), Vector::Ones(n));
  EXPECT_FALSE(EncloseSolution(large, Vector::Zero(n)).proved);
}

TEST(EncloseSolution, ProvesCertifiedReferencesOfGeneratedProblems) {
  // Certify attaches the radius; it is recomputed here, and the reference's distance from the generator's own
  // planted solution (a P-matrix: the only one) is within it up to the planted z*'s own rounding.
  const MatrixFamily families[] = {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix};
  const BoundKind bounds[] = {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed};
  int proved = 0;
  for (MatrixFamily family : families) {
    for (BoundKind bound : bounds) {
      GeneratorOptions g;
      g.size = 24;
      g.family = family;
      g.bounds = bound;
      const GeneratedProblem generated = GenerateProblem(g);
      const ReferenceSolution reference = Certify(generated.problem, {generated.z_star});
      ASSERT_TRUE(reference.verified()) << generated.problem.name();
      const SolutionEnclosure e = EncloseSolution(generated.problem, reference.z);
      ASSERT_TRUE(e.proved) << generated.problem.name() << ": " << e.why_not;
      EXPECT_EQ(reference.proved_radius, e.radius) << generated.problem.name();
      EXPECT_LE(e.radius, 1e-12 * (1 + reference.z.lpNorm<Eigen::Infinity>())) << generated.problem.name();
      ++proved;
    }
  }
  EXPECT_EQ(proved, 6);
}

TEST(EncloseSolution, CertifyLeavesTheRadiusNaNWhereNothingIsProved) {
  // The degenerate solution z = (1, 0) above: Certify verifies it (degenerate, unique), the enclosure cannot.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 2}}), Vec({-2, -1}));
  const ReferenceSolution reference = Certify(p, {Vec({1, 0})});
  EXPECT_EQ(reference.certificate, Certificate::kDegenerate);
  EXPECT_TRUE(std::isnan(reference.proved_radius));
  EXPECT_TRUE(std::isnan(ReferenceSolution{}.proved_radius));
}

TEST(ProveSymmetricPartPositiveDefinite, ProvesKnownDefiniteParts) {
  EXPECT_TRUE(ProveSymmetricPartPositiveDefinite(Mat({{2, 1}, {1, 3}})));
  // Nonsymmetric, with M + Mᵀ = 2I: the skew part does not matter.
  EXPECT_TRUE(ProveSymmetricPartPositiveDefinite(Mat({{1, 5}, {-5, 1}})));
  // The dyadic problems' diagonally dominant M (4n on the diagonal, |off| ≤ 3): Gershgorin, so their symmetric part
  // is positive definite.
  EXPECT_TRUE(ProveSymmetricPartPositiveDefinite(DyadicProblem(40, 3).problem.dense_matrix()));
  // The 1-D Laplacian tridiag(−1, 2, −1) of size 64: λ_min = 2 − 2cos(π/65) ≈ 2.3e-3, far above the rounding.
  const int n = 64;
  DenseMatrix T = DenseMatrix::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    T(i, i) = 2;
    if (i > 0) T(i, i - 1) = T(i - 1, i) = -1;
  }
  EXPECT_TRUE(ProveSymmetricPartPositiveDefinite(T));
}

TEST(ProveSymmetricPartPositiveDefinite, RefusesWhatIsNotOrTooNearlyNotDefinite) {
  EXPECT_FALSE(ProveSymmetricPartPositiveDefinite(Mat({{1, 2}, {2, 1}})));   // eigenvalues 3, −1
  EXPECT_FALSE(ProveSymmetricPartPositiveDefinite(Mat({{1, 1}, {1, 1}})));   // singular
  EXPECT_FALSE(ProveSymmetricPartPositiveDefinite(Mat({{0, 1}, {-1, 0}})));  // skew: M + Mᵀ = 0
  // λ_min = 1e-17 relative: positive definite in exact arithmetic, but below what a double Cholesky can prove.
  EXPECT_FALSE(ProveSymmetricPartPositiveDefinite(Mat({{1, 1}, {1, 1 + 1e-16}})));
  EXPECT_FALSE(ProveSymmetricPartPositiveDefinite(Mat({{1, std::nan("")}, {0, 1}})));
  const int n = kMaxEnclosureSize + 1;
  EXPECT_FALSE(ProveSymmetricPartPositiveDefinite(DenseMatrix::Identity(n, n)));
}

TEST(ProveSymmetricPartPositiveDefinite, CertifyMarksTheProvedUniqueReferences) {
  GeneratorOptions g;
  g.size = 16;
  g.family = MatrixFamily::kSymmetricPositiveDefinite;
  const ReferenceSolution spd = Certify(GenerateProblem(g).problem, {GenerateProblem(g).z_star});
  EXPECT_FALSE(std::isnan(spd.proved_radius));
  EXPECT_TRUE(spd.proved_unique);
  // An LCP whose M has an indefinite symmetric part (a P-matrix all the same: [[1, 4], [0, 1]] has minors 1, 1, 1):
  // its solution is proved, its uniqueness is not by this test.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{1, 4}, {0, 1}}), Vec({-1, -1}));
  const ReferenceSolution r = Certify(p, {Vec({0, 1})});
  ASSERT_TRUE(r.verified());
  EXPECT_FALSE(std::isnan(r.proved_radius));
  EXPECT_FALSE(r.proved_unique);
}

}  // namespace
}  // namespace smcbench
