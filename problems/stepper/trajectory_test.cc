// CSV output and the sliding-surface metrics / error norms, on hand-made trajectories with known answers.
#include "problems/stepper/trajectory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

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

}  // namespace
}  // namespace smcbench
