// smcbench.AffineVI, solve_avi, read_avi and write_avi: the AVI over a polytope (solvers/avi/affine_vi.h) built from
// numpy arrays, solved by any box backend through SolveAvi, judged by JudgeAvi, and its file (problems/io/avi_file.h).
// The GIL is released while the backend runs.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "convert.h"
#include "problems/io/avi_file.h"
#include "solvers/avi/avi_solver.h"
#include "solvers/avi/avi_verdict.h"
#include "solvers/core/problem.h"
#include "solvers/registry/registry.h"

namespace smcbench::python {
namespace {

// H or E: None or an empty array means no rows (a 0×n block), anything else a 2-D array whose sizes the AffineVI
// constructor checks (naming the field).
DenseMatrix RowsOrNone(const py::object& value, Eigen::Index n, const std::string& what) {
  if (value.is_none()) return DenseMatrix(0, n);
  if (py::len(value) == 0) return DenseMatrix(0, n);
  return ToDenseMatrix(value, what);
}

Vector VectorOrNone(const py::object& value, const std::string& what) {
  if (value.is_none() || py::len(value) == 0) return Vector(0);
  return ToVector(value, what);
}

AffineVI MakeAffineVI(const py::object& M, const py::object& q, const py::object& H, const py::object& K,
                      const py::object& E, const py::object& f, const std::string& name) {
  Vector q_vector = ToVector(q, "q");
  const Eigen::Index n = q_vector.size();
  if (E.is_none() != f.is_none()) throw InvalidInputError("AffineVI: E and f come together (give both or neither)");
  return AffineVI(ToDenseMatrix(M, "M"), std::move(q_vector), RowsOrNone(H, n, "H"), VectorOrNone(K, "K"),
                  RowsOrNone(E, n, "E"), VectorOrNone(f, "f"), name);
}

// The registry's backend with every keyword option set through Solver::SetOption (what `--set` uses).
std::unique_ptr<Solver> MakeAviSolver(const std::string& name, const py::dict& backend_options) {
  std::unique_ptr<Solver> solver = CreateSolver(name);  // InvalidInputError listing the known names
  if (!solver->info().box) {
    throw InvalidInputError("solve_avi: backend '" + name + "' does not solve box-MLCPs, so not the AVI's reduction");
  }
  SetBackendOptions(*solver, name, backend_options);
  return solver;
}

py::dict SolveAviPy(const AffineVI& avi, const std::string& solver_name, double tolerance,
                    std::optional<double> time_limit, const py::object& start, std::optional<int> max_iterations,
                    bool polish, const py::object& reference, const py::object& expected_name,
                    const py::dict& backend_options) {
  SolverOptions options;
  options.tolerance = tolerance;
  if (time_limit) options.time_limit_seconds = *time_limit;
  if (max_iterations) options.max_iterations = *max_iterations;
  options.polish = polish;
  const Eigen::Index n = avi.size(), full = n + avi.inequality_count() + avi.equality_count();
  if (!start.is_none()) {
    options.warm_start = ToVector(start, "start");
    if (options.warm_start.size() != n && options.warm_start.size() != full) {
      throw InvalidInputError("start has size " + std::to_string(options.warm_start.size()) + ", expected n = " +
                              std::to_string(n) + " (λ) or n + m + p = " + std::to_string(full) + " (λ, μ, ν)");
    }
  }
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInputError(why);
  ExpectedOutcome expected = ExpectedAviOutcome(avi);
  if (!expected_name.is_none()) {
    const std::string text = py::str(expected_name);
    const std::optional<ExpectedOutcome> parsed = ExpectedOutcomeFromString(text);
    if (!parsed) throw InvalidInputError("expected: 'solvable', 'infeasible' or 'unknown', got '" + text + "'");
    expected = *parsed;
  }
  std::optional<AviReference> certified;
  if (!reference.is_none()) {
    const Vector lambda = ToVector(reference, "reference");
    if (lambda.size() != n) {
      throw InvalidInputError("reference has size " + std::to_string(lambda.size()) + ", expected n = " +
                              std::to_string(n));
    }
    ValidateFinite("solve_avi", "reference", lambda);
    certified = CertifyAvi(avi, {AviMultipliersAt(avi, lambda)});
  }
  std::unique_ptr<Solver> solver = MakeAviSolver(solver_name, backend_options);
  AviResult r;
  {
    py::gil_scoped_release release;
    r = SolveAvi(avi, *solver, options, certified ? &*certified : nullptr);
  }
  // SolveAvi judged by ExpectedAviOutcome; the caller's statement of the outcome decides instead.
  r.judgement = JudgeAvi(avi, expected, certified ? &*certified : nullptr, r.status, r.solution, tolerance);
  const AviJudgement& j = r.judgement;
  py::dict out;
  out["status"] = std::string(ToString(r.status));
  out["message"] = r.message;
  out["solver"] = std::string(r.solver);
  out["verdict"] = std::string(ToString(j.verdict));
  out["expected"] = std::string(ToString(expected));
  out["lambda_"] = ToNumpy(r.solution.lambda);
  out["mu"] = ToNumpy(r.solution.mu);
  out["nu"] = ToNumpy(r.solution.nu);
  out["iterations"] = r.iterations;
  out["time_seconds"] = r.solve_seconds;
  out["residual_rel"] = j.residual.rel;
  out["residual_scaled"] = j.residual.scaled;
  out["primal_infeasibility"] = j.primal_infeasibility;
  out["complementarity"] = j.complementarity;
  out["forward_error"] = j.forward_error_applicable ? py::object(py::float_(j.forward_error)) : py::object(py::none());
  out["reference_certificate"] = certified ? py::object(py::str(std::string(ToString(certified->reduced.certificate))))
                                           : py::object(py::none());
  out["reduced"] = ResultToDict(r.reduced);
  return out;
}

py::tuple ReadAviPy(const std::string& path) {
  AviFile file = ReadAviFile(path);
  const py::object solution = file.solution.size() > 0 ? py::object(ToNumpy(file.solution)) : py::object(py::none());
  return py::make_tuple(std::move(file.avi), solution, std::string(ToString(file.expected)));
}

void WriteAviPy(const AffineVI& avi, const std::string& path, const py::object& solution,
                const py::object& expected_name) {
  Vector lambda;
  if (!solution.is_none()) lambda = ToVector(solution, "solution");
  if (!solution.is_none() && lambda.size() == 0) throw InvalidInputError("solution is empty");
  std::optional<ExpectedOutcome> expected;
  if (!expected_name.is_none()) {
    const std::string text = py::str(expected_name);
    expected = ExpectedOutcomeFromString(text);
    if (!expected) throw InvalidInputError("expected: 'solvable', 'infeasible' or 'unknown', got '" + text + "'");
  }
  WriteAviFile(avi, path, lambda, expected);
}

}  // namespace

void BindAvi(py::module_& m) {
  using namespace pybind11::literals;
  py::class_<AffineVI>(m, "AffineVI",
                       "An affine variational inequality over a polytope (see smcbench.AffineVI; docs/avi.md).")
      .def(py::init(&MakeAffineVI), "M"_a, "q"_a, "H"_a = py::none(), "K"_a = py::none(), "E"_a = py::none(),
           "f"_a = py::none(), "name"_a = "")
      .def_property_readonly("M", [](const AffineVI& a) { return ToNumpyRows(a.M()); })
      .def_property_readonly("q", [](const AffineVI& a) { return ToNumpy(a.q()); })
      .def_property_readonly("H", [](const AffineVI& a) { return ToNumpyRows(a.H()); })
      .def_property_readonly("K", [](const AffineVI& a) { return ToNumpy(a.K()); })
      .def_property_readonly("E", [](const AffineVI& a) { return ToNumpyRows(a.E()); })
      .def_property_readonly("f", [](const AffineVI& a) { return ToNumpy(a.f()); })
      .def_property_readonly("name", &AffineVI::name)
      .def_property_readonly("n", &AffineVI::size)
      .def_property_readonly("m", &AffineVI::inequality_count)
      .def_property_readonly("p", &AffineVI::equality_count)
      .def_property_readonly("feasible_point", [](const AffineVI& a) { return ToNumpy(a.feasible_point()); })
      .def_property_readonly("boundedness", [](const AffineVI& a) { return std::string(ToString(a.boundedness())); })
      .def_property_readonly("expected",
                             [](const AffineVI& a) { return std::string(ToString(ExpectedAviOutcome(a))); })
      .def("__repr__", [](const AffineVI& a) {
        return "AffineVI(name='" + a.name() + "', n=" + std::to_string(a.size()) + ", m=" +
               std::to_string(a.inequality_count()) + ", p=" + std::to_string(a.equality_count()) + ")";
      });
  m.def("_solve_avi", &SolveAviPy, "avi"_a, "solver"_a, "tol"_a, "time_limit"_a, "start"_a, "max_iterations"_a,
        "polish"_a, "reference"_a, "expected"_a, "backend_options"_a,
        "Solve one AVI through SolveAvi (see smcbench.solve_avi); returns a dict.");
  m.def("_read_avi", &ReadAviPy, "path"_a, "Read an .avi.json file: (AffineVI, solution or None, expected).");
  m.def("_write_avi", &WriteAviPy, "avi"_a, "path"_a, "solution"_a, "expected"_a, "Write an .avi.json file.");
}

}  // namespace smcbench::python
