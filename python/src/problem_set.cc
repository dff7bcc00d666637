// .smcps problem sets from Python (problems/library/problem_set_io.h): read a set into plain dicts of numpy arrays
// and metadata, write a set from such dicts. __init__.py wraps the dicts in smcbench.Problem, or for a set of AVIs
// (format version 4) in smcbench.AviProblem around an AffineVI.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "convert.h"
#include "problems/avi_library/avi_library.h"
#include "problems/library/references.h"
#include "problems/library/problem_set_io.h"

namespace smcbench::python {
namespace {

Tristate TristateFromText(const std::string& text, const std::string& field) {
  for (Tristate value : {Tristate::kUnknown, Tristate::kNo, Tristate::kYes}) {
    if (text == ToString(value)) return value;
  }
  throw InvalidInputError(field + ": expected 'yes', 'no' or 'unknown', got '" + text + "'");
}

py::object MatrixToPython(const BoxMLCP& problem) {
  if (!problem.is_sparse()) return ToNumpyRows(problem.dense_matrix());
  // (rows, cols, indptr, indices, data): __init__.py makes a scipy.sparse.csc_matrix of it.
  const SparseMatrix& M = problem.sparse_matrix();
  const int nnz = static_cast<int>(M.nonZeros());
  py::array_t<std::int32_t> indptr(M.outerSize() + 1), indices(nnz);
  py::array_t<double> data(nnz);
  std::copy(M.outerIndexPtr(), M.outerIndexPtr() + M.outerSize() + 1, indptr.mutable_data());
  std::copy(M.innerIndexPtr(), M.innerIndexPtr() + nnz, indices.mutable_data());
  std::copy(M.valuePtr(), M.valuePtr() + nnz, data.mutable_data());
  return py::make_tuple(M.rows(), M.cols(), indptr, indices, data);
}

py::dict ProblemToDict(const LibraryProblem& p) {
  py::dict out;
  out["id"] = p.id;
  out["source"] = p.source;
  out["M"] = MatrixToPython(p.problem);
  out["q"] = ToNumpy(p.problem.q());
  out["l"] = ToNumpy(p.problem.l());
  out["u"] = ToNumpy(p.problem.u());
  out["tags"] = p.tags;
  out["seed"] = p.seed ? py::object(py::int_(*p.seed)) : py::object(py::none());
  out["expected"] = std::string(ToString(p.expected));
  out["solution"] = p.solution.size() ? py::object(ToNumpy(p.solution)) : py::object(py::none());
  out["metadata"] = p.metadata;
  py::dict matrix;
  matrix["symmetric"] = std::string(ToString(p.matrix.symmetric));
  matrix["positive_definite"] = std::string(ToString(p.matrix.positive_definite));
  matrix["p_matrix"] = std::string(ToString(p.matrix.p_matrix));
  out["matrix"] = matrix;
  // Proved by an interval enclosure (radius NaN: not proved); computed, never read back from a dict.
  out["reference"] = ReferenceToDict(ProvedReference(p));
  return out;
}

py::dict ReadSet(const std::string& path) {
  ProblemSetFileInfo info;
  ProblemSet set;
  {
    py::gil_scoped_release release;
    set = ReadProblemSetFile(path, &info);
  }
  py::dict out;
  out["name"] = set.name;
  out["description"] = set.description;
  out["version"] = info.version;
  py::list problems;
  for (const LibraryProblem& p : set.problems) problems.append(ProblemToDict(p));
  out["problems"] = problems;
  return out;
}

// One dict (keys as ProblemToDict; id, M, q, l, u required, the rest optional) as a LibraryProblem.
LibraryProblem ProblemFromDict(const py::dict& d, std::size_t index) {
  std::string where = "problems[" + std::to_string(index) + "]";
  for (const char* key : {"id", "M", "q", "l", "u"}) {
    if (!d.contains(key)) throw InvalidInputError(where + ": missing '" + key + "'");
  }
  const py::object M = d["M"];
  const std::string id = d["id"].cast<std::string>();
  where += " ('" + id + "')";  // every later message names the problem by index and id
  const std::string source = d.contains("source") && !d["source"].is_none() ? d["source"].cast<std::string>() : "python";
  Vector q = ToVector(d["q"], where + ".q"), l = ToVector(d["l"], where + ".l"), u = ToVector(d["u"], where + ".u");
  std::optional<LibraryProblem> built;
  try {
    built = IsCscTuple(M) ? MakeLibraryProblem(id, source,
                                               BoxMLCP(ToSparseMatrix(M.cast<py::tuple>(), where + ".M"), std::move(q),
                                                       std::move(l), std::move(u), id))
                          : MakeLibraryProblem(id, source,
                                               BoxMLCP(ToDenseMatrix(M, where + ".M"), std::move(q), std::move(l),
                                                       std::move(u), id));
  } catch (const InvalidInputError& e) {
    // The problem's own checks ("BoxMLCP: l[1] = 2 > u[1] = 1") do not know which problem of the set they are.
    const std::string what = e.what();
    if (what.rfind(where, 0) == 0) throw;
    throw InvalidInputError(where + ": " + what);
  }
  LibraryProblem p = std::move(*built);
  const auto has = [&](const char* key) { return d.contains(key) && !d[key].is_none(); };
  if (has("tags")) p.tags = d["tags"].cast<std::vector<std::string>>();
  if (has("seed")) p.seed = d["seed"].cast<std::uint64_t>();
  if (has("expected")) {
    const std::string text = d["expected"].cast<std::string>();
    const auto expected = ExpectedOutcomeFromString(text);
    if (!expected) {
      throw InvalidInputError(where + ".expected: expected 'unknown', 'solvable' or 'infeasible', got '" + text + "'");
    }
    p.expected = *expected;
  }
  if (has("solution")) p.solution = ToVector(d["solution"], where + ".solution");
  if (has("metadata")) p.metadata = d["metadata"].cast<std::map<std::string, std::string>>();
  if (has("matrix")) {
    const py::dict matrix = d["matrix"].cast<py::dict>();
    const auto tristate = [&](const char* key, Tristate* field) {
      if (matrix.contains(key)) *field = TristateFromText(matrix[key].cast<std::string>(), where + ".matrix." + key);
    };
    tristate("symmetric", &p.matrix.symmetric);
    tristate("positive_definite", &p.matrix.positive_definite);
    tristate("p_matrix", &p.matrix.p_matrix);
  }
  if (has("reference")) {
    const py::dict reference = d["reference"].cast<py::dict>();
    if (reference.contains("certificate")) {
      const std::string text = reference["certificate"].cast<std::string>();
      const auto certificate = CertificateFromString(text);
      if (!certificate) throw InvalidInputError(where + ".reference.certificate: unknown certificate '" + text + "'");
      p.reference.certificate = *certificate;
    }
    if (reference.contains("z") && !reference["z"].is_none()) {
      p.reference.z = ToVector(reference["z"], where + ".reference.z");
    }
    if (reference.contains("condition")) p.reference.condition = reference["condition"].cast<double>();
  }
  return p;
}

void WriteSet(const std::string& path, const py::list& problems, const std::string& name,
              const std::string& description) {
  ProblemSet set;
  set.name = name;
  set.description = description;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    set.problems.push_back(ProblemFromDict(problems[i].cast<py::dict>(), i));
  }
  py::gil_scoped_release release;
  WriteProblemSetFile(set, path);  // validates the set (ids unique, sizes) first
}

std::string ReadKind(const std::string& path) {
  return ReadProblemSetKind(path) == ProblemSetKind::kAvi ? "avi" : "box";
}

// reference of an AVI as Python sees it: the reduction's certificate, condition and z* (what the file stores, so a
// read set writes back bit for bit) and λ*, μ*, ν* split from it (arrays, empty without rows); z, lambda_, mu and
// nu are None when no solution was verified.
py::dict AviReferenceToDict(const AviReference& r) {
  const bool verified = r.verified();
  const auto vector_or_none = [verified](const Vector& v) {
    return verified ? py::object(ToNumpy(v)) : py::object(py::none());
  };
  py::dict out;
  out["certificate"] = std::string(ToString(r.reduced.certificate));
  out["condition"] = r.reduced.condition;
  out["z"] = vector_or_none(r.reduced.z);
  out["lambda_"] = vector_or_none(r.solution.lambda);
  out["mu"] = vector_or_none(r.solution.mu);
  out["nu"] = vector_or_none(r.solution.nu);
  out["lambda_unique"] = r.lambda_unique;
  out["strictly_monotone"] = std::string(ToString(r.strictly_monotone));
  return out;
}

py::dict ReadAviSet(const std::string& path) {
  ProblemSetFileInfo info;
  AviProblemSet set;
  {
    py::gil_scoped_release release;
    set = ReadAviProblemSetFile(path, &info);
  }
  py::dict out;
  out["name"] = set.name;
  out["description"] = set.description;
  out["version"] = info.version;
  py::list problems;
  for (const AviLibraryProblem& p : set.problems) {
    py::dict d;
    d["id"] = p.id;
    d["avi"] = py::cast(*p.problem);  // a copy owned by Python
    d["source"] = p.source;
    d["tags"] = p.tags;
    d["expected"] = std::string(ToString(p.expected));
    d["metadata"] = p.metadata;
    d["reference"] = AviReferenceToDict(p.reference);
    problems.append(d);
  }
  out["problems"] = problems;
  return out;
}

// One dict (id, avi required; source, tags, expected, metadata, reference optional) as an AviLibraryProblem. The
// reference is taken as given (z*, condition, certificate, μ*, ν*, uniqueness); the writer checks that it is
// consistent (λ* the head of z*, sizes, a verified one not on an AVI expected infeasible).
AviLibraryProblem AviProblemFromDict(const py::dict& d, std::size_t index) {
  const std::string where = "problems[" + std::to_string(index) + "]";
  for (const char* key : {"id", "avi"}) {
    if (!d.contains(key)) throw InvalidInputError(where + ": missing '" + key + "'");
  }
  AviLibraryProblem p;
  p.id = d["id"].cast<std::string>();
  if (!py::isinstance<AffineVI>(d["avi"])) throw InvalidInputError(where + ".avi: expected an smcbench.AffineVI");
  p.problem = std::make_shared<const AffineVI>(d["avi"].cast<const AffineVI&>());
  const auto has = [&](const char* key) { return d.contains(key) && !d[key].is_none(); };
  p.source = has("source") ? d["source"].cast<std::string>() : "python";
  if (has("tags")) p.tags = d["tags"].cast<std::vector<std::string>>();
  p.expected = ExpectedAviOutcome(*p.problem);
  if (has("expected")) {
    const std::string text = d["expected"].cast<std::string>();
    const auto expected = ExpectedOutcomeFromString(text);
    if (!expected) {
      throw InvalidInputError(where + ".expected: expected 'unknown', 'solvable' or 'infeasible', got '" + text + "'");
    }
    p.expected = *expected;
  }
  if (has("metadata")) p.metadata = d["metadata"].cast<std::map<std::string, std::string>>();
  if (!has("reference")) return p;
  const py::dict reference = d["reference"].cast<py::dict>();
  const auto has_ref = [&](const char* key) { return reference.contains(key) && !reference[key].is_none(); };
  AviReference& r = p.reference;
  if (has_ref("certificate")) {
    const std::string text = reference["certificate"].cast<std::string>();
    const auto certificate = CertificateFromString(text);
    if (!certificate) throw InvalidInputError(where + ".reference.certificate: unknown certificate '" + text + "'");
    r.reduced.certificate = *certificate;
  }
  if (has_ref("condition")) r.reduced.condition = reference["condition"].cast<double>();
  if (has_ref("z")) r.reduced.z = ToVector(reference["z"], where + ".reference.z");
  if (r.reduced.verified()) {
    const Eigen::Index n = p.problem->size();
    if (r.reduced.z.size() < n) {
      throw InvalidInputError(where + ".reference.z: has " + std::to_string(r.reduced.z.size()) +
                              " entries, fewer than n = " + std::to_string(n));
    }
    r.solution.lambda = r.reduced.z.head(n);
    if (has_ref("mu")) r.solution.mu = ToVector(reference["mu"], where + ".reference.mu");
    if (has_ref("nu")) r.solution.nu = ToVector(reference["nu"], where + ".reference.nu");
  }
  if (has_ref("lambda_unique")) r.lambda_unique = reference["lambda_unique"].cast<bool>();
  if (has_ref("strictly_monotone")) {
    const std::string text = reference["strictly_monotone"].cast<std::string>();
    bool known = false;
    for (MatrixClassAnswer answer :
         {MatrixClassAnswer::kNotDecided, MatrixClassAnswer::kNo, MatrixClassAnswer::kYes}) {
      if (text == ToString(answer)) {
        r.strictly_monotone = answer;
        known = true;
      }
    }
    if (!known) {
      throw InvalidInputError(where + ".reference.strictly_monotone: expected 'yes', 'no' or 'not decided', got '" +
                              text + "'");
    }
  }
  return p;
}

void WriteAviSet(const std::string& path, const py::list& problems, const std::string& name,
                 const std::string& description) {
  AviProblemSet set;
  set.name = name;
  set.description = description;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    set.problems.push_back(AviProblemFromDict(problems[i].cast<py::dict>(), i));
  }
  py::gil_scoped_release release;
  set.Validate();  // ids unique and not empty, a verified λ* of size n
  WriteAviProblemSetFile(set, path);  // and what the reader refuses; written under a temporary name
}

}  // namespace

void BindProblemSet(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_read_problem_set", &ReadSet, "path"_a, "Read a .smcps file into dicts (see smcbench.read_problem_set).");
  m.def("_write_problem_set", &WriteSet, "path"_a, "problems"_a, "name"_a, "description"_a,
        "Write dicts as a .smcps file (see smcbench.write_problem_set).");
  m.def("_problem_set_kind", &ReadKind, "path"_a, "'box' or 'avi': what a .smcps file holds, from its header.");
  m.def("_read_avi_problem_set", &ReadAviSet, "path"_a,
        "Read a .smcps set of AVIs into dicts (see smcbench.read_problem_set).");
  m.def("_write_avi_problem_set", &WriteAviSet, "path"_a, "problems"_a, "name"_a, "description"_a,
        "Write dicts holding AffineVIs as a .smcps set of AVIs (see smcbench.write_problem_set).");
}

}  // namespace smcbench::python
