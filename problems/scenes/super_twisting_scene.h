// Super-twisting scenes as data: a JSON file of system type "super-twisting" states the gains k1, k2, a disturbance
// d(t) (constant plus sinusoids, unknown to the controller) and the band of the convergence time, and runs the
// implicit (BPE 2020) or explicit Euler discretization of problems/stepper/super_twisting.h. Example (the format is
// in problems/scenes/README.md and docs/scenes.md):
//
//   {
//     "format": "smcbench-scene/1",
//     "name": "super-twisting-disturbed",
//     "parameters": {"k1": 3.5, "k2": 2, "amplitude": 0.5, "omega": 2},
//     "system": {"type": "super-twisting", "k1": "k1", "k2": "k2", "convergence_band": 1e-3,
//                "disturbance": {"sinusoids": [{"amplitude": "amplitude", "omega": "omega"}]}},
//     "simulation": {"method": "implicit", "algorithm": "closed-form", "h": 0.01, "T": 10, "x0": [1, 0]}
//   }
//
// The state is x = (σ, v), y = σ; simulation.algorithm closed-form (default) or mcp (each step's generalized
// equation as an MCP on the run's backend, newton by default). Errors name the file and the field.
#pragma once

#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "problems/scenes/scene.h"
#include "problems/stepper/super_twisting.h"

namespace smcbench {

class SuperTwistingScene final : public Scene {
 public:
  static std::unique_ptr<SuperTwistingScene> FromJson(const nlohmann::json& document, const std::string& source);
  ~SuperTwistingScene() override;

  const SceneInfo& info() const override;
  SceneStepKind step_kind() const override { return SceneStepKind::kSuperTwisting; }
  const SimulationSettings& defaults() const override;
  bool Supports(Method method) const override { return method == Method::kImplicit || method == Method::kExplicit; }
  // Implicit: settings.algorithm closed-form (solver unused, may be null) or mcp (solver must solve MCPs);
  // newton-mlcp is an InvalidInputError (a super-twisting step is not a box-MLCP). Explicit: no solver.
  void Run(const SimulationSettings& settings, Solver* solver, Trajectory* out) const override;
  using Scene::Run;

  // The system with these parameter values (undeclared names are an error; missing ones take their defaults).
  SuperTwistingSystem System(const SceneParameters& parameters) const;
  // |σ| ≤ band defines the convergence time of the summary.
  std::optional<double> convergence_band() const override;

  struct Spec;

 private:
  explicit SuperTwistingScene(std::unique_ptr<Spec> spec);
  std::unique_ptr<Spec> spec_;
};

// True if a scene document declares system type "super-twisting" (the registry's dispatch).
bool IsSuperTwistingDocument(const nlohmann::json& document);

}  // namespace smcbench
