// smcbench.judge_mcp and smcbench.bench_mcp: a Python user's MCPs (callables, bounds, starts, references) judged by
// the one MCP verdict (JudgeMCP, solvers/core/verdict.h) and timed on every MCP backend as `smcbench bench` times
// the box: an untimed warm-up solve, then samples of repeated solves, median over the samples. The timing loop runs
// here in C++ without the GIL; F and J take it back per call, so the times include the user's Python F and J.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "convert.h"
#include "problems/mcp/mcp_library.h"
#include "python_mcp.h"
#include "solvers/core/solver.h"
#include "solvers/registry/registry.h"

namespace smcbench::python {
namespace {

using Clock = std::chrono::steady_clock;

// A problem × start × backend's timing, with the defaults of `smcbench bench` (ReplayOptions) where they apply.
struct McpBenchOptions {
  double tolerance = 1e-10;
  double time_limit_seconds = 10.0;   // per solve; a solve that reaches it is timed once
  int repetitions = 5;                // timing samples per problem × start × backend
  double min_sample_seconds = 2e-4;   // a sample repeats the solve until it lasts this long (clock resolution)
  double max_seconds_per_pair = 2.0;  // stop sampling after this long (at least one sample)
};

struct McpTiming {
  double median = 0.0, min = 0.0, max = 0.0;
  int samples = 0;
  std::int64_t solves_per_sample = 0;
};

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Repeated cold solves from the same start into *result (the last one is judged). Called without the GIL. An
// exception from F or J ends it after the warm-up solve (PythonMCP::RethrowCallbackError).
McpTiming TimeMcpSolves(Solver* solver, PythonMCP& problem, const SolverOptions& options,
                        const McpBenchOptions& bench, SolveResult* result) {
  const auto t0 = Clock::now();
  solver->Solve(problem, options, result);  // warm-up: sizes the workspaces, tells how long one solve takes
  const double first = std::chrono::duration<double>(Clock::now() - t0).count();
  problem.RethrowCallbackError();
  McpTiming timing;
  std::vector<double> samples;
  std::int64_t count = 1;
  if (first > 0.0) count = static_cast<std::int64_t>(std::ceil(bench.min_sample_seconds / first));
  count = std::clamp<std::int64_t>(count, 1, 1 << 20);
  if (result->status == SolveStatus::kTimeLimit) {  // its time is the limit, not a measurement
    samples.push_back(first);
    count = 1;
  }
  const auto pair_start = Clock::now();
  while (static_cast<int>(samples.size()) < bench.repetitions) {
    const auto s0 = Clock::now();
    for (std::int64_t i = 0; i < count; ++i) solver->Solve(problem, options, result);
    samples.push_back(std::chrono::duration<double>(Clock::now() - s0).count() / static_cast<double>(count));
    if (std::chrono::duration<double>(Clock::now() - pair_start).count() > bench.max_seconds_per_pair) break;
  }
  timing.samples = static_cast<int>(samples.size());
  timing.solves_per_sample = count;
  timing.median = Median(samples);
  timing.min = *std::min_element(samples.begin(), samples.end());
  timing.max = *std::max_element(samples.begin(), samples.end());
  return timing;
}

// The F and J of a problem dict as a PythonMCP (F, J, l, u, variable_scale as __init__.py prepares them), its
// Jacobian's kind probed at `start` (empty: the projection of 0 onto the box); `what` names it in every message.
std::shared_ptr<PythonMCP> MakePythonMcp(const py::dict& d, Vector start, const std::string& what) {
  std::shared_ptr<PythonMCP> problem;
  try {
    problem = std::make_shared<PythonMCP>(ToVector(d["l"], "l"), ToVector(d["u"], "u"), d["F"].cast<py::function>(),
                                          d["J"].cast<py::function>(), what);
    if (!d["variable_scale"].is_none()) problem->set_variable_scale(ToVector(d["variable_scale"], "variable_scale"));
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(what + ": " + e.what());  // "bench_mcp: problems[1] ('x'): MCP: l[0] is NaN"
  }
  if (start.size() != problem->size() || !start.allFinite()) ProjectZeroOntoBox(problem->l(), problem->u(), &start);
  problem->ProbeJacobianKind(start);
  return problem;
}

py::dict JudgementToDict(const Judgement& j) {
  py::dict out;
  out["verdict"] = std::string(ToString(j.verdict));
  out["wrong"] = IsWrong(j.verdict);
  out["residual_abs"] = j.residual.abs;
  out["residual_rel"] = j.residual.rel;
  out["residual_scaled"] = j.residual.scaled;
  out["forward_error"] = j.forward_error;
  out["forward_error_rel"] = j.forward_error_rel;
  out["forward_allowance"] = j.forward_allowance;
  return out;
}

py::dict JudgeMcp(const py::dict& problem_dict, const py::object& z, const std::string& status, double tolerance) {
  const std::string what = "judge_mcp";
  const Vector answer = ToVector(z, what + ": z");
  const std::shared_ptr<PythonMCP> problem = MakePythonMcp(problem_dict, answer, what);
  if (answer.size() != problem->size()) {
    throw InvalidInputError(what + ": z has size " + std::to_string(answer.size()) + " but the problem has " +
                            std::to_string(problem->size()) + " unknowns");
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw InvalidInputError(what + ": tol must be finite and > 0");
  }
  const std::vector<ReferenceSolution> references =
      ToReferences(problem_dict["references"], problem->size(), what + ": references");
  const Judgement j = JudgeMCP(*problem, ToExpectedOutcome(problem_dict["expected"].cast<std::string>(),
                                                           what + ": expected"),
                               references, problem_dict["references_complete"].cast<bool>(),
                               ToSolveStatus(status, what + ": status"), answer, tolerance);
  problem->RethrowCallbackError();
  return JudgementToDict(j);
}

// A user's suite as McpLibraryProblems (the library's data model), checked here with messages naming the problem:
// ids unique and non-empty, starts of the right size and finite, one label per start.
// *callbacks: the same problems as PythonMCP, for RethrowCallbackError.
std::vector<McpLibraryProblem> ToSuite(const py::list& problems, std::vector<std::shared_ptr<PythonMCP>>* callbacks) {
  std::vector<McpLibraryProblem> suite;
  std::set<std::string> ids;
  for (std::size_t index = 0; index < problems.size(); ++index) {
    const py::dict d = problems[index].cast<py::dict>();
    McpLibraryProblem p;
    p.id = d["id"].cast<std::string>();
    const std::string what = "bench_mcp: problems[" + std::to_string(index) + "] ('" + p.id + "')";
    if (p.id.empty()) throw InvalidInputError(what + ": id is empty");
    if (!ids.insert(p.id).second) throw InvalidInputError(what + ": id '" + p.id + "' is used twice");
    const py::list starts = d["starts"].cast<py::list>();
    if (starts.size() == 0) throw InvalidInputError(what + ": starts is empty (give at least one start point)");
    const std::shared_ptr<PythonMCP> problem = MakePythonMcp(d, ToVector(starts[0], what + ": starts[0]"), what);
    p.problem = problem;
    callbacks->push_back(problem);
    p.source = d["source"].cast<std::string>();
    p.tags = d["tags"].cast<std::vector<std::string>>();
    p.expected = ToExpectedOutcome(d["expected"].cast<std::string>(), what + ": expected");
    p.references = ToReferences(d["references"], problem->size(), what + ": references");
    p.references_complete = d["references_complete"].cast<bool>();
    p.start_labels = d["start_labels"].cast<std::vector<std::string>>();
    if (p.start_labels.size() != starts.size()) {
      throw InvalidInputError(what + ": start_labels has " + std::to_string(p.start_labels.size()) +
                              " entries for " + std::to_string(starts.size()) + " starts");
    }
    for (std::size_t k = 0; k < starts.size(); ++k) {
      const std::string field = "starts[" + std::to_string(k) + "]";
      Vector start = ToVector(starts[k], what + ": " + field);
      if (start.size() != problem->size()) {
        throw InvalidInputError(what + ": " + field + " has size " + std::to_string(start.size()) +
                                " but the problem has " + std::to_string(problem->size()) + " unknowns");
      }
      ValidateFinite(what.c_str(), field.c_str(), start);
      p.starts.push_back(std::move(start));
    }
    suite.push_back(std::move(p));
  }
  return suite;
}

// The backends by name (empty: every MCP backend), each checked to solve MCPs.
std::vector<std::unique_ptr<Solver>> McpSolvers(std::vector<std::string>* names) {
  if (names->empty()) *names = McpBackends();
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const std::string& name : *names) {
    solvers.push_back(CreateSolver(name));  // unknown: InvalidInputError listing the known names
    if (!solvers.back()->info().mcp) {
      throw InvalidInputError("bench_mcp: solvers: backend '" + name +
                              "' does not solve nonlinear MCPs (those that do: " + McpBackendList() + ")");
    }
  }
  return solvers;
}

// One row per problem × start × backend, as dicts of the DataFrame's columns.
py::list BenchMcp(const py::list& problems, std::vector<std::string> solver_names, double tolerance,
                  int repetitions, double time_limit) {
  McpBenchOptions bench;
  bench.tolerance = tolerance;
  bench.repetitions = repetitions;
  bench.time_limit_seconds = time_limit;
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw InvalidInputError("bench_mcp: tol must be finite and > 0");
  if (repetitions < 1) throw InvalidInputError("bench_mcp: repetitions must be >= 1");
  if (!(time_limit > 0.0)) throw InvalidInputError("bench_mcp: time_limit must be > 0 seconds");
  // Built and destroyed with the GIL held (they own Python objects); only the solves run without it.
  std::vector<std::shared_ptr<PythonMCP>> callbacks;
  const std::vector<McpLibraryProblem> suite = ToSuite(problems, &callbacks);
  std::vector<std::unique_ptr<Solver>> solvers = McpSolvers(&solver_names);
  py::list rows;
  SolveResult result;
  for (std::size_t index = 0; index < suite.size(); ++index) {
    const McpLibraryProblem& p = suite[index];
    PythonMCP& problem = *callbacks[index];
    for (std::size_t k = 0; k < p.starts.size(); ++k) {
      for (std::size_t s = 0; s < solvers.size(); ++s) {
        SolverOptions options;
        options.tolerance = bench.tolerance;
        options.time_limit_seconds = bench.time_limit_seconds;
        options.measure_time = false;  // timed from outside, around many solves
        options.warm_start = p.starts[k];
        McpTiming timing;
        Judgement j;
        {
          py::gil_scoped_release release;
          timing = TimeMcpSolves(solvers[s].get(), problem, options, bench, &result);
          j = JudgeMCP(problem, p.expected, p.references, p.references_complete, result.status, result.z,
                       bench.tolerance);
        }
        problem.RethrowCallbackError();
        py::dict row = JudgementToDict(j);
        row["problem"] = p.id;
        row["start"] = p.start_labels[k];
        row["solver"] = solver_names[s];
        row["size"] = p.size();
        row["expected"] = std::string(ToString(p.expected));
        row["status"] = std::string(ToString(result.status));
        row["iterations"] = result.iterations;
        row["tolerance"] = bench.tolerance;
        row["time_median"] = timing.median;
        row["time_min"] = timing.min;
        row["time_max"] = timing.max;
        row["samples"] = timing.samples;
        row["solves_per_sample"] = timing.solves_per_sample;
        row["message"] = result.message;
        rows.append(row);
      }
    }
  }
  return rows;
}

}  // namespace

void BindMcpSuite(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_judge_mcp", &JudgeMcp, "problem"_a, "z"_a, "status"_a, "tol"_a,
        "Judge one answer to a Python MCP with JudgeMCP (see smcbench.judge_mcp); returns a dict.");
  m.def("_bench_mcp", &BenchMcp, "problems"_a, "solvers"_a, "tol"_a, "repetitions"_a, "time_limit"_a,
        "Time and judge every problem x start x MCP backend (see smcbench.bench_mcp); returns a list of dicts.");
}

}  // namespace smcbench::python
