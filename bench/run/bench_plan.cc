#include "bench/run/bench_plan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <nlohmann/json.hpp>

#include "bench/replay/mcp_replay.h"
#include "bench/replay/replay.h"
#include "bench/run/warm_sequences.h"
#include "problems/library/problem_set_io.h"
#include "problems/library/references.h"
#include "problems/avi_library/avi_suite.h"
#include "problems/mcp/mcp_suite.h"
#include "solvers/core/glob_match.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Keeps the items of a list whose id the filter keeps, in order: the one place a run's problems are selected, for
// every kind of suite (box problems, MCP ids, AVIs, warm sequences).
template <typename Item, typename IdOf>
void KeepSelected(std::vector<Item>* items, IdOf id_of, ProblemFilter* filter) {
  const auto dropped = [&](const Item& item) { return !filter->Keeps(id_of(item)); };
  items->erase(std::remove_if(items->begin(), items->end(), dropped), items->end());
}

const std::string& IdOf(const std::string& id) { return id; }
const std::string& IdOf(const LibraryProblem& p) { return p.id; }
const std::string& IdOf(const AviLibraryProblem& p) { return p.id; }
const std::string& IdOf(const WarmSequence& w) { return w.id; }

template <typename Item>
void KeepSelected(std::vector<Item>* items, ProblemFilter* filter) {
  KeepSelected(items, [](const Item& item) -> const std::string& { return IdOf(item); }, filter);
}

bool IsMcpSuiteName(const std::string& name) { return name == "mcp"; }
bool IsAviSuiteName(const std::string& name) { return name == kAviSuiteName; }

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

// A suite's problems, built (captured suites certify while capturing), validated and (with certify) given their
// certified references, with one line for the log: size, time taken and certificates.
// The problems filter rejects are dropped before the references are computed; a suite left with none is returned
// empty (no line), for the caller to leave out. first_id: the suite's first problem, filtered or not (the no-match
// error's example).
ProblemSet BuildBoxSuite(const std::string& name, const BenchRequest& request, ProblemFilter* filter,
                         std::string* first_id, std::string* line) {
  SuiteRequest suite_request;
  suite_request.siconos_dir = request.siconos_dir;
  suite_request.quick = request.quick;
  suite_request.references = false;  // attached below, timed
  const auto build_start = Clock::now();
  ProblemSet set = BuildSuite(name, suite_request);
  if (set.problems.empty()) throw InvalidInputError("bench: suite '" + name + "' holds no problem");
  *first_id = set.problems.front().id;
  KeepSelected(&set.problems, filter);
  if (set.problems.empty()) return set;
  set.Validate();
  if (!request.certify) return set;
  const auto references_start = Clock::now();
  AttachReferences(&set);
  const double references_seconds = SecondsSince(references_start);
  std::map<Certificate, int> certificates;
  int proved = 0;
  for (const LibraryProblem& p : set.problems) {
    ++certificates[p.reference.certificate];
    proved += std::isnan(p.reference.proved_radius) ? 0 : 1;
  }
  std::string certified;
  for (const auto& [certificate, count] : certificates) {
    certified += (certified.empty() ? "" : ", ") + std::to_string(count) + " " + std::string(ToString(certificate));
  }
  certified += "; " + std::to_string(proved) + " proved by an interval enclosure";
  char seconds[96];
  std::snprintf(seconds, sizeof seconds, "built in %.2f s; certified references in %.2f s",
                std::chrono::duration<double>(references_start - build_start).count(), references_seconds);
  *line = "suite " + set.name + " (" + std::to_string(set.problems.size()) + " problems, " + seconds + ": " +
          certified + ")";
  return set;
}

// The MCP suite of these ids (references attached by the suite itself, to them only), validated, with one line
// for the log.
McpProblemSet BuildMcpBenchSuite(bool quick, const std::vector<std::string>& ids, std::string* line) {
  const auto build_start = Clock::now();
  McpProblemSet set = BuildMcpSuite(quick, ids);
  set.Validate();
  std::size_t instances = 0;
  std::map<std::string, int> certificates;
  for (const McpLibraryProblem& p : set.problems) {
    instances += p.starts.size();
    for (const ReferenceSolution& r : p.references) ++certificates[std::string(ToString(r.certificate))];
    if (p.references.empty()) ++certificates["no reference"];
  }
  std::string certified;
  for (const auto& [certificate, count] : certificates) {
    certified += (certified.empty() ? "" : ", ") + std::to_string(count) + " " + certificate;
  }
  char seconds[64];
  std::snprintf(seconds, sizeof seconds, "built in %.2f s", SecondsSince(build_start));
  *line = "suite " + set.name + " (" + std::to_string(set.problems.size()) + " MCPs, " + std::to_string(instances) +
          " problem x start, " + seconds + "; references: " + certified + ")";
  return set;
}

// The AVI suite (references attached by the suite itself), validated, with one line for the log.
AviProblemSet BuildAviBenchSuite(bool quick, std::string* line) {
  const auto build_start = Clock::now();
  AviProblemSet set = BuildAviSuite(quick);
  std::map<std::string, int> certificates;
  for (const AviLibraryProblem& p : set.problems) {
    const auto it = p.metadata.find("certificate");
    ++certificates[it == p.metadata.end() ? "none" : it->second];
  }
  std::string certified;
  for (const auto& [certificate, count] : certificates) {
    certified += (certified.empty() ? "" : ", ") + std::to_string(count) + " " + certificate;
  }
  char seconds[64];
  std::snprintf(seconds, sizeof seconds, "built and certified in %.2f s", SecondsSince(build_start));
  *line = "suite " + set.name + " (" + std::to_string(set.problems.size()) + " AVIs, " + seconds + "; references: " +
          certified + ")";
  return set;
}

// A file whose header says it holds a set of AVIs (false for anything else: the box reader then judges it).
bool IsAviSetFile(const std::string& name) {
  std::error_code ec;
  if (!fs::is_regular_file(name, ec)) return false;
  try {
    return ReadProblemSetKind(name) == ProblemSetKind::kAvi;
  } catch (const InvalidInputError&) {
    return false;
  }
}

// A set of AVIs frozen to a file (`smcbench library --write-suite avi FILE.smcps`), with its references as written.
AviProblemSet ReadAviBenchSuite(const std::string& path, std::string* line) {
  AviProblemSet set = ReadAviProblemSetFile(path);
  set.Validate();
  *line = "suite " + set.name + " (" + std::to_string(set.problems.size()) + " AVIs, read from " + path + ")";
  return set;
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

ProblemFilter::ProblemFilter(std::vector<std::string> globs_in)
    : globs(std::move(globs_in)), matched(globs.size(), 0) {}

bool ProblemFilter::Keeps(std::string_view id) {
  if (globs.empty()) return true;
  bool keep = false;
  for (std::size_t g = 0; g < globs.size(); ++g) {
    if (GlobMatch(globs[g], id)) keep = true, matched[g] = 1;  // every glob asked: each learns that it matched
  }
  return keep;
}

std::vector<std::string> ProblemFilter::Unmatched() const {
  std::vector<std::string> out;
  for (std::size_t g = 0; g < globs.size(); ++g) {
    if (!matched[g]) out.push_back(globs[g]);
  }
  return out;
}

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
  for (const std::string& name : ResolveSuiteNames(request.suites)) {
    const bool known =
        std::find(std::begin(kBenchSuiteNames), std::end(kBenchSuiteNames), name) != std::end(kBenchSuiteNames);
    std::error_code ec;
    if (!known && !fs::is_regular_file(name, ec)) {
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

  // Every suite's problems through the one filter (ProblemFilter); a suite with no problem left is left out of the
  // run (and of suite_names), said in the log.
  ProblemFilter filter(request.problems);
  std::vector<std::string> kept_suite_names, first_ids;
  for (const std::string& name : plan.suite_names) {
    std::string line, first_id;
    bool kept = true;
    if (IsMcpSuiteName(name)) {
      std::vector<std::string> ids = McpSuiteIds(request.quick);
      first_id = ids.empty() ? "" : ids.front();
      KeepSelected(&ids, &filter);
      kept = !ids.empty();
      if (kept) plan.mcp_suites.push_back(BuildMcpBenchSuite(request.quick, ids, &line));
    } else if (IsAviSuiteName(name) || IsAviSetFile(name)) {
      // The AVI suite is built whole (its certificates are cheap), then filtered.
      AviProblemSet set =
          IsAviSuiteName(name) ? BuildAviBenchSuite(request.quick, &line) : ReadAviBenchSuite(name, &line);
      first_id = set.problems.empty() ? "" : set.problems.front().id;
      const std::size_t built = set.problems.size();
      KeepSelected(&set.problems, &filter);
      kept = !set.problems.empty();
      if (kept && set.problems.size() < built) {
        line += "; " + std::to_string(set.problems.size()) + " of them selected by --problem";
      }
      if (kept) plan.avi_suites.push_back(std::move(set));
    } else {
      ProblemSet set = BuildBoxSuite(name, request, &filter, &first_id, &line);
      kept = !set.problems.empty();
      if (kept) plan.suites.push_back(std::move(set));
    }
    if (!first_id.empty()) first_ids.push_back(first_id);
    if (kept) kept_suite_names.push_back(name);
    if (!kept) {
      line = "suite " + name + ": no problem matches --problem " + QuotedList(request.problems) + ", left out";
    }
    if (log && !line.empty()) log(line);
  }
  const std::vector<std::string> all_suite_names = plan.suite_names;
  plan.suite_names = kept_suite_names;
  JobListRequest jobs;
  // The box suites' backends: every chosen one that solves box-MLCPs (an MCP-only adapter would only add rows of
  // not_applicable to every box table).
  for (const std::string& name : plan.solvers) {
    if (CreateSolver(name)->info().box) jobs.solvers.push_back(name);
  }
  jobs.generic_sparse_path = request.solvers.empty() ||
                             std::find(request.solvers.begin(), request.solvers.end(), "newton") != request.solvers.end();
  if (request.warm) {
    std::size_t box = 0;
    for (const std::string& name : plan.suite_names) {
      if (IsMcpSuiteName(name) || IsAviSuiteName(name) || IsAviSetFile(name)) continue;
      const ProblemSet& set = plan.suites[box++];
      const bool is_file =
          std::find(std::begin(kBenchSuiteNames), std::end(kBenchSuiteNames), name) == std::end(kBenchSuiteNames);
      const auto warm_start = Clock::now();
      // Listed uncertified, filtered by their ids, then the kept ones certified: a filtered run pays for its own.
      std::vector<WarmSequence> sequences =
          WarmSequencesForSuite(set, WarmSuiteKindOf(name, is_file), request.quick, /*certify=*/false);
      KeepSelected(&sequences, &filter);
      if (request.certify) {
        for (WarmSequence& sequence : sequences) CertifyWarmSequence(&sequence);
      }
      plan.warm_sequences.push_back(std::move(sequences));
      if (log && !plan.warm_sequences.back().empty()) {
        std::size_t steps = 0;
        for (const WarmSequence& w : plan.warm_sequences.back()) steps += w.steps.size();
        char line[200];
        std::snprintf(line, sizeof line, "warm track of suite %s: %zu sequences, %zu steps (built and certified in "
                      "%.2f s)", set.name.c_str(), plan.warm_sequences.back().size(), steps, SecondsSince(warm_start));
        log(line);
      }
    }
    jobs.warm = &plan.warm_sequences;
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
  if (!plan.mcp_suites.empty()) {
    jobs.mcp_solvers = BackendsWith(plan.solvers, &SolverInfo::mcp);
    if (jobs.mcp_solvers.empty() && log) {
      log("no chosen backend solves MCPs (`smcbench list` says: accepts nonlinear MCP): the MCP suite is not run");
    }
  }
  if (!plan.avi_suites.empty()) {
    jobs.avi_solvers = BackendsWith(plan.solvers, &SolverInfo::box);
    if (jobs.avi_solvers.empty() && log) {
      log("no chosen backend solves box-MLCPs (`smcbench list`): the AVI suite, solved through its reduction to a "
          "box-MLCP, is not run");
    }
  }
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
  plan.jobs = ListBenchJobs(plan.suites, plan.mcp_suites, plan.avi_suites, options, jobs);
  return plan;
}

std::vector<SuiteResults> PlanSuites(const BenchPlan& plan) {
  std::vector<SuiteResults> out;
  for (const ProblemSet& set : plan.suites) {
    SuiteResults suite;
    suite.suite = set.name;
    suite.description = set.description;
    suite.problems = static_cast<int>(set.problems.size());
    suite.checksum = ProblemSetContentChecksum(set);
    out.push_back(std::move(suite));
  }
  for (const McpProblemSet& set : plan.mcp_suites) {
    SuiteResults suite;
    suite.suite = set.name;
    suite.description = set.description;
    suite.problems = static_cast<int>(set.problems.size());
    suite.checksum = McpProblemSetChecksum(set);
    out.push_back(std::move(suite));
  }
  for (const AviProblemSet& set : plan.avi_suites) {
    SuiteResults suite;
    suite.suite = set.name;
    suite.description = set.description;
    suite.problems = static_cast<int>(set.problems.size());
    suite.checksum = AviProblemSetChecksum(set);
    out.push_back(std::move(suite));
  }
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
