// Seeded random box-MLCPs that are feasible by construction: pick z* and a complementary (w, v) first,
// then derive q = w − v − M z*. Used by the conformance tests and the benchmarks.
#pragma once

#include <cstdint>
#include <string>

#include "solvers/core/problem.h"

namespace smcbench {

enum class MatrixFamily {
  kSymmetricPositiveDefinite,  // M = AᵀA + δI, well conditioned
  kNonsymmetricPMatrix,        // M = S + K with S SPD and K skew-symmetric: positive definite, so a P-matrix
  kDiagonallyDominant,         // strictly row diagonally dominant with positive diagonal (nonsymmetric)
};

enum class BoundKind {
  kLCP,    // l = 0, u = +∞
  kRelay,  // l = −1, u = +1 (the paper's sign problem)
  kBox,    // random finite l < u
  kMixed,  // each row one of: free (−∞, +∞), LCP (0, +∞), upper only (−∞, u), finite box
};

struct GeneratorOptions {
  int size = 8;
  MatrixFamily family = MatrixFamily::kSymmetricPositiveDefinite;
  BoundKind bounds = BoundKind::kLCP;
  // Fraction of rows made degenerate: z*_i at a bound AND w*_i = 0 (weak complementarity).
  double degenerate_fraction = 0.0;
  std::uint64_t seed = 1;
  bool sparse = false;  // store M sparse (a banded/block pattern is used when true)
};

struct GeneratedProblem {
  BoxMLCP problem;
  Vector z_star;  // a solution; the unique one when M is a P-matrix
  GeneratorOptions options;
};

// Deterministic for a given options (std::mt19937_64 seeded with options.seed).
// The problem is named "<family>-<bounds>-n<size>-s<seed>" (e.g. "spd-lcp-n8-s1").
GeneratedProblem GenerateProblem(const GeneratorOptions& options);

std::string ToString(MatrixFamily family);
std::string ToString(BoundKind bounds);

}  // namespace smcbench
