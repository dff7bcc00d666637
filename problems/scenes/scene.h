// A scene: one sliding-mode system of the report (docs/scenes.md S1–S11) with its numerical settings, runnable on any
// backend. Linear scenes are data (JSON files, linear_scene.h); scenes that need code (nonlinear g, h) implement
// this interface in C++ and are added to the registry (registry.cc) by one line.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <optional>
#include <string>

#include "problems/scenes/expression.h"
#include "problems/stepper/discretization.h"
#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/metrics.h"
#include "problems/stepper/nonlinear_stepper.h"
#include "problems/stepper/trajectory.h"
#include "solvers/core/solver.h"

namespace smcbench {

// Everything a run needs besides the scene and the backend. A scene's defaults() gives its own values (those of
// docs/scenes.md); a caller overrides fields one by one.
struct SimulationSettings {
  Method method = Method::kImplicit;
  double h = 0.0;       // time step, > 0
  double T = 0.0;       // horizon, >= 0; N = round(T/h) steps (NumSteps)
  double theta = 1.0;   // θ of the θ-method on f, in [0, 1] (unused by ZOH)
  double gamma = 1.0;   // γ of the θ/γ scheme `eq:toto1`, in [0, 1]; no effect when g(x) = B is constant
  Vector x0;            // initial state, size n
  // Scene parameters by name (τ, α, k, ...). Start from the scene's; a name the scene does not declare is an error.
  SceneParameters parameters;
  // Backend options, warm start, failure policy and whether to record the history.
  StepperOptions stepper;
  // Name of the backend the scene suggests (a scene file's "simulation.solver"); callers may ignore it.
  std::string solver;
  // Nonlinear scenes only (S9, S10): the path each implicit step takes (Algorithm 1 "mcp" needs a backend that
  // solves MCPs; Algorithm 2 "newton-mlcp" runs on any box-MLCP backend) and the outer Newton loop's stopping rule.
  NonlinearAlgorithm algorithm = NonlinearAlgorithm::kNewtonMlcp;
  double newton_tolerance = 1e-10;
  int newton_max_iterations = 50;
  // ZOH methods only: the plant between samples (problems/stepper/sampled_plant.h). The outputs that show the
  // trajectory (`simulate --out`, `--plot`) get the exact plant state at s − 1 points between every two samples;
  // the run and its metrics stay on the controller's samples. 1 (the default): the samples alone.
  int plant_substeps = 1;

  // Throws InvalidInputError naming the field: h ≤ 0 or non-finite, T < 0 or non-finite, θ or γ outside [0, 1],
  // x0 not of size n or not finite, invalid stepper options, Newton tolerance not in (0, ∞) or budget < 1,
  // plant_substeps < 1.
  void Validate(int n) const;
};

struct SceneInfo {
  std::string name;         // the registry name ("sign", "observer", ...) or the file's "name"
  std::string description;  // one line
  std::string reference;    // where in the report (section, equation label)
  std::string source;       // the file it was read from, or "built-in"
  int n = 0;                // state dimension
  int m = 0;                // number of sliding surfaces
};

// What a scene's implicit step is, and so what a caller may do with the scene besides running it (capture its
// one-step problems, build families from its matrix, replay warm sequences): asked of the scene, never found by a
// cast to its concrete type.
enum class SceneStepKind {
  kLinearBox,      // a linear plant and law (LinearScene): a box-MLCP (or a polytope AVI) with the same matrix every
                   // step; linear_plant() gives the model and the one-step data
  kNonlinear,      // a nonlinear plant or input (S9, S10): Algorithm 2's inner box-MLCPs or one MCP per step;
                   // SimulationSettings::algorithm and the Newton settings apply
  kSuperTwisting,  // a super-twisting law: a scalar generalized equation per step (closed form or MCP), no box-MLCP
};

// The capability of a kLinearBox scene: its model and the data of its one-step problem (the same matrix M at
// every step), for callers that build problems from a scene rather than run it.
class LinearPlant {
 public:
  virtual ~LinearPlant() = default;
  // "sign" (E, B, C, D, forcing) or "zoh" (F, G, C, alpha).
  virtual const std::string& system_type() const = 0;
  // The model with these parameter values (undeclared names are an error; missing ones take their defaults). h is
  // the time step a polytope law's expressions see; absent: the scene's own.
  virtual LinearModel Model(const SceneParameters& parameters, std::optional<double> h = std::nullopt) const = 0;
  // Validates settings and discretizes Model(settings.parameters) with settings' method, h and θ.
  virtual OneStepData Discretization(const SimulationSettings& settings) const = 0;
};

class Scene {
 public:
  virtual ~Scene() = default;

  // What its implicit step is (above).
  virtual SceneStepKind step_kind() const = 0;
  // The linear plant's model and one-step data for a kLinearBox scene; null for the others.
  virtual const LinearPlant* linear_plant() const { return nullptr; }
  // A super-twisting scene's band |σ| ≤ band in which its precision is measured; nullopt for the others.
  virtual std::optional<double> convergence_band() const { return std::nullopt; }

  virtual const SceneInfo& info() const = 0;
  // The scene's own settings (record on, warm start on, stop at the first failed step).
  virtual const SimulationSettings& defaults() const = 0;
  // Whether Run accepts this method (a sign system cannot be run with ZOH, which needs the open-loop plant).
  virtual bool Supports(Method method) const = 0;
  // Why Run refuses method, as the sentence an error gives after the scene's name ("" when Supports(method)).
  virtual std::string WhyUnsupported(Method method) const;

  // Runs the scene into *out (storage reused). solver may be null for explicit-sign methods. Throws
  // InvalidInputError for invalid settings (naming the field) or an unsupported method; a one-step problem the
  // backend does not solve is a status in *out, never an exception.
  virtual void Run(const SimulationSettings& settings, Solver* solver, Trajectory* out) const = 0;
  Trajectory Run(const SimulationSettings& settings, Solver* solver) const {
    Trajectory out;
    Run(settings, solver, &out);
    return out;
  }

  // The exact solution of the continuous system from settings.x0 with settings.parameters, if the scene has one
  // (S1: x(t) = x0 − sgn(x0) t before t* = |x0|, 0 after; s = sgn(x0) then 0).
  virtual std::optional<ExactSolution> Exact(const SimulationSettings& settings) const {
    (void)settings;
    return std::nullopt;
  }
};

}  // namespace smcbench
