// numpy ↔ Eigen for the module: every array coming from Python is copied into the library's own types (any dtype
// numpy can cast to float64, any contiguity), every array going back is a fresh numpy array owned by Python.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <string>

#include "solvers/core/result.h"
#include "solvers/core/solver.h"
#include "solvers/core/types.h"
#include "solvers/core/verdict.h"

namespace smcbench::python {

namespace py = pybind11;

// A 1-D array (or anything numpy turns into one) as a Vector; InvalidInputError naming `what` if it is not 1-D.
Vector ToVector(const py::handle& array, const std::string& what);
// A 2-D array as a dense matrix; InvalidInputError naming `what` if it is not 2-D.
DenseMatrix ToDenseMatrix(const py::handle& array, const std::string& what);
// A sparse matrix handed over by __init__.py as the tuple (rows, cols, indptr, indices, data) of scipy's CSC
// form (int32 indices, float64 data). The index arrays are checked before Eigen sees them.
SparseMatrix ToSparseMatrix(const py::tuple& csc, const std::string& what);
// Either of the two: a tuple is CSC (above), anything else dense.
bool IsCscTuple(const py::handle& object);

py::array_t<double> ToNumpy(const Vector& v);
// Rows × cols in C order, so that a[k] is row k.
py::array_t<double> ToNumpyRows(const DenseMatrix& m);
// Transposed: column k of m becomes row k (a trajectory's columns are steps; Python reads rows = steps).
py::array_t<double> ToNumpyTransposed(const DenseMatrix& m);

// The box-MLCP of smcbench.solve's arguments as __init__.py prepares them: M dense or the CSC tuple, q, l, u.
// Validated by BoxMLCP (InvalidInputError naming M, q, l or u: NaN, sizes, l > u).
BoxMLCP ToBoxMLCP(const py::object& M, const py::object& q, const py::object& l, const py::object& u);
// A verdict's numbers as the dict judge() and judge_mcp() return: verdict, wrong, residual_abs/rel/scaled,
// forward_error, forward_error_rel, forward_allowance (NaN where no reference defines them).
py::dict JudgementToDict(const Judgement& judgement);
// A certified reference as Python sees it: certificate, z (None unless verified), condition, proved_radius,
// proved_unique.
py::dict ReferenceToDict(const ReferenceSolution& reference);
// A SolveResult as the plain dict __init__.py turns into smcbench.SolveResult.
py::dict ResultToDict(const SolveResult& result);

// Backend options from Python keyword values (bool, int, float, str) as the text Solver::SetOption parses.
std::string OptionValueText(const py::handle& value, const std::string& name);
// Sets every keyword option on solver through Solver::SetOption (what `--set` uses), so a wrong name or value is
// the backend's own message: InvalidInputError "<name>: <message>".
void SetBackendOptions(Solver& solver, const std::string& name, const py::dict& backend_options);

}  // namespace smcbench::python
