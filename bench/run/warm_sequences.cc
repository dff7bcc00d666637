#include "bench/run/warm_sequences.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>

#include "problems/library/capture.h"
#include "problems/library/references.h"
#include "problems/scenes/scene.h"
#include "problems/scenes/registry.h"
#include "problems/suites/families.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

bool SameData(const BoxMLCP& a, const BoxMLCP& b) {
  if (a.is_sparse() != b.is_sparse() || a.size() != b.size() || a.l() != b.l() || a.u() != b.u()) return false;
  if (a.is_sparse()) return DenseMatrix(a.sparse_matrix()) == DenseMatrix(b.sparse_matrix());
  return a.dense_matrix() == b.dense_matrix();
}

// "<suite>/warm/<what>", what without a leading "<suite>/".
std::string SequenceId(const std::string& suite, const std::string& what) {
  const std::string prefix = suite + "/";
  return prefix + "warm/" + (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
}

}  // namespace

WarmSuiteKind WarmSuiteKindOf(const std::string& suite_name, bool is_file) {
  if (is_file) return WarmSuiteKind::kCaptureFile;
  if (suite_name == "paper") return WarmSuiteKind::kScenes;
  if (suite_name == "families") return WarmSuiteKind::kFamilies;
  return WarmSuiteKind::kNone;
}

LibraryProblem TrajectoryStep(const LibraryProblem& base, int k, int steps, double relative_step) {
  const Vector& q0 = base.problem.q();
  const Eigen::Index n = q0.size();
  const double angle = 6.283185307179586 * k / std::max(steps, 1);  // 2πk/K
  const double scale = relative_step * (1.0 + q0.cwiseAbs().maxCoeff());
  Vector q = q0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double a = std::sin(1.3 * static_cast<double>(i) + 0.7);
    const double b = std::cos(0.9 * static_cast<double>(i) + 0.2);
    q[i] += scale * (std::sin(angle) * a + (1.0 - std::cos(angle)) * b);
  }
  BoxMLCP problem = base.problem.is_sparse()
                        ? BoxMLCP(base.problem.sparse_matrix(), q, base.problem.l(), base.problem.u())
                        : BoxMLCP(base.problem.dense_matrix(), q, base.problem.l(), base.problem.u());
  LibraryProblem step = MakeLibraryProblem(base.id + "/k" + std::to_string(k), base.source, std::move(problem));
  step.matrix = base.matrix;
  step.tags = base.tags;
  step.tags.push_back("warm-trajectory");
  step.seed = base.seed;
  step.expected = base.expected;
  if (k == 0) step.solution = base.solution;
  step.metadata = base.metadata;
  step.metadata["step"] = std::to_string(k);
  return step;
}

std::vector<WarmSequence> TrajectoryWarmSequences(const std::string& suite, bool quick) {
  struct Case {
    MatrixFamily family;
    BoundKind bounds;
    int m;
  };
  std::vector<Case> cases;
  if (quick) {
    cases = {{MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 8},
             {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 64}};
  } else {
    for (int m : {8, 64, 256}) {
      for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix}) {
        for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay}) cases.push_back({family, bounds, m});
      }
    }
  }
  const int steps = quick ? 8 : 32;
  // Small enough that most steps keep the previous active set, large enough that some change it.
  constexpr double kRelativeStep = 0.05;
  std::vector<WarmSequence> out;
  for (const Case& c : cases) {
    const LibraryProblem base = RandomFamilyProblem(c.family, c.bounds, c.m, 1);
    WarmSequence sequence;
    sequence.suite = suite;
    sequence.id = SequenceId(suite, base.id);
    sequence.source = WarmSource::kTrajectory;
    for (int k = 0; k < steps; ++k) sequence.steps.push_back(TrajectoryStep(base, k, steps, kRelativeStep));
    out.push_back(std::move(sequence));
  }
  return out;
}

std::vector<WarmSequence> SceneWarmSequences(const std::string& suite, bool quick) {
  std::vector<std::string> names;
  if (quick) {
    names = {"sign", "galias-yu-2007"};
  } else {
    for (std::string_view name : PaperSceneNames()) names.emplace_back(name);
  }
  const int steps = quick ? 20 : 100;
  std::vector<WarmSequence> out;
  for (const std::string& name : names) {
    const std::unique_ptr<Scene> scene = LoadScene(name);
    if (scene->step_kind() != SceneStepKind::kLinearBox) continue;  // Newton's inner M changes per step
    SimulationSettings settings = scene->defaults();
    if (settings.method == Method::kExplicit) settings.method = Method::kImplicit;  // as the paper suite
    if (settings.method == Method::kZohExplicit) settings.method = Method::kZoh;
    settings.T = settings.h * steps;
    const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
    CaptureContext context = MakeCaptureContext(suite, *scene, settings, "lemke");
    context.tags.push_back("warm-scene");
    Trajectory trajectory;
    std::vector<LibraryProblem> problems = CaptureSceneRun(*scene, settings, lemke.get(), context, &trajectory);
    if (problems.size() < 2) continue;
    WarmSequence sequence;
    sequence.suite = suite;
    sequence.source = WarmSource::kScene;
    sequence.id = SequenceId(suite, name);
    for (LibraryProblem& p : problems) {
      if (!sequence.steps.empty() && !SameData(sequence.steps.front().problem, p.problem)) break;
      sequence.steps.push_back(std::move(p));
    }
    out.push_back(std::move(sequence));
  }
  return out;
}

std::vector<WarmSequence> CaptureWarmSequences(const ProblemSet& set, int max_sequences, int max_steps) {
  std::vector<WarmSequence> out;
  std::size_t i = 0;
  while (i < set.problems.size() && static_cast<int>(out.size()) < max_sequences) {
    std::size_t end = i + 1;
    while (end < set.problems.size() && SameData(set.problems[i].problem, set.problems[end].problem)) ++end;
    if (end - i >= 2) {
      WarmSequence sequence;
      sequence.suite = set.name;
      sequence.source = WarmSource::kCapture;
      sequence.id = SequenceId(set.name, set.problems[i].id);
      const std::size_t last = std::min(end, i + static_cast<std::size_t>(std::max(max_steps, 2)));
      sequence.steps.assign(set.problems.begin() + static_cast<std::ptrdiff_t>(i),
                            set.problems.begin() + static_cast<std::ptrdiff_t>(last));
      out.push_back(std::move(sequence));
    }
    i = end;
  }
  return out;
}

void CertifyWarmSequence(WarmSequence* sequence) {
  ProblemSet set;
  set.name = sequence->suite;
  set.problems = std::move(sequence->steps);
  AttachReferences(&set);
  sequence->steps = std::move(set.problems);
}

std::vector<WarmSequence> WarmSequencesForSuite(const ProblemSet& set, WarmSuiteKind kind, bool quick,
                                                bool certify) {
  std::vector<WarmSequence> out;
  switch (kind) {
    case WarmSuiteKind::kNone: return out;
    case WarmSuiteKind::kScenes: out = SceneWarmSequences(set.name, quick); break;
    case WarmSuiteKind::kFamilies: out = TrajectoryWarmSequences(set.name, quick); break;
    case WarmSuiteKind::kCaptureFile: out = CaptureWarmSequences(set, quick ? 2 : 8, quick ? 20 : 200); break;
  }
  for (WarmSequence& sequence : out) {
    if (certify) CertifyWarmSequence(&sequence);
    CheckWarmSequence(sequence);
  }
  return out;
}

}  // namespace smcbench
