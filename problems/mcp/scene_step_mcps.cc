// The captured one-step MCPs of S9/S10 (scene_step_mcps.h).
#include "problems/mcp/scene_step_mcps.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <utility>

#include "problems/mcp/builtin_mcp.h"
#include "problems/mcp/scalar_math.h"
#include "problems/stepper/nonlinear_scenes.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

enum class Scene { kHypomonotone, kArctan };

// OneStepMCP (problems/stepper/nonlinear_stepper.h) for the two scenes, f = 0:
//   F = ((1 + hρ)(x − x_k) + h g(x_γ) s, −h(x)),  x_γ = γx + (1 − γ)x_k,  z = (x, s) ∈ R × [−1, 1],
//   ∇F = [[1 + hρ + hγ g'(x_γ) s, h g(x_γ)], [−h'(x), 0]];
// S9: g = x + 1, h = x; S10: g = 1/(1 + x²), h = arctan x.
class SceneStepMcp final : public BuiltinMcp<SceneStepMcp> {
 public:
  SceneStepMcp(Scene scene, const NonlinearScheme& scheme, double x_k, std::string name)
      : BuiltinMcp(Lower(), Upper(), std::move(name)), scene_(scene), h_(scheme.h), gamma_(scheme.gamma),
        rho_(scheme.rho), x_k_(x_k) {}

  template <class T>
  void Function(const T* z, T* F) const {
    const T h = h_, xg = T(gamma_) * z[0] + (1 - T(gamma_)) * T(x_k_);
    F[0] = (1 + h * T(rho_)) * (z[0] - T(x_k_)) + h * G(xg) * z[1];
    F[1] = -Surface(z[0]);
  }
  template <class T, class Add>
  void Jacobian(const T* z, Add&& add) const {
    const T h = h_, xg = T(gamma_) * z[0] + (1 - T(gamma_)) * T(x_k_);
    add(0, 0, 1 + h * T(rho_) + h * T(gamma_) * GPrime(xg) * z[1]);
    add(0, 1, h * G(xg));
    add(1, 0, -SurfacePrime(z[0]));
    add(1, 1, T(0));
  }

 private:
  static Vector Lower() { return (Vector(2) << -kInf, -1.0).finished(); }
  static Vector Upper() { return (Vector(2) << kInf, 1.0).finished(); }
  template <class T>
  T G(T x) const { return scene_ == Scene::kHypomonotone ? x + 1 : 1 / (1 + x * x); }
  template <class T>
  T GPrime(T x) const {
    return scene_ == Scene::kHypomonotone ? T(1) : -2 * x / ((1 + x * x) * (1 + x * x));
  }
  template <class T>
  T Surface(T x) const { return scene_ == Scene::kHypomonotone ? x : mcp_math::Atan(x); }
  template <class T>
  T SurfacePrime(T x) const { return scene_ == Scene::kHypomonotone ? T(1) : 1 / (1 + x * x); }

  Scene scene_;
  double h_, gamma_, rho_, x_k_;
};

NonlinearScene SceneOf(Scene scene) { return scene == Scene::kHypomonotone ? HypomonotoneScene() : ArctanScene(); }
const char* NameOf(Scene scene) { return scene == Scene::kHypomonotone ? "hypomonotone" : "arctan"; }

// The scene's run: x_k and s_k for k = 0..N (Algorithm 2 with lemke).
Trajectory RunScene(Scene scene) {
  const NonlinearScene s = SceneOf(scene);
  NonlinearStepper stepper(s.system, s.scheme);
  std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  NonlinearStepperOptions options;
  options.algorithm = NonlinearAlgorithm::kNewtonMlcp;
  options.newton_tolerance = 1e-14;
  options.stepper.record = true;
  return stepper.Run(s.x0, s.num_steps(), lemke.get(), options);
}

}  // namespace

std::vector<std::string> SceneStepMcpIds() {
  std::vector<std::string> ids;
  for (Scene scene : {Scene::kHypomonotone, Scene::kArctan}) {
    const Trajectory tr = RunScene(scene);
    std::int64_t arrival = -1;
    for (std::int64_t k = 0; k < tr.steps_taken && arrival < 0; ++k) {
      if (std::abs(tr.s(0, k + 1)) < 1.0) arrival = k;
    }
    std::vector<std::int64_t> steps{0};
    if (arrival > 0) steps = {0, arrival - 1, arrival, arrival + 1};
    for (std::int64_t k : steps) {
      if (k < tr.steps_taken) ids.push_back(std::string("mcp/scene/") + NameOf(scene) + "/k" + std::to_string(k));
    }
  }
  return ids;
}

bool MakeSceneStepMcp(const std::string& id, BuiltinMcpEntry* out) {
  for (Scene scene : {Scene::kHypomonotone, Scene::kArctan}) {
    const std::string prefix = std::string("mcp/scene/") + NameOf(scene) + "/k";
    if (id.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = id.substr(prefix.size());
    const NonlinearScene s = SceneOf(scene);
    const bool number = !digits.empty() && digits.size() <= 9 &&
                        digits.find_first_not_of("0123456789") == std::string::npos &&
                        (digits == "0" || digits[0] != '0');
    const long k = number ? std::strtol(digits.c_str(), nullptr, 10) : -1;
    if (k < 0 || k >= s.num_steps()) {
      throw InvalidInputError("MakeBuiltinMcp: id '" + id + "': the step must be k<K> with 0 <= K < " +
                              std::to_string(s.num_steps()) + " (the scene's number of steps)");
    }
    const Trajectory tr = RunScene(scene);
    if (k >= tr.steps_taken) {
      throw InvalidInputError("MakeBuiltinMcp: id '" + id + "': the scene's run stopped at step " +
                              std::to_string(tr.steps_taken) + " (" + tr.first_failure_message + ")");
    }
    const double x_k = tr.x(0, k), s_k = tr.s(0, k);
    McpLibraryProblem& p = out->problem;
    p = {};
    p.id = id;
    p.source = std::string("capture:") + NameOf(scene) + " step " + std::to_string(k);
    p.problem = std::make_shared<SceneStepMcp>(scene, s.scheme, x_k, id);
    p.starts = {(Vector(2) << x_k, s_k).finished(), Vector::Zero(2)};
    p.start_labels = {"warm=(x_k,s_k)", "z0=0"};
    p.tags = {"scene", NameOf(scene)};
    p.expected = ExpectedOutcome::kSolvable;
    p.references_complete = false;
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x_k);
    p.metadata["x_k"] = text;
    std::snprintf(text, sizeof text, "%.17g", s.scheme.h);
    p.metadata["h"] = text;
    out->known_solutions = {(Vector(2) << tr.x(0, k + 1), tr.s(0, k + 1)).finished()};
    return true;
  }
  return false;
}

}  // namespace smcbench
