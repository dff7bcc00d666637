#include "tools/smcbench/simulate.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <sstream>
#include <system_error>

#include "bench/figures/gnuplot_figure.h"
#include "bench/figures/trajectory_plot.h"
#include "problems/library/capture.h"
#include "problems/scenes/registry.h"
#include "problems/scenes/run_summary.h"
#include "problems/scenes/scene_overrides.h"
#include "problems/scenes/scene.h"
#include "problems/stepper/sampled_plant.h"
#include "solvers/core/duration_text.h"
#include "solvers/core/number_text.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/output_paths.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string VectorText(const Vector& v) {
  std::string text = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) text += (i ? ", " : "") + NumberText(v[i]);
  return text + "]";
}

// A double from the whole of text (no locale, no trailing characters); nullopt otherwise.
std::optional<double> ParseDouble(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

Vector ParseVector(const std::string& text, const char* option) {
  std::vector<double> values;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    const auto v = ParseDouble(item);
    if (!v) throw InvalidInputError(std::string(option) + ": '" + item + "' is not a number (expected v1,v2,...)");
    values.push_back(*v);
  }
  if (values.empty() || (!text.empty() && text.back() == ',')) {
    throw InvalidInputError(std::string(option) + ": expected comma-separated numbers v1,v2,..., got '" + text + "'");
  }
  return Eigen::Map<const Vector>(values.data(), static_cast<Eigen::Index>(values.size()));
}

std::string FormatSeconds(double seconds) { return DurationText(seconds); }

std::string FormatRate(double per_second) {
  char buffer[48];
  if (per_second >= 1e6) {
    std::snprintf(buffer, sizeof buffer, "%.1f M", per_second / 1e6);
  } else if (per_second >= 1e3) {
    std::snprintf(buffer, sizeof buffer, "%.1f k", per_second / 1e3);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.0f ", per_second);
  }
  return buffer;
}

}  // namespace

// ------------------------------------------------------------------------------------------------------------
// simulate

struct SimulateCommand::Flags {
  std::string scene, method, x0, solver, out, summary, plot, on_failure = "stop", algorithm, record;
  double h = 0.0, T = 0.0, theta = 0.0, gamma = 0.0, tol = 1e-10, reach_tol = 0.0, newton_tol = 0.0;
  int max_iter = 0, newton_max_iter = 0, plant_substeps = 1;
  bool no_warm_start = false, flush_subnormals = false, ieee_subnormals = false, no_polish = false;
  std::vector<std::string> params, sets;
  CLI::Option *method_opt = nullptr, *h_opt = nullptr, *T_opt = nullptr, *theta_opt = nullptr,
              *gamma_opt = nullptr, *x0_opt = nullptr, *reach_opt = nullptr, *solver_opt = nullptr,
              *algorithm_opt = nullptr, *newton_tol_opt = nullptr, *newton_max_iter_opt = nullptr,
              *plant_substeps_opt = nullptr;
};

SimulateCommand::SimulateCommand(CLI::App* app) : flags_(std::make_unique<Flags>()) {
  Flags& f = *flags_;
  command_ = app->add_subcommand("simulate", "run a scene of docs/scenes.md (see `smcbench scenes`) or a scene file");
  command_->add_option("SCENE", f.scene, "registered scene name or path to a scene JSON file")->required();
  f.method_opt = command_->add_option("--method", f.method,
                                      "implicit | explicit | zoh | zoh-explicit (default: the scene's); explicit "
                                      "without --theta/--gamma is the classical explicit Euler scheme (theta = "
                                      "gamma = 0)");
  f.h_opt = command_->add_option("--h", f.h, "time step (default: the scene's)");
  f.T_opt = command_->add_option("--T", f.T, "horizon; N = round(T/h) steps (default: the scene's)");
  f.x0_opt = command_->add_option("--x0", f.x0, "initial state v1,v2,... (default: the scene's)");
  f.theta_opt = command_->add_option("--theta", f.theta, "theta of the theta-method on f, in [0, 1]");
  f.gamma_opt = command_->add_option("--gamma", f.gamma, "gamma of the theta/gamma scheme, in [0, 1] (nonlinear g)");
  command_->add_option("--param", f.params, "scene parameter NAME=VALUE, e.g. --param tau=0.5 (repeatable)");
  f.solver_opt = command_->add_option("--solver", f.solver,
                                      std::string("backend for the one-step problems (default: the scene's, else ") +
                                          kDefaultSceneBackend + ")");
  f.algorithm_opt = command_->add_option(
      "--algorithm", f.algorithm,
      "nonlinear scenes: newton-mlcp (Algorithm 2: outer Newton, each iteration a box-MLCP on any backend; "
      "default) | mcp (Algorithm 1: the step's MCP, backend newton); super-twisting scenes: closed-form (default) | "
      "mcp (the step's generalized equation as an MCP, backend newton)");
  f.newton_tol_opt = command_->add_option("--newton-tol", f.newton_tol,
                                          "nonlinear scenes: Newton stopping tolerance on the step's relative "
                                          "residual (default 1e-10)");
  f.newton_max_iter_opt = command_->add_option("--newton-max-iter", f.newton_max_iter,
                                               "nonlinear scenes: Newton iterations per step (default 50)");
  command_->add_option("--tol", f.tol, "tolerance on each step's relative natural residual (default 1e-10)");
  command_->add_option("--max-iter", f.max_iter, "backend iteration budget (0: its default)");
  command_->add_option("--set", f.sets, "typed backend option BACKEND.OPTION=VALUE (see `smcbench list`)");
  command_->add_option("--on-failure", f.on_failure, "stop | continue when a step's problem is not solved");
  command_->add_flag("--no-warm-start", f.no_warm_start, "cold-start every step instead of starting from s_k");
  command_->add_flag("--no-polish", f.no_polish,
                     "no exact polish of the backend's answers (SolverOptions::polish = false): the raw algorithm");
  command_->add_flag("--flush-subnormals", f.flush_subnormals,
                     "x86 flush-to-zero for the whole run, backend included, instead of the default (a state "
                     "component that underflows below 2.2e-308 after an implicit step is set to 0)");
  command_->add_flag("--ieee-subnormals", f.ieee_subnormals,
                     "plain IEEE arithmetic: keep subnormal states (a long run decaying to the origin then steps "
                     "2-18x slower; the default sets a state component below 2.2e-308 to 0)");
  f.reach_opt = command_->add_option("--reach-tol", f.reach_tol,
                                     "|y| bound defining 'on the surface' for the reaching step (default 10*tol)");
  command_->add_option("--out", f.out, "write the trajectory CSV t,x1..xn,s1..sm,y1..ym,iterations,residual (then u1..um, the "
                       "input applied over [t_k, t_k+1), for ZOH scenes and S1)");
  command_->add_option("--summary", f.summary,
                       "write the JSON summary (steps, x_final, reaching_step, s_error_max and y_error_max against a "
                       "certified reference run, ...)");
  command_->add_option("--plot", f.plot, "write a PNG (gnuplot): x, s, y against t and the phase portrait");
  f.plant_substeps_opt = command_->add_option(
      "--plant-substeps", f.plant_substeps,
      "methods zoh/zoh-explicit: S >= 1; --out and --plot also get the exact plant state at S-1 points between "
      "samples under the held input (default: the scene's plant_substeps, else 1; metrics stay on the samples)");
  command_->add_option("--record", f.record,
                       "write every one-step box-MLCP of the run (M, q, l, u, the z used, scene, method, h, theta, "
                       "step) to FILE, a problem set (problems/library/README.md; see `smcbench library FILE`)");
}

SimulateCommand::~SimulateCommand() = default;

bool SimulateCommand::parsed() const { return command_->parsed(); }

namespace {

using Flags = SimulateCommand::Flags;

// What one `simulate` run is: the scene, its defaults with the command line's overrides, and how errors read.
struct SimulatePlan {
  std::unique_ptr<Scene> scene;
  SimulationSettings settings;
  double reach_tol = 0.0;
  bool nonlinear = false;
  std::string backend;  // empty for explicit methods
  std::string prefix;   // "simulate NAME: " before every error

  [[noreturn]] void Fail(const std::string& what) const { throw InvalidInputError(prefix + what); }
};

// Phase 1: the scene, by name or file.
SimulatePlan LoadPlan(const Flags& f) {
  SimulatePlan plan;
  plan.scene = LoadScene(f.scene);
  plan.prefix = "simulate " + plan.scene->info().name + ": ";
  plan.settings = plan.scene->defaults();
  return plan;
}

// The flags as overrides: those given on the command line, and the stepper's options always (their defaults are
// the command's).
SceneOverrides OverridesOf(const Flags& f, const SimulatePlan& plan) {
  SceneOverrides o;
  if (f.method_opt->count()) o.method = f.method;
  if (f.h_opt->count()) o.h = f.h;
  if (f.T_opt->count()) o.T = f.T;
  if (f.theta_opt->count()) o.theta = f.theta;
  if (f.gamma_opt->count()) o.gamma = f.gamma;
  if (f.x0_opt->count()) o.x0 = ParseVector(f.x0, "--x0");
  for (const std::string& p : f.params) {
    const auto eq = p.find('=');
    const auto value = eq == std::string::npos ? std::nullopt : ParseDouble(std::string_view(p).substr(eq + 1));
    if (!value) plan.Fail("--param expects NAME=VALUE with a number, got '" + p + "'");
    o.parameters.emplace_back(p.substr(0, eq), *value);
  }
  if (f.solver_opt->count()) o.solver = f.solver;
  if (f.algorithm_opt->count()) o.algorithm = f.algorithm;
  if (f.newton_tol_opt->count()) o.newton_tolerance = f.newton_tol;
  if (f.newton_max_iter_opt->count()) o.newton_max_iterations = f.newton_max_iter;
  o.tolerance = f.tol;
  o.max_iterations = f.max_iter;
  o.warm_start = !f.no_warm_start;
  o.polish = !f.no_polish;
  if (f.flush_subnormals && f.ieee_subnormals) plan.Fail("--flush-subnormals and --ieee-subnormals exclude each other");
  o.subnormals = f.flush_subnormals  ? SubnormalPolicy::kFlushToZero
                 : f.ieee_subnormals ? SubnormalPolicy::kIeee
                                     : SubnormalPolicy::kZeroState;
  o.on_failure = f.on_failure;
  if (f.plant_substeps_opt->count()) o.plant_substeps = f.plant_substeps;
  if (f.reach_opt->count()) o.reach_tolerance = f.reach_tol;
  return o;
}

// Phase 2: every command-line override on the scene's defaults (problems/scenes/scene_overrides.h: the rules
// Python's smcbench.simulate shares), notes on err.
void ApplyOverrides(const Flags& f, SimulatePlan* plan, std::ostream& err) {
  SceneRunSettings run;
  try {
    run = ApplySceneOverrides(*plan->scene, OverridesOf(f, *plan), OverrideSpelling::kCommandLine);
  } catch (const InvalidInputError& e) {
    plan->Fail(e.what());
  }
  for (const std::string& note : run.notes) err << "note: " << note << "\n";
  plan->settings = std::move(run.settings);
  // Outputs are computed while the run goes (sinks): nothing is recorded.
  plan->settings.stepper.record = false;
  plan->reach_tol = run.reach_tolerance;
  plan->nonlinear = run.nonlinear;
  plan->backend = run.backend;
}

struct Backend {
  std::unique_ptr<Solver> solver;  // null for explicit methods (no one-step problem)
  std::string name;
};

// Phase 3: the backend, for implicit methods only, with its --set options.
Backend PickBackend(const Flags& f, const SimulatePlan& plan) {
  Backend backend;
  if (plan.backend.empty()) return backend;
  backend.name = plan.backend;
  backend.solver = CreateSolver(backend.name);  // unknown name: error listing the known ones
  SceneRunSettings run;
  run.settings = plan.settings;
  run.nonlinear = plan.nonlinear;
  run.backend = plan.backend;
  try {
    CheckSceneBackend(run, *backend.solver, OverrideSpelling::kCommandLine);
    ApplyBackendSettings(f.sets, {backend.solver.get()});  // the one --set parser: solvers/registry/backend_settings.h
  } catch (const InvalidInputError& e) {
    plan.Fail(e.what());
  }
  return backend;
}

// Everything the run writes or measures besides its counters, each fed while the run goes (bounded memory whatever
// the number of steps). Built in place (the sinks point at the members): never moved.
struct SimulateOutputs {
  // --record: each one-step problem, streamed to the file.
  std::unique_ptr<ProblemSetWriter> record_writer;
  std::unique_ptr<ProblemRecorder> recorder;
  // The run's rows (the controller's samples) go to `sinks`; the CSV and the plot get them through `plant` (the
  // states between samples inserted) when plant_substeps > 1, else directly.
  TrajectorySinks sinks;
  TrajectorySinks trajectory;
  std::unique_ptr<SampledPlantSink> plant;
  std::unique_ptr<TrajectoryCsvWriter> csv;
  std::optional<TrajectoryPlotData> plot_data;
  std::optional<MetricsAccumulator> metrics;
  std::optional<ChatteringAccumulator> chattering;
  std::optional<ErrorsAccumulator> exact_errors;
  std::optional<SuperTwistingPrecisionAccumulator> super_twisting;  // super-twisting scenes
  std::string exact_unavailable;
  std::unique_ptr<RunRowsForReference> run_rows;
  std::string no_run_rows;

  bool writes_files = false;  // --out, --summary or --plot: the run feeds them as it goes ("recording")
};

// --record: the run hands each one-step problem to a recorder that streams it to the file.
void SetUpRecorder(const Flags& f, SimulatePlan* plan, const std::string& solver_name, SimulateOutputs* outputs) {
  if (f.record.empty()) return;
  SimulationSettings& s = plan->settings;
  if (!IsImplicit(s.method)) {
    plan->Fail("--record: method '" + std::string(ToString(s.method)) + "' solves no one-step problem: nothing to record");
  }
  if (plan->scene->step_kind() == SceneStepKind::kSuperTwisting) {
    plan->Fail("--record captures box-MLCPs; a super-twisting step is a scalar generalized equation (closed form "
               "or MCP): there is nothing to record");
  }
  if (plan->nonlinear && s.algorithm == NonlinearAlgorithm::kMcp) {
    plan->Fail("--record captures box-MLCPs, but --algorithm mcp solves each step as a nonlinear MCP; use --algorithm "
               "newton-mlcp (its inner problems are box-MLCPs)");
  }
  // The recorder's ids are distinct by construction: the writer need not remember them (constant memory).
  ProblemSetWriterOptions writer_options;
  writer_options.id_check = IdCheck::kGuaranteedByCaller;
  outputs->record_writer = std::make_unique<ProblemSetWriter>(
      f.record, "capture",
      "one-step problems of smcbench simulate " + plan->scene->info().name + " (" + std::string(ToString(s.method)) +
          ", h = " + NumberText(s.h) + ", backend " + solver_name + ")",
      writer_options);
  outputs->recorder = std::make_unique<ProblemRecorder>(MakeCaptureContext("capture", *plan->scene, s, solver_name),
                                                        outputs->record_writer.get());
  s.stepper.observer = outputs->recorder.get();
}

// The ZOH plant of a linear scene with the run's parameters (plant_substeps > 1 needs it).
ZohSmcSystem PlantOf(const SimulatePlan& plan) {
  try {
    return ZohPlantOf(*plan.scene, plan.settings.parameters);
  } catch (const InvalidInputError& e) {
    plan.Fail(e.what());
  }
}

// --out and --plot: the trajectory as users read it, the plant between samples included when asked for.
void SetUpTrajectoryOutputs(const Flags& f, const SimulatePlan& plan, std::int64_t num_steps, SimulateOutputs* o) {
  const SceneInfo& info = plan.scene->info();
  if (!f.out.empty()) {
    try {
      o->csv = std::make_unique<TrajectoryCsvWriter>(f.out);
    } catch (const InvalidInputError& e) {
      plan.Fail(std::string("--out: ") + e.what());
    }
    o->trajectory.Add(o->csv.get());
  }
  const int substeps = plan.settings.plant_substeps;
  if (!f.plot.empty()) {
    o->plot_data.emplace(info.n, info.m, num_steps * substeps + 1);
    o->trajectory.Add(&*o->plot_data);
  }
  if (o->trajectory.empty()) return;
  if (substeps > 1) {
    o->plant = std::make_unique<SampledPlantSink>(PlantOf(plan), plan.settings.h, substeps, &o->trajectory);
    o->sinks.Add(o->plant.get());
  } else {
    o->sinks.Add(&o->trajectory);
  }
}

// Phase 4: every output as a sink on the run's rows.
void SetUpOutputs(const Flags& f, SimulatePlan* plan, std::int64_t num_steps, SimulateOutputs* o) {
  const SceneInfo& info = plan->scene->info();
  const SimulationSettings& s = plan->settings;
  SetUpTrajectoryOutputs(f, *plan, num_steps, o);
  o->writes_files = !f.out.empty() || !f.summary.empty() || !f.plot.empty();
  // Always (O(m) memory): the outcome on stdout names the reaching step and the chattering even without a file.
  o->metrics.emplace(info.m, plan->reach_tol);
  o->sinks.Add(&*o->metrics);
  o->chattering.emplace(info.m, plan->reach_tol);
  o->sinks.Add(&*o->chattering);
  if (const std::optional<double> band = plan->scene->convergence_band()) {
    o->super_twisting.emplace(*band, num_steps, s.h);
    o->sinks.Add(&*o->super_twisting);
  }
  if (!f.summary.empty()) {
    try {
      if (auto exact = plan->scene->Exact(s)) {
        o->exact_errors.emplace(info.n, info.m, s.h, std::move(*exact));
        o->sinks.Add(&*o->exact_errors);
      }
    } catch (const InvalidInputError& e) {
      o->exact_unavailable = e.what();
    }
    // With --summary: the run's error in s and y against a certified reference run (a second run, made only up
    // to kMaxReferenceSteps steps), compared against the run's rows kept in a temporary file.
    if (ReferenceRunSkipReason(s, info.m, num_steps).empty()) {
      try {
        o->run_rows = std::make_unique<RunRowsForReference>(info.m);
        o->sinks.Add(o->run_rows.get());
      } catch (const InvalidInputError& e) {
        o->no_run_rows = e.what();  // no temporary file: the summary says so instead of the errors
      }
    }
  }
  plan->settings.stepper.sink = o->sinks.empty() ? nullptr : &o->sinks;
}

// Phase 5: the run, timed (set-up included); no half-written CSV is left under --out when it throws.
double RunTimed(const Flags& f, const SimulatePlan& plan, const Backend& backend, SimulateOutputs* o, Trajectory* tr) {
  const auto start = std::chrono::steady_clock::now();
  try {
    plan.scene->Run(plan.settings, backend.solver.get(), tr);
  } catch (const InvalidInputError& e) {
    if (o->csv) {
      o->csv.reset();
      std::error_code ec;
      fs::remove(f.out, ec);
    }
    plan.Fail(e.what());
  }
  if (o->plant) o->plant->Finish();  // the run's last row, held back by the plant sink
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o->record_writer) o->record_writer->Close();
  if (o->csv) o->csv->Close();
  return wall;
}

// Phase 6: the summary and the figure.
std::optional<ReferenceComparison> WriteSummaryAndPlot(const Flags& f, const SimulatePlan& plan,
                                                       const std::string& solver_name, const Trajectory& tr,
                                                       double wall, SimulateOutputs* o) {
  std::optional<ReferenceComparison> reference;
  if (!f.summary.empty()) {
    reference = CompareWithReferenceRun(*plan.scene, plan.settings, tr, o->run_rows.get());
    if (!o->no_run_rows.empty()) reference->skipped = o->no_run_rows;
    RunMetrics run_metrics;
    run_metrics.metrics = o->metrics->Result(tr);
    if (o->exact_errors) run_metrics.exact_errors = o->exact_errors->Result();
    run_metrics.exact_unavailable = o->exact_unavailable;
    run_metrics.chattering = o->chattering->Result();
    if (o->super_twisting) run_metrics.super_twisting = o->super_twisting->Result();
    const json summary =
        SimulationSummary(*plan.scene, plan.settings, solver_name, tr, run_metrics, plan.reach_tol, wall, &*reference);
    std::ofstream js(f.summary);
    js << summary.dump(2) << "\n";
    if (!js) plan.Fail("cannot write the summary '" + f.summary + "'");
  }
  if (o->plot_data) {
    std::string title = plan.scene->info().name + ": " + tr.description + ", h = " + NumberText(plan.settings.h);
    if (!solver_name.empty()) title += ", " + solver_name;
    PlotTrajectory(*o->plot_data, title, f.plot);
  }
  return reference;
}

// The surfaces and the input after reaching, from the metrics gathered during the run.
void ReportMetrics(const SimulateOutputs& o, double reach_tol, const Trajectory& tr, std::ostream& out) {
  const TrajectoryMetrics result = o.metrics->Result(tr);
  if (result.reaching_step >= 0) {
    double max_y = 0.0;
    std::int64_t changes = 0;
    for (const auto& sm : result.surfaces) {
      max_y = std::max(max_y, sm.max_abs_y_after);
      changes += sm.sign_changes_after;
    }
    out << "  surfaces reached at step " << result.reaching_step << " (t = " << NumberText(tr.time(result.reaching_step))
        << "; |y| <= " << NumberText(reach_tol) << " at every later step): max |y| after " << NumberText(max_y)
        << ", sign changes of s after " << changes << "\n";
  } else {
    out << "  not every surface is reached (|y| <= " << NumberText(reach_tol) << " to the end)\n";
  }
  const ChatteringMetrics& c = o.chattering->Result();
  if (c.from_step >= 0) {
    // The classical reaching time, which a chattering run also has: it can come before the step above.
    out << "  from the first arrival t = " << NumberText(tr.time(c.from_step))
        << " (every surface touched or crossed once): sigma band "
        << NumberText(c.sigma_band);
    if (c.has_input) {
      out << ", input total variation " << NumberText(c.u_total_variation) << ", max jump "
          << NumberText(c.u_max_jump) << ", max |u| " << NumberText(c.u_max_abs);
    }
    out << ", sign changes of the switching part " << c.switching_sign_changes << "\n";
  }
  if (o.super_twisting) {
    const SuperTwistingPrecision p = o.super_twisting->Result();
    out << "  super-twisting: |sigma| <= " << NumberText(p.band) << " from "
        << (p.convergence_step >= 0 ? "t = " + NumberText(tr.time(p.convergence_step)) : std::string("never"))
        << "; from t = " << NumberText(tr.time(p.tail_from)) << ": max |sigma| " << NumberText(p.max_abs_sigma_tail)
        << ", max |sigma'| " << NumberText(p.max_abs_sigma_dot_tail) << "\n";
  }
}

// Phase 7: a short report on out (the files hold the details) and the first failure on err.
void Report(const Flags& f, const SimulatePlan& plan, const std::string& solver_name, const Trajectory& tr,
            double wall, const SimulateOutputs& o, const std::optional<ReferenceComparison>& reference,
            std::ostream& out, std::ostream& err) {
  const SimulationSettings& s = plan.settings;
  out << plan.scene->info().name << ": " << ToString(s.method) << " (" << tr.description
      << "), h = " << NumberText(s.h) << ", T = " << NumberText(s.T) << ", " << tr.steps_taken << " of "
      << tr.num_steps << " steps" << (solver_name.empty() ? "" : ", backend " + solver_name) << "\n";
  out << "  x_final = " << VectorText(tr.x_final) << ", s_final = " << VectorText(tr.s_final) << "\n";
  ReportMetrics(o, plan.reach_tol, tr, out);
  if (IsImplicit(s.method)) {
    out << "  max one-step residual " << NumberText(tr.max_residual) << ", " << tr.total_iterations
        << " backend iterations, " << tr.failed_steps << " failed steps\n";
  }
  if (o.plant) {
    out << "  plant between samples: " << o.plant->substeps() - 1 << " point(s) per interval in the trajectory ("
        << o.plant->RowsFor(tr.steps_taken) << " rows)\n";
  }
  // One cold run, set-up (discretization, factorization) included: `stepper_benchmark` measures the loop itself.
  out << "  wall " << FormatSeconds(wall) << " for set-up + " << tr.steps_taken << " steps ("
      << FormatRate(wall > 0 ? tr.steps_taken / wall : 0.0) << "steps/s" << (o.writes_files ? ", recording" : "")
      << ")\n";
  if (o.record_writer) {
    const std::uint64_t matrices = o.record_writer->matrices_written();
    out << "  recorded " << o.record_writer->problems_written() << " one-step problem(s), " << matrices
        << " distinct matri" << (matrices == 1 ? "x" : "ces") << ", to " << f.record << "\n";
  }
  if (reference) {
    if (reference->errors) {
      out << "  against the certified reference run (the same scene, h, method and x0 stepped with the backend "
             "'reference', each step's problem solved and verified in extended precision; "
          << FormatSeconds(reference->wall_seconds) << "): max |s - s_ref| " << NumberText(reference->errors->s_error_max) << ", max |y - y_ref| "
          << NumberText(reference->errors->y_error_max) << " over " << reference->errors->steps_compared
          << " steps\n";
    } else {
      out << "  no reference run: " << reference->skipped << "\n";
    }
  }
  if (tr.first_failed_step >= 0) {
    err << (tr.stopped_early ? "error: step " : "warning: step ") << tr.first_failed_step << ": " << ToString(tr.first_failure_status) << " (residual "
        << NumberText(tr.first_failure_residual) << ")" << (tr.first_failure_message.empty() ? "" : ": ")
        << tr.first_failure_message
        << (tr.stopped_early ? "; the run stopped there (" + std::to_string(tr.steps_taken) + " of " +
                                   std::to_string(tr.num_steps) + " steps; exit status " +
                                   std::to_string(kStoppedEarlyExitStatus) + ")"
                             : "")
        << "\n";
  }
}

}  // namespace

// Named phases, top to bottom: load the scene, apply the overrides, pick the backend, set up the outputs, run,
// write the outputs, report.
int SimulateCommand::Run(std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  // Fail before simulating, not after: every output path, then gnuplot.
  if (!f.out.empty()) CheckOutputFile("--out", f.out);
  if (!f.summary.empty()) CheckOutputFile("--summary", f.summary);
  if (!f.plot.empty()) CheckOutputFile("--plot", f.plot);
  if (!f.record.empty()) CheckOutputFile("--record", f.record);
  if (!f.plot.empty() && !GnuplotAvailable()) {
    throw InvalidInputError("--plot needs gnuplot (Debian package gnuplot-nox), which is not on PATH");
  }
  SimulatePlan plan = LoadPlan(f);
  ApplyOverrides(f, &plan, err);
  const Backend backend = PickBackend(f, plan);
  SimulateOutputs outputs;
  SetUpRecorder(f, &plan, backend.name, &outputs);
  const std::int64_t num_steps = NumSteps(plan.settings.T, plan.settings.h);
  SetUpOutputs(f, &plan, num_steps, &outputs);
  Trajectory tr;
  const double wall = RunTimed(f, plan, backend, &outputs, &tr);
  const std::optional<ReferenceComparison> reference =
      WriteSummaryAndPlot(f, plan, backend.name, tr, wall, &outputs);
  Report(f, plan, backend.name, tr, wall, outputs, reference, out, err);
  // The outputs hold the steps taken; the status says the run did not reach T.
  return tr.stopped_early ? kStoppedEarlyExitStatus : 0;
}

// ------------------------------------------------------------------------------------------------------------
// scenes

ScenesCommand::ScenesCommand(CLI::App* app) {
  command_ = app->add_subcommand("scenes", "list the registered scenes (docs/scenes.md) with one-line descriptions");
}

bool ScenesCommand::parsed() const { return command_->parsed(); }

int ScenesCommand::Run(std::ostream& out, std::ostream& err) const {
  int status = 0;
  std::size_t width = 0;
  for (auto name : SceneNames()) width = std::max(width, name.size());
  for (auto name : SceneNames()) {
    out << name << std::string(width + 2 - name.size(), ' ');
    try {
      const auto scene = LoadScene(name);
      const SceneInfo& info = scene->info();
      const SimulationSettings& d = scene->defaults();
      out << info.description << "  [n=" << info.n << " m=" << info.m << "; " << ToString(d.method)
          << " h=" << NumberText(d.h) << " T=" << NumberText(d.T) << "]\n";
    } catch (const InvalidInputError& e) {
      out << "(cannot load)\n";
      err << "smcbench: scene " << name << ": " << e.what() << "\n";
      status = 1;
    }
  }
  return status;
}

}  // namespace smcbench
