// Two `smcbench bench` runs of the same suites compared (two builds, commits, machines or option sets): the
// verdicts that changed, and per suite × backend × size band the time ratio B/A with a confidence interval, flagged
// when the whole interval lies beyond a threshold. The engine of `smcbench compare` (tools/smcbench/compare_command.h).
//
// The interval (TimeRatioInterval): the records keep per problem the median, MAD and sample count of the timing
// samples, not the samples, so a rank test (Mann–Whitney, Wilcoxon) on the samples is impossible. The ratio is that
// of the shifted geometric means (SGM) of the per-problem medians, the report's summary statistic, and its interval a
// paired bootstrap: problems resampled with replacement (the same problems for A and B: the runs' spread across
// problems), and each resampled median drawn from its own sampling distribution, log-normal with the standard error
// of a median 1.2533·1.4826·MAD/√samples (the repetitions' spread, which also gives a band of one problem an
// interval). Percentile interval, fixed seed: the same inputs give the same interval on every machine.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bench/replay/size_band.h"
#include "bench/replay/results_io.h"

namespace smcbench {

struct CompareOptions {
  // A group is flagged slower when its interval lies entirely above 1 + threshold, faster when entirely below
  // 1 / (1 + threshold) (the same distance from 1 on a log scale).
  double threshold = 0.05;
  int resamples = 2000;       // bootstrap resamples per group (≥ 100)
  double confidence = 0.95;   // of the percentile interval, in (0, 1)
  std::uint64_t seed = 20261126;
  // Added to every time before the geometric mean, so that sub-microsecond solves near the clock's floor do not
  // dominate it. Smaller than the report's 1 µs: the m ≤ 4 problems solve in a fraction of a microsecond
  // (docs/benchmarks.md), where a 1 µs shift would hide most of a 2× slowdown.
  double shift_seconds = 1e-7;
  // Empty, or InvalidInputError-style text naming the field that is out of range.
  std::string Invalid() const;
};

// What happened to one (suite, problem, start, backend, mode, tolerance) between the runs. Append-only values.
enum class VerdictChangeKind : int {
  kRegression = 0,   // right in A (solved or correctly refused), not in B
  kImprovement = 1,  // not right in A, right in B
  kOther = 2,        // right in both or in neither, but the verdict or the status changed
};
std::string_view ToString(VerdictChangeKind kind);  // "regression", "improvement", "changed"

struct VerdictChange {
  VerdictChangeKind kind = VerdictChangeKind::kOther;
  std::string suite, problem, start, solver, mode;
  double tolerance = 0.0;
  Verdict verdict_a = Verdict::kFailed, verdict_b = Verdict::kFailed;
  SolveStatus status_a = SolveStatus::kNotRun, status_b = SolveStatus::kNotRun;
  std::string message_b;  // B's solver message: why it failed there
};

// One problem solved in both runs: its timing summary in each (ReplayRecord's time_median, time_mad, samples).
struct PairedTiming {
  double median_a = 0.0, mad_a = 0.0;
  int samples_a = 1;
  double median_b = 0.0, mad_b = 0.0;
  int samples_b = 1;
};

enum class TimeFlag : int { kNone = 0, kSlower = 1, kFaster = 2 };  // append-only
std::string_view ToString(TimeFlag flag);  // "", "SLOWER", "faster"

struct TimeRatio {
  double ratio = 1.0;             // SGM(B) / SGM(A) of the medians
  double low = 1.0, high = 1.0;   // the bootstrap interval at CompareOptions::confidence
  TimeFlag flag = TimeFlag::kNone;
};

// The ratio and its interval for one group of problems (see the file comment). Empty pairs: ratio 1, no flag.
TimeRatio TimeRatioInterval(const std::vector<PairedTiming>& pairs, const CompareOptions& options);

struct RatioGroup {
  std::string suite, solver;
  SizeBand band = SizeBand::kTiny;
  int problems = 0;     // solved in both runs (the ones timed)
  double sgm_a = 0.0, sgm_b = 0.0;  // seconds
  TimeRatio time;
};

struct RunComparison {
  // Regressions first, then improvements, then other changes; each in the runs' record order.
  std::vector<VerdictChange> verdict_changes;
  // Suite (run order), backend (first appearance), band: every group with at least one problem solved in both.
  std::vector<RatioGroup> groups;
  int matched_records = 0;
  // "suite|problem|backend|mode" of records only one run holds (other backend lists, or a partial merge).
  std::vector<std::string> only_in_a, only_in_b;

  int regressions() const;
  int slower_groups() const;
  // What CI acts on: a verdict regression or a group flagged slower.
  bool regressed() const { return regressions() > 0 || slower_groups() > 0; }
};

// The first difference between the runs' suites (names, order, problem counts, content checksums) as one line, or
// empty when they may be compared. The same check `merge` applies to shards (ManifestMismatch, bench/replay/jobs.h),
// without its build and options checks: comparing other builds and options is compare's purpose.
std::string SuitesMismatch(const BenchResults& a, const BenchResults& b);

// InvalidInputError when the suites differ ("compare: <difference>") or options are invalid (naming the field).
RunComparison CompareRuns(const BenchResults& a, const BenchResults& b, const CompareOptions& options);

// compare.md: how the runs were compared, verdict changes first, then the ratio table (one row per group) and
// what a flag means. figure_stem: the ratio figure's file stem to link (empty: none).
std::string CompareMarkdown(const RunComparison& comparison, const CompareOptions& options, const std::string& label_a,
                            const std::string& label_b, const std::string& figure_stem);

// The short table for a terminal: counts, the verdict changes (at most max_changes), and the groups (all when at most
// max_groups, else only the flagged ones).
std::string CompareSummaryText(const RunComparison& comparison, const CompareOptions& options,
                               std::size_t max_changes = 10, std::size_t max_groups = 30);

}  // namespace smcbench
