// The box-MLCP ↔ physics-engine box-LCP rewrite (peer_box_form.h), tested both ways without any peer library: known
// solutions of ours satisfy the peer's complementarity conditions, the peer problem solved by our exact backend maps
// back to a solution of ours, and points make the round trip z → x → z exactly where the shift is zero.
#include "solvers/peer/peer_box_form.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "solvers/generators/random_problems.h"
#include "solvers/enumerative/enumerative_solver.h"

namespace smcbench {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// One row of each kind, two of them shifted: free, lower (0), upper (1), box around 0, fixed, lower at 2 (c = 2),
// upper at −3 (c = −3).
BoxMLCP EveryRowKind() {
  DenseMatrix M(7, 7);
  M << 4, 1, 0, 0.5, 0, 0.2, 0.1,  //
      1, 5, 1, 0, 0.3, 0, 0,       //
      0, -1, 6, 1, 0, 0.1, 0,      //
      0.5, 0, 1, 5, 1, 0, 0.3,     //
      0, 0.3, 0, 1, 4, 1, 0,       //
      0.2, 0, 0.1, 0, 1, 3, 0.5,   //
      0.1, 0, 0, -0.3, 0, 0.5, 2;
  Vector q(7), l(7), u(7);
  q << 1, -2, 3, -4, 0.5, 2, -1;
  l << -kInfinity, 0, -kInfinity, -1, 0.25, 2, -5;
  u << kInfinity, kInfinity, 1, 1, 0.25, 4, -3;
  return BoxMLCP(M, q, l, u, "every-row-kind");
}

// The peer's conditions at x (A x = b + w; x = lo ⇒ w ≥ 0, x = hi ⇒ w ≤ 0, inside ⇒ w = 0), as the largest
// violation: min(x − lo, w⁺)-style natural residual of their convention, x − Π_[lo,hi](x − w).
double PeerViolation(const PeerBoxForm& f, const Vector& x) {
  const Vector w = f.A * x - f.b;
  double worst = 0.0;
  for (int k = 0; k < f.size(); ++k) {
    const double projected = std::clamp(x[k] - w[k], f.lo[k], f.hi[k]);
    worst = std::max(worst, std::abs(x[k] - projected));
  }
  return worst;
}

TEST(PeerBoxForm, FreeRowsFirstFixedRowsEliminatedBoundsAroundZero) {
  const BoxMLCP p = EveryRowKind();
  const PeerBoxForm f = ToPeerBoxForm(p);
  EXPECT_EQ(f.nub, 1);
  EXPECT_EQ(f.permutation, (std::vector<int>{0, 1, 2, 3, 5, 6}));  // row 4 is fixed
  ASSERT_EQ(f.size(), 6);
  Vector expected_shift(7);
  expected_shift << 0, 0, 0, 0, 0.25, 2, -3;
  EXPECT_EQ(f.shift, expected_shift);
  for (int k = 0; k < f.size(); ++k) {
    EXPECT_LE(f.lo[k], 0.0) << k;
    EXPECT_GE(f.hi[k], 0.0) << k;
  }
  EXPECT_EQ(f.lo[0], -kInfinity);
  EXPECT_EQ(f.hi[0], kInfinity);
  EXPECT_EQ(f.lo[4], 0.0);  // row 5: [2, 4] − 2
  EXPECT_EQ(f.hi[4], 2.0);
  EXPECT_EQ(f.lo[5], -2.0);  // row 6: [−5, −3] + 3
  EXPECT_EQ(f.hi[5], 0.0);
  // A is M on the kept rows and columns, in the peer's order; b = −(q + M c) with the fixed row's c = 0.25 included.
  EXPECT_EQ(f.A(2, 1), -1.0);  // M(2, 1)
  EXPECT_EQ(f.A(5, 3), -0.3);  // M(6, 3)
  const Vector qc = p.q() + p.dense_matrix() * f.shift;
  for (int k = 0; k < f.size(); ++k) EXPECT_DOUBLE_EQ(f.b[k], -qc[f.permutation[k]]) << k;
}

TEST(PeerBoxForm, KnownSolutionsSatisfyThePeersComplementarityConditions) {
  int checked = 0;
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox, BoundKind::kMixed}) {
    for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix}) {
      for (std::uint64_t seed : {1u, 2u, 3u}) {
        GeneratorOptions g;
        g.size = 10;
        g.family = family;
        g.bounds = bounds;
        g.seed = seed;
        g.degenerate_fraction = 0.2;
        const GeneratedProblem gen = GenerateProblem(g);
        SCOPED_TRACE(gen.problem.name());
        const PeerBoxForm f = ToPeerBoxForm(gen.problem);
        for (int k = 0; k < f.size(); ++k) {
          ASSERT_LE(f.lo[k], 0.0);
          ASSERT_GE(f.hi[k], 0.0);
          ASSERT_EQ(k < f.nub, std::isinf(f.lo[k]) && std::isinf(f.hi[k]));
        }
        Vector x;
        ToPeerPoint(f, gen.z_star, &x);
        const double scale = 1.0 + gen.problem.q().cwiseAbs().maxCoeff() + gen.z_star.cwiseAbs().maxCoeff();
        EXPECT_LE(PeerViolation(f, x), 1e-12 * scale);
        // And a point that is not a solution violates them by as much as it violates ours.
        Vector z_off = gen.z_star;
        z_off[0] += 0.5;
        ToPeerPoint(f, z_off, &x);
        Vector w;
        EXPECT_NEAR(PeerViolation(f, x), gen.problem.NaturalResidual(z_off, &w).abs, 1e-12 * scale);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 24);
}

TEST(PeerBoxForm, ThePeerProblemSolvedByOurExactBackendMapsBackToASolution) {
  const BoxMLCP p = EveryRowKind();
  const PeerBoxForm f = ToPeerBoxForm(p);
  // Their problem in our words: w = A x − b, lo ≤ x ≤ hi.
  const BoxMLCP theirs(f.A, -f.b, f.lo, f.hi, "peer-form");
  EnumerativeSolver exact;
  SolverOptions options;
  options.tolerance = 1e-12;
  const SolveResult s = exact.Solve(theirs, options);
  ASSERT_TRUE(s.solved()) << s.message;
  Vector z;
  FromPeerPoint(f, s.z, &z);
  Vector w;
  EXPECT_LE(p.NaturalResidual(z, &w).rel, 1e-11);
  EXPECT_EQ(z[4], 0.25);  // the eliminated fixed row
  const SolveResult direct = exact.Solve(p, options);
  ASSERT_TRUE(direct.solved());
  EXPECT_LE((z - direct.z).cwiseAbs().maxCoeff(), 1e-10);  // M is a P-matrix here: one solution
}

TEST(PeerBoxForm, RoundTripGivesBackExactlyTheOriginalPoint) {
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int exact_rows = 0, shifted_rows = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 12;
    DenseMatrix M = DenseMatrix::NullaryExpr(n, n, [&] { return unit(rng); });
    Vector q = Vector::NullaryExpr(n, [&] { return 10.0 * unit(rng); });
    Vector l(n), u(n), z(n);
    for (int i = 0; i < n; ++i) {
      const int kind = static_cast<int>(rng() % 6);
      const double a = 100.0 * unit(rng), b = 100.0 * unit(rng);
      l[i] = kind == 0 ? -kInfinity : kind == 1 ? 0.0 : kind == 2 ? -kInfinity : std::min(a, b);
      u[i] = kind == 0 ? kInfinity : kind == 1 ? kInfinity : kind == 2 ? std::max(a, b) : std::max(a, b);
      if (kind == 5) u[i] = l[i];  // fixed
      // Any point in the box (a random mix of interior values and bounds).
      const double lo = std::isinf(l[i]) ? -1e3 : l[i], hi = std::isinf(u[i]) ? 1e3 : u[i];
      const double t = (unit(rng) + 1.0) / 2.0;
      z[i] = rng() % 4 == 0 ? (rng() % 2 == 0 ? lo : hi) : lo + t * (hi - lo);
      if (kind == 5) z[i] = l[i];
    }
    const BoxMLCP p(M, q, l, u);
    const PeerBoxForm f = ToPeerBoxForm(p);
    Vector x, back;
    ToPeerPoint(f, z, &x);
    FromPeerPoint(f, x, &back);
    for (int i = 0; i < n; ++i) {
      if (f.shift[i] == 0.0 || l[i] == u[i]) {
        EXPECT_EQ(back[i], z[i]) << "trial " << trial << " row " << i;  // bitwise
        ++exact_rows;
      } else {
        // A row shifted by c ≠ 0 (c and z on the same side of 0, |c| ≤ |z|): one subtraction, one addition.
        EXPECT_LE(std::abs(back[i] - z[i]), 2.0 * std::numeric_limits<double>::epsilon() * std::abs(z[i]))
            << "trial " << trial << " row " << i;
        ++shifted_rows;
      }
    }
    // b = −q bitwise when nothing is shifted.
    if (f.shift.cwiseAbs().maxCoeff() == 0.0) {
      for (int k = 0; k < f.size(); ++k) EXPECT_EQ(f.b[k], -q[f.permutation[k]]);
    }
  }
  EXPECT_GT(exact_rows, 300);
  EXPECT_GT(shifted_rows, 100);
}

TEST(PeerBoxForm, RoundTripIsExactOnShiftedRowsWhenTheDifferenceIsRepresentable) {
  // Dyadic data (multiples of 1/8 below 2^20): every z − c is a double, so the shifted rows come back bitwise too.
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 1 + trial % 8;
    DenseMatrix M = DenseMatrix::Identity(n, n);
    Vector q = Vector::Zero(n), l(n), u(n), z(n);
    for (int i = 0; i < n; ++i) {
      const double a = static_cast<double>(rng() % 8000) / 8.0 + 0.125;
      const double width = static_cast<double>(rng() % 800) / 8.0;
      const bool negative = rng() % 2 == 0;
      l[i] = negative ? -(a + width) : a;
      u[i] = negative ? -a : a + width;
      z[i] = l[i] + static_cast<double>(rng() % (static_cast<std::uint64_t>(width * 8.0) + 1)) / 8.0;
    }
    const BoxMLCP p(M, q, l, u);
    const PeerBoxForm f = ToPeerBoxForm(p);
    ASSERT_EQ(f.shift.cwiseAbs().minCoeff() > 0.0, true);
    Vector x, back;
    ToPeerPoint(f, z, &x);
    FromPeerPoint(f, x, &back);
    EXPECT_EQ(back, z) << "trial " << trial;
  }
}

}  // namespace
}  // namespace smcbench
