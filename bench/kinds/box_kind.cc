#include "bench/kinds/box_kind.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <map>
#include <mutex>

#include "bench/kinds/set_kind_suite.h"
#include "bench/replay/floor.h"
#include "bench/run/warm_sequences.h"
#include "problems/avi_library/avi_library.h"
#include "problems/library/problem_set_io.h"
#include "problems/library/references.h"
#include "problems/mcp/mcp_library.h"
#include "problems/suites/catalogue.h"
#include "solvers/core/solver.h"

namespace smcbench {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool IsBoxSuiteName(const std::string& name) {
  return std::find(std::begin(kBoxSuiteNames), std::end(kBoxSuiteNames), name) != std::end(kBoxSuiteNames);
}

// The generic path the report compares against: the same problems with M stored sparse, solved by the semismooth
// Newton backend through UMFPACK (what a general sparse complementarity code does), judged against the same
// certified solutions.
ProblemSet SparseCopy(const ProblemSet& set) {
  ProblemSet sparse;
  sparse.name = set.name;
  sparse.description = set.description;
  for (const LibraryProblem& p : set.problems) {
    const SparseMatrix S = p.problem.dense_matrix().sparseView();
    LibraryProblem copy = MakeLibraryProblem(p.id, p.source, BoxMLCP(S, p.problem.q(), p.problem.l(), p.problem.u()));
    copy.expected = p.expected;
    copy.reference = p.reference;
    sparse.problems.push_back(std::move(copy));
  }
  return sparse;
}

class BoxKindSuite final : public SetKindSuite<ProblemSet, ProblemSetContentChecksum> {
 public:
  BoxKindSuite(ProblemSet set, bool generic_sparse_path)
      : SetKindSuite(std::move(set)), generic_sparse_path_(generic_sparse_path && set_.name == "paper") {}

  std::string kind() const override { return "box"; }

  // Per suite: the cold jobs (problem, backend), the floor (problem), the generic sparse path (problem), the sweep
  // (SweepProblemIndices, backend, tolerance).
  std::vector<SuiteJob> Jobs(const std::vector<std::string>& backends, const ReplayOptions& options,
                             bool floor) const override {
    const std::vector<SuiteUnit> units = Units();
    std::vector<SuiteJob> jobs;
    for (const SuiteUnit& unit : units) {
      for (const std::string& solver : backends) jobs.push_back({JobKind::kCold, unit, solver, options.tolerance});
    }
    if (floor && !backends.empty()) {
      for (const SuiteUnit& unit : units) jobs.push_back({JobKind::kFloor, unit, kFloorSolver, options.tolerance});
    }
    if (generic_sparse_path_) {
      for (const SuiteUnit& unit : units) {
        jobs.push_back({JobKind::kCold, unit, kGenericSparsePath, options.tolerance});
      }
    }
    for (const std::size_t p : SweepProblemIndices(units.size(), options.tolerance_sweep_problems)) {
      for (const std::string& solver : backends) {
        for (const double tol : kSweepTolerances) jobs.push_back({JobKind::kSweep, units[p], solver, tol});
      }
    }
    return jobs;
  }

  std::string ColdJobName(const std::string& solver) const override {
    return solver == kGenericSparsePath ? "generic-sparse" : "cold";
  }

  double EstimateSeconds(const SuiteJob& job, const ReplayOptions& options, const BackendCost& cost,
                         const JobBudgets& budgets) const override {
    return EstimateJobSeconds(set_.problems.at(job.unit.problem), options, job.kind, cost, budgets);
  }

  ReplayRecord Replay(const BenchJob& job, Solver* solver, const ReplayOptions& options) const override {
    if (job.solver == kGenericSparsePath) {
      const ProblemSet& sparse = SparseSet();
      return ReplayOne(sparse, sparse.problems.at(job.problem), solver, job.solver, options, "cold", job.tolerance);
    }
    return ReplayOne(set_, set_.problems.at(job.problem), solver, job.solver, options,
                     job.kind == JobKind::kSweep ? "sweep" : "cold", job.tolerance);
  }

  ReplayRecord Floor(const BenchJob& job, const ReplayOptions& options) const override {
    return ReplayFloor(set_, set_.problems.at(job.problem), options);
  }

  ReplayRecord NotRun(const BenchJob& job, const std::string& message) const override {
    const LibraryProblem& p = set_.problems.at(job.problem);
    ReplayRecord r;
    r.suite = set_.name;
    r.problem = p.id;
    r.solver = job.solver;
    r.size = p.size();
    r.sparse = p.sparse() || job.solver == kGenericSparsePath;
    for (const auto& t : p.tags) r.tags += (r.tags.empty() ? "" : ",") + t;
    r.expected = p.expected;
    r.status = SolveStatus::kTimeLimit;
    r.message = message;
    r.verdict = Verdict::kFailed;  // not run is no answer, even on a problem with no solution
    r.residual_abs = r.residual_rel = r.residual_scaled = kInf;
    r.certificate = std::string(ToString(p.reference.certificate));
    r.tolerance = job.tolerance;
    return r;
  }

 private:
  // The sparse copy of the generic path, made the first time one of its jobs runs.
  const ProblemSet& SparseSet() const {
    std::call_once(sparse_made_, [this] { sparse_ = SparseCopy(set_); });
    return sparse_;
  }

  bool generic_sparse_path_;
  mutable std::once_flag sparse_made_;
  mutable ProblemSet sparse_;
};

class BoxKind final : public ProblemKind {
 public:
  std::string name() const override { return "box"; }

  bool Builds(const std::string& suite_name) const override {
    if (IsBoxSuiteName(suite_name)) return true;
    // The other kinds' built-in suites, never a file of this one (even beside a file of that name).
    if (suite_name == kMcpSuiteName || suite_name == kAviSuiteName) return false;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(suite_name, ec)) return false;
    try {
      return ReadProblemSetKind(suite_name) != ProblemSetKind::kAvi;
    } catch (const InvalidInputError&) {
      return true;  // the box reader says what is wrong with it
    }
  }

  // The suite's problems, built (captured suites certify while capturing), validated and (with certify) given their
  // certified references, with one line for the log: size, time taken and certificates. The problems the filter
  // rejects are dropped before the references are computed. Then its warm sequences (bench/run/warm_sequences.h):
  // listed uncertified, filtered by their ids, the kept ones certified.
  BuiltSuite Build(const std::string& suite_name, const SuiteBuildRequest& request,
                   ProblemFilter* filter) const override {
    BuiltSuite built;
    SuiteRequest suite_request;
    suite_request.siconos_dir = request.siconos_dir;
    suite_request.quick = request.quick;
    suite_request.references = false;  // attached below, timed
    const auto build_start = Clock::now();
    ProblemSet set = BuildSuite(suite_name, suite_request);
    if (set.problems.empty()) throw InvalidInputError("bench: suite '" + suite_name + "' holds no problem");
    built.first_id = set.problems.front().id;
    KeepSelected(&set.problems, [](const LibraryProblem& p) -> const std::string& { return p.id; }, filter);
    // The warm sequences are filtered on their own ids: `--problem 'families/warm/*'` keeps the suite for them alone,
    // with no cold problem.
    if (request.warm) built.warm = WarmSequences(set, suite_name, request, filter, &built.warm_line);
    if (set.problems.empty() && built.warm.empty()) return built;
    set.Validate();
    if (request.certify && !set.problems.empty()) built.line = Certify(&set, build_start);
    const bool generic_sparse_path =
        request.solvers.empty() ||
        std::find(request.solvers.begin(), request.solvers.end(), "newton") != request.solvers.end();
    built.suite = MakeBoxSuite(std::move(set), generic_sparse_path);
    return built;
  }

  std::vector<std::string> Backends(const std::vector<std::string>& solvers) const override {
    // Every chosen backend that solves box-MLCPs (an MCP-only adapter would only add rows of not_applicable to
    // every box table).
    return BackendsWith(solvers, &SolverInfo::box);
  }

 private:
  static std::string Certify(ProblemSet* set, Clock::time_point build_start) {
    const auto references_start = Clock::now();
    AttachReferences(set);
    const double references_seconds = SecondsSince(references_start);
    std::map<Certificate, int> certificates;
    int proved = 0;
    for (const LibraryProblem& p : set->problems) {
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
    return "suite " + set->name + " (" + std::to_string(set->problems.size()) + " problems, " + seconds + ": " +
           certified + ")";
  }

  static std::vector<WarmSequence> WarmSequences(const ProblemSet& set, const std::string& suite_name,
                                                 const SuiteBuildRequest& request, ProblemFilter* filter,
                                                 std::string* line) {
    const auto warm_start = Clock::now();
    std::vector<WarmSequence> sequences = WarmSequencesForSuite(
        set, WarmSuiteKindOf(suite_name, !IsBoxSuiteName(suite_name)), request.quick, /*certify=*/false);
    KeepSelected(&sequences, [](const WarmSequence& w) -> const std::string& { return w.id; }, filter);
    if (request.certify) {
      for (WarmSequence& sequence : sequences) CertifyWarmSequence(&sequence);
    }
    if (!sequences.empty()) {
      std::size_t steps = 0;
      for (const WarmSequence& w : sequences) steps += w.steps.size();
      char text[200];
      std::snprintf(text, sizeof text, "warm track of suite %s: %zu sequences, %zu steps (built and certified in "
                    "%.2f s)", set.name.c_str(), sequences.size(), steps, SecondsSince(warm_start));
      *line = text;
    }
    return sequences;
  }
};

}  // namespace

std::shared_ptr<const ProblemKind> BoxProblemKind() { return std::make_shared<BoxKind>(); }

PlanSuite MakeBoxSuite(ProblemSet set, bool generic_sparse_path) {
  return std::make_shared<BoxKindSuite>(std::move(set), generic_sparse_path);
}

const ProblemSet& BoxSet(const KindSuite& suite) {
  return SetOf<BoxKindSuite>(suite, "box");
}

std::vector<PlanSuite> BoxSuites(std::vector<ProblemSet> sets) {
  std::vector<PlanSuite> suites;
  for (ProblemSet& set : sets) suites.push_back(MakeBoxSuite(std::move(set)));
  return suites;
}

}  // namespace smcbench
