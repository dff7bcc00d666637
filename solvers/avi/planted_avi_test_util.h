// Random AVIs with a planted solution (Feasible by construction: λ*, an active face and μ* ≥ 0 chosen first, then
// q := −Mλ* + Hᵀμ* + Eᵀν*), for the AVI tests. Seeded, so a failure names its problem.
#pragma once

#include <cstdint>
#include <string>

#include "solvers/avi/affine_vi.h"
#include "solvers/avi/avi_reduction.h"
#include "solvers/generators/seeded_random.h"

namespace smcbench {

struct PlantedAvi {
  AffineVI avi;
  AviSolution solution;  // λ*, μ*, ν*: unique when M + Mᵀ is positive definite (strictly_monotone)
  int active_rows = 0;   // rows of H with H_iλ* = K_i (μ*_i > 0 on them: strictly complementary)
};

// n unknowns, m random rows of H (the first `active` of them through λ*, the others 0.2 to 1 away from it), then the
// 2n rows λ*_j − 2 ≤ λ_j ≤ λ*_j + 2 (inactive, so P is bounded), and p random equality rows through λ*. active + p
// must be ≤ n (the active rows are then linearly independent with probability 1, and μ*, ν* unique).
// strictly_monotone: M = AᵀA/n + I/2 + (S − Sᵀ) (M + Mᵀ positive definite, M not symmetric); otherwise M = BᵀB
// with B of rank 1 (positive semidefinite and singular: λ need not be unique).
inline PlantedAvi MakePlantedAvi(int n, int m, int active, int p, std::uint64_t seed, bool strictly_monotone = true) {
  SeededRandom rng(seed);
  const auto uniform_matrix = [&](int rows, int cols) {
    DenseMatrix A(rows, cols);
    for (int j = 0; j < cols; ++j) {
      for (int i = 0; i < rows; ++i) A(i, j) = rng.Uniform(-1.0, 1.0);
    }
    return A;
  };
  Vector lambda(n);
  for (int j = 0; j < n; ++j) lambda[j] = rng.Uniform(-1.0, 1.0);
  const int rows = m + 2 * n;
  DenseMatrix H = DenseMatrix::Zero(rows, n);
  H.topRows(m) = uniform_matrix(m, n);
  Vector K(rows), mu = Vector::Zero(rows);
  for (int i = 0; i < m; ++i) {
    K[i] = H.row(i).dot(lambda) - (i < active ? 0.0 : rng.Uniform(0.2, 1.0));
    if (i < active) mu[i] = rng.Uniform(0.5, 2.0);
  }
  for (int j = 0; j < n; ++j) {
    H(m + 2 * j, j) = 1.0;
    K[m + 2 * j] = lambda[j] - 2.0;
    H(m + 2 * j + 1, j) = -1.0;
    K[m + 2 * j + 1] = -lambda[j] - 2.0;
  }
  const DenseMatrix E = uniform_matrix(p, n);
  const Vector f = E * lambda;
  Vector nu(p);
  for (int j = 0; j < p; ++j) nu[j] = rng.Uniform(-1.0, 1.0);
  DenseMatrix M;
  if (strictly_monotone) {
    const DenseMatrix A = uniform_matrix(n, n), S = uniform_matrix(n, n);
    M = A.transpose() * A / n + 0.5 * DenseMatrix::Identity(n, n) + (S - S.transpose());
  } else {
    const DenseMatrix B = uniform_matrix(1, n);
    M = B.transpose() * B;
  }
  const Vector q = -M * lambda + H.transpose() * mu + E.transpose() * nu;
  const std::string name = "planted-avi-n" + std::to_string(n) + "-m" + std::to_string(m) + "-a" +
                           std::to_string(active) + "-p" + std::to_string(p) + "-s" + std::to_string(seed);
  return PlantedAvi{AffineVI(M, q, H, K, E, f, name), AviSolution{lambda, mu, nu}, active};
}

}  // namespace smcbench
