// The shared Newton globalization on its own: the descent test, Armijo backtracking on known functions, the
// non-monotone reference, the stagnation window, the step and divergence tests, the best iterate and the report.
#include "solvers/newton/newton_globalization.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace smcbench {
namespace newton {
namespace {

// Psi(x) = ½x² at x0 + t·d, one unknown; counts the trials.
struct Quadratic {
  double x0 = 1.0;
  double d = -1.0;
  int trials = 0;
  bool operator()(double t, double* psi) {
    ++trials;
    const double x = x0 + t * d;
    *psi = 0.5 * x * x;
    return true;
  }
};

TEST(SufficientDescentTest, AgreesWithThePowerForm) {
  // The short cuts through ‖d‖² and ‖d‖³ decide exactly as gd ≤ −ρ‖d‖^p does.
  for (double p : {2.1, 2.5, 3.0, 4.0}) {
    for (double norm_d : {0.0, 1e-8, 0.3, 0.999, 1.0, 1.001, 2.0, 1e3}) {
      const double bound = -1e-2 * std::pow(norm_d, p);
      for (double gd : {bound * 2.0, bound, bound * 0.5, -1e-300, 0.0, 1.0}) {
        const bool reference = gd < 0.0 && gd <= -1e-2 * std::pow(norm_d, p);
        EXPECT_EQ(SufficientDescent(gd, norm_d, 1e-2, p), reference) << "p " << p << " |d| " << norm_d << " gd " << gd;
      }
    }
  }
  EXPECT_FALSE(SufficientDescent(std::numeric_limits<double>::quiet_NaN(), 1.0, 1e-8, 2.1));
  EXPECT_FALSE(SufficientDescent(-1.0, 1e6, 1e-8, 2.1));  // a huge step with little descent
  EXPECT_TRUE(SufficientDescent(-1.0, 1.0, 1e-8, 2.1));
}

TEST(ArmijoBacktrackTest, AcceptsTheFullNewtonStepOnAQuadratic) {
  Quadratic q;  // x = 1, d = −1 (the Newton step of x = 0), Psi = ½, ∇Psiᵀd = −1
  double psi = -1.0, t = -1.0;
  bool all_nan = true;
  int backtracks = 0;
  ASSERT_TRUE(ArmijoBacktrack(ArmijoRule{}, 0.5, -1.0, q, &psi, &t, &all_nan, &backtracks));
  EXPECT_EQ(t, 1.0);
  EXPECT_EQ(psi, 0.0);
  EXPECT_EQ(backtracks, 0);
  EXPECT_EQ(q.trials, 1);
  EXPECT_FALSE(all_nan);
}

TEST(ArmijoBacktrackTest, BacktracksToTheFirstStepWithSufficientDecrease) {
  // x = 1, d = −4: t = 1 lands at −3 (Psi 4.5), t = ½ at −1 (Psi ½, not below ½ − σ·½·4), t = ¼ at 0.
  Quadratic q;
  q.d = -4.0;
  double psi = -1.0, t = -1.0;
  bool all_nan = true;
  int backtracks = 5;  // added to, not reset
  ASSERT_TRUE(ArmijoBacktrack(ArmijoRule{}, 0.5, -4.0, q, &psi, &t, &all_nan, &backtracks));
  EXPECT_EQ(t, 0.25);
  EXPECT_EQ(psi, 0.0);
  EXPECT_EQ(backtracks, 7);
  EXPECT_EQ(q.trials, 3);
  // With β = 0.1 the first trials are 1 and 0.1 (x = 0.6, Psi 0.18 ≤ ½ − σ·0.4): accepted.
  Quadratic q2;
  q2.d = -4.0;
  backtracks = 0;
  ASSERT_TRUE(ArmijoBacktrack(ArmijoRule{1e-4, 0.1, 40}, 0.5, -4.0, q2, &psi, &t, &all_nan, &backtracks));
  EXPECT_DOUBLE_EQ(t, 0.1);
  EXPECT_DOUBLE_EQ(psi, 0.18);
  EXPECT_EQ(backtracks, 1);
}

TEST(ArmijoBacktrackTest, ANonMonotoneReferenceAcceptsAnIncrease) {
  // Psi(x0 + t d) = 4.5 at t = 1 is above Psi(x0) = ½ but below the reference 10 + σ·gd.
  Quadratic q;
  q.d = -4.0;
  double psi = 0.0, t = 0.0;
  bool all_nan = true;
  int backtracks = 0;
  ASSERT_TRUE(ArmijoBacktrack(ArmijoRule{}, 10.0, -4.0, q, &psi, &t, &all_nan, &backtracks));
  EXPECT_EQ(t, 1.0);
  EXPECT_EQ(psi, 4.5);
}

TEST(ArmijoBacktrackTest, FailsAlongAnAscentDirectionAfterEveryTrial) {
  Quadratic q;
  q.d = 1.0;  // Psi grows along d: no step is accepted
  double psi = -7.0, t = -7.0;
  bool all_nan = true;
  int backtracks = 0;
  const ArmijoRule rule{1e-4, 0.5, 12};
  EXPECT_FALSE(ArmijoBacktrack(rule, 0.5, -1.0, q, &psi, &t, &all_nan, &backtracks));
  EXPECT_EQ(backtracks, 13);
  EXPECT_EQ(q.trials, 13);
  EXPECT_FALSE(all_nan);  // the trials were finite
  EXPECT_EQ(psi, -7.0);   // untouched on failure
  EXPECT_EQ(t, -7.0);
}

TEST(ArmijoBacktrackTest, ReportsThatEveryTrialWasNotFinite) {
  int trials = 0;
  const auto nan_everywhere = [&trials](double, double*) {
    ++trials;
    return false;
  };
  double psi = 0.0, t = 0.0;
  bool all_nan = false;
  int backtracks = 0;
  EXPECT_FALSE(ArmijoBacktrack(ArmijoRule{1e-4, 0.5, 3}, 1.0, -1.0, nan_everywhere, &psi, &t, &all_nan, &backtracks));
  EXPECT_TRUE(all_nan);
  EXPECT_EQ(trials, 4);
  EXPECT_EQ(backtracks, 4);
  // NaN at the full step only: the shorter step is accepted and all_nan is cleared.
  const auto nan_at_one = [](double t, double* psi_t) {
    if (t == 1.0) return false;
    *psi_t = 0.0;
    return true;
  };
  backtracks = 0;
  EXPECT_TRUE(ArmijoBacktrack(ArmijoRule{}, 1.0, -1.0, nan_at_one, &psi, &t, &all_nan, &backtracks));
  EXPECT_FALSE(all_nan);
  EXPECT_EQ(t, 0.5);
  EXPECT_EQ(backtracks, 1);
}

TEST(NonmonotoneReferenceTest, IsTheLargestOfTheLastMemoryValues) {
  NonmonotoneReference r;
  r.Reset(1, 5.0);
  EXPECT_EQ(r.Reference(), 5.0);
  r.Push(3.0);
  EXPECT_EQ(r.Reference(), 3.0);  // memory 1: monotone, the reference is the last value
  r.Reset(3, 5.0);
  EXPECT_EQ(r.memory(), 3);
  r.Push(4.0);
  r.Push(1.0);
  EXPECT_EQ(r.Reference(), 5.0);
  r.Push(2.0);  // 5 leaves the memory
  EXPECT_EQ(r.Reference(), 4.0);
  r.Push(0.5);
  r.Push(0.25);
  EXPECT_EQ(r.Reference(), 2.0);
  r.Reset(0.1);  // keeps the memory, forgets the values
  EXPECT_EQ(r.memory(), 3);
  EXPECT_EQ(r.Reference(), 0.1);
  r.Push(0.2);
  EXPECT_EQ(r.Reference(), 0.2);
}

TEST(MeritWindowTest, ReportsStallOnlyAfterAWindowWithoutEnoughDecrease) {
  MeritWindow w;
  w.SetWindow(3);
  // Psi halves every iteration: never stagnated with ratio 0.5 (0.5^3 < 0.5).
  double psi = 1.0;
  for (int k = 0; k < 20; ++k, psi *= 0.5) {
    w.Record(k, psi);
    EXPECT_FALSE(w.Stagnated(k, psi, 0.5)) << k;
  }
  // Psi constant: stagnated from the first iteration that has a value window iterations back.
  for (int k = 0; k < 10; ++k) {
    w.Record(k, 1.0);
    EXPECT_EQ(w.Stagnated(k, 1.0, 0.5), k >= 3) << k;
  }
  // Compared with the value recorded exactly window iterations earlier.
  const double values[] = {8.0, 100.0, 100.0, 100.0, 3.9, 4.1};
  for (int k = 0; k < 4; ++k) w.Record(k, values[k]);
  EXPECT_FALSE(w.Stagnated(3, 3.9, 0.5));  // against 8: 3.9 < 4
  EXPECT_TRUE(w.Stagnated(3, 4.1, 0.5));
  // Filled with ∞: nothing recorded before can report stagnation.
  w.Fill(kInf);
  EXPECT_FALSE(w.Stagnated(3, 1e300, 0.5));
}

TEST(StepMovedTest, RoundingLevelStepsDoNotCount) {
  Vector z(3), zt(3);
  z << 1.0, -2.0, 0.0;
  zt = z;
  EXPECT_FALSE(StepMoved(z, zt));
  zt[0] = 1.0 + std::numeric_limits<double>::epsilon();  // one ulp: within 2ε|z|
  EXPECT_FALSE(StepMoved(z, zt));
  zt[1] = -2.0 - 1e-10;
  EXPECT_TRUE(StepMoved(z, zt));
  zt = z;
  zt[2] = 1e-300;  // any move away from an exact zero counts
  EXPECT_TRUE(StepMoved(z, zt));
  EXPECT_TRUE(IterateBounded(1e99));
  EXPECT_FALSE(IterateBounded(1e100));
  EXPECT_FALSE(IterateBounded(std::numeric_limits<double>::quiet_NaN()));
}

TEST(BestIterateTest, KeepsThePointOfTheSmallestMeasure) {
  BestIterate best;
  best.z.resize(1);
  Vector x(1);
  x << 1.0;
  best.Track(3.0, x);
  x << 2.0;
  best.Track(1.0, x);
  x << 3.0;
  best.Track(2.0, x);
  best.Track(std::numeric_limits<double>::quiet_NaN(), x);
  EXPECT_EQ(best.residual, 1.0);
  EXPECT_EQ(best.z[0], 2.0);
  best.Reset();
  EXPECT_EQ(best.residual, kInf);
}

TEST(ReportExitTest, StatusAndMessage) {
  SolveResult r;
  ReportExit(Exit::kConverged, "unused", 4, 200, 0, "scale-free residual", 1e-12, &r);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_TRUE(r.message.empty());
  ReportExit(Exit::kBudget, "unused", 200, 200, 0, "scale-free residual", 0.5, &r);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit);
  EXPECT_EQ(r.message, "iteration limit (200) reached after 200 iterations; best scale-free residual 0.5");
  ReportExit(Exit::kStagnated, "the merit function stagnated", 17, 200, 3, "relative natural residual", 0.25, &r);
  EXPECT_EQ(r.status, SolveStatus::kStalled);
  EXPECT_EQ(r.message,
            "the merit function stagnated after 17 iterations; 3 proximal-perturbation rounds did not recover; best "
            "relative natural residual 0.25");
  const struct {
    Exit exit;
    SolveStatus status;
  } cases[] = {{Exit::kStalled, SolveStatus::kStalled},
               {Exit::kSingular, SolveStatus::kSingular},
               {Exit::kNumericalFailure, SolveStatus::kNumericalFailure},
               {Exit::kTimeLimit, SolveStatus::kTimeLimit},
               {Exit::kDiverged, SolveStatus::kDiverged}};
  for (const auto& c : cases) {
    ReportExit(c.exit, "why", 1, 10, 0, "m", 1.0, &r);
    EXPECT_EQ(r.status, c.status);
    EXPECT_EQ(IsHardFailure(c.exit),
              c.exit == Exit::kNumericalFailure || c.exit == Exit::kTimeLimit || c.exit == Exit::kDiverged);
  }
  EXPECT_EQ(r.message, "why after 1 iterations; best m 1");
}

TEST(OptionChecksTest, NameTheFieldAndTheRange) {
  std::string why;
  EXPECT_TRUE(ValidArmijoRule(ArmijoRule{}, &why));
  EXPECT_FALSE(ValidArmijoRule(ArmijoRule{0.5, 0.5, 40}, &why));
  EXPECT_EQ(why, "armijo_sigma must be in (0, 0.5), got 0.5");
  EXPECT_FALSE(ValidArmijoRule(ArmijoRule{1e-4, 1.0, 40}, &why));
  EXPECT_EQ(why, "backtrack_factor must be in (0, 1), got 1");
  EXPECT_FALSE(ValidArmijoRule(ArmijoRule{1e-4, 0.5, 0}, nullptr));
  EXPECT_TRUE(ValidDescentTest(1e-8, 2.1, &why));
  EXPECT_FALSE(ValidDescentTest(1e-8, 2.0, &why));
  EXPECT_EQ(why, "descent_power must be > 2 (DFK 1996 require p > 2), got 2");
  EXPECT_FALSE(ValidDescentTest(kInf, 2.1, &why));
  EXPECT_TRUE(ValidStagnation(MeritWindow::kMaxWindow, 0.9, &why));
  EXPECT_FALSE(ValidStagnation(MeritWindow::kMaxWindow + 1, 0.9, &why));
  EXPECT_EQ(why, "stagnation_window must be in [1, 64], got 65");
  EXPECT_FALSE(ValidStagnation(10, 1.0, &why));
  EXPECT_EQ(why, "stagnation_ratio must be in (0, 1), got 1");
}

}  // namespace
}  // namespace newton
}  // namespace smcbench
