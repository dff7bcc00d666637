// PythonMCP and the conversions of a Python user's MCP statements (python_mcp.h).
#include "python_mcp.h"

#include <cmath>
#include <string_view>
#include <utility>

#include "solvers/registry/registry.h"

namespace smcbench::python {

PythonMCP::PythonMCP(Vector l, Vector u, py::function F, py::function J, std::string what)
    : MCP(std::move(l), std::move(u), "python"), F_(std::move(F)), J_(std::move(J)), what_(std::move(what)) {}

void PythonMCP::ProbeJacobianKind(const Vector& z) {
  kind_ = IsCscTuple(J_(ToNumpy(z))) ? JacobianKind::kSparse : JacobianKind::kDense;
}

void PythonMCP::Evaluate(const Vector& z, Vector* F) const {
  try {
    py::gil_scoped_acquire acquire;
    const Vector value = ToVector(F_(ToNumpy(z)), what_ + ": F(z)");
    if (value.size() != size()) {
      throw InvalidInputError(what_ + ": F(z) returned " + std::to_string(value.size()) + " entries, expected " +
                              std::to_string(size()));
    }
    *F = value;
  } catch (...) {
    KeepAndRethrow();
  }
}

void PythonMCP::JacobianDense(const Vector& z, DenseMatrix* J) const {
  try {
    py::gil_scoped_acquire acquire;
    const py::object value = J_(ToNumpy(z));
    *J = IsCscTuple(value) ? DenseMatrix(ToSparseMatrix(value.cast<py::tuple>(), what_ + ": J(z)"))
                           : ToDenseMatrix(value, what_ + ": J(z)");
    CheckShape(J->rows(), J->cols());
  } catch (...) {
    KeepAndRethrow();
  }
}

void PythonMCP::JacobianSparse(const Vector& z, SparseMatrix* J) const {
  try {
    py::gil_scoped_acquire acquire;
    const py::object value = J_(ToNumpy(z));
    *J = IsCscTuple(value) ? ToSparseMatrix(value.cast<py::tuple>(), what_ + ": J(z)")
                           : SparseMatrix(ToDenseMatrix(value, what_ + ": J(z)").sparseView());
    CheckShape(J->rows(), J->cols());
  } catch (...) {
    KeepAndRethrow();
  }
}

void PythonMCP::KeepAndRethrow() const {
  if (!callback_error_) callback_error_ = std::current_exception();
  throw;
}

void PythonMCP::RethrowCallbackError() {
  if (!callback_error_) return;
  std::exception_ptr error;
  std::swap(error, callback_error_);
  std::rethrow_exception(error);
}

void PythonMCP::CheckShape(Eigen::Index rows, Eigen::Index cols) const {
  if (rows != size() || cols != size()) {
    throw InvalidInputError(what_ + ": J(z) returned a " + std::to_string(rows) + "x" + std::to_string(cols) +
                            " matrix, expected " + std::to_string(size()) + "x" + std::to_string(size()));
  }
}

std::vector<std::string> McpBackends() {
  std::vector<std::string> names;
  for (std::string_view name : SolverNames()) {
    if (CreateSolver(name)->info().mcp) names.emplace_back(name);
  }
  return names;
}

std::string McpBackendList() {
  std::string list;
  for (const std::string& name : McpBackends()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

ExpectedOutcome ToExpectedOutcome(const std::string& text, const std::string& field) {
  const auto expected = ExpectedOutcomeFromString(text);
  if (!expected) {
    throw InvalidInputError(field + ": expected 'unknown', 'solvable' or 'infeasible', got '" + text + "'");
  }
  return *expected;
}

SolveStatus ToSolveStatus(const std::string& text, const std::string& field) {
  const auto status = SolveStatusFromString(text);
  if (!status) {
    throw InvalidInputError(field + ": unknown status '" + text + "' (a SolveResult.status name: 'solved', "
                            "'iteration_limit', 'infeasible', ...)");
  }
  return *status;
}

std::vector<ReferenceSolution> ToReferences(const py::handle& list, int n, const std::string& field) {
  std::vector<ReferenceSolution> out;
  if (list.is_none()) return out;
  std::size_t index = 0;
  for (const py::handle item : list) {
    const std::string where = field + "[" + std::to_string(index++) + "]";
    const py::dict d = py::reinterpret_borrow<py::dict>(item);
    ReferenceSolution r;
    const std::string name = py::str(d["certificate"]);
    const auto certificate = CertificateFromString(name);
    if (!certificate) {
      throw InvalidInputError(where + ".certificate: unknown certificate '" + name +
                              "' (unique, degenerate, isolated, non-unique, none found, none)");
    }
    r.certificate = *certificate;
    r.condition = d["condition"].cast<double>();
    if (!std::isfinite(r.condition) || r.condition < 0.0) {
      throw InvalidInputError(where + ".condition: must be finite and >= 0, got " +
                              std::string(py::str(d["condition"])));
    }
    r.z = ToVector(d["z"], where + ".z");
    if (r.z.size() != n) {
      throw InvalidInputError(where + ".z has size " + std::to_string(r.z.size()) + " but the problem has " +
                              std::to_string(n) + " unknowns");
    }
    ValidateFinite("MCP reference", (where + ".z").c_str(), r.z);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace smcbench::python
