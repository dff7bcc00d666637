// The measures every paper study shares (paper/study.h), on runs built by hand with a known answer: fitted orders
// of a planted power law, cycles of planted periodic tails, the error against a finer reference, verdict counts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tools/smcbench/paper/study.h"

namespace smcbench::paper {
namespace {

// A recorded one-state run x_k = f(k), k = 0..steps, step h.
template <typename F>
Trajectory RunOf(std::int64_t steps, double h, F f) {
  Trajectory tr;
  tr.n = 1;
  tr.h = h;
  tr.recorded = true;
  tr.num_steps = tr.steps_taken = steps;
  tr.x = DenseMatrix(1, steps + 1);
  for (std::int64_t k = 0; k <= steps; ++k) tr.x(0, k) = f(k);
  return tr;
}

TEST(PaperStudy, FittedOrderIsTheSlopeOfAPlantedPowerLaw) {
  const std::vector<double> hs{0.1, 0.05, 0.02, 0.01, 0.005};
  std::vector<double> errs;
  for (double h : hs) errs.push_back(3.0 * h * h);
  EXPECT_NEAR(FittedOrder(hs, errs), 2.0, 1e-12);
  // Zero and non-finite errors are left out of the fit: the slope of the others stays 2.
  errs[1] = 0.0;
  errs[3] = std::numeric_limits<double>::infinity();
  EXPECT_NEAR(FittedOrder(hs, errs), 2.0, 1e-12);
  // Fewer than two usable points: no order.
  EXPECT_TRUE(std::isnan(FittedOrder({0.1, 0.05}, {1e-3, 0.0})));
}

TEST(PaperStudy, MaxErrorAgainstComparesOnTheCoarseGrid) {
  // Reference at h = 0.01, x = 100 t (integers: every difference below is exact); the coarse run at h = 0.1
  // equals it on its grid except at k = 3 (t = 0.3), off by 0.25.
  const Trajectory ref = RunOf(100, 0.01, [](std::int64_t k) { return static_cast<double>(k); });
  const Trajectory coarse =
      RunOf(10, 0.1, [&](std::int64_t k) { return ref.x(0, 10 * k) + (k == 3 ? 0.25 : 0.0); });
  EXPECT_EQ(MaxErrorAgainst(coarse, ref), 0.25);
}

TEST(PaperStudy, DetectCycleFindsThePlantedPeriod) {
  // A transient, then ±0.3 alternating: period 2 with the last two points; N = 40 is even, so x_N = +0.3.
  const Cycle two = DetectCycle(RunOf(40, 0.1, [](std::int64_t k) { return k < 10 ? 5.0 - k : (k % 2 ? -0.3 : 0.3); }));
  EXPECT_EQ(two.period, 2);
  EXPECT_EQ(two.a[0], -0.3);
  EXPECT_EQ(two.b[0], 0.3);
  EXPECT_EQ(two.drift, 0.0);
  EXPECT_EQ(CycleText(two), "period 2: (-0.3) ↔ (0.3)");
  // At rest: period 1 (a fixed point).
  EXPECT_EQ(DetectCycle(RunOf(40, 0.1, [](std::int64_t k) { return k < 5 ? 1.0 / (k + 1) : 0.0; })).period, 1);
  // A three-point cycle.
  EXPECT_EQ(DetectCycle(RunOf(60, 0.1, [](std::int64_t k) { return static_cast<double>(k % 3); })).period, 3);
  // A ramp repeats with no period; its period-2 drift is |x_{k+2} − x_k| = 2.
  const Cycle none = DetectCycle(RunOf(60, 0.1, [](std::int64_t k) { return static_cast<double>(k); }));
  EXPECT_EQ(none.period, 0);
  EXPECT_EQ(none.drift, 2.0);
  // Too short to judge (fewer than 16 + 8 steps): nothing found.
  EXPECT_EQ(DetectCycle(RunOf(20, 0.1, [](std::int64_t) { return 0.0; })).period, 0);
}

TEST(PaperStudy, CountVerdictsAndNumbers) {
  const std::vector<PaperClaim> claims{{"S1", "a", "m", kHolds},    {"S1", "b", "m", kHolds},
                                       {"S2", "c", "m", kPartly},   {"S3", "d", "m", kFails},
                                       {"S11", "e", "m", kMeasured}};
  const VerdictCounts n = CountVerdicts(claims);
  EXPECT_EQ(n.holds, 2);
  EXPECT_EQ(n.partly, 1);
  EXPECT_EQ(n.fails, 1);
  EXPECT_EQ(n.measured, 1);
  EXPECT_EQ(G(0.0019412345), "0.00194");
  EXPECT_EQ(G(std::nan("")), "NaN");
  EXPECT_EQ(G(-std::numeric_limits<double>::infinity()), "-inf");
  std::string list;
  AppendListItem(&list, "a");
  AppendListItem(&list, "b", "; ");
  EXPECT_EQ(list, "a; b");
}

}  // namespace
}  // namespace smcbench::paper
