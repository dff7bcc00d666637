// Two `smcbench bench` runs of the same suites compared (two builds, commits, machines or option sets): what differed
// between the runs (settings, build, machine: bench/compare/run_identity.h), the verdicts that changed, and per
// suite × backend × size band the time ratio B/A with a confidence interval and the median iteration counts,
// flagged when the whole interval, after removing a uniform machine drift, lies beyond the noise floor. The engine
// of `smcbench compare` (tools/smcbench/compare_command.h).
//
// The interval (TimeRatioInterval): the records keep per problem the median, MAD and sample count of the timing
// samples, not the samples, so a rank test (Mann–Whitney, Wilcoxon) on the samples is impossible. The ratio is that
// of the shifted geometric means (SGM) of the per-problem medians, the report's summary statistic, and its interval a
// paired bootstrap: problems resampled with replacement (the same problems for A and B: the runs' spread across
// problems), and each resampled median drawn from its own sampling distribution, log-normal with the standard error
// of a median 1.2533·1.4826·MAD/√samples (the repetitions' spread, which also gives a band of one problem an
// interval). Percentile interval, fixed seed: the same inputs give the same interval on every machine.
//
// The noise floor (NoiseFloors): an A/A calibration of each run from its own repeated samples. With s the median
// over the run's cold solved records of 1.4826·MAD/median (the relative spread of one sample), two repeated samples
// of a typical problem of the run differ by a ratio within exp(±1.96·√2·s) 95 % of the time. A group is flagged only
// when its interval lies beyond the flag limit, the larger of that floor (of either run) and 1 + threshold.
//
// Machine drift (EstimateDrift): two runs of the same build on a shared machine move every group by about the same
// factor. When more than half of the groups agree (their interval, divided by a common factor, reaches the flag
// limit's band) on a factor beyond the band, that factor is reported as drift and every ratio divided by it before
// flagging. The factor is the floor records' ratio (one factorization of M per problem, bench/replay/floor.h: code
// neither run changed, so it moves with the machine only) when the groups agree with it, else the median group ratio
// (from kMinGroupsForDrift groups on). The floor of the small problems is a factorization of a few nanoseconds and
// drifts on its own (seen ×1.02 to ×1.67 between runs whose backends all moved ×1.2), so it confirms a drift but
// does not veto one: a change common to every backend cannot be told from a drift, and is reported as one unless
// CompareOptions::divide_drift is false.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "bench/compare/run_identity.h"
#include "bench/replay/size_band.h"
#include "bench/replay/results_io.h"

namespace smcbench {

struct CompareOptions {
  // The minimum relative change: a group is flagged slower when its interval (after the drift) lies entirely above
  // the flag limit max(1 + threshold, noise floor), faster when entirely below its inverse (the same distance from 1
  // on a log scale).
  double threshold = 0.05;
  int resamples = 2000;       // bootstrap resamples per group (≥ 100)
  double confidence = 0.95;   // of the percentile interval, in (0, 1)
  std::uint64_t seed = 20261126;
  // Added to every time before the geometric mean, so that sub-microsecond solves near the clock's floor do not
  // dominate it. Smaller than the report's 1 µs: the m ≤ 4 problems solve in a fraction of a microsecond
  // (docs/benchmarks.md), where a 1 µs shift would hide most of a 2× slowdown.
  double shift_seconds = 1e-7;
  // Divide a uniform drift (EstimateDrift) out of the ratios before flagging. False (`compare --keep-drift`): report
  // it, flag on the raw ratios: on a dedicated machine, where every backend slower by one factor is a real slowdown.
  bool divide_drift = true;
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
  int iterations_a = 0, iterations_b = 0;
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
  double iterations_a = 0.0, iterations_b = 0.0;  // median over the problems
  // The raw ratio and interval; its flag is the comparison's: against the flag limit, after dividing by the drift.
  TimeRatio time;
};

// The A/A calibration of each run (file comment): exp(1.96·√2·s), 1 when no record has two samples or spread.
struct NoiseFloor {
  double a = 1.0, b = 1.0;
  double spread_a = 0.0, spread_b = 0.0;  // s: median relative spread of one sample (1.4826·MAD/median)
  int records_a = 0, records_b = 0;       // cold solved records with at least two samples
};
NoiseFloor NoiseFloors(const BenchResults& a, const BenchResults& b);

// Where the drift factor comes from. Append-only values.
enum class DriftSource : int {
  kNone = 0,    // no uniform move beyond the band: ratios are not normalized
  kFloor = 1,   // the floor records' ratio
  kGroups = 2,  // the median group ratio (no floor records, or the groups disagree with theirs)
};
std::string_view ToString(DriftSource source);  // "none", "floor", "groups"

inline constexpr int kMinGroupsForDrift = 3;

// Whether a ratio lies in [1/limit, limit]: inside the flag limit, neither slower nor faster.
inline bool WithinBand(double ratio, double limit) { return ratio <= limit && ratio >= 1.0 / limit; }

struct Drift {
  DriftSource source = DriftSource::kNone;
  double factor = 1.0;          // the common ratio found (1 when source is none)
  bool divided = false;         // the ratios were divided by factor before flagging (CompareOptions::divide_drift)
  int agreeing_groups = 0;      // groups whose interval ÷ factor reaches the band [1/limit, limit]
  double median_group_ratio = 1.0;
  bool has_floor = false;       // floor records timed in both runs
  int floor_problems = 0;
  TimeRatio floor;              // their ratio B/A and interval (no flag)
  double divisor() const { return divided ? factor : 1.0; }
};
// The drift of groups (their raw ratios and intervals) given the floor records' pairs and the flag limit.
Drift EstimateDrift(const std::vector<RatioGroup>& groups, const std::vector<PairedTiming>& floor_pairs,
                    double flag_limit, const CompareOptions& options);

struct RunComparison {
  // Regressions first, then improvements, then other changes; each in the runs' record order.
  std::vector<VerdictChange> verdict_changes;
  // Suite (run order), backend (first appearance), band: every group with at least one problem solved in both.
  std::vector<RatioGroup> groups;
  int matched_records = 0;
  // "suite|problem|backend|mode" of records only one run holds (other backend lists, or a partial merge).
  std::vector<std::string> only_in_a, only_in_b;
  NoiseFloor noise;
  double flag_limit = 1.0;  // max(1 + threshold, noise.a, noise.b)
  Drift drift;
  // The runs' settings, build and machine side by side (IdentityRows); empty unless the caller fills it in.
  std::vector<IdentityRow> identity;

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

// The results folders a and b (as `smcbench bench --out` wrote them) compared, with their settings, build and
// machine side by side (identity): what `smcbench compare A B` and Python's smcbench.compare both report.
// InvalidInputError for an unreadable folder, as CompareRuns for runs that cannot be compared.
RunComparison CompareRunFolders(const std::string& a, const std::string& b, const CompareOptions& options);

}  // namespace smcbench
