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

}  // namespace

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
      pairs.push_back({ra->time_median, ra->time_mad, ra->samples, rb.time_median, rb.time_mad, rb.samples});
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
    std::vector<double> times_a, times_b;
    for (const PairedTiming& p : pairs) {
      times_a.push_back(p.median_a);
      times_b.push_back(p.median_b);
    }
    group.sgm_a = ShiftedGeometricMean(times_a, options.shift_seconds);
    group.sgm_b = ShiftedGeometricMean(times_b, options.shift_seconds);
    group.time = TimeRatioInterval(pairs, options);
    out.groups.push_back(std::move(group));
  }
  return out;
}

std::string CompareMarkdown(const RunComparison& c, const CompareOptions& options, const std::string& label_a,
                            const std::string& label_b, const std::string& figure_stem) {
  std::ostringstream md;
  const int percent = static_cast<int>(std::lround(options.confidence * 100.0));
  md << "# smcbench compare\n\nA: `" << label_a << "`  \nB: `" << label_b << "`\n\n"
     << c.matched_records << " records in both runs; " << c.regressions() << " verdict regression(s), "
     << c.slower_groups() << " group(s) flagged slower. "
     << (c.regressed() ? "**B regressed** (exit status 1)." : "No regression (exit status 0).") << "\n\n";
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
        "1.2533·1.4826·MAD/√samples (the records keep median, MAD and sample count, not the samples). Flagged "
        "SLOWER when the whole interval lies above "
     << Ratio(1.0 + options.threshold) << " (1 + --threshold), faster when below " << Ratio(1.0 / (1.0 + options.threshold))
     << ".\n\n";
  if (!figure_stem.empty()) {
    md << "![time ratios B/A with their intervals](" << figure_stem << ".png)\n\n([SVG](" << figure_stem
       << ".svg), [data](" << figure_stem << ".dat), [gnuplot script](" << figure_stem << ".gp))\n\n";
  }
  md << "| suite | backend | band | problems | SGM A | SGM B | B/A | " << percent << " % interval | flag |\n"
     << "|---|---|---|---:|---:|---:|---:|---|---|\n";
  for (const RatioGroup& g : c.groups) {
    md << "| " << g.suite << " | " << g.solver << " | " << ShortName(g.band) << " | " << g.problems << " | "
       << Seconds(g.sgm_a) << " | " << Seconds(g.sgm_b) << " | " << Ratio(g.time.ratio) << " | [" << Ratio(g.time.low)
       << ", " << Ratio(g.time.high) << "] | " << ToString(g.time.flag) << " |\n";
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

std::string CompareSummaryText(const RunComparison& c, const CompareOptions& options, std::size_t max_changes,
                               std::size_t max_groups) {
  std::ostringstream text;
  text << "compare: " << c.matched_records << " records in both runs, " << c.verdict_changes.size()
       << " verdict change(s) (" << c.regressions() << " regression(s)), " << c.groups.size() << " group(s), "
       << c.slower_groups() << " flagged slower (interval above " << Ratio(1.0 + options.threshold) << ")\n";
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
      char line[160];
      std::snprintf(line, sizeof line, "  %-*s %-9s %5s %8s  %-19s\n", static_cast<int>(width), "backend", "band",
                    "n", "B/A", "interval");
      text << line;
      header = true;
    }
    const std::string interval = "[" + Ratio(g.time.low) + ", " + Ratio(g.time.high) + "]";
    char line[256];
    std::snprintf(line, sizeof line, "  %-*s %-9s %5d %8s  %-19s %s\n", static_cast<int>(width),
                  (g.suite + "/" + g.solver).c_str(), std::string(ShortName(g.band)).c_str(), g.problems,
                  Ratio(g.time.ratio).c_str(), interval.c_str(), std::string(ToString(g.time.flag)).c_str());
    text << line;
  }
  if (!all) text << "  (only the flagged groups of " << c.groups.size() << "; every group in compare.md)\n";
  return text.str();
}

}  // namespace smcbench
