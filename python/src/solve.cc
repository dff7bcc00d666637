// smcbench.solve and smcbench.solve_mcp: a numpy problem built into a BoxMLCP (or a PythonMCP whose F and J call
// back into Python), one backend from the registry with the caller's options, and the result as a dict. The GIL is
// released while the backend runs; the MCP callbacks take it back for each call into Python.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "convert.h"
#include "python_mcp.h"
#include "solvers/core/mcp_derivatives.h"
#include "solvers/core/problem.h"
#include "solvers/registry/registry.h"

namespace smcbench::python {
namespace {

// The registry's backend with every keyword option set through Solver::SetOption (what `--set` uses), so a
// wrong name or value is the backend's own message.
std::unique_ptr<Solver> MakeSolver(const std::string& name, const py::dict& backend_options) {
  std::unique_ptr<Solver> solver = CreateSolver(name);  // InvalidInputError listing the known names
  SetBackendOptions(*solver, name, backend_options);
  return solver;
}

SolverOptions MakeOptions(double tolerance, std::optional<double> time_limit, std::optional<int> max_iterations,
                          bool polish, const py::object& z0, int n) {
  SolverOptions options;
  options.tolerance = tolerance;
  if (time_limit) options.time_limit_seconds = *time_limit;
  if (max_iterations) options.max_iterations = *max_iterations;
  options.polish = polish;
  if (!z0.is_none()) {
    options.warm_start = ToVector(z0, "z0");
    if (options.warm_start.size() != n) {
      throw InvalidInputError("z0 has size " + std::to_string(options.warm_start.size()) + " but the problem has " +
                              std::to_string(n) + " unknowns");
    }
  }
  // A solve with invalid options would only report kInvalidOptions: Python callers get the error instead.
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInputError(why);
  return options;
}

py::dict SolveBox(const py::object& M, const py::object& q, const py::object& l, const py::object& u,
                  const std::string& solver_name, double tolerance, std::optional<double> time_limit,
                  const py::object& z0, std::optional<int> max_iterations, bool polish,
                  const py::dict& backend_options) {
  // The problem is validated here (InvalidInputError → ValueError): NaN, sizes, l > u.
  const BoxMLCP problem = ToBoxMLCP(M, q, l, u);
  const SolverOptions options = MakeOptions(tolerance, time_limit, max_iterations, polish, z0, problem.size());
  std::unique_ptr<Solver> solver = MakeSolver(solver_name, backend_options);
  SolveResult result;
  {
    py::gil_scoped_release release;
    solver->Solve(problem, options, &result);
  }
  return ResultToDict(result);
}

py::dict SolveMcp(const py::function& F, const py::function& J, const py::object& l, const py::object& u,
                  const py::object& z0, const py::object& variable_scale, const std::string& solver_name,
                  double tolerance, std::optional<double> time_limit, std::optional<int> max_iterations,
                  const py::dict& backend_options, bool derivative_test, double derivative_test_tol) {
  PythonMCP problem(ToVector(l, "l"), ToVector(u, "u"), F, J, "solve_mcp");
  if (!variable_scale.is_none()) problem.set_variable_scale(ToVector(variable_scale, "variable_scale"));
  const SolverOptions options = MakeOptions(tolerance, time_limit, max_iterations, true, z0, problem.size());
  Vector start = options.warm_start;
  if (start.size() == 0) ProjectZeroOntoBox(problem.l(), problem.u(), &start);
  // The Jacobian's kind is probed where the solve starts: the start projected onto the box, as Solve does
  // (docs/problem.md, "Starts outside the box"); J need not be defined outside the box.
  if (start.size() == problem.size()) start = start.cwiseMax(problem.l()).cwiseMin(problem.u());
  problem.ProbeJacobianKind(start);
  std::unique_ptr<Solver> solver = MakeSolver(solver_name, backend_options);
  if (!solver->info().mcp) {
    throw InvalidInputError("solve_mcp: backend '" + solver_name + "' does not solve nonlinear MCPs (those that do: " +
                            McpBackendList() + ")");
  }
  // The derivative test at the start point, before the solve (an exception from F or J is raised as itself).
  std::optional<JacobianCheck> check;
  if (derivative_test) {
    if (!(derivative_test_tol > 0.0) || !std::isfinite(derivative_test_tol)) {
      throw InvalidInputError("solve_mcp: derivative_test_tol must be finite and > 0");
    }
    check = CheckMcpJacobian(problem, start, {derivative_test_tol});
  }
  SolveResult result;
  {
    py::gil_scoped_release release;
    solver->Solve(problem, options, &result);
  }
  problem.RethrowCallbackError();
  if (check) {
    result.SetDetail("derivative_check_error", check->max_error);
    if (!check->ok) result.message = check->message + (result.message.empty() ? "" : "; " + result.message);
  }
  return ResultToDict(result);
}

}  // namespace

void BindSolve(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_solve", &SolveBox, "M"_a, "q"_a, "l"_a, "u"_a, "solver"_a, "tol"_a, "time_limit"_a, "z0"_a,
        "max_iterations"_a, "polish"_a, "backend_options"_a,
        "Solve one box-MLCP (arrays prepared by smcbench.solve); returns a dict.");
  m.def("_solve_mcp", &SolveMcp, "F"_a, "J"_a, "l"_a, "u"_a, "z0"_a, "variable_scale"_a,
        "solver"_a, "tol"_a, "time_limit"_a, "max_iterations"_a, "backend_options"_a, "derivative_test"_a,
        "derivative_test_tol"_a, "Solve one nonlinear MCP with Python callables (see smcbench.solve_mcp); returns a dict.");
}

}  // namespace smcbench::python
