#include "bench/run/bench_plan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <nlohmann/json.hpp>

#include "bench/kinds/box_kind.h"
#include "bench/kinds/builtin_kinds.h"
#include "bench/replay/replay.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The defaults filled in and "all" expanded, in the order given.
std::vector<std::string> ResolveSuiteNames(const std::vector<std::string>& named) {
  if (named.empty()) return {std::begin(kDefaultBenchSuites), std::end(kDefaultBenchSuites)};
  if (std::find(named.begin(), named.end(), "all") != named.end()) {
    return {std::begin(kAllBenchSuites), std::end(kAllBenchSuites)};
  }
  return named;
}

// The backends named (none: every registered one), each created once, so an unknown name fails here.
std::vector<std::string> ResolveSolverNames(const std::vector<std::string>& named) {
  std::vector<std::string> names = named;
  if (names.empty()) {
    for (auto n : SolverNames()) names.emplace_back(n);
  }
  for (const std::string& name : names) CreateSolver(name);  // InvalidInputError listing the known names
  return names;
}

// The kinds of a request (none given: the built-in ones).
ProblemKinds KindsOf(const BenchRequest& request) {
  return request.kinds.empty() ? BuiltinProblemKinds() : request.kinds;
}

// The position in kinds of the kind that builds the suite named (the first that Builds it), or kinds.size().
std::size_t KindOfSuite(const ProblemKinds& kinds, const std::string& name) {
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    if (kinds[k]->Builds(name)) return k;
  }
  return kinds.size();
}

// A dense m × m SPD LCP with a known interior-and-bound mix: M = I + (1/m)·11ᵀ, q alternating −1 and 1.
LibraryProblem ProbeProblem(int m) {
  DenseMatrix M = DenseMatrix::Identity(m, m) + DenseMatrix::Constant(m, m, 1.0 / m);
  Vector q(m);
  for (int i = 0; i < m; ++i) q[i] = i % 2 ? 1.0 : -1.0;
  LibraryProblem p = MakeLibraryProblem("probe/m" + std::to_string(m), "probe", BoxMLCP::LCP(M, q));
  p.expected = ExpectedOutcome::kSolvable;
  return p;
}

// A list for a message: 'a', 'b', 'c'.
std::string QuotedList(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "'" : ", '") + item + "'";
  return out;
}

}  // namespace

std::map<std::string, BackendCost> CalibrateBackendCosts(const ReplayOptions& options,
                                                         const std::vector<std::string>& solvers) {
  ProblemSet set;
  set.name = "probe";
  set.problems = {ProbeProblem(2), ProbeProblem(32)};
  const double units = 32.0 * (32.0 + 32.0 * 32.0);
  std::map<std::string, BackendCost> costs;
  for (const std::string& name : solvers) {
    try {
      ReplayOptions o = options;
      std::vector<std::string> names{name};
      o.settings = SettingsReaching(name, options.settings);
      const std::unique_ptr<Solver> solver = std::move(CreateReplaySolvers(o, &names).front());
      if (!solver->info().box) continue;
      // Twice: the first job of a backend also pays what a run pays once (an external adapter's worker started,
      // workspaces sized); the second is what every further job pays.
      ReplayOne(set, set.problems[0], solver.get(), name, o, "cold", o.tolerance);
      const auto tiny_start = Clock::now();
      const ReplayRecord tiny = ReplayOne(set, set.problems[0], solver.get(), name, o, "cold", o.tolerance);
      BackendCost cost;
      cost.job_seconds = SecondsSince(tiny_start);
      o.repetitions = 1;
      const ReplayRecord mid = ReplayOne(set, set.problems[1], solver.get(), name, o, "cold", o.tolerance);
      if (mid.samples > 0 && tiny.samples > 0) {
        cost.seconds_per_unit = std::max(mid.time_median - tiny.time_median, 1e-12 * units) / units;
      }
      costs[name] = cost;
    } catch (const std::exception&) {
      // keeps the defaults: the run itself reports what is wrong with this backend
    }
  }
  if (costs.count("newton")) costs[kGenericSparsePath] = costs.at("newton");
  return costs;
}

bool IncludesStepperStudy(const std::vector<std::string>& suite_names, StepperStudyChoice choice) {
  if (choice != StepperStudyChoice::kIfSceneSuite) return choice == StepperStudyChoice::kAlways;
  return std::find(suite_names.begin(), suite_names.end(), "paper") != suite_names.end();
}

void CheckBenchRequest(const BenchRequest& request) {
  const ProblemKinds kinds = KindsOf(request);
  for (const std::string& name : ResolveSuiteNames(request.suites)) {
    std::error_code ec;
    if (KindOfSuite(kinds, name) == kinds.size() && !fs::is_regular_file(name, ec)) {
      throw InvalidInputError("bench: unknown suite '" + name + "' (known: paper, families, hard, siconos, scale, "
                              "tiny, mcp, avi, all, or a problem-set file)");
    }
    if ((name == "siconos" || name == "hard") && !fs::is_directory(request.siconos_dir, ec)) {
      throw InvalidInputError("bench: suite " + name + " needs the Siconos collection: --siconos-dir '" +
                              request.siconos_dir + "' is not a folder");
    }
  }
  for (const std::string& glob : request.problems) {
    if (glob.empty()) throw InvalidInputError("bench: --problem needs a non-empty GLOB (a problem id pattern)");
  }
  const std::vector<std::string> solvers = ResolveSolverNames(request.solvers);
  try {
    CheckBackendSettings(request.settings, solvers);  // the one --set parser: solvers/registry/backend_settings.h
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(std::string("bench: ") + e.what());
  }
  const auto refuse = [](const char* field, double value, const char* must) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", value);
    throw InvalidInputError(std::string("bench: ") + field + " must be " + must + ", got " + text);
  };
  if (!(request.tolerance > 0.0) || !std::isfinite(request.tolerance)) {
    refuse("tolerance", request.tolerance, "a positive finite number");
  }
  if (!(request.time_limit_seconds > 0.0) || !std::isfinite(request.time_limit_seconds)) {
    refuse("time limit", request.time_limit_seconds, "a positive finite number of seconds");
  }
  if (request.repetitions < 1) refuse("repetitions", request.repetitions, "a whole number >= 1");
  if (!(request.backend_budget_seconds >= 0.0) || !std::isfinite(request.backend_budget_seconds)) {
    refuse("backend budget", request.backend_budget_seconds, "a finite number of seconds >= 0");
  }
  if (!(request.job_budget_seconds >= 0.0) || !std::isfinite(request.job_budget_seconds)) {
    refuse("job budget", request.job_budget_seconds, "a finite number of seconds >= 0");
  }
  if (!(request.sequence_budget_seconds >= 0.0) || !std::isfinite(request.sequence_budget_seconds)) {
    refuse("sequence budget", request.sequence_budget_seconds, "a finite number of seconds >= 0");
  }
}

BenchPlan MakeBenchPlan(const BenchRequest& request, const std::function<void(const std::string&)>& log) {
  CheckBenchRequest(request);
  BenchPlan plan;
  plan.request = request;
  plan.suite_names = ResolveSuiteNames(request.suites);
  plan.solvers = ResolveSolverNames(request.solvers);
  ReplayOptions& options = plan.options;
  options.solvers = plan.solvers;
  options.settings = request.settings;
  options.tolerance = request.tolerance;
  options.time_limit_seconds = request.time_limit_seconds;
  options.repetitions = request.quick ? std::min(request.repetitions, 3) : request.repetitions;
  if (request.quick) {
    options.max_seconds_per_pair = 0.2;
    options.tolerance_sweep_problems = 2;
  }
  options.polish = request.polish;
  CreateReplaySolvers(options, &plan.solvers);  // applies the settings once: a rejected value fails here

  // Every suite built by its kind, its problems through the one filter (ProblemFilter); a suite with no problem
  // left is left out of the run (and of suite_names), said in the log. The suites are then grouped by kind, in the
  // order of the kinds.
  const ProblemKinds kinds = KindsOf(request);
  SuiteBuildRequest build;
  build.siconos_dir = request.siconos_dir;
  build.quick = request.quick;
  build.certify = request.certify;
  build.warm = request.warm;
  build.solvers = request.solvers;
  ProblemFilter filter(request.problems);
  std::vector<std::string> kept_suite_names, first_ids;
  std::vector<std::pair<std::size_t, BuiltSuite>> built;  // kind, suite
  for (const std::string& name : plan.suite_names) {
    const std::size_t kind = KindOfSuite(kinds, name);
    if (kind == kinds.size()) throw InvalidInputError("bench: no problem kind builds suite '" + name + "'");
    BuiltSuite suite = kinds[kind]->Build(name, build, &filter);
    if (!suite.first_id.empty()) first_ids.push_back(suite.first_id);
    if (suite.suite) {
      kept_suite_names.push_back(name);
    } else {
      suite.line = "suite " + name + ": no problem matches --problem " + QuotedList(request.problems) + ", left out";
    }
    if (log && !suite.line.empty()) log(suite.line);
    if (suite.suite) built.emplace_back(kind, std::move(suite));
  }
  std::stable_sort(built.begin(), built.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const std::vector<std::string> all_suite_names = plan.suite_names;
  plan.suite_names = kept_suite_names;
  JobListRequest jobs;
  std::vector<char> kind_has_suites(kinds.size(), 0);
  for (auto& [kind, suite] : built) {
    plan.suites.push_back(suite.suite);
    kind_has_suites[kind] = 1;
    if (request.warm) plan.warm_sequences.push_back(std::move(suite.warm));
    if (log && !suite.warm_line.empty()) log(suite.warm_line);
  }
  if (request.warm) jobs.warm = &plan.warm_sequences;
  // The backends of each kind's jobs (ProblemKind::Backends); the warm jobs run on the box kind's.
  jobs.solvers = BoxProblemKind()->Backends(plan.solvers);
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    std::vector<std::string> backends = kinds[k]->Backends(plan.solvers);
    if (kind_has_suites[k] && backends.empty() && log && !kinds[k]->NoBackendsLine().empty()) {
      log(kinds[k]->NoBackendsLine());
    }
    jobs.kind_solvers[kinds[k]->name()] = std::move(backends);
  }
  if (const std::vector<std::string> unmatched = filter.Unmatched(); !unmatched.empty()) {
    std::string suites;
    for (const std::string& name : all_suite_names) suites += (suites.empty() ? "" : ", ") + name;
    throw InvalidInputError("bench: --problem " + QuotedList(unmatched) +
                            (unmatched.size() == 1 ? " matches" : " match") + " no problem of the suites " + suites +
                            " (ids look like " + QuotedList(first_ids) + "; '*' matches any characters, '/' "
                            "included)");
  }
  // The stepper studies run scenes, not problems: a run restricted to some problems runs them only when asked to.
  const StepperStudyChoice stepper = request.problems.empty() || request.stepper != StepperStudyChoice::kIfSceneSuite
                                         ? request.stepper
                                         : StepperStudyChoice::kNever;
  plan.stepper = IncludesStepperStudy(plan.suite_names, stepper);
  jobs.stepper = plan.stepper;
  jobs.floor = true;  // the report's floor: one factorization per problem (bench/replay/floor.h)
  jobs.budgets.job_seconds = request.job_budget_seconds;
  jobs.budgets.sequence_seconds = request.sequence_budget_seconds;
  jobs.budgets.backend_seconds = request.backend_budget_seconds;
  if (request.calibrate) {
    const auto calibrate_start = Clock::now();
    jobs.costs = CalibrateBackendCosts(options, plan.solvers);
    if (log) {
      char line[160];
      std::snprintf(line, sizeof line, "job costs of %zu backends measured in %.2f s (the estimates and the ETA)",
                    jobs.costs.size() - jobs.costs.count(kGenericSparsePath), SecondsSince(calibrate_start));
      log(line);
    }
  }
  plan.jobs = ListBenchJobs(plan.suites, options, jobs);
  return plan;
}

std::vector<SuiteResults> PlanSuites(const BenchPlan& plan) {
  std::vector<SuiteResults> out;
  for (const PlanSuite& suite : plan.suites) out.push_back(suite->Describe());
  return out;
}

nlohmann::json PlanOptionsJson(const BenchPlan& plan) {
  const ReplayOptions& o = plan.options;
  nlohmann::json options = {{"solvers", plan.solvers},
                            {"settings", plan.request.settings},
                            {"tolerance", o.tolerance},
                            {"time_limit", o.time_limit_seconds},
                            {"repetitions", o.repetitions},
                            {"max_seconds_per_pair", o.max_seconds_per_pair},
                            {"tolerance_sweep_problems", o.tolerance_sweep_problems},
                            {"polish", o.polish},
                            {"quick", plan.request.quick},
                            {"stepper", plan.stepper},
                            {"warm", plan.request.warm},
                            {"backend_budget", plan.request.backend_budget_seconds},
                            {"job_budget", plan.request.job_budget_seconds},
                            {"sequence_budget", plan.request.sequence_budget_seconds}};
  // Only when given: a run without a filter keeps the manifest earlier runs wrote (resumable, mergeable).
  if (!plan.request.problems.empty()) options["problems"] = plan.request.problems;
  return options;
}

BenchResults PlanResults(const BenchPlan& plan, const std::map<std::size_t, JobLine>& done) {
  RunManifest manifest;
  manifest.options = PlanOptionsJson(plan);
  manifest.suites = PlanSuites(plan);
  manifest.jobs = plan.jobs;
  return AssembleResults(manifest, done);
}

}  // namespace smcbench
