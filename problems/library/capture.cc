#include "problems/library/capture.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>
#include <utility>

#include "problems/library/references.h"
#include "problems/scenes/scene.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/metrics.h"
#include "solvers/core/number_text.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// M of a and b identical bit by bit (the recorder's classification cache).
bool SameMatrix(const BoxMLCP& a, const BoxMLCP& b) {
  if (a.is_sparse() != b.is_sparse() || a.size() != b.size()) return false;
  if (!a.is_sparse()) {
    return std::memcmp(a.dense_matrix().data(), b.dense_matrix().data(),
                       static_cast<std::size_t>(a.dense_matrix().size()) * sizeof(double)) == 0;
  }
  const SparseMatrix &x = a.sparse_matrix(), &y = b.sparse_matrix();
  if (x.nonZeros() != y.nonZeros()) return false;
  const auto nnz = static_cast<std::size_t>(x.nonZeros());
  return std::memcmp(x.outerIndexPtr(), y.outerIndexPtr(), static_cast<std::size_t>(x.outerSize() + 1) * 4) == 0 &&
         std::memcmp(x.innerIndexPtr(), y.innerIndexPtr(), nnz * 4) == 0 &&
         std::memcmp(x.valuePtr(), y.valuePtr(), nnz * 8) == 0;
}

}  // namespace

CaptureContext MakeCaptureContext(const std::string& set, const Scene& scene, const SimulationSettings& settings,
                                  std::string_view backend) {
  CaptureContext c;
  c.set = set;
  c.scene = scene.info().name;
  c.method = std::string(ToString(settings.method));
  c.h = settings.h;
  if (settings.method == Method::kImplicit || settings.method == Method::kExplicit) c.theta = settings.theta;
  c.backend = std::string(backend);
  if (scene.step_kind() == SceneStepKind::kNonlinear) {
    c.metadata["gamma"] = NumberText(settings.gamma);
    c.metadata["algorithm"] = std::string(ToString(settings.algorithm));
  }
  return c;
}

std::string CaptureId(const CaptureContext& context, std::int64_t step, int newton_iteration) {
  std::string id = context.set + "/" + context.scene + "/" + context.method + "/h" + NumberText(context.h) + "/k" +
                   std::to_string(step);
  if (newton_iteration > 0) id += "/it" + std::to_string(newton_iteration);
  return id;
}

ProblemRecorder::ProblemRecorder(CaptureContext context, ProblemSetWriter* writer, ClassifyOptions classify)
    : context_(std::move(context)), writer_(writer), classify_(classify) {}

void ProblemRecorder::OnStep(std::int64_t step, int newton_iteration, const BoxMLCP& problem,
                             const SolveResult& result) {
  if (step < last_step_ || (step == last_step_ && newton_iteration <= last_iteration_)) {
    throw std::logic_error("ProblemRecorder: step " + std::to_string(step) + " iteration " +
                           std::to_string(newton_iteration) + " after step " + std::to_string(last_step_) +
                           " iteration " + std::to_string(last_iteration_) + ": the ids would repeat");
  }
  last_step_ = step;
  last_iteration_ = newton_iteration;
  if (!classified_ || !SameMatrix(*classified_, problem)) {
    classified_tags_ = ClassifyMatrix(problem, classify_);
    classified_.emplace(problem);
  }
  const std::string id = CaptureId(context_, step, newton_iteration);
  BoxMLCP copy = problem;
  copy.set_name(id);
  std::vector<std::string> labels = context_.tags;
  if (newton_iteration > 0) labels.emplace_back("newton-mlcp");
  std::map<std::string, std::string> metadata = context_.metadata;
  metadata["scene"] = context_.scene;
  metadata["method"] = context_.method;
  metadata["h"] = NumberText(context_.h);
  if (context_.theta) metadata["theta"] = NumberText(*context_.theta);
  metadata["step"] = std::to_string(step);
  if (newton_iteration > 0) metadata["iteration"] = std::to_string(newton_iteration);
  if (!context_.backend.empty()) metadata["backend"] = context_.backend;
  metadata["status"] = std::string(ToString(result.status));
  Vector solution;
  if (result.z.size() == problem.size() && result.z.allFinite()) solution = result.z;
  LibraryProblem p{id,
                   "capture:" + context_.scene,
                   std::move(copy),
                   classified_tags_,
                   std::move(labels),
                   std::nullopt,
                   result.solved() ? ExpectedOutcome::kSolvable : ExpectedOutcome::kUnknown,
                   std::move(solution),
                   std::move(metadata),
                   ReferenceSolution{}};
  if (context_.attach_references && p.size() <= kCaptureReferenceMaxSize) {
    p.reference = ComputeReference(p, ReferenceOptions{kCaptureReferenceMaxSize, /*ask_backends=*/false});
  }
  ++count_;
  if (writer_) {
    writer_->Add(p);
  } else {
    problems_.push_back(std::move(p));
  }
}

std::vector<LibraryProblem> ProblemRecorder::TakeProblems() {
  std::vector<LibraryProblem> out = std::move(problems_);
  problems_.clear();
  return out;
}

std::vector<LibraryProblem> CaptureSceneRun(const Scene& scene, SimulationSettings settings, Solver* solver,
                                            const CaptureContext& context, Trajectory* trajectory) {
  ProblemRecorder recorder(context);
  settings.stepper.observer = &recorder;
  settings.stepper.record = true;
  scene.Run(settings, solver, trajectory);
  return recorder.TakeProblems();
}

std::vector<std::int64_t> SubsampleSteps(std::int64_t num_steps, std::int64_t reaching_step, int max_steps,
                                         int first_steps, int reaching_window) {
  std::vector<std::int64_t> out;
  if (num_steps <= 0 || max_steps <= 0) return out;
  if (num_steps <= max_steps) {
    for (std::int64_t k = 1; k <= num_steps; ++k) out.push_back(k);
    return out;
  }
  std::set<std::int64_t> kept;
  for (std::int64_t k = 1; k <= std::min<std::int64_t>(first_steps, num_steps); ++k) kept.insert(k);
  if (reaching_step >= 1) {
    for (std::int64_t k = reaching_step - reaching_window; k <= reaching_step + reaching_window; ++k) {
      if (k >= 1 && k <= num_steps) kept.insert(k);
    }
  }
  while (static_cast<int>(kept.size()) > max_steps) kept.erase(std::prev(kept.end()));
  const std::int64_t budget = max_steps - static_cast<std::int64_t>(kept.size());
  std::vector<std::int64_t> rest;
  for (std::int64_t k = 1; k <= num_steps; ++k) {
    if (!kept.count(k)) rest.push_back(k);
  }
  const auto r = static_cast<std::int64_t>(rest.size());
  for (std::int64_t i = 0; i < budget && r > 0; ++i) {
    // Evenly spaced over the remaining steps, first and last included.
    const std::int64_t j = budget == 1 ? r - 1 : (i * (r - 1) + (budget - 1) / 2) / (budget - 1);
    kept.insert(rest[static_cast<std::size_t>(j)]);
  }
  return std::vector<std::int64_t>(kept.begin(), kept.end());
}

ProblemSet CapturePaperSuite(const PaperSuiteOptions& options) {
  ProblemSet set;
  set.name = "paper";
  set.description = "one-step box-MLCPs of the report's scenes S1-S11 (implicit/ZOH runs with " + options.backend +
                    ", at most " + std::to_string(options.max_steps_per_scene) +
                    " steps per scene; Algorithm 2 inner problems for S9, S10)";
  for (std::string_view name : PaperSceneNames()) {
    const std::unique_ptr<Scene> scene = LoadScene(name);
    if (scene->step_kind() == SceneStepKind::kSuperTwisting) continue;  // no box-MLCP to capture
    SimulationSettings settings = scene->defaults();
    if (settings.method == Method::kExplicit) settings.method = Method::kImplicit;
    if (settings.method == Method::kZohExplicit) settings.method = Method::kZoh;
    if (scene->step_kind() == SceneStepKind::kNonlinear) settings.algorithm = NonlinearAlgorithm::kNewtonMlcp;
    settings.stepper.solver.tolerance = options.tolerance;
    const std::unique_ptr<Solver> solver = CreateSolver(options.backend);
    CaptureContext context = MakeCaptureContext("paper", *scene, settings, options.backend);
    context.tags.push_back("paper");
    context.attach_references = false;  // most steps are subsampled away: certify only those kept, below
    Trajectory trajectory;
    std::vector<LibraryProblem> problems = CaptureSceneRun(*scene, settings, solver.get(), context, &trajectory);
    const TrajectoryMetrics metrics = ComputeMetrics(trajectory, 10.0 * options.tolerance);
    const std::vector<std::int64_t> steps =
        SubsampleSteps(trajectory.steps_taken, metrics.reaching_step, options.max_steps_per_scene,
                       options.first_steps, options.reaching_window);
    const std::set<std::int64_t> keep(steps.begin(), steps.end());
    for (LibraryProblem& p : problems) {
      if (keep.count(std::stoll(p.metadata.at("step")))) set.problems.push_back(std::move(p));
    }
  }
  // m ≤ 2 everywhere: the run's z and the complete enumeration (at most 3² active sets) need no backend.
  AttachReferences(&set, ReferenceOptions{ReferenceOptions{}.max_size, /*ask_backends=*/false});
  set.Validate();
  return set;
}

}  // namespace smcbench
