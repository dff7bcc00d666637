#include "bench/kinds/mcp_kind.h"

#include <chrono>
#include <cstdio>
#include <map>

#include "bench/kinds/set_kind_suite.h"
#include "bench/replay/floor.h"
#include "bench/replay/mcp_replay.h"
#include "problems/mcp/mcp_suite.h"
#include "solvers/core/solver.h"

namespace smcbench {
namespace {

using Clock = std::chrono::steady_clock;

class McpKindSuite final : public SetKindSuite<McpProblemSet, McpProblemSetChecksum> {
 public:
  using SetKindSuite::SetKindSuite;

  std::string kind() const override { return "mcp"; }

  // Problem × start, in that order.
  std::vector<SuiteUnit> Units() const override {
    std::vector<SuiteUnit> units;
    for (std::size_t p = 0; p < set_.problems.size(); ++p) {
      const McpLibraryProblem& problem = set_.problems[p];
      for (std::size_t start = 0; start < problem.starts.size(); ++start) {
        const std::string label = start < problem.start_labels.size() ? problem.start_labels[start] : "";
        units.push_back({p, problem.id, /*has_start=*/true, start, label});
      }
    }
    return units;
  }
  std::string UnitsNoun() const override { return "problem x start"; }

  std::string ColdJobName(const std::string& /*solver*/) const override { return "mcp"; }

  double EstimateSeconds(const SuiteJob& job, const ReplayOptions& options, const BackendCost& cost,
                         const JobBudgets& budgets) const override {
    return EstimateMcpJobSeconds(set_.problems.at(job.unit.problem), options, cost, budgets);
  }

  ReplayRecord Replay(const BenchJob& job, Solver* solver, const ReplayOptions& options) const override {
    return ReplayMcpOne(set_, set_.problems.at(job.problem), job.start, solver, job.solver, options, job.tolerance);
  }

  ReplayRecord Floor(const BenchJob& job, const ReplayOptions& options) const override {
    return ReplayMcpFloor(set_, set_.problems.at(job.problem), job.start, options);
  }

  ReplayRecord NotRun(const BenchJob& job, const std::string& message) const override {
    return McpNotRunRecord(set_, set_.problems.at(job.problem), job.start, job.solver, job.tolerance, message);
  }

};

class McpKind final : public ProblemKind {
 public:
  std::string name() const override { return "mcp"; }
  bool Builds(const std::string& suite_name) const override { return suite_name == kMcpSuiteName; }

  // The MCP suite of the ids the filter keeps (references attached by the suite itself, to them only), validated,
  // with one line for the log.
  BuiltSuite Build(const std::string& /*suite_name*/, const SuiteBuildRequest& request,
                   ProblemFilter* filter) const override {
    BuiltSuite built;
    std::vector<std::string> ids = McpSuiteIds(request.quick);
    built.first_id = ids.empty() ? "" : ids.front();
    KeepSelected(&ids, [](const std::string& id) -> const std::string& { return id; }, filter);
    if (ids.empty()) return built;
    const auto build_start = Clock::now();
    McpProblemSet set = BuildMcpSuite(request.quick, ids);
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
    std::snprintf(seconds, sizeof seconds, "built in %.2f s",
                  std::chrono::duration<double>(Clock::now() - build_start).count());
    built.line = "suite " + set.name + " (" + std::to_string(set.problems.size()) + " MCPs, " +
                 std::to_string(instances) + " problem x start, " + seconds + "; references: " + certified + ")";
    built.suite = MakeMcpSuite(std::move(set));
    return built;
  }

  std::vector<std::string> Backends(const std::vector<std::string>& solvers) const override {
    return BackendsWith(solvers, &SolverInfo::mcp);
  }
  std::string NoBackendsLine() const override {
    return "no chosen backend solves MCPs (`smcbench list` says: accepts nonlinear MCP): the MCP suite is not run";
  }
};

}  // namespace

std::shared_ptr<const ProblemKind> McpProblemKind() { return std::make_shared<McpKind>(); }

PlanSuite MakeMcpSuite(McpProblemSet set) { return std::make_shared<McpKindSuite>(std::move(set)); }

const McpProblemSet& McpSet(const KindSuite& suite) {
  return SetOf<McpKindSuite>(suite, "mcp");
}

}  // namespace smcbench
