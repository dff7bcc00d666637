// Pins down "no allocation per step": a second run of the pre-factored stepper into the same Trajectory
// allocates nothing (fixed-size and dynamic kernels, implicit and explicit, with forcing; recorded, unrecorded and
// streamed to a sink), given a backend that does not allocate. Registry backends are reported, not asserted
// (tests/allocation_test owns them).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <utility>

#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/sampled_plant.h"
#include "problems/stepper/stepper_test_util.h"
#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

using stepper_test::Vec;

// Calls of the global operator new while fn runs (tests/support/malloc_counter.h); tests skip where they cannot be
// observed (sanitizer builds own the allocator).
template <typename Fn>
long CountAllocations(Fn&& fn) {
  return test_support::CountOperatorNew(std::forward<Fn>(fn));
}

struct Case {
  const char* name;
  LinearSignSystem system;
  SignTreatment sign;
  Vector x0;
};

std::vector<Case> Cases() {
  LinearSignSystem big;  // n = 6, m = 3: dynamic kernel
  big.E = -0.1 * DenseMatrix::Identity(6, 6);
  big.B = DenseMatrix::Zero(6, 3);
  big.B(0, 0) = 1, big.B(2, 1) = 1, big.B(4, 2) = 1;
  big.C = big.B.transpose();
  big.forcing = [](double t, Eigen::Ref<Vector> g) { g.setConstant(0.01 * t); };
  return {
      {"S1 implicit", stepper_test::SignScene(), SignTreatment::kImplicit, Vec({1.01})},
      {"S2 explicit", stepper_test::GaliasYuScene(), SignTreatment::kExplicit, Vec({0.0, 2.21})},
      {"S3 implicit", stepper_test::MultiSurfaceScene(), SignTreatment::kImplicit, Vec({1.0, -1.0})},
      {"S7 implicit forced", stepper_test::LyapunovScene(), SignTreatment::kImplicit, Vec({1.0})},
      {"S8 implicit", stepper_test::ObserverScene(0.001), SignTreatment::kImplicit, Vec({2.0, 0.0, 0.0, 0.0})},
      {"n=6 m=3 implicit forced", big, SignTreatment::kImplicit, Vec({1, -1, 0.5, 0.3, -0.7, 0.2})},
  };
}

// Reads every streamed row (x_1, and u_1 when the rows carry an input) and keeps a sum, so that the rows are really
// used, allocating nothing.
class SummingSink final : public TrajectorySink {
 public:
  void OnRows(const TrajectoryBlock& block) override {
    for (std::int64_t j = 0; j < block.rows; ++j) {
      sum += block.x(0, static_cast<Eigen::Index>(j));
      if (block.has_input()) sum += block.u(0, static_cast<Eigen::Index>(j));
    }
  }
  double sum = 0.0;
};

// Allocations of a second run of 5000 steps from x0 into tr (the first sizes everything: streamed, more than one
// block), then the trajectory's checks.
long SecondRunAllocations(LinearStepper& stepper, const Vector& x0, Solver* solver, const StepperOptions& options,
                          Trajectory* tr) {
  stepper.Run(x0, 5000, solver, options, tr);
  const long count = CountAllocations([&] { stepper.Run(x0, 5000, solver, options, tr); });
  EXPECT_TRUE(tr->ok());
  return count;
}

// S5's plant with Siconos' θ = 0.5 equivalent control and a matched sinusoidal disturbance 0.5 sin(50 t).
ZohSmcSystem DisturbedSiso() {
  ZohSmcSystem siso = stepper_test::ZohSisoScene();
  siso.equivalent_control = EquivalentControl{0.5};
  siso.disturbance.W = siso.G;
  siso.disturbance.sinusoids = {{Vec({0.5}), 50.0, 0.0}};
  return siso;
}

TEST(StepperAllocation, RepeatedRunsDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "the allocator is not ours to observe (sanitizer build)";
  stepper_test::ReferenceSolver solver;
  SummingSink sink;
  for (const Case& c : Cases()) {
    for (const char* mode : {"recorded", "unrecorded", "streamed"}) {
      SCOPED_TRACE(std::string(c.name) + " " + mode);
      const bool record = std::string(mode) == "recorded";
      LinearStepper stepper(DiscretizeTheta(c.system, 0.05, 1.0, c.sign));
      StepperOptions options;
      options.record = record;
      if (std::string(mode) == "streamed") options.sink = &sink;
      Trajectory tr;
      EXPECT_EQ(SecondRunAllocations(stepper, c.x0, &solver, options, &tr), 0);
    }
  }
}

// Runs that report their control input (u columns, set one step late through the stream) and carry a plant
// disturbance (sines evaluated per step) allocate nothing either.

TEST(StepperAllocation, InputAndDisturbanceRunsDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "the allocator is not ours to observe (sanitizer build)";
  stepper_test::ReferenceSolver solver;
  SummingSink sink;
  ZohSmcSystem siso = DisturbedSiso();
  siso.disturbance.constant = Vec({0.1});
  ZohSmcSystem mimo = stepper_test::ZohMimoScene();
  mimo.disturbance.W = mimo.G;
  mimo.disturbance.sinusoids = {{Vec({0.2, -0.1}), 20.0, 0.5}};
  LinearSignSystem s1 = stepper_test::SignScene();
  s1.control_input = true;
  const std::pair<const char*, OneStepData> cases[] = {
      {"S5 siconos implicit", DiscretizeZoh(siso, 0.01, SignTreatment::kImplicit)},
      {"S5 siconos explicit", DiscretizeZoh(siso, 0.01, SignTreatment::kExplicit)},
      {"S6 paper implicit", DiscretizeZoh(mimo, 0.01, SignTreatment::kImplicit)},
      {"S1 input", DiscretizeTheta(s1, 0.01, 1.0, SignTreatment::kImplicit)},
  };
  for (const auto& [name, data] : cases) {
    for (const char* mode : {"recorded", "streamed"}) {
      SCOPED_TRACE(std::string(name) + " " + mode);
      LinearStepper stepper(data);
      StepperOptions options;
      options.record = std::string(mode) == "recorded";
      if (!options.record) options.sink = &sink;
      const Vector x0 = Vector::Constant(data.n(), 0.3);
      Trajectory tr;
      EXPECT_EQ(SecondRunAllocations(stepper, x0, &solver, options, &tr), 0);
      EXPECT_TRUE(tr.has_input);
    }
  }
}

// The plant between samples (sampled_plant.h) is made of exponentials computed once; streaming a
// run through it (its points inserted, a row held back, Finish) allocates nothing either.
TEST(StepperAllocation, PlantBetweenSamplesDoesNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "the allocator is not ours to observe (sanitizer build)";
  stepper_test::ReferenceSolver solver;
  SummingSink sink;
  for (const ZohSmcSystem& plant : {DisturbedSiso(), stepper_test::ZohMimoScene()}) {
    LinearStepper stepper(DiscretizeZoh(plant, 0.01, SignTreatment::kImplicit));
    SampledPlantSink between(plant, 0.01, 7, &sink);
    StepperOptions options;
    options.record = false;
    options.sink = &between;
    const Vector x0 = Vector::Constant(plant.n(), 0.3);
    Trajectory tr;
    const auto run = [&] {
      stepper.Run(x0, 5000, &solver, options, &tr);
      between.Finish();
    };
    run();
    EXPECT_EQ(CountAllocations(run), 0);
    EXPECT_TRUE(tr.ok());
  }
}

TEST(StepperAllocation, RegistryBackendsReport) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "the allocator is not ours to observe (sanitizer build)";
  for (std::string_view name : SolverNames()) {
    if (IsExternalBackend(name)) continue;  // a child process per solve: allocation is the point
    auto solver = CreateSolver(name);
    LinearStepper stepper(DiscretizeTheta(stepper_test::MultiSurfaceScene(), 0.02, 1.0, SignTreatment::kImplicit));
    StepperOptions options;
    options.record = false;
    Trajectory tr;
    stepper.Run(Vec({1.0, -1.0}), 75, solver.get(), options, &tr);
    const long count = CountAllocations([&] { stepper.Run(Vec({1.0, -1.0}), 75, solver.get(), options, &tr); });
    std::printf("[ info     ] %-8s S3 75 steps: %ld allocations, status %s\n", std::string(name).c_str(), count,
                tr.ok() ? "ok" : std::string(ToString(tr.first_failure_status)).c_str());
  }
}

// A polytope law (implicit twisting's parallelogram): the AviSession is built when a run starts, and then no step
// allocates: a run of 5000 steps allocates exactly as much as a run of 50 (θ-method and ZOH).
TEST(StepperAllocation, PolytopeLawStepsDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "the allocator is not ours to observe (sanitizer build)";
  LinearSignSystem twisting;  // Siconos' tutorial double integrator
  twisting.E = DenseMatrix::Zero(2, 2);
  twisting.E(0, 1) = 1.0;
  twisting.B = DenseMatrix::Zero(2, 2);
  twisting.B(1, 0) = 10.0, twisting.B(1, 1) = 3.0;
  twisting.C = DenseMatrix::Identity(2, 2);
  twisting.law.H.resize(4, 2);
  twisting.law.H << 1, 0, -0.05, 1, -1, 0, 0.05, -1;
  twisting.law.K = Vector::Constant(4, -1.0);
  ZohSmcSystem plant;  // Siconos' regression plant with its Twisting controller
  plant.F.resize(2, 2);
  plant.F << 0, 1, 19, -2;
  plant.G = DenseMatrix::Zero(2, 2);
  plant.G(1, 0) = 300.0, plant.G(1, 1) = 60.0;
  plant.C = DenseMatrix::Identity(2, 2);
  plant.switching_only = true;
  plant.law.H.resize(4, 2);
  plant.law.H << 1, 0, -0.025, 1, -1, 0, 0.025, -1;
  plant.law.K = Vector::Constant(4, -1.0);
  const std::pair<const char*, OneStepData> cases[] = {
      {"theta", DiscretizeTheta(twisting, 0.1, 0.5, SignTreatment::kImplicit)},
      {"zoh", DiscretizeZoh(plant, 0.05, SignTreatment::kImplicit)}};
  auto lemke = CreateSolver("lemke");
  ASSERT_TRUE(lemke->info().allocation_free);
  for (const auto& [name, data] : cases) {
    LinearStepper stepper(data);
    ASSERT_NE(stepper.avi(), nullptr);
    StepperOptions options;
    options.record = false;
    Trajectory tr;
    const Vector x0 = name == std::string("theta") ? Vec({10.0, 10.0}) : Vec({-15.0, 20.0});
    stepper.Run(x0, 50, lemke.get(), options, &tr);
    const long short_run = CountAllocations([&] { stepper.Run(x0, 50, lemke.get(), options, &tr); });
    const long long_run = CountAllocations([&] { stepper.Run(x0, 5000, lemke.get(), options, &tr); });
    EXPECT_TRUE(tr.ok()) << name << ": " << tr.first_failure_message;
    EXPECT_EQ(long_run, short_run) << name << ": the steps allocate";
  }
}

}  // namespace
}  // namespace smcbench
