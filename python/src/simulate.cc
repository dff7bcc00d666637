// smcbench.simulate: a scene (registered name, scene file, or a scene document given as JSON text by __init__.py)
// run with the overrides `smcbench simulate` takes (problems/scenes/scene_overrides.h: the same rules and
// messages), recorded, and returned as numpy arrays with the same JSON summary `smcbench simulate --summary` writes
// (problems/scenes/run_summary.h, with the certified reference run), the control input u and, for a ZOH run with
// plant_substeps > 1, the plant's rows between samples as `simulate --out` writes them.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "convert.h"
#include "problems/scenes/linear_scene.h"
#include "problems/scenes/reference_run.h"
#include "problems/scenes/registry.h"
#include "problems/scenes/run_summary.h"
#include "problems/scenes/scene_overrides.h"
#include "problems/scenes/super_twisting_scene.h"
#include "problems/stepper/sampled_plant.h"
#include "solvers/registry/registry.h"

namespace smcbench::python {
namespace {

// The keywords of smcbench.simulate as Python sets them; an unset field keeps the scene's value. The stepper's
// options always apply, with the command line's defaults.
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
  std::optional<int> plant_substeps;
  bool reference = true;
};

SceneOverrides ToSceneOverrides(const SimulateOverrides& o) {
  SceneOverrides s;
  s.method = o.method;
  s.h = o.h;
  s.T = o.T;
  s.theta = o.theta;
  s.gamma = o.gamma;
  if (!o.x0.is_none()) s.x0 = ToVector(o.x0, "x0");
  s.parameters.assign(o.parameters.begin(), o.parameters.end());
  s.solver = o.solver;
  s.algorithm = o.algorithm;
  s.newton_tolerance = o.newton_tolerance;
  s.newton_max_iterations = o.newton_max_iterations;
  s.tolerance = o.tolerance;
  s.max_iterations = o.max_iterations;
  s.warm_start = o.warm_start;
  s.polish = o.polish;
  s.on_failure = o.on_failure;
  s.plant_substeps = o.plant_substeps;
  s.reach_tolerance = o.reach_tolerance;
  return s;
}

// Every row a sink receives, kept (the plant's rows between samples: s·N + 1 of them, for Python's arrays).
class RowCollector final : public TrajectorySink {
 public:
  void OnRows(const TrajectoryBlock& block) override {
    n_ = block.n;
    m_ = block.m;
    for (std::int64_t c = 0; c < block.rows; ++c) {
      const auto col = static_cast<Eigen::Index>(c);
      t_.push_back(block.t[static_cast<std::size_t>(c)]);
      for (int i = 0; i < block.n; ++i) x_.push_back(block.x(i, col));
      for (int i = 0; i < block.m; ++i) {
        s_.push_back(block.s(i, col));
        y_.push_back(block.y(i, col));
        u_.push_back(block.has_input() ? block.u(i, col) : std::numeric_limits<double>::quiet_NaN());
      }
    }
  }
  // {t, x, s, y, u}: t of shape (rows,), the others (rows, n or m).
  py::dict ToDict() const {
    const auto rows = static_cast<py::ssize_t>(t_.size());
    const auto table = [rows](const std::vector<double>& values, int columns) {
      return py::array_t<double>({rows, static_cast<py::ssize_t>(columns)}, values.data());
    };
    py::dict out;
    out["t"] = py::array_t<double>(rows, t_.data());
    out["x"] = table(x_, n_);
    out["s"] = table(s_, m_);
    out["y"] = table(y_, m_);
    out["u"] = table(u_, m_);
    return out;
  }

 private:
  int n_ = 0, m_ = 0;
  std::vector<double> t_, x_, s_, y_, u_;
};

// A scene given as a dict: a super-twisting scene if its system type says so, else a linear scene (whose reader
// names every defect, invalid JSON included).
std::unique_ptr<Scene> SceneFromDocument(const std::string& text) {
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_discarded() && IsSuperTwistingDocument(doc)) return SuperTwistingScene::FromJson(doc, "scene dict");
  return LinearScene::FromText(text, "scene dict");
}

py::dict Simulate(const std::string& scene_text, bool is_document, const SimulateOverrides& o,
                  const py::dict& backend_options) {
  const std::unique_ptr<Scene> scene = is_document ? SceneFromDocument(scene_text) : LoadScene(scene_text);
  const SceneInfo& info = scene->info();
  SceneRunSettings run = ApplySceneOverrides(*scene, ToSceneOverrides(o), OverrideSpelling::kPython);
  SimulationSettings& s = run.settings;
  s.stepper.record = true;  // Python gets the whole trajectory

  std::unique_ptr<Solver> solver;
  if (!run.backend.empty()) {
    solver = CreateSolver(run.backend);
    CheckSceneBackend(run, *solver, OverrideSpelling::kPython);
    SetBackendOptions(*solver, run.backend, backend_options);
  } else if (!backend_options.empty()) {
    throw InvalidInputError("backend_options given, but method '" + std::string(ToString(s.method)) +
                            "' solves no one-step problem");
  }
  // The plant between samples (ZOH runs with plant_substeps > 1): built before the run, so a scene without a ZOH
  // plant fails before simulating.
  std::unique_ptr<ZohSmcSystem> plant;
  if (s.plant_substeps > 1) plant = std::make_unique<ZohSmcSystem>(ZohPlantOf(*scene, s.parameters));

  Trajectory trajectory;
  std::optional<ReferenceComparison> reference;
  RowCollector plant_rows;
  double wall = 0.0;
  std::string summary_text;
  {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    scene->Run(s, solver.get(), &trajectory);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (plant) {
      SampledPlantSink sampled(*plant, s.h, s.plant_substeps, &plant_rows);
      FeedRecorded(trajectory, &sampled);
      sampled.Finish();
    }
    if (o.reference) reference = CompareWithReferenceRun(*scene, s, trajectory);
    summary_text = SimulationSummary(*scene, s, run.backend, trajectory, run.reach_tolerance, wall,
                                     reference ? &*reference : nullptr)
                       .dump();
  }

  py::dict out;
  out["scene"] = info.name;
  out["description"] = trajectory.description;
  out["solver"] = run.backend.empty() ? py::object(py::none()) : py::object(py::str(run.backend));
  out["t"] = py::array_t<double>(static_cast<py::ssize_t>(trajectory.t.size()), trajectory.t.data());
  out["x"] = ToNumpyTransposed(trajectory.x);
  out["s"] = ToNumpyTransposed(trajectory.s);
  out["y"] = ToNumpyTransposed(trajectory.y);
  // The input applied over [t_k, t_k+1) (the CLI's u columns); None when the run has none.
  out["u"] = trajectory.has_input ? py::object(ToNumpyTransposed(trajectory.u)) : py::object(py::none());
  out["iterations"] = py::array_t<int>(static_cast<py::ssize_t>(trajectory.iterations.size()),
                                       trajectory.iterations.data());
  out["residual"] = py::array_t<double>(static_cast<py::ssize_t>(trajectory.residual.size()),
                                        trajectory.residual.data());
  py::list status;
  for (SolveStatus st : trajectory.status) status.append(std::string(ToString(st)));
  out["status"] = status;
  out["summary_json"] = summary_text;
  out["wall_seconds"] = wall;
  out["plant"] = plant ? py::object(plant_rows.ToDict()) : py::object(py::none());
  out["notes"] = run.notes;
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
      .def_readwrite("plant_substeps", &SimulateOverrides::plant_substeps)
      .def_readwrite("reference", &SimulateOverrides::reference);
  m.def("_simulate", &Simulate, "scene"_a, "is_document"_a, "overrides"_a, "backend_options"_a,
        "Run a scene (see smcbench.simulate); returns a dict.");
  m.def("scenes", &Scenes, "The registered scene names, in the order of docs/scenes.md.");
  m.def("scenes_directory", &ScenesDirectory,
        "The folder the registered scene files are read from ($SMCBENCH_SCENES_DIR overrides it).");
}

}  // namespace smcbench::python
