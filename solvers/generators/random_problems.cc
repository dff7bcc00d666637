// Seeded random box-MLCPs with a known solution (feasible by construction, as OSQP's and proxsuite's test
// generators do): pick bounds, then z* and a complementary w*, then set q = w* − M z*.
//
// Reproducibility: every random number comes from std::mt19937_64 (fully specified by the standard) through our
// own bit manipulation, never a std::*_distribution (their algorithms differ between standard libraries), and
// every floating-point reduction is an explicit loop in a fixed order (Eigen's products change their summation
// order with the SIMD width). The output is therefore bit-identical wherever IEEE double arithmetic is, i.e.
// unless the compiler contracts a*b+c into FMAs (-ffp-contract=fast with an FMA-capable -march).
#include "solvers/generators/random_problems.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solvers/core/number_text.h"
#include "solvers/generators/seeded_random.h"

namespace smcbench {
namespace {

// SPD part S = AᵀA/λ̂ + δI with λ̂ ≈ λ_max(AᵀA): spectrum in [δ, 1 + δ], so cond(S) ≲ 1 + 1/δ = kTargetCondition.
// Moderate on purpose: iterative backends (PSOR) should converge on it in a benchmark-friendly time.
constexpr double kTargetCondition = 100.0;
constexpr double kDelta = 1.0 / (kTargetCondition - 1.0);
// Skew part K of the P-matrix family, scaled to ‖K‖₂ ≈ kSkewNorm: as large as the symmetric part.
constexpr double kSkewNorm = 1.0;
// Half-bandwidth of M in sparse mode (7 diagonals).
constexpr int kHalfBandwidth = 3;
constexpr int kPowerIterations = 60;
// Dense construction costs n³/2 flops (AᵀA) and 8n² bytes; sparse O(n·h²).
constexpr int kMaxDenseSize = 8192;
constexpr int kMaxSparseSize = 4'000'000;

using Random = SeededRandom;

// M while it is built: dense column-major n×n, or banded with entries (i, j), |i − j| ≤ h, stored row by row.
class WorkMatrix {
 public:
  WorkMatrix(int n, bool banded) : n_(n), banded_(banded), h_(std::min(kHalfBandwidth, n - 1)) {
    const std::size_t width = banded_ ? static_cast<std::size_t>(2 * h_ + 1) : static_cast<std::size_t>(n_);
    values_.assign(static_cast<std::size_t>(n_) * width, 0.0);
  }

  int half_bandwidth() const { return h_; }
  // Columns j of row i in the pattern: [first(i), last(i)].
  int first(int i) const { return banded_ ? std::max(0, i - h_) : 0; }
  int last(int i) const { return banded_ ? std::min(n_ - 1, i + h_) : n_ - 1; }

  double& at(int i, int j) { return values_[Offset(i, j)]; }
  double at(int i, int j) const { return values_[Offset(i, j)]; }

  // y = M x with every y_i summed over j in increasing order (the dense column sweep adds the same terms in
  // the same order as a row sweep, so both layouts round identically while reading memory contiguously).
  void Multiply(const std::vector<double>& x, std::vector<double>* y) const {
    double* out = y->data();
    if (banded_) {
      for (int i = 0; i < n_; ++i) {
        const int j0 = first(i);
        const int j1 = last(i);
        const double* row = values_.data() + Offset(i, j0);
        double s = 0.0;
        for (int j = j0; j <= j1; ++j) s += row[j - j0] * x[static_cast<std::size_t>(j)];
        out[i] = s;
      }
      return;
    }
    std::fill(out, out + n_, 0.0);
    for (int j = 0; j < n_; ++j) {
      const double xj = x[static_cast<std::size_t>(j)];
      const double* column = values_.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(n_);
      for (int i = 0; i < n_; ++i) out[i] += column[i] * xj;
    }
  }

  void Scale(double factor) {
    for (double& v : values_) v *= factor;
  }

  void AddScaled(const WorkMatrix& other, double factor) {
    for (std::size_t k = 0; k < values_.size(); ++k) values_[k] += factor * other.values_[k];
  }

 private:
  std::size_t Offset(int i, int j) const {
    const auto row = static_cast<std::size_t>(i);
    const auto col = static_cast<std::size_t>(j);
    if (banded_) return row * static_cast<std::size_t>(2 * h_ + 1) + (col + static_cast<std::size_t>(h_) - row);
    return row + col * static_cast<std::size_t>(n_);
  }

  int n_;
  bool banded_;
  int h_;
  std::vector<double> values_;
};

double Dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}

// λ_max of the symmetric positive semidefinite operator x ↦ apply(x) by the power method from (1, ..., 1):
// a Rayleigh-quotient estimate from below, which is all the scaling needs.
template <typename Apply>
double LargestEigenvalue(int n, Apply apply) {
  std::vector<double> x(static_cast<std::size_t>(n), 1.0 / std::sqrt(static_cast<double>(n)));
  std::vector<double> y(static_cast<std::size_t>(n));
  double lambda = 0.0;
  for (int it = 0; it < kPowerIterations; ++it) {
    apply(x, &y);
    lambda = Dot(x, y);
    const double norm = std::sqrt(Dot(y, y));
    if (!(norm > 0.0)) return 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = y[k] / norm;
  }
  return lambda;
}

// S = AᵀA/λ̂ + δI. Dense: A is n×n with entries U(−1, 1). Banded: A is upper banded (A_kj ≠ 0 for
// 0 ≤ j − k ≤ h), so (AᵀA)_ij = Σ_k A_ki A_kj vanishes for |i − j| > h and S keeps M's band.
WorkMatrix SymmetricPositiveDefinite(int n, bool banded, Random& rng) {
  WorkMatrix S(n, banded);
  if (!banded) {
    std::vector<double> A(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));  // column-major
    for (double& a : A) a = rng.Uniform(-1.0, 1.0);
    for (int j = 0; j < n; ++j) {
      const double* aj = A.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(n);
      for (int i = 0; i <= j; ++i) {
        const double* ai = A.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(n);
        // Four fixed partial sums: instruction-level parallelism with a deterministic order.
        double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
        int k = 0;
        for (; k + 4 <= n; k += 4) {
          s0 += ai[k] * aj[k];
          s1 += ai[k + 1] * aj[k + 1];
          s2 += ai[k + 2] * aj[k + 2];
          s3 += ai[k + 3] * aj[k + 3];
        }
        for (; k < n; ++k) s0 += ai[k] * aj[k];
        const double s = (s0 + s1) + (s2 + s3);
        S.at(i, j) = s;
        S.at(j, i) = s;
      }
    }
  } else {
    WorkMatrix A(n, true);  // only the upper half of the band is used
    for (int k = 0; k < n; ++k) {
      for (int j = k; j <= A.last(k); ++j) A.at(k, j) = rng.Uniform(-1.0, 1.0);
    }
    const int h = S.half_bandwidth();
    for (int i = 0; i < n; ++i) {
      for (int j = i; j <= S.last(i); ++j) {
        // Rows k of A holding both columns i and j: j − h ≤ k ≤ i.
        double s = 0.0;
        for (int k = std::max(0, j - h); k <= i; ++k) s += A.at(k, i) * A.at(k, j);
        S.at(i, j) = s;
        S.at(j, i) = s;
      }
    }
  }
  const double lambda = LargestEigenvalue(n, [&S](const std::vector<double>& x, std::vector<double>* y) {
    S.Multiply(x, y);
  });
  S.Scale(lambda > 0.0 ? 1.0 / lambda : 0.0);
  for (int i = 0; i < n; ++i) S.at(i, i) += kDelta;
  return S;
}

// K = G − Gᵀ with G strictly upper triangular, U(−1, 1) entries (within the band if banded), not normalized.
WorkMatrix UnitEntrySkew(int n, bool banded, Random& rng) {
  WorkMatrix K(n, banded);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j <= K.last(i); ++j) {
      const double g = rng.Uniform(-1.0, 1.0);
      K.at(i, j) = g;
      K.at(j, i) = -g;
    }
  }
  return K;
}

// UnitEntrySkew scaled to ‖K‖₂ ≈ kSkewNorm.
WorkMatrix SkewSymmetric(int n, bool banded, Random& rng) {
  WorkMatrix K = UnitEntrySkew(n, banded, rng);
  std::vector<double> t(static_cast<std::size_t>(n));
  // ‖K‖₂² = λ_max(KᵀK) and KᵀK = −K².
  const double sigma2 = LargestEigenvalue(n, [&](const std::vector<double>& x, std::vector<double>* y) {
    K.Multiply(x, &t);
    K.Multiply(t, y);
    for (double& v : *y) v = -v;
  });
  if (sigma2 > 0.0) K.Scale(kSkewNorm / std::sqrt(sigma2));
  return K;
}

// Off-diagonal entries U(−1, 1)/c (c = off-diagonal count of a full row, so row sums stay ≤ 1) and
// M_ii = (1 + θ_i)·Σ_j|M_ij| + 0.05 with θ_i ∈ [0.05, 0.5]: strictly row diagonally dominant, positive diagonal.
WorkMatrix DiagonallyDominant(int n, bool banded, Random& rng) {
  WorkMatrix M(n, banded);
  const int full_row = banded ? std::min(n - 1, 2 * kHalfBandwidth) : n - 1;
  const double scale = 1.0 / std::max(1, full_row);
  for (int i = 0; i < n; ++i) {
    double off = 0.0;
    for (int j = M.first(i); j <= M.last(i); ++j) {
      if (j == i) continue;
      M.at(i, j) = scale * rng.Uniform(-1.0, 1.0);
      off += std::abs(M.at(i, j));
    }
    M.at(i, i) = (1.0 + rng.Uniform(0.05, 0.5)) * off + 0.05;
  }
  return M;
}

// Column j of M divided by d_j = c_j·10^k_j, c_j ∈ U(1, 10), k_j ∈ {−2, 0, 2} with equal odds: d spans five
// decades, [0.01, 1000] (arithmetic only, so the bits do not depend on the math library).
void ScaleColumnsByDecades(WorkMatrix* M, int n, Random& rng) {
  constexpr double kDecade[3] = {0.01, 1.0, 100.0};
  std::vector<double> scale(static_cast<std::size_t>(n));
  for (double& s : scale) s = 1.0 / (rng.Uniform(1.0, 10.0) * kDecade[rng.Index(3)]);
  for (int i = 0; i < n; ++i) {
    for (int j = M->first(i); j <= M->last(i); ++j) M->at(i, j) *= scale[static_cast<std::size_t>(j)];
  }
}

struct RowBounds {
  double l;
  double u;
};

RowBounds FiniteBox(Random& rng) {
  const double l = rng.Uniform(-2.0, 1.0);
  return {l, l + rng.Uniform(0.5, 3.0)};
}

RowBounds DrawBounds(BoundKind kind, Random& rng) {
  switch (kind) {
    case BoundKind::kLCP:
      return {0.0, kInf};
    case BoundKind::kRelay:
      return {-1.0, 1.0};
    case BoundKind::kBox:
      return FiniteBox(rng);
    case BoundKind::kMixed:
      switch (rng.Index(4)) {
        case 0:
          return {-kInf, kInf};
        case 1:
          return {0.0, kInf};
        case 2:
          return {-kInf, rng.Uniform(-1.0, 2.0)};
        default:
          return FiniteBox(rng);
      }
  }
  return {0.0, kInf};
}

// A point strictly inside [l, u], at least 0.1 (or 10% of the width) away from every finite bound.
double Interior(const RowBounds& b, Random& rng) {
  const bool has_l = std::isfinite(b.l);
  const bool has_u = std::isfinite(b.u);
  if (has_l && has_u) return b.l + (b.u - b.l) * rng.Uniform(0.1, 0.9);
  if (has_l) return b.l + rng.Uniform(0.1, 2.0);
  if (has_u) return b.u - rng.Uniform(0.1, 2.0);
  return rng.Uniform(-2.0, 2.0);
}

void Validate(const GeneratorOptions& o) {
  const std::string owner = "GeneratorOptions: ";
  if (o.size <= 0) throw InvalidInputError(owner + "size = " + std::to_string(o.size) + " must be positive");
  const int limit = o.sparse ? kMaxSparseSize : kMaxDenseSize;
  if (o.size > limit) {
    throw InvalidInputError(owner + "size = " + std::to_string(o.size) + " exceeds the " +
                            (o.sparse ? "sparse" : "dense") + " limit " + std::to_string(limit));
  }
  if (!(o.degenerate_fraction >= 0.0 && o.degenerate_fraction <= 1.0)) {
    throw InvalidInputError(owner + "degenerate_fraction = " + NumberText(o.degenerate_fraction) +
                            " must lie in [0, 1]");
  }
  if (ToString(o.family).rfind("invalid", 0) == 0) {
    throw InvalidInputError(owner + "family " + ToString(o.family) + " is not a MatrixFamily");
  }
  if (ToString(o.bounds).rfind("invalid", 0) == 0) {
    throw InvalidInputError(owner + "bounds " + ToString(o.bounds) + " is not a BoundKind");
  }
}

}  // namespace

std::string ToString(MatrixFamily family) {
  switch (family) {
    case MatrixFamily::kSymmetricPositiveDefinite:
      return "spd";
    case MatrixFamily::kNonsymmetricPMatrix:
      return "pmatrix";
    case MatrixFamily::kDiagonallyDominant:
      return "diagdom";
    case MatrixFamily::kSkewPMatrix:
      return "pmatrix-skew";
    case MatrixFamily::kScaledPMatrix:
      return "pmatrix-scaled";
  }
  return "invalid(" + std::to_string(static_cast<int>(family)) + ")";
}

std::string ToString(BoundKind bounds) {
  switch (bounds) {
    case BoundKind::kLCP:
      return "lcp";
    case BoundKind::kRelay:
      return "relay";
    case BoundKind::kBox:
      return "box";
    case BoundKind::kMixed:
      return "mixed";
  }
  return "invalid(" + std::to_string(static_cast<int>(bounds)) + ")";
}

GeneratedProblem GenerateProblem(const GeneratorOptions& options) {
  Validate(options);
  const int n = options.size;
  const bool banded = options.sparse;
  Random rng(options.seed);

  // 1. The matrix (draws first, so the same seed gives the same M whatever the bounds).
  WorkMatrix M(n, banded);
  switch (options.family) {
    case MatrixFamily::kSymmetricPositiveDefinite:
      M = SymmetricPositiveDefinite(n, banded, rng);
      break;
    case MatrixFamily::kNonsymmetricPMatrix: {
      // xᵀ(S + K)x = xᵀSx > 0: positive definite, hence every principal minor is positive (a P-matrix).
      M = SymmetricPositiveDefinite(n, banded, rng);
      M.AddScaled(SkewSymmetric(n, banded, rng), 1.0);
      break;
    }
    case MatrixFamily::kDiagonallyDominant:
      M = DiagonallyDominant(n, banded, rng);
      break;
    case MatrixFamily::kSkewPMatrix:  // xᵀ(S + K)x = xᵀSx > 0, as for kNonsymmetricPMatrix, with a larger K
      M = SymmetricPositiveDefinite(n, banded, rng);
      M.AddScaled(UnitEntrySkew(n, banded, rng), 1.0);
      break;
    case MatrixFamily::kScaledPMatrix:  // (W D⁻¹) D = W strictly row dominant, positive diagonal: an H-, so P-matrix
      M = DiagonallyDominant(n, banded, rng);
      ScaleColumnsByDecades(&M, n, rng);
      break;
  }

  // 2. Bounds, row by row.
  std::vector<RowBounds> bounds(static_cast<std::size_t>(n));
  for (RowBounds& b : bounds) b = DrawBounds(options.bounds, rng);

  // 3. Degenerate rows: round(fraction·n) of the rows with a finite bound (fewer if there are not enough),
  // chosen by a partial Fisher–Yates shuffle driven by our own Index().
  std::vector<int> eligible;
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(bounds[static_cast<std::size_t>(i)].l) || std::isfinite(bounds[static_cast<std::size_t>(i)].u)) {
      eligible.push_back(i);
    }
  }
  const int wanted = static_cast<int>(std::lround(options.degenerate_fraction * n));
  const int degenerate_count = std::min(wanted, static_cast<int>(eligible.size()));
  std::vector<bool> degenerate(static_cast<std::size_t>(n), false);
  for (int k = 0; k < degenerate_count; ++k) {
    const int pick = k + rng.Index(static_cast<int>(eligible.size()) - k);
    std::swap(eligible[static_cast<std::size_t>(k)], eligible[static_cast<std::size_t>(pick)]);
    degenerate[static_cast<std::size_t>(eligible[static_cast<std::size_t>(k)])] = true;
  }

  // 4. z* and w* complementary, row by row: at l with w > 0, at u with w < 0, strictly inside with w = 0; a
  // degenerate row sits at a bound with w = 0 (weak complementarity).
  std::vector<double> z(static_cast<std::size_t>(n));
  std::vector<double> w(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const RowBounds& b = bounds[static_cast<std::size_t>(i)];
    const bool has_l = std::isfinite(b.l);
    const bool has_u = std::isfinite(b.u);
    double& zi = z[static_cast<std::size_t>(i)];
    double& wi = w[static_cast<std::size_t>(i)];
    if (degenerate[static_cast<std::size_t>(i)]) {
      const bool at_lower = has_l && (!has_u || rng.Index(2) == 0);
      zi = at_lower ? b.l : b.u;
      wi = 0.0;
      continue;
    }
    // Equal odds for every state the row allows.
    const int states = 1 + (has_l ? 1 : 0) + (has_u ? 1 : 0);
    int state = rng.Index(states);  // 0 inside, then lower (if any), then upper (if any)
    if (state == 1 && !has_l) state = 2;
    if (state == 0) {
      zi = Interior(b, rng);
      wi = 0.0;
    } else if (state == 1) {
      zi = b.l;
      wi = rng.Uniform(0.1, 1.1);
    } else {
      zi = b.u;
      wi = -rng.Uniform(0.1, 1.1);
    }
  }

  // 5. q = w* − M z*.
  std::vector<double> Mz(static_cast<std::size_t>(n));
  M.Multiply(z, &Mz);
  Vector q(n), l(n), u(n), z_star(n);
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    q[i] = w[k] - Mz[k];
    l[i] = bounds[k].l;
    u[i] = bounds[k].u;
    z_star[i] = z[k];
  }

  // The documented "<family>-<bounds>-n<size>-s<seed>", plus "-sparse" and "-deg<fraction>" when those options
  // are not the defaults, so that different problems never share a name.
  std::string name = ToString(options.family) + "-" + ToString(options.bounds) + "-n" + std::to_string(n) + "-s" +
                     std::to_string(options.seed);
  if (options.sparse) name += "-sparse";
  if (options.degenerate_fraction > 0.0) name += "-deg" + NumberText(options.degenerate_fraction);

  if (banded) {
    std::vector<Eigen::Triplet<double, int>> entries;
    entries.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(2 * kHalfBandwidth + 1));
    for (int i = 0; i < n; ++i) {
      for (int j = M.first(i); j <= M.last(i); ++j) entries.emplace_back(i, j, M.at(i, j));
    }
    SparseMatrix S(n, n);
    S.setFromTriplets(entries.begin(), entries.end());
    return GeneratedProblem{BoxMLCP(std::move(S), std::move(q), std::move(l), std::move(u), std::move(name)),
                            std::move(z_star), options};
  }
  DenseMatrix D(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) D(i, j) = M.at(i, j);
  }
  return GeneratedProblem{BoxMLCP(std::move(D), std::move(q), std::move(l), std::move(u), std::move(name)),
                          std::move(z_star), options};
}

GeneratedProblem GenerateSpdWithCondition(int n, double condition, BoundKind bounds) {
  SeededRandom random(29);
  DenseMatrix A(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) A(i, j) = random.Uniform(-1.0, 1.0);
  }
  const DenseMatrix Q = Eigen::HouseholderQR<DenseMatrix>(A).householderQ();
  Vector lambda(n);
  for (int i = 0; i < n; ++i) lambda[i] = std::pow(condition, -static_cast<double>(i) / (n - 1));
  DenseMatrix M = Q * lambda.asDiagonal() * Q.transpose();
  M = 0.5 * (M + M.transpose()).eval();
  Vector z_star = Vector::Zero(n), w = Vector::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (bounds == BoundKind::kRelay) {
      if (i % 3 == 0) z_star[i] = 1.0, w[i] = -random.Uniform(0.1, 1.1);
      if (i % 3 == 1) z_star[i] = -1.0, w[i] = random.Uniform(0.1, 1.1);
      if (i % 3 == 2) z_star[i] = random.Uniform(-0.9, 0.9);
    } else if (i % 2 == 0) {
      z_star[i] = random.Uniform(0.5, 1.5);
    } else {
      w[i] = random.Uniform(0.1, 1.1);
    }
  }
  GeneratorOptions g;
  g.size = n;
  g.bounds = bounds;
  const std::string name = "spd-cond" + std::to_string(static_cast<long>(condition));
  const Vector q = w - M * z_star;
  return {bounds == BoundKind::kRelay ? BoxMLCP::Relay(M, q, -1.0, 1.0, name) : BoxMLCP::LCP(M, q, name), z_star, g};
}

}  // namespace smcbench
