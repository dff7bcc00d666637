// What the report's opening summary and its floor columns compute, as pure functions over results (no text, no
// files), rendered by report_markdown.h: the problem class of a record from its tags (matrix
// class × size band × bounds), the floor of each problem (one factorization of its matrix, bench/replay/floor.h) and
// a backend's times against it, per class the fastest correct and the most reliable backend with its gap to the
// floor, and per backend its failures with their most common cause.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "bench/analysis/record_facts.h"
#include "bench/analysis/suite_tables.h"
#include "bench/replay/results_io.h"
#include "bench/replay/size_band.h"

namespace smcbench {

// The matrix class of a record's problem, from its tags (ReplayRecord::tags) and storage: "sparse" (stored sparse,
// or tagged "sparse"; the generic sparse path's copies of dense problems are not), "SPD" ("spd", or "symmetric"
// and "positive_definite"), "nonsymmetric P" ("pmatrix", "p_matrix", "diagdom", or a tag starting "nonsym"),
// else "general"; an MCP suite's records are "MCP", the AVI suite's "AVI" (told by the flags, or by the tag
// kMcpSuiteTag / kAviSuiteTag that PooledColdRecords adds).
inline constexpr const char* kMcpSuiteTag = "mcp-suite";
inline constexpr const char* kAviSuiteTag = "avi-suite";
std::string MatrixClassOf(const ReplayRecord& record, bool mcp_suite = false, bool avi_suite = false);
// The bounds of a record's problem from its tags: "LCP" ("lcp"), "relay" ("relay"), "mixed" ("mixed", "mlcp",
// "box"), else "untagged".
std::string BoundsClassOf(const ReplayRecord& record);

// A problem class: matrix class × size band × bounds.
struct ProblemClass {
  std::string matrix;
  SizeBand band = SizeBand::kTiny;
  std::string bounds;
  bool operator<(const ProblemClass& o) const;
  bool operator==(const ProblemClass& o) const;
};
// The class of a record: MatrixClassOf (mcp, avi: the suite's kind), its size band, BoundsClassOf.
ProblemClass ClassOfRecord(const ReplayRecord& record, bool mcp_suite, bool avi_suite);
// "SPD · relay" (the band is a column of its own).
std::string ClassName(const ProblemClass& c);

// The floor's median time per instance of one suite (ReplayResults::floor, keyed by InstanceOf); empty when the
// run measured none.
std::map<std::string, double> FloorTimes(const SuiteResults& suite);

// The solver's time over the floor on each instance of records where it is correct (solved or correctly refused)
// and the floor was measured, sorted. Empty when there is none.
std::vector<double> FloorRatios(const std::vector<ReplayRecord>& records, const std::map<std::string, double>& floor,
                                const std::string& solver);

// One row of the summary: a class, its fastest correct backend and its most reliable one.
struct ClassSummary {
  ProblemClass problem_class;
  int problems = 0;  // instances (suite × problem [× start]) in the class
  // The fastest correct: among the backends with no wrong answer in the class, the smallest SGM time (failures
  // counted at the penalty of SummarizeRecords, so a backend that fails often is not the fastest). Empty when every
  // backend gave a wrong answer.
  std::string fastest;
  int fastest_correct = 0;
  double fastest_sgm = kNaN;
  // Its time over the floor, median over the instances it got right where the floor was measured (NaN: none), and
  // over how many.
  double fastest_over_floor = kNaN;
  int floor_instances = 0;
  // The most reliable: the most correct answers, then the fewest wrong ones, then the smaller SGM time.
  std::string most_reliable;
  int reliable_correct = 0;
  int reliable_wrong = 0;
};

// The cold records of every suite of the run (box, MCP, AVI; not the sweep, the warm track or records with mode
// "cached"), each named "<suite>/<instance>" in ReplayRecord::problem so that suites never share an instance, an MCP
// or AVI suite's records tagged kMcpSuiteTag / kAviSuiteTag, with the floor times keyed the same way in *floor
// (when given).
std::vector<ReplayRecord> PooledColdRecords(const BenchResults& results, std::map<std::string, double>* floor);

// Per class (sorted by matrix class, bounds, band) over PooledColdRecords: the summary rows.
std::vector<ClassSummary> SummarizeClasses(const BenchResults& results, double time_limit_seconds = 10.0);

// A backend's answers that are not correct over the whole run, with their most common cause.
struct BackendFailures {
  std::string solver;
  int records = 0;      // cold records of the backend, every suite
  int not_correct = 0;  // failed or wrong
  int wrong = 0;        // wrongly claimed, inaccurate, wrongly refused
  FailureReason cause;  // over the records not correct (count 0: none)
  // One entry per record not correct, in the order of the results: suite/instance, class, status, verdict, message.
  struct Entry {
    std::string instance;
    std::string problem_class;  // ClassName and the band
    SolveStatus status = SolveStatus::kNotRun;
    Verdict verdict = Verdict::kFailed;
    std::string message;
  };
  std::vector<Entry> entries;
};
// Every backend of the run's cold records, in the order they first appear.
std::vector<BackendFailures> FailuresPerBackend(const BenchResults& results);

}  // namespace smcbench
