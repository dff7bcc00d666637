// The small-h relay shared by the backends' tests: W = h·G with a planted solution s*, on which a residual test
// alone lets wrong s through as "solved" (the residual is O(h)), and the check each backend's test runs on it.
// Header-only: each backend test includes it.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solvers/core/problem.h"
#include "solvers/core/solver.h"
#include "solvers/core/verdict.h"

namespace smcbench::test_support {

// G is a fixed nonsymmetric matrix, diagonally dominant by rows and by columns (so its symmetric part is positive
// definite and G is a P-matrix and an H-matrix) with diagonal 1 … 300 (condition ≈ 300). s* has rows at ±1 and
// interior rows; q = −W s* + w with the correctly signed slack w = ∓h·c on the bound rows (w ≤ 0 at +1, ≥ 0 at
// −1), so s* is the unique solution for every h. The forward error allowed is verdict.h's, with μ computed here.
inline DenseMatrix SmallHMatrixG(int n) {
  std::mt19937_64 rng(1000 + n);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  DenseMatrix G(n, n);
  Vector d(n);
  for (int i = 0; i < n; ++i) d[i] = std::pow(300.0, static_cast<double>(i) / (n - 1));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      G(i, j) = i == j ? d[i] : 0.6 * unit(rng) * std::min(d[i], d[j]) / (n - 1);
    }
  }
  return G;
}

struct SmallHRelay {
  BoxMLCP problem;
  ReferenceSolution reference;  // s*, unique, with μ = ‖(D_F⁻¹ W_FF)⁻¹‖∞
};

inline SmallHRelay MakeSmallHRelay(int n, double h) {
  const DenseMatrix W = h * SmallHMatrixG(n);
  Vector s(n), w(n);
  for (int i = 0; i < n; ++i) {
    const double c = 0.1 + 0.25 * (i % 4);
    switch (i % 3) {
      case 0: s[i] = 1.0, w[i] = -h * c; break;           // at the upper bound: w ≤ 0
      case 1: s[i] = -1.0, w[i] = h * c; break;           // at the lower bound: w ≥ 0
      default: s[i] = 0.7 - 0.2 * (i % 5), w[i] = 0.0;    // interior
    }
  }
  const Vector q = w - W * s;
  BoxMLCP problem = BoxMLCP::Relay(W, q, -1.0, 1.0, "small-h-relay-n" + std::to_string(n));
  std::vector<int> free_rows;
  for (int i = 0; i < n; ++i) {
    if (w[i] == 0.0) free_rows.push_back(i);
  }
  const int nf = static_cast<int>(free_rows.size());
  DenseMatrix block(nf, nf);
  for (int a = 0; a < nf; ++a) {
    for (int b = 0; b < nf; ++b) block(a, b) = W(free_rows[a], free_rows[b]) / problem.row_scale()[free_rows[a]];
  }
  ReferenceSolution reference;
  reference.certificate = Certificate::kUnique;
  reference.z = s;
  reference.condition = nf == 0 ? 0.0 : DenseMatrix(block.inverse()).cwiseAbs().rowwise().sum().maxCoeff();
  return {std::move(problem), std::move(reference)};
}

inline constexpr double kSmallHs[] = {1e-2, 1e-4, 1e-6, 1e-8, 1e-10};

// The small-h check on one backend: at n = 4, 6, 8 and every h of kSmallHs, "solved" with ‖z − s*‖∞ within the
// forward-error allowance, with the base's exact polish and without it (the backend's own stopping test then
// decides). GoogleTest assertions: call it from a TEST.
inline void ExpectSolvedWithinAllowanceAtSmallH(Solver& solver) {
  for (int n : {4, 6, 8}) {
    for (double h : kSmallHs) {
      const SmallHRelay relay = MakeSmallHRelay(n, h);
      const std::string where =
          std::string(solver.info().name) + ": n = " + std::to_string(n) + ", h = " + std::to_string(h);
      SolverOptions options;  // tolerance 1e-10, polish on
      const double allowance = ForwardErrorAllowance(relay.reference, options.tolerance);
      const SolveResult r = solver.Solve(relay.problem, options);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << where << ": " << r.message;
      EXPECT_LE((r.z - relay.reference.z).cwiseAbs().maxCoeff(), allowance) << where;
      options.polish = false;
      const SolveResult raw = solver.Solve(relay.problem, options);
      ASSERT_EQ(raw.status, SolveStatus::kSolved) << where << " (polish off): " << raw.message;
      EXPECT_LE((raw.z - relay.reference.z).cwiseAbs().maxCoeff(), allowance) << where << " (polish off)";
    }
  }
}

}  // namespace smcbench::test_support
