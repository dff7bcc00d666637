// Seeded random box-MLCPs that are feasible by construction: pick z* and a complementary (w, v) first,
// then derive q = w − v − M z*. Used by the conformance tests and the benchmarks.
//
// Every family is a P-matrix, so z* is the unique solution. Rows of z*: at l with w ∈ [0.1, 1.1], at u with
// w ∈ [−1.1, −0.1], or at least 0.1 (10% of a finite box) inside with w = 0, with equal odds among the states
// the row's bounds allow; degenerate rows sit at a finite bound with w = 0. Sizes are capped (dense 8192,
// sparse 4,000,000); the dense build costs n³/2 flops, which dominates generating a large dense problem.
#pragma once

#include <cstdint>
#include <string>

#include "solvers/core/problem.h"

namespace smcbench {

enum class MatrixFamily {
  // M = AᵀA/λ̂ + δI, A with U(−1, 1) entries, λ̂ ≈ λ_max(AᵀA), δ = 1/99: spectrum in [δ, 1 + δ], cond ≈ 100.
  kSymmetricPositiveDefinite,
  // M = S + K with S as above and K skew-symmetric with ‖K‖₂ ≈ 1: positive definite, so a P-matrix.
  kNonsymmetricPMatrix,
  // Off-diagonal U(−1, 1)/(entries per row), M_ii = (1 + θ_i)·Σ_j≠i |M_ij| + 0.05 with θ_i ∈ [0.05, 0.5]:
  // strictly row diagonally dominant with positive diagonal (nonsymmetric), hence a P-matrix.
  kDiagonallyDominant,
  // M = S + K with S as in kSymmetricPositiveDefinite and K = G − Gᵀ, G strictly upper triangular with U(−1, 1)
  // entries, not normalized: ‖K‖₂ grows like √n while ‖S‖₂ ≈ 1, so M is strongly nonsymmetric (what a controller
  // with strong cross-coupling gives). Still positive definite (xᵀMx = xᵀSx), hence a P-matrix.
  kSkewPMatrix,
  // M = W D⁻¹ with W as in kDiagonallyDominant and D = diag(d_j), d_j ∈ [0.01, 1000] (U(1, 10) times 0.01, 1 or
  // 100 with equal odds), columns in units that differ by decades: M D = W is strictly row diagonally dominant with
  // a positive diagonal, so M is an H-matrix with positive diagonal, hence a P-matrix; its symmetric part is
  // indefinite (a P-matrix that is not positive definite: the methods whose proofs need M + Mᵀ ≻ 0 have none here).
  kScaledPMatrix,
};

enum class BoundKind {
  kLCP,    // l = 0, u = +∞
  kRelay,  // l = −1, u = +1 (the paper's sign problem)
  kBox,    // random finite l < u
  kMixed,  // each row, with equal odds: free (−∞, +∞), LCP (0, +∞), upper only (−∞, u), finite box
};

struct GeneratorOptions {
  int size = 8;
  MatrixFamily family = MatrixFamily::kSymmetricPositiveDefinite;
  BoundKind bounds = BoundKind::kLCP;
  // Fraction of rows made degenerate: z*_i at a bound AND w*_i = 0 (weak complementarity). round(fraction·n)
  // rows, fewer if fewer rows have a finite bound (free rows cannot be degenerate). Must lie in [0, 1].
  double degenerate_fraction = 0.0;
  std::uint64_t seed = 1;
  bool sparse = false;  // store M sparse with half-bandwidth 3 (7 diagonals); same families and properties
};

struct GeneratedProblem {
  BoxMLCP problem;
  Vector z_star;  // a solution; the unique one when M is a P-matrix
  GeneratorOptions options;
};

// Deterministic for a given options: std::mt19937_64 seeded with options.seed, uniform doubles taken from its
// raw bits and fixed-order loops (no std::*_distribution, no Eigen products), so the output is bit-identical
// across standard libraries and optimisation levels; only FMA contraction (-march with FMA) changes rounding.
// The problem is named "<family>-<bounds>-n<size>-s<seed>" (e.g. "spd-lcp-n8-s1"), with "-sparse" and
// "-deg<fraction>" appended when those options are set, so distinct problems never share a name.
// Throws InvalidInputError on invalid options (size <= 0 or above the cap, fraction outside [0, 1] or NaN,
// an out-of-range enum value).
GeneratedProblem GenerateProblem(const GeneratorOptions& options);

// An SPD problem of n rows with eigenvalues from 1 down to 1/condition (M = Q diag(λ) Qᵀ, Q orthogonal from a
// seeded random matrix, seed 29) and a planted solution. LCP (bounds kLCP): even rows positive with w = 0, odd rows
// at 0 with w > 0. Relay: rows at 1 (w < 0), at −1 (w > 0) and inside (w = 0) in turn. For the condition-dependent
// choice of the auto backend (docs/auto.md). Unlike GenerateProblem it uses Eigen's QR and products, so its bits may
// differ between builds. n ≥ 2, condition ≥ 1.
GeneratedProblem GenerateSpdWithCondition(int n, double condition, BoundKind bounds);

std::string ToString(MatrixFamily family);
std::string ToString(BoundKind bounds);

}  // namespace smcbench
