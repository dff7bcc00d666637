// The nonlinear scenes of docs/scenes.md (S9 `hypomonotone`, S10 `arctan`) behind the same Scene interface as the
// linear ones, so `simulate`, the paper report and the benchmarks run them by name. Their g and h are code
// (problems/stepper/nonlinear_scenes.h); this adapter maps SimulationSettings onto the θ/γ/ρ scheme and the
// two solution paths (Algorithm 1 MCP, Algorithm 2 Newton + any MLCP backend).
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <functional>
#include <memory>

#include "problems/scenes/scene.h"
#include "problems/stepper/nonlinear_scenes.h"

namespace smcbench {

class NonlinearSceneAdapter final : public Scene {
 public:
  // build returns the scene for given parameter values (S9 declares "rho", the ρ-shift of `neuf`); defaults
  // holds the declared parameters with their default values.
  using Builder = std::function<NonlinearScene(const SceneParameters& parameters)>;
  NonlinearSceneAdapter(Builder build, SceneParameters defaults, std::string reference);

  const SceneInfo& info() const override { return info_; }
  SceneStepKind step_kind() const override { return SceneStepKind::kNonlinear; }
  const SimulationSettings& defaults() const override { return defaults_; }
  // Implicit (s_{k+1} ∈ Sgn(h(x_{k+1}))) and explicit (s_{k+1} = sgn(h(x_k))); ZOH needs a linear plant.
  bool Supports(Method method) const override { return method == Method::kImplicit || method == Method::kExplicit; }
  // settings.algorithm picks the path of the implicit steps; Algorithm 1 needs a backend that solves MCPs
  // (each step is kNotApplicable otherwise, reported in *out). settings.theta/gamma/h override the scene's.
  void Run(const SimulationSettings& settings, Solver* solver, Trajectory* out) const override;
  using Scene::Run;
  std::optional<ExactSolution> Exact(const SimulationSettings& settings) const override;

  // The scene built with settings' parameters and numerical settings (what Run steps).
  NonlinearScene Build(const SimulationSettings& settings) const;

 private:
  Builder build_;
  SceneInfo info_;
  SimulationSettings defaults_;
};

// S9 with its parameter rho (default 0) and S10 (no parameters).
std::unique_ptr<Scene> MakeHypomonotoneScene();
std::unique_ptr<Scene> MakeArctanScene();

}  // namespace smcbench
