// A nonlinear MCP whose F and Jacobian are Python callables, shared by smcbench.solve_mcp, judge_mcp and bench_mcp,
// and the conversions of what a Python user states about an MCP (expected outcome, reference solutions).
#pragma once

#include <pybind11/pybind11.h>

#include <exception>
#include <string>
#include <vector>

#include "convert.h"
#include "solvers/core/problem.h"
#include "solvers/core/verdict.h"

namespace smcbench::python {

// F and J are called with the GIL re-acquired (backends run without it). A result of the wrong shape is an
// InvalidInputError that starts with `what` (the caller: "solve_mcp", "bench_mcp: problems[0] ('x')"). An exception
// from F or J (a Python one, or that error) is thrown into the solve, which may turn it into a status, and kept:
// RethrowCallbackError raises the first one after the solve, so a bug in the user's F reaches the caller as itself
// instead of hiding in a status message. Construct and destroy it with the GIL held (it owns Python objects).
class PythonMCP final : public MCP {
 public:
  // Bounds validated by MCP (InvalidInputError naming l or u); the Jacobian is dense until ProbeJacobianKind.
  PythonMCP(Vector l, Vector u, py::function F, py::function J, std::string what);

  // The Jacobian's kind is that of J's value at z (a start point): scipy.sparse (a CSC tuple from __init__.py)
  // sends the problem down the backends' sparse paths. Python calls J once; needs the GIL.
  void ProbeJacobianKind(const Vector& z);

  JacobianKind jacobian_kind() const override { return kind_; }
  void Evaluate(const Vector& z, Vector* F) const override;
  void JacobianDense(const Vector& z, DenseMatrix* J) const override;
  void JacobianSparse(const Vector& z, SparseMatrix* J) const override;

  // Throws the first exception F or J threw since the last call (and forgets it); nothing if there was none.
  void RethrowCallbackError();

 private:
  void CheckShape(Eigen::Index rows, Eigen::Index cols) const;
  // Keeps the exception being handled (the first one only) and throws it on.
  [[noreturn]] void KeepAndRethrow() const;

  py::function F_, J_;
  JacobianKind kind_ = JacobianKind::kDense;
  std::string what_;
  mutable std::exception_ptr callback_error_;  // set from the const F/J calls of a solve
};

// The registered backends that solve nonlinear MCPs (SolverInfo::mcp), in registry order, and the same as one
// comma-separated line for messages.
std::vector<std::string> McpBackends();
std::string McpBackendList();

// "unknown", "solvable" or "infeasible"; InvalidInputError naming `field` otherwise.
ExpectedOutcome ToExpectedOutcome(const std::string& text, const std::string& field);
// A status name as SolveResult.status prints it ("solved", "iteration_limit", ...); InvalidInputError naming `field`.
SolveStatus ToSolveStatus(const std::string& text, const std::string& field);
// The references as __init__.py normalizes them: a list of dicts {"z": array of size n, "certificate": name,
// "condition": float ≥ 0}. InvalidInputError naming `field` and the index for a wrong size, NaN, or an unknown
// certificate.
std::vector<ReferenceSolution> ToReferences(const py::handle& list, int n, const std::string& field);

}  // namespace smcbench::python
