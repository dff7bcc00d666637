#include "bench/compare/compare_runs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <tuple>

#include "bench/replay/jobs.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

// Standard error of a sample median from the MAD: 1.4826·MAD estimates σ of a normal sample, and the median's
// standard error is √(π/2)·σ/√n.
constexpr double kMadToSigma = 1.4826;
constexpr double kMedianStandardError = 1.2533;
constexpr double kPi = 3.14159265358979323846;

bool Right(Verdict v) { return v == Verdict::kSolved || v == Verdict::kCorrectlyRefused; }

double ShiftedGeometricMean(const std::vector<double>& times, double shift) {
  double log_sum = 0.0;
  for (double t : times) log_sum += std::log(t + shift);
  return std::exp(log_sum / static_cast<double>(times.size())) - shift;
}

// σ of log(median): the median's standard error relative to the median (0 without spread or samples).
double LogMedianSigma(double median, double mad, int samples) {
  if (!(median > 0.0) || !(mad > 0.0) || samples < 1) return 0.0;
  return kMedianStandardError * kMadToSigma * mad / (median * std::sqrt(static_cast<double>(samples)));
}

// Uniform and normal draws written out from the 64-bit Mersenne twister, whose output the standard fixes: the
// library's distributions differ between standard libraries, and the interval must not.
class Draws {
 public:
  explicit Draws(std::uint64_t seed) : engine_(seed) {}
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  std::size_t Index(std::size_t n) { return static_cast<std::size_t>(Uniform() * static_cast<double>(n)); }
  double Normal() {  // Box–Muller
    const double u = 1.0 - Uniform(), v = Uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * kPi * v);
  }

 private:
  std::mt19937_64 engine_;
};

double Quantile(std::vector<double> sorted_values, double p) {
  std::sort(sorted_values.begin(), sorted_values.end());
  const double position = p * static_cast<double>(sorted_values.size() - 1);
  const std::size_t below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, sorted_values.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return sorted_values[below] * (1.0 - fraction) + sorted_values[above] * fraction;
}

std::string RecordKey(const ReplayRecord& r) {
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%.17g", r.tolerance);
  return r.suite + "|" + r.problem + (r.start.empty() ? "" : "@" + r.start) + "|" + r.solver + "|" + r.mode + "|" +
         tolerance;
}

std::string ShortKey(const ReplayRecord& r) {
  return r.suite + "|" + r.problem + (r.start.empty() ? "" : "@" + r.start) + "|" + r.solver + "|" + r.mode;
}

// Every record of a run (cold ones, then the tolerance sweep's), in run order.
std::vector<const ReplayRecord*> AllRecords(const BenchResults& results) {
  std::vector<const ReplayRecord*> all;
  for (const SuiteResults& suite : results.suites) {
    for (const ReplayRecord& r : suite.replay.records) all.push_back(&r);
    for (const ReplayRecord& r : suite.replay.sweep) all.push_back(&r);
  }
  return all;
}

// Two-sided 95 % normal quantile, and the √2 of a ratio of two independent samples: the noise floor's constants.
constexpr double kZ95 = 1.96;
constexpr double kSqrt2 = 1.41421356237309505;

double MedianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  return Quantile(std::move(values), 0.5);
}

// The relative spreads of one sample (1.4826·MAD/median) of a run's cold solved records with at least two samples.
std::vector<double> SampleSpreads(const BenchResults& run) {
  std::vector<double> spreads;
  for (const SuiteResults& suite : run.suites) {
    for (const ReplayRecord& r : suite.replay.records) {
      if (r.mode != "cold" || r.verdict != Verdict::kSolved || r.samples < 2 || !(r.time_median > 0.0)) continue;
      spreads.push_back(kMadToSigma * r.time_mad / r.time_median);
    }
  }
  return spreads;
}

// Whether an interval divided by factor reaches the band [1/limit, limit].
bool ReachesBand(const TimeRatio& t, double factor, double limit) {
  return t.low / factor <= limit && t.high / factor >= 1.0 / limit;
}

int AgreeingGroups(const std::vector<RatioGroup>& groups, double factor, double limit) {
  return static_cast<int>(std::count_if(groups.begin(), groups.end(), [&](const RatioGroup& g) {
    return ReachesBand(g.time, factor, limit);
  }));
}

TimeFlag FlagOf(double low, double high, double limit) {
  if (low > limit) return TimeFlag::kSlower;
  if (high < 1.0 / limit) return TimeFlag::kFaster;
  return TimeFlag::kNone;
}

// The floor records both runs timed (status solved in both), paired as the groups' problems are.
std::vector<PairedTiming> FloorPairs(const BenchResults& a, const BenchResults& b) {
  std::map<std::string, const ReplayRecord*> in_b;
  for (const SuiteResults& suite : b.suites) {
    for (const ReplayRecord& r : suite.replay.floor) in_b.emplace(RecordKey(r), &r);
  }
  std::vector<PairedTiming> pairs;
  for (const SuiteResults& suite : a.suites) {
    for (const ReplayRecord& ra : suite.replay.floor) {
      const auto found = in_b.find(RecordKey(ra));
      if (found == in_b.end()) continue;
      const ReplayRecord& rb = *found->second;
      if (ra.status != SolveStatus::kSolved || rb.status != SolveStatus::kSolved) continue;
      if (!(ra.time_median > 0.0) || !(rb.time_median > 0.0)) continue;
      pairs.push_back({ra.time_median, ra.time_mad, ra.samples, rb.time_median, rb.time_mad, rb.samples});
    }
  }
  return pairs;
}

}  // namespace

NoiseFloor NoiseFloors(const BenchResults& a, const BenchResults& b) {
  NoiseFloor out;
  const auto floor_of = [](const std::vector<double>& spreads, double* spread) {
    *spread = MedianOf(spreads);
    return std::exp(kZ95 * kSqrt2 * *spread);
  };
  const std::vector<double> spreads_a = SampleSpreads(a), spreads_b = SampleSpreads(b);
  out.a = floor_of(spreads_a, &out.spread_a);
  out.b = floor_of(spreads_b, &out.spread_b);
  out.records_a = static_cast<int>(spreads_a.size());
  out.records_b = static_cast<int>(spreads_b.size());
  return out;
}

std::string_view ToString(DriftSource source) {
  switch (source) {
    case DriftSource::kNone: return "none";
    case DriftSource::kFloor: return "floor";
    case DriftSource::kGroups: return "groups";
  }
  return "?";
}

Drift EstimateDrift(const std::vector<RatioGroup>& groups, const std::vector<PairedTiming>& floor_pairs,
                    double flag_limit, const CompareOptions& options) {
  Drift out;
  std::vector<double> log_ratios;
  for (const RatioGroup& g : groups) log_ratios.push_back(std::log(g.time.ratio));
  out.median_group_ratio = groups.empty() ? 1.0 : std::exp(MedianOf(log_ratios));
  out.has_floor = !floor_pairs.empty();
  out.floor_problems = static_cast<int>(floor_pairs.size());
  if (out.has_floor) {
    out.floor = TimeRatioInterval(floor_pairs, options);
    out.floor.flag = TimeFlag::kNone;
  }
  // A factor is the drift when it lies beyond the band and more than half of the groups agree with it.
  const auto try_factor = [&](double factor, DriftSource source) {
    if (groups.empty() || WithinBand(factor, flag_limit)) return false;
    const int agreeing = AgreeingGroups(groups, factor, flag_limit);
    if (2 * agreeing <= static_cast<int>(groups.size())) return false;
    out.source = source;
    out.factor = factor;
    out.divided = options.divide_drift;
    out.agreeing_groups = agreeing;
    return true;
  };
  if (out.has_floor && try_factor(out.floor.ratio, DriftSource::kFloor)) return out;
  if (static_cast<int>(groups.size()) >= kMinGroupsForDrift) {
    try_factor(out.median_group_ratio, DriftSource::kGroups);
  }
  return out;
}

std::string CompareOptions::Invalid() const {
  if (!(threshold >= 0.0) || !std::isfinite(threshold)) return "threshold must be a finite number >= 0";
  if (resamples < 100) return "resamples must be at least 100";
  if (!(confidence > 0.0 && confidence < 1.0)) return "confidence must lie in (0, 1)";
  if (!(shift_seconds >= 0.0) || !std::isfinite(shift_seconds)) return "shift_seconds must be a finite number >= 0";
  return "";
}

std::string_view ToString(VerdictChangeKind kind) {
  switch (kind) {
    case VerdictChangeKind::kRegression: return "regression";
    case VerdictChangeKind::kImprovement: return "improvement";
    case VerdictChangeKind::kOther: return "changed";
  }
  return "?";
}

std::string_view ToString(TimeFlag flag) {
  switch (flag) {
    case TimeFlag::kNone: return "";
    case TimeFlag::kSlower: return "SLOWER";
    case TimeFlag::kFaster: return "faster";
  }
  return "?";
}

TimeRatio TimeRatioInterval(const std::vector<PairedTiming>& pairs, const CompareOptions& options) {
  TimeRatio out;
  if (pairs.empty()) return out;
  const std::size_t n = pairs.size();
  const double shift = options.shift_seconds;
  std::vector<double> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    a[i] = pairs[i].median_a;
    b[i] = pairs[i].median_b;
  }
  out.ratio = ShiftedGeometricMean(b, shift) / ShiftedGeometricMean(a, shift);
  std::vector<double> sigma_a(n), sigma_b(n);
  for (std::size_t i = 0; i < n; ++i) {
    sigma_a[i] = LogMedianSigma(pairs[i].median_a, pairs[i].mad_a, pairs[i].samples_a);
    sigma_b[i] = LogMedianSigma(pairs[i].median_b, pairs[i].mad_b, pairs[i].samples_b);
  }
  Draws draws(options.seed);
  std::vector<double> ratios(static_cast<std::size_t>(options.resamples));
  for (double& ratio : ratios) {
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = draws.Index(n);
      a[k] = pairs[i].median_a * std::exp(sigma_a[i] * draws.Normal());
      b[k] = pairs[i].median_b * std::exp(sigma_b[i] * draws.Normal());
    }
    ratio = ShiftedGeometricMean(b, shift) / ShiftedGeometricMean(a, shift);
  }
  const double tail = (1.0 - options.confidence) / 2.0;
  out.low = Quantile(ratios, tail);
  out.high = Quantile(ratios, 1.0 - tail);
  if (out.low > 1.0 + options.threshold) {
    out.flag = TimeFlag::kSlower;
  } else if (out.high < 1.0 / (1.0 + options.threshold)) {
    out.flag = TimeFlag::kFaster;
  }
  return out;
}

int RunComparison::regressions() const {
  return static_cast<int>(std::count_if(verdict_changes.begin(), verdict_changes.end(), [](const VerdictChange& c) {
    return c.kind == VerdictChangeKind::kRegression;
  }));
}

int RunComparison::slower_groups() const {
  return static_cast<int>(std::count_if(groups.begin(), groups.end(), [](const RatioGroup& g) {
    return g.time.flag == TimeFlag::kSlower;
  }));
}

std::string SuitesMismatch(const BenchResults& a, const BenchResults& b) {
  // Manifests holding only the suites: ManifestMismatch then finds nothing but a suite difference.
  RunManifest manifest_a, manifest_b;
  for (const SuiteResults& s : a.suites) {
    manifest_a.suites.push_back({s.suite, s.description, s.problems, s.checksum, {}});
  }
  for (const SuiteResults& s : b.suites) {
    manifest_b.suites.push_back({s.suite, s.description, s.problems, s.checksum, {}});
  }
  return ManifestMismatch(manifest_a, manifest_b);
}

RunComparison CompareRuns(const BenchResults& a, const BenchResults& b, const CompareOptions& options) {
  if (const std::string invalid = options.Invalid(); !invalid.empty()) {
    throw InvalidInputError("compare: " + invalid);
  }
  if (const std::string mismatch = SuitesMismatch(a, b); !mismatch.empty()) {
    throw InvalidInputError("compare: the runs cannot be compared: " + mismatch);
  }
  RunComparison out;
  std::map<std::string, const ReplayRecord*> in_b;
  for (const ReplayRecord* r : AllRecords(b)) in_b.emplace(RecordKey(*r), r);
  std::map<std::string, bool> matched_b;

  // Groups keyed by (suite index, backend's first appearance, band), so the table follows the run's order.
  std::map<std::string, std::size_t> solver_order;
  std::map<std::tuple<std::size_t, std::size_t, int>, std::pair<RatioGroup, std::vector<PairedTiming>>> groups;
  std::vector<VerdictChange> improvements, others;
  for (std::size_t s = 0; s < a.suites.size(); ++s) {
    std::vector<const ReplayRecord*> records;
    for (const ReplayRecord& r : a.suites[s].replay.records) records.push_back(&r);
    for (const ReplayRecord& r : a.suites[s].replay.sweep) records.push_back(&r);
    for (const ReplayRecord* ra : records) {
      const std::string key = RecordKey(*ra);
      const auto found = in_b.find(key);
      if (found == in_b.end()) {
        out.only_in_a.push_back(ShortKey(*ra));
        continue;
      }
      const ReplayRecord& rb = *found->second;
      matched_b[key] = true;
      ++out.matched_records;
      if (ra->verdict != rb.verdict || ra->status != rb.status) {
        VerdictChange change;
        change.kind = Right(ra->verdict) && !Right(rb.verdict)   ? VerdictChangeKind::kRegression
                      : !Right(ra->verdict) && Right(rb.verdict) ? VerdictChangeKind::kImprovement
                                                                 : VerdictChangeKind::kOther;
        change.suite = ra->suite;
        change.problem = ra->problem;
        change.start = ra->start;
        change.solver = ra->solver;
        change.mode = ra->mode;
        change.tolerance = ra->tolerance;
        change.verdict_a = ra->verdict;
        change.verdict_b = rb.verdict;
        change.status_a = ra->status;
        change.status_b = rb.status;
        change.message_b = rb.message;
        (change.kind == VerdictChangeKind::kRegression    ? out.verdict_changes
         : change.kind == VerdictChangeKind::kImprovement ? improvements
                                                          : others)
            .push_back(std::move(change));
      }
      // Times of the cold solves both runs got right as solved; the sweep is a study of its own.
      if (ra->mode != "cold" || ra->verdict != Verdict::kSolved || rb.verdict != Verdict::kSolved) continue;
      const std::size_t solver_index = solver_order.emplace(ra->solver, solver_order.size()).first->second;
      auto& [group, pairs] = groups[{s, solver_index, static_cast<int>(SizeBandOf(ra->size))}];
      group.suite = ra->suite;
      group.solver = ra->solver;
      group.band = SizeBandOf(ra->size);
      pairs.push_back({ra->time_median, ra->time_mad, ra->samples, rb.time_median, rb.time_mad, rb.samples,
                       ra->iterations, rb.iterations});
    }
  }
  for (auto& change : improvements) out.verdict_changes.push_back(std::move(change));
  for (auto& change : others) out.verdict_changes.push_back(std::move(change));
  for (const ReplayRecord* rb : AllRecords(b)) {
    if (!matched_b.count(RecordKey(*rb))) out.only_in_b.push_back(ShortKey(*rb));
  }
  for (auto& [key, entry] : groups) {
    auto& [group, pairs] = entry;
    group.problems = static_cast<int>(pairs.size());
    std::vector<double> times_a, times_b, iterations_a, iterations_b;
    for (const PairedTiming& p : pairs) {
      times_a.push_back(p.median_a);
      times_b.push_back(p.median_b);
      iterations_a.push_back(p.iterations_a);
      iterations_b.push_back(p.iterations_b);
    }
    group.sgm_a = ShiftedGeometricMean(times_a, options.shift_seconds);
    group.sgm_b = ShiftedGeometricMean(times_b, options.shift_seconds);
    group.iterations_a = MedianOf(iterations_a);
    group.iterations_b = MedianOf(iterations_b);
    group.time = TimeRatioInterval(pairs, options);
    out.groups.push_back(std::move(group));
  }
  out.noise = NoiseFloors(a, b);
  out.flag_limit = std::max({1.0 + options.threshold, out.noise.a, out.noise.b});
  out.drift = EstimateDrift(out.groups, FloorPairs(a, b), out.flag_limit, options);
  for (RatioGroup& g : out.groups) {
    g.time.flag = FlagOf(g.time.low / out.drift.divisor(), g.time.high / out.drift.divisor(), out.flag_limit);
  }
  return out;
}

RunComparison CompareRunFolders(const std::string& a, const std::string& b, const CompareOptions& options) {
  nlohmann::json environment_a, environment_b;
  const BenchResults results_a = ReadBenchResults(a, &environment_a);
  const BenchResults results_b = ReadBenchResults(b, &environment_b);
  RunComparison comparison = CompareRuns(results_a, results_b, options);
  comparison.identity = IdentityRows(MakeRunIdentity(results_a, environment_a, ReadRunOptions(a)),
                                     MakeRunIdentity(results_b, environment_b, ReadRunOptions(b)));
  return comparison;
}

}  // namespace smcbench
