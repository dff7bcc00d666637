// smcbench.judge: one answer to a box-MLCP judged as `smcbench bench` judges it (Judge, solvers/core/verdict.h),
// against a certified reference, so a Python user gets the bench's verdict and forward error for a single solve.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "convert.h"
#include "problems/library/references.h"
#include "python_mcp.h"
#include "solvers/reference/certify.h"

namespace smcbench::python {
namespace {

// The reference the answer is judged against: z_star certified by the library's certifier (Certify, in extended
// precision, with its interval proof) when given, else the library's own reference for the problem
// (ComputeReference: the answer judged and those of lemke, enum and newton as candidates, each checked; n > 64 gets
// none). Without the GIL.
ReferenceSolution CertifiedReference(const BoxMLCP& problem, const Vector& answer, const py::object& z_star,
                                     ExpectedOutcome expected) {
  if (!z_star.is_none()) {
    const Vector candidate = ToVector(z_star, "judge: reference");
    if (candidate.size() != problem.size()) {
      throw InvalidInputError("judge: reference has size " + std::to_string(candidate.size()) +
                              " but the problem has " + std::to_string(problem.size()) + " unknowns");
    }
    ValidateFinite("judge", "reference", candidate);
    py::gil_scoped_release release;
    return Certify(problem, {candidate});
  }
  LibraryProblem library = MakeLibraryProblem("python", "python", problem);
  library.expected = expected;
  if (answer.allFinite()) library.solution = answer;
  py::gil_scoped_release release;
  try {
    return ComputeReference(library);
  } catch (const std::logic_error& e) {  // a verified solution on a problem said to be infeasible
    throw InvalidInputError(std::string("judge: expected: ") + e.what());
  }
}

// Judge of z with status on the problem (M, q, l, u as smcbench.solve prepares them): the judgement's numbers and
// the reference it used.
py::dict JudgeBox(const py::object& M, const py::object& q, const py::object& l, const py::object& u,
                  const py::object& z, const std::string& status, double tolerance, const py::object& reference,
                  const std::string& expected) {
  const BoxMLCP problem = ToBoxMLCP(M, q, l, u);
  const Vector answer = ToVector(z, "judge: z");
  if (answer.size() != problem.size()) {
    throw InvalidInputError("judge: z has size " + std::to_string(answer.size()) + " but the problem has " +
                            std::to_string(problem.size()) + " unknowns");
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) throw InvalidInputError("judge: tol must be finite and > 0");
  const SolveStatus solve_status = ToSolveStatus(status, "judge: status");
  const ExpectedOutcome outcome = ToExpectedOutcome(expected, "judge: expected");
  const ReferenceSolution certified = CertifiedReference(problem, answer, reference, outcome);
  py::dict out = JudgementToDict(Judge(problem, outcome, &certified, solve_status, answer, tolerance));
  out["reference"] = ReferenceToDict(certified);
  return out;
}

}  // namespace

void BindJudge(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_judge", &JudgeBox, "M"_a, "q"_a, "l"_a, "u"_a, "z"_a, "status"_a, "tol"_a, "reference"_a, "expected"_a,
        "Judge one answer to a box-MLCP against a certified reference (see smcbench.judge); returns a dict.");
}

}  // namespace smcbench::python
