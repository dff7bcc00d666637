// Linear scenes as data: a JSON file describes a class-(2) system x' ∈ E x + g(t) − B Sgn(C x + D) or a ZOH
// plant x' = F x + G u with the ECB-SMC, its parameters, x0, h, T, θ and method, so a user can write a new
// linear sliding-mode system without recompiling. The format is documented in problems/scenes/README.md; an
// example (S8 of docs/scenes.md, abridged):
//
//   {
//     "format": "smcbench-scene/1",
//     "name": "observer",
//     "description": "observer-based SMC with a parasitic actuator of time constant tau (stiff for small tau)",
//     "reference": "Acary & Brogliato 2009, Example Ex:observer (eq. observer)",
//     "parameters": {"tau": 0.001, "k": 1},
//     "system": {
//       "type": "sign",
//       "E": [[0, 0, 0, 0], ["k", "-k", "-k", 0], [0, 0, 0, 1], ["1/tau^2", 0, "-1/tau^2", "-2/tau"]],
//       "B": [[1], [0], [0], [0]],
//       "C": [[1, -1, 0, 0]]
//     },
//     "simulation": {"method": "implicit", "theta": 1, "h": 0.1, "T": 10, "x0": [2, 0, 0, 0]}
//   }
//
// Matrix entries, D, alpha and forcing values are numbers or expressions over the parameters (expression.h).
// Every defect is an InvalidInputError naming the file and the field: "scene file 'x.json': system.B has 3
// rows, expected n = 2 (the size of E)".
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "problems/scenes/scene.h"

namespace smcbench {

class LinearScene final : public Scene, public LinearPlant {
 public:
  // source names the document in error messages (normally the file path).
  static std::unique_ptr<LinearScene> FromJson(const nlohmann::json& document, const std::string& source);
  static std::unique_ptr<LinearScene> FromText(std::string_view text, const std::string& source);
  static std::unique_ptr<LinearScene> FromFile(const std::string& path);

  ~LinearScene() override;

  const SceneInfo& info() const override;
  const SimulationSettings& defaults() const override;
  bool Supports(Method method) const override;
  std::string WhyUnsupported(Method method) const override;
  void Run(const SimulationSettings& settings, Solver* solver, Trajectory* out) const override;
  using Scene::Run;
  std::optional<ExactSolution> Exact(const SimulationSettings& settings) const override;
  SceneStepKind step_kind() const override { return SceneStepKind::kLinearBox; }
  const LinearPlant* linear_plant() const override { return this; }

  // "sign" (E, B, C, D, forcing) or "zoh" (F, G, C, alpha).
  const std::string& system_type() const override;
  // The declared parameters with their default values.
  const SceneParameters& parameters() const;
  // The model with these parameter values (undeclared names are an error; missing ones take their defaults). h is
  // the time step a polytope law's expressions see (system.law may depend on it, as implicit twisting's
  // parallelogram does); absent: the scene's simulation.h.
  LinearModel Model(const SceneParameters& parameters, std::optional<double> h = std::nullopt) const override;
  // Validates settings and discretizes Model(settings.parameters) with settings' method, h and θ: what Run
  // builds its LinearStepper from (benchmarks build it once and time the runs).
  OneStepData Discretization(const SimulationSettings& settings) const override;

  struct Spec;  // the parsed document (implementation detail)

 private:
  explicit LinearScene(std::unique_ptr<Spec> spec);
  // Model() without the "scene 'name': " prefix on errors (the file reader adds its own).
  LinearModel ModelWithoutName(const SceneParameters& parameters, std::optional<double> h = std::nullopt) const;
  std::unique_ptr<Spec> spec_;
};

}  // namespace smcbench
