// smcbench.simulate: a scene (registered name, scene file, or a scene document given as JSON text by __init__.py)
// run with the CLI's overrides (tools/smcbench/simulate.cc: h, T, method, theta, gamma, x0, parameters, solver,
// tolerance, algorithm, Newton settings, backend options), recorded, and returned as numpy arrays with the same
// JSON summary `smcbench simulate --summary` writes (SimulationSummary, with the certified reference run).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "convert.h"
#include "problems/scenes/linear_scene.h"
#include "problems/scenes/nonlinear_scene.h"
#include "problems/scenes/registry.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/simulate.h"

namespace smcbench::python {
namespace {

// The settings a Python caller may override; an unset field keeps the scene's value (as an absent CLI flag).
struct SimulateOverrides {
  std::optional<std::string> method;
  std::optional<double> h, T, theta, gamma;
  py::object x0 = py::none();
  std::map<std::string, double> parameters;
  std::optional<std::string> solver;
  double tolerance = 1e-10;
  std::optional<int> max_iterations;
  bool warm_start = true;
  bool polish = true;
  std::string on_failure = "stop";
  std::optional<std::string> algorithm;
  std::optional<double> newton_tolerance;
  std::optional<int> newton_max_iterations;
  std::optional<double> reach_tolerance;
  bool reference = true;
};

bool IsImplicit(Method m) { return m == Method::kImplicit || m == Method::kZoh; }

// The CLI's rules (SimulateCommand::Run), error texts included: Python and the command line accept and refuse the
// same settings.
SimulationSettings ApplyOverrides(const Scene& scene, const SimulateOverrides& o) {
  SimulationSettings s = scene.defaults();
  if (o.method) {
    const auto method = MethodFromString(*o.method);
    if (!method) {
      throw InvalidInputError("method: unknown method '" + *o.method +
                              "' (known: implicit, explicit, zoh, zoh-explicit)");
    }
    s.method = *method;
    // "explicit" means the classical explicit Euler scheme unless a θ (γ) is asked for.
    if (s.method == Method::kExplicit && !o.theta) s.theta = 0.0;
    if (s.method == Method::kExplicit && !o.gamma) s.gamma = 0.0;
  }
  if (o.h) s.h = *o.h;
  if (o.T) s.T = *o.T;
  if (o.theta) s.theta = *o.theta;
  if (o.gamma) s.gamma = *o.gamma;
  if (!o.x0.is_none()) s.x0 = ToVector(o.x0, "x0");
  for (const auto& [name, value] : o.parameters) {
    if (!scene.defaults().parameters.count(name)) {
      std::string known;
      for (const auto& [k, v] : scene.defaults().parameters) known += (known.empty() ? "" : ", ") + k;
      throw InvalidInputError("parameters: the scene has no parameter '" + name + "' (parameters: " +
                              (known.empty() ? "none" : known) + ")");
    }
    s.parameters[name] = value;
  }
  if (o.algorithm) {
    const auto algorithm = NonlinearAlgorithmFromString(*o.algorithm);
    if (!algorithm) {
      throw InvalidInputError("algorithm: unknown algorithm '" + *o.algorithm + "' (known: newton-mlcp, mcp)");
    }
    s.algorithm = *algorithm;
  }
  if (o.newton_tolerance) s.newton_tolerance = *o.newton_tolerance;
  if (o.newton_max_iterations) s.newton_max_iterations = *o.newton_max_iterations;
  s.stepper.solver.tolerance = o.tolerance;
  if (o.max_iterations) s.stepper.solver.max_iterations = *o.max_iterations;
  s.stepper.warm_start = o.warm_start;
  s.stepper.solver.polish = o.polish;
  if (o.on_failure == "stop") {
    s.stepper.on_failure = FailurePolicy::kStop;
  } else if (o.on_failure == "continue") {
    s.stepper.on_failure = FailurePolicy::kContinue;
  } else {
    throw InvalidInputError("on_failure: expected 'stop' or 'continue', got '" + o.on_failure + "'");
  }
  s.stepper.record = true;  // Python gets the whole trajectory
  s.Validate(scene.info().n);
  if (!scene.Supports(s.method)) {
    throw InvalidInputError("method '" + std::string(ToString(s.method)) +
                            "' needs a ZOH plant (system type zoh); this scene runs implicit or explicit");
  }
  return s;
}

py::dict Simulate(const std::string& scene_text, bool is_document, const SimulateOverrides& o,
                  const py::dict& backend_options) {
  const std::unique_ptr<Scene> scene =
      is_document ? std::unique_ptr<Scene>(LinearScene::FromText(scene_text, "scene dict")) : LoadScene(scene_text);
  const SceneInfo& info = scene->info();
  const SimulationSettings s = ApplyOverrides(*scene, o);

  // The backend, only for methods that solve a one-step problem: the override, else the scene's, else auto
  // (newton for Algorithm 1 on a nonlinear scene), as `smcbench simulate` chooses.
  const bool nonlinear = dynamic_cast<const NonlinearSceneAdapter*>(scene.get()) != nullptr;
  std::unique_ptr<Solver> solver;
  std::string solver_name;
  if (IsImplicit(s.method)) {
    const bool mcp = nonlinear && s.algorithm == NonlinearAlgorithm::kMcp;
    solver_name = o.solver ? *o.solver : !s.solver.empty() ? s.solver : mcp ? "newton" : "auto";
    solver = CreateSolver(solver_name);
    if (mcp && !solver->info().mcp) {
      throw InvalidInputError("algorithm 'mcp' needs a backend that solves nonlinear MCPs (newton); '" + solver_name +
                              "' solves box-MLCPs only: use algorithm='newton-mlcp' with it");
    }
    for (const auto& [key, value] : backend_options) {
      const std::string option = py::str(key);
      std::string error;
      if (!solver->SetOption(option, OptionValueText(value, option), &error)) {
        throw InvalidInputError(solver_name + ": " + error);
      }
    }
  } else if (!backend_options.empty()) {
    throw InvalidInputError("backend_options given, but method '" + std::string(ToString(s.method)) +
                            "' solves no one-step problem");
  }

  Trajectory trajectory;
  std::optional<ReferenceComparison> reference;
  double wall = 0.0;
  std::string summary_text;
  {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    scene->Run(s, solver.get(), &trajectory);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.reference) reference = CompareWithReferenceRun(*scene, s, trajectory);
    const double reach_tol = o.reach_tolerance ? *o.reach_tolerance : 10.0 * o.tolerance;
    summary_text = SimulationSummary(*scene, s, solver_name, trajectory, reach_tol, wall,
                                     reference ? &*reference : nullptr)
                       .dump();
  }

  py::dict out;
  out["scene"] = info.name;
  out["description"] = trajectory.description;
  out["solver"] = solver_name.empty() ? py::object(py::none()) : py::object(py::str(solver_name));
  out["t"] = py::array_t<double>(static_cast<py::ssize_t>(trajectory.t.size()), trajectory.t.data());
  out["x"] = ToNumpyTransposed(trajectory.x);
  out["s"] = ToNumpyTransposed(trajectory.s);
  out["y"] = ToNumpyTransposed(trajectory.y);
  out["iterations"] = py::array_t<int>(static_cast<py::ssize_t>(trajectory.iterations.size()),
                                       trajectory.iterations.data());
  out["residual"] = py::array_t<double>(static_cast<py::ssize_t>(trajectory.residual.size()),
                                        trajectory.residual.data());
  py::list status;
  for (SolveStatus st : trajectory.status) status.append(std::string(ToString(st)));
  out["status"] = status;
  out["summary_json"] = summary_text;
  out["wall_seconds"] = wall;
  return out;
}

std::vector<std::string> Scenes() {
  std::vector<std::string> names;
  for (std::string_view name : SceneNames()) names.emplace_back(name);
  return names;
}

}  // namespace

void BindSimulate(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<SimulateOverrides>(m, "_SimulateOverrides")
      .def(py::init<>())
      .def_readwrite("method", &SimulateOverrides::method)
      .def_readwrite("h", &SimulateOverrides::h)
      .def_readwrite("T", &SimulateOverrides::T)
      .def_readwrite("theta", &SimulateOverrides::theta)
      .def_readwrite("gamma", &SimulateOverrides::gamma)
      .def_readwrite("x0", &SimulateOverrides::x0)
      .def_readwrite("parameters", &SimulateOverrides::parameters)
      .def_readwrite("solver", &SimulateOverrides::solver)
      .def_readwrite("tol", &SimulateOverrides::tolerance)
      .def_readwrite("max_iterations", &SimulateOverrides::max_iterations)
      .def_readwrite("warm_start", &SimulateOverrides::warm_start)
      .def_readwrite("polish", &SimulateOverrides::polish)
      .def_readwrite("on_failure", &SimulateOverrides::on_failure)
      .def_readwrite("algorithm", &SimulateOverrides::algorithm)
      .def_readwrite("newton_tol", &SimulateOverrides::newton_tolerance)
      .def_readwrite("newton_max_iterations", &SimulateOverrides::newton_max_iterations)
      .def_readwrite("reach_tol", &SimulateOverrides::reach_tolerance)
      .def_readwrite("reference", &SimulateOverrides::reference);
  m.def("_simulate", &Simulate, "scene"_a, "is_document"_a, "overrides"_a, "backend_options"_a,
        "Run a scene (see smcbench.simulate); returns a dict.");
  m.def("scenes", &Scenes, "The registered scene names, in the order of docs/scenes.md.");
  m.def("scenes_directory", &ScenesDirectory,
        "The folder the registered scene files are read from ($SMCBENCH_SCENES_DIR overrides it).");
}

}  // namespace smcbench::python
