#include "bench/replay/mcp_replay.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "bench/replay/sample_times.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// The certificate a record carries: the single reference's, or, with several, how many and whether they are all
// the solutions (the report groups problems by this text).
std::string CertificateText(const McpLibraryProblem& p) {
  if (p.references.empty()) return std::string(ToString(Certificate::kNone));
  if (p.references.size() == 1) return std::string(ToString(p.references.front().certificate));
  return std::to_string(p.references.size()) + " solutions" + (p.references_complete ? " (all)" : "");
}

ReplayRecord Describe(const McpProblemSet& set, const McpLibraryProblem& p, std::size_t start,
                      const std::string& solver, double tolerance) {
  if (start >= p.starts.size() || start >= p.start_labels.size()) {
    throw InvalidInputError("bench: MCP " + p.id + " has no start " + std::to_string(start + 1));
  }
  ReplayRecord r;
  r.suite = set.name;
  r.problem = p.id;
  r.start = p.start_labels[start];
  r.solver = solver;
  r.size = p.size();
  r.sparse = p.sparse();
  for (const auto& t : p.tags) r.tags += (r.tags.empty() ? "" : ",") + t;
  r.expected = p.expected;
  r.certificate = CertificateText(p);
  r.tolerance = tolerance;
  r.mode = "cold";
  return r;
}

// FNV-1a 64, fed field by field.
class Hasher {
 public:
  void Bytes(const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ b[i]) * 1099511628211ull;
  }
  void Text(const std::string& s) {
    Count(s.size());
    Bytes(s.data(), s.size());
  }
  void Count(std::uint64_t n) { Bytes(&n, sizeof n); }
  void Number(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    Bytes(&bits, sizeof bits);
  }
  void Numbers(const Vector& v) {
    Count(static_cast<std::uint64_t>(v.size()));
    for (Eigen::Index i = 0; i < v.size(); ++i) Number(v[i]);
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ull;
};

}  // namespace

void TimeMcpSolves(Solver* solver, const MCP& problem, const SolverOptions& options, const ReplayOptions& replay,
                   SolveResult* result, ReplayRecord* record) {
  // Every solve starts again from options.warm_start: Solve(MCP) copies it into result->z, so no answer leaks
  // into the next solve.
  replay_internal::SampleSolveTimes([&] { solver->Solve(problem, options, result); }, result, replay, record);
}

ReplayRecord ReplayMcpOne(const McpProblemSet& set, const McpLibraryProblem& p, std::size_t start, Solver* solver,
                          const std::string& solver_name, const ReplayOptions& options, double tolerance) {
  ReplayRecord r = Describe(set, p, start, solver_name, tolerance);
  if (!p.problem) throw InvalidInputError("bench: MCP " + p.id + " has no problem");
  SolverOptions o = ReplaySolverOptions(options, tolerance);
  o.warm_start = p.starts[start];
  SolveResult result;
  if (!solver->info().mcp) {
    result.status = SolveStatus::kNotApplicable;
    result.message = "backend does not solve nonlinear MCPs (SolverInfo::mcp is false)";
  } else {
    TimeMcpSolves(solver, *p.problem, o, options, &result, &r);
  }
  // The verdict recomputes the residuals from z with the Jacobian at z; the backend's own numbers only stand in
  // when it returned no z.
  const Judgement j = JudgeMCP(*p.problem, p.expected, p.references, p.references_complete, result.status,
                               result.z, tolerance);
  const bool has_z = result.z.size() == p.size();
  r.status = result.status;
  r.message = result.message;
  r.iterations = result.iterations;
  r.residual_abs = has_z ? j.residual.abs : result.residual_abs;
  r.residual_rel = has_z ? j.residual.rel : result.residual_rel;
  r.residual_scaled = has_z ? j.residual.scaled : result.residual_scaled;
  r.forward_error = j.forward_error;
  r.forward_error_rel = j.forward_error_rel;
  r.forward_allowance = j.forward_allowance;
  r.verdict = j.verdict;
  r.backend_code = result.backend_code;
  return r;
}

ReplayResults ReplayMcpProblemSet(const McpProblemSet& set, const ReplayOptions& options) {
  std::vector<std::string> names = BackendsWith(options.solvers, &SolverInfo::mcp);
  // The settings were checked against the whole selection: each MCP backend gets those that reach it.
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const std::string& name : names) {
    ReplayOptions one = options;
    one.settings = SettingsReaching(name, options.settings);
    std::vector<std::string> single{name};
    solvers.push_back(std::move(CreateReplaySolvers(one, &single).front()));
  }
  ReplayResults out;
  std::size_t total = 0, done = 0;
  for (const McpLibraryProblem& p : set.problems) total += p.starts.size() * solvers.size();
  for (const McpLibraryProblem& p : set.problems) {
    for (std::size_t s = 0; s < p.starts.size(); ++s) {
      for (std::size_t b = 0; b < solvers.size(); ++b) {
        out.records.push_back(ReplayMcpOne(set, p, s, solvers[b].get(), names[b], options, options.tolerance));
        if (options.progress) {
          options.progress(++done, total, set.name + " " + p.id + "@" + p.start_labels[s] + " " + names[b]);
        }
      }
    }
  }
  return out;
}

std::string McpProblemSetChecksum(const McpProblemSet& set) {
  Hasher h;
  h.Text(set.name);
  h.Count(set.problems.size());
  Vector F;
  for (const McpLibraryProblem& p : set.problems) {
    h.Text(p.id);
    h.Text(p.source);
    h.Count(p.tags.size());
    for (const auto& t : p.tags) h.Text(t);
    h.Text(std::string(ToString(p.expected)));
    h.Count(p.problem ? 1 : 0);
    if (p.problem) {
      h.Numbers(p.problem->l());
      h.Numbers(p.problem->u());
      h.Numbers(p.problem->variable_scale());
    }
    h.Count(p.starts.size());
    for (std::size_t s = 0; s < p.starts.size(); ++s) {
      h.Text(s < p.start_labels.size() ? p.start_labels[s] : std::string());
      h.Numbers(p.starts[s]);
      if (p.problem && p.starts[s].size() == p.size()) {
        F.resize(p.size());
        p.problem->Evaluate(p.starts[s], &F);
        h.Numbers(F);
      }
    }
    h.Count(p.references.size());
    for (const ReferenceSolution& ref : p.references) {
      h.Text(std::string(ToString(ref.certificate)));
      h.Number(ref.condition);
      h.Numbers(ref.z);
    }
    h.Count(p.references_complete ? 1 : 0);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.value()));
  return hex;
}

ReplayRecord McpNotRunRecord(const McpProblemSet& set, const McpLibraryProblem& p, std::size_t start,
                             const std::string& solver_name, double tolerance, const std::string& message) {
  ReplayRecord r = Describe(set, p, start, solver_name, tolerance);
  r.status = SolveStatus::kTimeLimit;
  r.message = message;
  r.verdict = Verdict::kFailed;  // not run is no answer, even on a problem with no solution
  r.residual_abs = r.residual_rel = r.residual_scaled = kInf;
  return r;
}

}  // namespace smcbench
