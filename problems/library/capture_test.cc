// Capture of runs: the stepper hook (called once per implicit step, once per Newton iteration of Algorithm 2,
// never for Algorithm 1, and without changing the run), the recorder's problems (ids, metadata, the z the run
// used, which solves them), streaming to a file, the step subsample and the "paper" suite.
#include "problems/library/capture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

#include "problems/scenes/linear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/nonlinear_scenes.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

constexpr double kTol = 1e-10;

bool SameBits(const Vector& a, const Vector& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

struct Counter final : StepObserver {
  std::int64_t calls = 0;
  std::int64_t last_step = 0;
  void OnStep(std::int64_t step, int newton_iteration, const BoxMLCP&, const SolveResult&) override {
    ++calls;
    EXPECT_GE(step, last_step);
    EXPECT_EQ(newton_iteration, 0);
    last_step = step;
  }
};

TEST(Capture, LinearRunGivesOneSolvedProblemPerStep) {
  const auto scene = LoadScene("sign");
  const SimulationSettings settings = scene->defaults();
  auto solver = CreateSolver("lemke");
  Trajectory tr;
  const std::vector<LibraryProblem> problems =
      CaptureSceneRun(*scene, settings, solver.get(), MakeCaptureContext("run", *scene, settings, "lemke"), &tr);
  ASSERT_TRUE(tr.ok());
  ASSERT_EQ(static_cast<std::int64_t>(problems.size()), tr.steps_taken);
  ASSERT_EQ(tr.steps_taken, 200);
  for (std::int64_t k = 1; k <= tr.steps_taken; ++k) {
    const LibraryProblem& p = problems[static_cast<std::size_t>(k - 1)];
    SCOPED_TRACE(p.id);
    EXPECT_EQ(p.id, "run/sign/implicit/h0.01/k" + std::to_string(k));
    EXPECT_EQ(p.problem.name(), p.id);
    EXPECT_EQ(p.source, "capture:sign");
    EXPECT_EQ(p.expected, ExpectedOutcome::kSolvable);
    EXPECT_EQ(p.metadata.at("scene"), "sign");
    EXPECT_EQ(p.metadata.at("method"), "implicit");
    EXPECT_EQ(p.metadata.at("h"), "0.01");
    EXPECT_EQ(p.metadata.at("theta"), "1");
    EXPECT_EQ(p.metadata.at("step"), std::to_string(k));
    EXPECT_EQ(p.metadata.at("backend"), "lemke");
    EXPECT_EQ(p.metadata.at("status"), "solved");
    EXPECT_EQ(p.metadata.count("iteration"), 0u);
    EXPECT_EQ(p.tags, std::vector<std::string>{"capture"});
    // M = C S = h > 0 (1×1): symmetric, positive definite, a P-matrix.
    EXPECT_EQ(p.matrix.symmetric, Tristate::kYes);
    EXPECT_EQ(p.matrix.positive_definite, Tristate::kYes);
    EXPECT_EQ(p.matrix.p_matrix, Tristate::kYes);
    // The solution is the s_k the run used, and it solves the captured problem.
    EXPECT_TRUE(SameBits(p.solution, tr.s.col(k)));
    EXPECT_EQ(Judge(p, SolveStatus::kSolved, p.solution, kTol).verdict, Verdict::kSolved);
  }
}

// S1: M = h (1×1), relay bounds, so the solution is z = clamp(−q/h, −1, 1): interior (w = 0, μ = 1 for the
// equilibrated 1×1 block [1]) when |q| < h, at the bound −sign(q) otherwise (no free row, μ = 0).
TEST(Capture, RecordedProblemsCarryCertifiedReferences) {
  const auto scene = LoadScene("sign");
  const SimulationSettings settings = scene->defaults();
  auto solver = CreateSolver("lemke");
  Trajectory tr;
  const std::vector<LibraryProblem> problems =
      CaptureSceneRun(*scene, settings, solver.get(), MakeCaptureContext("run", *scene, settings, "lemke"), &tr);
  ASSERT_EQ(problems.size(), 200u);
  int interior = 0;
  for (const LibraryProblem& p : problems) {
    SCOPED_TRACE(p.id);
    const double h = p.problem.dense_matrix()(0, 0), q = p.problem.q()[0];
    ASSERT_EQ(h, 0.01);
    const double z = std::clamp(-q / h, -1.0, 1.0);
    const ReferenceSolution& r = p.reference;
    ASSERT_TRUE(r.unique()) << ToString(r.certificate);
    ASSERT_EQ(r.z.size(), 1);
    EXPECT_NEAR(r.z[0], z, 1e-15 * (1.0 + std::abs(z)));
    if (std::abs(q) < h) {
      ++interior;
      EXPECT_EQ(r.condition, 1.0);
    } else if (std::abs(q) > h) {
      EXPECT_EQ(r.condition, 0.0);
    }
  }
  // S1 reaches the surface and slides: both kinds of step are checked.
  EXPECT_GE(interior, 50);
  EXPECT_LE(interior, 150);

  CaptureContext off = MakeCaptureContext("run", *scene, settings, "lemke");
  off.attach_references = false;
  for (const LibraryProblem& p : CaptureSceneRun(*scene, settings, solver.get(), off, &tr)) {
    EXPECT_EQ(p.reference.certificate, Certificate::kNone) << p.id;
  }
}

// Up to kCaptureReferenceMaxSize rows a recorded problem is certified; above, it keeps Certificate::kNone.
TEST(Capture, ReferencesOnlyUpToFourRows) {
  ProblemRecorder recorder(CaptureContext{});
  for (int m : {kCaptureReferenceMaxSize, kCaptureReferenceMaxSize + 1}) {
    const DenseMatrix M = 2.0 * DenseMatrix::Identity(m, m);
    const BoxMLCP problem = BoxMLCP::Relay(M, Vector::Constant(m, 1.0));  // z = −½ on every row
    SolveResult result;
    result.status = SolveStatus::kSolved;
    result.z = Vector::Constant(m, -0.5);
    recorder.OnStep(m, 0, problem, result);
  }
  ASSERT_EQ(recorder.problems().size(), 2u);
  const ReferenceSolution& small = recorder.problems()[0].reference;
  EXPECT_EQ(small.certificate, Certificate::kUnique);
  EXPECT_EQ(small.z, Vector::Constant(kCaptureReferenceMaxSize, -0.5));
  EXPECT_EQ(recorder.problems()[1].reference.certificate, Certificate::kNone);
}

TEST(Capture, ObserverDoesNotChangeTheRun) {
  const auto scene = LoadScene("multi-surface");
  SimulationSettings settings = scene->defaults();
  auto solver = CreateSolver("lemke");
  const Trajectory plain = scene->Run(settings, solver.get());
  Counter counter;
  settings.stepper.observer = &counter;
  const Trajectory observed = scene->Run(settings, solver.get());
  EXPECT_EQ(counter.calls, plain.steps_taken);
  EXPECT_EQ(counter.last_step, plain.steps_taken);
  ASSERT_EQ(plain.x.size(), observed.x.size());
  EXPECT_EQ(std::memcmp(plain.x.data(), observed.x.data(), sizeof(double) * plain.x.size()), 0);
  EXPECT_EQ(std::memcmp(plain.s.data(), observed.s.data(), sizeof(double) * plain.s.size()), 0);
}

TEST(Capture, RebuildingPathCallsTheObserverToo) {
  const auto loaded = LoadScene("galias-yu-2007");
  ASSERT_EQ(loaded->step_kind(), SceneStepKind::kLinearBox);
  const LinearPlant& scene = *loaded->linear_plant();
  const SimulationSettings& d = loaded->defaults();
  auto solver = CreateSolver("lemke");
  Counter counter;
  StepperOptions options;
  options.observer = &counter;
  Trajectory tr;
  SimulateRebuildingEachStep(scene.Model(d.parameters), Method::kImplicit, d.h, d.theta, d.x0, 20, solver.get(),
                             options, &tr);
  EXPECT_EQ(counter.calls, 20);
}

TEST(Capture, ExplicitRunSolvesNothingAndCapturesNothing) {
  const auto scene = LoadScene("sign");
  SimulationSettings settings = scene->defaults();
  settings.method = Method::kExplicit;
  Trajectory tr;
  const auto problems = CaptureSceneRun(*scene, settings, nullptr, CaptureContext{}, &tr);
  EXPECT_EQ(tr.steps_taken, 200);
  EXPECT_TRUE(problems.empty());
}

TEST(Capture, AlgorithmTwoGivesOneProblemPerNewtonIteration) {
  const NonlinearScene scene = ArctanScene();
  NonlinearStepper stepper(scene.system, scene.scheme);
  auto solver = CreateSolver("lemke");
  CaptureContext context;
  context.scene = "arctan";
  context.method = "implicit";
  context.h = scene.scheme.h;
  ProblemRecorder recorder(context);
  NonlinearStepperOptions options;
  options.stepper.observer = &recorder;
  const Trajectory tr = stepper.Run(scene.x0, scene.num_steps(), solver.get(), options);
  ASSERT_TRUE(tr.ok());
  const NewtonStats& stats = stepper.newton_stats();
  EXPECT_GT(stats.total_iterations, tr.steps_taken / 2);
  ASSERT_EQ(static_cast<std::int64_t>(recorder.count()), stats.total_iterations);
  // Per step: iterations 1..α_k in order; the last one's solution is the s_k the run kept.
  std::map<std::int64_t, std::vector<const LibraryProblem*>> by_step;
  for (const LibraryProblem& p : recorder.problems()) by_step[std::stoll(p.metadata.at("step"))].push_back(&p);
  for (const auto& [k, list] : by_step) {
    SCOPED_TRACE("step " + std::to_string(k));
    ASSERT_EQ(static_cast<int>(list.size()), stats.iterations[static_cast<std::size_t>(k)]);
    for (std::size_t i = 0; i < list.size(); ++i) {
      const LibraryProblem& p = *list[i];
      EXPECT_EQ(p.metadata.at("iteration"), std::to_string(i + 1));
      EXPECT_EQ(p.id, CaptureId(context, k, static_cast<int>(i + 1)));
      EXPECT_EQ(p.tags.back(), "newton-mlcp");
      EXPECT_EQ(Judge(p, SolveStatus::kSolved, p.solution, kTol).verdict, Verdict::kSolved);
    }
    EXPECT_TRUE(SameBits(list.back()->solution, tr.s.col(k)));
  }
}

TEST(Capture, AlgorithmOneSolvesMcpsAndCapturesNothing) {
  const auto scene = LoadScene("hypomonotone");
  SimulationSettings settings = scene->defaults();
  settings.algorithm = NonlinearAlgorithm::kMcp;
  auto solver = CreateSolver("newton");
  Trajectory tr;
  const auto problems = CaptureSceneRun(*scene, settings, solver.get(), CaptureContext{}, &tr);
  EXPECT_GT(tr.steps_taken, 0);
  EXPECT_TRUE(problems.empty());
}

TEST(Capture, StreamsToAWriterWithTheConstantMatrixStoredOnce) {
  const auto scene = LoadScene("observer");
  SimulationSettings settings = scene->defaults();
  auto solver = CreateSolver("lemke");
  std::ostringstream out;
  ProblemSetWriter writer(out, "capture stream", "capture", "observer run");
  ProblemRecorder recorder(MakeCaptureContext("capture", *scene, settings, "lemke"), &writer);
  settings.stepper.observer = &recorder;
  const Trajectory tr = scene->Run(settings, solver.get());
  writer.Close();
  EXPECT_TRUE(recorder.problems().empty());  // streamed, not kept
  EXPECT_EQ(static_cast<std::int64_t>(recorder.count()), tr.steps_taken);
  EXPECT_EQ(writer.problems_written(), recorder.count());
  EXPECT_EQ(writer.matrices_written(), 1u);
  const ProblemSet back = ReadProblemSetBytes(out.str(), "capture stream");
  ASSERT_EQ(static_cast<std::int64_t>(back.problems.size()), tr.steps_taken);
  for (std::int64_t k = 1; k <= tr.steps_taken; ++k) {
    const LibraryProblem& p = back.problems[static_cast<std::size_t>(k - 1)];
    EXPECT_TRUE(SameBits(p.solution, tr.s.col(k))) << p.id;
    EXPECT_EQ(Judge(p, SolveStatus::kSolved, p.solution, kTol).verdict, Verdict::kSolved) << p.id;
  }
}

TEST(Capture, SubsampleSteps) {
  EXPECT_EQ(SubsampleSteps(4, 2, 50, 5, 2), (std::vector<std::int64_t>{1, 2, 3, 4}));
  EXPECT_TRUE(SubsampleSteps(0, -1, 50, 5, 2).empty());
  for (std::int64_t reach : {-1, 1, 400, 750}) {
    SCOPED_TRACE("reaching step " + std::to_string(reach));
    const auto steps = SubsampleSteps(750, reach, 50, 5, 2);
    ASSERT_EQ(steps.size(), 50u);
    EXPECT_TRUE(std::is_sorted(steps.begin(), steps.end()));
    EXPECT_EQ(std::set<std::int64_t>(steps.begin(), steps.end()).size(), 50u);
    const std::set<std::int64_t> kept(steps.begin(), steps.end());
    for (std::int64_t k = 1; k <= 5; ++k) EXPECT_TRUE(kept.count(k)) << k;
    EXPECT_TRUE(kept.count(750));
    if (reach > 0) {
      for (std::int64_t k = std::max<std::int64_t>(1, reach - 2); k <= std::min<std::int64_t>(750, reach + 2); ++k) {
        EXPECT_TRUE(kept.count(k)) << k;
      }
    }
    // Evenly spaced: at most 10 steps are fixed, so the 40 or more others leave no gap above 749 / 39 + 1.
    for (std::size_t i = 1; i < steps.size(); ++i) EXPECT_LE(steps[i] - steps[i - 1], 20);
  }
}

TEST(Capture, PaperSuite) {
  const ProblemSet set = CapturePaperSuite();
  EXPECT_EQ(set.name, "paper");
  EXPECT_NO_THROW(set.Validate());
  std::map<std::string, std::set<std::int64_t>> steps;
  std::map<std::string, int> count;
  for (const LibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    const std::string& scene = p.metadata.at("scene");
    steps[scene].insert(std::stoll(p.metadata.at("step")));
    ++count[scene];
    EXPECT_EQ(p.id.rfind("paper/" + scene + "/", 0), 0u);
    EXPECT_NE(std::find(p.tags.begin(), p.tags.end(), "paper"), p.tags.end());
    EXPECT_EQ(p.expected, ExpectedOutcome::kSolvable);  // lemke solves every step of every scene
    EXPECT_EQ(Judge(p, SolveStatus::kSolved, p.solution, kTol).verdict, Verdict::kSolved);
    const bool nonlinear = scene == "hypomonotone" || scene == "arctan";
    EXPECT_EQ(p.metadata.count("iteration"), nonlinear ? 1u : 0u);
  }
  std::set<std::string> names;
  for (auto name : PaperSceneNames()) names.emplace(name);
  EXPECT_EQ(steps.size(), names.size());
  for (const auto& [scene, kept] : steps) {
    SCOPED_TRACE(scene);
    EXPECT_TRUE(names.count(scene));
    EXPECT_LE(kept.size(), 50u);
    EXPECT_TRUE(kept.count(1));
  }
  EXPECT_EQ(count["filippov"], 50);  // 750 steps, subsampled
  EXPECT_EQ(count["galias-yu-2007"], 33);  // 33 steps, all kept

  // Deterministic, and small on disk: each linear scene's M is stored once.
  std::ostringstream a, b;
  WriteProblemSet(set, a);
  WriteProblemSet(CapturePaperSuite(), b);
  EXPECT_EQ(a.str(), b.str());
  const ProblemSet back = ReadProblemSetBytes(a.str(), "paper");
  ASSERT_EQ(back.problems.size(), set.problems.size());
  for (std::size_t i = 0; i < set.problems.size(); ++i) {
    EXPECT_TRUE(SameBits(back.problems[i].problem.q(), set.problems[i].problem.q()));
  }
}

}  // namespace
}  // namespace smcbench
