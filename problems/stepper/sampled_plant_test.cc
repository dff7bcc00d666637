// The sampled-data plant (sampled_plant.h) against an independent integration: a fine classical RK4 of the
// continuous plant x' = F x + G u_k + W d(t) with the held input taken from the rows themselves, from every sample
// through its interval; the samples pass unchanged; s = 1 is the run itself; bad values are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/sampled_plant.h"
#include "problems/stepper/stepper_test_util.h"
#include "problems/stepper/streaming_test_util.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using stepper_test::CollectingSink;
using stepper_test::Vec;

// The plant's right-hand side F x + G u + W d(t), written out from the model's fields (not the discretization's).
Vector PlantRate(const ZohSmcSystem& sys, const Vector& x, const Vector& u, double t) {
  Vector rate = sys.F * x + sys.G * u;
  if (sys.disturbance.empty()) return rate;
  Vector d = sys.disturbance.constant.size() ? sys.disturbance.constant : Vector::Zero(sys.disturbance.W.cols());
  for (const DisturbanceSinusoid& term : sys.disturbance.sinusoids) {
    d += term.amplitude * std::sin(term.omega * t + term.phase);
  }
  return rate + sys.disturbance.W * d;
}

// x(t + tau) by `fine` classical RK4 steps from x at t under the constant input u.
Vector Rk4(const ZohSmcSystem& sys, Vector x, const Vector& u, double t, double tau, int fine) {
  const double dt = tau / fine;
  for (int i = 0; i < fine; ++i) {
    const double ti = t + i * dt;
    const Vector k1 = PlantRate(sys, x, u, ti);
    const Vector k2 = PlantRate(sys, x + 0.5 * dt * k1, u, ti + 0.5 * dt);
    const Vector k3 = PlantRate(sys, x + 0.5 * dt * k2, u, ti + 0.5 * dt);
    const Vector k4 = PlantRate(sys, x + dt * k3, u, ti + dt);
    x += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return x;
}

struct SampledRun {
  CollectingSink samples;  // the run's own rows
  CollectingSink plant;    // through SampledPlantSink
};

// One streamed run with the plant sink and a second, identical one without it.
SampledRun RunBoth(const ZohSmcSystem& sys, SignTreatment sign, double h, int substeps, const Vector& x0, int steps) {
  // Two steppers and two backends: a second run of one stepper would start from the first's remembered active set.
  const std::unique_ptr<Solver> solver = CreateSolver("lemke"), second_solver = CreateSolver("lemke");
  LinearStepper stepper(DiscretizeZoh(sys, h, sign)), second_stepper(DiscretizeZoh(sys, h, sign));
  SampledRun run;
  StepperOptions options;
  options.record = false;
  options.sink = &run.samples;
  stepper.Run(x0, steps, solver.get(), options);
  SampledPlantSink plant(sys, h, substeps, &run.plant);
  options.sink = &plant;
  second_stepper.Run(x0, steps, second_solver.get(), options);
  plant.Finish();
  return run;
}

// Every row of every interval (the last one included) against RK4 from the sample with the row's own u, and the
// samples bit for bit; tol is absolute on states of order 1.
void ExpectContinuousPlant(const ZohSmcSystem& sys, const SampledRun& run, int substeps, double h, double tol) {
  const Trajectory& samples = run.samples.rows;
  const Trajectory& plant = run.plant.rows;
  ASSERT_TRUE(run.plant.in_order);
  ASSERT_EQ(plant.steps_taken, samples.steps_taken * substeps);  // s·N + 1 rows
  ASSERT_TRUE(plant.has_input);
  constexpr int kFinePerPoint = 400;
  for (std::int64_t k = 0; k <= samples.steps_taken; ++k) {
    const auto row = static_cast<Eigen::Index>(k * substeps);
    const auto c = static_cast<Eigen::Index>(k);
    // The sample row itself is the run's, bit for bit (u included).
    EXPECT_EQ(plant.t[static_cast<std::size_t>(row)], samples.t[static_cast<std::size_t>(c)]) << k;
    EXPECT_TRUE(stepper_test::SameBits(plant.x.col(row), samples.x.col(c))) << k;
    EXPECT_TRUE(stepper_test::SameBits(plant.s.col(row), samples.s.col(c))) << k;
    EXPECT_EQ(plant.iterations[static_cast<std::size_t>(row)], samples.iterations[static_cast<std::size_t>(c)]);
    if (k == samples.steps_taken) {
      EXPECT_TRUE(plant.u.col(row).array().isNaN().all()) << "the last row's u: no step applied it";
      break;
    }
    EXPECT_TRUE(stepper_test::SameBits(plant.u.col(row), samples.u.col(c))) << k;
    const Vector u = samples.u.col(c);
    Vector x = samples.x.col(c);
    double t = samples.t[static_cast<std::size_t>(c)];
    for (int j = 1; j <= substeps; ++j) {
      // RK4 from the previous point: the same continuous solution, integrated piece by piece.
      x = Rk4(sys, x, u, t, h / substeps, kFinePerPoint);
      t = samples.t[static_cast<std::size_t>(c)] + j * h / substeps;
      if (j == substeps) {
        // The next sample is the continuous plant's too (the ZOH step and the disturbance's step are exact).
        EXPECT_LE((x - Vector(samples.x.col(c + 1))).lpNorm<Eigen::Infinity>(), tol) << "sample " << k + 1;
        break;
      }
      const auto r = row + j;
      EXPECT_NEAR(plant.t[static_cast<std::size_t>(r)], t, 1e-15 * (1.0 + std::abs(t))) << k << "," << j;
      EXPECT_LE((Vector(plant.x.col(r)) - x).lpNorm<Eigen::Infinity>(), tol) << "interval " << k << ", point " << j;
      EXPECT_TRUE(stepper_test::SameBits(plant.u.col(r), samples.u.col(c))) << "the u applied over the interval";
      EXPECT_TRUE(stepper_test::SameBits(plant.s.col(r), samples.s.col(c + 1))) << "s_{k+1}, the held multiplier";
      EXPECT_LE((Vector(plant.y.col(r)) - sys.C * Vector(plant.x.col(r))).lpNorm<Eigen::Infinity>(), 1e-15);
      EXPECT_EQ(plant.iterations[static_cast<std::size_t>(r)], 0);
      EXPECT_EQ(plant.status[static_cast<std::size_t>(r)], SolveStatus::kNotRun);
    }
  }
}

ZohSmcSystem DisturbedSiso() {
  ZohSmcSystem sys = stepper_test::ZohSisoScene();
  sys.equivalent_control = EquivalentControl{0.5};  // Siconos' LinearSMC
  sys.disturbance.W = sys.G;                        // matched
  sys.disturbance.constant = Vec({0.1});
  sys.disturbance.sinusoids.push_back({Vec({0.5}), 50.0, 0.3});
  return sys;
}

TEST(SampledPlant, DisturbedSisoMatchesRk4BetweenSamples) {
  const ZohSmcSystem sys = DisturbedSiso();
  const double h = 0.05;
  const SampledRun run = RunBoth(sys, SignTreatment::kImplicit, h, 5, Vec({1.0, -0.5}), 40);
  ExpectContinuousPlant(sys, run, 5, h, 1e-10);
}

TEST(SampledPlant, MimoPaperSchemeExplicitMatchesRk4BetweenSamples) {
  const ZohSmcSystem sys = stepper_test::ZohMimoScene();
  const double h = 0.02;
  const SampledRun run = RunBoth(sys, SignTreatment::kExplicit, h, 3, Vec({1.0, -1.0, 0.5}), 60);
  ExpectContinuousPlant(sys, run, 3, h, 1e-10);
}

TEST(SampledPlant, OneSubstepIsTheRunItself) {
  const SampledRun run = RunBoth(DisturbedSiso(), SignTreatment::kImplicit, 0.05, 1, Vec({1.0, -0.5}), 30);
  stepper_test::ExpectSameRows(run.samples.rows, run.plant);
  EXPECT_TRUE(stepper_test::SameBits(run.samples.rows.u, run.plant.rows.u));
}

TEST(SampledPlant, BadValuesAreRefusedNamingTheField) {
  const ZohSmcSystem sys = DisturbedSiso();
  for (int bad : {0, -3, 2'000'000}) {
    try {
      DiscretizeBetweenSamples(sys, 0.05, bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find("plant_substeps: must be an integer in [1, 1000000], got " +
                                           std::to_string(bad)),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(DiscretizeBetweenSamples(sys, 0.0, 4), InvalidInputError);
  // Rows without an input (a class-(2) run) have no plant between samples.
  CollectingSink rows;
  SampledPlantSink plant(sys, 0.05, 4, &rows);
  TrajectoryBlock block;
  block.n = 2;
  block.m = 1;
  block.rows = 0;
  try {
    plant.OnRows(block);
    ADD_FAILURE() << "rows without u accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("carry no input u"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace smcbench
