// CSV output and the sliding-surface metrics / error norms, on hand-made trajectories with known answers.
#include "problems/stepper/trajectory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/metrics.h"
#include "problems/stepper/stepper_test_util.h"

namespace smcbench {
namespace {

using stepper_test::Vec;
using ::testing::HasSubstr;

// A recorded trajectory with n = 1, m = 1 and the given y and s rows (x = y).
Trajectory Handmade(const std::vector<double>& y, const std::vector<double>& s, double h = 0.5) {
  Trajectory tr;
  tr.n = 1;
  tr.m = 1;
  tr.h = h;
  tr.recorded = true;
  const auto N = static_cast<std::int64_t>(y.size()) - 1;
  tr.num_steps = tr.steps_taken = N;
  tr.x.resize(1, N + 1);
  tr.y.resize(1, N + 1);
  tr.s.resize(1, N + 1);
  for (std::int64_t k = 0; k <= N; ++k) {
    tr.t.push_back(tr.time(k));
    tr.x(0, k) = tr.y(0, k) = y[k];
    tr.s(0, k) = s[k];
    tr.iterations.push_back(static_cast<int>(k));
    tr.residual.push_back(k * 1e-13);
    tr.status.push_back(k ? SolveStatus::kSolved : SolveStatus::kNotRun);
  }
  return tr;
}

TEST(Csv, HeaderAndRows) {
  stepper_test::ReferenceSolver solver;
  LinearStepper stepper(DiscretizeTheta(stepper_test::MultiSurfaceScene(), 0.25, 1.0, SignTreatment::kImplicit));
  const Trajectory tr = stepper.Run(Vec({1.0, -1.0}), 2, &solver);
  std::ostringstream out;
  WriteTrajectoryCsv(tr, out);
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,x1,x2,s1,s2,y1,y2,iterations,residual");
  std::getline(in, line);
  EXPECT_EQ(line, "0,1,-1,0,0,-1,3,0,0");  // y0 = C x0 = [1 − 2, 2 + 1]
  int rows = 1;
  while (std::getline(in, line)) {
    ++rows;
    // Every number reads back exactly (shortest round-trip form).
    std::istringstream fields(line);
    std::string field;
    std::vector<double> values;
    while (std::getline(fields, field, ',')) values.push_back(std::stod(field));
    ASSERT_EQ(values.size(), 9u);
    const int k = rows - 1;
    EXPECT_EQ(values[0], tr.t[k]);
    EXPECT_EQ(values[1], tr.x(0, k));
    EXPECT_EQ(values[4], tr.s(1, k));
    EXPECT_EQ(values[6], tr.y(1, k));
    EXPECT_EQ(values[7], tr.iterations[k]);
    EXPECT_EQ(values[8], tr.residual[k]);
  }
  EXPECT_EQ(rows, 3);
}

TEST(Csv, RejectsUnrecordedTrajectories) {
  Trajectory tr;
  std::ostringstream out;
  EXPECT_THAT([&] { WriteTrajectoryCsv(tr, out); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("not recorded")));
  Trajectory rec = Handmade({1.0}, {0.0});
  EXPECT_THAT([&] { WriteTrajectoryCsvFile(rec, "/nonexistent-dir/x.csv"); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("cannot open '/nonexistent-dir/x.csv'")));
}

TEST(Metrics, ReachingStepSignChangesAndVariation) {
  //        k:   0     1     2     3     4      5      6     7     8
  const Trajectory tr = Handmade({2.0, 1.0, -0.5, 1e-3, 0.0, -1e-13, 0.0, 0.0, 1e-14},
                                 {0.0, 1.0, 1.0, -1.0, 0.5, -0.25, 0.0, 0.25, 0.25});
  const TrajectoryMetrics m = ComputeMetrics(tr, 1e-12);
  ASSERT_EQ(m.surfaces.size(), 1u);
  const SurfaceMetrics& s = m.surfaces[0];
  EXPECT_EQ(s.reaching_step, 4);           // |y_3| = 1e-3 > tol; y_4.. within tol
  EXPECT_EQ(m.reaching_step, 4);
  EXPECT_EQ(s.max_abs_y_after, 1e-13);
  // After reaching (rows 4..8): s = 0.5, −0.25, 0, 0.25, 0.25 → changes 0.5→−0.25 and −0.25→(0)→0.25.
  EXPECT_EQ(s.sign_changes_after, 2);
  EXPECT_DOUBLE_EQ(s.total_variation_after, 0.75 + 0.25 + 0.25 + 0.0);
  // Whole run (rows 1..8): 1, 1, −1, 0.5, −0.25, 0, 0.25, 0.25 → 4 changes.
  EXPECT_EQ(s.sign_changes_total, 4);
  EXPECT_DOUBLE_EQ(s.total_variation_total, 0.0 + 2.0 + 1.5 + 0.75 + 0.25 + 0.25 + 0.0);
  EXPECT_THAT([&] { ComputeMetrics(tr, -1.0); }, ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("tol")));
}

TEST(Metrics, RoundingLevelValuesOfSAreNotSignChanges) {
  // A backend leaves s = ±1e-12 instead of 0 on the surface: not chattering. 1e-3 is a real (small) sign.
  const Trajectory tr = Handmade({1.0, 0.0, 0.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 1e-12, -1e-12, 1e-12, -1e-3});
  const TrajectoryMetrics m = ComputeMetrics(tr, 1e-9);
  EXPECT_EQ(m.sign_dead_zone, kSignDeadZone);
  // On the surface from row 1: s = 1, (1e-12, −1e-12, 1e-12 count as 0), −1e-3: one real change.
  EXPECT_EQ(m.surfaces[0].reaching_step, 1);
  EXPECT_EQ(m.surfaces[0].sign_changes_after, 1);
  EXPECT_EQ(m.surfaces[0].sign_changes_total, 1);
  // With no dead zone every rounding flip counts (1 → 1e-12 → −1e-12 → 1e-12 → −1e-3: 3 changes).
  EXPECT_EQ(ComputeMetrics(tr, 1e-9, 0.0).surfaces[0].sign_changes_total, 3);
  EXPECT_THAT([&] { ComputeMetrics(tr, 1e-9, -1.0); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("sign_dead_zone")));
}

TEST(Metrics, NeverReachedAndNaN) {
  EXPECT_EQ(ComputeMetrics(Handmade({1.0, 0.0, 0.1}, {0, 1, 1}), 1e-9).reaching_step, -1);
  EXPECT_EQ(ComputeMetrics(Handmade({1.0, 0.0, NAN}, {0, 1, 1}), 1e-9).surfaces[0].reaching_step, -1);
  EXPECT_EQ(ComputeMetrics(Handmade({0.0, 0.0}, {0, 0}), 1e-9).reaching_step, 0);
}

TEST(Metrics, ReachingStepIsTheLatestSurface) {
  stepper_test::ReferenceSolver solver;
  LinearStepper stepper(DiscretizeTheta(stepper_test::MultiSurfaceScene(), 0.02, 1.0, SignTreatment::kImplicit));
  const Trajectory tr = stepper.Run(Vec({1.0, -1.0}), 75, &solver);
  const TrajectoryMetrics m = ComputeMetrics(tr, 1e-10);
  EXPECT_EQ(m.reaching_step, std::max(m.surfaces[0].reaching_step, m.surfaces[1].reaching_step));
  EXPECT_EQ(m.total_iterations, tr.total_iterations);
}

TEST(ErrorNorms, HandComputed) {
  // x_k = k h against x(t) = 0: e = 0, 0.5, 1 (h = 0.5) → l1 = 0.75, l2 = sqrt(0.5·1.25), max = 1.
  Trajectory tr = Handmade({0.0, 0.5, 1.0}, {0.0, 1.0, -1.0});
  ExactSolution exact;
  exact.x = [](double, Eigen::Ref<Vector> x) { x.setZero(); };
  exact.s = [](double t, Eigen::Ref<Vector> s) { s[0] = t < 0.75 ? 1.0 : 0.0; };
  const SolutionErrors e = ComputeErrors(tr, exact);
  ASSERT_TRUE(e.x.has_value());
  EXPECT_DOUBLE_EQ(e.x->l1, 0.75);
  EXPECT_DOUBLE_EQ(e.x->l2, std::sqrt(0.625));
  EXPECT_DOUBLE_EQ(e.x->max, 1.0);
  // s rows 1..2: s_1 = 1 vs s(0.5) = 1 → 0; s_2 = −1 vs s(1) = 0 → 1.
  ASSERT_TRUE(e.s.has_value());
  EXPECT_DOUBLE_EQ(e.s->l1, 0.5);
  EXPECT_DOUBLE_EQ(e.s->max, 1.0);
  EXPECT_FALSE(ComputeErrors(tr, ExactSolution{}).x.has_value());
}

TEST(ErrorNorms, SignSceneConverges) {
  // S1 against x(t) = max(1.01 − t, 0): implicit Euler is exact at the nodes up to rounding (x_k = x0 − k h
  // until arrival, then 0); s differs from s(t) only on the arrival step.
  stepper_test::ReferenceSolver solver;
  ExactSolution exact;
  exact.x = [](double t, Eigen::Ref<Vector> x) { x[0] = std::max(1.01 - t, 0.0); };
  exact.s = [](double t, Eigen::Ref<Vector> s) { s[0] = t < 1.01 ? 1.0 : 0.0; };
  for (double h : {0.2, 0.02}) {
    LinearStepper stepper(DiscretizeTheta(stepper_test::SignScene(), h, 1.0, SignTreatment::kImplicit));
    const Trajectory tr = stepper.Run(Vec({1.01}), NumSteps(2.0, h), &solver);
    const SolutionErrors e = ComputeErrors(tr, exact);
    EXPECT_LT(e.x->max, 1e-12) << h;
    EXPECT_LE(e.s->max, 1.0) << h;
    EXPECT_LE(e.s->l1, h) << h;
  }
}

TEST(ReferenceErrors, HandComputedMaxOverStepsAndComponents) {
  // s differs by 0.25 at k = 1 and 0.5 at k = 2; y (= x) by 0.125 at k = 2; row 0 is never compared.
  const Trajectory run = Handmade({9.0, 1.0, 0.125}, {7.0, 0.75, 0.5});
  const Trajectory reference = Handmade({1.0, 1.0, 0.0}, {0.0, 1.0, 0.0});
  const ReferenceErrors e = CompareWithReference(run, reference);
  EXPECT_EQ(e.s_error_max, 0.5);
  EXPECT_EQ(e.y_error_max, 0.125);
  EXPECT_EQ(e.steps_compared, 2);
  EXPECT_EQ(CompareWithReference(run, run).s_error_max, 0.0);
}

TEST(ReferenceErrors, StopsBeforeTheReferenceFailsAndTreatsNaNAsInfinite) {
  const Trajectory run = Handmade({1.0, 0.5, 0.25, 0.0}, {0.0, 1.0, 1.0, 1.0});
  Trajectory reference = Handmade({1.0, 0.5, 7.0, 7.0}, {0.0, 1.0, 9.0, 9.0});
  reference.first_failed_step = 2;  // its s_2 was not certified: only k = 1 counts
  ReferenceErrors e = CompareWithReference(run, reference);
  EXPECT_EQ(e.steps_compared, 1);
  EXPECT_EQ(e.s_error_max, 0.0);
  EXPECT_EQ(e.y_error_max, 0.0);
  // A shorter run: steps up to its end.
  e = CompareWithReference(Handmade({1.0, 0.5}, {0.0, 1.0}), Handmade({1.0, 0.5, 0.25}, {0.0, 0.5, 1.0}));
  EXPECT_EQ(e.steps_compared, 1);
  EXPECT_EQ(e.s_error_max, 0.5);
  e = CompareWithReference(Handmade({1.0, NAN}, {0.0, 1.0}), Handmade({1.0, 0.5}, {0.0, 1.0}));
  EXPECT_EQ(e.y_error_max, kInf);
  // Unrecorded or mismatched runs are errors that say so.
  Trajectory unrecorded = run;
  unrecorded.recorded = false;
  EXPECT_THAT([&] { CompareWithReference(unrecorded, run); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("not recorded")));
  EXPECT_THROW(CompareWithReference(run, Handmade({1.0, 0.5, 0.25, 0.0}, {0.0, 1.0, 1.0, 1.0}, 0.25)),
               InvalidInputError);
}

// ----------------------------------------------------------------------------------------------------------
// The streamed counterparts: the same numbers, bit for bit, from rows handed out in blocks.

// A recorded trajectory with m surfaces from explicit rows (x = y, n = m).
Trajectory HandmadeRows(const std::vector<std::vector<double>>& y, const std::vector<std::vector<double>>& s) {
  Trajectory tr;
  tr.m = tr.n = static_cast<int>(y.front().size());
  tr.h = 0.25;
  tr.recorded = true;
  const auto N = static_cast<std::int64_t>(y.size()) - 1;
  tr.num_steps = tr.steps_taken = N;
  tr.x.resize(tr.n, N + 1), tr.y.resize(tr.m, N + 1), tr.s.resize(tr.m, N + 1);
  for (std::int64_t k = 0; k <= N; ++k) {
    tr.t.push_back(tr.time(k));
    for (int i = 0; i < tr.m; ++i) tr.x(i, k) = tr.y(i, k) = y[k][i], tr.s(i, k) = s[k][i];
    tr.iterations.push_back(1);
    tr.residual.push_back(0.0);
    tr.status.push_back(k ? SolveStatus::kSolved : SolveStatus::kNotRun);
  }
  return tr;
}

bool SameDouble(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every field of the streamed metrics equals the backward scan's, bit for bit.
void ExpectSameMetrics(const TrajectoryMetrics& a, const TrajectoryMetrics& b) {
  EXPECT_EQ(a.reaching_step, b.reaching_step);
  EXPECT_EQ(a.failed_steps, b.failed_steps);
  EXPECT_EQ(a.total_iterations, b.total_iterations);
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  for (std::size_t i = 0; i < a.surfaces.size(); ++i) {
    SCOPED_TRACE("surface " + std::to_string(i));
    const SurfaceMetrics &x = a.surfaces[i], &y = b.surfaces[i];
    EXPECT_EQ(x.reaching_step, y.reaching_step);
    EXPECT_TRUE(SameDouble(x.max_abs_y_after, y.max_abs_y_after)) << x.max_abs_y_after << " " << y.max_abs_y_after;
    EXPECT_EQ(x.sign_changes_after, y.sign_changes_after);
    EXPECT_TRUE(SameDouble(x.total_variation_after, y.total_variation_after));
    EXPECT_EQ(x.sign_changes_total, y.sign_changes_total);
    EXPECT_TRUE(SameDouble(x.total_variation_total, y.total_variation_total));
  }
}

TrajectoryMetrics Streamed(const Trajectory& tr, double tol, std::int64_t block_rows,
                           double dead_zone = kSignDeadZone) {
  MetricsAccumulator accumulator(tr.m, tol, dead_zone);
  FeedRecorded(tr, &accumulator, block_rows);
  return accumulator.Result(tr);
}

TEST(MetricsAccumulator, HandMadeCasesMatchTheBackwardScan) {
  const std::vector<Trajectory> cases = {
      Handmade({2.0, 1.0, -0.5, 1e-3, 0.0, -1e-13, 0.0, 0.0, 1e-14},
               {0.0, 1.0, 1.0, -1.0, 0.5, -0.25, 0.0, 0.25, 0.25}),
      Handmade({1.0, 0.0, 0.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 1e-12, -1e-12, 1e-12, -1e-3}),
      Handmade({1.0, 0.0, 0.1}, {0, 1, 1}),         // never reached
      Handmade({1.0, 0.0, NAN}, {0, 1, 1}),         // NaN at the end
      Handmade({0.0, NAN, 0.0, 0.0}, {0, 1, -1, 1}),  // NaN in the middle
      Handmade({0.0, 0.0}, {0, 0}),                 // reached at row 0
      Handmade({0.0}, {0.0}),                       // no step at all
      Handmade({3.0}, {0.0}),
  };
  for (std::size_t c = 0; c < cases.size(); ++c) {
    for (std::int64_t block : {1, 2, 3, 4096}) {
      SCOPED_TRACE("case " + std::to_string(c) + ", blocks of " + std::to_string(block));
      ExpectSameMetrics(Streamed(cases[c], 1e-12, block), ComputeMetrics(cases[c], 1e-12));
      ExpectSameMetrics(Streamed(cases[c], 1e-9, block, 0.0), ComputeMetrics(cases[c], 1e-9, 0.0));
    }
  }
  EXPECT_THAT([&] { MetricsAccumulator(1, -1.0); }, ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("tol")));
  EXPECT_THAT([&] { MetricsAccumulator(1, 1e-9, NAN); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("sign_dead_zone")));
}

// Random rows with every situation the scan distinguishes: |y| inside and outside the tolerance, NaN, s in and
// outside the dead zone, of both signs; two surfaces; block sizes that cut the rows anywhere.
TEST(MetricsAccumulator, RandomRowsMatchTheBackwardScan) {
  std::mt19937 rng(13);
  const double ys[] = {0.0, 1e-13, -1e-11, 2.0, -0.5, NAN};
  const double ss[] = {0.0, 1.0, -1.0, 1e-12, -1e-7, 0.3, -0.7};
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + static_cast<int>(rng() % 40);
    // Mostly inside the tolerance near the end, so that "reached" happens often.
    std::vector<std::vector<double>> y(rows), s(rows);
    for (int k = 0; k < rows; ++k) {
      for (int i = 0; i < 2; ++i) {
        const bool late = k > rows / 2 && rng() % 4 != 0;
        y[k].push_back(late ? ys[rng() % 2] : ys[rng() % 6]);
        s[k].push_back(ss[rng() % 7]);
      }
    }
    const Trajectory tr = HandmadeRows(y, s);
    const std::int64_t block = 1 + static_cast<std::int64_t>(rng() % 9);
    SCOPED_TRACE("trial " + std::to_string(trial));
    ExpectSameMetrics(Streamed(tr, 1e-12, block), ComputeMetrics(tr, 1e-12));
  }
}

// A real run (S3, two surfaces, 4000 rows: blocks of 4096 and of 7).
TEST(MetricsAccumulator, SteppedRunMatchesTheBackwardScan) {
  stepper_test::ReferenceSolver solver;
  LinearStepper stepper(DiscretizeTheta(stepper_test::MultiSurfaceScene(), 0.0005, 1.0, SignTreatment::kImplicit));
  const Trajectory tr = stepper.Run(Vec({1.0, -1.0}), 4000, &solver);
  ASSERT_GE(ComputeMetrics(tr, 1e-10).reaching_step, 1);
  for (std::int64_t block : {7, 4096}) ExpectSameMetrics(Streamed(tr, 1e-10, block), ComputeMetrics(tr, 1e-10));
}

TEST(ErrorsAccumulator, MatchesComputeErrorsBitForBit) {
  stepper_test::ReferenceSolver solver;
  ExactSolution exact;
  exact.x = [](double t, Eigen::Ref<Vector> x) { x[0] = std::max(1.01 - t, 0.0); };
  exact.s = [](double t, Eigen::Ref<Vector> s) { s[0] = t < 1.01 ? 1.0 : 0.0; };
  LinearStepper stepper(DiscretizeTheta(stepper_test::SignScene(), 0.0003, 1.0, SignTreatment::kImplicit));
  const Trajectory tr = stepper.Run(Vec({1.01}), NumSteps(2.0, 0.0003), &solver);
  const SolutionErrors whole = ComputeErrors(tr, exact);
  for (std::int64_t block : {1, 5, 4096}) {
    ErrorsAccumulator accumulator(tr.n, tr.m, tr.h, exact);
    FeedRecorded(tr, &accumulator, block);
    const SolutionErrors streamed = accumulator.Result();
    for (const auto& [a, b] : {std::pair{whole.x, streamed.x}, std::pair{whole.s, streamed.s}}) {
      ASSERT_TRUE(a && b);
      EXPECT_TRUE(SameDouble(a->l1, b->l1));
      EXPECT_TRUE(SameDouble(a->l2, b->l2));
      EXPECT_TRUE(SameDouble(a->max, b->max));
    }
  }
  ErrorsAccumulator none(1, 1, 0.5, ExactSolution{});
  FeedRecorded(tr, &none);
  EXPECT_FALSE(none.Result().x.has_value());
  EXPECT_FALSE(none.Result().s.has_value());
}

TEST(ReferenceErrorsAccumulator, MatchesCompareWithReference) {
  const Trajectory run = Handmade({9.0, 1.0, 0.125, NAN}, {7.0, 0.75, 0.5, 0.0});
  const Trajectory reference = Handmade({1.0, 1.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0});
  for (std::int64_t last : {1, 2, 3}) {
    Trajectory shorter = reference;
    shorter.first_failed_step = last + 1;  // compared: k = 1..last
    const ReferenceErrors whole = CompareWithReference(run, shorter);
    ReferenceErrorsAccumulator accumulator;
    for (Eigen::Index k = 1; k <= last; ++k) {
      accumulator.Add(&run.s(0, k), &run.y(0, k), &reference.s(0, k), &reference.y(0, k), 1);
    }
    EXPECT_EQ(accumulator.errors().steps_compared, whole.steps_compared);
    EXPECT_EQ(accumulator.errors().s_error_max, whole.s_error_max);
    EXPECT_EQ(accumulator.errors().y_error_max, whole.y_error_max);
  }
}

TEST(Csv, StreamedWriterWritesTheSameBytes) {
  stepper_test::ReferenceSolver solver;
  LinearStepper stepper(DiscretizeTheta(stepper_test::MultiSurfaceScene(), 0.001, 1.0, SignTreatment::kImplicit));
  const Trajectory tr = stepper.Run(Vec({1.0, -1.0}), 3000, &solver);
  std::ostringstream whole, streamed;
  WriteTrajectoryCsv(tr, whole);
  TrajectoryCsvWriter writer(&streamed, "memory");
  FeedRecorded(tr, &writer, 7);
  writer.Close();
  EXPECT_EQ(writer.rows_written(), 3001);
  EXPECT_EQ(streamed.str(), whole.str());
  EXPECT_THAT([&] { TrajectoryCsvWriter("/nonexistent-dir/x.csv"); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("cannot open '/nonexistent-dir/x.csv'")));
  Trajectory unrecorded;
  EXPECT_THAT([&] { FeedRecorded(unrecorded, &writer); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("not recorded")));
}

}  // namespace
}  // namespace smcbench
