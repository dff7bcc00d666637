// smcbench.judge_mcp and smcbench.bench_mcp: a Python user's MCPs (callables, bounds, starts, references) judged by
// the one MCP verdict (JudgeMCP, solvers/core/verdict.h) and timed on every MCP backend by the engine of
// `smcbench bench` (ReplayMcpOne, bench/replay/mcp_replay.h: an untimed warm-up solve, then samples of repeated
// solves, median over the samples). The engine runs without the GIL; F and J take it back per call, so the times
// include the user's Python F and J.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "bench/replay/mcp_replay.h"
#include "bench/replay/results_io.h"
#include "convert.h"
#include "problems/mcp/mcp_library.h"
#include "python_mcp.h"
#include "solvers/core/solver.h"
#include "solvers/registry/registry.h"

namespace smcbench::python {
namespace {

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

// One record's row of the DataFrame (bench_mcp's columns: results.csv's, with `wrong`).
py::dict RecordToRow(const ReplayRecord& r) {
  py::dict row;
  row["problem"] = r.problem;
  row["start"] = r.start;
  row["solver"] = r.solver;
  row["size"] = r.size;
  row["expected"] = std::string(ToString(r.expected));
  row["status"] = std::string(ToString(r.status));
  row["verdict"] = std::string(ToString(r.verdict));
  row["wrong"] = IsWrong(r.verdict);
  row["iterations"] = r.iterations;
  row["residual_abs"] = r.residual_abs;
  row["residual_rel"] = r.residual_rel;
  row["residual_scaled"] = r.residual_scaled;
  row["tolerance"] = r.tolerance;
  row["forward_error"] = r.forward_error;
  row["forward_error_rel"] = r.forward_error_rel;
  row["forward_allowance"] = r.forward_allowance;
  row["time_median"] = r.time_median;
  row["time_min"] = r.time_min;
  row["time_max"] = r.time_max;
  row["samples"] = r.samples;
  row["solves_per_sample"] = r.solves_per_sample;
  row["certificate"] = r.certificate;
  row["tags"] = r.tags;
  row["message"] = r.message;
  return row;
}

// One row per problem × start × backend, as dicts of the DataFrame's columns: each job timed and judged by the
// engine of `smcbench bench` (ReplayMcpOne: the same samples, the same JudgeMCP), without the GIL. With out_dir,
// the records are also written as `bench --out` writes them (results.json, results.csv: suite `suite_name`), so
// `smcbench report` and smcbench.report read them.
py::list BenchMcp(const py::list& problems, std::vector<std::string> solver_names, double tolerance,
                  int repetitions, double time_limit, const std::string& suite_name, const std::string& out_dir) {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw InvalidInputError("bench_mcp: tol must be finite and > 0");
  if (repetitions < 1) throw InvalidInputError("bench_mcp: repetitions must be >= 1");
  if (!(time_limit > 0.0)) throw InvalidInputError("bench_mcp: time_limit must be > 0 seconds");
  ReplayOptions replay;
  replay.tolerance = tolerance;
  replay.repetitions = repetitions;
  replay.time_limit_seconds = time_limit;
  // Built and destroyed with the GIL held (they own Python objects); only the solves run without it.
  std::vector<std::shared_ptr<PythonMCP>> callbacks;
  McpProblemSet set{suite_name, "MCPs given to smcbench.bench_mcp", ToSuite(problems, &callbacks)};
  std::vector<std::unique_ptr<Solver>> solvers = McpSolvers(&solver_names);
  SuiteResults suite;
  suite.suite = set.name;
  suite.kind = "mcp";  // McpProblemKind's name: the report's MCP section whatever the suite's name
  suite.description = set.description;
  suite.problems = static_cast<int>(set.problems.size());
  suite.checksum = McpProblemSetChecksum(set);  // calls F at every start (the GIL is held)
  py::list rows;
  for (std::size_t index = 0; index < set.problems.size(); ++index) {
    const McpLibraryProblem& p = set.problems[index];
    for (std::size_t k = 0; k < p.starts.size(); ++k) {
      for (std::size_t s = 0; s < solvers.size(); ++s) {
        ReplayRecord record;
        {
          py::gil_scoped_release release;
          record = ReplayMcpOne(set, p, k, solvers[s].get(), solver_names[s], replay, tolerance);
        }
        callbacks[index]->RethrowCallbackError();
        rows.append(RecordToRow(record));
        suite.replay.records.push_back(std::move(record));
      }
    }
  }
  if (!out_dir.empty()) {
    BenchResults results;
    results.command = "smcbench.bench_mcp (Python)";
    results.suites.push_back(std::move(suite));
    WriteBenchResults(results, out_dir);
  }
  return rows;
}

}  // namespace

void BindMcpSuite(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_judge_mcp", &JudgeMcp, "problem"_a, "z"_a, "status"_a, "tol"_a,
        "Judge one answer to a Python MCP with JudgeMCP (see smcbench.judge_mcp); returns a dict.");
  m.def("_bench_mcp", &BenchMcp, "problems"_a, "solvers"_a, "tol"_a, "repetitions"_a, "time_limit"_a, "suite"_a,
        "out_dir"_a,
        "Time and judge every problem x start x MCP backend (see smcbench.bench_mcp); returns a list of dicts.");
}

}  // namespace smcbench::python
