#include "bench/compare/compare_runs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <sstream>
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

std::string Seconds(double s) {
  char text[32];
  if (s >= 1.0) {
    std::snprintf(text, sizeof text, "%.3g s", s);
  } else if (s >= 1e-3) {
    std::snprintf(text, sizeof text, "%.3g ms", s * 1e3);
  } else if (s >= 1e-6) {
    std::snprintf(text, sizeof text, "%.3g µs", s * 1e6);
  } else {
    std::snprintf(text, sizeof text, "%.3g ns", s * 1e9);
  }
  return text;
}

std::string Ratio(double r) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", r);
  return text;
}

std::string ChangeLine(const VerdictChange& c) {
  std::string line = std::string(ToString(c.kind)) + ": " + c.suite + " " + c.problem +
                     (c.start.empty() ? "" : "@" + c.start) + " " + c.solver +
                     (c.mode == "cold" ? "" : " " + c.mode + " tol " + Ratio(c.tolerance)) + ": " +
                     std::string(ToString(c.verdict_a)) + " (" + std::string(ToString(c.status_a)) + ") -> " +
                     std::string(ToString(c.verdict_b)) + " (" + std::string(ToString(c.status_b)) + ")";
  if (!c.message_b.empty() && !Right(c.verdict_b)) line += ": " + c.message_b;
  return line;
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

bool WithinBand(double ratio, double limit) { return ratio <= limit && ratio >= 1.0 / limit; }

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

// "×1.12": a factor to three digits.
std::string Times(double factor) { return "×" + Ratio(factor); }

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

// One sentence on the drift for compare.md and the terminal, "" when there is nothing to say.
std::string DriftText(const RunComparison& c) {
  const Drift& d = c.drift;
  const std::string floor = d.has_floor ? "the floor (one factorization of M per problem, " +
                                              std::to_string(d.floor_problems) + " problems) " + Times(d.floor.ratio)
                                        : "no floor records";
  const std::string groups = d.agreeing_groups == static_cast<int>(c.groups.size())
                                 ? "all " + std::to_string(c.groups.size()) + " groups"
                                 : std::to_string(d.agreeing_groups) + " of " + std::to_string(c.groups.size()) +
                                       " groups";
  const std::string divided = d.divided ? " Ratios divided by " + Ratio(d.factor) + " before flagging."
                                          : " Not divided out (--keep-drift): flagged on the raw ratios.";
  switch (d.source) {
    case DriftSource::kFloor:
      return groups + " " + Times(d.factor) + " with " + floor + ": machine drift." + divided;
    case DriftSource::kGroups:
      return groups + " " + Times(d.factor) + " (" + floor + (d.has_floor ? ", which disagrees" : "") +
             "): machine drift? (or a change common to every backend)" + divided;
    case DriftSource::kNone:
      break;
  }
  const bool groups_moved = !c.groups.empty() && !WithinBand(d.median_group_ratio, c.flag_limit);
  if (d.has_floor && !WithinBand(d.floor.ratio, c.flag_limit)) {
    return floor + ", but most groups do not move with it: ratios not normalized.";
  }
  if (groups_moved) {
    return "median group " + Times(d.median_group_ratio) + " (" + floor + "), but " +
           (static_cast<int>(c.groups.size()) < kMinGroupsForDrift
                ? "fewer than " + std::to_string(kMinGroupsForDrift) + " groups to call it drift"
                : "most groups do not agree on a common factor") +
           ": ratios not normalized.";
  }
  return "";
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

namespace {

std::string Cell(const std::string& text) {
  std::string out;
  for (char ch : text) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

std::string Iterations(double median) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", median);
  return text;
}

// The runs side by side: what differs named first, the machine warning, then every field.
void IdentitySection(const std::vector<IdentityRow>& rows, std::ostringstream& md) {
  if (rows.empty()) return;
  md << "## The runs\n\n";
  const std::string differences = DifferencesLine(rows);
  md << (differences.empty() ? "Same settings, build and machine." : "**Differs:** " + Cell(differences) + ".")
     << "\n\n";
  if (MachinesDiffer(rows)) {
    md << "> **Warning: the runs come from different machines.** Their times are not comparable: the ratios below "
          "measure the machines as much as the builds or settings.\n\n";
  }
  md << "| | field | A | B |\n|---|---|---|---|\n";
  for (const IdentityRow& row : rows) {
    md << "| " << ToString(row.part) << " | " << row.name << (row.differs() ? " **≠**" : "") << " | " << Cell(row.a)
       << " | " << Cell(row.b) << " |\n";
  }
  md << "\n";
}

void NoiseSection(const RunComparison& c, const CompareOptions& options, std::ostringstream& md) {
  const NoiseFloor& n = c.noise;
  md << "## Noise floor and drift\n\n"
     << "Noise floor (A/A calibration of each run from its own repeated samples): with s the median over its cold "
        "solved records of 1.4826·MAD/median (the relative spread of one sample), two repeated samples of a typical "
        "problem differ by a ratio within exp(1.96·√2·s) 95 % of the time: A "
     << Ratio(n.a) << " (s = " << Ratio(n.spread_a) << ", " << n.records_a << " records), B " << Ratio(n.b)
     << " (s = " << Ratio(n.spread_b) << ", " << n.records_b << " records). Flag limit: the larger of these and 1 + "
     << "--threshold (" << Ratio(1.0 + options.threshold) << "): **" << Ratio(c.flag_limit) << "**.\n\n"
     << "Drift: ";
  const std::string drift = DriftText(c);
  md << (drift.empty() ? "none beyond the flag limit (median group " + Times(c.drift.median_group_ratio) +
                             (c.drift.has_floor ? ", floor " + Times(c.drift.floor.ratio) : "") +
                             "): ratios not normalized."
                       : drift)
     << " A factor is taken as drift when it lies beyond the flag limit and more than half of the groups agree with "
        "it (their interval divided by it reaches [1/limit, limit]): the floor records' ratio first (one "
        "factorization of M per problem, code neither run changes), else the median group ratio (from "
     << kMinGroupsForDrift << " groups on). A change common to every backend cannot be told from a drift: "
        "`--keep-drift` flags on the raw ratios.\n\n";
}

}  // namespace

std::string CompareMarkdown(const RunComparison& c, const CompareOptions& options, const std::string& label_a,
                            const std::string& label_b, const std::string& figure_stem) {
  std::ostringstream md;
  const int percent = static_cast<int>(std::lround(options.confidence * 100.0));
  md << "# smcbench compare\n\nA: `" << label_a << "`  \nB: `" << label_b << "`\n\n"
     << c.matched_records << " records in both runs; " << c.regressions() << " verdict regression(s), "
     << c.slower_groups() << " group(s) flagged slower beyond the noise floor. "
     << (c.regressed() ? "**B regressed** (exit status 1)." : "No regression (exit status 0).") << "\n\n";
  IdentitySection(c.identity, md);
  NoiseSection(c, options, md);
  md << "## Verdict changes\n\n";
  if (c.verdict_changes.empty()) {
    md << "None: every record has the same verdict and status in both runs.\n\n";
  } else {
    md << "| change | suite | problem | backend | mode | A | B | B's message |\n|---|---|---|---|---|---|---|---|\n";
    for (const VerdictChange& v : c.verdict_changes) {
      md << "| " << ToString(v.kind) << " | " << v.suite << " | " << v.problem << (v.start.empty() ? "" : "@" + v.start)
         << " | " << v.solver << " | " << v.mode << (v.mode == "cold" ? "" : " " + Ratio(v.tolerance)) << " | "
         << ToString(v.verdict_a) << " (" << ToString(v.status_a) << ") | " << ToString(v.verdict_b) << " ("
         << ToString(v.status_b) << ") | " << v.message_b << " |\n";
    }
    md << "\n";
  }
  md << "## Time ratio B/A per suite, backend and size band\n\n"
     << "Ratio of the shifted geometric means (shift " << Seconds(options.shift_seconds)
     << ") of the per-problem median times, over the problems both runs solved. Interval: " << percent
     << " % paired bootstrap (" << options.resamples << " resamples, seed " << options.seed
     << "): problems resampled with replacement, each median drawn log-normally with its standard error "
        "1.2533·1.4826·MAD/√samples (the records keep median, MAD and sample count, not the samples). ÷ drift: the "
        "ratio divided by the drift factor "
     << Ratio(c.drift.divisor()) << ". Flagged SLOWER when the whole interval ÷ drift lies above the flag limit "
     << Ratio(c.flag_limit) << ", faster when below " << Ratio(1.0 / c.flag_limit)
     << ". Iterations: the median over the group's problems.\n\n";
  if (!figure_stem.empty()) {
    md << "![time ratios B/A with their intervals](" << figure_stem << ".png)\n\n([SVG](" << figure_stem
       << ".svg), [data](" << figure_stem << ".dat), [gnuplot script](" << figure_stem << ".gp))\n\n";
  }
  md << "| suite | backend | band | problems | SGM A | SGM B | B/A | " << percent
     << " % interval | ÷ drift | iterations A | iterations B | flag |\n"
     << "|---|---|---|---:|---:|---:|---:|---|---:|---:|---:|---|\n";
  for (const RatioGroup& g : c.groups) {
    md << "| " << g.suite << " | " << g.solver << " | " << ShortName(g.band) << " | " << g.problems << " | "
       << Seconds(g.sgm_a) << " | " << Seconds(g.sgm_b) << " | " << Ratio(g.time.ratio) << " | [" << Ratio(g.time.low)
       << ", " << Ratio(g.time.high) << "] | " << Ratio(g.time.ratio / c.drift.divisor()) << " | "
       << Iterations(g.iterations_a) << " | " << Iterations(g.iterations_b) << " | " << ToString(g.time.flag)
       << " |\n";
  }
  if (c.groups.empty()) md << "\nNo problem was solved in both runs: nothing to time.\n";
  if (!c.only_in_a.empty() || !c.only_in_b.empty()) {
    md << "\n" << c.only_in_a.size() << " record(s) only in A and " << c.only_in_b.size()
       << " only in B (other backend lists or a partial run) are left out";
    const std::vector<std::string>& first = c.only_in_a.empty() ? c.only_in_b : c.only_in_a;
    md << ", e.g. `" << first.front() << "`.\n";
  }
  return md.str();
}

nlohmann::json CompareJson(const RunComparison& c, const CompareOptions& options, const std::string& label_a,
                           const std::string& label_b) {
  using json = nlohmann::json;
  const auto flag = [](TimeFlag f) {
    return f == TimeFlag::kSlower ? "slower" : f == TimeFlag::kFaster ? "faster" : "none";
  };
  json j = {{"format", "smcbench-compare/1"}, {"a", label_a}, {"b", label_b}, {"regressed", c.regressed()},
            {"matched_records", c.matched_records}, {"regressions", c.regressions()},
            {"slower_groups", c.slower_groups()}, {"only_in_a", c.only_in_a.size()},
            {"only_in_b", c.only_in_b.size()}};
  j["differences"] = DifferencesLine(c.identity);
  j["machines_differ"] = MachinesDiffer(c.identity);
  j["runs"] = json::array();
  for (const IdentityRow& row : c.identity) {
    j["runs"].push_back({{"part", ToString(row.part)}, {"name", row.name}, {"a", row.a}, {"b", row.b},
                         {"differs", row.differs()}});
  }
  j["method"] = {
      {"ratio", "shifted geometric mean of the per-problem median times, B over A"},
      {"interval",
       "paired bootstrap: problems resampled, each median drawn log-normally with 1.2533*1.4826*MAD/sqrt(samples)"},
      {"noise_floor", "per run exp(1.96*sqrt(2)*s), s the median over its cold solved records of 1.4826*MAD/median"},
      {"flag", "interval divided by the drift entirely beyond the flag limit max(1 + threshold, noise floors)"},
      {"threshold", options.threshold}, {"confidence", options.confidence}, {"resamples", options.resamples},
      {"seed", options.seed}, {"shift_seconds", options.shift_seconds}, {"divide_drift", options.divide_drift}};
  const NoiseFloor& n = c.noise;
  j["noise_floor"] = {{"a", n.a}, {"b", n.b}, {"spread_a", n.spread_a}, {"spread_b", n.spread_b},
                      {"records_a", n.records_a}, {"records_b", n.records_b}};
  j["flag_limit"] = c.flag_limit;
  const Drift& d = c.drift;
  j["drift"] = {{"source", ToString(d.source)}, {"factor", d.factor}, {"divided", d.divided},
                {"agreeing_groups", d.agreeing_groups}, {"median_group_ratio", d.median_group_ratio},
                {"text", DriftText(c)}};
  j["drift"]["floor"] = d.has_floor ? json{{"ratio", d.floor.ratio}, {"low", d.floor.low}, {"high", d.floor.high},
                                           {"problems", d.floor_problems}}
                                    : json(nullptr);
  j["verdict_changes"] = json::array();
  for (const VerdictChange& v : c.verdict_changes) {
    j["verdict_changes"].push_back(
        {{"kind", ToString(v.kind)}, {"suite", v.suite}, {"problem", v.problem}, {"start", v.start},
         {"backend", v.solver}, {"mode", v.mode}, {"tolerance", v.tolerance}, {"verdict_a", ToString(v.verdict_a)},
         {"status_a", ToString(v.status_a)}, {"verdict_b", ToString(v.verdict_b)},
         {"status_b", ToString(v.status_b)}, {"message_b", v.message_b}});
  }
  j["groups"] = json::array();
  for (const RatioGroup& g : c.groups) {
    j["groups"].push_back({{"suite", g.suite}, {"backend", g.solver}, {"band", ShortName(g.band)},
                           {"problems", g.problems}, {"sgm_a", g.sgm_a}, {"sgm_b", g.sgm_b},
                           {"ratio", g.time.ratio}, {"low", g.time.low}, {"high", g.time.high},
                           {"ratio_over_drift", g.time.ratio / d.divisor()}, {"iterations_a", g.iterations_a},
                           {"iterations_b", g.iterations_b}, {"flag", flag(g.time.flag)}});
  }
  return j;
}

std::string CompareSummaryText(const RunComparison& c, const CompareOptions& options, std::size_t max_changes,
                               std::size_t max_groups) {
  std::ostringstream text;
  text << "compare: " << c.matched_records << " records in both runs, " << c.verdict_changes.size()
       << " verdict change(s) (" << c.regressions() << " regression(s)), " << c.groups.size() << " group(s), "
       << c.slower_groups() << " flagged slower (interval ÷ drift above the flag limit " << Ratio(c.flag_limit)
       << ": noise floor A " << Ratio(c.noise.a) << ", B " << Ratio(c.noise.b) << ", 1 + threshold "
       << Ratio(1.0 + options.threshold) << ")\n";
  if (!c.identity.empty()) {
    const std::string differences = DifferencesLine(c.identity);
    text << "  " << (differences.empty() ? "same settings, build and machine" : "differs: " + differences) << "\n";
    if (MachinesDiffer(c.identity)) text << "  WARNING: different machines: the times are not comparable\n";
  }
  if (const std::string drift = DriftText(c); !drift.empty()) text << "  drift: " << drift << "\n";
  for (std::size_t i = 0; i < std::min(max_changes, c.verdict_changes.size()); ++i) {
    text << "  " << ChangeLine(c.verdict_changes[i]) << "\n";
  }
  if (c.verdict_changes.size() > max_changes) {
    text << "  (and " << c.verdict_changes.size() - max_changes << " more verdict changes)\n";
  }
  const bool all = c.groups.size() <= max_groups;
  std::size_t width = 7;
  for (const RatioGroup& g : c.groups) width = std::max(width, g.suite.size() + g.solver.size() + 1);
  bool header = false;
  for (const RatioGroup& g : c.groups) {
    if (!all && g.time.flag == TimeFlag::kNone) continue;
    if (!header) {
      char line[200];
      std::snprintf(line, sizeof line, "  %-*s %-9s %5s %8s  %-19s %8s  %-15s\n", static_cast<int>(width), "backend",
                    "band", "n", "B/A", "interval", "÷drift", "iterations A→B");
      text << line;
      header = true;
    }
    const std::string interval = "[" + Ratio(g.time.low) + ", " + Ratio(g.time.high) + "]";
    const std::string iterations = Iterations(g.iterations_a) + "→" + Iterations(g.iterations_b);
    char line[320];
    std::snprintf(line, sizeof line, "  %-*s %-9s %5d %8s  %-19s %8s  %-15s %s\n", static_cast<int>(width),
                  (g.suite + "/" + g.solver).c_str(), std::string(ShortName(g.band)).c_str(), g.problems,
                  Ratio(g.time.ratio).c_str(), interval.c_str(), Ratio(g.time.ratio / c.drift.divisor()).c_str(),
                  iterations.c_str(), std::string(ToString(g.time.flag)).c_str());
    text << line;
  }
  if (!all) text << "  (only the flagged groups of " << c.groups.size() << "; every group in compare.md)\n";
  return text.str();
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
