// The step verdict's two paths (problems/stepper/step_verdict.h): a run is judged by the cached inverse of its
// active set's KKT matrix, a singular or ill-conditioned active set by the factored path, and both give the same
// verdict and the same s* (a refiner's first step since Reset is the factored path: the reference here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

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

}  // namespace
}  // namespace smcbench
