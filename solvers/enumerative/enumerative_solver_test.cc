// Tests of the exhaustive active-set backend: known (multiple) solutions, closed-form relay problems,
// infeasibility proofs, singular free blocks, mixed bounds, limits, seeded P-matrix problems with a planted
// solution, degenerate rows and the Siconos problem on which Siconos' own enumeration fails. Every success is
// re-checked with a natural residual computed here, never by trusting the status.
#include "solvers/enumerative/enumerative_solver.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "tests/support/eigen_literals.h"

namespace smcbench {
namespace {

using test_support::Mat;
using test_support::Vec;

constexpr double kTol = 1e-10;

// ‖z − Π_[l,u](z − (Mz + q))‖∞ / (1 + ‖q‖∞), recomputed independently of the solver and of BoxMLCP.
double Residual(const BoxMLCP& p, const Vector& z) {
  const Vector w = p.dense_matrix() * z + p.q();
  double r = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    r = std::max(r, std::abs(z[i] - std::min(std::max(z[i] - w[i], p.l()[i]), p.u()[i])));
  }
  return r / (1.0 + p.q().cwiseAbs().maxCoeff());
}

SolveResult SolveWith(EnumerativeSolver& solver, const BoxMLCP& p, SolverOptions options = {}) {
  if (options.tolerance == SolverOptions{}.tolerance) options.tolerance = kTol;
  return solver.Solve(p, options);
}

// The default solver and one without the guided phase, so that the exhaustive nearest-first order alone is
// exercised too.
EnumerativeOptions Unguided() {
  EnumerativeOptions o;
  o.guided_steps = 0;
  return o;
}

void ExpectSolved(const BoxMLCP& p, const SolveResult& r, const std::string& where = {}) {
  EXPECT_EQ(r.status, SolveStatus::kSolved) << where << ": " << ToString(r.status) << " " << r.message;
  EXPECT_LE(Residual(p, r.z), kTol) << where;
  for (int i = 0; i < p.size(); ++i) {
    EXPECT_GE(r.z[i], p.l()[i]) << where << " row " << i;
    EXPECT_LE(r.z[i], p.u()[i]) << where << " row " << i;
  }
}

// ---------------------------------------------------------------------------------------------------------
// A small local generator of problems with a planted solution (feasible by construction): pick M, pick z* and
// each row's state, then choose w* with the complementary sign and set q = w* − M z*.

enum class Bounds { kLCP, kRelay, kBox, kMixed };

struct Planted {
  BoxMLCP problem;
  Vector z_star;
};

// Nonsymmetric P-matrix: S + K with S symmetric positive definite and K skew-symmetric (positive definite,
// hence every principal minor is positive).
DenseMatrix RandomPMatrix(int n, std::mt19937_64& rng, bool symmetric) {
  std::normal_distribution<double> g(0.0, 1.0);
  DenseMatrix A(n, n), K(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A(i, j) = g(rng), K(i, j) = g(rng);
  }
  DenseMatrix M = A.transpose() * A / n + 0.5 * DenseMatrix::Identity(n, n);
  if (!symmetric) M += 0.5 * (K - K.transpose());
  return M;
}

Planted MakePlanted(int n, Bounds bounds, std::uint64_t seed, double degenerate = 0.0, bool symmetric = false) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  const DenseMatrix M = RandomPMatrix(n, rng, symmetric);
  Vector l(n), u(n), z(n), w(n);
  for (int i = 0; i < n; ++i) {
    switch (bounds) {
      case Bounds::kLCP: l[i] = 0, u[i] = kInf; break;
      case Bounds::kRelay: l[i] = -1, u[i] = 1; break;
      case Bounds::kBox: l[i] = -1 - 2 * unif(rng), u[i] = l[i] + 0.5 + 3 * unif(rng); break;
      case Bounds::kMixed: {
        const int kind = static_cast<int>(5 * unif(rng));
        if (kind == 0) l[i] = -kInf, u[i] = kInf;                  // free
        else if (kind == 1) l[i] = 0, u[i] = kInf;                 // LCP
        else if (kind == 2) l[i] = -kInf, u[i] = 2 * unif(rng);    // upper only
        else if (kind == 3) l[i] = -1 - unif(rng), u[i] = 1;       // box
        else l[i] = u[i] = unif(rng) - 0.5;                         // fixed
        break;
      }
    }
    const double s = unif(rng);
    const bool degen = unif(rng) < degenerate;
    const double mag = degen ? 0.0 : 0.1 + unif(rng);
    if (l[i] == u[i]) {
      z[i] = l[i], w[i] = 2 * unif(rng) - 1;  // fixed row: any w
    } else if (s < 1.0 / 3 && std::isfinite(l[i])) {
      z[i] = l[i], w[i] = mag;
    } else if (s < 2.0 / 3 && std::isfinite(u[i])) {
      z[i] = u[i], w[i] = -mag;
    } else {
      const double lo = std::isfinite(l[i]) ? l[i] : -2.0, hi = std::isfinite(u[i]) ? u[i] : lo + 4.0;
      z[i] = lo + (0.1 + 0.8 * unif(rng)) * (hi - lo), w[i] = 0.0;
    }
  }
  Vector q = w - M * z;
  return {BoxMLCP(M, q, l, u, "planted-n" + std::to_string(n) + "-s" + std::to_string(seed)), z};
}

// ---------------------------------------------------------------------------------------------------------

TEST(EnumerativeOptions, DefaultsAreValidAndBadValuesAreExplained) {
  EXPECT_TRUE(EnumerativeOptions{}.IsValid(nullptr));
  EnumerativeOptions o;
  o.size_limit = 0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("size_limit"), std::string::npos) << why;
  o = {};
  o.rank_tolerance = 2.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("rank_tolerance"), std::string::npos) << why;

  EnumerativeSolver solver(o);
  const SolveResult r = solver.Solve(BoxMLCP::LCP(Mat({{1.0}}), Vec({-1.0})));
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("rank_tolerance"), std::string::npos) << r.message;
}

TEST(EnumerativeOptions, SetFromTextAndInfo) {
  EnumerativeSolver solver;
  std::string error;
  EXPECT_TRUE(solver.SetOption("size_limit", "12", &error)) << error;
  EXPECT_EQ(solver.options().size_limit, 12);
  EXPECT_TRUE(solver.SetOption("solve_singular_blocks", "false", &error)) << error;
  EXPECT_FALSE(solver.options().solve_singular_blocks);
  EXPECT_FALSE(solver.SetOption("feasibility_scale", "-1", &error));
  EXPECT_NE(error.find("feasibility_scale"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("omega", "1.5", &error));
  EXPECT_NE(error.find("unknown option"), std::string::npos) << error;
  EXPECT_NE(solver.OptionsHelp().find("max_candidates"), std::string::npos);

  const SolverInfo& info = solver.info();
  EXPECT_EQ(info.name, "enum");
  EXPECT_TRUE(info.dense);
  EXPECT_FALSE(info.sparse);
  EXPECT_TRUE(info.exact);
  EXPECT_EQ(info.default_size_limit, 20);
  EXPECT_FALSE(info.reference.empty());
}

TEST(Enumerative, OneByOneLcp) {
  EnumerativeSolver solver;
  // z = 2 > 0, w = 0.
  SolveResult r = SolveWith(solver, BoxMLCP::LCP(Mat({{2.0}}), Vec({-4.0})));
  ExpectSolved(BoxMLCP::LCP(Mat({{2.0}}), Vec({-4.0})), r);
  EXPECT_DOUBLE_EQ(r.z[0], 2.0);
  EXPECT_EQ(r.iterations, 1);
  // q > 0: z = 0.
  r = SolveWith(solver, BoxMLCP::LCP(Mat({{2.0}}), Vec({3.0})));
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.z[0], 0.0);
  EXPECT_EQ(r.iterations, 1);
}

TEST(Enumerative, InfeasibleLcpsAreProvenInfeasible) {
  EnumerativeSolver solver;
  // w = −z − 1 < 0 for every z ≥ 0.
  const BoxMLCP p1 = BoxMLCP::LCP(Mat({{-1.0}}), Vec({-1.0}));
  SolveResult r = SolveWith(solver, p1);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(r.iterations, 2 + r.GetDetail("guided_sets"));  // guided steps, then the full search
  EXPECT_LE(r.GetDetail("guided_sets"), 2.0) << "the guided phase stops at the first repeated set";
  EXPECT_NE(r.message.find("all 2 active sets"), std::string::npos) << r.message;
  EXPECT_GT(r.residual_rel, kTol);

  // w1 + w2 = −2 for every z: both cannot be ≥ 0.
  const BoxMLCP p2 = BoxMLCP::LCP(Mat({{1.0, -1.0}, {-1.0, 1.0}}), Vec({1.0, -3.0}));
  r = SolveWith(solver, p2);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(r.iterations, 4 + r.GetDetail("guided_sets"));
  EXPECT_NE(r.message.find("all 4 active sets"), std::string::npos) << r.message;

  // Same infeasibility through the run-time-size path (n = 6 > 4), with the other rows harmless.
  DenseMatrix M = DenseMatrix::Identity(6, 6);
  M(0, 0) = -1.0;
  Vector q = Vector::Ones(6);
  q[0] = -1.0;
  r = SolveWith(solver, BoxMLCP::LCP(M, q));
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(r.iterations, 64 + r.GetDetail("guided_sets"));
}

TEST(Enumerative, InfeasibilityIsOnlyClaimedWithAMargin) {
  // w = −z − 1e-9 < 0 for every z ≥ 0: infeasible, but the best candidate (z = 0) misses by only 1e-9, within
  // 100× the test threshold at tolerance 1e-10. That is reported as too close to call, not as a proof.
  EnumerativeSolver solver;
  SolveResult r = SolveWith(solver, BoxMLCP::LCP(Mat({{-1.0}}), Vec({-1e-9})));
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
  EXPECT_NE(r.message.find("not a proof of infeasibility"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("closest refutation"), std::string::npos) << r.message;
  // At a looser tolerance the same point is a solution.
  SolverOptions loose;
  loose.tolerance = 1e-8;
  r = SolveWith(solver, BoxMLCP::LCP(Mat({{-1.0}}), Vec({-1e-9})), loose);
  EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.z[0], 0.0);
}

TEST(Enumerative, IterationsCountEveryActiveSetOfAnInfeasibleMixedProblem) {
  // Row 0 is an infeasible decoupled LCP row; the others have 1 (free, fixed), 2 (one bound) or 3 (box)
  // states, so the exhaustive search must examine exactly 2 · 1 · 1 · 2 · 2 · 3 · 3 = 72 sets.
  DenseMatrix M = DenseMatrix::Identity(7, 7) * 2.0;
  M(0, 0) = -1.0;
  M(3, 4) = 0.5;
  M(5, 6) = -0.3;
  const Vector q = Vec({-1.0, 0.2, 0.1, -0.4, 0.3, 0.5, -0.5});
  const Vector l = Vec({0.0, -kInf, 0.5, 0.0, -kInf, -1.0, -2.0});
  const Vector u = Vec({kInf, kInf, 0.5, kInf, 1.0, 1.0, 3.0});
  const BoxMLCP p(M, q, l, u);
  EnumerativeSolver solver;
  SolveResult r = SolveWith(solver, p);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(r.iterations, 72 + r.GetDetail("guided_sets"));
  EXPECT_EQ(r.GetDetail("active_sets_total"), 72.0);
  EXPECT_NE(r.message.find("all 72 active sets"), std::string::npos) << r.message;
  // Without the guided phase the count is exactly the size of the full search.
  EnumerativeOptions o;
  o.guided_steps = 0;
  EnumerativeSolver plain(o);
  r = SolveWith(plain, p);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(r.iterations, 72);
  EXPECT_EQ(r.GetDetail("guided_sets"), 0.0);
}

TEST(Enumerative, FindsEachOfSeveralIsolatedSolutions) {
  // M = [1 2; 2 1], q = (−1, −1) has exactly three solutions: (1/3, 1/3), (1, 0) and (0, 1).
  const BoxMLCP p = BoxMLCP::LCP(Mat({{1.0, 2.0}, {2.0, 1.0}}), Vec({-1.0, -1.0}));
  EnumerativeSolver solver;
  const SolveResult cold = SolveWith(solver, p);
  ExpectSolved(p, cold, "cold");
  const std::vector<Vector> solutions = {Vec({1.0 / 3, 1.0 / 3}), Vec({1.0, 0.0}), Vec({0.0, 1.0})};
  bool cold_is_one = false;
  for (const Vector& s : solutions) cold_is_one = cold_is_one || (cold.z - s).cwiseAbs().maxCoeff() < 1e-12;
  EXPECT_TRUE(cold_is_one) << cold.z.transpose();
  // Warm-started at (near) each solution, the first active set tried is that solution's.
  for (const Vector& s : solutions) {
    SolverOptions o;
    o.warm_start = s + Vector::Constant(2, 1e-3);
    o.warm_start = o.warm_start.cwiseMax(0.0);
    if (s[0] == 0.0) o.warm_start[0] = 0.0;
    if (s[1] == 0.0) o.warm_start[1] = 0.0;
    const SolveResult r = SolveWith(solver, p, o);
    ExpectSolved(p, r, "warm");
    EXPECT_LT((r.z - s).cwiseAbs().maxCoeff(), 1e-12) << r.z.transpose() << " vs " << s.transpose();
    EXPECT_EQ(r.iterations, 1);
  }
}

TEST(Enumerative, ContinuumOfSolutions) {
  // M = [1 1; 1 1], q = (−1, −1): every z ≥ 0 with z1 + z2 = 1 solves it (M_FF singular for F = {1, 2}).
  const BoxMLCP p = BoxMLCP::LCP(Mat({{1.0, 1.0}, {1.0, 1.0}}), Vec({-1.0, -1.0}));
  EnumerativeSolver solver;
  const SolveResult r = SolveWith(solver, p);
  ExpectSolved(p, r);
  EXPECT_NEAR(r.z[0] + r.z[1], 1.0, 1e-12);
}

TEST(Enumerative, SingularFreeBlockWithConsistentSolution) {
  // M = [0 1; 0 0], q = (−1, 0): solutions are z = (0, s ≥ 1) and z = (t ≥ 0, 1), and every active set with a
  // free row has a singular M_FF (the free-free block is [0], [0] or M itself). Only the least-norm solution of
  // the consistent singular system for F = {1, 2}, z = (0, 1), solves it.
  const BoxMLCP p = BoxMLCP::LCP(Mat({{0.0, 1.0}, {0.0, 0.0}}), Vec({-1.0, 0.0}));
  EnumerativeSolver solver;
  SolveResult r = SolveWith(solver, p);
  ExpectSolved(p, r);
  EXPECT_NEAR(r.z[0], 0.0, 1e-14);
  EXPECT_NEAR(r.z[1], 1.0, 1e-14);
  EXPECT_GE(r.GetDetail("singular_blocks"), 1.0);

  // Skipping singular blocks (what a plain LU enumeration does) misses it, and says so: a skipped block could hide
  // a solution (here it does), so this is a failure of the method, never a claim that none exists.
  EnumerativeOptions o;
  o.solve_singular_blocks = false;
  EnumerativeSolver skipping(o);
  SolverOptions raw;
  raw.polish = false;
  r = SolveWith(skipping, p, raw);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
  EXPECT_NE(r.message.find("skipped"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("not a proof of infeasibility"), std::string::npos) << r.message;

  // The same structure in the run-time-size path: a 6×6 LCP with two such 2×2 blocks and an SPD remainder,
  // which makes the 4×4 free block singular of rank 2.
  DenseMatrix M = DenseMatrix::Zero(6, 6);
  M(0, 1) = 1.0, M(2, 3) = 2.0;
  M(4, 4) = 2.0, M(5, 5) = 3.0, M(4, 5) = M(5, 4) = 1.0;
  const Vector q = Vec({-1.0, 0.0, -4.0, 0.0, -1.0, 2.0});
  const BoxMLCP p6 = BoxMLCP::LCP(M, q);
  r = SolveWith(solver, p6);
  ExpectSolved(p6, r, "6x6");
}

TEST(Enumerative, InconsistentSingularBlocksAreRejected) {
  // M = 0 with q = (−1, 1): w = q, so row 0 can never have w ≥ 0 at z = 0 nor w = 0 when free.
  const BoxMLCP p = BoxMLCP::LCP(DenseMatrix::Zero(2, 2), Vec({-1.0, 1.0}));
  EnumerativeSolver solver;
  const SolveResult r = SolveWith(solver, p);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(r.iterations, 4 + r.GetDetail("guided_sets"));
  EXPECT_NE(r.message.find("singular"), std::string::npos) << r.message;
}

TEST(Enumerative, RelayOneByOneMatchesClosedForm) {
  // The paper's one-step relay problem, m = 1: z = Π_[−1,1](−q/M) for M > 0, found by the first guess.
  EnumerativeSolver solver;
  for (double m : {0.01, 0.5, 1.0, 7.0}) {
    for (double q : {-3.0, -1.0, -0.3, 0.0, 0.2, 0.999, 2.5, 40.0}) {
      const BoxMLCP p = BoxMLCP::Relay(Mat({{m}}), Vec({q}));
      const SolveResult r = SolveWith(solver, p);
      ExpectSolved(p, r, "m=" + std::to_string(m) + " q=" + std::to_string(q));
      EXPECT_NEAR(r.z[0], std::min(1.0, std::max(-1.0, -q / m)), 1e-15 * (1 + std::abs(q / m)));
      EXPECT_EQ(r.iterations, 1);
    }
  }
}

// Every solution of a 2×2 box-MLCP by independent case analysis: 3 × 3 state pairs, Cramer's rule.
std::vector<Vector> AllSolutions2x2(const BoxMLCP& p) {
  const DenseMatrix& M = p.dense_matrix();
  std::vector<Vector> out;
  for (int s0 = 0; s0 < 3; ++s0) {
    for (int s1 = 0; s1 < 3; ++s1) {
      const int s[2] = {s0, s1};  // 0 lower, 1 upper, 2 free
      Vector z(2);
      for (int i = 0; i < 2; ++i) z[i] = s[i] == 0 ? p.l()[i] : s[i] == 1 ? p.u()[i] : 0.0;
      if (!std::isfinite(z[0]) || !std::isfinite(z[1])) continue;
      if (s0 == 2 && s1 == 2) {
        const double det = M(0, 0) * M(1, 1) - M(0, 1) * M(1, 0);
        z[0] = (-p.q()[0] * M(1, 1) + p.q()[1] * M(0, 1)) / det;
        z[1] = (-p.q()[1] * M(0, 0) + p.q()[0] * M(1, 0)) / det;
      } else if (s0 == 2) {
        z[0] = -(p.q()[0] + M(0, 1) * z[1]) / M(0, 0);
      } else if (s1 == 2) {
        z[1] = -(p.q()[1] + M(1, 0) * z[0]) / M(1, 1);
      }
      if (Residual(p, z) <= 1e-12) out.push_back(z);
    }
  }
  return out;
}

TEST(Enumerative, RelayTwoByTwoMatchesCaseAnalysis) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unif(-3.0, 3.0);
  EnumerativeSolver solver;
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const DenseMatrix M = RandomPMatrix(2, rng, trial % 2 == 0);
    const BoxMLCP p = BoxMLCP::Relay(M, Vec({unif(rng), unif(rng)}));
    const std::vector<Vector> all = AllSolutions2x2(p);
    ASSERT_EQ(all.size(), 1u) << "a P-matrix relay problem has exactly one solution";
    const SolveResult r = SolveWith(solver, p);
    ExpectSolved(p, r, "trial " + std::to_string(trial));
    EXPECT_LT((r.z - all[0]).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE(r.iterations, 9);
    ++checked;
  }
  EXPECT_EQ(checked, 300);
}

TEST(Enumerative, BlockCacheFollowsTheMatrix) {
  // One problem object whose M changes between solves (set_M), a copy, and another problem of the same size:
  // the fast path's per-M factors must never be reused for another M. Each answer is checked against the case
  // analysis, and from a warm start at the previous answer so the same free set is guessed again.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unif(-3.0, 3.0);
  EnumerativeSolver solver;
  BoxMLCP p = BoxMLCP::Relay(RandomPMatrix(2, rng, true), Vec({0.1, -0.2}));
  SolveResult r;
  SolverOptions options;
  for (int trial = 0; trial < 200; ++trial) {
    if (trial % 3 == 1) p.set_M(RandomPMatrix(2, rng, trial % 2 == 0));
    p.set_q(Vec({0.2 * unif(rng), 0.2 * unif(rng)}));  // small q: mostly both rows free, the 2×2 block
    const BoxMLCP copy = p;
    const BoxMLCP other = BoxMLCP::Relay(RandomPMatrix(2, rng, true), p.q());
    for (const BoxMLCP* problem : {static_cast<const BoxMLCP*>(&p), &copy, &other}) {
      const std::vector<Vector> all = AllSolutions2x2(*problem);
      ASSERT_EQ(all.size(), 1u);
      options.warm_start = r.z.size() == 2 ? r.z : Vector();
      solver.Solve(*problem, options, &r);
      ExpectSolved(*problem, r, "trial " + std::to_string(trial));
      EXPECT_LT((r.z - all[0]).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
    }
  }
}

TEST(Enumerative, BlockCacheFollowsTheRankTolerance) {
  // A nearly singular free block: factored under the default rank tolerance, treated as singular (least-norm
  // solve in the full search) under a looser one set between two solves of the same problem.
  const BoxMLCP p = BoxMLCP::Relay(Mat({{1.0, 1.0}, {1.0, 1.0 + 1e-9}}), Vec({-0.1, -0.1}));
  EnumerativeSolver solver;
  SolveResult r;
  solver.Solve(p, SolverOptions{}, &r);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(r.GetDetail("singular_blocks"), 0.0);
  solver.mutable_options().rank_tolerance = 1e-6;
  solver.Solve(p, SolverOptions{}, &r);
  EXPECT_TRUE(r.solved()) << r.message;
  EXPECT_GE(r.GetDetail("singular_blocks"), 1.0);
  solver.mutable_options().rank_tolerance = 2.0;  // invalid, set directly between solves: still caught
  solver.Solve(p, SolverOptions{}, &r);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("rank_tolerance"), std::string::npos) << r.message;
}

TEST(Enumerative, MixedBoundsFreeUpperOnlyBoxFixed) {
  // Free row 0 (l = −∞, u = ∞), upper-only row 1, LCP row 2, box row 3, fixed row 4; z* planted with row 1 at
  // its upper bound, row 2 at 0, row 3 interior.
  const DenseMatrix M = Mat({{4, 1, 0, 0.5, 0},
                             {1, 3, 0.5, 0, 0.2},
                             {0, 0.5, 2, 0.3, 0},
                             {0.5, 0, 0.3, 5, 1},
                             {0, 0.2, 0, 1, 1}});
  const Vector l = Vec({-kInf, -kInf, 0.0, -1.0, 0.25});
  const Vector u = Vec({kInf, 2.0, kInf, 1.5, 0.25});
  const Vector z_star = Vec({-3.0, 2.0, 0.0, 0.7, 0.25});
  const Vector w_star = Vec({0.0, -1.5, 0.8, 0.0, 3.0});
  const BoxMLCP p(M, w_star - M * z_star, l, u);
  EnumerativeSolver solver;
  const SolveResult r = SolveWith(solver, p);
  ExpectSolved(p, r);
  EXPECT_LT((r.z - z_star).cwiseAbs().maxCoeff(), 1e-12) << r.z.transpose();
  EXPECT_EQ(r.GetDetail("active_sets_total"), 2.0 * 2.0 * 3.0);
}

TEST(Enumerative, SizeLimitIsCheckedBeforeAnyWork) {
  EnumerativeSolver solver;
  const int n = 21;
  SolveResult r = SolveWith(solver, BoxMLCP::LCP(DenseMatrix::Identity(n, n), Vector::Ones(n)));
  EXPECT_EQ(r.status, SolveStatus::kSizeLimit);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_NE(r.message.find("size_limit = 20"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("size_limit=N"), std::string::npos) << r.message;

  // 17 relay rows: 3^17 > max_candidates.
  r = SolveWith(solver, BoxMLCP::Relay(DenseMatrix::Identity(17, 17), Vector::Ones(17)));
  EXPECT_EQ(r.status, SolveStatus::kSizeLimit);
  EXPECT_NE(r.message.find("max_candidates"), std::string::npos) << r.message;

  // Free rows do not count: 40 free rows and 5 LCP rows is a 32-set search (planted solution).
  std::mt19937_64 rng(3);
  const DenseMatrix M = RandomPMatrix(45, rng, false);
  Vector l = Vector::Constant(45, -kInf), u = Vector::Constant(45, kInf), z = Vector::Zero(45), w = Vector::Zero(45);
  for (int i = 0; i < 45; ++i) {
    if (i < 5) l[i] = 0.0;
    if (i < 5 && i % 2 == 0) {
      w[i] = 0.5 + i;  // at the bound
    } else {
      z[i] = std::sin(1.0 + i) + (i < 5 ? 1.5 : 0.0);  // free (positive on the LCP rows)
    }
  }
  const BoxMLCP mlcp(M, w - M * z, l, u);
  r = SolveWith(solver, mlcp);
  ExpectSolved(mlcp, r, "mlcp");
  EXPECT_LT((r.z - z).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_EQ(r.GetDetail("active_sets_total"), 32.0);

  // Raising the limit lets a 21-row LCP run (its solution is z = 0).
  EnumerativeOptions o;
  o.size_limit = 21;
  o.max_candidates = 1 << 21;
  EnumerativeSolver big(o);
  r = SolveWith(big, BoxMLCP::LCP(DenseMatrix::Identity(n, n), Vector::Ones(n)));
  EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.iterations, 1);
}

TEST(Enumerative, RandomPMatrixProblemsMatchThePlantedSolution) {
  EnumerativeSolver guided, unguided(Unguided());
  for (EnumerativeSolver* solver : {&guided, &unguided})
  for (Bounds b : {Bounds::kLCP, Bounds::kRelay, Bounds::kBox, Bounds::kMixed}) {
    for (int n : {1, 2, 3, 4, 5, 7, 9, 12}) {
      if (b != Bounds::kLCP && n > 9) continue;  // 3^12 sets: keep the suite fast
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const Planted pl = MakePlanted(n, b, 100 * n + seed, 0.0, seed % 2 == 0);
        const SolveResult r = SolveWith(*solver, pl.problem);
        const std::string where = pl.problem.name() + " bounds " + std::to_string(static_cast<int>(b));
        ExpectSolved(pl.problem, r, where);
        EXPECT_LT((r.z - pl.z_star).cwiseAbs().maxCoeff(), 1e-8 * (1 + pl.z_star.cwiseAbs().maxCoeff())) << where;
      }
    }
  }
}

TEST(Enumerative, FindsTheSolutionFromAnyWarmStart) {
  // The nearest-first order covers every active set, whatever the starting guess.
  EnumerativeSolver solver(Unguided());
  std::mt19937_64 rng(5);
  int max_sets = 0;
  std::uniform_real_distribution<double> unif(-4.0, 4.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 3 + trial % 6;
    const Planted pl = MakePlanted(n, trial % 2 ? Bounds::kRelay : Bounds::kMixed, 900 + trial);
    SolverOptions o;
    o.warm_start = Vector(n);
    for (int i = 0; i < n; ++i) o.warm_start[i] = unif(rng);
    const SolveResult r = SolveWith(solver, pl.problem, o);
    ExpectSolved(pl.problem, r, pl.problem.name());
    EXPECT_LT((r.z - pl.z_star).cwiseAbs().maxCoeff(), 1e-8 * (1 + pl.z_star.cwiseAbs().maxCoeff()));
    max_sets = std::max(max_sets, r.iterations);
  }
  EXPECT_GT(max_sets, 20) << "some warm starts should be far from the solution's active set";
}

TEST(Enumerative, GuidedPhaseShortensTheSearch) {
  // Block principal pivoting from the natural-map guess: on P-matrix problems it typically needs a handful of
  // sets where the bare nearest-first order needs hundreds; both find the planted solution.
  EnumerativeSolver guided, unguided(Unguided());
  long long sets_guided = 0, sets_unguided = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Planted pl = MakePlanted(10, Bounds::kRelay, 4000 + seed, 0.0, true);
    const SolveResult a = SolveWith(guided, pl.problem), b = SolveWith(unguided, pl.problem);
    ExpectSolved(pl.problem, a, "guided");
    ExpectSolved(pl.problem, b, "unguided");
    EXPECT_LT((a.z - b.z).cwiseAbs().maxCoeff(), 1e-10);
    sets_guided += a.iterations;
    sets_unguided += b.iterations;
  }
  EXPECT_LT(sets_guided, sets_unguided);
  EXPECT_LE(sets_guided, 10 * 8) << "a few sets per problem";
}

TEST(Enumerative, WarmStartAtTheSolutionTakesOneActiveSet) {
  EnumerativeSolver solver;
  for (Bounds b : {Bounds::kLCP, Bounds::kRelay, Bounds::kMixed}) {
    const Planted pl = MakePlanted(10, b, 77);
    SolverOptions o;
    o.warm_start = pl.z_star;
    const SolveResult r = SolveWith(solver, pl.problem, o);
    ExpectSolved(pl.problem, r);
    EXPECT_EQ(r.iterations, 1);
  }
}

TEST(Enumerative, DegenerateProblems) {
  // z*_i at a bound with w*_i = 0 on half the rows: several active sets describe the same solution.
  EnumerativeSolver solver, unguided(Unguided());
  for (Bounds b : {Bounds::kLCP, Bounds::kRelay, Bounds::kBox, Bounds::kMixed}) {
    for (int n : {1, 2, 4, 6, 8}) {
      const Planted pl = MakePlanted(n, b, 31 * n + static_cast<int>(b), 0.5, true);
      for (EnumerativeSolver* s : {&solver, &unguided}) {
        const SolveResult r = SolveWith(*s, pl.problem);
        ExpectSolved(pl.problem, r, pl.problem.name());
        EXPECT_LT((r.z - pl.z_star).cwiseAbs().maxCoeff(), 1e-8 * (1 + pl.z_star.cwiseAbs().maxCoeff()));
      }
    }
  }
  // Fully degenerate: q = 0 (z = 0 with w = 0).
  const BoxMLCP p = BoxMLCP::LCP(Mat({{1.0, -1.0}, {-1.0, 1.0}}), Vec({0.0, 0.0}));
  const SolveResult r = SolveWith(solver, p);
  ExpectSolved(p, r);
}

// Reads a Siconos LCP file with dense storage: n, 0, rows, cols, rows, cols, M column-major, q.
BoxMLCP ReadSiconosDenseLcp(const std::string& path) {
  std::ifstream in(path);
  int n = 0, storage = -1, r0 = 0, c0 = 0, r1 = 0, c1 = 0;
  in >> n >> storage >> r0 >> c0 >> r1 >> c1;
  if (!in || storage != 0 || r0 != n || c0 != n) throw std::runtime_error("cannot read " + path);
  DenseMatrix M(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) in >> M(i, j);
  }
  Vector q(n);
  for (int i = 0; i < n; ++i) in >> q[i];
  if (!in) throw std::runtime_error("truncated " + path);
  return BoxMLCP::LCP(M, q, path.substr(path.find_last_of('/') + 1));
}

std::string SiconosLcp(const std::string& name) {
  return std::string(SMCBENCH_PEER_DATA_DIR) + "/siconos/lcp/" + name + ".dat";
}

TEST(Enumerative, SiconosPerturbedPangProblemIsInfeasible) {
  // M = [0 −1 −1; 1 0 0; −1 0 0], q = (−1e-4, −1, 1): rows 2 and 3 force z1 = 1, and then
  // w1 = −z2 − z3 − 1e-4 < 0. Siconos marks its own enumeration as failing here; the right answer is a proof.
  const BoxMLCP p = ReadSiconosDenseLcp(SiconosLcp("lcp_Pang_isolated_sol_perturbed"));
  EnumerativeSolver solver;
  const SolveResult r = SolveWith(solver, p);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_NE(r.message.find("all 8 active sets"), std::string::npos) << r.message;
  // The unperturbed problem (q1 = 0) is solvable.
  const BoxMLCP exact = ReadSiconosDenseLcp(SiconosLcp("lcp_Pang_isolated_sol"));
  ExpectSolved(exact, SolveWith(solver, exact));
}

// Occurrences of what in text.
int CountOf(const std::string& text, const std::string& what) {
  int count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++count;
  return count;
}

TEST(Enumerative, TheExhaustivePhaseDoesNotExamineTheGuidedSetsAgain) {
  // lcp_CPS_4 (M_44 = 0): the guided phase examines LLLF, whose free block (row 4 alone) is singular, and stops
  // when its next set repeats it; the exhaustive phase starts at that set. It still counts (iterations, singular
  // blocks, the determinant's sign), but its block's line of solutions is not searched a second time.
  EnumerativeSolver solver;
  SolverOptions verbose;
  verbose.verbosity = 2;
  const BoxMLCP cps4 = ReadSiconosDenseLcp(SiconosLcp("lcp_CPS_4"));
  testing::internal::CaptureStderr();
  SolveResult r = SolveWith(solver, cps4, verbose);
  std::string trace = testing::internal::GetCapturedStderr();
  ExpectSolved(cps4, r);
  EXPECT_NEAR((r.z - Vec({2.0, 2.0, 2.0, 92.0})).cwiseAbs().maxCoeff(), 0.0, 1e-12);
  EXPECT_EQ(r.iterations, 13);
  EXPECT_EQ(r.GetDetail("guided_sets"), 1.0);
  EXPECT_EQ(r.GetDetail("singular_blocks"), 2.0);
  EXPECT_EQ(CountOf(trace, "singular block, no point of its line"), 1) << trace;
  EXPECT_NE(trace.find("set 2 LLLF: examined in the guided phase; not again"), std::string::npos) << trace;

  // lcp_inf_sol_perturbed: both guided sets (FFL, then FLL with a singular block) come back first.
  const BoxMLCP perturbed = ReadSiconosDenseLcp(SiconosLcp("lcp_inf_sol_perturbed"));
  testing::internal::CaptureStderr();
  r = SolveWith(solver, perturbed, verbose);
  trace = testing::internal::GetCapturedStderr();
  ExpectSolved(perturbed, r);
  EXPECT_EQ(r.iterations, 5);
  EXPECT_EQ(CountOf(trace, "examined in the guided phase; not again"), 2) << trace;
  EXPECT_EQ(CountOf(trace, "singular block, no point of its line"), 1) << trace;

  // A proof of infeasibility still counts every set, the guided ones too (lcp_Pang_isolated_sol_perturbed).
  const BoxMLCP pang = ReadSiconosDenseLcp(SiconosLcp("lcp_Pang_isolated_sol_perturbed"));
  testing::internal::CaptureStderr();
  r = SolveWith(solver, pang, verbose);
  trace = testing::internal::GetCapturedStderr();
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_NE(r.message.find("all 8 active sets"), std::string::npos) << r.message;
  EXPECT_GE(CountOf(trace, "examined in the guided phase; not again"), 1) << trace;
}

TEST(Enumerative, SiconosEnumFailsProblem) {
  // Three 2-D frictional contacts: the friction-cone rows have M_ii = 0 and each multiplier column is a unit
  // vector, so 296 of the 512 complementary bases are singular. Siconos' lcp_enum detects singularity only by
  // an exactly zero LAPACK pivot and accepts any solution with no entry < −1e-6 (NaN and huge values pass): on
  // a platform where a singular basis rounds to a ~1e-18 pivot of the "wrong" sign it accepts a 1e13-sized
  // "solution". Here a relative pivot test routes such blocks to a rank-revealing least-norm solve, and the
  // merit function has the last word.
  const BoxMLCP p = ReadSiconosDenseLcp(SiconosLcp("lcp_enum_fails"));
  ASSERT_EQ(p.size(), 9);
  EnumerativeSolver solver;
  const SolveResult r = SolveWith(solver, p);
  ExpectSolved(p, r);
  EXPECT_LT(r.z.cwiseAbs().maxCoeff(), 1.0) << "a physical solution, not a blown-up singular one";

  // From scattered warm starts the search walks through many singular bases and still ends at a solution.
  EnumerativeSolver unguided(Unguided());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unif(0.0, 1e-3);
  double singular = 0.0;
  int max_sets = 0;
  for (int trial = 0; trial < 30; ++trial) {
    SolverOptions o;
    o.warm_start = Vector(9);
    for (int i = 0; i < 9; ++i) o.warm_start[i] = trial % 3 == 0 ? 0.0 : unif(rng);
    if (trial % 3 == 0) o.warm_start[trial % 9] = 1.0;
    const SolveResult rw = SolveWith(trial % 2 ? solver : unguided, p, o);
    ExpectSolved(p, rw, "trial " + std::to_string(trial));
    EXPECT_LT(rw.z.cwiseAbs().maxCoeff(), 1.0);
    singular += rw.GetDetail("singular_blocks");
    max_sets = std::max(max_sets, rw.iterations);
  }
  EXPECT_GT(singular, 0.0) << "the warm starts should lead the search through singular bases";
  EXPECT_GT(max_sets, 3);
}

TEST(Enumerative, IterationBudgetAndTimeLimit) {
  // An infeasible LCP (M = −I, q = −1: w = −z − 1 < 0) whose proof needs all 2^20 sets.
  const int n = 20;
  const BoxMLCP p = BoxMLCP::LCP(-DenseMatrix::Identity(n, n), -Vector::Ones(n));
  EnumerativeSolver solver;
  SolverOptions o;
  o.max_iterations = 1000;
  SolveResult r = SolveWith(solver, p, o);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_EQ(r.iterations, 1000);

  o = {};
  o.time_limit_seconds = 0.02;
  const auto t0 = std::chrono::steady_clock::now();
  r = SolveWith(solver, p, o);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit) << r.message;
  EXPECT_LT(elapsed, 1.0);
  EXPECT_GT(r.iterations, 0);
}

TEST(Enumerative, LongGuidedHistoryAndTracing) {
  // More guided steps than the fixed-size path keeps on its stack, on a 3-row problem and a 6-row one.
  EnumerativeOptions o;
  o.guided_steps = 50;
  EnumerativeSolver solver(o);
  DenseMatrix M = DenseMatrix::Identity(3, 3);
  M(0, 0) = -1.0;
  // Row 0 is an LCP row with w = −z − 2 < 0 for all z ≥ 0; rows 1, 2 are relay rows.
  const BoxMLCP infeasible(M, Vec({-2.0, 0.5, 3.0}), Vec({0.0, -1.0, -1.0}), Vec({kInf, 1.0, 1.0}));
  SolveResult r = SolveWith(solver, infeasible);
  EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(r.iterations, 18 + r.GetDetail("guided_sets"));
  const Planted pl = MakePlanted(6, Bounds::kBox, 12);
  r = SolveWith(solver, pl.problem);
  ExpectSolved(pl.problem, r);

  // Verbosity 2 traces every examined set to stderr (as a string of L/U/F/X states), verbosity 1 prints one line.
  SolverOptions verbose;
  verbose.verbosity = 2;
  testing::internal::CaptureStderr();
  r = SolveWith(solver, pl.problem, verbose);
  std::string trace = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(r.solved());
  EXPECT_NE(trace.find("enum: set 1 "), std::string::npos) << trace;
  EXPECT_NE(trace.find("solves; merit"), std::string::npos) << trace;
  verbose.verbosity = 1;
  testing::internal::CaptureStderr();
  r = SolveWith(solver, infeasible, verbose);
  trace = testing::internal::GetCapturedStderr();
  EXPECT_NE(trace.find("no solution exists"), std::string::npos) << trace;
}

TEST(Enumerative, ReusesTheWorkspaceAcrossSizes) {
  // Fixed-size and run-time-size paths interleaved, the workspace resized back and forth.
  EnumerativeSolver solver;
  const Planted a = MakePlanted(3, Bounds::kRelay, 1), b = MakePlanted(8, Bounds::kMixed, 2),
                c = MakePlanted(11, Bounds::kLCP, 3);
  for (int k = 0; k < 3; ++k) {
    for (const Planted* pl : {&a, &b, &c, &b}) {
      SolveResult r = SolveWith(solver, pl->problem);
      ExpectSolved(pl->problem, r, pl->problem.name());
      EXPECT_LT((r.z - pl->z_star).cwiseAbs().maxCoeff(), 1e-8 * (1 + pl->z_star.cwiseAbs().maxCoeff()));
    }
  }
}

// The fast path's 2×2 free blocks: a well-conditioned one is solved with its cached inverse, one with κ∞ above
// BlockCache::kInverseConditionLimit from its LU factors; both to the solve tolerance, in one set, warm or cold.
TEST(EnumerativeSolver, TwoByTwoFreeBlocksWellAndIllConditioned) {
  for (double eps : {1.0, 1e-7}) {
    SCOPED_TRACE(eps);
    DenseMatrix M(2, 2);
    M << 1.0, 1.0, 1.0, 1.0 + eps;  // κ∞ ≈ 4 / eps
    const Vector z_star = (Vector(2) << 0.3, -0.2).finished();  // inside the box: both rows free
    const Vector q = -(M * z_star);
    const BoxMLCP p = BoxMLCP::Relay(M, q);
    EnumerativeSolver solver;
    SolverOptions options;
    for (bool warm : {false, true}) {
      if (warm) options.warm_start = (Vector(2) << 0.1, 0.1).finished();
      const SolveResult r = solver.Solve(p, options);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      EXPECT_EQ(r.iterations, 1);
      EXPECT_LE(r.residual_rel, options.tolerance);
      const Vector reference = M.fullPivLu().solve(-q);
      EXPECT_LE((r.z - reference).cwiseAbs().maxCoeff(), 1e-9 / eps) << r.z.transpose();
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// Regression tests for verdicts that see the error in s: answers a residual test alone would pass as solved.

// A fixed orthogonal 3×3 matrix: the Householder reflection I − 2 v vᵀ / vᵀv.
DenseMatrix Householder3(const Vector& v) {
  return DenseMatrix::Identity(3, 3) - 2.0 * v * v.transpose() / v.squaredNorm();
}

// enum answered "infeasible" on a 3×3 SPD LCP with condition 1e13. An SPD matrix is a P-matrix: such an LCP always
// has exactly one solution, so that was a false certificate. Planted solutions are now found (the merit function
// accepts the LU candidate even though a pivot of the free block looks small); and when the one solution lies far
// out along the near-null direction (here ≈ 5e12, beyond what double precision can verify to 1e-10), the answer
// is a numerical failure, never a claim of infeasibility.
TEST(Enumerative, IllConditionedSpdLcpWasCalledInfeasible) {
  const Vector lambda = Vec({1.0, 1.0, 1e-13});
  EnumerativeSolver solver, unguided(Unguided());
  {
    const DenseMatrix Q = Householder3(Vec({1.0, 2.0, 3.0}));
    const DenseMatrix M = Q * lambda.asDiagonal() * Q.transpose();
    ASSERT_EQ(M.llt().info(), Eigen::Success);
    // An interior z* > 0, q = −M z*; and planted mixes: rows at 0 with w* > 0, the others interior.
    const std::vector<Vector> z_stars = {Vec({1.0, 2.0, 0.5}), Vec({0.0, 1.5, 0.7}), Vec({0.3, 0.0, 0.0})};
    for (const Vector& z_star : z_stars) {
      Vector w_star = Vector::Zero(3);
      for (int i = 0; i < 3; ++i) w_star[i] = z_star[i] == 0.0 ? 0.5 + i : 0.0;
      const BoxMLCP p = BoxMLCP::LCP(M, w_star - M * z_star);
      for (EnumerativeSolver* s : {&solver, &unguided}) {
        for (bool polish : {false, true}) {
          SolverOptions o;
          o.polish = polish;
          const SolveResult r = SolveWith(*s, p, o);
          EXPECT_NE(r.status, SolveStatus::kInfeasible) << r.message;
          ExpectSolved(p, r, "z* = " + std::to_string(z_star[0]) + " polish " + std::to_string(polish));
        }
      }
    }
  }
  {  // The near-null vector Q e₃ = (6, 6, 17)/19 is positive, and q = −e: the solution −M⁻¹q ≈ 5e12 (6, 6, 17)/19.
    const DenseMatrix Q = Householder3(Vec({-3.0, -3.0, 1.0}));
    const DenseMatrix M = Q * lambda.asDiagonal() * Q.transpose();
    ASSERT_EQ(M.llt().info(), Eigen::Success);
    const BoxMLCP p = BoxMLCP::LCP(M, Vec({-1.0, -1.0, -1.0}));
    for (EnumerativeSolver* s : {&solver, &unguided}) {
      for (bool polish : {false, true}) {
        SolverOptions o;
        o.polish = polish;
        const SolveResult r = SolveWith(*s, p, o);
        EXPECT_NE(r.status, SolveStatus::kInfeasible) << r.message;
        if (r.status == SolveStatus::kNumericalFailure) {
          EXPECT_NE(r.message.find("not a proof of infeasibility"), std::string::npos) << r.message;
        }
      }
    }
  }
}

// enum reported numerical_failure on an answer whose residual was within tolerance: a test of its own (the fast
// path's 4-ulp safety margin, the search's column-by-column merit value) rejected a point that the merit function,
// BoxMLCP::NaturalResidual, accepts. Rows with largest entry exactly 1 make the row equilibration the identity, so
// the search sees the same numbers as the base class. With the tolerance set to exactly the residual of the first
// answer, that answer is acceptable, and enum must say solved.
TEST(Enumerative, ReportedNumericalFailureOnAnAnswerWithinTolerance) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unif(-0.9, 0.9), unit(0.0, 1.0);
  int tested = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 6;
    DenseMatrix M(n, n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) M(i, j) = i == j ? 1.0 : unif(rng) / n;  // row max 1: D = I
    }
    Vector l(n), u(n), z(n), w(n);
    for (int i = 0; i < n; ++i) {
      l[i] = trial % 2 ? -1.0 : 0.0, u[i] = trial % 2 ? 1.0 : kInf;
      const double t = unit(rng);
      if (t < 0.3) {
        z[i] = l[i], w[i] = 0.1 + unit(rng);
      } else if (t < 0.5 && u[i] < kInf) {
        z[i] = u[i], w[i] = -0.1 - unit(rng);
      } else {
        z[i] = l[i] + (0.1 + 0.8 * unit(rng)) * (std::min(u[i], 2.0) - l[i]), w[i] = 0.0;
      }
    }
    const BoxMLCP p(M, w - M * z, l, u);
    ASSERT_TRUE((p.row_scale().array() == 1.0).all());
    EnumerativeSolver solver;
    SolverOptions o;
    o.polish = false;
    o.tolerance = 1e-12;
    const SolveResult first = solver.Solve(p, o);
    ASSERT_EQ(first.status, SolveStatus::kSolved) << first.message;
    const double reached = std::max(first.residual_rel, first.residual_scaled);
    if (!(reached > 0.0)) continue;  // an exact answer: no threshold to sit on
    o.tolerance = reached;
    for (int rep = 0; rep < 2; ++rep) {  // a fresh solver, then one with the block cache warm
      EnumerativeSolver again_solver;
      EnumerativeSolver& s = rep == 0 ? again_solver : solver;
      const SolveResult again = s.Solve(p, o);
      EXPECT_EQ(again.status, SolveStatus::kSolved) << "trial " << trial << ": " << again.message;
      EXPECT_LE(again.residual_rel, o.tolerance);
      EXPECT_LE(again.residual_scaled, o.tolerance);
    }
    ++tested;
  }
  EXPECT_GT(tested, 100);
}

// The small-h relay family: W = h·G with G a fixed nonsymmetric 6×6 matrix with a positive definite
// symmetric part (condition ≈ 230), planted s* with rows at ±1 and inside, q = −W s* + h·c (c ≤ 0 at +1, ≥ 0 at −1).
// At h = 1e-8 a wrong active set (|s − s*|∞ = 1) leaves a residual of order h, small enough to pass as solved;
// enum must not return it.
TEST(Enumerative, SmallStepRelayReturnedAWrongActiveSet) {
  constexpr int n = 6;
  std::mt19937 rng(2026);
  std::normal_distribution<double> normal(0.0, 1.0);
  DenseMatrix X(n, n), K(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) X(i, j) = normal(rng), K(i, j) = normal(rng);
  }
  const DenseMatrix Q = Eigen::HouseholderQR<DenseMatrix>(X).householderQ();
  Vector lambda(n);
  for (int i = 0; i < n; ++i) lambda[i] = std::pow(300.0, i / (n - 1.0));
  const DenseMatrix G = Q * lambda.asDiagonal() * Q.transpose() + 0.5 * (K - K.transpose());
  ASSERT_EQ((0.5 * (G + G.transpose())).llt().info(), Eigen::Success);
  const Vector sigma = Eigen::JacobiSVD<DenseMatrix>(G).singularValues();
  EXPECT_GT(sigma[0] / sigma[n - 1], 100.0);
  EXPECT_LT(sigma[0] / sigma[n - 1], 1000.0);
  const Vector s_star = Vec({1.0, -1.0, 0.3, 1.0, -0.55, -1.0});
  const Vector c = Vec({-0.8, 0.5, 0.0, -2.0, 0.0, 1.3});
  EnumerativeSolver solver, unguided(Unguided());
  for (double h : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10}) {
    const DenseMatrix W = h * G;
    const BoxMLCP p = BoxMLCP::Relay(W, -W * s_star + h * c);
    for (EnumerativeSolver* s : {&solver, &unguided}) {
      for (bool polish : {false, true}) {
        SolverOptions o;
        o.polish = polish;
        const SolveResult r = s->Solve(p, o);
        ASSERT_EQ(r.status, SolveStatus::kSolved) << "h = " << h << " polish " << polish << ": " << r.message;
        EXPECT_LE((r.z - s_star).cwiseAbs().maxCoeff(), 1e-9) << "h = " << h << " polish " << polish;
      }
    }
  }
}

// A problem that genuinely has no solution, of a class that can lack one (an infinite bound), keeps its
// certificate: every active set refuted with a margin.
TEST(Enumerative, InfeasibleWithAnInfiniteBoundKeepsItsCertificate) {
  EnumerativeSolver solver;
  SolverOptions raw;
  raw.polish = false;
  {  // LCP M = [−1], q = [−1]: w = −z − 1 < 0 for every z ≥ 0.
    const SolveResult r = SolveWith(solver, BoxMLCP::LCP(Mat({{-1.0}}), Vec({-1.0})), raw);
    EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
    EXPECT_NE(r.message.find("no solution exists"), std::string::npos) << r.message;
  }
  {  // A certificate row: row 0 of M is zero and q_0 = −1, so w_0 = −1 < 0 whatever z (the other rows are a
     // harmless P-matrix block); its free blocks are singular (a zero row), refuted by their equations.
    const BoxMLCP p = BoxMLCP::LCP(Mat({{0.0, 0.0, 0.0}, {0.5, 2.0, 1.0}, {-0.3, 1.0, 3.0}}), Vec({-1.0, 0.4, -2.0}));
    const SolveResult r = SolveWith(solver, p, raw);
    EXPECT_EQ(r.status, SolveStatus::kInfeasible) << r.message;
    EXPECT_NE(r.message.find("all 8 active sets"), std::string::npos) << r.message;
  }
}

// An exhausted search on a class that always has a solution is a failure of the method, and the message says why.
// A tolerance far below rounding makes every candidate miss while none is refuted (rows of largest entry 1, so the
// row equilibration is the identity and the search sees the numbers the base class judges).
TEST(Enumerative, ExhaustedSearchOnASolvableClassIsNotAProof) {
  const DenseMatrix M = Mat({{1.0, 0.3, -0.7}, {0.1, 1.0, 0.2}, {0.5, -0.2, 1.0}});  // M + Mᵀ diagonally dominant
  const Vector q = Vec({-1.0 / 3.0, -1.0 / 7.0, -2.0 / 3.0});
  SolverOptions tight;
  tight.polish = false;
  tight.tolerance = 1e-30;
  EnumerativeSolver solver;
  {  // M + Mᵀ positive definite (an LCP: infinite upper bounds).
    const SolveResult r = solver.Solve(BoxMLCP::LCP(M, q), tight);
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
    EXPECT_NE(r.message.find("not a proof of infeasibility"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("M + Mᵀ is positive definite, so a solution exists"), std::string::npos) << r.message;
  }
  {  // Every bound finite (a relay problem).
    const SolveResult r = solver.Solve(BoxMLCP::Relay(M, q), tight);
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
    EXPECT_NE(r.message.find("every bound is finite, so a solution exists"), std::string::npos) << r.message;
  }
  {  // A skipped singular block is never refuted: M = [0 1; 0 0], q = (−1, 0), whose solutions (0, s ≥ 1) and
     // (t ≥ 0, 1) all need one.
    const BoxMLCP p = BoxMLCP::LCP(Mat({{0.0, 1.0}, {0.0, 0.0}}), Vec({-1.0, 0.0}));
    EnumerativeOptions o;
    o.solve_singular_blocks = false;
    EnumerativeSolver skipping(o);
    SolverOptions raw;
    raw.polish = false;
    const SolveResult r = skipping.Solve(p, raw);
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
    EXPECT_NE(r.message.find("singular free blocks were skipped"), std::string::npos) << r.message;
  }
}

}  // namespace
}  // namespace smcbench
