// The generators: z* solves every generated problem (residual recomputed here), the matrix families have the
// properties they promise, degenerate rows are degenerate, and the output is a pure function of the options.
#include "solvers/generators/random_problems.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace smcbench {
namespace {

constexpr MatrixFamily kFamilies[] = {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix,
                                      MatrixFamily::kDiagonallyDominant, MatrixFamily::kSkewPMatrix,
                                      MatrixFamily::kScaledPMatrix};
constexpr BoundKind kBounds[] = {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed};

GeneratorOptions Options(MatrixFamily family, BoundKind bounds, int size, std::uint64_t seed, bool sparse = false,
                         double degenerate = 0.0) {
  GeneratorOptions g;
  g.family = family;
  g.bounds = bounds;
  g.size = size;
  g.seed = seed;
  g.sparse = sparse;
  g.degenerate_fraction = degenerate;
  return g;
}

// w = M z + q computed here, densely, without the problem's own Affine().
Vector W(const BoxMLCP& p, const Vector& z) { return p.ToDense() * z + p.q(); }

// ‖z − Π_[l,u](z − w)‖∞ / (1 + ‖q‖∞), written out independently of the core library.
double RelativeNaturalResidual(const BoxMLCP& p, const Vector& z) {
  const Vector w = W(p, z);
  double r = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    const double projected = std::min(std::max(z[i] - w[i], p.l()[i]), p.u()[i]);
    r = std::max(r, std::abs(z[i] - projected));
    if (std::isnan(w[i])) r = kInf;
  }
  return r / (1.0 + p.q().cwiseAbs().maxCoeff());
}

std::string Describe(const GeneratorOptions& g) {
  return ToString(g.family) + "/" + ToString(g.bounds) + " n=" + std::to_string(g.size) + " seed=" +
         std::to_string(g.seed) + (g.sparse ? " sparse" : " dense") + " deg=" + std::to_string(g.degenerate_fraction);
}

void ExpectBoundsOfKind(const BoxMLCP& p, BoundKind kind) {
  for (int i = 0; i < p.size(); ++i) {
    const double l = p.l()[i];
    const double u = p.u()[i];
    switch (kind) {
      case BoundKind::kLCP:
        EXPECT_EQ(l, 0.0);
        EXPECT_EQ(u, kInf);
        break;
      case BoundKind::kRelay:
        EXPECT_EQ(l, -1.0);
        EXPECT_EQ(u, 1.0);
        break;
      case BoundKind::kBox:
        EXPECT_TRUE(std::isfinite(l) && std::isfinite(u) && l < u) << i;
        break;
      case BoundKind::kMixed: {
        const bool free_row = l == -kInf && u == kInf;
        const bool lcp_row = l == 0.0 && u == kInf;
        const bool upper_only = l == -kInf && std::isfinite(u);
        const bool box = std::isfinite(l) && std::isfinite(u) && l < u;
        EXPECT_TRUE(free_row || lcp_row || upper_only || box) << i << ": [" << l << ", " << u << "]";
        break;
      }
    }
  }
}

TEST(RandomProblems, ZStarSolvesEveryFamilyBoundKindSizeAndSeed) {
  int checked = 0;
  for (MatrixFamily family : kFamilies) {
    for (BoundKind bounds : kBounds) {
      for (int size : {1, 2, 5, 50}) {
        for (std::uint64_t seed : {1u, 2u, 977u}) {
          for (bool sparse : {false, true}) {
            for (double degenerate : {0.0, 0.3}) {
              const GeneratorOptions g = Options(family, bounds, size, seed, sparse, degenerate);
              SCOPED_TRACE(Describe(g));
              const GeneratedProblem gen = GenerateProblem(g);
              const BoxMLCP& p = gen.problem;
              ASSERT_EQ(p.size(), size);
              ASSERT_EQ(gen.z_star.size(), size);
              EXPECT_EQ(p.is_sparse(), sparse);
              ExpectBoundsOfKind(p, bounds);
              for (int i = 0; i < size; ++i) {
                EXPECT_GE(gen.z_star[i], p.l()[i]);
                EXPECT_LE(gen.z_star[i], p.u()[i]);
              }
              EXPECT_LE(RelativeNaturalResidual(p, gen.z_star), 1e-12);
              EXPECT_EQ(gen.options.seed, seed);
              ++checked;
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(checked, 5 * 4 * 4 * 3 * 2 * 2);
}

TEST(RandomProblems, StrictComplementarityWithoutDegenerateRows) {
  // With degenerate_fraction = 0, each row is either at a bound with |w| >= 0.1 of the right sign, or at least
  // 0.1 (or 10% of the box) inside with w = 0 up to rounding.
  for (MatrixFamily family : kFamilies) {
    for (BoundKind bounds : kBounds) {
      const GeneratorOptions g = Options(family, bounds, 50, 3);
      SCOPED_TRACE(Describe(g));
      const GeneratedProblem gen = GenerateProblem(g);
      const Vector w = W(gen.problem, gen.z_star);
      int at_lower = 0, at_upper = 0, inside = 0;
      for (int i = 0; i < 50; ++i) {
        const double z = gen.z_star[i];
        const double l = gen.problem.l()[i];
        const double u = gen.problem.u()[i];
        if (z == l) {
          EXPECT_GE(w[i], 0.1 - 1e-12) << i;
          ++at_lower;
        } else if (z == u) {
          EXPECT_LE(w[i], -0.1 + 1e-12) << i;
          ++at_upper;
        } else {
          const double margin = std::isfinite(u - l) ? 0.1 * (u - l) : 0.1;
          EXPECT_GE(z - l, margin * (1 - 1e-12)) << i;
          EXPECT_GE(u - z, margin * (1 - 1e-12)) << i;
          EXPECT_LE(std::abs(w[i]), 1e-12) << i;
          ++inside;
        }
      }
      // A mix of active sets: 50 rows give every available state several times.
      EXPECT_GT(at_lower, 0);
      EXPECT_GT(inside, 0);
      if (bounds != BoundKind::kLCP) {
        EXPECT_GT(at_upper, 0);
      } else {
        EXPECT_EQ(at_upper, 0);
      }
    }
  }
}

TEST(RandomProblems, DegenerateRowsAreAtABoundWithZeroW) {
  for (BoundKind bounds : kBounds) {
    for (double fraction : {0.2, 0.5, 1.0}) {
      const GeneratorOptions g = Options(MatrixFamily::kNonsymmetricPMatrix, bounds, 40, 11, false, fraction);
      SCOPED_TRACE(Describe(g));
      const GeneratedProblem gen = GenerateProblem(g);
      const Vector w = W(gen.problem, gen.z_star);
      int bounded_rows = 0;
      int degenerate_rows = 0;
      for (int i = 0; i < 40; ++i) {
        const double l = gen.problem.l()[i];
        const double u = gen.problem.u()[i];
        if (std::isfinite(l) || std::isfinite(u)) ++bounded_rows;
        const bool at_bound = gen.z_star[i] == l || gen.z_star[i] == u;
        if (at_bound && std::abs(w[i]) <= 1e-12) ++degenerate_rows;
      }
      // round(fraction·n) rows, or every row with a finite bound if there are fewer (mixed has free rows).
      const int expected = std::min(static_cast<int>(std::lround(fraction * 40)), bounded_rows);
      EXPECT_EQ(degenerate_rows, expected);
    }
  }
}

// All 2ⁿ − 1 principal minors of a 5×5 matrix.
void ExpectAllPrincipalMinorsPositive(const DenseMatrix& M) {
  const int n = static_cast<int>(M.rows());
  for (int mask = 1; mask < (1 << n); ++mask) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i) {
      if (mask & (1 << i)) idx.push_back(i);
    }
    DenseMatrix sub(idx.size(), idx.size());
    for (std::size_t a = 0; a < idx.size(); ++a) {
      for (std::size_t b = 0; b < idx.size(); ++b) sub(a, b) = M(idx[a], idx[b]);
    }
    EXPECT_GT(sub.determinant(), 0.0) << "principal minor with mask " << mask;
  }
}

TEST(RandomProblems, EveryFamilyIsAPMatrix) {
  for (MatrixFamily family : kFamilies) {
    for (bool sparse : {false, true}) {
      for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const GeneratorOptions g = Options(family, BoundKind::kLCP, 5, seed, sparse);
        SCOPED_TRACE(Describe(g));
        ExpectAllPrincipalMinorsPositive(GenerateProblem(g).problem.ToDense());
      }
    }
  }
}

TEST(RandomProblems, FamilyProperties) {
  for (bool sparse : {false, true}) {
    for (int n : {1, 2, 5, 50}) {
      SCOPED_TRACE(std::to_string(n) + (sparse ? " sparse" : " dense"));
      // SPD: symmetric, eigenvalues in [δ, ~1 + δ]: a moderate condition number.
      const BoxMLCP spd = GenerateProblem(Options(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, n, 7,
                                                  sparse)).problem;
      EXPECT_TRUE(spd.IsSymmetric(0.0));
      const Vector eig = Eigen::SelfAdjointEigenSolver<DenseMatrix>(spd.ToDense()).eigenvalues();
      EXPECT_GT(eig.minCoeff(), 0.0);
      EXPECT_LE(eig.maxCoeff() / eig.minCoeff(), 150.0);
      EXPECT_LE(eig.maxCoeff(), 1.5);

      // P-matrix family: nonsymmetric (n > 1) with a positive definite symmetric part.
      const BoxMLCP pm =
          GenerateProblem(Options(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, n, 7, sparse)).problem;
      const DenseMatrix P = pm.ToDense();
      if (n > 1) {
        EXPECT_FALSE(pm.IsSymmetric(1e-3));
      }
      const DenseMatrix sym = (P + P.transpose()) / 2;
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<DenseMatrix>(sym).eigenvalues().minCoeff(), 0.0);

      // Diagonally dominant: strict by rows, positive diagonal, nonsymmetric.
      const BoxMLCP dd =
          GenerateProblem(Options(MatrixFamily::kDiagonallyDominant, BoundKind::kLCP, n, 7, sparse)).problem;
      const DenseMatrix D = dd.ToDense();
      for (int i = 0; i < n; ++i) {
        const double off = D.row(i).cwiseAbs().sum() - std::abs(D(i, i));
        EXPECT_GT(D(i, i), 0.0);
        EXPECT_GT(D(i, i), off * 1.04) << "row " << i;
      }
      if (n > 2) {
        EXPECT_FALSE(dd.IsSymmetric(1e-3));
      }

      // Strongly nonsymmetric P-matrix: the same positive definite symmetric part as the SPD family, a skew part
      // with unit-scale entries that dominates it (‖K‖₂ ≥ 2‖S‖₂ at n = 50).
      const DenseMatrix K =
          GenerateProblem(Options(MatrixFamily::kSkewPMatrix, BoundKind::kLCP, n, 7, sparse)).problem.ToDense();
      const DenseMatrix k_sym = (K + K.transpose()) / 2, k_skew = (K - K.transpose()) / 2;
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<DenseMatrix>(k_sym).eigenvalues().minCoeff(), 0.0);
      if (n == 50) {
        const DenseMatrix gram = k_skew.transpose() * k_skew;
        const double skew_norm = std::sqrt(Eigen::SelfAdjointEigenSolver<DenseMatrix>(gram).eigenvalues().maxCoeff());
        const double sym_norm = Eigen::SelfAdjointEigenSolver<DenseMatrix>(k_sym).eigenvalues().maxCoeff();
        EXPECT_GT(skew_norm, 2.0 * sym_norm);
      }

      // Column-scaled diagonally dominant: an H-matrix with positive diagonal (some positive diagonal D makes M D
      // strictly row dominant), i.e. its comparison matrix (|M_ii| on the diagonal, −|M_ij| off it) is a
      // nonsingular M-matrix: its inverse is nonnegative.
      const DenseMatrix S =
          GenerateProblem(Options(MatrixFamily::kScaledPMatrix, BoundKind::kLCP, n, 7, sparse)).problem.ToDense();
      DenseMatrix comparison = -S.cwiseAbs();
      comparison.diagonal() = S.diagonal().cwiseAbs();
      for (int i = 0; i < n; ++i) EXPECT_GT(S(i, i), 0.0);
      const DenseMatrix inverse = comparison.inverse();
      EXPECT_GE(inverse.minCoeff(), -1e-12 * inverse.maxCoeff()) << "the comparison matrix of an H-matrix is a nonsingular M-matrix";
    }
  }
  // The column scaling makes the symmetric part indefinite: a P-matrix that is not positive definite.
  const DenseMatrix S =
      GenerateProblem(Options(MatrixFamily::kScaledPMatrix, BoundKind::kLCP, 50, 7, false)).problem.ToDense();
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<DenseMatrix>((S + S.transpose()) / 2).eigenvalues().minCoeff(), 0.0);
}

TEST(RandomProblems, SparseModeIsBanded) {
  for (MatrixFamily family : kFamilies) {
    const GeneratedProblem gen = GenerateProblem(Options(family, BoundKind::kBox, 200, 4, true));
    const SparseMatrix& S = gen.problem.sparse_matrix();
    for (int k = 0; k < S.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(S, k); it; ++it) EXPECT_LE(std::abs(it.row() - it.col()), 3);
    }
    EXPECT_LE(S.nonZeros(), 200 * 7);
    EXPECT_GE(S.nonZeros(), 200 * 5);
  }
}

bool SameBits(const Vector& a, const Vector& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

bool SameBits(const GeneratedProblem& a, const GeneratedProblem& b) {
  const DenseMatrix Ma = a.problem.ToDense();
  const DenseMatrix Mb = b.problem.ToDense();
  return Ma.size() == Mb.size() && std::memcmp(Ma.data(), Mb.data(), sizeof(double) * Ma.size()) == 0 &&
         SameBits(a.problem.q(), b.problem.q()) && SameBits(a.problem.l(), b.problem.l()) &&
         SameBits(a.problem.u(), b.problem.u()) && SameBits(a.z_star, b.z_star) &&
         a.problem.name() == b.problem.name();
}

TEST(RandomProblems, DeterministicInTheSeed) {
  for (MatrixFamily family : kFamilies) {
    for (BoundKind bounds : kBounds) {
      for (bool sparse : {false, true}) {
        const GeneratorOptions g = Options(family, bounds, 30, 42, sparse, 0.2);
        SCOPED_TRACE(Describe(g));
        const GeneratedProblem a = GenerateProblem(g);
        const GeneratedProblem b = GenerateProblem(g);
        EXPECT_TRUE(SameBits(a, b));
        GeneratorOptions other = g;
        other.seed = 43;
        const GeneratedProblem c = GenerateProblem(other);
        EXPECT_FALSE(SameBits(a, c));
        EXPECT_NE(a.problem.q(), c.problem.q());
        EXPECT_NE(a.problem.ToDense(), c.problem.ToDense());
      }
    }
  }
}

// FNV-1a over the bytes of M (dense, column-major), q, l, u and z*.
std::uint64_t Fingerprint(const GeneratedProblem& g) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto mix = [&h](const double* data, Eigen::Index count) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < static_cast<std::size_t>(count) * sizeof(double); ++k) {
      h = (h ^ bytes[k]) * 1099511628211ULL;
    }
  };
  const DenseMatrix M = g.problem.ToDense();
  mix(M.data(), M.size());
  mix(g.problem.q().data(), g.problem.size());
  mix(g.problem.l().data(), g.problem.size());
  mix(g.problem.u().data(), g.problem.size());
  mix(g.z_star.data(), g.z_star.size());
  return h;
}

TEST(RandomProblems, GoldenOutputIsStable) {
  // mt19937_64 is specified bit for bit by the standard (its 10000th output from the default seed).
  std::mt19937_64 engine(5489u);
  engine.discard(9999);
  EXPECT_EQ(engine(), 9981545732273789042ULL);
  // n = 1: M = a²/λ̂ + δ with λ̂ = a², i.e. 1 + 1/99 up to rounding.
  const GeneratedProblem one =
      GenerateProblem(Options(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 1, 1));
  EXPECT_DOUBLE_EQ(one.problem.ToDense()(0, 0), 1.0 + 1.0 / 99.0);
#if !defined(__FP_FAST_FMA)
  // Pinned outputs: a generated problem is identified by its options forever (benchmarks and stored results
  // refer to it by name). A change here changes every "<family>-<bounds>-n<size>-s<seed>" problem: do it only
  // on purpose. (Skipped where the compiler may fuse multiply-adds, which changes the rounding.)
  EXPECT_EQ(Fingerprint(GenerateProblem(Options(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 6, 1))),
            0xba00880753f45905ULL);
  EXPECT_EQ(Fingerprint(GenerateProblem(Options(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 7, 2,
                                                false, 0.3))),
            0x935054523843a58ULL);
  EXPECT_EQ(Fingerprint(GenerateProblem(Options(MatrixFamily::kDiagonallyDominant, BoundKind::kRelay, 9, 3, true))),
            0x34f79ec8ce234443ULL);
  EXPECT_EQ(Fingerprint(GenerateProblem(Options(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kBox, 12, 4, true,
                                                0.5))),
            0x8f3d2876ffa653f5ULL);
#endif
}

TEST(RandomProblems, Names) {
  EXPECT_EQ(GenerateProblem(GeneratorOptions{}).problem.name(), "spd-lcp-n8-s1");
  EXPECT_EQ(GenerateProblem(Options(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 5, 9)).problem.name(),
            "pmatrix-relay-n5-s9");
  EXPECT_EQ(GenerateProblem(Options(MatrixFamily::kDiagonallyDominant, BoundKind::kMixed, 3, 2, true, 0.25))
                .problem.name(),
            "diagdom-mixed-n3-s2-sparse-deg0.25");
  EXPECT_EQ(ToString(BoundKind::kBox), "box");
  EXPECT_EQ(ToString(MatrixFamily::kSymmetricPositiveDefinite), "spd");
}

TEST(RandomProblems, InvalidOptionsThrow) {
  GeneratorOptions g;
  g.size = 0;
  EXPECT_THROW(GenerateProblem(g), InvalidInputError);
  g.size = -4;
  EXPECT_THROW(GenerateProblem(g), InvalidInputError);
  g.size = 100000;  // dense limit
  EXPECT_THROW(GenerateProblem(g), InvalidInputError);
  g = GeneratorOptions{};
  for (double bad : {-0.01, 1.01, std::numeric_limits<double>::quiet_NaN(), kInf}) {
    g.degenerate_fraction = bad;
    EXPECT_THROW(GenerateProblem(g), InvalidInputError) << bad;
  }
  g = GeneratorOptions{};
  g.family = static_cast<MatrixFamily>(17);
  EXPECT_THROW(GenerateProblem(g), InvalidInputError);
  g = GeneratorOptions{};
  g.bounds = static_cast<BoundKind>(-1);
  EXPECT_THROW(GenerateProblem(g), InvalidInputError);
  try {
    g = GeneratorOptions{};
    g.degenerate_fraction = 2.0;
    GenerateProblem(g);
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate_fraction"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace smcbench
