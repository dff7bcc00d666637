// Steps per second of the linear time-stepper on every linear scene of docs/scenes.md with every backend: the
// pre-factored LinearStepper (M = CS built once, record = false) against the generic path that re-discretizes and
// rebuilds the one-step problem at every step (SimulateRebuildingEachStep), plus the explicit scheme (no solve) as
// the floor of the per-step bookkeeping. One benchmark iteration is one whole run of the scene (N steps); the
// counter steps/s is the rate, s/step its inverse. A run whose steps are not all solved is reported as an error.
// Long runs (1000× the scene's horizon, psor and enum) show the steady state once the state has decayed to the
// origin, where plain IEEE arithmetic spends most of its time on subnormal numbers: `.../prefactored-long` runs
// the default StepperOptions (SubnormalPolicy::kZeroState: a state component below 2.2e-308 becomes 0),
// `-long-flush` SubnormalPolicy::kFlushToZero (x86 FTZ/DAZ) and `-long-ieee` SubnormalPolicy::kIeee.
// The super-twisting scenes (stepper/super-twisting*/...) time the two routes of the implicit step, its closed form
// and its MCP on newton and auto, and the explicit Euler scheme, one whole run per iteration.
// After the run a table on stderr gives, per scene and backend, prefactored vs rebuild steps/s, their ratio and
// the goal (≥ 20 M steps/s for S1–S8); docs/benchmarks.md, 'Time-stepper throughput', has the measured rates and
// those of the reference, Siconos 4.4.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "problems/scenes/linear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/scenes/super_twisting_scene.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

constexpr double kGoalStepsPerSecond = 20e6;

enum class Path { kPrefactored, kRebuild };

const char* ToString(Path p) { return p == Path::kPrefactored ? "prefactored" : "rebuild"; }

struct Case {
  std::shared_ptr<const LinearScene> scene;
  SimulationSettings settings;  // the scene's, with record off
  std::string backend;          // "explicit": the explicit-sign scheme, no backend
  double horizon_factor = 1.0;  // the run covers horizon_factor × the scene's T
};

void ReportFailure(benchmark::State& state, const Trajectory& tr) {
  const std::string why = "step " + std::to_string(tr.first_failed_step) + ": " +
                          std::string(smcbench::ToString(tr.first_failure_status)) + " " + tr.first_failure_message;
  state.SkipWithError(why.c_str());
}

void StepperBenchmark(benchmark::State& state, Case c, Path path) {
  const std::int64_t steps = NumSteps(c.horizon_factor * c.settings.T, c.settings.h);
  std::unique_ptr<Solver> solver;
  if (c.backend != "explicit") solver = CreateSolver(c.backend);
  Trajectory tr;
  std::unique_ptr<LinearStepper> stepper;
  LinearModel model;
  if (path == Path::kPrefactored) {
    stepper = std::make_unique<LinearStepper>(c.scene->Discretization(c.settings));
  } else {
    model = c.scene->Model(c.settings.parameters);
  }
  const auto run = [&] {
    if (stepper) {
      stepper->Run(c.settings.x0, steps, solver.get(), c.settings.stepper, &tr);
    } else {
      SimulateRebuildingEachStep(model, c.settings.method, c.settings.h, c.settings.theta, c.settings.x0, steps,
                                 solver.get(), c.settings.stepper, &tr);
    }
  };
  run();  // warm-up: sizes every workspace, and a failing backend is an error, not a fast time
  if (!tr.ok()) return ReportFailure(state, tr);
  for (auto _ : state) {
    run();
    benchmark::DoNotOptimize(tr.x_final.data());
    benchmark::ClobberMemory();
  }
  if (!tr.ok()) return ReportFailure(state, tr);
  const double total = static_cast<double>(steps) * static_cast<double>(state.iterations());
  state.counters["steps/s"] = benchmark::Counter(total, benchmark::Counter::kIsRate);
  state.counters["s/step"] = benchmark::Counter(total, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["iter/step"] = steps ? static_cast<double>(tr.total_iterations) / static_cast<double>(steps) : 0.0;
  state.counters["max_residual"] = tr.max_residual;
  state.counters["N"] = static_cast<double>(steps);
}

// One run of a super-twisting scene per iteration: route "closed-form", "explicit", or a backend name (the MCP route).
void SuperTwistingBenchmark(benchmark::State& state, std::shared_ptr<const Scene> scene, std::string route) {
  SimulationSettings settings = scene->defaults();
  settings.stepper.record = false;
  std::unique_ptr<Solver> solver;
  if (route == "explicit") {
    settings.method = Method::kExplicit;
  } else if (route == "closed-form") {
    settings.method = Method::kImplicit;
    settings.algorithm = NonlinearAlgorithm::kClosedForm;
  } else {
    settings.method = Method::kImplicit;
    settings.algorithm = NonlinearAlgorithm::kMcp;
    solver = CreateSolver(route);
  }
  Trajectory tr;
  scene->Run(settings, solver.get(), &tr);  // warm-up; a failed step is an error, not a fast time
  if (!tr.ok()) return ReportFailure(state, tr);
  for (auto _ : state) {
    scene->Run(settings, solver.get(), &tr);
    benchmark::DoNotOptimize(tr.x_final.data());
    benchmark::ClobberMemory();
  }
  if (!tr.ok()) return ReportFailure(state, tr);
  const double total = static_cast<double>(tr.steps_taken) * static_cast<double>(state.iterations());
  state.counters["steps/s"] = benchmark::Counter(total, benchmark::Counter::kIsRate);
  state.counters["s/step"] = benchmark::Counter(total, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["iter/step"] =
      tr.steps_taken ? static_cast<double>(tr.total_iterations) / static_cast<double>(tr.steps_taken) : 0.0;
  state.counters["max_residual"] = tr.max_residual;
  state.counters["N"] = static_cast<double>(tr.steps_taken);
}

// Forwards to the default display reporter and keeps every run's steps/s for the ratio table.
class CollectingReporter final : public benchmark::BenchmarkReporter {
 public:
  explicit CollectingReporter(benchmark::BenchmarkReporter* display) : display_(display) {}
  bool ReportContext(const Context& context) override { return display_->ReportContext(context); }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const auto it = run.counters.find("steps/s");
      if (it != run.counters.end()) rates_[run.run_name.str()] = it->second.value;
    }
    display_->ReportRuns(runs);
  }
  void Finalize() override { display_->Finalize(); }
  const std::map<std::string, double>& rates() const { return rates_; }

 private:
  benchmark::BenchmarkReporter* display_;
  std::map<std::string, double> rates_;  // run name → steps/s (the last repetition)
};

std::string Rate(double r) {
  char buffer[32];
  if (r <= 0) return "-";
  if (r >= 1e6) {
    std::snprintf(buffer, sizeof buffer, "%.1f M", r / 1e6);
  } else if (r >= 1e4) {
    std::snprintf(buffer, sizeof buffer, "%.0f k", r / 1e3);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.2f k", r / 1e3);
  }
  return buffer;
}

std::vector<std::string> g_scenes, g_backends;

std::string Name(const std::string& scene, const std::string& backend, Path path) {
  return "stepper/" + scene + "/" + backend + "/" + ToString(path);
}

void RegisterAll() {
  g_backends.clear();
  for (auto b : SolverNames()) g_backends.emplace_back(b);
  g_backends.emplace_back("explicit");
  for (auto name : SceneNames()) {
    std::shared_ptr<Scene> scene = LoadScene(name);
    if (std::dynamic_pointer_cast<const SuperTwistingScene>(scene)) {
      if (scene->defaults().method != Method::kImplicit) continue;  // the explicit files: the same runs as below
      // Every backend that solves MCPs takes the MCP route (capabilities, not names).
      std::vector<std::string> routes = {"closed-form", "explicit"};
      for (auto b : SolverNames()) {
        if (CreateSolver(b)->info().mcp) routes.emplace_back(b);
      }
      for (const std::string& route : routes) {
        benchmark::RegisterBenchmark(("stepper/" + std::string(name) + "/" + route).c_str(), SuperTwistingBenchmark,
                                     scene, route)
            ->Unit(benchmark::kMicrosecond);
      }
      continue;
    }
    auto linear = std::dynamic_pointer_cast<const LinearScene>(scene);
    if (!linear) continue;  // nonlinear scenes have their own stepper
    g_scenes.emplace_back(name);
    for (const std::string& backend : g_backends) {
      Case c{linear, linear->defaults(), backend};
      c.settings.stepper.record = false;
      if (backend == "explicit") {
        // The classical explicit scheme of the scene's family: explicit Euler (θ = 0) or explicit ZOH.
        const bool zoh = c.settings.method == Method::kZoh || c.settings.method == Method::kZohExplicit;
        c.settings.method = zoh ? Method::kZohExplicit : Method::kExplicit;
        if (!zoh) c.settings.theta = 0.0;
        if (!linear->Supports(c.settings.method)) continue;  // a polytope law has no explicit scheme
      }
      for (Path path : {Path::kPrefactored, Path::kRebuild}) {
        benchmark::RegisterBenchmark(Name(std::string(name), backend, path).c_str(), StepperBenchmark, c, path)
            ->Unit(benchmark::kMicrosecond);
      }
      if (backend == "psor" || backend == "enum") {
        Case long_run = c;
        long_run.horizon_factor = 1000.0;
        const std::pair<SubnormalPolicy, const char*> policies[] = {{SubnormalPolicy::kZeroState, ""},
                                                                   {SubnormalPolicy::kFlushToZero, "-flush"},
                                                                   {SubnormalPolicy::kIeee, "-ieee"}};
        for (const auto& [policy, suffix] : policies) {
          long_run.settings.stepper.subnormals = policy;
          const std::string long_name = Name(std::string(name), backend, Path::kPrefactored) + "-long" + suffix;
          benchmark::RegisterBenchmark(long_name.c_str(), StepperBenchmark, long_run, Path::kPrefactored)
              ->Unit(benchmark::kMillisecond);
        }
      }
    }
  }
}

void PrintTable(const std::map<std::string, double>& rates) {
  if (rates.empty()) return;
  std::fprintf(stderr, "\nsteps/s per scene and backend: prefactored / rebuild-every-step (ratio); goal >= %s for "
                       "S1-S8 prefactored\n", Rate(kGoalStepsPerSecond).c_str());
  std::fprintf(stderr, "%-16s", "scene");
  for (const auto& b : g_backends) std::fprintf(stderr, " | %-26s", b.c_str());
  std::fprintf(stderr, "\n");
  for (const auto& scene : g_scenes) {
    bool any = false;
    std::string line;
    char cell[96];
    std::snprintf(cell, sizeof cell, "%-16s", scene.c_str());
    line += cell;
    for (const auto& b : g_backends) {
      const auto p = rates.find(Name(scene, b, Path::kPrefactored));
      const auto r = rates.find(Name(scene, b, Path::kRebuild));
      const double pr = p == rates.end() ? 0 : p->second, rr = r == rates.end() ? 0 : r->second;
      any = any || pr > 0 || rr > 0;
      char ratio[24] = "";
      if (pr > 0 && rr > 0) std::snprintf(ratio, sizeof ratio, " (%.0fx)", pr / rr);
      std::snprintf(cell, sizeof cell, " | %-26s",
                    (Rate(pr) + (pr >= kGoalStepsPerSecond ? "*" : "") + " / " + Rate(rr) + ratio).c_str());
      line += cell;
    }
    if (any) std::fprintf(stderr, "%s\n", line.c_str());
  }
  std::fprintf(stderr, "(* = meets the goal; S11 'parasitic' is outside S1-S8)\n");
}

}  // namespace
}  // namespace smcbench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  smcbench::RegisterAll();
  benchmark::AddCustomContext("tolerance", "1e-10 relative natural residual per step");
  benchmark::AddCustomContext("iteration", "one whole run of the scene (N steps), record = false");
  // The library keeps the default display reporter (--benchmark_format) alive itself.
  smcbench::CollectingReporter reporter(benchmark::CreateDefaultDisplayReporter());
  benchmark::RunSpecifiedBenchmarks(&reporter);
  smcbench::PrintTable(reporter.rates());
  benchmark::Shutdown();
  return 0;
}
