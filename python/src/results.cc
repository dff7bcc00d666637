// smcbench.report, smcbench.report_tables and smcbench.compare: the report of a bench results folder (`smcbench
// report DIR`, bench/analysis/report_markdown.h), its tables (bench/analysis/report_tables.h) and the comparison of
// two (`smcbench compare A B`, bench/compare/compare_runs.h), through the same C++ functions the commands call.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bench/compare/compare_output.h"
#include "bench/compare/compare_render.h"
#include "bench/replay/results_io.h"
#include "bench/analysis/report_markdown.h"
#include "bench/analysis/report_tables.h"

namespace py = pybind11;

namespace smcbench::python {
namespace {

// WriteBenchReport on dir (dir/results.json in, dir/report.md and, with plots, its PNGs out): the markdown.
std::string Report(const std::string& dir, bool plots) {
  py::gil_scoped_release release;
  return WriteBenchReport(dir, plots);
}

// ReportTables of dir/results.json: a list of (name, columns, rows), each row a list of floats and strings.
py::list Tables(const std::string& dir) {
  std::vector<ReportTable> tables;
  {
    py::gil_scoped_release release;
    tables = ReportTables(ReadBenchResults(dir, nullptr));
  }
  py::list out;
  for (const ReportTable& t : tables) {
    py::list rows;
    for (const auto& row : t.rows) {
      py::list cells;
      for (const TableCell& cell : row) {
        if (const double* v = std::get_if<double>(&cell)) {
          cells.append(py::float_(*v));
        } else {
          cells.append(py::str(std::get<std::string>(cell)));
        }
      }
      rows.append(cells);
    }
    out.append(py::make_tuple(t.name, t.columns, rows));
  }
  return out;
}

py::dict VerdictChangeToDict(const VerdictChange& c) {
  py::dict out;
  out["kind"] = std::string(ToString(c.kind));
  out["suite"] = c.suite;
  out["problem"] = c.problem;
  out["start"] = c.start;
  out["solver"] = c.solver;
  out["mode"] = c.mode;
  out["tolerance"] = c.tolerance;
  out["verdict_a"] = std::string(ToString(c.verdict_a));
  out["verdict_b"] = std::string(ToString(c.verdict_b));
  out["status_a"] = std::string(ToString(c.status_a));
  out["status_b"] = std::string(ToString(c.status_b));
  out["message_b"] = c.message_b;
  return out;
}

py::dict RatioGroupToDict(const RatioGroup& g) {
  py::dict out;
  out["suite"] = g.suite;
  out["solver"] = g.solver;
  out["band"] = std::string(ShortName(g.band));
  out["problems"] = g.problems;
  out["sgm_a"] = g.sgm_a;
  out["sgm_b"] = g.sgm_b;
  out["ratio"] = g.time.ratio;
  out["low"] = g.time.low;
  out["high"] = g.time.high;
  out["flag"] = std::string(ToString(g.time.flag));
  return out;
}

// CompareRuns of the folders a and b (labels: how compare.md names them), with what `smcbench compare` prints
// (summary) and writes (markdown: compare.md; data: compare.json) and the comparison's parts. out: a folder to write
// them to as `smcbench compare --out` does, with the ratio figure when plots (WriteComparisonFolder), or empty;
// figure_error: why a figure asked for was not drawn.
py::dict Compare(const std::string& a, const std::string& b, const std::string& label_a, const std::string& label_b,
                 double threshold, int resamples, double confidence, bool keep_drift, const std::string& out_dir,
                 bool plots) {
  CompareOptions options;
  options.threshold = threshold;
  options.resamples = resamples;
  options.confidence = confidence;
  options.divide_drift = !keep_drift;
  RunComparison comparison;
  ComparisonFiles files;
  {
    py::gil_scoped_release release;
    comparison = CompareRunFolders(a, b, options);
    if (!out_dir.empty()) files = WriteComparisonFolder(comparison, options, label_a, label_b, out_dir, plots);
  }
  py::dict out;
  out["summary"] = CompareSummaryText(comparison, options);
  out["markdown"] = CompareMarkdown(comparison, options, label_a, label_b, files.figure_stem);
  out["figure_error"] = files.figure_error;
  out["data"] = CompareJson(comparison, options, label_a, label_b).dump(1);
  out["regressed"] = comparison.regressed();
  out["regressions"] = comparison.regressions();
  out["slower_groups"] = comparison.slower_groups();
  out["matched_records"] = comparison.matched_records;
  py::list changes, groups;
  for (const VerdictChange& c : comparison.verdict_changes) changes.append(VerdictChangeToDict(c));
  for (const RatioGroup& g : comparison.groups) groups.append(RatioGroupToDict(g));
  out["verdict_changes"] = changes;
  out["groups"] = groups;
  out["only_in_a"] = comparison.only_in_a;
  out["only_in_b"] = comparison.only_in_b;
  return out;
}

}  // namespace

void BindResults(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_report", &Report, "dir"_a, "plots"_a,
        "Write dir/report.md from dir/results.json as `smcbench report` does; returns the markdown.");
  m.def("_report_tables", &Tables, "dir"_a,
        "The report's tables of dir/results.json (bench/analysis/report_tables.h): a list of (name, columns, rows).");
  m.def("_compare", &Compare, "a"_a, "b"_a, "label_a"_a, "label_b"_a, "threshold"_a, "resamples"_a, "confidence"_a,
        "keep_drift"_a, "out"_a, "plots"_a, "Compare two bench results folders as `smcbench compare` does (see smcbench.compare); returns a dict.");
}

}  // namespace smcbench::python
