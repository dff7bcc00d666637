// The suites keep their promises: planted solutions solve their problems, generation is a pure function of the
// seed, infeasible problems carry a certificate, matrix-class tags are true, Murty's family is exponential for
// Lemke, and on the hard suite no registered backend ever claims a solution it does not have.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "problems/library/references.h"
#include "problems/suites/families.h"
#include "problems/suites/hard_cases.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

const std::string kSiconosDir = std::string(SMCBENCH_PEER_DATA_DIR) + "/siconos";

// Built once: the suites are pure functions of their options.
const ProblemSet& Families() {
  static const ProblemSet set = FamiliesSuite();
  return set;
}
const ProblemSet& HardCases() {
  static const ProblemSet set = HardSuite(kSiconosDir);
  return set;
}

std::vector<const LibraryProblem*> AllSmallProblems() {
  std::vector<const LibraryProblem*> all;
  for (const LibraryProblem& p : Families().problems) all.push_back(&p);
  for (const LibraryProblem& p : HardCases().problems) all.push_back(&p);
  return all;
}

bool HasTag(const LibraryProblem& p, const std::string& tag) {
  for (const std::string& t : p.tags) {
    if (t == tag) return true;
  }
  return false;
}

double RelativeResidual(const LibraryProblem& p, const Vector& z) {
  Vector w;
  return p.problem.NaturalResidual(z, &w).rel;
}

// --- Bits. ---------------------------------------------------------------------------------------------------
template <typename T>
bool SameBytes(const T* a, const T* b, std::size_t count) {
  return count == 0 || std::memcmp(a, b, count * sizeof(T)) == 0;
}

bool SameBits(const Vector& a, const Vector& b) {
  return a.size() == b.size() && SameBytes(a.data(), b.data(), static_cast<std::size_t>(a.size()));
}

bool SameBits(const LibraryProblem& a, const LibraryProblem& b) {
  if (a.id != b.id || a.source != b.source || a.tags != b.tags || a.seed != b.seed || a.expected != b.expected ||
      a.metadata != b.metadata || a.matrix.symmetric != b.matrix.symmetric ||
      a.matrix.positive_definite != b.matrix.positive_definite || a.matrix.p_matrix != b.matrix.p_matrix) {
    return false;
  }
  const BoxMLCP& x = a.problem;
  const BoxMLCP& y = b.problem;
  if (x.is_sparse() != y.is_sparse() || !SameBits(x.q(), y.q()) || !SameBits(x.l(), y.l()) || !SameBits(x.u(), y.u()) ||
      !SameBits(a.solution, b.solution)) {
    return false;
  }
  if (x.is_sparse()) {
    const SparseMatrix& A = x.sparse_matrix();
    const SparseMatrix& B = y.sparse_matrix();
    const auto nnz = static_cast<std::size_t>(A.nonZeros());
    return A.rows() == B.rows() && A.nonZeros() == B.nonZeros() && SameBytes(A.valuePtr(), B.valuePtr(), nnz) &&
           SameBytes(A.innerIndexPtr(), B.innerIndexPtr(), nnz) &&
           SameBytes(A.outerIndexPtr(), B.outerIndexPtr(), static_cast<std::size_t>(A.cols() + 1));
  }
  const DenseMatrix& A = x.dense_matrix();
  const DenseMatrix& B = y.dense_matrix();
  return A.rows() == B.rows() && A.cols() == B.cols() &&
         SameBytes(A.data(), B.data(), static_cast<std::size_t>(A.size()));
}

// --- Infeasibility certificate: a row i with one infinite bound whose s (Mz + q)_i stays below 0 on the box. ----
// Returns the certified margin (> 0) of the best row, or 0 if no row certifies.
double CertificateMargin(const BoxMLCP& p) {
  const DenseMatrix M = p.ToDense();
  const Vector& l = p.l();
  const Vector& u = p.u();
  double best = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    if (std::isinf(l[i]) == std::isinf(u[i])) continue;  // needs exactly one infinite bound
    const double s = std::isinf(u[i]) ? 1.0 : -1.0;      // u = ∞ ⇒ (Mz+q)_i ≥ 0 required; l = −∞ ⇒ ≤ 0
    double sup = s * p.q()[i];
    for (int j = 0; j < p.size(); ++j) {
      const double a = s * M(i, j);
      if (a > 0.0) sup += a * u[j];
      if (a < 0.0) sup += a * l[j];
    }
    if (sup < 0.0) best = std::max(best, -sup);  // sup = +∞ (unbounded term) never certifies
  }
  return best;
}

// --- Matrix classes, checked independently of ClassifyMatrix. --------------------------------------------------
double MinSymmetricEigenvalue(const DenseMatrix& M, double* largest) {
  const DenseMatrix S = 0.5 * (M + M.transpose());
  const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(S, Eigen::EigenvaluesOnly);
  *largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  return eig.eigenvalues()[0];
}

// Smallest principal minor over all 2^n − 1 index sets, each relative to its Hadamard bound.
double SmallestRelativeMinor(const DenseMatrix& M) {
  const int n = static_cast<int>(M.rows());
  double smallest = kInf;
  for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i) {
      if (mask & (1u << i)) idx.push_back(i);
    }
    const int k = static_cast<int>(idx.size());
    DenseMatrix S(k, k);
    for (int a = 0; a < k; ++a) {
      for (int b = 0; b < k; ++b) S(a, b) = M(idx[static_cast<std::size_t>(a)], idx[static_cast<std::size_t>(b)]);
    }
    // det/Hadamard is invariant under scaling S: normalize first, so that M scaled by 1e±150 neither under- nor
    // overflows a k×k determinant.
    const double largest = S.cwiseAbs().maxCoeff();
    if (largest > 0.0) S /= largest;
    double hadamard = 1.0;
    for (int a = 0; a < k; ++a) hadamard *= S.row(a).norm();
    smallest = std::min(smallest, hadamard > 0.0 ? S.fullPivLu().determinant() / hadamard : 0.0);
  }
  return smallest;
}

bool StrictlyRowDominant(const DenseMatrix& M) {
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    if (!(M(i, i) > M.row(i).cwiseAbs().sum() - std::abs(M(i, i)))) return false;
  }
  return true;
}

// An H-matrix with a positive diagonal (some positive diagonal D makes M D strictly row dominant), hence a P-matrix:
// its comparison matrix (|M_ii| on the diagonal, −|M_ij| off it) is a nonsingular M-matrix, i.e. its inverse exists
// and is entrywise nonnegative (Berman & Plemmons, Nonnegative Matrices, ch. 6).
bool HMatrixPositiveDiagonal(const DenseMatrix& M) {
  if (!(M.diagonal().array() > 0.0).all()) return false;
  DenseMatrix comparison = -M.cwiseAbs();
  comparison.diagonal() = M.diagonal();
  const Eigen::FullPivLU<DenseMatrix> lu(comparison);
  if (!lu.isInvertible()) return false;
  const DenseMatrix inverse = lu.inverse();
  return inverse.minCoeff() >= -1e-12 * inverse.maxCoeff();
}

// Triangular with a positive diagonal: every principal minor is a product of diagonal entries.
bool TriangularPositiveDiagonal(const DenseMatrix& M) {
  const bool lower = DenseMatrix(M.triangularView<Eigen::StrictlyUpper>()).isZero(0.0);
  const bool upper = DenseMatrix(M.triangularView<Eigen::StrictlyLower>()).isZero(0.0);
  return (lower || upper) && (M.diagonal().array() > 0.0).all();
}

void ExpectTagsTrue(const LibraryProblem& p) {
  SCOPED_TRACE(p.id);
  if (p.size() > 512) return;
  const DenseMatrix M = p.problem.ToDense();
  const int n = p.size();
  const double max_abs = M.cwiseAbs().maxCoeff();
  const double asym = (M - M.transpose()).cwiseAbs().maxCoeff();
  if (p.matrix.symmetric == Tristate::kYes) {
    EXPECT_LE(asym, 1e-12 * max_abs);
  }
  if (p.matrix.symmetric == Tristate::kNo) {
    EXPECT_GT(asym, 0.0);
  }

  double largest = 0.0;
  const double lambda_min = MinSymmetricEigenvalue(M, &largest);
  if (p.matrix.positive_definite == Tristate::kYes) {
    const Eigen::LLT<DenseMatrix> llt(0.5 * (M + M.transpose()));
    EXPECT_EQ(llt.info(), Eigen::Success) << "Cholesky of the symmetric part failed";
    EXPECT_GT(lambda_min, 0.0);
  }
  if (p.matrix.positive_definite == Tristate::kNo) {
    EXPECT_LE(lambda_min, 1e-12 * std::max(largest, 1e-300)) << "symmetric part looks PD, lambda_min = " << lambda_min;
  }

  if (n <= 10) {
    const double minor = SmallestRelativeMinor(M);
    if (p.matrix.p_matrix == Tristate::kYes) {
      EXPECT_GT(minor, 0.0);
    }
    if (p.matrix.p_matrix == Tristate::kNo) {
      EXPECT_LE(minor, 1e-13);
    }
  } else {
    if (p.matrix.p_matrix == Tristate::kYes) {
      const bool pd = Eigen::LLT<DenseMatrix>(0.5 * (M + M.transpose())).info() == Eigen::Success && lambda_min > 0.0;
      EXPECT_TRUE(pd || StrictlyRowDominant(M) || HMatrixPositiveDiagonal(M) || TriangularPositiveDiagonal(M))
          << "P-matrix claim without a proof";
    }
    if (p.matrix.p_matrix == Tristate::kNo) {
      const bool nonpositive_diagonal = (M.diagonal().array() <= 0.0).any();
      const bool singular_psd = HasTag(p, "psd-singular");
      EXPECT_TRUE(nonpositive_diagonal || singular_psd || CertificateMargin(p.problem) > 0.0)
          << "non-P claim without a witness";
    }
  }
}

// All solutions of a small box-MLCP by enumerating row states (inside / at l / at u): for each pattern solve the
// inside rows exactly and keep the points that satisfy every sign condition. Distinct solutions (to 1e-6).
std::vector<Vector> EnumerateSolutions(const BoxMLCP& p) {
  const DenseMatrix M = p.ToDense();
  const int n = p.size();
  std::vector<Vector> found;
  std::vector<int> state(static_cast<std::size_t>(n), 0);  // 0 inside, 1 at l, 2 at u
  while (true) {
    bool valid = true;
    for (int i = 0; i < n; ++i) {
      const int s = state[static_cast<std::size_t>(i)];
      if ((s == 1 && std::isinf(p.l()[i])) || (s == 2 && std::isinf(p.u()[i]))) valid = false;
    }
    if (valid) {
      Vector z = Vector::Zero(n);
      std::vector<int> inside;
      for (int i = 0; i < n; ++i) {
        const int s = state[static_cast<std::size_t>(i)];
        if (s == 0) inside.push_back(i);
        if (s == 1) z[i] = p.l()[i];
        if (s == 2) z[i] = p.u()[i];
      }
      const int k = static_cast<int>(inside.size());
      bool ok = true;
      if (k > 0) {
        DenseMatrix A(k, k);
        Vector b(k);
        for (int a = 0; a < k; ++a) {
          const int i = inside[static_cast<std::size_t>(a)];
          b[a] = -p.q()[i];
          for (int j = 0; j < n; ++j) {
            if (state[static_cast<std::size_t>(j)] != 0) b[a] -= M(i, j) * z[j];
          }
          for (int c = 0; c < k; ++c) A(a, c) = M(i, inside[static_cast<std::size_t>(c)]);
        }
        const Eigen::FullPivLU<DenseMatrix> lu(A);
        if (!lu.isInvertible()) ok = false;
        if (ok) {
          const Vector x = lu.solve(b);
          for (int a = 0; a < k; ++a) z[inside[static_cast<std::size_t>(a)]] = x[a];
        }
      }
      Vector w;
      if (ok && p.NaturalResidual(z, &w).rel <= 1e-9) {
        bool fresh = true;
        for (const Vector& f : found) fresh = fresh && (f - z).cwiseAbs().maxCoeff() > 1e-6;
        if (fresh) found.push_back(z);
      }
    }
    int i = 0;
    while (i < n && state[static_cast<std::size_t>(i)] == 2) state[static_cast<std::size_t>(i++)] = 0;
    if (i == n) break;
    ++state[static_cast<std::size_t>(i)];
  }
  return found;
}

// --- The families suite. ------------------------------------------------------------------------------------
TEST(FamiliesSuite, HasEveryFamilyAtSmallSizes) {
  const ProblemSet& set = Families();
  EXPECT_EQ(set.name, "families");
  EXPECT_NO_THROW(set.Validate());
  EXPECT_GE(set.problems.size(), 140u);
  EXPECT_LE(set.problems.size(), 200u);
  std::map<std::string, int> per_family;
  for (const LibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    EXPECT_EQ(p.id.rfind("families/", 0), 0u);
    EXPECT_EQ(p.source.rfind("generated:", 0), 0u);
    EXPECT_LE(p.size(), 64);
    EXPECT_NE(p.expected, ExpectedOutcome::kUnknown);
    EXPECT_FALSE(p.tags.empty());
    EXPECT_EQ(p.problem.name(), p.id);
    ++per_family[p.source.substr(std::strlen("generated:"))];
  }
  for (const char* family : {"spd", "pmatrix", "pmatrix-skew", "diagdom", "pmatrix-scaled", "psd-singular", "nonp-multi", "nonp-infeasible", "scene-step",
                             "small-h", "murty", "coupled-smc"}) {
    EXPECT_GE(per_family[family], 4) << family;
  }
  EXPECT_EQ(per_family["murty"], 13);       // n = 4 … 16
  EXPECT_EQ(per_family["scene-step"], 40);  // 5 scenes × 8 decades of h
  EXPECT_EQ(per_family["small-h"], 40);     // (3 scenes with m = 2 + 5 P-matrices) × 5 values of h
}

TEST(FamiliesSuite, OptionsLimitTheSuite) {
  FamiliesOptions options;
  options.seeds = 1;
  options.max_size = 8;
  options.scenes = false;
  const ProblemSet small = FamiliesSuite(options);
  EXPECT_GE(small.problems.size(), 15u);
  for (const LibraryProblem& p : small.problems) {
    EXPECT_LE(p.size(), 8) << p.id;
    EXPECT_FALSE(HasTag(p, "h-sweep")) << p.id;
    EXPECT_TRUE(!p.seed || *p.seed == 1u) << p.id;
  }
}

TEST(FamiliesSuite, PlantedSolutionsSolveTheirProblemsTo1e12) {
  int checked = 0;
  for (const LibraryProblem* p : AllSmallProblems()) {
    SCOPED_TRACE(p->id);
    if (p->expected == ExpectedOutcome::kInfeasible) {
      EXPECT_EQ(p->solution.size(), 0);
      continue;
    }
    if (p->source.rfind("generated:", 0) == 0) {
      ASSERT_EQ(p->solution.size(), p->size()) << "generated without z*";
    }
    if (p->solution.size() == 0) continue;
    EXPECT_LE(RelativeResidual(*p, p->solution), 1e-12);
    EXPECT_TRUE(((p->solution - p->problem.l()).array() >= 0.0).all() &&
                ((p->problem.u() - p->solution).array() >= 0.0).all());
    ++checked;
  }
  EXPECT_GE(checked, 120);
}

TEST(FamiliesSuite, GenerationIsDeterministic) {
  const ProblemSet again = FamiliesSuite();
  ASSERT_EQ(again.problems.size(), Families().problems.size());
  for (std::size_t k = 0; k < again.problems.size(); ++k) {
    EXPECT_TRUE(SameBits(again.problems[k], Families().problems[k])) << again.problems[k].id;
  }
  const ProblemSet hard = HardSuite(kSiconosDir);
  ASSERT_EQ(hard.problems.size(), HardCases().problems.size());
  for (std::size_t k = 0; k < hard.problems.size(); ++k) {
    EXPECT_TRUE(SameBits(hard.problems[k], HardCases().problems[k])) << hard.problems[k].id;
  }
  // A different seed gives a different problem.
  EXPECT_FALSE(SameBits(PsdSingularProblem(BoundKind::kRelay, 8, 1), PsdSingularProblem(BoundKind::kRelay, 8, 2)));
  EXPECT_FALSE(SameBits(CoupledSlidingModeProblem(50, 1), CoupledSlidingModeProblem(50, 2)));
}

TEST(FamiliesSuite, InfeasibleProblemsCarryACertificate) {
  int infeasible = 0;
  for (const LibraryProblem* p : AllSmallProblems()) {
    if (p->expected != ExpectedOutcome::kInfeasible) continue;
    SCOPED_TRACE(p->id);
    ++infeasible;
    EXPECT_GE(CertificateMargin(p->problem), 1e-4);
    EXPECT_EQ(p->matrix.p_matrix, Tristate::kNo);
  }
  EXPECT_GE(infeasible, 12);
  // And the certificate is not vacuous: a feasible problem of the same shape has none.
  EXPECT_EQ(CertificateMargin(
                RandomFamilyProblem(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kMixed, 16, 1).problem),
            0.0);
}

TEST(FamiliesSuite, MatrixTagsAreTrue) {
  for (const LibraryProblem* p : AllSmallProblems()) ExpectTagsTrue(*p);
}

TEST(FamiliesSuite, PsdSingularHasASecondSolution) {
  int checked = 0;
  for (const LibraryProblem* p : AllSmallProblems()) {
    if (!HasTag(*p, "psd-singular")) continue;
    SCOPED_TRACE(p->id);
    const DenseMatrix M = p->problem.ToDense();
    const Eigen::SelfAdjointEigenSolver<DenseMatrix> eig(M);
    const double top = eig.eigenvalues().cwiseAbs().maxCoeff();
    std::vector<int> null_columns, bound_rows;
    for (int k = 0; k < p->size(); ++k) {
      if (std::abs(eig.eigenvalues()[k]) <= 1e-12 * top) null_columns.push_back(k);
    }
    ASSERT_FALSE(null_columns.empty()) << "M is not singular";
    const Vector& z = p->solution;
    for (int i = 0; i < p->size(); ++i) {
      if (z[i] == p->problem.l()[i] || z[i] == p->problem.u()[i]) bound_rows.push_back(i);
    }
    // A null vector of M that vanishes on the rows at a bound: N c with N_B c = 0.
    DenseMatrix N(p->size(), static_cast<int>(null_columns.size()));
    for (std::size_t c = 0; c < null_columns.size(); ++c)
      N.col(static_cast<int>(c)) = eig.eigenvectors().col(null_columns[c]);
    DenseMatrix NB(static_cast<int>(bound_rows.size()), N.cols());
    for (std::size_t r = 0; r < bound_rows.size(); ++r) NB.row(static_cast<int>(r)) = N.row(bound_rows[r]);
    Vector d;
    if (bound_rows.empty()) {
      d = N.col(0);
    } else {
      const Eigen::FullPivLU<DenseMatrix> lu(NB);
      const DenseMatrix kernel = lu.kernel();
      ASSERT_GT(kernel.cols(), 0);
      ASSERT_GT(kernel.col(0).norm(), 0.0) << "no null direction avoids the bound rows";
      d = N * kernel.col(0);
    }
    d /= d.cwiseAbs().maxCoeff();
    for (int i : bound_rows) d[i] = 0.0;  // zero up to rounding already
    double t = kInf;
    for (int i = 0; i < p->size(); ++i) {
      if (d[i] == 0.0) continue;
      t = std::min(t, 0.5 * std::min(z[i] - p->problem.l()[i], p->problem.u()[i] - z[i]) / std::abs(d[i]));
    }
    ASSERT_TRUE(std::isfinite(t) && t > 1e-3);
    const Vector other = z + t * d;
    EXPECT_GT((other - z).cwiseAbs().maxCoeff(), 1e-3);
    EXPECT_LE(RelativeResidual(*p, other), 1e-12);
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

TEST(FamiliesSuite, NonPMultipleHasSeveralSolutions) {
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay}) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const LibraryProblem p = NonPMultipleProblem(bounds, 8, seed);
      SCOPED_TRACE(p.id);
      const std::vector<Vector> solutions = EnumerateSolutions(p.problem);
      EXPECT_GE(solutions.size(), 2u);
      bool planted_found = false;
      for (const Vector& s : solutions) planted_found = planted_found || (s - p.solution).cwiseAbs().maxCoeff() < 1e-8;
      EXPECT_TRUE(planted_found);
    }
  }
  // A P-matrix problem of the same size has exactly one (the check can tell the difference).
  EXPECT_EQ(EnumerateSolutions(RandomFamilyProblem(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 8, 1).problem)
                .size(),
            1u);
}

TEST(FamiliesSuite, SceneStepsShrinkWithHAndKeepQOrderOne) {
  for (const char* scene : {"filippov", "parasitic"}) {
    double previous = kInf;
    for (double h : HSweepSteps()) {
      const LibraryProblem p = SceneStepProblem(scene, h, 1);
      SCOPED_TRACE(p.id);
      const double norm = p.problem.dense_matrix().cwiseAbs().maxCoeff();
      EXPECT_LT(norm, previous);  // strictly decreasing with h
      previous = norm;
      EXPECT_GE(p.problem.q().cwiseAbs().maxCoeff(), 0.1 - 1e-6);  // a row at a bound: |q| ≥ |w*| − |W z*|
      EXPECT_EQ(p.metadata.at("scene"), scene);
    }
  }
  // ZOH scenes take the implicit θ-method on their closed loop: m = 2 for S6.
  const LibraryProblem zoh = SceneStepProblem("zoh-mimo", 1e-3, 1);
  EXPECT_EQ(zoh.size(), 2);
  EXPECT_LE(RelativeResidual(zoh, zoh.solution), 1e-12);
  // S11 is O(h³): a factor ~1e3 per decade at small h.
  const double w6 = SceneStepProblem("parasitic", 1e-6, 1).problem.dense_matrix()(0, 0);
  const double w7 = SceneStepProblem("parasitic", 1e-7, 1).problem.dense_matrix()(0, 0);
  EXPECT_NEAR(w6 / w7, 1e3, 10.0);
}

TEST(FamiliesSuite, CoupledFamilyIsTridiagonalAndDominant) {
  const LibraryProblem p = CoupledSlidingModeProblem(1000, 3, 1e-2);
  ASSERT_TRUE(p.problem.is_sparse());
  const SparseMatrix& W = p.problem.sparse_matrix();
  EXPECT_EQ(W.nonZeros(), 3 * 1000 - 2);
  for (int j = 0; j < W.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(W, j); it; ++it) EXPECT_LE(std::abs(it.row() - it.col()), 1);
  }
  EXPECT_EQ(p.matrix.p_matrix, Tristate::kYes);
  EXPECT_EQ(p.matrix.positive_definite, Tristate::kYes);
  EXPECT_EQ(p.matrix.symmetric, Tristate::kNo);
  EXPECT_TRUE(StrictlyRowDominant(DenseMatrix(W)));
}

// --- The small-h family: every datum O(h), the planted slack signed, G fixed across h, the condition as proved. ----
TEST(SmallHFamily, IsHTimesAUnitProblemWithInteriorAndBoundRows) {
  int checked = 0;
  for (const LibraryProblem& p : Families().problems) {
    if (!HasTag(p, "small-h")) continue;
    SCOPED_TRACE(p.id);
    ++checked;
    const double h = std::stod(p.metadata.at("h"));
    const DenseMatrix& W = p.problem.dense_matrix();
    ASSERT_GE(p.size(), 2);
    // O(h): W = h G with ‖G‖ of order 1, and q = w* − W s* with |w*| ≤ 1.1 h, |s*| ≤ 1.
    const double g_norm = W.cwiseAbs().maxCoeff() / h;
    EXPECT_GT(g_norm, 1e-3);
    EXPECT_LT(g_norm, 1e3);
    EXPECT_LE(p.problem.q().cwiseAbs().maxCoeff(), h * (1.1 + W.cwiseAbs().rowwise().sum().maxCoeff() / h) * 1.0001);
    // The planted rows: inside with w = 0 (to rounding), or at ±1 with w of the bound's sign and size in [0.1h, 1.1h].
    const Vector w = W * p.solution + p.problem.q();
    int inside = 0, at_bound = 0;
    for (int i = 0; i < p.size(); ++i) {
      const double z = p.solution[i];
      if (z == -1.0 || z == 1.0) {
        ++at_bound;
        EXPECT_GE(-z * w[i], 0.1 * h * (1 - 1e-9)) << "row " << i;
        EXPECT_LE(-z * w[i], 1.1 * h * (1 + 1e-9)) << "row " << i;
      } else {
        ++inside;
        EXPECT_LT(std::abs(z), 1.0);
        EXPECT_LE(std::abs(w[i]), 1e-14 * h * (1.0 + g_norm)) << "row " << i;
      }
    }
    EXPECT_GE(inside, 1);
    EXPECT_GE(at_bound, 1);
    EXPECT_EQ(p.expected, ExpectedOutcome::kSolvable);
  }
  EXPECT_EQ(checked, 40);
}

TEST(SmallHFamily, PMatrixGIsTheSameForEveryHAndHasTheProvedCondition) {
  for (const auto& [m, c] : {std::pair{2, 1}, std::pair{4, 3}, std::pair{8, 6}}) {
    const LibraryProblem big = SmallHPMatrixProblem(m, c, 1e-2, 1);
    const LibraryProblem small = SmallHPMatrixProblem(m, c, 1e-10, 1);
    SCOPED_TRACE(big.id);
    const DenseMatrix G = big.problem.dense_matrix() / 1e-2;
    EXPECT_LE((small.problem.dense_matrix() / 1e-10 - G).cwiseAbs().maxCoeff(), 1e-14 * G.cwiseAbs().maxCoeff());
    EXPECT_EQ(big.solution, small.solution);  // the same draw of s*
    // κ₂(G) ∈ [c/2, √2·c] (families.cc), checked here by an SVD; the symmetric part is PD (the P-matrix proof).
    const Eigen::JacobiSVD<DenseMatrix> svd(G);
    const double kappa = svd.singularValues()[0] / svd.singularValues()[m - 1];
    const double target = std::pow(10.0, c);
    EXPECT_GE(kappa, 0.5 * target * (1 - 1e-6));
    EXPECT_LE(kappa, std::sqrt(2.0) * target * (1 + 1e-6));
    double largest = 0.0;
    EXPECT_GT(MinSymmetricEigenvalue(G, &largest), 0.0);
    EXPECT_EQ(big.matrix.p_matrix, Tristate::kYes);
    EXPECT_EQ(big.matrix.symmetric, Tristate::kNo);
  }
  EXPECT_THROW(SmallHPMatrixProblem(1, 2, 1e-2, 1), InvalidInputError);
  EXPECT_THROW(SmallHPMatrixProblem(4, 2, 0.0, 1), InvalidInputError);
  EXPECT_THROW(SmallHSceneProblem("sign", 1e-2, 1), InvalidInputError);  // m = 1
}

// --- Murty's family: exponential for raw Lemke, not for ours. --------------------------------------------------------
// Murty's theorem is about Lemke with covering vector e on (M̃, q̂). Our backends receive the row-equilibrated problem
// (D⁻¹M̃, D⁻¹q̂) with D = the row maxima (1, 2, …, 2) (solvers/core): for lemke that is the path of covering
// vector d on the original rows, which Murty's construction does not force through 2ⁿ cones. Siconos' Lemke gets
// the problem as written (SolverInfo::equilibrate false) and still shows the exponential growth.
TEST(MurtyFamily, RawLemkeIsExponentialOurEquilibratedLemkeSolvesItExactly) {
  std::vector<std::string> lemkes{"lemke"};
  for (std::string_view name : SolverNames()) {
    if (name == "siconos-lcp-lemke") lemkes.emplace_back(name);  // registered when Siconos is built in
  }
  for (const std::string& name : lemkes) {
    const auto solver = CreateSolver(name);
    std::vector<int> pivots;
    for (int n = 4; n <= 16; ++n) {
      const LibraryProblem p = MurtyProblem(n);
      SolverOptions options;
      options.max_iterations = 1 << 20;
      options.time_limit_seconds = 10.0;
      const SolveResult r = solver->Solve(p.problem, options);
      ASSERT_TRUE(r.solved()) << name << " on " << p.id << ": " << r.message;
      EXPECT_LE((r.z - p.solution).cwiseAbs().maxCoeff(), 1e-9 * p.solution.cwiseAbs().maxCoeff()) << name;
      pivots.push_back(r.iterations);
    }
    std::string line;
    for (std::size_t k = 0; k < pivots.size(); ++k)
      line += " n=" + std::to_string(4 + k) + ":" + std::to_string(pivots[k]);
    std::cout << "[ " << name << " pivots on Murty (q^(n), M~(n)) ]" << line << "\n";
    if (name == "lemke") continue;  // equilibrated: no claim on its pivot count
    for (std::size_t k = 0; k + 1 < pivots.size(); ++k) {
      EXPECT_GE(pivots[k + 1], 1.8 * pivots[k]) << name << " n = " << 4 + k << " -> " << 5 + k;
    }
    EXPECT_GE(pivots.back(), (1 << 16) - 1) << name;  // Murty: 2^n cones (Siconos counts 2^n − 1 pivots)
  }
}

// --- The hard suite. ---------------------------------------------------------------------------------------------
TEST(HardSuite, EveryCaseIsNamedAndExplained) {
  const ProblemSet& set = HardCases();
  EXPECT_NO_THROW(set.Validate());
  std::set<std::string> kinds;
  for (const LibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    ASSERT_FALSE(p.tags.empty());
    EXPECT_EQ(p.id.rfind("hard/" + p.tags.front() + "/", 0), 0u);
    ASSERT_TRUE(p.metadata.count("why"));
    EXPECT_FALSE(p.metadata.at("why").empty());
    kinds.insert(p.tags.front());
  }
  EXPECT_EQ(kinds, (std::set<std::string>{"cycling", "degenerate", "h-to-zero", "infeasible", "near-singular",
                                          "non-unique", "parasitic", "siconos", "small-h", "row-scaling",
                                          "joint-scaling", "free-row"}));
  // The cases where residual-only verdicts passed wrong answers, by name.
  std::set<std::string> ids;
  for (const LibraryProblem& p : set.problems) ids.insert(p.id);
  for (const char* id : {"hard/small-h/relay-h1e-8-m4", "hard/row-scaling/pmatrix-1e6-1e-5",
                         "hard/joint-scaling/x1e-150", "hard/joint-scaling/x1e150",
                         "hard/near-singular/spd-lcp-cond1e13", "hard/free-row/zero"}) {
    EXPECT_EQ(ids.count(id), 1u) << id;
  }
  EXPECT_EQ(HardSuite("").problems.size() + HardSiconosFiles().size(), set.problems.size());
  EXPECT_THROW(HardSuite("/nonexistent/siconos"), InvalidInputError);
}

// THE test of the hard suite: every registered backend on every hard case; none may claim a solution it does not have.
TEST(HardSuite, NoBackendWronglyClaimsSuccess) {
  const ProblemSet& set = HardCases();
  SolverOptions options;
  options.time_limit_seconds = 2.0;
  std::map<std::string, int> solved_by_someone;
  std::map<std::string, std::string> not_solved;  // id → the backends that failed it (for the log)
  std::cout << "[ hard suite: solved / correctly refused / failed / WRONGLY CLAIMED ]\n";
  for (std::string_view name : SolverNames()) {
    const auto solver = CreateSolver(name);
    int counts[4] = {0, 0, 0, 0};
    const auto start = std::chrono::steady_clock::now();
    for (const LibraryProblem& p : set.problems) {
      const SolveResult r = solver->Solve(p.problem, options);
      const Verdict v = Judge(p, r.status, r.z, options.tolerance).verdict;
      ++counts[static_cast<int>(v)];
      EXPECT_NE(v, Verdict::kWronglyClaimed)
          << name << " on " << p.id << ": status " << ToString(r.status) << ", residual " << r.residual_rel;
      if (v == Verdict::kSolved) ++solved_by_someone[p.id];
      if (v == Verdict::kFailed)
        not_solved[p.id] += " " + std::string(name) + "(" + std::string(ToString(r.status)) + ")";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "  " << name << ": " << counts[0] << " / " << counts[1] << " / " << counts[2] << " / " << counts[3]
              << " (" << seconds << " s)\n";
  }
  std::cout << "[ hard suite: failures per case ]\n";
  for (const auto& [id, names] : not_solved) std::cout << "  " << id << ":" << names << "\n";
  // Every Siconos case expected solvable was solved by some backend (the basis of that expectation).
  for (const LibraryProblem& p : set.problems) {
    if (HasTag(p, "siconos") && p.expected == ExpectedOutcome::kSolvable) {
      EXPECT_GE(solved_by_someone[p.id], 1) << p.id;
    }
  }
}

// THE test of the one verdict on the suites: each of our backends on every families and hard problem, judged by the one
// verdict with certified references (forward error against z*, false "infeasible" claims): no wrong answer at all,
// and the small-h family (h down to 1e-10) solved by the exact backends.
const ProblemSet& WithReferences(const ProblemSet& set) {
  static std::map<const ProblemSet*, ProblemSet> cache;
  auto it = cache.find(&set);
  if (it == cache.end()) {
    ProblemSet copy = set;
    AttachReferences(&copy);
    it = cache.emplace(&set, std::move(copy)).first;
  }
  return it->second;
}

TEST(Verdicts, NoBackendOfOursIsWrongOnFamiliesAndHardWithReferences) {
  SolverOptions options;
  options.time_limit_seconds = 2.0;
  const auto start = std::chrono::steady_clock::now();
  const ProblemSet& families = WithReferences(Families());
  const ProblemSet& hard = WithReferences(HardCases());
  std::cout << "[ references attached in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s ]\n";
  int unique_references = 0;
  for (const ProblemSet* set : {&families, &hard}) {
    for (const LibraryProblem& p : set->problems) unique_references += p.reference.unique() ? 1 : 0;
  }
  std::cout << "[ " << unique_references << " problems with a unique certified reference ]\n";
  std::cout << "[ families + hard with references: solved / refused / failed / wrongly claimed / inaccurate / "
               "wrongly refused ]\n";
  for (const char* name : {"lemke", "psor", "newton", "enum", "ipopt"}) {
    const auto solver = CreateSolver(name);
    const bool exact = solver->info().exact;
    int counts[6] = {0, 0, 0, 0, 0, 0};
    for (const ProblemSet* set : {&families, &hard}) {
      for (const LibraryProblem& p : set->problems) {
        const SolveResult r = solver->Solve(p.problem, options);
        const Judgement j = Judge(p, r.status, r.z, options.tolerance);
        ++counts[static_cast<int>(j.verdict)];
        EXPECT_FALSE(IsWrong(j.verdict))
            << name << " on " << p.id << ": " << ToString(j.verdict) << ", status " << ToString(r.status)
            << ", residual rel " << j.residual.rel << " scaled " << j.residual.scaled << ", forward error "
            << j.forward_error << " (allowance " << j.forward_allowance << "), certificate "
            << ToString(p.reference.certificate) << (r.message.empty() ? "" : ": " + r.message);
        if (exact && HasTag(p, "small-h")) {
          EXPECT_EQ(j.verdict, Verdict::kSolved) << name << " on " << p.id << ": status " << ToString(r.status)
                                                 << ", forward error " << j.forward_error << ": " << r.message;
        }
      }
    }
    std::cout << "  " << name << ": " << counts[0] << " / " << counts[1] << " / " << counts[2] << " / " << counts[3]
              << " / " << counts[4] << " / " << counts[5] << "\n";
  }
}

// --- The scale family. -------------------------------------------------------------------------------------------
TEST(ScaleSuite, TenThousandGeneratesFastAndItsPlantedSolutionChecks) {
  ScaleOptions options;
  options.max_size = 10000;
  const auto start = std::chrono::steady_clock::now();
  const ProblemSet set = ScaleSuite(options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(set.problems.size(), 3u);  // 1e2, 1e3, 1e4
  EXPECT_LT(seconds, 1.0);
  for (const LibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    EXPECT_EQ(p.id.rfind("scale/coupled-smc/m", 0), 0u);
    EXPECT_TRUE(p.problem.is_sparse());
    EXPECT_LE(RelativeResidual(p, p.solution), 1e-12);
    EXPECT_EQ(p.matrix.p_matrix, Tristate::kYes);
  }
  EXPECT_EQ(set.problems.back().size(), 10000);
}

// --- Invalid arguments are errors that name the argument. ---------------------------------------------------------
TEST(Families, InvalidArgumentsThrow) {
  EXPECT_THROW(PsdSingularProblem(BoundKind::kBox, 8, 1), InvalidInputError);
  EXPECT_THROW(PsdSingularProblem(BoundKind::kLCP, 1, 1), InvalidInputError);
  EXPECT_THROW(NonPMultipleProblem(BoundKind::kMixed, 8, 1), InvalidInputError);
  EXPECT_THROW(NonPInfeasibleProblem(BoundKind::kRelay, 8, 1), InvalidInputError);  // finite box: always solvable
  EXPECT_THROW(NonPInfeasibleProblem(BoundKind::kLCP, 0, 1), InvalidInputError);
  EXPECT_THROW(SceneStepProblem("sign", 0.0, 1), InvalidInputError);
  EXPECT_THROW(SceneStepProblem("arctan", 0.1, 1), InvalidInputError);  // nonlinear scene
  EXPECT_THROW(SceneStepProblem("no-such-scene", 0.1, 1), InvalidInputError);
  EXPECT_THROW(MurtyProblem(1), InvalidInputError);
  EXPECT_THROW(MurtyProblem(41), InvalidInputError);
  EXPECT_THROW(CoupledSlidingModeProblem(0, 1), InvalidInputError);
  EXPECT_THROW(CoupledSlidingModeProblem(10, 1, 0.0), InvalidInputError);
  EXPECT_THROW(CoupledSlidingModeProblem(10, 1, std::nan("")), InvalidInputError);
  FamiliesOptions bad;
  bad.seeds = 0;
  std::string why;
  EXPECT_FALSE(bad.IsValid(&why));
  EXPECT_NE(why.find("seeds"), std::string::npos);
  EXPECT_THROW(FamiliesSuite(bad), InvalidInputError);
  ScaleOptions bad_scale;
  bad_scale.h = -1.0;
  EXPECT_THROW(ScaleSuite(bad_scale), InvalidInputError);
  try {
    MurtyProblem(1);
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("MurtyProblem"), std::string::npos);
  }
}

}  // namespace
}  // namespace smcbench
