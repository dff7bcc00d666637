// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/scenes/nonlinear_scene.h"

#include <utility>

namespace smcbench {

NonlinearSceneAdapter::NonlinearSceneAdapter(Builder build, SceneParameters defaults, std::string reference)
    : build_(std::move(build)) {
  const NonlinearScene scene = build_(defaults);
  info_.name = scene.name;
  info_.description = scene.title;
  info_.reference = std::move(reference);
  info_.source = "built-in";
  info_.n = scene.system.n;
  info_.m = scene.system.m;
  defaults_.method = Method::kImplicit;
  defaults_.h = scene.scheme.h;
  defaults_.T = scene.T;
  defaults_.theta = scene.scheme.theta;
  defaults_.gamma = scene.scheme.gamma;
  defaults_.x0 = scene.x0;
  defaults_.parameters = std::move(defaults);
  defaults_.stepper.record = true;
}

NonlinearScene NonlinearSceneAdapter::Build(const SimulationSettings& settings) const {
  for (const auto& [name, value] : settings.parameters) {
    if (!defaults_.parameters.count(name)) {
      throw InvalidInputError("scene '" + info_.name + "' has no parameter '" + name + "'");
    }
  }
  SceneParameters parameters = defaults_.parameters;
  for (const auto& [name, value] : settings.parameters) parameters[name] = value;
  NonlinearScene scene = build_(parameters);
  scene.scheme.h = settings.h;
  scene.scheme.theta = settings.theta;
  scene.scheme.gamma = settings.gamma;
  scene.scheme.sign = settings.method == Method::kExplicit ? SignTreatment::kExplicit : SignTreatment::kImplicit;
  scene.x0 = settings.x0;
  scene.T = settings.T;
  scene.scheme.Validate();
  return scene;
}

void NonlinearSceneAdapter::Run(const SimulationSettings& settings, Solver* solver, Trajectory* out) const {
  settings.Validate(info_.n);
  if (!Supports(settings.method)) {
    throw InvalidInputError("scene '" + info_.name + "' " + WhyUnsupported(settings.method));
  }
  const NonlinearScene scene = Build(settings);
  NonlinearStepperOptions options;
  options.stepper = settings.stepper;
  options.algorithm = settings.algorithm;
  options.newton_tolerance = settings.newton_tolerance;
  options.newton_max_iterations = settings.newton_max_iterations;
  NonlinearStepper stepper(scene.system, scene.scheme);
  stepper.Run(scene.x0, scene.num_steps(), solver, options, out);
}

std::optional<ExactSolution> NonlinearSceneAdapter::Exact(const SimulationSettings& settings) const {
  const NonlinearScene scene = Build(settings);
  if (!scene.exact) return std::nullopt;
  // The exact solutions are those of the continuous system; the ρ-shift changes only the scheme.
  return scene.exact(settings.x0);
}

std::unique_ptr<Scene> MakeHypomonotoneScene() {
  return std::make_unique<NonlinearSceneAdapter>(
      [](const SceneParameters& p) { return HypomonotoneScene(p.at("rho")); }, SceneParameters{{"rho", 0.0}},
      "Acary & Brogliato 2009, section \"A simple hypomonotone case\" (sixe, neuf; Lemma youpi)");
}

std::unique_ptr<Scene> MakeArctanScene() {
  return std::make_unique<NonlinearSceneAdapter>([](const SceneParameters&) { return ArctanScene(); },
                                                 SceneParameters{},
                                                 "Acary & Brogliato 2009, class (4) eq:quatre, Example example4");
}

}  // namespace smcbench
