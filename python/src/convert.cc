// numpy ↔ Eigen conversions shared by the module's files (convert.h).
#include "convert.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>

#include "solvers/auto/auto_solver.h"
#include "solvers/core/number_text.h"
#include "solvers/core/problem.h"

namespace smcbench::python {
namespace {

using CArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// float64, C-contiguous (copied by numpy if needed); InvalidInputError if numpy cannot make one.
CArray ToCArray(const py::handle& object, const std::string& what) {
  CArray array = CArray::ensure(object);
  if (!array) throw InvalidInputError(what + ": expected an array of numbers, got " + std::string(py::str(py::type::handle_of(object).attr("__name__"))));
  return array;
}

std::string ShapeText(const CArray& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) text += (i ? ", " : "") + std::to_string(array.shape(i));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

}  // namespace

Vector ToVector(const py::handle& object, const std::string& what) {
  const CArray array = ToCArray(object, what);
  if (array.ndim() != 1) {
    throw InvalidInputError(what + ": expected a 1-D array, got shape " + ShapeText(array));
  }
  return Eigen::Map<const Vector>(array.data(), array.shape(0));
}

DenseMatrix ToDenseMatrix(const py::handle& object, const std::string& what) {
  const CArray array = ToCArray(object, what);
  if (array.ndim() != 2) {
    throw InvalidInputError(what + ": expected a 2-D array, got shape " + ShapeText(array));
  }
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  return Eigen::Map<const RowMajor>(array.data(), array.shape(0), array.shape(1));
}

bool IsCscTuple(const py::handle& object) { return py::isinstance<py::tuple>(object); }

SparseMatrix ToSparseMatrix(const py::tuple& csc, const std::string& what) {
  if (csc.size() != 5) throw InvalidInputError(what + ": internal CSC tuple must have 5 entries");
  const auto rows = csc[0].cast<std::int64_t>(), cols = csc[1].cast<std::int64_t>();
  using IndexArray = py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>;
  const IndexArray indptr = IndexArray::ensure(csc[2]), indices = IndexArray::ensure(csc[3]);
  const CArray data = ToCArray(csc[4], what);
  if (!indptr || !indices || indptr.ndim() != 1 || indices.ndim() != 1 || data.ndim() != 1) {
    throw InvalidInputError(what + ": malformed sparse matrix (indptr, indices, data must be 1-D)");
  }
  if (rows < 0 || cols < 0 || rows > INT32_MAX || cols > INT32_MAX || indptr.shape(0) != cols + 1) {
    throw InvalidInputError(what + ": malformed sparse matrix (shape " + std::to_string(rows) + "x" +
                            std::to_string(cols) + ", indptr of length " + std::to_string(indptr.shape(0)) + ")");
  }
  const std::int32_t* p = indptr.data();
  const std::int32_t* r = indices.data();
  const std::int64_t nnz = indices.shape(0);
  if (data.shape(0) != nnz || p[0] != 0 || p[cols] != nnz) {
    throw InvalidInputError(what + ": malformed sparse matrix (indptr does not match " + std::to_string(nnz) +
                            " stored entries)");
  }
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(static_cast<std::size_t>(nnz));
  for (std::int64_t j = 0; j < cols; ++j) {
    if (p[j] > p[j + 1]) throw InvalidInputError(what + ": malformed sparse matrix (indptr decreases)");
    for (std::int32_t k = p[j]; k < p[j + 1]; ++k) {
      if (r[k] < 0 || r[k] >= rows) {
        throw InvalidInputError(what + ": malformed sparse matrix (row index " + std::to_string(r[k]) +
                                " out of range)");
      }
      entries.emplace_back(r[k], static_cast<int>(j), data.data()[k]);
    }
  }
  SparseMatrix matrix(static_cast<int>(rows), static_cast<int>(cols));
  matrix.setFromTriplets(entries.begin(), entries.end());  // sums duplicates, as scipy does
  matrix.makeCompressed();
  return matrix;
}

py::array_t<double> ToNumpy(const Vector& v) {
  py::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

py::array_t<double> ToNumpyRows(const DenseMatrix& m) {
  py::array_t<double> out({m.rows(), m.cols()});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  }
  return out;
}

py::array_t<double> ToNumpyTransposed(const DenseMatrix& m) { return ToNumpyRows(m.transpose()); }

py::dict ResultToDict(const SolveResult& result) {
  py::dict out;
  out["status"] = std::string(ToString(result.status));
  out["message"] = result.message;
  out["solver"] = std::string(result.solver);
  out["z"] = ToNumpy(result.z);
  out["w"] = ToNumpy(result.w);
  out["iterations"] = result.iterations;
  out["residual_abs"] = result.residual_abs;
  out["residual_rel"] = result.residual_rel;
  out["residual_scaled"] = result.residual_scaled;
  out["time_seconds"] = result.solve_seconds;
  py::dict details;
  for (int i = 0; i < result.num_details; ++i) {
    // A code by its name ("reused_active_set"), a measurement as a number.
    const std::string_view code = SolveResult::CodeText(result.details[i]);
    if (code.empty()) {
      details[result.details[i].name] = result.details[i].value;
    } else {
      details[result.details[i].name] = std::string(code);
    }
  }
  out["details"] = details;
  // auto: the backend whose answer this is.
  const std::optional<AutoCandidate> chosen = ChosenCandidateOf(result);
  out["chosen"] = chosen ? py::object(py::str(std::string(ToString(*chosen)))) : py::object(py::none());
  return out;
}

std::string OptionValueText(const py::handle& value, const std::string& name) {
  // bool before int: Python's True is also an int.
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return std::to_string(value.cast<long long>());
  if (py::isinstance<py::float_>(value)) return NumberText(value.cast<double>());
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  throw InvalidInputError("option '" + name + "': expected a bool, number or string, got " +
                          std::string(py::str(py::type::handle_of(value).attr("__name__"))));
}

void SetBackendOptions(Solver& solver, const std::string& name, const py::dict& backend_options) {
  for (const auto& [key, value] : backend_options) {
    const std::string option = py::str(key);
    std::string error;
    if (!solver.SetOption(option, OptionValueText(value, option), &error)) throw InvalidInputError(name + ": " + error);
  }
}

BoxMLCP ToBoxMLCP(const py::object& M, const py::object& q, const py::object& l, const py::object& u) {
  if (IsCscTuple(M)) {
    return BoxMLCP(ToSparseMatrix(M.cast<py::tuple>(), "M"), ToVector(q, "q"), ToVector(l, "l"), ToVector(u, "u"));
  }
  return BoxMLCP(ToDenseMatrix(M, "M"), ToVector(q, "q"), ToVector(l, "l"), ToVector(u, "u"));
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

py::dict ReferenceToDict(const ReferenceSolution& reference) {
  py::dict out;
  out["certificate"] = std::string(ToString(reference.certificate));
  out["z"] = reference.z.size() ? py::object(ToNumpy(reference.z)) : py::object(py::none());
  out["condition"] = reference.condition;
  out["proved_radius"] = reference.proved_radius;  // NaN: not proved by an interval enclosure
  out["proved_unique"] = reference.proved_unique;
  return out;
}

}  // namespace smcbench::python
