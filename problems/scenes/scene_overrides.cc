#include "problems/scenes/scene_overrides.h"

#include <cmath>
#include <variant>

#include "problems/scenes/scene.h"
#include "solvers/core/number_text.h"

namespace smcbench {
namespace {

// Field → {command-line flag, Python keyword}; the struct's own name when both spell it alike.
struct FieldSpelling {
  std::string_view field, flag, keyword;
};
constexpr FieldSpelling kSpellings[] = {
    {"method", "--method", "method"},
    {"h", "--h", "h"},
    {"T", "--T", "T"},
    {"theta", "--theta", "theta"},
    {"gamma", "--gamma", "gamma"},
    {"x0", "--x0", "x0"},
    {"parameters", "--param", "parameters"},
    {"solver", "--solver", "solver"},
    {"algorithm", "--algorithm", "algorithm"},
    {"newton_tolerance", "--newton-tol", "newton_tol"},
    {"newton_max_iterations", "--newton-max-iter", "newton_max_iterations"},
    {"tolerance", "--tol", "tol"},
    {"max_iterations", "--max-iter", "max_iterations"},
    {"on_failure", "--on-failure", "on_failure"},
    {"plant_substeps", "--plant-substeps", "plant_substeps"},
    {"reach_tolerance", "--reach-tol", "reach_tol"},
};

// The overridden numbers are checked where they are given, naming the field and the value the caller wrote;
// SimulationSettings::Validate then checks the whole (the scene's own values included).
class Checker {
 public:
  explicit Checker(OverrideSpelling spelling) : spelling_(spelling) {}
  std::string Name(std::string_view field) const { return OverrideName(field, spelling_); }
  [[noreturn]] void Fail(std::string_view field, const std::string& what) const {
    throw InvalidInputError(Name(field) + what);
  }
  void Positive(std::string_view field, double value, const char* what) const {
    if (!(value > 0.0) || !std::isfinite(value)) {
      Fail(field, std::string(" must be ") + what + ", got " + NumberText(value));
    }
  }
  void UnitInterval(std::string_view field, double value) const {
    if (!(value >= 0.0 && value <= 1.0)) Fail(field, " must lie in [0, 1], got " + NumberText(value));
  }

 private:
  OverrideSpelling spelling_;
};

void ApplyMethodAndStep(const SceneOverrides& o, const Checker& check, SimulationSettings* s) {
  if (o.method) {
    const auto method = MethodFromString(*o.method);
    if (!method) {
      check.Fail("method", ": unknown method '" + *o.method + "' (known: implicit, explicit, zoh, zoh-explicit)");
    }
    s->method = *method;
    // "explicit" means the classical explicit Euler scheme unless a θ (γ) is asked for.
    if (s->method == Method::kExplicit && !o.theta) s->theta = 0.0;
    if (s->method == Method::kExplicit && !o.gamma) s->gamma = 0.0;
  }
  if (o.h) {
    check.Positive("h", *o.h, "a positive finite time step");
    s->h = *o.h;
  }
  if (o.T) {
    if (!(*o.T >= 0.0) || !std::isfinite(*o.T)) {
      check.Fail("T", " must be a finite horizon >= 0, got " + NumberText(*o.T));
    }
    s->T = *o.T;
  }
  if (o.theta) {
    check.UnitInterval("theta", *o.theta);
    s->theta = *o.theta;
  }
  if (o.gamma) {
    check.UnitInterval("gamma", *o.gamma);
    s->gamma = *o.gamma;
  }
  if (o.x0) s->x0 = *o.x0;
}

void ApplyParameters(const Scene& scene, const SceneOverrides& o, const Checker& check, SimulationSettings* s) {
  const SceneParameters& declared = scene.defaults().parameters;
  for (const auto& [name, value] : o.parameters) {
    if (!declared.count(name)) {
      std::string known;
      for (const auto& [k, v] : declared) known += (known.empty() ? "" : ", ") + k;
      check.Fail("parameters", ": the scene has no parameter '" + name + "' (parameters: " +
                                   (known.empty() ? "none" : known) + ")");
    }
    s->parameters[name] = value;
  }
}

void ApplyNonlinear(const SceneOverrides& o, const Checker& check, bool nonlinear, SimulationSettings* s,
                    std::vector<std::string>* notes) {
  if (o.algorithm) {
    const auto algorithm = NonlinearAlgorithmFromString(*o.algorithm);
    if (!algorithm) {
      check.Fail("algorithm", ": unknown algorithm '" + *o.algorithm + "' (known: newton-mlcp, mcp, closed-form)");
    }
    s->algorithm = *algorithm;
  }
  if (o.newton_tolerance) {
    if (!(*o.newton_tolerance > 0.0) || !std::isfinite(*o.newton_tolerance)) {
      check.Fail("newton_tolerance", ": the newton tolerance must be positive and finite, got " +
                                         NumberText(*o.newton_tolerance));
    }
    s->newton_tolerance = *o.newton_tolerance;
  }
  if (o.newton_max_iterations) {
    if (*o.newton_max_iterations < 1) {
      check.Fail("newton_max_iterations",
                 ": the newton iteration limit must be >= 1, got " + std::to_string(*o.newton_max_iterations));
    }
    s->newton_max_iterations = *o.newton_max_iterations;
  }
  if (!nonlinear && (o.algorithm || o.newton_tolerance || o.newton_max_iterations)) {
    notes->push_back(check.Name("algorithm") + ", " + check.Name("newton_tolerance") + " and " +
                     check.Name("newton_max_iterations") +
                     " apply to nonlinear scenes only; a linear scene solves one box-MLCP per step");
  }
}

void ApplyStepper(const SceneOverrides& o, const Checker& check, StepperOptions* stepper) {
  if (o.tolerance) {
    check.Positive("tolerance", *o.tolerance, "a positive finite number");
    stepper->solver.tolerance = *o.tolerance;
  }
  if (o.max_iterations) {
    if (*o.max_iterations < 0) {
      check.Fail("max_iterations",
                 " must be an integer >= 0 (0: the backend's default), got " + std::to_string(*o.max_iterations));
    }
    stepper->solver.max_iterations = *o.max_iterations;
  }
  if (o.warm_start) stepper->warm_start = *o.warm_start;
  if (o.polish) stepper->solver.polish = *o.polish;
  if (o.subnormals) stepper->subnormals = *o.subnormals;
  if (o.on_failure) {
    if (*o.on_failure == "stop") {
      stepper->on_failure = FailurePolicy::kStop;
    } else if (*o.on_failure == "continue") {
      stepper->on_failure = FailurePolicy::kContinue;
    } else {
      check.Fail("on_failure", ": expected stop or continue, got '" + *o.on_failure + "'");
    }
  }
}

// The plant between samples exists for the ZOH methods only (an Euler method integrates the closed loop itself:
// there is no held input between samples); a scene file's value on another method is dropped with a note.
void ApplyPlantSubsteps(const SceneOverrides& o, const Checker& check, SimulationSettings* s,
                        std::vector<std::string>* notes) {
  if (o.plant_substeps) {
    const int substeps = *o.plant_substeps;
    if (substeps < 1) check.Fail("plant_substeps", " must be an integer >= 1, got " + std::to_string(substeps));
    if (!IsZoh(s->method) && substeps > 1) {
      check.Fail("plant_substeps", " " + std::to_string(substeps) +
                                       " needs method zoh or zoh-explicit (the plant between a ZOH controller's "
                                       "samples); method '" + std::string(ToString(s->method)) +
                                       "' integrates the closed loop");
    }
    s->plant_substeps = substeps;
  } else if (!IsZoh(s->method) && s->plant_substeps > 1) {
    notes->push_back("the scene's plant_substeps applies to methods zoh and zoh-explicit only; method " +
                     std::string(ToString(s->method)) + " reports its samples");
    s->plant_substeps = 1;
  }
}

// The override, else the scene's, else newton for Algorithm 1 (the step's MCP), else auto; none for explicit methods.
std::string BackendName(const SceneOverrides& o, const Checker& check, const SceneRunSettings& run,
                        std::vector<std::string>* notes) {
  const SimulationSettings& s = run.settings;
  if (!IsImplicit(s.method)) {
    if (o.solver) {
      notes->push_back(check.Name("solver") + " is ignored: method " + std::string(ToString(s.method)) +
                       " solves no one-step problem");
    }
    return "";
  }
  if (o.solver) return *o.solver;
  if (!s.solver.empty()) return s.solver;
  if (run.nonlinear && s.algorithm == NonlinearAlgorithm::kClosedForm) return "";  // nothing to solve numerically
  return run.nonlinear && s.algorithm == NonlinearAlgorithm::kMcp ? "newton" : kDefaultSceneBackend;
}

}  // namespace

std::string OverrideName(std::string_view field, OverrideSpelling spelling) {
  for (const FieldSpelling& f : kSpellings) {
    if (f.field == field) return std::string(spelling == OverrideSpelling::kCommandLine ? f.flag : f.keyword);
  }
  return std::string(field);
}

SceneRunSettings ApplySceneOverrides(const Scene& scene, const SceneOverrides& o, OverrideSpelling spelling) {
  const Checker check(spelling);
  SceneRunSettings run;
  const bool super_twisting = scene.step_kind() == SceneStepKind::kSuperTwisting;
  run.nonlinear = super_twisting || scene.step_kind() == SceneStepKind::kNonlinear;
  SimulationSettings& s = run.settings;
  s = scene.defaults();
  ApplyMethodAndStep(o, check, &s);
  ApplyParameters(scene, o, check, &s);
  ApplyNonlinear(o, check, run.nonlinear, &s, &run.notes);
  // Each scene kind takes the algorithms that solve its steps: Algorithms 1 and 2 for S9/S10, closed-form or mcp for
  // super-twisting (its step is a scalar generalized equation, not a box-MLCP).
  if (super_twisting && s.algorithm == NonlinearAlgorithm::kNewtonMlcp) {
    check.Fail("algorithm", " newton-mlcp: a super-twisting step is not a box-MLCP; use closed-form or mcp");
  }
  if (!super_twisting && run.nonlinear && s.algorithm == NonlinearAlgorithm::kClosedForm) {
    check.Fail("algorithm", " closed-form solves the super-twisting scenes' steps only; use newton-mlcp or mcp");
  }
  ApplyStepper(o, check, &s.stepper);
  ApplyPlantSubsteps(o, check, &s, &run.notes);
  run.reach_tolerance = o.reach_tolerance ? *o.reach_tolerance : 10.0 * s.stepper.solver.tolerance;
  if (!(run.reach_tolerance >= 0.0) || !std::isfinite(run.reach_tolerance)) {
    check.Fail("reach_tolerance", " must be finite and >= 0, got " + NumberText(run.reach_tolerance));
  }
  s.Validate(scene.info().n);
  if (!scene.Supports(s.method)) {
    throw InvalidInputError("scene '" + scene.info().name + "' " + scene.WhyUnsupported(s.method));
  }
  if (o.gamma && !run.nonlinear) {
    run.notes.push_back(check.Name("gamma") + " has no effect on a linear scene (g(x) = B is constant)");
  }
  run.backend = BackendName(o, check, run, &run.notes);
  return run;
}

void CheckSceneBackend(const SceneRunSettings& run, const Solver& backend, OverrideSpelling spelling) {
  if (run.nonlinear && run.settings.algorithm == NonlinearAlgorithm::kMcp && !backend.info().mcp) {
    const std::string algorithm = OverrideName("algorithm", spelling);
    throw InvalidInputError(algorithm + " mcp needs a backend that solves nonlinear MCPs (newton); '" + run.backend +
                            "' solves box-MLCPs only: use " + algorithm + " newton-mlcp with it");
  }
}

ZohSmcSystem ZohPlantOf(const Scene& scene, const SceneParameters& parameters) {
  const LinearPlant* linear = scene.linear_plant();
  if (linear == nullptr) throw InvalidInputError("plant_substeps needs a linear scene of system type zoh");
  const LinearModel model = linear->Model(parameters);
  const auto* plant = std::get_if<ZohSmcSystem>(&model);
  if (plant == nullptr) throw InvalidInputError("plant_substeps needs a system of type zoh (a ZOH-sampled plant)");
  return *plant;
}

}  // namespace smcbench
