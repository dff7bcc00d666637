// The step verdict's two paths (problems/stepper/step_verdict.h): a run is judged by the cached inverse of its
// active set's KKT matrix, a singular or ill-conditioned active set by the factored path, and both give the same
// verdict and the same s* (a refiner's first step since Reset is the factored path: the reference here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "problems/stepper/step_verdict.h"
#include "solvers/core/problem.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The factored path's judgement of the answer s (a fresh refiner: nothing cached).
StepCheck Factored(const DenseMatrix& M, const DenseMatrix& S, const Vector& q, Vector* s) {
  StepRefiner fresh;
  fresh.Reset(M, S, DenseMatrix(0, M.rows()), Vector());
  return fresh.Refine(q.data(), nullptr, s->data());
}

void ExpectSameJudgement(const StepCheck& a, const Vector& sa, const StepCheck& b, const Vector& sb) {
  EXPECT_EQ(a.exact, b.exact);
  if (!a.exact || !b.exact) return;
  for (Eigen::Index j = 0; j < sa.size(); ++j) EXPECT_NEAR(sa[j], sb[j], kEps * std::abs(sb[j])) << "s*_" << j;
  EXPECT_NEAR(a.x_error, b.x_error, 1e-6 * b.x_error + 1e-300);
}

// A relay run x_{k+1} = x_k − S s_{k+1}, q = −C x_k, solved by lemke to 1e-10: the reaching phase (both rows on a
// face), then sliding (interior) — two active sets, each repeated for many steps.
TEST(StepVerdictPaths, AWellConditionedRunIsJudgedByTheCachedPath) {
  const double h = 0.05;
  DenseMatrix B(2, 2), C(2, 2);
  B << 1.0, 0.2, 0.0, 1.0;
  C << 1.0, 0.0, 0.3, 1.0;
  const DenseMatrix S = h * B, M = C * S;
  StepRefiner refiner;
  refiner.Reset(M, S, DenseMatrix(0, 2), Vector());
  auto solver = CreateSolver("lemke");
  SolverOptions options;
  options.tolerance = 1e-10;
  Vector x(2);
  x << 0.4, -0.3;
  int cached = 0, steps = 0;
  for (int k = 0; k < 60; ++k, ++steps) {
    const Vector q = -C * x;
    SolveResult result;
    solver->Solve(BoxMLCP::Relay(M, q), options, &result);
    ASSERT_EQ(result.status, SolveStatus::kSolved) << "step " << k;
    Vector s = result.z, s_factored = result.z;
    const StepCheck check = refiner.Refine(q.data(), nullptr, s.data());
    const StepCheck factored = Factored(M, S, q, &s_factored);
    EXPECT_FALSE(factored.cached);
    ASSERT_TRUE(check.exact) << "step " << k;
    ExpectSameJudgement(check, s, factored, s_factored);
    cached += check.cached ? 1 : 0;
    x -= S * s;
  }
  EXPECT_LT(x.cwiseAbs().maxCoeff(), 1e-3);  // the run reached the sliding phase near the origin
  // Only the first step goes to the factored path (and a step the cached path cannot prove exact to a quarter ulp).
  std::printf("[ info     ] %d of %d steps judged by the cached path\n", cached, steps);
  EXPECT_GE(cached, steps - 3);
  // A refiner that forgets its active sets judges the next step by the factored path again.
  refiner.ForgetActiveSets();
  Vector s = Vector::Zero(2);
  const Vector q = -C * x;
  EXPECT_FALSE(refiner.Refine(q.data(), nullptr, s.data()).cached);
}

// The same answer judged three times (the active set repeats): the cached path declines where it cannot prove s*
// exact to a quarter ulp, and the factored path's verdict stands.
void ExpectFactoredEveryTime(const DenseMatrix& M, const Vector& q, const Vector& answer) {
  const DenseMatrix S = 0.1 * DenseMatrix::Identity(M.rows(), M.cols());
  StepRefiner refiner;
  refiner.Reset(M, S, DenseMatrix(0, M.rows()), Vector());
  for (int repeat = 0; repeat < 3; ++repeat) {
    Vector s = answer, s_factored = answer;
    const StepCheck check = refiner.Refine(q.data(), nullptr, s.data());
    const StepCheck factored = Factored(M, S, q, &s_factored);
    EXPECT_TRUE(check.exact) << "repeat " << repeat;
    EXPECT_FALSE(check.cached) << "repeat " << repeat;
    ExpectSameJudgement(check, s, factored, s_factored);
  }
}

TEST(StepVerdictPaths, ASingularActiveSetIsJudgedByTheFactoredPath) {
  // M of rank one (as the twisting scenes' C S): the interior set's KKT matrix is M itself, singular; s* is one of
  // the solutions s_1 + s_2 = 0.5.
  DenseMatrix M(2, 2);
  M << 0.1, 0.1, 0.1, 0.1;
  const Vector q = -M * Vector::Constant(2, 0.25);
  Vector answer(2);
  answer << 0.25 + 1e-9, 0.25 - 3e-9;
  ExpectFactoredEveryTime(M, q, answer);
}

TEST(StepVerdictPaths, AnIllConditionedActiveSetIsJudgedByTheFactoredPath) {
  // κ(M) ≈ 4e13: the cached inverse passes its residual test, but the bound on s*'s error (≈ κ u of long double)
  // is far above a quarter ulp.
  DenseMatrix M(2, 2);
  M << 1.0, 1.0, 1.0, 1.0 + 1e-13;
  Vector star(2);
  star << 0.3, -0.2;
  const Vector q = -M * star;
  Vector answer = star;
  answer[0] += 1e-11;
  ExpectFactoredEveryTime(M, q, answer);
}

// S4 filippov at h = 1e-5 (M = h(I − hA)⁻¹B ≈ 1e-5 B, |q| ≈ 1): the backend's answer s = (1, −1) is the exact
// solution (both rows on a face, multipliers of order 1), but w̃ = w/σ ≈ 5e4 made the long double solve's δ of
// order 1e-15 on the faces, read as s* outside the box: the run stopped on a correct step. On the box an active row
// fixes its coordinate exactly.
TEST(StepVerdictPaths, ASaturatedAnswerWithASmallMatrixIsExact) {
  DenseMatrix M(2, 2);
  M << 0x1.4f8b588e368f1p-17, -0x1.4f8b588e368f1p-16, 0x1.4f8b588e368f1p-16, 0x1.4f8b588e368f1p-17;
  Vector q(2);
  q << -0x1.fbaf102363b66p-1, 0x1.00b827fa1a122p+0;
  Vector s(2);
  s << 1.0, -1.0;
  const StepCheck check = Factored(M, M, q, &s);  // C = I: S = M
  ASSERT_TRUE(check.exact);
  EXPECT_EQ(s[0], 1.0);
  EXPECT_EQ(s[1], -1.0);
  EXPECT_EQ(check.x_error, 0.0);
}

// The same answer judged by a refiner that has judged a step before (the proofs in double, the cached path, then
// the factored path) and by a fresh one (the factored path): the judgement must not depend on which path gave it.
StepCheck JudgedAgainstFactored(const DenseMatrix& M, const DenseMatrix& S, const Vector& q, Vector* s) {
  StepRefiner refiner;
  refiner.Reset(M, S, DenseMatrix(0, M.rows()), Vector());
  Vector first = *s;
  refiner.Refine(q.data(), nullptr, first.data());  // the first step judged: the factored path
  Vector s_factored = *s;
  const StepCheck factored = Factored(M, S, q, &s_factored);
  const StepCheck check = refiner.Refine(q.data(), nullptr, s->data());
  EXPECT_EQ(check.exact, factored.exact);
  if (check.exact && factored.exact) {
    for (Eigen::Index j = 0; j < s->size(); ++j) EXPECT_NEAR((*s)[j], s_factored[j], kEps * std::abs(s_factored[j]));
    // The factored path's δ is within a few u_ld (|q|/σ + |s|) of s* − s (its w̃ = q/σ + M̃ s in long double).
    const double input_scale = S.cwiseAbs().rowwise().sum().maxCoeff();
    const double sigma = M.cwiseAbs().maxCoeff() > 0 ? M.cwiseAbs().maxCoeff() : 1.0;
    const double resolution = input_scale * 0x1p-60 * (q.cwiseAbs().maxCoeff() / sigma + s_factored.cwiseAbs().maxCoeff());
    EXPECT_NEAR(check.x_error, factored.x_error, 1e-6 * factored.x_error + resolution);
  }
  if (check.proved) {
    EXPECT_TRUE(check.cached);
  }
  return check;
}

// A saturated answer s = −1 with w = q − 1 = k ε exactly (q = 1 + kε, M = 1): the proof's bound is 2ε(|q| + |M|) ≈ 4ε,
// so k ≥ 5 is proved (s* = s, x_error 0) and k ≤ 4 goes to the solve, which gives the same verdict: exact for k > 0
// (the face), and for k ≤ 0 the free row's s* = −q (inside by |k|ε), never a proof.
TEST(StepVerdictProofs, ASaturatedAnswerIsProvedOnlyWithAMarginAboveTheRoundingBound) {
  DenseMatrix M(1, 1), S(1, 1);
  M << 1.0;
  S << 0.1;
  for (int k = -3; k <= 8; ++k) {
    Vector q(1), s(1);
    q << 1.0 + k * kEps;
    s << -1.0;
    const StepCheck check = JudgedAgainstFactored(M, S, q, &s);
    ASSERT_TRUE(check.exact) << "k = " << k;
    EXPECT_EQ(check.proved, k >= 5) << "k = " << k;
    if (k >= 0) {
      EXPECT_EQ(s[0], -1.0) << "k = " << k;
      EXPECT_EQ(check.x_error, 0.0) << "k = " << k;
    } else {
      EXPECT_EQ(s[0], -q[0]) << "k = " << k;
    }
  }
}

// Two inputs (the general proof, m + 1 = 3 terms a row): the second row's w moved across its bound. Far above it the
// step is proved; at half the bound or less it is not (the solve judges, the same verdict); the wrong sign is never
// proved (the answer is not on its face: the solve finds the exact step elsewhere).
TEST(StepVerdictProofs, ATwoInputSaturatedAnswerIsProvedOnlyWithAMargin) {
  DenseMatrix M(2, 2), S(2, 2);
  M << 1.0, 0.5, 0.25, 1.0;
  S << 0.1, 0.02, 0.0, 0.1;
  Vector s0(2);
  s0 << -1.0, 1.0;
  const double bound = 3 * kEps * (0.75 + 1.25);  // (m + 1)ε (|q_1| + Σ_j |M_1j|), q_1 ≈ 0.75
  for (const double factor : {-8.0, -1.0, -0.5, 0.0, 0.25, 0.5, 2.0, 8.0, 1e6}) {
    Vector q(2), s = s0;
    q << 2.0, 0.75;                    // w_0 = 2 − 1 + 0.5 = 1.5 > 0: row 0 on its lower face
    q[1] = -0.75 - factor * bound;     // w_1 = q_1 − 0.25 + 1 = −factor·bound (to rounding): upper face needs w_1 < 0
    const double w1 = q[1] + 0.25 * s[0] + 1.0 * s[1];
    const StepCheck check = JudgedAgainstFactored(M, S, q, &s);
    if (factor >= 2.0) {
      EXPECT_TRUE(check.proved) << "factor " << factor << ", w_1 = " << w1;
      EXPECT_EQ(s, s0);
    }
    if (factor <= 0.5) {
      EXPECT_FALSE(check.proved) << "factor " << factor << ", w_1 = " << w1;
    }
    if (check.proved) {
      EXPECT_EQ(s, s0);
      EXPECT_EQ(check.x_error, 0.0);
    }
  }
}

// h → 0: M = h B small, q of order 1 (filippov at h = 1e-5, the step of ASaturatedAnswerWithASmallMatrixIsExact, and
// a one-input relay down to h = 1e-9): the saturated answer is proved, exactly, where the long double solve's δ grows
// with w/σ.
TEST(StepVerdictProofs, ASaturatedAnswerWithASmallMatrixIsProved) {
  DenseMatrix M(2, 2);
  M << 0x1.4f8b588e368f1p-17, -0x1.4f8b588e368f1p-16, 0x1.4f8b588e368f1p-16, 0x1.4f8b588e368f1p-17;
  Vector q(2), s(2);
  q << -0x1.fbaf102363b66p-1, 0x1.00b827fa1a122p+0;
  s << 1.0, -1.0;
  StepCheck check = JudgedAgainstFactored(M, M, q, &s);
  EXPECT_TRUE(check.proved);
  EXPECT_EQ(s[0], 1.0);
  EXPECT_EQ(s[1], -1.0);
  for (const double h : {1e-5, 1e-7, 1e-9}) {
    DenseMatrix m1(1, 1);
    m1 << h;
    Vector q1(1), s1(1);
    q1 << 0.7;
    s1 << -1.0;
    check = JudgedAgainstFactored(m1, m1, q1, &s1);
    EXPECT_TRUE(check.proved) << "h = " << h;
    EXPECT_EQ(s1[0], -1.0);
  }
}

// m = 1 inside the box: s* = −q/M, the correctly rounded quotient, near the origin (x = 1e-10, 1e-14, 0: q = −x for
// x' ∈ −sgn(x), M = S = h) and at ordinary states, for answers exact and off by 1e-12 or by an ulp; the verdict is the
// factored path's, and the proof holds on all of them.
TEST(StepVerdictProofs, AOneInputStepInsideTheBoxIsTheCorrectlyRoundedQuotient) {
  for (const double h : {1e-2, 1e-5}) {
    DenseMatrix M(1, 1);
    M << h;
    for (const double x : {1e-10, -1e-14, 0.0, 0.3 * h, -0.999 * h}) {
      Vector q(1);
      q << -x;
      const double exact = x / h;
      for (const double off : {0.0, 1e-12, -2.2e-16}) {
        Vector s(1);
        s << exact + off;
        const StepCheck check = JudgedAgainstFactored(M, M, q, &s);
        ASSERT_TRUE(check.exact) << "h " << h << " x " << x << " off " << off;
        EXPECT_TRUE(check.proved) << "h " << h << " x " << x << " off " << off;
        EXPECT_EQ(s[0], -q[0] / M(0, 0));
        // ‖S‖∞|s − s*| = h|off|, to the rounding of the exact quotient.
        EXPECT_NEAR(check.x_error, h * std::abs(off), h * (1e-3 * std::abs(off) + 2 * kEps * std::abs(exact)) + 1e-300);
      }
    }
  }
}

// m = 1 inside the box near its face: s = 0.75, w = M s + q moved across the slack 1 − |s| = 0.25 (toward the upper
// face, w < 0). Far inside the slack it is proved; at the slack (to a few ulps) and past it the solve judges, with the
// same verdict, and a wrong answer (w far past the slack: the face is active) is never proved.
TEST(StepVerdictProofs, AOneInputStepAtTheSlackIsLeftToTheSolve) {
  DenseMatrix M(1, 1);
  M << 1.0;
  for (const double w : {-0.2, -0.25 * (1 - 64 * kEps), -0.25 * (1 - 4 * kEps), -0.25, -0.25 * (1 + 4 * kEps), -0.3,
                         -2.0}) {
    Vector q(1), s(1);
    s << 0.75;
    q << w - 0.75;
    const StepCheck check = JudgedAgainstFactored(M, 0.1 * M, q, &s);
    if (w >= -0.2) {
      EXPECT_TRUE(check.proved) << "w = " << w;
    }
    if (w <= -0.25 * (1 - 4 * kEps)) {
      EXPECT_FALSE(check.proved) << "w = " << w;
    }
    if (check.proved) {
      EXPECT_EQ(s[0], -q[0]);
    }
  }
}

// m = 2 inside the box: s* = s − M̃⁻¹w̃ with the inverse made at Reset, proved on the cached path's terms, near the
// origin (q = 1e-10, 1e-14, 0 in several directions), at an ordinary state and at h → 0 (M = h B), for exact answers
// and answers off by 1e-12 (but s* = 0 from an inexact answer: the factored path); near a face (1 − |s_j| down to
// 2^-40) and past it the verdict is the factored path's, whichever path gives it.
TEST(StepVerdictProofs, ATwoInputStepInsideTheBoxIsProvedAsTheFactoredPathJudgesIt) {
  DenseMatrix B(2, 2);
  B << 1.0, 0.5, 0.25, 1.0;
  for (const double h : {1e-2, 1e-5}) {
    const DenseMatrix M = h * B, S = h * DenseMatrix::Identity(2, 2);
    for (const double r : {1e-10, 1e-14, 0.0, 0.3 * h}) {
      for (const auto& [a, b] : {std::pair{0.0, 1.0}, {0.6, -0.8}}) {
        Vector star(2);
        star << r / h * a, r / h * b;
        const Vector q = -M * star;
        for (const double off : {0.0, 1e-12}) {
          Vector s = star;
          s[1] += off;
          const StepCheck check = JudgedAgainstFactored(M, S, q, &s);
          ASSERT_TRUE(check.exact) << "h " << h << " r " << r << " off " << off;
          // s* = 0 is taken on the cached path's terms only with a zero error bound (an exact answer, w = 0).
          if (r != 0.0 || off == 0.0) {
            EXPECT_TRUE(check.proved) << "h " << h << " r " << r << " off " << off;
          }
        }
      }
    }
    for (const double gap : {0x1p-10, 0x1p-30, 0x1p-40, 0.0, -0x1p-30}) {
      Vector star(2);
      star << 1.0 - gap, -0.2;
      const Vector q = -M * star;
      Vector s = star;
      s[0] = std::min(s[0], 1.0);
      const StepCheck check = JudgedAgainstFactored(M, S, q, &s);
      EXPECT_TRUE(check.exact) << "h " << h << " gap " << gap;
      if (gap == 0x1p-10) {
        EXPECT_TRUE(check.proved) << "h " << h;
      }
      // At the face the answer s_0 = 1 is a mixed one: past it (w_0 = −M_00 2^-30, the face's sign far above its
      // rounding) the mixed proof holds; at it, w_0 is the rounding of q = −M s* and the proof may or may not.
      if (gap < 0.0) {
        EXPECT_TRUE(check.proved) << "h " << h << " gap " << gap;
      }
    }
  }
}

// m = 2, a mixed set: row a saturated (s_a = ±1 exactly, its w_a of its face's sign), the other row inside with
// s*_i = −(q_i + M_ia s_a)/M_ii. Every face, either row saturated, interior values ordinary, near the origin and 0,
// exact answers and answers off by 1e-12 or 1e-6 (s* is the exact step and x_error says how far the answer was:
// the stepper's allowance then refines it): proved, with the factored path's verdict, and s* as the cached path
// takes it (within a quarter ulp of ‖s*‖∞ = 1 of the exact step each: an interior 1e-12 is the difference of
// q_i and M_ia s_a, of order 1, and no path resolves it below u_ld).
TEST(StepVerdictProofs, AMixedAnswerIsProvedAsTheFactoredPathJudgesIt) {
  DenseMatrix B(2, 2);
  B << 1.0, 0.5, 0.25, 1.0;
  const double h = 1e-2;
  const DenseMatrix M = h * B, S = h * DenseMatrix::Identity(2, 2);
  for (const int a : {0, 1}) {
    const int i = 1 - a;
    for (const double face : {-1.0, 1.0}) {
      for (const double interior : {0.3, -0.7, 1e-12, 0.0}) {
        for (const double off : {0.0, 1e-12, 1e-6}) {
          Vector star(2);
          star[a] = face;
          star[i] = interior;
          Vector q = -M * star;
          q[a] += -face * 0.3 * h;  // w_a = −face·0.3h: the face's sign (s_a = −1: w_a > 0)
          StepRefiner refiner;
          refiner.Reset(M, S, DenseMatrix(0, 2), Vector());
          Vector first = star;
          refiner.Refine(q.data(), nullptr, first.data());  // the first step judged: the factored path
          Vector s = star, s_factored = star;
          s[i] += off;
          s_factored[i] += off;
          const StepCheck check = refiner.Refine(q.data(), nullptr, s.data());
          const StepCheck factored = Factored(M, S, q, &s_factored);
          const std::string where = "a " + std::to_string(a) + " face " + std::to_string(face) + " interior " +
                                    std::to_string(interior) + " off " + std::to_string(off);
          ASSERT_TRUE(factored.exact) << where;
          ASSERT_TRUE(check.exact) << where;
          EXPECT_TRUE(check.proved) << where;
          EXPECT_TRUE(check.cached) << where;
          EXPECT_EQ(s[a], face) << where;
          EXPECT_NEAR(s[i], s_factored[i], kEps / 2) << where;
          // x_error = h|s − s*|: off, to the resolution of w̃ (u_ld times terms of order 1, in units of s).
          EXPECT_NEAR(check.x_error, factored.x_error, 1e-6 * factored.x_error + h * 0x1p-58) << where;
          EXPECT_NEAR(check.x_error, h * off, 1e-6 * h * off + h * 4 * kEps) << where;
        }
      }
    }
  }
}

// The mixed proof falls through (the cached or factored path judges, with the same verdict) when the saturated row's
// w has the wrong sign, is 0, or is positive by less than its rounding bound; when the row inside reads its face; and
// when the step's s*_i is inside the box by less than its error bound. M = [[1, 2^-70], [1/4, 1]]: w_0 = q_0 − 1 +
// 2^-70 s_1 is exact in binary.
TEST(StepVerdictProofs, AMixedAnswerIsProvedOnlyWithItsMargins) {
  DenseMatrix M(2, 2);
  M << 1.0, 0x1p-70, 0.25, 1.0;
  const DenseMatrix S = 0.1 * M;
  struct Case {
    double d;   // q_0 = 1 + d
    double s1;  // the answer's (and the step's) s_1: q_1 = 1/4 − s_1
    bool proved;
  };
  for (const Case c : {Case{-0.3, 0.25, false}, Case{0.0, 0.0, false}, Case{0.0, 0.25, false},  // w_0 < 0, 0, 2^-72
                       Case{0.3, 0.25, true}}) {
    Vector q(2), s(2);
    q << 1.0 + c.d, 0.25 - c.s1;
    s << -1.0, c.s1;
    const StepCheck check = JudgedAgainstFactored(M, S, q, &s);
    EXPECT_EQ(check.proved, c.proved) << "d " << c.d << " s_1 " << c.s1;
  }
  // The row inside read at its face: s_1 = 0.95 with w̃_1 = −0.1 past its slack 0.05 (the step is on both faces).
  {
    DenseMatrix B(2, 2);
    B << 1.0, 0.5, 0.25, 1.0;
    Vector q(2), s(2);
    s << -1.0, 0.95;
    q << 1.0 - 0.5 * 0.95 + 0.3, 0.25 - 0.95 - 0.1;
    const StepCheck check = JudgedAgainstFactored(B, 0.1 * B, q, &s);
    EXPECT_TRUE(check.exact);
    EXPECT_FALSE(check.proved);
  }
  // s*_1 = 1 − gap (M_10 = −gap, q_1 = −1, s_0 = −1): proved far inside (2^-10, 2^-40), not within the bound of the
  // face (2^-70: the answer's double is 1 − 2^-53, an ulp inside, whose slack |w̃_1| misses by 2^-70) nor at it.
  for (const double gap : {0x1p-10, 0x1p-40, 0x1p-70, 0.0}) {
    DenseMatrix Mg(2, 2);
    Mg << 1.0, 0.5, -gap, 1.0;
    Vector q(2), s(2);
    s << -1.0, gap >= 0x1p-40 ? 1.0 - gap : std::nextafter(1.0, 0.0);
    q << 0.3 - (-1.0 + 0.5 * s[1]), -1.0;
    const StepCheck check = JudgedAgainstFactored(Mg, 0.1 * Mg, q, &s);
    EXPECT_TRUE(check.exact) << "gap " << gap;
    EXPECT_EQ(check.proved, gap >= 0x1p-40) << "gap " << gap;
  }
}

// filippov (S4) at h = 1e-5, step 77778 (t = 0.77778): row 0 on its lower face, row 1 reaching its surface, s*_1 =
// (x_2 + 2h)/h. w̃_0 = w_0/σ ≈ 2e4 entered the long double solve's rounding: the factored path's s*_1 was 15.7 ulps
// (2^-53) below the exact step's double, 0x1.ffffe3ed5e6c7p-1 (x_2 after the step 1.7e-20 instead of 0); the proof's
// quotient does not see w̃_0, and gives that double from either answer.
TEST(StepVerdictProofs, AMixedAnswerWithASmallMatrixIsTheExactStep) {
  const double h = 1e-5;
  DenseMatrix B(2, 2);
  B << 1.0, -2.0, 2.0, 1.0;
  const DenseMatrix M = h * B;
  Vector q(2);
  q << 0.4444300000003037, 1.000000433268082e-05;  // −x_k
  for (const double answer : {0.9999995667319164, 0.9999995667319181}) {
    StepRefiner refiner;
    refiner.Reset(M, M, DenseMatrix(0, 2), Vector());
    Vector first(2);
    first << -1.0, answer;
    refiner.Refine(q.data(), nullptr, first.data());  // the first step judged: the factored path
    Vector s(2);
    s << -1.0, answer;
    const StepCheck check = refiner.Refine(q.data(), nullptr, s.data());
    ASSERT_TRUE(check.exact);
    EXPECT_TRUE(check.proved);
    EXPECT_EQ(s[0], -1.0);
    EXPECT_EQ(s[1], 0.9999995667319181) << "answer " << answer;
  }
}

// A two-input relay run with a mixed phase (row 0 reaches its surface first): every step judged as the factored
// path judges it, and the mixed steps by the proof.
TEST(StepVerdictProofs, ARunsMixedStepsAreProved) {
  const double h = 0.01;
  DenseMatrix Bm(2, 2), C(2, 2);
  Bm << 1.0, 0.2, 0.0, 1.0;
  C << 1.0, 0.0, 0.3, 1.0;
  const DenseMatrix S = h * Bm, M = C * S;
  StepRefiner refiner;
  refiner.Reset(M, S, DenseMatrix(0, 2), Vector());
  auto solver = CreateSolver("lemke");
  SolverOptions options;
  options.tolerance = 1e-10;
  Vector x(2);
  x << 0.05, -0.6;
  int mixed = 0, mixed_proved = 0;
  for (int k = 0; k < 200; ++k) {
    const Vector q = -C * x;
    SolveResult result;
    solver->Solve(BoxMLCP::Relay(M, q), options, &result);
    ASSERT_EQ(result.status, SolveStatus::kSolved) << "step " << k;
    Vector s = result.z, s_factored = result.z;
    const StepCheck check = refiner.Refine(q.data(), nullptr, s.data());
    const StepCheck factored = Factored(M, S, q, &s_factored);
    ASSERT_TRUE(check.exact) << "step " << k;
    ASSERT_TRUE(factored.exact) << "step " << k;
    // The cached path's standard: s* within a quarter ulp of ‖s*‖∞ of the exact step, x_error to w̃'s resolution.
    for (int j = 0; j < 2; ++j) EXPECT_NEAR(s[j], s_factored[j], kEps / 2) << "step " << k;
    EXPECT_NEAR(check.x_error, factored.x_error, 1e-6 * factored.x_error + h * 0x1p-58) << "step " << k;
    if (k > 0 && (std::abs(s[0]) == 1.0) != (std::abs(s[1]) == 1.0)) {
      ++mixed;
      mixed_proved += check.proved ? 1 : 0;
    }
    x -= S * s;
  }
  std::printf("[ info     ] %d of %d mixed steps proved\n", mixed_proved, mixed);
  EXPECT_GT(mixed, 10);
  EXPECT_EQ(mixed_proved, mixed);
}

// The polytope law's analogue of ASaturatedAnswerWithASmallMatrixIsExact: the same step with the box stated as
// H = [I; −I], K = −1 (Siconos' regular twisting states its box so), and a vertex of the rotated square |s_1 ± s_2| ≤ 1,
// with M scaled down to h = 1e-9. The long double solve's rounding grows with w̃ = w/σ and left s* off the active
// faces by more than the 8-ulp feasibility test (a correct vertex answer refused at h = 1e-5, 1e-8, 1e-9, and s*
// 3e-14 off the vertex at h = 1e-6); projected onto the faces it is the vertex, exactly.
TEST(StepVerdictPaths, APolytopeVertexAnswerWithASmallMatrixIsExact) {
  DenseMatrix M0(2, 2);
  M0 << 0x1.4f8b588e368f1p-17, -0x1.4f8b588e368f1p-16, 0x1.4f8b588e368f1p-16, 0x1.4f8b588e368f1p-17;
  Vector q(2);
  q << -0x1.fbaf102363b66p-1, 0x1.00b827fa1a122p+0;
  const Vector K = Vector::Constant(4, -1.0);
  DenseMatrix box(4, 2), square(4, 2);
  box << 1, 0, 0, 1, -1, 0, 0, -1;
  square << 1, 1, 1, -1, -1, -1, -1, 1;  // s_1 + s_2 ≥ −1, s_1 − s_2 ≥ −1, and their negations
  for (const double h : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9}) {
    const DenseMatrix M = (h / 1e-5) * M0;
    {
      Vector s(2);
      s << 1.0, -1.0;  // rows 2 (−s_1 ≥ −1) and 1 (s_2 ≥ −1) active
      const Vector w = M * s + q;
      Vector mu = Vector::Zero(4);
      mu[2] = -w[0];
      mu[1] = w[1];
      ASSERT_GT(mu.minCoeff(), -1e-300);
      StepRefiner refiner;
      refiner.Reset(M, M, box, K);
      const StepCheck check = refiner.Refine(q.data(), mu.data(), s.data());
      ASSERT_TRUE(check.exact) << "box, h = " << h;
      EXPECT_EQ(s[0], 1.0) << "box, h = " << h;
      EXPECT_EQ(s[1], -1.0) << "box, h = " << h;
      EXPECT_EQ(check.x_error, 0.0) << "box, h = " << h;
    }
    {
      Vector s(2);
      s << 0.0, -1.0;  // rows 0 (s_1 + s_2 = −1) and 3 (s_2 − s_1 = −1) active: w = μ_0 (1, 1) + μ_3 (−1, 1)
      const Vector w = M * s + q;
      Vector mu = Vector::Zero(4);
      mu[0] = (w[0] + w[1]) / 2;
      mu[3] = (w[1] - w[0]) / 2;
      ASSERT_GT(mu.minCoeff(), -1e-300);
      StepRefiner refiner;
      refiner.Reset(M, M, square, K);
      const StepCheck check = refiner.Refine(q.data(), mu.data(), s.data());
      ASSERT_TRUE(check.exact) << "square, h = " << h;
      EXPECT_EQ(s[0], 0.0) << "square, h = " << h;
      EXPECT_EQ(s[1], -1.0) << "square, h = " << h;
      EXPECT_EQ(check.x_error, 0.0) << "square, h = " << h;
    }
  }
}

}  // namespace
}  // namespace smcbench
