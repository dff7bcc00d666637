// The extension module smcbench._smcbench: the library's errors as Python exceptions, the backend list, and the
// bindings of solve.cc, simulate.cc, problem_set.cc, mcp_suite.cc, bench.cc, avi.cc, judge.cc and results.cc.
// Python users import the package smcbench (__init__.py), which wraps these functions in the documented API
// (docs/python.md).
#include <pybind11/pybind11.h>

#include <string>

#include "problems/io/data_dirs.h"
#include "solvers/core/problem.h"
#include "solvers/registry/registry.h"

namespace py = pybind11;

namespace smcbench::python {

void BindSolve(py::module_& m);
void BindSimulate(py::module_& m);
void BindProblemSet(py::module_& m);
void BindMcpSuite(py::module_& m);
void BindBench(py::module_& m);
void BindAvi(py::module_& m);
void BindJudge(py::module_& m);
void BindResults(py::module_& m);

namespace {

// Every backend with what SolverInfo says about it (`smcbench list`).
py::list Solvers() {
  py::list out;
  for (std::string_view name : SolverNames()) {
    const SolverInfo& info = CreateSolver(name)->info();
    py::dict entry;
    entry["name"] = std::string(info.name);
    entry["algorithm"] = std::string(info.algorithm);
    entry["reference"] = std::string(info.reference);
    entry["dense"] = info.dense;
    entry["sparse"] = info.sparse;
    entry["symmetric_only"] = info.symmetric_only;
    entry["exact"] = info.exact;
    entry["mcp"] = info.mcp;
    entry["default_size_limit"] = info.default_size_limit > 0 ? py::object(py::int_(info.default_size_limit))
                                                              : py::object(py::none());
    entry["options"] = CreateSolver(name)->OptionsHelp();
    out.append(entry);
  }
  return out;
}

// A data folder as every program finds it (problems/io/data_dirs.h): "scenes" or "siconos". __main__.py passes
// them to the packaged command-line program, whose own lookup does not reach the environment's share/ from there.
std::string DataDirectoryOf(const std::string& name) {
  for (DataFolder folder : {DataFolder::kScenes, DataFolder::kSiconosCollection}) {
    if (name == DataFolderName(folder)) return DataDirectory(folder);
  }
  throw InvalidInputError("unknown data folder '" + name + "' (known: scenes, siconos)");
}

}  // namespace
}  // namespace smcbench::python

PYBIND11_MODULE(_smcbench, m) {
  m.doc() = "smcbench's C++ core (use the package smcbench, not this module)";
  // InvalidInputError (bad problem, file, option or name) is a ValueError carrying the C++ message, as its own
  // subclass so callers can tell it from other ValueErrors.
  py::register_exception<smcbench::InvalidInputError>(m, "InvalidInputError", PyExc_ValueError);
  m.def("solvers", &smcbench::python::Solvers, "The registered backends with their capabilities (list of dicts).");
  m.def("_data_directory", &smcbench::python::DataDirectoryOf,
        "The data folder 'scenes' or 'siconos' (DataDirectory).");
  smcbench::python::BindSolve(m);
  smcbench::python::BindSimulate(m);
  smcbench::python::BindProblemSet(m);
  smcbench::python::BindMcpSuite(m);
  smcbench::python::BindBench(m);
  smcbench::python::BindAvi(m);
  smcbench::python::BindJudge(m);
  smcbench::python::BindResults(m);
}
