// Tests of the extended-precision certification against facts known independently of it: hand-solved 1×1 and
// 2×2 problems, the same problems rescaled, planted solutions of time-step problems W = h·G, problems with a
// segment of solutions or none, a condition number known by construction, and the matrix classes that decide
// uniqueness. Every verified z is re-checked with a residual computed here in long double.
#include "solvers/reference/certify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <random>
#include <vector>

#include "tests/support/eigen_literals.h"

namespace smcbench {
namespace {

using test_support::Mat;
using test_support::Vec;

Vector Filled(int n, double value) { return Vector::Constant(n, value); }

// ‖z − Π_[l,u](z − w_i/d_i)‖∞ with w = M z + q in long double and d_i = max_j |M_ij| (1 for a zero row): the
// equilibrated natural residual, computed here without the library.
long double ScaledResidual(const BoxMLCP& p, const Vector& z) {
  const DenseMatrix& M = p.dense_matrix();
  long double r = 0;
  for (int i = 0; i < p.size(); ++i) {
    long double w = p.q()[i], d = 0;
    for (int j = 0; j < p.size(); ++j) {
      w += static_cast<long double>(M(i, j)) * z[j];
      d = std::max(d, std::abs(static_cast<long double>(M(i, j))));
    }
    if (d == 0) d = 1;
    const long double y = std::min<long double>(std::max<long double>(z[i] - w / d, p.l()[i]), p.u()[i]);
    r = std::max(r, std::abs(z[i] - y));
  }
  return r;
}

void ExpectSolution(const BoxMLCP& p, const ReferenceSolution& r, long double tol = 1e-15L) {
  ASSERT_TRUE(r.verified()) << "certificate " << static_cast<int>(r.certificate);
  ASSERT_EQ(r.z.size(), p.size());
  EXPECT_LE(ScaledResidual(p, r.z), tol * (1 + r.z.cwiseAbs().maxCoeff()));
}

// ---------------------------------------------------------------------------------------------------------
// Hand-solved problems.

TEST(CertifyTest, RelayOneRow) {
  // 2z + 1 = 0 at z = −0.5, inside [−1, 1]: the only solution; D⁻¹M = [1], so μ = 1.
  const BoxMLCP p = BoxMLCP::Relay(Mat({{2}}), Vec({1}));
  const ReferenceSolution r = Certify(p, {});
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  ExpectSolution(p, r);
  EXPECT_EQ(r.z[0], -0.5);
  EXPECT_DOUBLE_EQ(r.condition, 1.0);
}

TEST(CertifyTest, LcpTwoByTwo) {
  // Both rows free: [[2,1],[1,2]] z = (1,1) gives z = (1/3, 1/3) > 0. D⁻¹M = [[1,½],[½,1]], inverse
  // (4/3)[[1,−½],[−½,1]]: μ = 2.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 2}}), Vec({-1, -1}));
  const ReferenceSolution r = Certify(p, {});
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  ExpectSolution(p, r);
  EXPECT_EQ(r.z[0], 1.0 / 3.0);
  EXPECT_EQ(r.z[1], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(r.condition, 2.0);
}

TEST(CertifyTest, DegenerateLcp) {
  // z ≥ 0, w = z: only z = 0, where w = 0 too. μ is 0 with the row bound and 1 with it free: the larger counts.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{1}}), Vec({0}));
  const ReferenceSolution r = Certify(p, {});
  EXPECT_EQ(r.certificate, Certificate::kDegenerate);
  ExpectSolution(p, r);
  EXPECT_EQ(r.z[0], 0.0);
  EXPECT_DOUBLE_EQ(r.condition, 1.0);
}

TEST(CertifyTest, RowAtUpperBound) {
  // Relay M = [1], q = −3: z = 3 is outside [−1, 1], so z = 1 with w = −2 ≤ 0; strictly complementary, no free row.
  const BoxMLCP p = BoxMLCP::Relay(Mat({{1}}), Vec({-3}));
  const ReferenceSolution r = Certify(p, {});
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_EQ(r.condition, 0.0);
}

// ---------------------------------------------------------------------------------------------------------
// Scaling: a positive row scaling, or scaling (M, q) together, changes neither z* nor the certificate.

TEST(CertifyTest, BadlyScaledProblemsGiveTheSameAnswer) {
  const DenseMatrix M = Mat({{2, 1}, {1, 2}});
  const Vector q = Vec({-1, -1});
  const ReferenceSolution base = Certify(BoxMLCP::LCP(M, q), {});
  ASSERT_EQ(base.certificate, Certificate::kUnique);
  const Vector rows = Vec({1e6, 1e-5});
  for (const double whole : {1.0, 1e-150, 1e150}) {
    const BoxMLCP p = BoxMLCP::LCP(whole * (rows.asDiagonal() * M), whole * rows.cwiseProduct(q));
    const ReferenceSolution r = Certify(p, {});
    EXPECT_EQ(r.certificate, Certificate::kUnique) << whole;
    EXPECT_EQ(r.z[0], 1.0 / 3.0) << whole;
    EXPECT_EQ(r.z[1], 1.0 / 3.0) << whole;
    EXPECT_NEAR(r.condition, base.condition, 1e-12) << whole;
  }
  for (const double whole : {1e-150, 1e150}) {
    const ReferenceSolution r = Certify(BoxMLCP::Relay(Mat({{2 * whole}}), Vec({whole})), {});
    EXPECT_EQ(r.certificate, Certificate::kUnique) << whole;
    EXPECT_EQ(r.z[0], -0.5) << whole;
  }
}

// ---------------------------------------------------------------------------------------------------------
// Time-step problems W = h·G with a planted solution s*.

TEST(CertifyTest, PlantedRelayStepSmallH) {
  // G = S + K: symmetric part S = [[4,0,0,½],[0,3,0,0],[0,0,5,0],[½,0,0,2]] (positive definite), K skew.
  const DenseMatrix G = Mat({{4, 1, -2, 0.5}, {-1, 3, 1, 0.7}, {2, -1, 5, 0}, {0.5, -0.7, 0, 2}});
  const Vector s = Vec({1, -1, 0.3, -0.7});  // rows 0, 1 at the upper and lower bound, rows 2, 3 inside
  for (const double h : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10}) {
    const DenseMatrix W = h * G;
    Vector q = -(W * s);
    q[0] -= 0.5 * h;  // w_0 = −h/2 ≤ 0 at the upper bound
    q[1] += 0.5 * h;  // w_1 = +h/2 ≥ 0 at the lower bound
    const BoxMLCP p = BoxMLCP::Relay(W, q);
    const ReferenceSolution r = Certify(p, {s});
    EXPECT_EQ(r.certificate, Certificate::kUnique) << h;
    ExpectSolution(p, r);
    EXPECT_LE((r.z - s).cwiseAbs().maxCoeff(), 1e-13) << h;
  }
}

// ---------------------------------------------------------------------------------------------------------
// Several solutions, or none.

TEST(CertifyTest, PsdSingularLcpIsNonUnique) {
  // z ≥ 0, w = (z₁ + z₂ − 1)(1, 1): every z ≥ 0 on the segment z₁ + z₂ = 1 solves.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{1, 1}, {1, 1}}), Vec({-1, -1}));
  const ReferenceSolution r = Certify(p, {});
  EXPECT_EQ(r.certificate, Certificate::kNonUnique);
  ExpectSolution(p, r);
  EXPECT_NEAR(r.z[0] + r.z[1], 1.0, 1e-15);
}

TEST(CertifyTest, PsdSingularFreeRowsAreNonUnique) {
  // The same equations without bounds: one active set, with a singular free block, and a line of solutions.
  const BoxMLCP p(Mat({{1, 1}, {1, 1}}), Vec({-1, -1}), Filled(2, -kInf), Filled(2, kInf));
  const ReferenceSolution r = Certify(p, {});
  EXPECT_EQ(r.certificate, Certificate::kNonUnique);
  ExpectSolution(p, r);
  EXPECT_NEAR(r.z[0] + r.z[1], 1.0, 1e-15);
}

TEST(CertifyTest, ZeroFreeRowIsNonUnique) {
  // M = 0, q = 0, no bounds: w = 0 for every z.
  const BoxMLCP p(Mat({{0}}), Vec({0}), Filled(1, -kInf), Filled(1, kInf));
  const ReferenceSolution r = Certify(p, {Vec({0.25})});
  EXPECT_EQ(r.certificate, Certificate::kNonUnique);
  ExpectSolution(p, r);
}

TEST(CertifyTest, NoSolutionIsNoneFound) {
  // z ≥ 0 and w = −z − 1 < 0 always: no solution.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{-1}}), Vec({-1}));
  CertifyStats stats;
  const ReferenceSolution r = Certify(p, {Vec({3.0})}, {}, &stats);
  EXPECT_EQ(r.certificate, Certificate::kNoneFound);
  EXPECT_FALSE(r.verified());
  EXPECT_EQ(r.z.size(), 0);
  EXPECT_TRUE(stats.enumerated);
  EXPECT_EQ(stats.active_sets, 2);
}

// ---------------------------------------------------------------------------------------------------------
// Candidates.

TEST(CertifyTest, WrongCandidatesAreHarmless) {
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 2}}), Vec({-1, -1}));
  CertifyOptions no_enumeration;
  no_enumeration.max_enumerated = 0;
  const Vector right = Vec({1.0 / 3.0, 1.0 / 3.0});
  for (const std::vector<Vector>& candidates :
       {std::vector<Vector>{Vec({5, -3}), right}, std::vector<Vector>{Vec({1, 2, 3}), Vec({kNaN, 0}), right},
        std::vector<Vector>{Vec({1, 2, 3})}, std::vector<Vector>{}}) {
    const ReferenceSolution r = Certify(p, candidates, no_enumeration);
    EXPECT_EQ(r.certificate, Certificate::kUnique) << candidates.size();
    EXPECT_EQ(r.z[0], 1.0 / 3.0);
    EXPECT_EQ(r.z[1], 1.0 / 3.0);
  }
}

TEST(CertifyTest, CandidateChoosesAmongSeveralSolutions) {
  // z ≥ 0, w = 1 − z: z = 0 (w = 1) and z = 1 (w = 0) both solve. z* is the candidate's solution; the cold point
  // Π(0) = 0 finds the other, which proves non-uniqueness.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{-1}}), Vec({1}));
  CertifyOptions no_enumeration;
  no_enumeration.max_enumerated = 0;
  const ReferenceSolution r = Certify(p, {Vec({1, 1}), Vec({0.999999})}, no_enumeration);
  EXPECT_EQ(r.certificate, Certificate::kNonUnique);
  EXPECT_EQ(r.z[0], 1.0);
}

// ---------------------------------------------------------------------------------------------------------
// Conditioning and uniqueness tests.

TEST(CertifyTest, NearSingularSpdIsCertifiedWithItsCondition) {
  // M = Q diag(1, 1, 1e-13) Qᵀ with Q orthogonal (two plane rotations), interior planted z*: every row free.
  const double a = 0.7, b = 1.1;
  const DenseMatrix R1 = Mat({{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}});
  const DenseMatrix R2 = Mat({{1, 0, 0}, {0, std::cos(b), -std::sin(b)}, {0, std::sin(b), std::cos(b)}});
  const DenseMatrix Q = R1 * R2;
  const DenseMatrix M = Q * Vec({1, 1, 1e-13}).asDiagonal() * Q.transpose();
  const Vector planted = Vec({1, 2, 3});
  const BoxMLCP p = BoxMLCP::LCP(M, -(M * planted));
  const ReferenceSolution r = Certify(p, {planted});
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  ExpectSolution(p, r);
  // The rounding of q (≈ 1e-16) moves the exact solution by up to ≈ 1e13 · 1e-16 along the weak direction.
  EXPECT_LE((r.z - planted).cwiseAbs().maxCoeff(), 0.05);
  // ‖(D⁻¹M)⁻¹‖∞ ≈ 1e13 (D⁻¹ is within a factor 2 of the identity here).
  EXPECT_GE(r.condition, 1e12);
  EXPECT_LE(r.condition, 1e14);
}

// Upper triangular, unit diagonal, 3 above it: every principal minor is 1 (a P-matrix), but its symmetric part is
// indefinite. LCP with a planted solution: even rows positive and free, odd rows zero with w = 1.
BoxMLCP TriangularLcp(int n, Vector* planted) {
  DenseMatrix M = DenseMatrix::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) M(i, j) = 3;
  }
  Vector z(n), w(n);
  for (int i = 0; i < n; ++i) {
    z[i] = i % 2 == 0 ? 1.0 + i : 0.0;
    w[i] = i % 2 == 0 ? 0.0 : 1.0;
  }
  *planted = z;
  return BoxMLCP::LCP(M, w - M * z);
}

TEST(CertifyTest, PMatrixByMinorsOrByTheCallersWord) {
  CertifyOptions no_enumeration;
  no_enumeration.max_enumerated = 0;
  Vector planted;
  const BoxMLCP small = TriangularLcp(6, &planted);  // n ≤ 12: the principal minors are tested
  ReferenceSolution r = Certify(small, {planted}, no_enumeration);
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  EXPECT_EQ(r.z, planted);

  const BoxMLCP large = TriangularLcp(16, &planted);  // too large for the minors, and 2^16 sets
  r = Certify(large, {planted});
  EXPECT_EQ(r.certificate, Certificate::kIsolated);
  EXPECT_EQ(r.z, planted);
  CertifyOptions told;
  told.p_matrix = true;
  r = Certify(large, {planted}, told);
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  EXPECT_EQ(r.z, planted);
}

TEST(CertifyTest, EnumerationProvesUniquenessBeyondPMatrices) {
  // [[1,2],[2,1]] has determinant −3 (not a P-matrix); with q = (1,1) only z = 0 solves (every other set needs a
  // negative z), and every free block is nonsingular, so enumeration proves it.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{1, 2}, {2, 1}}), Vec({1, 1}));
  EXPECT_EQ(Certify(p, {}).certificate, Certificate::kUnique);
  CertifyOptions no_enumeration;
  no_enumeration.max_enumerated = 0;
  const ReferenceSolution r = Certify(p, {}, no_enumeration);
  EXPECT_EQ(r.certificate, Certificate::kIsolated);
  EXPECT_EQ(r.z, Vec({0, 0}));
}

TEST(CertifyTest, SizeLimit) {
  CertifyOptions small;
  small.max_size = 1;
  const ReferenceSolution r = Certify(BoxMLCP::LCP(Mat({{2, 1}, {1, 2}}), Vec({-1, -1})), {}, small);
  EXPECT_EQ(r.certificate, Certificate::kNone);
  EXPECT_EQ(r.z.size(), 0);
}

// ---------------------------------------------------------------------------------------------------------
// Larger problems (their gtest times are the figures quoted for Certify's cost).

// Relay problem M = G + n·I (G uniform in [−1, 1]: diagonally dominant, positive definite symmetric part) with a
// planted solution: a third of the rows at each bound with slack ½, the rest inside.
BoxMLCP PlantedRelay(int n, unsigned seed, Vector* planted) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  DenseMatrix M(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) M(i, j) = uniform(rng) + (i == j ? n : 0);
  }
  Vector s(n);
  for (int i = 0; i < n; ++i) s[i] = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? -1.0 : 0.9 * uniform(rng));
  Vector q = -(M * s);
  for (int i = 0; i < n; ++i) q[i] += i % 3 == 0 ? -0.5 : (i % 3 == 1 ? 0.5 : 0.0);
  *planted = s;
  return BoxMLCP::Relay(M, q);
}

TEST(CertifyTest, Dense64WithOneGoodCandidate) {
  Vector planted;
  const BoxMLCP p = PlantedRelay(64, 7, &planted);
  CertifyStats stats;
  const ReferenceSolution r = Certify(p, {planted}, {}, &stats);
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  ExpectSolution(p, r);
  EXPECT_LE((r.z - planted).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_FALSE(stats.enumerated);
  EXPECT_LE(stats.active_sets, 2);  // the candidate's set and the cold point's
}

TEST(CertifyTest, EightRelayRowsEnumerated) {
  Vector planted;
  const BoxMLCP p = PlantedRelay(8, 11, &planted);
  CertifyStats stats;
  CertifyOptions unknown_class;
  unknown_class.p_matrix = false;  // so that only the enumeration can prove uniqueness
  const ReferenceSolution r = Certify(p, {}, unknown_class, &stats);
  EXPECT_EQ(r.certificate, Certificate::kUnique);
  ExpectSolution(p, r);
  EXPECT_LE((r.z - planted).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_TRUE(stats.enumerated);
  EXPECT_EQ(stats.active_sets, 6561);
  EXPECT_EQ(stats.singular_blocks, 0);
}

// ---------------------------------------------------------------------------------------------------------
// The backend.

TEST(ReferenceSolverTest, SolvesTheLcpExactly) {
  ReferenceSolver solver;
  EXPECT_EQ(solver.info().name, "reference");
  EXPECT_TRUE(solver.info().exact);
  const BoxMLCP p = BoxMLCP::LCP(Mat({{2, 1}, {1, 2}}), Vec({-1, -1}));
  const SolveResult result = solver.Solve(p);
  ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
  EXPECT_EQ(result.z[0], 1.0 / 3.0);
  EXPECT_EQ(result.z[1], 1.0 / 3.0);
  EXPECT_EQ(kCertificateDetail.Get(result), Certificate::kUnique);
  EXPECT_GE(result.iterations, 1);
}

TEST(ReferenceSolverTest, SparseInputAndWarmStart) {
  Vector planted;
  const BoxMLCP dense = PlantedRelay(12, 3, &planted);
  const BoxMLCP sparse(SparseMatrix(dense.dense_matrix().sparseView()), dense.q(), dense.l(), dense.u());
  SolverOptions options;
  options.warm_start = -planted;  // every bound row on the wrong bound
  ReferenceSolver solver;
  for (const BoxMLCP* p : {&dense, &sparse}) {
    const SolveResult result = solver.Solve(*p, options);
    ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
    EXPECT_LE((result.z - planted).cwiseAbs().maxCoeff(), 1e-13);
  }
}

TEST(ReferenceSolverTest, ReportsWhatItTriedWithoutClaimingInfeasibility) {
  ReferenceSolver solver;
  const BoxMLCP p = BoxMLCP::LCP(Mat({{-1}}), Vec({-1}));
  const SolveResult result = solver.Solve(p);
  EXPECT_EQ(result.status, SolveStatus::kNumericalFailure);
  EXPECT_NE(result.message.find("not a proof"), std::string::npos) << result.message;
  EXPECT_EQ(kCertificateDetail.Get(result), Certificate::kNoneFound);
}

}  // namespace
}  // namespace smcbench
