#include "bench/perf/perf_figures.h"

#include <algorithm>
#include <optional>
#include <utility>

#include "problems/library/capture.h"
#include "problems/scenes/scene.h"
#include "problems/scenes/registry.h"
#include "problems/suites/families.h"
#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {
namespace {

constexpr double kTolerance = 1e-10;  // as in the paper suite and the stepper benchmark

bool IsSlow(const std::string& backend) { return backend == "ipopt"; }

class SolveWorkload final : public PerfWorkload {
 public:
  SolveWorkload(BoxMLCP problem, const std::string& backend)
      : problem_(std::move(problem)), solver_(CreateSolver(backend)),
        solves_(IsSlow(backend) ? kPerfSlowSolvesPerRun : kPerfSolvesPerRun) {
    options_.tolerance = kTolerance;
    options_.measure_time = false;  // a clock read per solve would be measured too
  }
  void Run() override {
    status_ = SolveStatus::kSolved;
    for (int i = 0; i < solves_; ++i) {
      solver_->Solve(problem_, options_, &result_);
      if (status_ == SolveStatus::kSolved) status_ = result_.status;
    }
  }
  std::int64_t units() const override { return solves_; }
  SolveStatus status() const override { return status_; }

 private:
  BoxMLCP problem_;
  std::unique_ptr<Solver> solver_;
  int solves_;
  SolverOptions options_;
  SolveResult result_;
  SolveStatus status_ = SolveStatus::kNotRun;
};

class StepWorkload final : public PerfWorkload {
 public:
  StepWorkload(const Scene& scene, const LinearPlant& plant, const std::string& backend)
      : settings_(scene.defaults()), stepper_(plant.Discretization(settings_)), solver_(CreateSolver(backend)) {
    settings_.stepper.record = false;
    settings_.stepper.solver.tolerance = kTolerance;
    const std::int64_t cap = IsSlow(backend) ? kPerfSlowStepsPerRun : kPerfStepsPerRun;
    steps_ = std::min(NumSteps(settings_.T, settings_.h), cap);
  }
  void Run() override { stepper_.Run(settings_.x0, steps_, solver_.get(), settings_.stepper, &trajectory_); }
  std::int64_t units() const override { return steps_; }
  SolveStatus status() const override {
    return trajectory_.ok() ? SolveStatus::kSolved : trajectory_.first_failure_status;
  }

 private:
  SimulationSettings settings_;
  LinearStepper stepper_;
  std::unique_ptr<Solver> solver_;
  std::int64_t steps_ = 0;
  Trajectory trajectory_;
};

// The one-step problem of `scene` (its own settings, lemke, the paper suite's tolerance) at step k; k = 0 means
// the last step of the run (on the sliding surface, an interior solution); k = 1 is in the reaching phase.
BoxMLCP PaperProblem(const std::string& scene_name, std::int64_t k) {
  const std::unique_ptr<Scene> scene = LoadScene(scene_name);
  SimulationSettings settings = scene->defaults();
  settings.stepper.solver.tolerance = kTolerance;
  const std::unique_ptr<Solver> solver = CreateSolver("lemke");
  Trajectory trajectory;
  std::vector<LibraryProblem> problems =
      CaptureSceneRun(*scene, settings, solver.get(), MakeCaptureContext("perf", *scene, settings, "lemke"),
                      &trajectory);
  if (problems.empty()) throw InvalidInputError("perf: scene '" + scene_name + "' captured no problem");
  const std::size_t index = k <= 0 ? problems.size() - 1 : static_cast<std::size_t>(k - 1);
  if (index >= problems.size()) {
    throw InvalidInputError("perf: scene '" + scene_name + "' has no step " + std::to_string(k));
  }
  return std::move(problems[index].problem);
}

struct NamedProblem {
  std::string id;
  std::function<BoxMLCP()> make;
};

std::vector<NamedProblem> Problems() {
  return {
      {"paper/multi-surface/k1", [] { return PaperProblem("multi-surface", 1); }},
      {"paper/multi-surface/last", [] { return PaperProblem("multi-surface", 0); }},
      {"paper/zoh-mimo/last", [] { return PaperProblem("zoh-mimo", 0); }},
      {"paper/parasitic/k1", [] { return PaperProblem("parasitic", 1); }},
      {"families/spd-relay/m8/s1",
       [] { return RandomFamilyProblem(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 8, 1).problem; }},
      {"families/pmatrix-mixed/m32/s1",
       [] { return RandomFamilyProblem(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 32, 1).problem; }},
      {"families/murty/n8", [] { return MurtyProblem(8).problem; }},
      {"families/coupled-smc/m64/s1", [] { return CoupledSlidingModeProblem(64, 1).problem; }},
  };
}

}  // namespace

std::vector<PerfCase> PerfCases() {
  std::vector<std::string> backends;
  for (std::string_view name : SolverNames()) {
    if (!IsExternalBackend(name)) backends.emplace_back(name);
  }
  std::vector<PerfCase> cases;
  for (const NamedProblem& p : Problems()) {
    // Made once for all backends (capturing a scene run is the slow part of setting up), on first use.
    auto cache = std::make_shared<std::optional<BoxMLCP>>();
    for (const std::string& backend : backends) {
      cases.push_back({"solve/" + p.id + "/" + backend, "solve", [p, backend, cache] {
                         if (!cache->has_value()) cache->emplace(p.make());
                         return std::make_unique<SolveWorkload>(**cache, backend);
                       }});
    }
  }
  for (const std::string scene : {"galias-yu-2007", "observer"}) {
    for (const std::string& backend : backends) {
      cases.push_back({"step/" + scene + "/" + backend, "step", [scene, backend]() -> std::unique_ptr<PerfWorkload> {
                         const std::unique_ptr<Scene> loaded = LoadScene(scene);
                         const LinearPlant* linear = loaded->linear_plant();
                         if (!linear) throw InvalidInputError("perf: scene '" + scene + "' is not linear");
                         return std::make_unique<StepWorkload>(*loaded, *linear, backend);
                       }});
    }
  }
  return cases;
}

}  // namespace smcbench
