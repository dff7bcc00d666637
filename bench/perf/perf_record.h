// The perf gate's records: instructions per solve or per step (callgrind, deterministic) and wall-clock per unit
// (information only) for a fixed set of figures, the comparison against a committed baseline, and the history CSV.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace smcbench {

// One tracked figure: a backend on a problem (unit "solve") or a time-stepper run (unit "step").
struct PerfFigure {
  std::string id;              // "solve/<problem>/<backend>" or "step/<scene>/<backend>"
  std::string unit;            // "solve" or "step"
  std::int64_t units = 0;      // solves or steps measured (the instruction count is divided by it)
  std::string status;          // "solved", or what the backend said when it did not solve (then not gated)
  double instructions = -1.0;  // per unit; < 0: not measured (the run was not under callgrind)
  double ns = -1.0;            // wall-clock per unit, median of the samples; < 0: not measured
  double ns_min = -1.0, ns_max = -1.0;  // spread of the samples
};

struct PerfRun {
  nlohmann::json environment;  // BenchEnvironment(): git SHA, compiler, flags, build type, CPU, date
  std::vector<PerfFigure> figures;

  // The figure with this id, or null.
  const PerfFigure* Find(const std::string& id) const;
};

// JSON format "smcbench-perf/1". Read/Write throw InvalidInputError naming the file or the field.
nlohmann::json ToJson(const PerfRun& run);
PerfRun PerfRunFromJson(const nlohmann::json& document);
PerfRun ReadPerfRun(const std::string& path);
void WritePerfRun(const PerfRun& run, const std::string& path);

// The instruction counts of instructions_run with the wall-clock numbers of wallclock_run (matched by id).
PerfRun MergePerfRuns(const PerfRun& instructions_run, const PerfRun& wallclock_run);

enum class PerfVerdict {
  kSame,           // within the threshold
  kRegressed,      // more instructions than baseline × (1 + threshold): fails the gate
  kImproved,       // fewer than baseline × (1 − threshold): passes; refresh the baseline with tools/perf-update
  kStatusChanged,  // solved in the baseline, not now (or the reverse): fails the gate
  kMissing,        // in the baseline, not measured now: fails the gate
  kNew,            // measured now, not in the baseline: information
};
const char* ToString(PerfVerdict verdict);

struct PerfRow {
  std::string id;
  double baseline_instructions = -1.0, instructions = -1.0;
  double ratio = -1.0;  // instructions / baseline_instructions; < 0 when either is missing
  double baseline_ns = -1.0, ns = -1.0;  // information only
  PerfVerdict verdict = PerfVerdict::kSame;
};

struct PerfComparison {
  double threshold = 0.05;
  std::vector<PerfRow> rows;  // every figure of either run, in baseline order then new ones
  // Why the runs are not comparable (different compiler, flags or build type; no instruction counts); empty if
  // they are. A non-comparable pair fails the gate.
  std::vector<std::string> incomparable;
  bool failed() const;
  int count(PerfVerdict verdict) const;
};

// threshold in (0, 1): 0.05 fails on a regression of more than 5 %. Throws InvalidInputError on a bad threshold.
PerfComparison ComparePerfRuns(const PerfRun& baseline, const PerfRun& current, double threshold);

// 12345678 → "12.35 M", 12345 → "12.3 k", 123 → "123"; "-" when not measured (< 0).
std::string FormatInstructions(double value);

// Markdown: a one-line verdict, then the table of every figure (baseline, now, ratio, verdict, wall-clock).
std::string FormatComparison(const PerfComparison& comparison);

// The history: one CSV line per tracked figure and run —
//   date,git_sha,id,unit,instructions,baseline_instructions,ratio,ns
// The header is written when the file is new or empty. Throws InvalidInputError if the file cannot be written.
void AppendPerfHistory(const std::string& path, const PerfRun& current, const PerfComparison& comparison);

struct PerfHistoryRow {
  std::string date, git_sha, id, unit;
  double instructions = -1.0, baseline_instructions = -1.0, ratio = -1.0, ns = -1.0;
};
// Throws InvalidInputError naming the file and line on a malformed history.
std::vector<PerfHistoryRow> ReadPerfHistory(const std::string& path);

}  // namespace smcbench
