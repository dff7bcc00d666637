#include "bench/kinds/avi_kind.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "bench/kinds/set_kind_suite.h"
#include "bench/replay/avi_replay.h"
#include "bench/replay/floor.h"
#include "problems/avi_library/avi_suite.h"
#include "problems/library/problem_set_io.h"
#include "solvers/core/solver.h"

namespace smcbench {
namespace {

using Clock = std::chrono::steady_clock;

// A file whose header says it holds a set of AVIs (false for anything else: the box reader then judges it).
bool IsAviSetFile(const std::string& name) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(name, ec)) return false;
  try {
    return ReadProblemSetKind(name) == ProblemSetKind::kAvi;
  } catch (const InvalidInputError&) {
    return false;
  }
}

class AviKindSuite final : public SetKindSuite<AviProblemSet, AviProblemSetChecksum> {
 public:
  using SetKindSuite::SetKindSuite;

  std::string kind() const override { return "avi"; }

  std::string ColdJobName(const std::string& /*solver*/) const override { return "avi"; }

  double EstimateSeconds(const SuiteJob& job, const ReplayOptions& options, const BackendCost& cost,
                         const JobBudgets& budgets) const override {
    return EstimateAviJobSeconds(set_.problems.at(job.unit.problem), options, cost, budgets);
  }

  ReplayRecord Replay(const BenchJob& job, Solver* solver, const ReplayOptions& options) const override {
    return ReplayAviOne(set_, set_.problems.at(job.problem), solver, job.solver, options, job.tolerance);
  }

  ReplayRecord Floor(const BenchJob& job, const ReplayOptions& options) const override {
    return ReplayAviFloor(set_, set_.problems.at(job.problem), options);
  }

  ReplayRecord NotRun(const BenchJob& job, const std::string& message) const override {
    return AviNotRunRecord(set_, set_.problems.at(job.problem), job.solver, job.tolerance, message);
  }

};

class AviKind final : public ProblemKind {
 public:
  std::string name() const override { return "avi"; }
  bool Builds(const std::string& suite_name) const override {
    return suite_name == kAviSuiteName || IsAviSetFile(suite_name);
  }

  // The AVI suite (references attached by the suite itself; built whole, its certificates are cheap, then
  // filtered), or a set of AVIs frozen to a file (`smcbench library --write-suite avi FILE.smcps`) with its
  // references as written; validated, with one line for the log.
  BuiltSuite Build(const std::string& suite_name, const SuiteBuildRequest& request,
                   ProblemFilter* filter) const override {
    BuiltSuite built;
    AviProblemSet set;
    if (suite_name == kAviSuiteName) {
      const auto build_start = Clock::now();
      set = BuildAviSuite(request.quick);
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
      std::snprintf(seconds, sizeof seconds, "built and certified in %.2f s",
                    std::chrono::duration<double>(Clock::now() - build_start).count());
      built.line = "suite " + set.name + " (" + std::to_string(set.problems.size()) + " AVIs, " + seconds +
                   "; references: " + certified + ")";
    } else {
      set = ReadAviProblemSetFile(suite_name);
      set.Validate();
      built.line = "suite " + set.name + " (" + std::to_string(set.problems.size()) + " AVIs, read from " +
                   suite_name + ")";
    }
    built.first_id = set.problems.empty() ? "" : set.problems.front().id;
    const std::size_t all = set.problems.size();
    KeepSelected(&set.problems, [](const AviLibraryProblem& p) -> const std::string& { return p.id; }, filter);
    if (set.problems.empty()) return built;
    if (set.problems.size() < all) {
      built.line += "; " + std::to_string(set.problems.size()) + " of them selected by --problem";
    }
    built.suite = MakeAviSuite(std::move(set));
    return built;
  }

  std::vector<std::string> Backends(const std::vector<std::string>& solvers) const override {
    return BackendsWith(solvers, &SolverInfo::box);  // solved through the reduction to a box-MLCP
  }
  std::string NoBackendsLine() const override {
    return "no chosen backend solves box-MLCPs (`smcbench list`): the AVI suite, solved through its reduction to a "
           "box-MLCP, is not run";
  }
};

}  // namespace

std::shared_ptr<const ProblemKind> AviProblemKind() { return std::make_shared<AviKind>(); }

PlanSuite MakeAviSuite(AviProblemSet set) { return std::make_shared<AviKindSuite>(std::move(set)); }

const AviProblemSet& AviSet(const KindSuite& suite) {
  return SetOf<AviKindSuite>(suite, "avi");
}

}  // namespace smcbench
