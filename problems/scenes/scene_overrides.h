// One set of rules for changing a scene's settings before a run: `smcbench simulate`'s flags and Python's
// smcbench.simulate() keywords both become a SceneOverrides, applied here with the same checks and messages.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "problems/scenes/scene.h"

namespace smcbench {

// The backend of an implicit run when neither the caller nor the scene names one: "auto" (solvers/auto) picks per
// one-step problem the fastest backend that is exact or reliable for its class.
inline constexpr const char* kDefaultSceneBackend = "auto";

// How errors and notes name a field: the command line's flags ("--max-iter") or Python's keywords
// ("max_iterations").
enum class OverrideSpelling { kCommandLine, kPython };

// The settings a caller may change; an unset field keeps the scene's value (docs/cli.md, docs/python.md).
struct SceneOverrides {
  std::optional<std::string> method;  // implicit | explicit | zoh | zoh-explicit; explicit alone means θ = γ = 0
  std::optional<double> h, T, theta, gamma;
  std::optional<Vector> x0;
  std::vector<std::pair<std::string, double>> parameters;  // each a parameter the scene declares
  std::optional<std::string> solver;                       // the backend; ignored (with a note) by explicit methods
  std::optional<std::string> algorithm;                    // nonlinear scenes: newton-mlcp | mcp
  std::optional<double> newton_tolerance;                  // nonlinear scenes
  std::optional<int> newton_max_iterations;                // nonlinear scenes
  std::optional<double> tolerance;                         // each step's relative natural residual
  std::optional<int> max_iterations;                       // the backend's budget, 0: its default
  std::optional<bool> warm_start, polish;
  std::optional<SubnormalPolicy> subnormals;
  std::optional<std::string> on_failure;                   // stop | continue
  std::optional<int> plant_substeps;                       // ZOH methods: points of the plant between samples
  std::optional<double> reach_tolerance;                   // |y| bound of "reached"; default 10 × tolerance
};

// A scene's settings with the overrides applied and checked.
struct SceneRunSettings {
  SimulationSettings settings;
  double reach_tolerance = 0.0;
  bool nonlinear = false;           // a NonlinearSceneAdapter or a SuperTwistingScene (the algorithm applies)
  std::string backend;              // the backend to create; empty for explicit methods (no one-step problem)
  std::vector<std::string> notes;   // overrides that have no effect here, said in one line each
};

// The overrides on scene.defaults(), in a fixed order, then SimulationSettings::Validate and scene.Supports.
// InvalidInputError naming the field in the caller's spelling ("--h must be a positive finite time step, got 0",
// "method: unknown method 'rk4' (known: ...)"): the two callers refuse the same values with the same words.
SceneRunSettings ApplySceneOverrides(const Scene& scene, const SceneOverrides& overrides, OverrideSpelling spelling);

// InvalidInputError if the run's algorithm cannot use this backend (Algorithm 1, mcp, needs one that solves MCPs).
void CheckSceneBackend(const SceneRunSettings& run, const Solver& backend, OverrideSpelling spelling);

// The field's name in errors: "--plant-substeps" or "plant_substeps" for field "plant_substeps" (the struct's names,
// with "tolerance" → tol / --tol and so on).
std::string OverrideName(std::string_view field, OverrideSpelling spelling);

// The ZOH plant of a linear scene of system type zoh with these parameters (the plant between samples:
// sampled_plant.h); InvalidInputError for another scene.
ZohSmcSystem ZohPlantOf(const Scene& scene, const SceneParameters& parameters);

}  // namespace smcbench
