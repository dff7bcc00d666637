// The built-in AVI suite (avi_suite.h): the generators (each picks λ*, the active rows and the multipliers first,
// then q := −Mλ* + Hᵀμ* + Eᵀν*), the capture of the twisting scenes' one-step AVIs, and the references.
#include "problems/avi_library/avi_suite.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "problems/scenes/scene.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/linear_stepper.h"
#include "solvers/avi/avi_reduction.h"
#include "solvers/core/number_text.h"
#include "solvers/generators/seeded_random.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// The planted problems reach n + m + p = 32 + 98 + 8 rows in the reduction: above Certify's default of 64, which
// is sized for the enumeration it does not need here (a planted candidate is verified directly).
constexpr int kCertifyMaxSize = 256;

// How M is drawn.
enum class MonotoneKind {
  kStrict,    // M = AᵀA/n + I/2 + (S − Sᵀ): M + Mᵀ positive definite, M not symmetric; λ unique
  kSingular,  // M = bbᵀ, b random: positive semidefinite of rank 1; λ need not be unique
};

DenseMatrix UniformMatrix(SeededRandom* rng, int rows, int cols) {
  DenseMatrix A(rows, cols);
  for (int j = 0; j < cols; ++j) {
    for (int i = 0; i < rows; ++i) A(i, j) = rng->Uniform(-1.0, 1.0);
  }
  return A;
}

DenseMatrix DrawM(SeededRandom* rng, int n, MonotoneKind kind) {
  if (kind == MonotoneKind::kSingular) {
    const DenseMatrix b = UniformMatrix(rng, n, 1);
    return b * b.transpose();
  }
  const DenseMatrix A = UniformMatrix(rng, n, n), S = UniformMatrix(rng, n, n);
  return A.transpose() * A / n + 0.5 * DenseMatrix::Identity(n, n) + (S - S.transpose());
}

// A problem being built: the entry and the solutions known to the generator (the reference's candidates).
struct Draft {
  AviLibraryProblem entry;
  std::vector<AviSolution> known;
};

std::string BoundednessTag(const AffineVI& avi) {
  switch (avi.boundedness()) {
    case PolytopeBoundedness::kBounded: return "bounded";
    case PolytopeBoundedness::kUnbounded: return "unbounded";
    case PolytopeBoundedness::kNotDecided: break;
  }
  return "boundedness-not-decided";
}

Draft Finish(std::string id, std::string source, DenseMatrix M, Vector q, DenseMatrix H, Vector K, DenseMatrix E,
             Vector f, std::vector<std::string> tags, ExpectedOutcome expected) {
  Draft d;
  d.entry.problem = std::make_shared<const AffineVI>(std::move(M), std::move(q), std::move(H), std::move(K),
                                                     std::move(E), std::move(f), id);
  d.entry.id = std::move(id);
  d.entry.source = std::move(source);
  tags.push_back(BoundednessTag(*d.entry.problem));
  if (d.entry.problem->equality_count() > 0) tags.emplace_back("equalities");
  d.entry.tags = std::move(tags);
  d.entry.expected = expected;
  d.entry.metadata["boundedness"] = std::string(ToString(d.entry.problem->boundedness()));
  return d;
}

// Random rows through or around λ*: the first `active` rows pass through λ* with μ*_i in [0.5, 2], the others
// 0.2 to 1 away from it (μ*_i = 0). bounded adds the 2n inactive rows λ*_j − 2 ≤ λ_j ≤ λ*_j + 2, so P is bounded
// whatever the random rows are; without them, fewer than n rows leave a recession direction (P unbounded).
// p random equality rows through λ* with ν* in [−1, 1]. λ* ∈ P by construction, so P is never empty.
Draft MakePlanted(const std::string& family, int n, int random_rows, int active, int p, bool bounded,
                  MonotoneKind kind, std::uint64_t seed) {
  SeededRandom rng(seed);
  Vector lambda(n);
  for (int j = 0; j < n; ++j) lambda[j] = rng.Uniform(-1.0, 1.0);
  const int rows = random_rows + (bounded ? 2 * n : 0);
  DenseMatrix H = DenseMatrix::Zero(rows, n);
  H.topRows(random_rows) = UniformMatrix(&rng, random_rows, n);
  Vector K(rows), mu = Vector::Zero(rows);
  for (int i = 0; i < random_rows; ++i) {
    K[i] = H.row(i).dot(lambda) - (i < active ? 0.0 : rng.Uniform(0.2, 1.0));
    if (i < active) mu[i] = rng.Uniform(0.5, 2.0);
  }
  for (int j = 0; bounded && j < n; ++j) {
    H(random_rows + 2 * j, j) = 1.0;
    K[random_rows + 2 * j] = lambda[j] - 2.0;
    H(random_rows + 2 * j + 1, j) = -1.0;
    K[random_rows + 2 * j + 1] = -lambda[j] - 2.0;
  }
  const DenseMatrix E = UniformMatrix(&rng, p, n);
  const Vector f = E * lambda;
  Vector nu(p);
  for (int j = 0; j < p; ++j) nu[j] = rng.Uniform(-1.0, 1.0);
  DenseMatrix M = DrawM(&rng, n, kind);
  Vector q = -M * lambda + H.transpose() * mu + E.transpose() * nu;
  const std::string id = "avi/" + family + "/n" + std::to_string(n) + "/s" + std::to_string(seed);
  std::vector<std::string> tags{family, kind == MonotoneKind::kStrict ? "strictly-monotone" : "singular-M"};
  Draft d = Finish(id, "generated:" + family, std::move(M), std::move(q), std::move(H), std::move(K), E, f,
                   std::move(tags), ExpectedOutcome::kSolvable);
  d.entry.metadata["seed"] = std::to_string(seed);
  d.entry.metadata["active_rows"] = std::to_string(active);
  d.known.push_back(AviSolution{lambda, mu, nu});
  return d;
}

// A draw on the grid k/8 (exact in binary, and so are the few products and sums the degenerate vertex makes).
double OnGrid(SeededRandom* rng, double lo, double hi) { return std::round(rng->Uniform(lo, hi) * 8.0) / 8.0; }

// A degenerate vertex: λ* lies on n + extra random rows (more active faces than unknowns), only the first ⌈n/2⌉ of
// them with a positive multiplier and the rest with μ*_i = 0 (not strictly complementary). Every row is drawn with
// H_i·c ≥ 0.2·‖H_i‖∞ for one random direction c, so λ* + εc is interior: P is full-dimensional and λ* a vertex of
// it. The 2n rows λ*_j ± 2 keep P bounded; M strictly monotone, so λ* is the only solution (μ* is not unique).
// Why every number is on the grid k/8, each row's largest entry is ±1 and max|M_ij| a power of two: the zero
// slacks of the extra rows must stay exactly zero in the normalized reduction (rows divided by their largest
// entry, M and q by max|M_ij|), or the certifier, whose margins are ~1e-30, sees them violated by rounding.
Draft MakeDegenerateVertex(int n, int extra, std::uint64_t seed) {
  SeededRandom rng(seed);
  Vector lambda(n), c(n);
  for (int j = 0; j < n; ++j) lambda[j] = OnGrid(&rng, -1.0, 1.0);
  for (int j = 0; j < n; ++j) c[j] = rng.Uniform(-1.0, 1.0);
  const int through = n + extra, positive = (n + 1) / 2, rows = through + 2 * n;
  DenseMatrix H = DenseMatrix::Zero(rows, n);
  Vector K(rows), mu = Vector::Zero(rows);
  for (int i = 0; i < through; ++i) {
    Vector row(n);
    do {
      for (int j = 0; j < n; ++j) row[j] = OnGrid(&rng, -1.0, 1.0);
      Eigen::Index largest = 0;
      row.cwiseAbs().maxCoeff(&largest);
      row[largest] = row[largest] < 0.0 ? -1.0 : 1.0;
      if (row.dot(c) < 0.0) row = -row;
    } while (row.dot(c) < 0.2 * c.cwiseAbs().maxCoeff());
    H.row(i) = row.transpose();
    K[i] = row.dot(lambda);
    if (i < positive) mu[i] = OnGrid(&rng, 0.5, 2.0);
  }
  for (int j = 0; j < n; ++j) {
    H(through + 2 * j, j) = 1.0;
    K[through + 2 * j] = lambda[j] - 2.0;
    H(through + 2 * j + 1, j) = -1.0;
    K[through + 2 * j + 1] = -lambda[j] - 2.0;
  }
  DenseMatrix A(n, n), S(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) A(i, j) = OnGrid(&rng, -1.0, 1.0), S(i, j) = OnGrid(&rng, -1.0, 1.0);
  }
  DenseMatrix M = A.transpose() * A / 8.0 + 0.5 * DenseMatrix::Identity(n, n) + (S - S.transpose());
  // Raising M_00 to the power of two at or above max|M_ij| keeps M + Mᵀ positive definite and makes it σ.
  M(0, 0) = std::exp2(std::ceil(std::log2(M.cwiseAbs().maxCoeff())));
  Vector q = -M * lambda + H.transpose() * mu;
  const std::string id = "avi/degenerate/n" + std::to_string(n) + "/a" + std::to_string(through) + "/s" +
                         std::to_string(seed);
  Draft d = Finish(id, "generated:degenerate-vertex", std::move(M), std::move(q), std::move(H), std::move(K),
                   DenseMatrix(), Vector(), {"degenerate", "strictly-monotone"}, ExpectedOutcome::kSolvable);
  d.entry.metadata["seed"] = std::to_string(seed);
  d.entry.metadata["active_rows"] = std::to_string(through);
  d.entry.metadata["zero_multipliers"] = std::to_string(through - positive);
  d.known.push_back(AviSolution{lambda, mu, Vector()});
  return d;
}

// P the nonnegative orthant (a cone: the AVI is the LCP of M), M strictly monotone: the first half of λ* at 0 with
// μ* in [0.5, 2], the rest in [0.5, 1.5] with μ* = 0.
Draft MakeOrthantCone(int n, std::uint64_t seed) {
  SeededRandom rng(seed);
  Vector lambda = Vector::Zero(n), mu = Vector::Zero(n);
  for (int j = 0; j < n; ++j) {
    if (j < n / 2) {
      mu[j] = rng.Uniform(0.5, 2.0);
    } else {
      lambda[j] = rng.Uniform(0.5, 1.5);
    }
  }
  DenseMatrix M = DrawM(&rng, n, MonotoneKind::kStrict);
  Vector q = -M * lambda + mu;
  const std::string id = "avi/cone/n" + std::to_string(n) + "/s" + std::to_string(seed);
  Draft d = Finish(id, "generated:orthant-cone", std::move(M), std::move(q), DenseMatrix::Identity(n, n),
                   Vector::Zero(n), DenseMatrix(), Vector(), {"cone", "strictly-monotone"},
                   ExpectedOutcome::kSolvable);
  d.entry.metadata["seed"] = std::to_string(seed);
  d.known.push_back(AviSolution{lambda, mu, Vector()});
  return d;
}

// AVIs with no solution on a non-empty (unbounded) P. A solution needs Mλ + q = Hᵀμ + Eᵀν with μ ≥ 0 on the rows
// active at λ ∈ P; each comment shows that no λ, μ, ν can.
std::vector<Draft> MakeInfeasible() {
  const auto matrix = [](int rows, int cols, std::initializer_list<double> values) {
    DenseMatrix A(rows, cols);
    auto it = values.begin();
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j < cols; ++j) A(i, j) = *it++;
    }
    return A;
  };
  const auto column = [](std::initializer_list<double> values) {
    Vector v(static_cast<Eigen::Index>(values.size()));
    Eigen::Index i = 0;
    for (double x : values) v[i++] = x;
    return v;
  };
  std::vector<Draft> out;
  // λ ≥ 0, M = 0, q = −1: 0·λ − 1 = μ ≥ 0 is impossible.
  out.push_back(Finish("avi/infeasible/halfline", "hand-made:no solution on a half-line", matrix(1, 1, {0.0}),
                       column({-1.0}), matrix(1, 1, {1.0}), column({0.0}), DenseMatrix(), Vector(), {"infeasible"},
                       ExpectedOutcome::kInfeasible));
  // λ ≥ 0 in R², M skew [[0, 1], [−1, 0]], q = (−1, −1): the second row reads −λ₁ − 1 = μ₂ ≥ 0 with λ₁ ≥ 0.
  out.push_back(Finish("avi/infeasible/skew-orthant", "hand-made:monotone LCP with no solution",
                       matrix(2, 2, {0.0, 1.0, -1.0, 0.0}), column({-1.0, -1.0}), DenseMatrix::Identity(2, 2),
                       Vector::Zero(2), DenseMatrix(), Vector(), {"infeasible"}, ExpectedOutcome::kInfeasible));
  // The ray {λ₁ ≥ 0, λ₁ + λ₂ = 1}, M = 0, q = (−1, 0): (−1, 0) = μ(1, 0) + ν(1, 1) forces ν = 0 and μ = −1 < 0.
  out.push_back(Finish("avi/infeasible/ray-with-equality", "hand-made:no solution on a ray", matrix(2, 2, {0, 0, 0, 0}),
                       column({-1.0, 0.0}), matrix(1, 2, {1.0, 0.0}), column({0.0}), matrix(1, 2, {1.0, 1.0}),
                       column({1.0}), {"infeasible"}, ExpectedOutcome::kInfeasible));
  return out;
}

// Watches a polytope-law run: at the requested steps, the AVI the backend was handed (q = σ·q̃ of the session's
// normalized reduction, whose σ and row scales are those of the stepper's AVI with q = 0) and the run's answer.
class AviStepCapture final : public StepObserver {
 public:
  struct Step {
    std::int64_t step = 0;
    Vector q;
    AviSolution answer;  // empty λ when the backend returned no z of the reduction's size
    SolveStatus status = SolveStatus::kNotRun;
  };

  AviStepCapture(const AffineVI& one_step, std::vector<std::int64_t> steps)
      : reduction_(ReduceToBoxMlcp(one_step, AviReductionScaling::kNormalized)), steps_(std::move(steps)) {}

  void OnStep(std::int64_t step, int /*newton_iteration*/, const BoxMLCP& problem, const SolveResult& result) override {
    if (!std::binary_search(steps_.begin(), steps_.end(), step)) return;
    Step s;
    s.step = step;
    s.q = reduction_.sigma * problem.q().head(reduction_.n);
    const int total = reduction_.n + reduction_.m + reduction_.p;
    if (result.z.size() == total && result.z.allFinite()) s.answer = SplitReducedSolution(reduction_, result.z);
    s.status = result.status;
    captured_.push_back(std::move(s));
  }
  const std::vector<Step>& captured() const { return captured_; }

 private:
  AviReduction reduction_;
  std::vector<std::int64_t> steps_;
  std::vector<Step> captured_;
};

void AttachReference(Draft* d) {
  AviLibraryProblem& p = d->entry;
  if (p.expected != ExpectedOutcome::kInfeasible) {
    CertifyOptions options;
    options.max_size = kCertifyMaxSize;
    p.reference = CertifyAvi(*p.problem, d->known, options);
  }
  p.metadata["certificate"] = std::string(ToString(p.reference.reduced.certificate));
  p.metadata["lambda_unique"] = p.reference.lambda_unique ? "yes" : "no";
}

// Steps spread over a run of num_steps: the first ones (reaching phase), then fractions of the run (sliding).
std::vector<std::int64_t> CaptureSteps(std::int64_t num_steps, bool quick) {
  using Steps = std::vector<std::int64_t>;
  Steps steps = quick ? Steps{1, 3} : Steps{1, 2, 3, 5, 8};
  const Steps eighths = quick ? Steps{4, 8} : Steps{1, 2, 4, 6, 8};
  for (std::int64_t e : eighths) steps.push_back(std::max<std::int64_t>(1, num_steps * e / 8));
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  return steps;
}

}  // namespace

std::vector<AviLibraryProblem> CaptureSceneAvis(const std::string& scene_name, const std::vector<std::int64_t>& steps,
                                                const std::string& backend) {
  const std::unique_ptr<Scene> scene = LoadScene(scene_name);
  const LinearPlant* linear = scene->linear_plant();
  if (linear == nullptr) throw InvalidInputError("CaptureSceneAvis: scene '" + scene_name + "' is not a linear scene");
  SimulationSettings settings = scene->defaults();
  LinearStepper stepper(linear->Discretization(settings));
  const AffineVI* one_step = stepper.avi();
  if (one_step == nullptr) {
    throw InvalidInputError("CaptureSceneAvis: scene '" + scene_name + "' has no polytope law (system.law)");
  }
  std::unique_ptr<Solver> solver = CreateSolver(backend);
  AviStepCapture capture(*one_step, steps);
  settings.stepper.observer = &capture;
  settings.stepper.record = false;
  Trajectory trajectory;
  stepper.Run(settings.x0, NumSteps(settings.T, settings.h), solver.get(), settings.stepper, &trajectory);
  std::vector<AviLibraryProblem> out;
  for (const AviStepCapture::Step& s : capture.captured()) {
    const std::string id = "avi/twisting/" + scene_name + "/k" + std::to_string(s.step);
    Draft d = Finish(id, "capture:" + scene_name, one_step->M(), s.q, one_step->H(), one_step->K(), one_step->E(),
                     one_step->f(), {"twisting", "capture"}, ExpectedAviOutcome(*one_step));
    d.entry.metadata["scene"] = scene_name;
    d.entry.metadata["step"] = std::to_string(s.step);
    d.entry.metadata["h"] = NumberText(settings.h);
    d.entry.metadata["backend"] = backend;
    d.entry.metadata["status"] = std::string(ToString(s.status));
    if (s.answer.lambda.size() > 0) d.known.push_back(s.answer);
    AttachReference(&d);
    out.push_back(std::move(d.entry));
  }
  return out;
}

AviProblemSet BuildAviSuite(bool quick) {
  AviProblemSet set;
  set.name = kAviSuiteName;
  set.description = std::string("AVIs over polytopes: twisting one-step problems, planted random polytopes, "
                                "degenerate vertices, unbounded P, no solution") +
                    (quick ? " (quick sizes)" : "");
  for (const char* scene : kAviSuiteScenes) {
    const std::unique_ptr<Scene> loaded = LoadScene(scene);
    const SimulationSettings defaults = loaded->defaults();
    for (AviLibraryProblem& p : CaptureSceneAvis(scene, CaptureSteps(NumSteps(defaults.T, defaults.h), quick))) {
      set.problems.push_back(std::move(p));
    }
  }
  std::vector<Draft> drafts;
  const std::vector<int> planted_sizes = quick ? std::vector<int>{2, 4, 8} : std::vector<int>{2, 4, 8, 16, 32};
  for (int n : planted_sizes) {
    // n + 2 random faces besides the 2n bounds (more than 2n faces in all), n/2 of them active, n/4 equalities
    // (at least one).
    const int active = std::max(1, n / 2), p = std::max(1, n / 4);
    drafts.push_back(MakePlanted("planted", n, n + 2, active, p, true, MonotoneKind::kStrict, 1));
    // M of rank 1: n − 1 − p active rows leave λ* the only solution (a nonsingular KKT block), so it is certified.
    drafts.push_back(MakePlanted("planted", n, n + 2, n - 1 - p, p, true, MonotoneKind::kSingular, 2));
  }
  for (int n : quick ? std::vector<int>{2, 4} : std::vector<int>{2, 3, 4, 8}) {
    drafts.push_back(MakeDegenerateVertex(n, 2, 1));
  }
  for (int n : quick ? std::vector<int>{2, 4} : std::vector<int>{2, 4, 8}) {
    // n/2 halfspaces (at least one active) and one equality when n ≥ 4: fewer rows than unknowns, P unbounded.
    drafts.push_back(MakePlanted("halfspaces", n, std::max(1, n / 2), 1, n >= 4 ? 1 : 0, false,
                                 MonotoneKind::kStrict, 1));
  }
  for (int n : quick ? std::vector<int>{4} : std::vector<int>{4, 16}) drafts.push_back(MakeOrthantCone(n, 1));
  for (Draft& d : MakeInfeasible()) drafts.push_back(std::move(d));
  for (Draft& d : drafts) {
    AttachReference(&d);
    set.problems.push_back(std::move(d.entry));
  }
  set.Validate();
  return set;
}

}  // namespace smcbench
