// The built-in MCP suite (mcp_suite.h): ids, rebuilding by id, and the certified references.
#include "problems/mcp/mcp_suite.h"

#include <algorithm>
#include <utility>

#include "problems/mcp/builtin_entry.h"
#include "problems/mcp/classic_mcps.h"
#include "problems/mcp/mcp_families.h"
#include "problems/mcp/scene_step_mcps.h"
#include "solvers/core/edit_distance.h"
#include "solvers/reference/mcp_certify.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

constexpr BuiltinMcpMaker kMakers[] = {MakeClassicMcp, MakeFamilyMcp, MakeSceneStepMcp};
constexpr int kMaxCertifiedSize = 64;
constexpr double kLargeCandidateResidual = 1e-6;
constexpr double kCandidateTimeLimitSeconds = 20.0;  // per backend and start

// Ids of the fixed tables (the scenes' ids need a run, so the suggestion lists their form instead).
std::vector<std::string> SuggestableIds() {
  std::vector<std::string> ids = ClassicMcpIds();
  const std::vector<std::string> hard = HardMcpIds(), families = McpFamilyIds(false);
  ids.insert(ids.end(), hard.begin(), hard.end());
  ids.insert(ids.end(), families.begin(), families.end());
  ids.emplace_back("mcp/scene/hypomonotone/k<K>");
  ids.emplace_back("mcp/scene/arctan/k<K>");
  return ids;
}

BuiltinMcpEntry MakeEntry(const std::string& id) {
  BuiltinMcpEntry entry;
  for (BuiltinMcpMaker make : kMakers) {
    if (make(id, &entry)) return entry;
  }
  std::string message = "MakeBuiltinMcp: unknown id '" + id + "'; closest built-in ids:";
  for (const std::string& known : NearestNames(id, SuggestableIds(), 3)) message += " " + known;
  throw InvalidInputError(message);
}

// McpScaledResidual of z with the Jacobian at z, in the storage the problem advertises.
double ScaledResidual(const MCP& problem, const Vector& z) {
  Vector F(problem.size()), d;
  problem.Evaluate(z, &F);
  if (problem.jacobian_kind() == MCP::JacobianKind::kSparse) {
    SparseMatrix J;
    problem.JacobianSparse(z, &J);
    McpRowScales(J, problem.variable_scale(), &d);
  } else {
    DenseMatrix J;
    problem.JacobianDense(z, &J);
    McpRowScales(J, problem.variable_scale(), &d);
  }
  return McpScaledResidual(z, F, problem.l(), problem.u(), d, problem.variable_scale());
}

void AttachReferences(McpLibraryProblem* p, const std::vector<Vector>& known_solutions) {
  p->references.clear();
  const auto* mcp = dynamic_cast<const ExtendedPrecisionMCP*>(p->problem.get());
  const int n = p->size();
  const McpCertifyOptions options;
  const bool small = n <= kMaxCertifiedSize;
  const bool banded = !small && p->sparse() && n <= options.max_banded_size;
  if (!mcp || (!small && !banded)) {
    p->references_complete = false;
    return;
  }
  // The starts too: a start from which no backend converges may still lead the certifier's Newton to a solution.
  // Large problems take only answers already close to a solution (each quad Newton step there is a banded
  // factorization of n unknowns).
  std::vector<Vector> candidates = known_solutions;
  if (small) candidates.insert(candidates.end(), p->starts.begin(), p->starts.end());
  // A large problem asks the next backend only from the starts no backend has answered yet (within
  // kLargeCandidateResidual): a second answer from the same start is a second banded certification and, for
  // ipopt, most of the suite's build time.
  std::vector<char> answered(p->starts.size(), 0);
  for (std::string_view name : SolverNames()) {
    std::unique_ptr<Solver> solver = CreateSolver(name);
    // auto's answer is the answer of a backend asked here anyway, from the same start (its chain: newton,
    // newton-min, ipopt); asking it too only repeats their solves (a sixth of the suite's build time).
    if (!solver->info().mcp || solver->info().delegates) continue;
    // A large sparse problem takes candidates from the backends that work on its sparse Jacobian in our process
    // (an external code's dense method factors a dense 10⁴ × 10⁴ Jacobian per iteration, and cannot be
    // interrupted).
    if (!small && (!solver->info().sparse || solver->info().external)) continue;
    for (std::size_t k = 0; k < p->starts.size(); ++k) {
      if (!small && answered[k]) continue;
      SolverOptions solver_options;
      solver_options.warm_start = p->starts[k];
      solver_options.time_limit_seconds = kCandidateTimeLimitSeconds;
      const SolveResult result = solver->Solve(*mcp, solver_options);
      if (result.z.size() != n || !result.z.allFinite()) continue;
      if (small || ScaledResidual(*mcp, result.z) <= kLargeCandidateResidual) {
        candidates.push_back(result.z);
        answered[k] = 1;
      }
    }
  }
  const std::vector<McpCertifiedSolution> solutions = CertifyMCPSolutions(*mcp, candidates, options);
  bool all_verified = true;
  for (const McpCertifiedSolution& s : solutions) {
    all_verified = all_verified && s.reference.verified();
    if (s.reference.verified()) p->references.push_back(s.reference);
  }
  bool complete = p->references_complete && all_verified;
  if (p->expected == ExpectedOutcome::kInfeasible) {
    complete = complete && p->references.empty();
  } else if (!known_solutions.empty()) {
    complete = complete && p->references.size() == known_solutions.size();
  } else {
    complete = complete && p->references.size() == 1 && p->references[0].unique();
  }
  p->references_complete = complete;
  std::string certificates;
  for (const ReferenceSolution& r : p->references) {
    certificates += (certificates.empty() ? "" : ",") + std::string(ToString(r.certificate));
  }
  p->metadata["certificates"] = certificates.empty() ? "none found" : certificates;
}

}  // namespace

std::vector<std::string> McpSuiteIds(bool quick) {
  std::vector<std::string> ids = ClassicMcpIds();
  for (const auto& more : {HardMcpIds(), McpFamilyIds(quick), SceneStepMcpIds()}) {
    ids.insert(ids.end(), more.begin(), more.end());
  }
  return ids;
}

std::shared_ptr<const MCP> MakeBuiltinMcp(const std::string& id) { return MakeEntry(id).problem.problem; }

McpLibraryProblem MakeBuiltinMcpProblem(const std::string& id) { return MakeEntry(id).problem; }

void AttachMcpReferences(McpLibraryProblem* problem) {
  BuiltinMcpEntry entry;
  bool builtin = false;
  for (BuiltinMcpMaker make : kMakers) {
    if (!builtin && make(problem->id, &entry)) builtin = true;
  }
  AttachReferences(problem, builtin ? entry.known_solutions : std::vector<Vector>{});
}

McpProblemSet BuildMcpSuite(bool quick) { return BuildMcpSuite(quick, McpSuiteIds(quick)); }

McpProblemSet BuildMcpSuite(bool quick, const std::vector<std::string>& ids) {
  if (ids.empty()) throw InvalidInputError("BuildMcpSuite: no id given");
  McpProblemSet set;
  set.name = "mcp";
  set.description = std::string("nonlinear MCPs: classic (MCPLIB-style), hard cases, families, S9/S10 steps") +
                    (quick ? " (quick sizes)" : "");
  for (const std::string& id : ids) {
    BuiltinMcpEntry entry = MakeEntry(id);
    AttachReferences(&entry.problem, entry.known_solutions);
    set.problems.push_back(std::move(entry.problem));
  }
  set.Validate();
  return set;
}

}  // namespace smcbench
