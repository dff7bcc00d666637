#include "problems/scenes/scene.h"

#include <cmath>

#include "solvers/core/number_text.h"

namespace smcbench {
namespace {

[[noreturn]] void Fail(const std::string& what) { throw InvalidInputError(what); }

}  // namespace

void SimulationSettings::Validate(int n) const {
  if (!(h > 0.0) || !std::isfinite(h)) Fail("h must be a positive finite time step, got " + NumberText(h));
  if (!(T >= 0.0) || !std::isfinite(T)) Fail("T must be a finite horizon >= 0, got " + NumberText(T));
  if (!(theta >= 0.0 && theta <= 1.0)) Fail("theta must lie in [0, 1], got " + NumberText(theta));
  if (!(gamma >= 0.0 && gamma <= 1.0)) Fail("gamma must lie in [0, 1], got " + NumberText(gamma));
  if (x0.size() != n) {
    Fail("x0 has " + std::to_string(x0.size()) + " entries but the scene's state has n = " + std::to_string(n));
  }
  for (Eigen::Index i = 0; i < x0.size(); ++i) {
    if (!std::isfinite(x0[i])) Fail("x0[" + std::to_string(i) + "] is not finite (" + NumberText(x0[i]) + ")");
  }
  for (const auto& [name, value] : parameters) {
    if (!std::isfinite(value)) Fail("parameter " + name + " is not finite (" + NumberText(value) + ")");
  }
  std::string why;
  if (!stepper.IsValid(&why)) Fail("stepper options: " + why);
  if (!(newton_tolerance > 0.0) || !std::isfinite(newton_tolerance)) {
    Fail("newton tolerance must be positive and finite, got " + NumberText(newton_tolerance));
  }
  if (newton_max_iterations < 1) {
    Fail("newton iteration limit must be >= 1, got " + std::to_string(newton_max_iterations));
  }
  if (plant_substeps < 1) Fail("plant_substeps must be an integer >= 1, got " + std::to_string(plant_substeps));
  NumSteps(T, h);  // rejects horizons of 2^40 steps or more
}

std::string Scene::WhyUnsupported(Method method) const {
  if (Supports(method)) return "";
  return "runs implicit or explicit, not '" + std::string(ToString(method)) + "' (ZOH needs a linear plant)";
}

}  // namespace smcbench
