// `smcbench report`: bench_report.h. The report is made in named phases (WriteBenchReport, at the end).
#include "tools/smcbench/bench_report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>

#include "bench/figures/gnuplot_figure.h"
#include "bench/replay/warm_track.h"
#include "problems/avi_library/avi_library.h"
#include "solvers/core/duration_text.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/report_classes.h"
#include "bench/replay/floor.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
constexpr double kInfTime = std::numeric_limits<double>::infinity();

std::string G(double v, int digits = 3) {
  if (std::isnan(v)) return "–";
  if (std::isinf(v)) return "∞";
  char b[40];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

std::string Seconds(double s) { return DurationText(s); }

// What a time is compared over: the problem, or for an MCP record the problem × start (each start is its own
// instance: the same backend may solve one start and fail another).
std::string Instance(const ReplayRecord& r) { return r.start.empty() ? r.problem : r.problem + "@" + r.start; }

bool Correct(const ReplayRecord& r) {
  return r.verdict == Verdict::kSolved || r.verdict == Verdict::kCorrectlyRefused;
}

std::vector<std::string> Solvers(const std::vector<ReplayRecord>& records) {
  std::vector<std::string> out;
  for (const auto& r : records) {
    if (std::find(out.begin(), out.end(), r.solver) == out.end()) out.push_back(r.solver);
  }
  return out;
}

double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const std::size_t n = x.size();
  if (n < 2) return std::nan("");
  for (std::size_t i = 0; i < n; ++i) {
    const double a = std::log(x[i]), b = std::log(y[i]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : std::nan("");
}

// A figure a user can restyle: dir/STEM.dat (the data), dir/STEM.gp (the gnuplot script, reading STEM.dat and
// writing STEM.png and STEM.svg; `cd DIR && gnuplot STEM.gp` remakes both) kept beside STEM.png and STEM.svg.
// body: the settings and the plot command, naming the data file as 'STEM.dat'.
void WriteFigure(const std::string& dir, const std::string& stem, const std::string& data, const std::string& body,
                 int width, int height) {
  WriteGnuplotFigure(dir, stem, data, body, width, height, "report");  // the one figure writer (bench/figures)
}

// The markdown of a figure: the PNG, with its SVG, data and script linked below it.
std::string FigureMarkdown(const std::string& alt, const std::string& stem) {
  return "![" + alt + "](" + stem + ".png)\n\n(" + "[SVG](" + stem + ".svg), [data](" + stem + ".dat), [gnuplot script](" +
         stem + ".gp))\n\n";
}

std::string Safe(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return out;
}

// The largest of a and b where NaN means "not defined" (so a defined value always wins).
double MaxDefined(double a, double b) { return std::isnan(a) ? b : std::isnan(b) ? a : std::max(a, b); }

// Median of the defined (non-NaN) values; NaN when there are none.
double MedianDefined(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string Count(int n) { return n ? "**" + std::to_string(n) + "**" : std::string("0"); }

// A table cell from free text: one line, no column separator, at most max_chars bytes.
std::string Cell(const std::string& text, std::size_t max_chars = 90) {
  std::string out;
  for (char c : text) out += c == '|' ? '/' : c == '\n' ? ' ' : c;
  if (out.size() > max_chars) out = out.substr(0, max_chars) + "…";
  return out;
}

// A value that is not defined (NaN: nothing solved, no reference) as an empty cell, never as a 0.
std::string Blank(double v) { return std::isnan(v) ? std::string() : G(v); }

// "12/16 (75%)"; empty when nothing was run.
std::string Fraction(int part, int whole) {
  if (whole == 0) return "";
  return std::to_string(part) + "/" + std::to_string(whole) + " (" + G(100.0 * part / whole, 3) + "%)";
}

// Tick labels in %g ("1e-06", "0.001", "100"): never gnuplot's default fixed notation ("0.0000010").
constexpr const char* kTickFormat = "set format x '%g'\nset format y '%g'\n";

// One curve per label of (x, time) points on log axes, joined in x order when sort_by_x (else in the given order,
// e.g. of decreasing h): the figure dir/STEM.{png,svg,dat,gp} (WriteFigure).
void PlotCurves(const std::map<std::string, std::vector<std::pair<double, double>>>& curves, const std::string& dir,
                const std::string& stem, const std::string& xlabel, const std::string& ylabel,
                const std::string& title, bool sort_by_x = true, const char* with = "linespoints") {
  std::ostringstream data, g;
  g << "set logscale xy\nset grid\nset key outside right top\n" << kTickFormat << "set xlabel " << GnuplotQuote(xlabel)
    << "\nset ylabel " << GnuplotQuote(ylabel) << "\nset title " << GnuplotQuote(title) << "\nplot ";
  int index = 0;
  for (const auto& [label, points] : curves) {
    auto sorted = points;
    if (sort_by_x) std::sort(sorted.begin(), sorted.end());
    data << "# " << label << "\n";
    for (auto [x, y] : sorted) data << x << ' ' << y << '\n';
    data << "\n\n";
    g << (index ? ", " : "") << GnuplotQuote(stem + ".dat") << " index " << index << " using 1:2 with " << with << " "
      << BackendStyle(label) << " title " << GnuplotQuote(label);
    ++index;
  }
  g << "\n";
  WriteFigure(dir, stem, data.str(), g.str(), 1100, 600);
}

}  // namespace

const char* const kVerdictInTwoSentences =
    "An answer z counts as solved when its status is solved and, recomputed by us from z, (1) the natural residual "
    "‖z − Π[l,u](z − w)‖∞ is ≤ tol·(1 + ‖q‖∞) and (2) the natural residual of the row-equilibrated problem (each "
    "row of M and q divided by d_i = max_j |M_ij|) is ≤ tol·(1 + ‖z‖∞). Where a certified reference z* proves the "
    "solution unique, also ‖z − z*‖∞ ≤ 10·max(1, μ)·tol·(1 + ‖z*‖∞), with μ = ‖(D⁻¹M)_FF⁻¹‖∞ the conditioning of "
    "z*'s free rows; a claim that no solution exists, on a problem known to have one, is wrongly refused.";

bool IsAviSuite(const SuiteResults& suite) { return suite.suite == kAviSuiteName; }

bool IsMcpSuite(const SuiteResults& suite) {
  return std::any_of(suite.replay.records.begin(), suite.replay.records.end(),
                     [](const ReplayRecord& r) { return !r.start.empty(); });
}

PlotStyle StyleOf(std::size_t index, bool external) {
  // Okabe & Ito (2008), "Color Universal Design": distinct under every common colour-vision deficiency. Its yellow
  // (#F0E442) is left out: it vanishes on a white background.
  static constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                             "#E69F00", "#56B4E9", "#000000"};
  // Filled circle, square, up and down triangles, diamond; open circle, open square.
  static constexpr int kPoints[] = {7, 5, 9, 11, 13, 6, 4};
  constexpr std::size_t kN = 7;
  const std::size_t colour = index % kN, round = index / kN;
  PlotStyle style;
  style.colour = kColours[colour];
  // Within one colour the point type steps with each round of the palette, so colour + point stays unique; the
  // external family starts 3 point types on, so our i-th and its i-th differ in more than the dash.
  style.point = kPoints[(colour + round + (external ? 3 : 0)) % kN];
  style.dash = external ? 2 + static_cast<int>(round % 4) : 1;
  style.width = external ? 2.0 : 2.5;
  return style;
}

std::string BackendStyle(const std::string& label) {
  std::vector<std::string> known;
  for (auto name : SolverNames()) known.emplace_back(name);
  known.emplace_back("newton-sparse-path");
  std::string backend = label;
  std::string token;
  for (char c : label + " ") {
    if (c == ' ' || c == '/' || c == '(' || c == ')' || c == ',') {
      if (!token.empty() && std::find(known.begin(), known.end(), token) != known.end()) {
        backend = token;
        break;
      }
      token.clear();
    } else {
      token.push_back(c);
    }
  }
  const bool external = IsExternalBackendName(backend);
  std::size_t index = 0;
  const auto it = std::find(known.begin(), known.end(), backend);
  if (it == known.end()) {
    index = std::hash<std::string>{}(backend) % 49;
  } else {
    for (auto k = known.begin(); k != it; ++k) index += IsExternalBackendName(*k) == external;
  }
  const PlotStyle style = StyleOf(index, external);
  char text[96];
  std::snprintf(text, sizeof text, "lw %g lc rgb '%s' dt %d pt %d", style.width, style.colour.c_str(), style.dash,
                style.point);
  return text;
}

std::vector<BackendSummary> SummarizeSuite(const SuiteResults& suite, double time_limit_seconds) {
  return SummarizeRecords(suite.replay.records, time_limit_seconds);
}

namespace {

// The most common ending of a backend's records that are not correct (FailureReason).
FailureReason MostCommonFailure(const std::vector<const ReplayRecord*>& not_correct) {
  return MostCommonFailureOf(not_correct);
}

}  // namespace

std::vector<BackendSummary> SummarizeRecords(const std::vector<ReplayRecord>& records, double time_limit_seconds) {
  // Slowest correct time per problem.
  std::map<std::string, double> slowest;
  for (const auto& r : records) {
    if (Correct(r)) slowest[Instance(r)] = std::max(slowest[Instance(r)], r.time_median);
  }
  std::vector<BackendSummary> out;
  for (const std::string& solver : Solvers(records)) {
    BackendSummary b;
    b.solver = solver;
    double log_sum = 0.0;
    constexpr double kShift = 1e-6;
    std::vector<const ReplayRecord*> not_correct;
    for (const auto& r : records) {
      if (r.solver != solver) continue;
      ++b.problems;
      ++b.statuses[r.status];
      if (!Correct(r)) not_correct.push_back(&r);
      switch (r.verdict) {
        case Verdict::kSolved:
          ++b.solved;
          b.worst_residual = MaxDefined(b.worst_residual, r.residual_rel);
          b.worst_residual_scaled = MaxDefined(b.worst_residual_scaled, r.residual_scaled);
          if (!std::isnan(r.forward_error)) {
            ++b.forward_error_defined;
            b.worst_forward_error = MaxDefined(b.worst_forward_error, r.forward_error);
          }
          break;
        case Verdict::kCorrectlyRefused:
          ++b.correctly_refused;
          break;
        case Verdict::kFailed:
          ++b.failed;
          break;
        case Verdict::kWronglyClaimed:
          ++b.wrongly_claimed;
          break;
        case Verdict::kInaccurate:
          ++b.inaccurate;
          break;
        case Verdict::kWronglyRefused:
          ++b.wrongly_refused;
          break;
      }
      const auto it = slowest.find(Instance(r));
      const double t = Correct(r) ? r.time_median
                                  : (it != slowest.end() ? kFailurePenaltyFactor * it->second : time_limit_seconds);
      log_sum += std::log(t + kShift);
    }
    if (!not_correct.empty()) b.failure = MostCommonFailure(not_correct);
    b.success_rate = b.problems ? static_cast<double>(b.solved + b.correctly_refused) / b.problems : 0.0;
    b.shifted_geomean = b.problems ? std::exp(log_sum / b.problems) - kShift : 0.0;
    out.push_back(b);
  }
  return out;
}

bool SolvedNothing(const BackendSummary& backend, const std::vector<BackendSummary>& suite) {
  return backend.solved == 0 &&
         std::any_of(suite.begin(), suite.end(), [](const BackendSummary& b) { return b.solved > 0; });
}

std::vector<BandWinner> FastestCorrectPerBand(const SuiteResults& suite, double time_limit_seconds) {
  std::vector<BandWinner> out;
  for (const SizeBand band : kSizeBands) {
    std::vector<ReplayRecord> records;
    for (const auto& r : suite.replay.records) {
      if (SizeBandOf(r.size) == band) records.push_back(r);
    }
    if (records.empty()) continue;
    BandWinner w;
    w.band = band;
    std::map<std::string, double> fastest;  // instance → smallest correct time
    for (const auto& r : records) {
      if (!Correct(r)) continue;
      auto [it, inserted] = fastest.emplace(Instance(r), r.time_median);
      if (!inserted) it->second = std::min(it->second, r.time_median);
    }
    std::set<std::string> instances;
    for (const auto& r : records) instances.insert(Instance(r));
    w.problems = static_cast<int>(instances.size());
    std::vector<BackendSummary> candidates;
    for (const BackendSummary& b : SummarizeRecords(records, time_limit_seconds)) {
      if (b.wrong() == 0 && b.correct() > 0) candidates.push_back(b);
    }
    // Most correct answers first, then the smaller SGM.
    std::stable_sort(candidates.begin(), candidates.end(), [](const BackendSummary& a, const BackendSummary& b) {
      return a.correct() != b.correct() ? a.correct() > b.correct() : a.shifted_geomean < b.shifted_geomean;
    });
    if (!candidates.empty()) {
      w.solver = candidates[0].solver;
      w.correct = candidates[0].correct();
      w.shifted_geomean = candidates[0].shifted_geomean;
      for (const auto& r : records) {
        w.fastest_on += r.solver == w.solver && Correct(r) && r.time_median <= fastest.at(Instance(r));
      }
    }
    if (candidates.size() > 1) {
      w.runner_up = candidates[1].solver;
      w.runner_up_correct = candidates[1].correct();
      w.runner_up_geomean = candidates[1].shifted_geomean;
    }
    out.push_back(w);
  }
  return out;
}

ToleranceLadder BuildToleranceLadder(const SuiteResults& suite) {
  ToleranceLadder ladder;
  std::set<double> tolerances;
  for (const auto& r : suite.replay.sweep) tolerances.insert(r.tolerance);
  ladder.tolerances.assign(tolerances.rbegin(), tolerances.rend());
  for (const std::string& solver : Solvers(suite.replay.sweep)) {
    ToleranceLadder::Row row;
    row.solver = solver;
    row.correct.assign(ladder.tolerances.size(), 0);
    row.problems.assign(ladder.tolerances.size(), 0);
    for (const auto& r : suite.replay.sweep) {
      if (r.solver != solver) continue;
      const auto k = static_cast<std::size_t>(
          std::find(ladder.tolerances.begin(), ladder.tolerances.end(), r.tolerance) - ladder.tolerances.begin());
      ++row.problems[k];
      row.correct[k] += Correct(r);
    }
    ladder.rows.push_back(std::move(row));
  }
  return ladder;
}

bool ClaimedSolved(const ReplayRecord& record) {
  return record.backend_code ? *record.backend_code == 0 : record.status == SolveStatus::kSolved;
}

std::vector<ClaimAudit> AuditClaims(const SuiteResults& suite) {
  std::vector<ClaimAudit> out;
  for (const std::string& solver : Solvers(suite.replay.records)) {
    ClaimAudit a;
    a.solver = solver;
    for (const auto& r : suite.replay.records) {
      if (r.solver != solver) continue;
      ++a.records;
      a.with_return_code += r.backend_code.has_value();
      const bool claimed = ClaimedSolved(r), solved = r.verdict == Verdict::kSolved;
      a.right += claimed == solved;
      a.false_success += claimed && !solved;
      a.false_failure += !claimed && solved;
    }
    out.push_back(a);
  }
  return out;
}

std::vector<std::pair<std::string, std::vector<double>>> PerformanceRatios(const SuiteResults& suite) {
  const auto& records = suite.replay.records;
  std::map<std::string, double> best;
  for (const auto& r : records) {
    if (r.verdict != Verdict::kSolved) continue;
    auto [it, inserted] = best.emplace(Instance(r), r.time_median);
    if (!inserted) it->second = std::min(it->second, r.time_median);
  }
  std::vector<std::pair<std::string, std::vector<double>>> out;
  for (const std::string& solver : Solvers(records)) {
    std::vector<double> ratios;
    for (const auto& r : records) {
      if (r.solver != solver || !best.count(Instance(r))) continue;  // problems nobody solves are left out
      ratios.push_back(r.verdict == Verdict::kSolved ? r.time_median / best.at(Instance(r)) : kInfTime);
    }
    std::sort(ratios.begin(), ratios.end());
    out.emplace_back(solver, std::move(ratios));
  }
  return out;
}

double GrowthExponent(const SuiteResults& suite, const std::string& solver) {
  std::map<int, std::vector<double>> by_size;
  for (const auto& r : suite.replay.records) {
    if (r.solver == solver && r.verdict == Verdict::kSolved) by_size[r.size].push_back(r.time_median);
  }
  std::vector<double> x, y;
  for (auto& [m, times] : by_size) {
    std::sort(times.begin(), times.end());
    x.push_back(m);
    y.push_back(times[times.size() / 2]);
  }
  return Slope(x, y);
}

SuiteResults SizeBandSlice(const SuiteResults& suite, SizeBand band) {
  SuiteResults slice;
  slice.suite = suite.suite + " " + std::string(ShortName(band));
  slice.description = suite.description;
  std::set<std::string> problems;
  for (const ReplayRecord& r : suite.replay.records) {
    if (SizeBandOf(r.size) != band) continue;
    slice.replay.records.push_back(r);
    problems.insert(Instance(r));
  }
  for (const ReplayRecord& r : suite.replay.floor) {
    if (SizeBandOf(r.size) == band) slice.replay.floor.push_back(r);
  }
  slice.problems = static_cast<int>(problems.size());
  return slice;
}

SuiteResults WarmTrackAsSuite(const SuiteResults& suite) {
  SuiteResults warm;
  warm.suite = suite.suite + " warm";
  warm.description = "warm track of suite " + suite.suite;
  std::set<std::string> sequences;
  for (const WarmRecord& w : suite.warm) {
    warm.replay.records.push_back(w.record);
    sequences.insert(w.record.problem);
  }
  warm.problems = static_cast<int>(sequences.size());
  return warm;
}

std::vector<PeerRatioRow> OursAgainstPeersPerBand(const SuiteResults& suite) {
  std::vector<PeerRatioRow> out;
  const auto rows = [&](const std::vector<ReplayRecord>& records, bool warm) {
    // problem → fastest correct time of ours, and of each peer family; problem → size.
    std::map<std::string, double> ours;
    std::map<std::string, std::map<std::string, double>> peers;
    std::map<std::string, int> sizes;
    for (const ReplayRecord& r : records) {
      if (r.verdict != Verdict::kSolved || r.solver == "newton-sparse-path") continue;
      const std::string key = Instance(r);
      sizes[key] = r.size;
      if (!IsExternalBackendName(r.solver)) {
        auto [it, inserted] = ours.emplace(key, r.time_median);
        if (!inserted) it->second = std::min(it->second, r.time_median);
        continue;
      }
      const std::string family = r.solver.substr(0, r.solver.find('-'));
      auto [it, inserted] = peers[family].emplace(key, r.time_median);
      if (!inserted) it->second = std::min(it->second, r.time_median);
    }
    std::map<SizeBand, PeerRatioRow> by_band;
    for (const auto& [family, times] : peers) {
      for (const auto& [key, t] : times) {
        if (!ours.count(key)) continue;
        PeerRatioRow& row = by_band[SizeBandOf(sizes.at(key))];
        row.band = SizeBandOf(sizes.at(key));
        row.warm = warm;
        row.by_peer[family].push_back(t / ours.at(key));
      }
    }
    for (auto& [band, row] : by_band) {
      for (auto& [family, ratios] : row.by_peer) std::sort(ratios.begin(), ratios.end());
    }
    return by_band;
  };
  std::vector<ReplayRecord> warm_records;
  for (const WarmRecord& w : suite.warm) warm_records.push_back(w.record);
  std::map<SizeBand, PeerRatioRow> cold = rows(suite.replay.records, false), warm = rows(warm_records, true);
  for (SizeBand band : kSizeBands) {
    if (cold.count(band)) out.push_back(cold.at(band));
    if (warm.count(band)) out.push_back(warm.at(band));
  }
  return out;
}

std::string SharedHostWarning(const BenchResults& results) {
  std::set<std::string> hosts;
  std::size_t timed = 0, shared = 0;
  int most = 0;
  for (const SuiteResults& suite : results.suites) {
    for (const auto* records : {&suite.replay.records, &suite.replay.sweep}) {
      for (const ReplayRecord& r : *records) {
        if (r.samples == 0) continue;  // not run: no time to compare
        ++timed;
        if (!r.host.empty()) hosts.insert(r.host);
        if (r.concurrent_jobs > 1) ++shared, most = std::max(most, r.concurrent_jobs);
      }
    }
  }
  std::string warning;
  if (shared > 0) {
    warning += "**Warning: shared hosts.** " + std::to_string(shared) + " of " + std::to_string(timed) +
               " timed records were measured while other `smcbench bench` jobs ran on the same host (up to " +
               std::to_string(most) + " at once, column `concurrent_jobs` of results.csv): jobs that share a host "
               "disturb each other's times, so compare those times with care (give each shard a whole node, e.g. "
               "`sbatch --exclusive`, or run the shards one after another). ";
  }
  if (hosts.size() > 1) {
    warning += "**Warning: several hosts.** The times come from " + std::to_string(hosts.size()) +
               " hosts (column `host` of results.csv): times of different backends on one problem may have been "
               "measured on different machines. ";
  }
  if (!warning.empty()) warning.back() = '\n';
  return warning.empty() ? warning : warning + "\n";
}

namespace {

// ---------------------------------------------------------------------------------------------------------------
// WriteBenchReport's phases: read the results, then per suite compute each table and write its section (figures
// beside the section that shows them), then the time-stepper's sections, then the file.

// The report's opening: the command, the environment, the verdict and what the columns mean.
void WriteHeader(std::ostream& md, const std::string& dir, const BenchResults& results, const json& env) {
  md << "# smcbench benchmark report\n\n"
     << "Made by `smcbench report " << dir << "` from `" << dir << "/results.json`, produced by\n\n    "
     << results.command << "\n\n"
     << "Environment: "
     << (env.value("build_revision", std::string()).empty()
             ? "git " + env.value("git_sha", std::string("?")).substr(0, 12) +
                   (env.value("git_dirty", false) ? " (dirty tree)" : "")
             : "build " + env.value("build_revision", std::string()))
     << ", " << env.value("compiler", std::string("?"))
     << " " << env.value("build_type", std::string("")) << ", " << env.value("cpu", std::string("?")) << " ("
     << env.value("cores", 0) << " cores), " << env.value("date", std::string("")) << ".\n\n"
     << SharedHostWarning(results)
     << "The summary comes first; every table after it is defined in [the appendix](#appendix-the-verdict-and-the-"
        "timing) (the verdict, the wrong answers, the SGM time), and [each backend's failures](#failures-per-"
        "backend) are listed before it.\n\n";
}

// The appendix: the verdict and how times are measured (what the header said before the summary came first).
void WriteVerdictAppendix(std::ostream& md, const BenchResults& results) {
  md << "## Appendix: the verdict and the timing\n\n"
     << "**The verdict.** " << kVerdictInTwoSentences
     << " (docs/verdict.md says why each part is there.) Success = solved, or — on a problem known to have no "
        "solution — any non-solved status ('correctly refused'). The **wrong** answers, which must be 0: **wrongly "
        "claimed** (status solved where a recomputed residual says otherwise, or on a problem with no solution), "
        "**inaccurate** (the residuals pass but z is farther from the certified z* than its conditioning allows) "
        "and **wrongly refused** (status infeasible on a problem known to be solvable). `smcbench bench` exits "
        "with status 3 when there is any (backends named by `--allow-wrong` excepted). Residual = relative "
        "natural residual (1), residual (eq.) = the row-equilibrated one (2), forward error = ‖z − z*‖∞ where a "
        "certified reference proves z* unique (– where none does). Times are medians over repeated cold solves "
        "(each sample repeats the solve until it lasts ≥ 0.2 ms) after one untimed warm-up solve, which for a "
        "`siconos-*` backend is the probe in its isolation worker, so that its timed solves run in process; SGM is "
        "the shifted geometric mean (shift 1 µs) "
        "with a wrong or failed problem counted at 10× the slowest correct time on it (10 s where no backend got it "
        "right). "
     << (results.polish ? "Every answer went through the base layer's exact polish (the default: from the answer's "
                          "active set, the reduced system solved directly), so an answer with the right active set "
                          "is exact whatever the tolerance; `smcbench bench --no-polish` times the raw algorithms."
                        : "**No polish** (`--no-polish`): the raw algorithms' answers.")
     << " The **floor** of a problem is one factorization of its matrix (bench/replay/floor.h: Cholesky when its "
        "tags say SPD, else LU with partial pivoting; sparse ones for a sparse M; an MCP's Jacobian at the start, an "
        "AVI's reduced system), timed in the same run with the same protocol as a cold solve; it is never a "
        "backend and counts in no ranking.\n\n";
}

std::string FailureText(const FailureReason& f, int problems);

// The summary: per problem class the fastest correct backend, the most reliable one and the gap to the floor
// (SummarizeClasses), then per backend its failures and their most common cause (FailuresPerBackend).
void WriteSummary(std::ostream& md, const BenchResults& results) {
  const std::vector<ClassSummary> classes = SummarizeClasses(results);
  if (classes.empty()) return;
  bool floor = false;
  for (const SuiteResults& s : results.suites) floor = floor || !s.replay.floor.empty();
  md << "## Summary\n\nPer problem class (matrix class and bounds from the problems' tags × size band; every "
        "suite's cold records pooled): the **fastest correct** backend (no wrong answer in the class, smallest SGM "
        "time, a failure counted at the penalty), the **most reliable** (most correct answers, then fewest wrong), "
        "and the fastest's median time over the **floor** (one factorization of the problem's matrix, n problems)"
     << (floor ? "" : " — floor not measured in this run") << ".\n\n"
     << "| class | size band | problems | fastest correct | its correct | its SGM time | fastest / floor | most "
        "reliable | its correct | its wrong |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ClassSummary& c : classes) {
    md << "| " << ClassName(c.problem_class) << " | " << ToString(c.problem_class.band) << " | " << c.problems
       << " | ";
    if (c.fastest.empty()) {
      md << "none (every backend gave a wrong answer) | | | |";
    } else {
      md << "**" << c.fastest << "** | " << c.fastest_correct << "/" << c.problems << " | "
         << Seconds(c.fastest_sgm) << " | "
         << (c.floor_instances ? G(c.fastest_over_floor) + "× (" + std::to_string(c.floor_instances) + ")"
                               : std::string(floor ? "–" : "not measured"))
         << " |";
    }
    md << " " << c.most_reliable << " | " << c.reliable_correct << "/" << c.problems << " | "
       << Count(c.reliable_wrong) << " |\n";
  }
  md << "\nFailures per backend over the whole run (failed or wrong; the list of each is in [Failures per "
        "backend](#failures-per-backend)):\n\n| backend | records | not correct | **wrong** | most common cause "
        "|\n|---|---|---|---|---|\n";
  for (const BackendFailures& b : FailuresPerBackend(results)) {
    if (b.not_correct == 0) continue;
    md << "| " << b.solver << " | " << b.records << " | " << b.not_correct << " | " << Count(b.wrong) << " | "
       << FailureText(b.cause, b.not_correct) << " |\n";
  }
  std::vector<std::string> clean;
  for (const BackendFailures& b : FailuresPerBackend(results)) {
    if (b.not_correct == 0) clean.push_back(b.solver);
  }
  if (!clean.empty()) {
    md << "\nNo failure: ";
    for (std::size_t i = 0; i < clean.size(); ++i) md << (i ? ", " : "") << clean[i];
    md << ".";
  }
  md << "\n\n";
}

// Per backend, every cold record that is not correct: problem (suite/instance), class, status, verdict, message.
void WriteFailureList(std::ostream& md, const BenchResults& results) {
  const std::vector<BackendFailures> all = FailuresPerBackend(results);
  md << "## Failures per backend\n\nEvery cold record that is not correct (failed, or a wrong answer in bold), per "
        "backend, in the order of the results.\n\n";
  for (const BackendFailures& b : all) {
    if (b.not_correct == 0) continue;
    md << "### " << b.solver << ": " << b.not_correct << " of " << b.records << "\n\n| problem | class | status | "
          "verdict | message |\n|---|---|---|---|---|\n";
    for (const BackendFailures::Entry& e : b.entries) {
      const bool wrong = e.verdict != Verdict::kFailed;
      md << "| " << Cell(e.instance, 120) << " | " << e.problem_class << " | `" << ToString(e.status) << "` | "
         << (wrong ? "**" : "") << ToString(e.verdict) << (wrong ? "**" : "") << " | " << Cell(e.message) << " |\n";
    }
    md << "\n";
  }
}

// "3 unique, 2 non-unique": what the certified references prove, counted per problem (every backend's record
// carries its problem's).
std::string CertificateCounts(const SuiteResults& suite) {
  std::map<std::string, std::string> certificate_of;
  for (const auto& r : suite.replay.records) certificate_of.emplace(r.problem, r.certificate);
  std::map<std::string, int> certificates;
  for (const auto& [problem, certificate] : certificate_of) ++certificates[certificate];
  std::string certified;
  for (const auto& [certificate, count] : certificates) {
    certified += (certified.empty() ? "" : ", ") + std::to_string(count) + " " + certificate;
  }
  return certified;
}

// "; 5 of the 7 verified proved by an interval enclosure (3 the only solution: M + Mᵀ proved positive definite),
// an exact solution within 2.2e-16 of z*": how many verified references an interval proof confirms
// (ReplayRecord::reference_radius, reference_proved_unique; solvers/reference/enclosure.h), counted per problem,
// with the largest radius; empty when the suite has no verified reference.
std::string ProvedCounts(const SuiteResults& suite) {
  std::map<std::string, const ReplayRecord*> record_of;
  for (const auto& r : suite.replay.records) record_of.emplace(r.problem, &r);
  int verified = 0, proved = 0, proved_unique = 0;
  double radius = 0.0;
  for (const auto& [problem, r] : record_of) {
    const std::optional<Certificate> certificate = CertificateFromString(r->certificate);
    if (!certificate) continue;
    ReferenceSolution reference;
    reference.certificate = *certificate;
    if (!reference.verified()) continue;
    ++verified;
    if (std::isnan(r->reference_radius)) continue;
    ++proved;
    proved_unique += r->reference_proved_unique ? 1 : 0;
    radius = std::max(radius, r->reference_radius);
  }
  if (verified == 0) return {};
  std::string text = "; " + std::to_string(proved) + " of the " + std::to_string(verified) +
                     " verified proved by an interval enclosure";
  if (proved_unique > 0) {
    text += " (" + std::to_string(proved_unique) + " the only solution: M + Mᵀ proved positive definite)";
  }
  if (proved > 0) text += ", an exact solution within " + G(radius) + " of z*";
  return text;
}

void WriteBackendTable(std::ostream& md, const SuiteResults& suite);

// The suite's heading and its table of verdict counts, success, SGM time and worst errors per backend.
void WriteSuiteSummary(std::ostream& md, const SuiteResults& suite) {
  const std::string certified = CertificateCounts(suite);
  md << "## Suite `" << suite.suite << "`: " << suite.description << "\n\n"
     << suite.problems << " problems; certified references: " << (certified.empty() ? "–" : certified)
     << " (forward errors are judged on the unique and degenerate ones)" << ProvedCounts(suite) << ".\n\n";
  WriteBackendTable(md, suite);
}

// The failure-penalty convention, in the words the report prints beside every table and figure that uses it.
const char* const kPenaltyConvention =
    "SGM time = shifted geometric mean (shift 1 µs) of the per-problem median times, where a problem the backend "
    "did not get right (failed, or a wrong answer) counts as 10× the slowest correct time on that problem, or as "
    "10 s when no backend got it right: a failure never costs less than the slowest success (qpbenchmark's "
    "convention, with 10× the slowest correct time in place of the time limit).";

// A backend's time over the floor as a cell: the median of sorted ratios and their count, "–" when none.
std::string FloorRatioCell(const std::vector<double>& sorted) {
  if (sorted.empty()) return "–";
  return G(MedianOfSorted(sorted)) + "× (" + std::to_string(sorted.size()) + ")";
}

// What the floor is, under a suite's first table: the factorizations timed and their times, or that the run
// measured none (results written before the floor, or a run without box, MCP or AVI jobs).
void WriteFloorLine(std::ostream& md, const SuiteResults& suite) {
  if (suite.replay.floor.empty()) {
    md << "Floor not measured in this run (no floor records in results.json): no time is given against one "
          "factorization of M.\n\n";
    return;
  }
  std::map<std::string, int> methods;  // "dense Cholesky" → problems
  std::vector<double> times;
  for (const ReplayRecord& r : suite.replay.floor) {
    std::string method = r.message.substr(r.message.find(": ") == std::string::npos ? 0 : r.message.find(": ") + 2);
    method = method.substr(0, method.find(" of a "));
    ++methods[method];
    if (r.samples > 0) times.push_back(r.time_median);
  }
  std::sort(times.begin(), times.end());
  std::string list;
  for (const auto& [method, count] : methods) list += (list.empty() ? "" : ", ") + method + " on " + std::to_string(count);
  md << "**Floor** (column *time / floor*): one factorization of each problem's matrix (" << list
     << "; an MCP's Jacobian at its start, an AVI's reduced box-MLCP), timed in this run with the cold protocol "
        "(same repetitions, the median): what a direct method pays at least once. *time / floor* is a backend's "
        "median, over the problems it got right, of its time over that problem's floor (n problems). Floor times: "
        "median "
     << (times.empty() ? "–" : Seconds(MedianOfSorted(times))) << " ["
     << (times.empty() ? "–" : Seconds(times.front())) << " – " << (times.empty() ? "–" : Seconds(times.back()))
     << "] over " << suite.replay.floor.size() << " problems.\n\n";
}

// Per backend: verdict counts, success, SGM time and worst errors (SummarizeSuite), and its time over the floor
// when the run measured one. Backends that solved nothing are listed apart (WriteSolvedNothing): their SGM would be
// the penalty alone.
void WriteBackendTableOnly(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BackendSummary> summary = SummarizeSuite(suite);
  const std::map<std::string, double> floor = FloorTimes(suite);
  md << "| backend | solved | correctly refused | failed | **wrongly claimed** | **inaccurate** | **wrongly "
        "refused** | success | SGM time | worst residual (solved) | worst residual (eq.) | worst forward error "
        "(solved) |"
     << (floor.empty() ? "" : " time / floor |") << "\n|---|---|---|---|---|---|---|---|---|---|---|---|"
     << (floor.empty() ? "" : "---|") << "\n";
  for (const BackendSummary& b : summary) {
    if (SolvedNothing(b, summary)) continue;
    md << "| " << b.solver << " | " << b.solved << " | " << b.correctly_refused << " | " << b.failed << " | "
       << Count(b.wrongly_claimed) << " | " << Count(b.inaccurate) << " | " << Count(b.wrongly_refused) << " | "
       << G(100.0 * b.success_rate, 3) << "% | " << Seconds(b.shifted_geomean) << " | " << Blank(b.worst_residual)
       << " | " << Blank(b.worst_residual_scaled) << " | ";
    // Nothing solved: blank; solved, but no problem with a unique reference: "–".
    if (b.solved > 0) md << G(b.worst_forward_error);
    if (b.forward_error_defined) md << " (" << b.forward_error_defined << " with z*)";
    md << " |";
    if (!floor.empty()) md << " " << FloorRatioCell(FloorRatios(suite.replay.records, floor, b.solver)) << " |";
    md << "\n";
  }
  md << "\n";
}

void WriteBackendTable(std::ostream& md, const SuiteResults& suite) {
  WriteBackendTableOnly(md, suite);
  md << kPenaltyConvention << " Worst residuals and forward error are over the solved answers (blank: none "
     << "solved; –: no solved problem has a unique certified reference).\n\n";
  WriteFloorLine(md, suite);
}

// "size_limit on 50 of 50: "refused m > 12" (50×), median 24 µs": the reason a backend solved nothing.
std::string FailureText(const FailureReason& f, int problems) {
  std::string text = "`" + std::string(ToString(f.status)) + "` on " + std::to_string(f.count) + " of " +
                     std::to_string(problems);
  if (!f.message.empty()) {
    text += ": \"" + Cell(f.message) + "\"";
    if (f.message_count != f.count) text += " (" + std::to_string(f.message_count) + "×)";
  }
  if (!std::isnan(f.median_time)) text += ", median " + Seconds(f.median_time);
  return text;
}

// The backends that solved nothing while others solved something, each with its most common ending.
void WriteSolvedNothing(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BackendSummary> summary = SummarizeSuite(suite);
  std::vector<const BackendSummary*> none;
  for (const BackendSummary& b : summary) {
    if (SolvedNothing(b, summary)) none.push_back(&b);
  }
  if (none.empty()) return;
  md << "**Solved nothing** in this suite (left out of the table above: their SGM would be the failure penalty "
        "alone). The most common ending, with its message and the median time it took:\n\n"
        "| backend | problems | correctly refused | failed | wrong | most common ending |\n|---|---|---|---|---|---|\n";
  for (const BackendSummary* b : none) {
    md << "| " << b->solver << " | " << b->problems << " | " << b->correctly_refused << " | " << b->failed << " | "
       << Count(b->wrong()) << " | " << FailureText(b->failure, b->problems) << " |\n";
  }
  md << "\n";
}

// Per backend, how many records ended with each status the backend returned (one column per status met in the
// suite), then the audit of claims (AuditClaims): whether its own success flag agreed with our verdict.
void WriteStatusesAndClaims(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BackendSummary> summary = SummarizeSuite(suite);
  const std::vector<ClaimAudit> audit = AuditClaims(suite);
  std::set<SolveStatus> met;
  for (const BackendSummary& b : summary) {
    for (const auto& [status, count] : b.statuses) met.insert(status);
  }
  md << "**Statuses returned and the audit of claims**: how each backend's answers ended in its own words, and "
        "whether its success flag was right — a claim is right when it says solved exactly when our verdict is "
        "solved. The flag is the external library's own (Siconos' `info` = 0, Bullet's and DART's success flag; column "
        "`backend_code` of results.csv, 0 = success) where the record has one, before our base layer re-judged the answer (with the polish on, a false failure can be a "
        "short stop our polish finished); else the status.\n\n| backend | ";
  for (SolveStatus s : met) md << "`" << ToString(s) << "` | ";
  md << "flag right | false success (said solved, is not) | false failure (said failed, is solved) | flag from the "
        "return code |\n|---|";
  for (std::size_t i = 0; i < met.size() + 4; ++i) md << "---|";
  md << "\n";
  for (std::size_t k = 0; k < summary.size(); ++k) {
    const BackendSummary& b = summary[k];
    const ClaimAudit& a = audit[k];  // both in the order the backends first appear in the records
    md << "| " << b.solver << " | ";
    for (SolveStatus s : met) {
      const auto it = b.statuses.find(s);
      md << (it == b.statuses.end() ? 0 : it->second) << " | ";
    }
    md << Fraction(a.right, a.records) << " | " << Count(a.false_success) << " | " << a.false_failure << " | "
       << a.with_return_code << "/" << a.records << " |\n";
  }
  md << "\n";
}

// The fastest correct backend per size band (FastestCorrectPerBand), with the evidence: its correct answers, SGM,
// on how many problems it was the fastest, and the runner-up.
void WriteBandWinners(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BandWinner> winners = FastestCorrectPerBand(suite);
  if (winners.empty()) return;
  const std::map<std::string, double> floor = FloorTimes(suite);
  md << "**Fastest correct backend per size band**: among the backends with no wrong answer in the band, those "
        "with the most correct answers, and of them the smallest SGM time over the band (penalty as above, from the "
        "band's problems alone)"
     << (floor.empty() ? "" : "; *fastest / floor*: its median time over the floor on the band's problems it got right")
     << ":\n\n| size band | problems | fastest correct | correct | SGM time | fastest on | "
        "runner-up | its correct | its SGM time | runner-up / fastest |"
     << (floor.empty() ? "" : " fastest / floor |") << "\n|---|---|---|---|---|---|---|---|---|---|"
     << (floor.empty() ? "" : "---|") << "\n";
  for (const BandWinner& w : winners) {
    md << "| " << ToString(w.band) << " | " << w.problems << " | ";
    if (w.solver.empty()) {
      md << "none (every backend gave a wrong answer) | | | | | | | |" << (floor.empty() ? "" : " |") << "\n";
      continue;
    }
    md << "**" << w.solver << "** | " << w.correct << "/" << w.problems << " | " << Seconds(w.shifted_geomean)
       << " | " << w.fastest_on << " | " << w.runner_up << " | "
       << (w.runner_up.empty() ? "" : std::to_string(w.runner_up_correct) + "/" + std::to_string(w.problems))
       << " | " << (w.runner_up.empty() ? "" : Seconds(w.runner_up_geomean)) << " | "
       << (w.runner_up.empty() ? "" : G(w.runner_up_geomean / w.shifted_geomean) + "×") << " |";
    if (!floor.empty()) {
      std::vector<ReplayRecord> band;
      for (const ReplayRecord& r : suite.replay.records) {
        if (SizeBandOf(r.size) == w.band) band.push_back(r);
      }
      md << " " << FloorRatioCell(FloorRatios(band, floor, w.solver)) << " |";
    }
    md << "\n";
  }
  md << "\n";
}

// Every wrong answer, so a reader can check it (the first few per suite; results.csv has them all).
void WriteWrongAnswers(std::ostream& md, const SuiteResults& suite) {
  std::vector<const ReplayRecord*> wrong;
  for (const auto& r : suite.replay.records) {
    if (IsWrong(r.verdict)) wrong.push_back(&r);
  }
  if (wrong.empty()) return;
  constexpr std::size_t kListed = 30;
  md << "Wrong answers (" << wrong.size() << (wrong.size() > kListed ? ", the first 30" : "")
     << "):\n\n| problem | backend | verdict | status | residual | residual (eq.) | forward error | "
        "allowance | certificate |\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < std::min(wrong.size(), kListed); ++i) {
    const ReplayRecord& r = *wrong[i];
    md << "| " << r.problem << " | " << r.solver << " | " << ToString(r.verdict) << " | " << ToString(r.status)
       << " | " << G(r.residual_rel) << " | " << G(r.residual_scaled) << " | " << G(r.forward_error) << " | "
       << G(r.forward_allowance) << " | " << r.certificate << " |\n";
  }
  md << "\n";
}

// The paper suite against the generic sparse path (bench adds it: newton on sparse copies), over the problems both
// solve: the speed-ups and the fastest time over an arithmetic floor, each sorted.
struct SparsePathComparison {
  std::vector<double> speedups, over_floor;
};

SparsePathComparison CompareWithSparsePath(const SuiteResults& suite) {
  std::map<std::string, double> best, generic;
  std::map<std::string, int> sizes;
  for (const auto& r : suite.replay.records) {
    if (r.verdict != Verdict::kSolved) continue;
    if (r.solver == "newton-sparse-path") {
      generic[r.problem] = r.time_median;
    } else {
      auto [it, inserted] = best.emplace(r.problem, r.time_median);
      if (!inserted) it->second = std::min(it->second, r.time_median);
      sizes[r.problem] = r.size;
    }
  }
  SparsePathComparison c;
  for (const auto& [problem, t] : generic) {
    if (!best.count(problem)) continue;
    c.speedups.push_back(t / best.at(problem));
    // Arithmetic floor: one m×m factorization and two mat-vecs, m³/3 + 4m² flops, at one flop per nanosecond
    // (scalar code at ~1–3 GHz).
    const double m = sizes.at(problem);
    c.over_floor.push_back(best.at(problem) / ((m * m * m / 3.0 + 4.0 * m * m) * 1e-9));
  }
  std::sort(c.speedups.begin(), c.speedups.end());
  std::sort(c.over_floor.begin(), c.over_floor.end());
  return c;
}

void WriteSparsePathComparison(std::ostream& md, const SparsePathComparison& c) {
  if (c.speedups.empty()) return;
  const auto& ratios = c.speedups;
  const auto& floors = c.over_floor;
  md << "Fastest correct backend on each problem against the generic sparse path (the same problems with M stored "
        "sparse, solved by `newton` with its UMFPACK sparse LU forced, `newton.linear_solver=sparse`): speed-up median "
     << G(ratios[ratios.size() / 2]) << "×, min " << G(ratios.front()) << "×, max " << G(ratios.back())
     << "× over " << ratios.size() << " problems (goal ≥ 10×). Distance from the arithmetic alone (m³/3 + 4m² "
        "flops at 1 flop/ns): the fastest solve takes median "
     << G(floors[floors.size() / 2]) << "× that floor — the rest is the fixed cost of a call (option checks, "
        "cold start, the merit function).\n\n";
}

// Ours against the external adapters (siconos-*), per size: best of each side per problem, Siconos time / ours.
// in_process: Siconos timed in process (each Siconos problem's untimed first solve is the probe in its isolation
// worker, the timed ones call Siconos directly); through_worker: Siconos records timed through the worker
// (isolate=always, a probe that crashed, results from before the probe policy), each solve's IPC round trip included.
struct SiconosComparison {
  std::map<int, std::vector<double>> in_process, through_worker;  // m → sorted ratios
};

SiconosComparison CompareWithSiconos(const SuiteResults& suite) {
  std::map<std::string, double> ours, theirs, theirs_through_worker;
  std::map<std::string, int> sizes;
  for (const auto& r : suite.replay.records) {
    if (r.verdict != Verdict::kSolved || r.solver == "newton-sparse-path") continue;
    const bool siconos = r.solver.rfind("siconos-", 0) == 0;
    if (!siconos && IsExternalBackendName(r.solver)) continue;  // another library (bullet-*, dart-*): not ours
    auto& side = !siconos ? ours : r.timed_in_worker ? theirs_through_worker : theirs;
    auto [it, inserted] = side.emplace(r.problem, r.time_median);
    if (!inserted) it->second = std::min(it->second, r.time_median);
    sizes[r.problem] = r.size;
  }
  const auto by_size = [&](const std::map<std::string, double>& external) {
    std::map<int, std::vector<double>> ratios;
    for (const auto& [problem, t] : external) {
      if (ours.count(problem)) ratios[sizes.at(problem)].push_back(t / ours.at(problem));
    }
    for (auto& [m, r] : ratios) std::sort(r.begin(), r.end());
    return ratios;
  };
  return {by_size(theirs), by_size(theirs_through_worker)};
}

void WriteRatioTable(std::ostream& md, const std::map<int, std::vector<double>>& ratios) {
  md << "| m | problems | median ratio | min | max |\n|---|---|---|---|---|\n";
  for (const auto& [m, r] : ratios) {
    md << "| " << m << " | " << r.size() << " | " << G(r[r.size() / 2]) << "× | " << G(r.front()) << "× | "
       << G(r.back()) << "× |\n";
  }
  md << "\n";
}

// The headline compares in-process times only; the through-worker ones get a labelled footnote.
void WriteSiconosComparison(std::ostream& md, const SiconosComparison& c) {
  if (!c.in_process.empty()) {
    md << "Our best backend against Siconos' best (`siconos-*`; on each problem the fastest correct answer of each "
          "side), both timed in process: each problem's first Siconos solve, untimed, is the probe in the backend's "
          "isolation worker (a crash or hang there is a status); once it came back, the timed solves call Siconos directly (`isolate=first`, see "
          "`solvers/siconos/README.md`). On the problems both solve — Siconos time / our time:\n\n";
    WriteRatioTable(md, c.in_process);
  }
  if (!c.through_worker.empty()) {
    md << (c.in_process.empty() ? "" : "Footnote: ")
       << "Siconos records timed through the isolation worker (≈ 7 µs of inter-process communication per solve "
          "included: `isolate=always`, a problem whose probe crashed or timed out, or results from before the "
          "probe policy) — IPC-inclusive Siconos time / our time, not a comparison of the solvers:\n\n";
    WriteRatioTable(md, c.through_worker);
  }
}

// Dolan–Moré performance profile of the suite: dir/profile-SUITE.{png,svg,dat,gp} and its markdown.
void WritePerformanceProfile(std::ostream& md, const SuiteResults& suite, const std::string& dir,
                             bool explain = true) {
  const auto ratios = PerformanceRatios(suite);
  if (ratios.empty()) return;
  std::ostringstream data;
  double tau_max = 2.0;
  for (const auto& [solver, r] : ratios) {
    for (double v : r) {
      if (std::isfinite(v)) tau_max = std::max(tau_max, v);
    }
  }
  tau_max = std::min(tau_max * 1.5, 1e6);
  std::ostringstream g;
  const std::string stem = "profile-" + Safe(suite.suite);
  // The key outside the plot: with 20 backends it would cover the curves.
  g << "set logscale x 2\nset grid\nset key outside right top\n" << kTickFormat
    << "set xlabel 'tau (time / best time)'\nset ylabel 'fraction of problems'\nset yrange [0:1.02]\nset xrange [1:"
    << tau_max << "]\nset title " << GnuplotQuote("Performance profile, suite " + suite.suite) << "\nplot ";
  // A backend that solved no problem would be a flat line on the x-axis, hiding the others' start: named below.
  std::vector<std::string> never;
  int index = 0;
  for (const auto& [solver, r] : ratios) {
    if (r.empty() || !std::isfinite(r.front())) {
      never.push_back(solver);
      continue;
    }
    // Step function: (τ_i, i/N), extended to τ_max.
    const double n = static_cast<double>(r.size());
    data << "# " << solver << "\n1 0\n";
    int k = 0;
    for (double v : r) {
      if (!std::isfinite(v)) break;
      ++k;
      data << v << ' ' << k / n << '\n';
    }
    data << tau_max << ' ' << k / n << "\n\n\n";
    // Steps draw no point types, and colour + dash alone repeat past seven backends: about eight markers on each
    // curve, and a key entry showing line and marker together.
    const std::string style = BackendStyle(solver), file = GnuplotQuote(stem + ".dat");
    g << (index ? ", " : "") << file << " index " << index << " using 1:2 with steps " << style << " notitle, "
      << file << " index " << index << " using 1:2 every " << std::max(1, k / 8) << " with points " << style
      << " notitle, keyentry with linespoints " << style << " title " << GnuplotQuote(solver);
    ++index;
  }
  g << "\n";
  if (index > 0) {
    WriteFigure(dir, stem, data.str(), g.str(), 1100, 600);
    md << FigureMarkdown("performance profile, " + suite.suite, stem);
  }
  if (!explain && never.empty()) return;
  if (!explain) {
    md << "Not drawn (solved none of these problems):";
    for (std::size_t i = 0; i < never.size(); ++i) md << (i ? ", " : " ") << never[i];
    md << ".\n\n";
    return;
  }
  md << "Performance profile: ρ(τ) = the fraction of problems a backend solved within τ × the fastest solved time "
        "on that problem; a failure or a wrong answer never counts (it sits at τ = ∞), and problems no backend "
        "solved are left out.";
  if (!never.empty()) {
    md << " Not drawn, since they solved none of those problems:";
    for (std::size_t i = 0; i < never.size(); ++i) md << (i ? ", " : " ") << never[i];
    md << ".";
  }
  md << "\n\n";
}

// One (backend, tolerance) row of the tolerance sweep: medians over the swept problems.
struct SweepRow {
  std::string solver;
  double tolerance = 0.0;
  double forward_error = kNaN;  // median over the problems with a unique certified reference
  std::size_t with_reference = 0, problems = 0;
  int solved = 0;
  double residual = kNaN, residual_scaled = kNaN;  // achieved, median
  double time = kNaN;                              // median over every swept problem
  double time_with_reference = kNaN;               // median over the problems with a reference
};

// Loosest tolerance first per backend. A non-finite error counts as 1e300 (NaN residual_scaled: not defined).
std::vector<SweepRow> SweepRows(const SuiteResults& suite) {
  std::map<std::pair<std::string, double>, std::vector<const ReplayRecord*>> groups;  // (backend, −tolerance)
  for (const auto& r : suite.replay.sweep) groups[{r.solver, -r.tolerance}].push_back(&r);
  std::vector<SweepRow> rows;
  for (const auto& [key, rs] : groups) {
    std::vector<double> res, res_scaled, fwd, t, t_fwd;
    SweepRow row;
    row.solver = key.first;
    row.tolerance = -key.second;
    row.problems = rs.size();
    for (const auto* r : rs) {
      res.push_back(std::isfinite(r->residual_rel) ? r->residual_rel : 1e300);
      res_scaled.push_back(std::isfinite(r->residual_scaled) ? r->residual_scaled
                                                             : std::isnan(r->residual_scaled) ? kNaN : 1e300);
      t.push_back(r->time_median);
      if (!std::isnan(r->forward_error)) {
        fwd.push_back(std::isfinite(r->forward_error) ? r->forward_error : 1e300);
        t_fwd.push_back(r->time_median);
      }
      row.solved += r->verdict == Verdict::kSolved;
    }
    row.residual = MedianDefined(res);
    row.residual_scaled = MedianDefined(res_scaled);
    row.time = MedianDefined(t);
    row.forward_error = MedianDefined(fwd);
    row.with_reference = fwd.size();
    row.time_with_reference = MedianDefined(t_fwd);
    rows.push_back(row);
  }
  return rows;
}

// The tolerance ladder: success per backend at each tolerance of the sweep (BuildToleranceLadder).
void WriteToleranceLadder(std::ostream& md, const SuiteResults& suite) {
  const ToleranceLadder ladder = BuildToleranceLadder(suite);
  if (ladder.rows.empty()) return;
  std::set<std::string> problems;
  for (const auto& r : suite.replay.sweep) problems.insert(Instance(r));
  md << "**Tolerance ladder**: success (solved + correctly refused) per backend and tolerance on the "
     << problems.size() << " swept problems (`bench` sweeps 16 per suite spread evenly over it, 2 with `--quick`). "
        "Each rung is its own solve at that tolerance — an untimed warm-up, then at most 3 timed samples — judged at "
        "that tolerance; the times are in the folded table below. With the polish on (the default) an answer with "
        "the right active set is exact at every rung (`--no-polish` shows the algorithms' own trade-off). Blank: "
        "not run (`--backend-budget` spent).\n\n| backend | ";
  for (double t : ladder.tolerances) md << "tol " << G(t) << " | ";
  md << "\n|---|";
  for (std::size_t i = 0; i < ladder.tolerances.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& row : ladder.rows) {
    md << "| " << row.solver << " | ";
    for (std::size_t k = 0; k < ladder.tolerances.size(); ++k) md << Fraction(row.correct[k], row.problems[k]) << " | ";
    md << "\n";
  }
  md << "\n";
}

// Speed against error: the tolerance sweep. Two errors: the forward error ‖z − z*‖∞ (what a user reads, on the
// swept problems with a unique certified reference) and the residual reached (every swept problem).
void WriteToleranceSweep(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  if (suite.replay.sweep.empty()) return;
  md << "<details><summary>Speed against error, per backend and tolerance (medians over the swept problems; "
        "forward error over those with a unique certified reference)</summary>\n\n"
     << "| backend | tolerance | forward error (median) | with z* | achieved residual (median) | achieved "
        "residual, eq. (median) | time (median) | solved |\n|---|---|---|---|---|---|---|---|\n";
  std::map<std::string, std::vector<std::pair<double, double>>> by_forward, by_residual;
  for (const SweepRow& row : SweepRows(suite)) {
    md << "| " << row.solver << " | " << G(row.tolerance) << " | " << G(row.forward_error) << " | "
       << row.with_reference << "/" << row.problems << " | " << G(row.residual) << " | " << G(row.residual_scaled)
       << " | " << Seconds(row.time) << " | " << row.solved << "/" << row.problems << " |\n";
    by_residual[row.solver].emplace_back(std::max(row.residual, 1e-17), row.time);
    // Time over the same problems as the error: the median time of those with a reference.
    if (row.with_reference > 0) {
      by_forward[row.solver].emplace_back(std::max(row.forward_error, 1e-17), row.time_with_reference);
    }
  }
  md << "\n</details>\n\n";
  if (plots && !by_forward.empty()) {
    const std::string stem = "speed-forward-error-" + Safe(suite.suite);
    PlotCurves(by_forward, dir, stem, "forward error |z - z*|inf (median; problems with a unique certified z*)",
               "time per solve [s]", "Speed against forward error, suite " + suite.suite);
    md << FigureMarkdown("speed against forward error, " + suite.suite, stem);
  }
  if (plots) {
    const std::string stem = "speed-residual-" + Safe(suite.suite);
    PlotCurves(by_residual, dir, stem, "achieved relative natural residual (median)", "time per solve [s]",
               "Speed against residual, suite " + suite.suite);
    md << FigureMarkdown("speed against residual, " + suite.suite, stem);
  }
}

// ---- The MCP section: a suite whose records are MCP problem × start (ReplayRecord::start). ----

// Per backend and start label: correct answers (solved + correctly refused) over the problems with that start.
void WriteMcpStarts(std::ostream& md, const SuiteResults& suite) {
  std::vector<std::string> labels;
  std::map<std::pair<std::string, std::string>, std::pair<int, int>> cells;  // (backend, label) → correct, total
  for (const auto& r : suite.replay.records) {
    if (std::find(labels.begin(), labels.end(), r.start) == labels.end()) labels.push_back(r.start);
    auto& [correct, total] = cells[{r.solver, r.start}];
    correct += Correct(r);
    ++total;
  }
  md << "Success per start (solved + correctly refused / problems with that start; a start label names the "
        "published starting point of each problem):\n\n| backend | ";
  for (const auto& label : labels) md << "`" << Cell(label, 40) << "` | ";
  md << "\n|---|";
  for (std::size_t i = 0; i < labels.size(); ++i) md << "---|";
  md << "\n";
  for (const std::string& solver : Solvers(suite.replay.records)) {
    md << "| " << solver << " | ";
    for (const auto& label : labels) {
      const auto it = cells.find({solver, label});
      md << (it == cells.end() ? std::string("–")
                               : std::to_string(it->second.first) + "/" + std::to_string(it->second.second))
         << " | ";
    }
    md << "\n";
  }
  md << "\n";
}

// Which backend fails where, and with what status: every record that is not correct (wrong answers first).
void WriteMcpFailures(std::ostream& md, const SuiteResults& suite) {
  std::vector<const ReplayRecord*> failures;
  for (const auto& r : suite.replay.records) {
    if (!Correct(r)) failures.push_back(&r);
  }
  if (failures.empty()) {
    md << "Every backend is right on every problem × start.\n\n";
    return;
  }
  std::stable_sort(failures.begin(), failures.end(), [](const ReplayRecord* a, const ReplayRecord* b) {
    return IsWrong(a->verdict) > IsWrong(b->verdict);
  });
  constexpr std::size_t kListed = 40;
  md << "Where the backends fail (" << failures.size() << " problem × start × backend"
     << (failures.size() > kListed ? ", the first 40; results.csv has them all" : "")
     << "; wrong answers first):\n\n| problem | start | backend | verdict | status | message | residual (eq.) | "
        "forward error | allowance |\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < std::min(failures.size(), kListed); ++i) {
    const ReplayRecord& r = *failures[i];
    const std::string verdict(ToString(r.verdict));
    md << "| " << r.problem << " | " << Cell(r.start, 40) << " | " << r.solver << " | "
       << (IsWrong(r.verdict) ? "**" + verdict + "**" : verdict) << " | " << ToString(r.status) << " | "
       << Cell(r.message) << " | " << G(r.residual_scaled) << " | " << G(r.forward_error) << " | "
       << G(r.forward_allowance) << " |\n";
  }
  md << "\n";
}

// Speed against forward error: one point per problem × start a backend answered, where the forward error is
// defined (a reference certified unique, or every solution listed).
void WriteMcpSpeedAgainstError(std::ostream& md, const SuiteResults& suite, const std::string& dir) {
  std::map<std::string, std::vector<std::pair<double, double>>> points;
  for (const auto& r : suite.replay.records) {
    if (std::isnan(r.forward_error) || r.samples == 0) continue;
    points[r.solver].emplace_back(std::max(std::isfinite(r.forward_error) ? r.forward_error : 1e300, 1e-17),
                                  std::max(r.time_median, 1e-9));
  }
  if (points.empty()) return;
  const std::string stem = "speed-forward-error-" + Safe(suite.suite);
  PlotCurves(points, dir, stem, "forward error |z - z*|inf against the nearest reference (1e-17 = exact)",
             "time per solve [s]", "Speed against forward error, MCP suite " + suite.suite, true, "points");
  md << FigureMarkdown("speed against forward error, MCP suite " + suite.suite, stem);
}

void WriteMcpSection(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  std::set<std::string> problems, instances;
  for (const auto& r : suite.replay.records) problems.insert(r.problem), instances.insert(Instance(r));
  const std::string certified = CertificateCounts(suite);
  md << "## MCP suite `" << suite.suite << "`: " << suite.description << "\n\n"
     << problems.size() << " nonlinear MCPs, " << instances.size()
     << " problem × start (each published starting point is its own instance; times are cold solves from it); "
        "references: "
     << (certified.empty() ? "–" : certified)
     << ". Only backends that solve MCPs run here (`smcbench list` says: accepts nonlinear MCP): the others have no "
        "record and are not counted. The verdict is the box's with F's Jacobian J at the answer in place of M: "
        "residual (eq.) is the scale-free MCP residual (row i divided by max_j |J_ij|·c_j, variables in their units "
        "c, relative to 1 + max_i |z_i|/c_i) and must be ≤ tol; the forward error is judged against the nearest "
        "reference when the references list every solution, else against one certified unique. Success and SGM "
        "time are over problem × start.\n\n";
  WriteBackendTable(md, suite);
  WriteSolvedNothing(md, suite);
  WriteStatusesAndClaims(md, suite);
  WriteBandWinners(md, suite);
  WriteMcpStarts(md, suite);
  WriteMcpFailures(md, suite);
  if (plots) {
    WriteMcpSpeedAgainstError(md, suite, dir);
    WritePerformanceProfile(md, suite, dir);
  }
}

// ---- The AVI section: the `avi` suite's AVI × box backend records (bench/replay/avi_replay.h). ----

// The family of an AVI id "avi/<family>/...".
std::string AviFamily(const std::string& id) {
  const auto first = id.find('/');
  if (first == std::string::npos) return id;
  const auto second = id.find('/', first + 1);
  return id.substr(first + 1, second == std::string::npos ? std::string::npos : second - first - 1);
}

// Per backend: the verdicts and the median cold time over the AVIs it got right.
void WriteAviBackends(std::ostream& md, const SuiteResults& suite) {
  const std::map<std::string, double> floor = FloorTimes(suite);
  md << "| backend | AVIs | solved | correctly refused | **wrongly claimed** | **inaccurate** | **wrongly refused** | "
        "failed | median time (correct) |"
     << (floor.empty() ? "" : " time / floor |") << "\n|---|---:|---:|---:|---:|---:|---:|---:|---:|"
     << (floor.empty() ? "" : "---:|") << "\n";
  for (const std::string& solver : Solvers(suite.replay.records)) {
    std::map<Verdict, int> count;
    std::vector<double> times;
    int total = 0;
    for (const auto& r : suite.replay.records) {
      if (r.solver != solver) continue;
      ++total;
      ++count[r.verdict];
      if (Correct(r) && r.samples > 0) times.push_back(r.time_median);
    }
    md << "| " << solver << " | " << total << " | " << count[Verdict::kSolved] << " | "
       << count[Verdict::kCorrectlyRefused] << " | " << Count(count[Verdict::kWronglyClaimed]) << " | "
       << Count(count[Verdict::kInaccurate]) << " | " << Count(count[Verdict::kWronglyRefused]) << " | "
       << count[Verdict::kFailed] << " | " << (times.empty() ? std::string("–") : Seconds(MedianDefined(times)))
       << " |";
    if (!floor.empty()) md << " " << FloorRatioCell(FloorRatios(suite.replay.records, floor, solver)) << " |";
    md << "\n";
  }
  md << "\n";
  WriteFloorLine(md, suite);
}

// Per backend and family: correct answers (solved + correctly refused) over the family's AVIs.
void WriteAviFamilies(std::ostream& md, const SuiteResults& suite) {
  std::vector<std::string> families;
  std::map<std::pair<std::string, std::string>, std::pair<int, int>> cells;  // (backend, family) → correct, total
  for (const auto& r : suite.replay.records) {
    const std::string family = AviFamily(r.problem);
    if (std::find(families.begin(), families.end(), family) == families.end()) families.push_back(family);
    auto& [correct, total] = cells[{r.solver, family}];
    correct += Correct(r);
    ++total;
  }
  md << "Correct answers per family (solved + correctly refused / AVIs of the family):\n\n| backend | ";
  for (const auto& family : families) md << family << " | ";
  md << "\n|---|";
  for (std::size_t i = 0; i < families.size(); ++i) md << "---:|";
  md << "\n";
  for (const std::string& solver : Solvers(suite.replay.records)) {
    md << "| " << solver << " | ";
    for (const auto& family : families) {
      const auto& [correct, total] = cells[{solver, family}];
      md << correct << "/" << total << " | ";
    }
    md << "\n";
  }
  md << "\n";
}

// Every record that is not correct, wrong answers first.
void WriteAviFailures(std::ostream& md, const SuiteResults& suite) {
  std::vector<const ReplayRecord*> failures;
  for (const auto& r : suite.replay.records) {
    if (!Correct(r)) failures.push_back(&r);
  }
  if (failures.empty()) {
    md << "Every backend is right on every AVI.\n\n";
    return;
  }
  std::stable_sort(failures.begin(), failures.end(), [](const ReplayRecord* a, const ReplayRecord* b) {
    return IsWrong(a->verdict) > IsWrong(b->verdict);
  });
  constexpr std::size_t kListed = 40;
  md << "Where the backends fail (" << failures.size() << " AVI × backend"
     << (failures.size() > kListed ? ", the first 40; results.csv has them all" : "")
     << "; wrong answers first):\n\n| AVI | backend | verdict | status | message | residual (eq.) | forward error | "
        "allowance |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < std::min(failures.size(), kListed); ++i) {
    const ReplayRecord& r = *failures[i];
    const std::string verdict(ToString(r.verdict));
    md << "| " << r.problem << " | " << r.solver << " | " << (IsWrong(r.verdict) ? "**" + verdict + "**" : verdict)
       << " | " << ToString(r.status) << " | " << Cell(r.message) << " | " << G(r.residual_scaled) << " | "
       << G(r.forward_error) << " | " << G(r.forward_allowance) << " |\n";
  }
  md << "\n";
}

void WriteAviSection(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  std::set<std::string> problems;
  std::map<std::string, int> families;
  for (const auto& r : suite.replay.records) {
    if (problems.insert(r.problem).second) ++families[AviFamily(r.problem)];
  }
  std::string family_counts;
  for (const auto& [family, count] : families) {
    family_counts += (family_counts.empty() ? "" : ", ") + std::to_string(count) + " " + family;
  }
  const std::string certified = CertificateCounts(suite);
  md << "## AVI suite `" << suite.suite << "`: " << suite.description << "\n\n"
     << problems.size() << " affine variational inequalities 0 ∈ Mλ + q + N_P(λ), P = {Hλ ≥ K, Eλ = f} ("
     << family_counts << "); references (of the reduction): " << (certified.empty() ? "–" : certified)
     << ProvedCounts(suite) << ". Every backend that solves box-MLCPs runs here, on the exact reduction to a box-MLCP in (λ, μ, ν) "
        "(SolveAvi, docs/avi.md); times are cold SolveAvi calls (building the reduction, the backend's solve, the "
        "mapping back). The verdict is JudgeAvi's, recomputed from the answer, never the backend's flag: residual "
        "(eq.) is the natural residual of the normalized reduction (rows of H, E divided by their largest entry, "
        "M and q by max|M_ij|), and λ's complementarity and feasibility in units of λ must also be ≤ tol; the "
        "forward error ‖λ − λ*‖∞ is judged only where λ is unique (M + Mᵀ positive definite, or certified), so "
        "on the twisting steps (M singular, λ not unique) the residual rule alone decides. AVIs with no solution "
        "must be refused.\n\n";
  WriteAviBackends(md, suite);
  WriteAviFamilies(md, suite);
  WriteStatusesAndClaims(md, suite);
  WriteAviFailures(md, suite);
  if (plots) WritePerformanceProfile(md, suite, dir);
}

// The growth exponent of the floor's times in m (GrowthExponent of the floor records as one backend's).
double FloorGrowthExponent(const SuiteResults& suite) {
  SuiteResults floor;
  floor.replay.records = suite.replay.floor;
  return GrowthExponent(floor, kFloorSolver);
}

// Scale: time against m with the fitted exponent (the scale suite, when it has at least three sizes).
void WriteScaleTable(std::ostream& md, const SuiteResults& suite) {
  std::set<int> sizes;
  for (const auto& r : suite.replay.records) sizes.insert(r.size);
  if (sizes.size() < 3 || suite.suite != "scale") return;
  md << "| backend | fitted exponent of time in m | ";
  for (int m : sizes) md << "m = " << m << " | ";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < sizes.size(); ++i) md << "---|";
  md << "\n";
  for (const std::string& solver : Solvers(suite.replay.records)) {
    md << "| " << solver << " | " << G(GrowthExponent(suite, solver)) << " | ";
    for (int m : sizes) {
      std::string cell = "–";
      for (const auto& r : suite.replay.records) {
        if (r.solver == solver && r.size == m) {
          cell = r.verdict == Verdict::kSolved ? Seconds(r.time_median) : std::string(ToString(r.status));
        }
      }
      md << cell << " | ";
    }
    md << "\n";
  }
  if (!suite.replay.floor.empty()) {  // not a backend: the time of one factorization, for comparison
    md << "| *floor: one factorization* | " << G(FloorGrowthExponent(suite)) << " | ";
    for (int m : sizes) {
      std::vector<double> t;
      for (const auto& r : suite.replay.floor) {
        if (r.size == m && r.samples > 0) t.push_back(r.time_median);
      }
      std::sort(t.begin(), t.end());
      md << (t.empty() ? std::string("–") : Seconds(MedianOfSorted(t))) << " | ";
    }
    md << "\n";
  }
  md << "\n";
}

// The bands a suite's records fall in, smallest first.
std::vector<SizeBand> BandsOf(const std::vector<ReplayRecord>& records) {
  std::set<SizeBand> bands;
  for (const ReplayRecord& r : records) bands.insert(SizeBandOf(r.size));
  return {bands.begin(), bands.end()};
}

// Every backend table and profile again per size band (one table and one figure per band), when the suite spans
// more than one band: rankings flip with size.
void WritePerBand(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots,
                  const std::string& what) {
  const std::vector<SizeBand> bands = BandsOf(suite.replay.records);
  if (bands.size() < 2) {
    if (bands.size() == 1) md << "Every " << what << " record is in the band " << ToString(bands[0]) << ".\n\n";
    return;
  }
  md << "**Per size band (" << what << ")**: the table above again, one band at a time (penalties from the band's "
        "problems alone)" << (plots ? ", with its performance profile" : "") << ".\n\n";
  for (SizeBand band : bands) {
    const SuiteResults slice = SizeBandSlice(suite, band);
    md << "*" << what << ", " << ToString(band) << "* (" << slice.problems << " problems):\n\n";
    WriteBackendTableOnly(md, slice);
    if (plots) WritePerformanceProfile(md, slice, dir, /*explain=*/false);
  }
}

// "1.8× [0.5 – 3] (12)": median [min – max] (n) of sorted ratios; empty when there are none.
std::string RatioSpread(const std::vector<double>& r) {
  if (r.empty()) return "";
  return G(r[r.size() / 2]) + "× [" + G(r.front()) + " – " + G(r.back()) + "] (" + std::to_string(r.size()) + ")";
}

// The cold peer table again per class × band (OursAgainstPeersPerClass), with our best over the floor.
void WritePeerRatiosPerClass(std::ostream& md, const SuiteResults& suite, const std::set<std::string>& families) {
  const std::vector<PeerClassRow> rows = OursAgainstPeersPerClass(suite);
  if (rows.empty()) return;
  const bool floor = !suite.replay.floor.empty();
  md << "**The same per class** (matrix class and bounds from the problems' tags × size band, cold): library's best "
        "/ ours as above"
     << (floor ? "; *ours / floor*: our fastest correct time over one factorization of M, median [min – max] (n)"
               : "; floor not measured in this run")
     << ".\n\n| class | size band |";
  for (const std::string& f : families) md << " " << f << " |";
  if (floor) md << " ours / floor |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < families.size() + (floor ? 1 : 0); ++i) md << "---|";
  md << "\n";
  for (const PeerClassRow& row : rows) {
    if (row.by_peer.empty()) continue;  // no library solved a problem of the class that we solved too
    md << "| " << ClassName(row.problem_class) << " | " << ToString(row.problem_class.band) << " |";
    for (const std::string& f : families) {
      const auto it = row.by_peer.find(f);
      md << " " << (it == row.by_peer.end() ? std::string() : RatioSpread(it->second)) << " |";
    }
    if (floor) md << " " << RatioSpread(row.ours_over_floor) << " |";
    md << "\n";
  }
  md << "\n";
}

// Ours against the best of each external library per band, cold and warm (OursAgainstPeersPerBand).
void WritePeerRatios(std::ostream& md, const SuiteResults& suite) {
  const std::vector<PeerRatioRow> rows = OursAgainstPeersPerBand(suite);
  if (rows.empty()) return;
  std::set<std::string> families;
  for (const PeerRatioRow& row : rows) {
    for (const auto& [family, ratios] : row.by_peer) families.insert(family);
  }
  md << "**Ours against each library's best, per size band, cold and warm**: on each problem (warm: each "
        "sequence, time per step) the fastest correct answer of our backends and of each library's (`siconos-*`, "
        "`bullet-*`, `dart-*`); the library's time / ours, median [min – max] over the problems both solve (n). "
        "Above 1×: ours is faster.\n\n| size band | track |";
  for (const std::string& f : families) md << " " << f << " |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < families.size(); ++i) md << "---|";
  md << "\n";
  for (const PeerRatioRow& row : rows) {
    md << "| " << ToString(row.band) << " | " << (row.warm ? "warm" : "cold") << " |";
    for (const std::string& f : families) {
      const auto it = row.by_peer.find(f);
      if (it == row.by_peer.end()) {
        md << " |";
        continue;
      }
      const std::vector<double>& r = it->second;
      md << " " << G(r[r.size() / 2]) << "× [" << G(r.front()) << " – " << G(r.back()) << "] (" << r.size() << ") |";
    }
    md << "\n";
  }
  md << "\n";
  WritePeerRatiosPerClass(md, suite, families);
}

// The warm track of a suite: per backend over its sequences (time per step), the winners per band, the profile, per
// band again, and per sequence its counts.
void WriteWarmTrack(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  if (suite.warm.empty()) return;
  const SuiteResults warm = WarmTrackAsSuite(suite);
  md << "### Warm track of suite `" << suite.suite << "`\n\n"
     << warm.problems << " sequences of one-step problems (M, l, u fixed, q moving) replayed in order, every step "
        "started from the previous step's answer by each backend's own warm mechanism: ours through one solve "
        "session whose reused active set answers when it still fits; `siconos-*`, `bullet-*` and `dart-*` through "
        "the same adapter instance kept alive (Siconos' direct solvers keep their cache) with the previous answer "
        "as start. Time = seconds per step, the median over repeats of the whole sequence (its set-up included). "
        "A sequence counts as solved only when every step is solved by the verdict of the cold records.\n\n";
  WriteBackendTableOnly(md, warm);
  WriteBandWinners(md, warm);
  if (plots) WritePerformanceProfile(md, warm, dir, /*explain=*/false);
  WritePerBand(md, warm, dir, plots, "warm");
  // Per sequence: the counts, and its fastest correct backend.
  std::map<std::string, std::vector<const WarmRecord*>> by_sequence;
  for (const WarmRecord& w : suite.warm) by_sequence[w.record.problem].push_back(&w);
  md << "Per sequence: steps, active-set changes between consecutive steps (of the fastest correct backend's "
        "answers), its pivots or iterations over the sequence, and our fastest backend's reused-set steps and "
        "fallbacks (steps where the previous active set did not answer and the backend ran).\n\n"
        "| sequence | source | m | steps | active-set changes | fastest correct | time per step | its iterations | "
        "ours fastest | reused / fallbacks | correct backends |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [sequence, records] : by_sequence) {
    const WarmRecord* best = nullptr;
    const WarmRecord* ours = nullptr;
    int correct = 0;
    for (const WarmRecord* w : records) {
      if (w->record.verdict != Verdict::kSolved) continue;
      ++correct;
      if (!best || w->record.time_median < best->record.time_median) best = w;
      if (w->counts.reuse && (!ours || w->record.time_median < ours->record.time_median)) ours = w;
    }
    const WarmRecord& head = *records.front();
    md << "| " << sequence << " | " << ToString(head.source) << " | " << head.record.size << " | "
       << head.counts.steps << " | " << (best ? std::to_string(best->counts.active_set_changes) : "") << " | "
       << (best ? best->record.solver : "none") << " | " << (best ? Seconds(best->record.time_median) : "") << " | "
       << (best ? std::to_string(best->counts.iterations) : "") << " | " << (ours ? ours->record.solver : "")
       << " | "
       << (ours ? std::to_string(ours->counts.reused_steps) + " / " + std::to_string(ours->counts.fallbacks) : "")
       << " | " << correct << "/" << records.size() << " |\n";
  }
  md << "\n";
}

// The suite without its records whose timed solves could not all start cold (mode "cached": bench/replay/replay.h,
// TimeSolves), which no cold table or profile may compare; *cached receives "backend on problem" for each.
SuiteResults WithoutCachedRecords(const SuiteResults& suite, std::vector<std::string>* cached) {
  SuiteResults cold = suite;
  auto& records = cold.replay.records;
  for (const auto& r : records) {
    if (r.mode == "cached") cached->push_back(r.solver + " on " + Instance(r));
  }
  const auto is_cached = [](const ReplayRecord& r) { return r.mode == "cached"; };
  records.erase(std::remove_if(records.begin(), records.end(), is_cached), records.end());
  return cold;
}

// The suite without its records cut by a time budget (mode "cut": bench/replay/warm_track.h), which have no verdict
// and so belong in no table; *cut receives them.
SuiteResults WithoutCutRecords(const SuiteResults& suite, std::vector<ReplayRecord>* cut) {
  SuiteResults kept = suite;
  const auto is_cut = [](const ReplayRecord& r) { return r.mode == kCutMode; };
  for (const auto& r : suite.replay.records) if (is_cut(r)) cut->push_back(r);
  for (const auto& w : suite.warm) if (is_cut(w.record)) cut->push_back(w.record);
  auto& records = kept.replay.records;
  records.erase(std::remove_if(records.begin(), records.end(), is_cut), records.end());
  kept.warm.erase(std::remove_if(kept.warm.begin(), kept.warm.end(), [&](const WarmRecord& w) {
    return is_cut(w.record); }), kept.warm.end());
  return kept;
}

void WriteCutNote(std::ostream& md, const std::vector<ReplayRecord>& cut) {
  if (cut.empty()) return;
  md << "<details><summary>Cut by a time budget: " << cut.size() << " job(s), neither solved nor failed and in no "
     << "table above (`bench --full` runs them to the end)</summary>\n\n| backend | problem or sequence | how far "
     << "|\n|---|---|---|\n";
  for (const ReplayRecord& r : cut) md << "| " << r.solver << " | " << Instance(r) << " | " << r.message << " |\n";
  md << "\n</details>\n\n";
}

void WriteCachedNote(std::ostream& md, const std::vector<std::string>& cached) {
  if (cached.empty()) return;
  md << "Left out of the tables and profiles above: " << cached.size()
     << " record(s) whose timed solves could not all start cold (mode `cached`): ";
  for (std::size_t i = 0; i < cached.size(); ++i) md << (i ? ", " : "") << cached[i];
  md << ".\n\n";
}

void WriteSuite(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  if (suite.replay.records.empty() && suite.replay.sweep.empty()) {
    md << "## Suite `" << suite.suite << "`: " << suite.description << "\n\nNo records: no chosen backend ran on it "
       << "(an MCP suite runs only on the backends that solve MCPs, an AVI suite on those that solve box-MLCPs).\n\n";
    return;
  }
  if (IsMcpSuite(suite)) return WriteMcpSection(md, suite, dir, plots);
  if (IsAviSuite(suite)) return WriteAviSection(md, suite, dir, plots);
  WriteSuiteSummary(md, suite);
  WriteSolvedNothing(md, suite);
  WriteStatusesAndClaims(md, suite);
  WriteBandWinners(md, suite);
  WriteWrongAnswers(md, suite);
  WriteSparsePathComparison(md, CompareWithSparsePath(suite));
  WriteSiconosComparison(md, CompareWithSiconos(suite));
  WritePeerRatios(md, suite);
  if (plots) WritePerformanceProfile(md, suite, dir);
  WritePerBand(md, suite, dir, plots, "cold");
  WriteToleranceLadder(md, suite);
  WriteToleranceSweep(md, suite, dir, plots);
  WriteScaleTable(md, suite);
  WriteWarmTrack(md, suite, dir, plots);
}

// The time-stepper: warm against cold starts, per scene and backend (records come in warm, cold pairs).
void WriteWarmStart(std::ostream& md, const StepperStudy& st) {
  md << "## Time-stepper: warm against cold starts\n\n"
     << "Each scene's own run (docs/scenes.md settings), every step's one-step problem started from the previous s "
        "(warm) or from Π(0) (cold).\n\n| scene | backend | warm: time/step | cold: time/step | cold/warm | "
        "iterations/step warm | cold |\n|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i + 1 < st.warm_start.size(); i += 2) {
    const auto& w = st.warm_start[i];
    const auto& c = st.warm_start[i + 1];
    md << "| " << w.scene << " | " << w.solver << (w.ok && c.ok ? "" : " (failed steps)") << " | "
       << Seconds(w.seconds_per_step) << " | " << Seconds(c.seconds_per_step) << " | "
       << G(c.seconds_per_step / w.seconds_per_step) << " | " << G(w.iterations_per_step) << " | "
       << G(c.iterations_per_step) << " |\n";
  }
}

using WorkPrecisionLines = std::map<std::string, std::vector<const WorkPrecisionRecord*>>;  // label → h halved

// One scene's line of the work-precision section: per label, x error and time from the largest h to the smallest.
void WriteWorkPrecisionText(std::ostream& md, const std::string& scene, const WorkPrecisionLines& lines) {
  md << "**" << scene << "**: ";
  for (const auto& [label, rs] : lines) {
    md << label << ": x error " << G(rs.front()->error) << " → " << G(rs.back()->error) << " in "
       << Seconds(rs.front()->seconds) << " → " << Seconds(rs.back()->seconds);
    double worst_s = kNaN;
    std::int64_t certified = 0, steps = 0;
    for (const auto* r : rs) {
      worst_s = MaxDefined(worst_s, r->s_forward_error);
      certified += r->s_certified_steps;
      steps += r->steps;
    }
    if (certified > 0) md << ", s per-step error ≤ " << G(worst_s) << " (" << certified << "/" << steps << " steps)";
    md << "; ";
  }
  md << "\n\n";
}

// One scene's work-precision figures: time against the x error, and against the per-step error of s.
void WriteWorkPrecisionFigures(std::ostream& md, const std::string& dir, const std::string& scene,
                               const WorkPrecisionLines& lines) {
  std::map<std::string, std::vector<std::pair<double, double>>> by_x, by_s;
  for (const auto& [label, rs] : lines) {
    for (const auto* r : rs) {
      by_x[label].emplace_back(std::max(r->error, 1e-17), r->seconds);
      // A certified exact answer has error 0: drawn at 1e-17, the bottom of the axis.
      if (!std::isnan(r->s_forward_error)) by_s[label].emplace_back(std::max(r->s_forward_error, 1e-17), r->seconds);
    }
  }
  const std::string stem = "work-precision-" + Safe(scene);
  PlotCurves(by_x, dir, stem, "trajectory error of x against a finer reference run (max)", "run time [s]",
             "Work-precision (trajectory error of x), " + scene, /*sort_by_x=*/false);
  md << FigureMarkdown("work-precision, " + scene, stem);
  if (by_s.empty()) return;
  const std::string stem_s = "work-precision-s-" + Safe(scene);
  PlotCurves(by_s, dir, stem_s, "per-step forward error of s against certified solutions (max; 1e-17 = exact)",
             "run time [s]", "Work-precision (per-step forward error of s), " + scene, /*sort_by_x=*/false);
  md << FigureMarkdown("work-precision against the per-step error of s, " + scene, stem_s);
}

void WriteWorkPrecision(std::ostream& md, const StepperStudy& st, const std::string& dir, bool plots) {
  md << "\n## Time-stepper: work-precision\n\nRun time (set-up included, median of repeats) against two errors, h "
        "halved from the scene's own: the **trajectory error of x** (max over the grid of ‖x_k − x_ref(t_k)‖∞, "
        "x_ref a finer reference run: implicit Euler with lemke at the smallest h / "
     << G(st.reference_h_factor)
     << "; mostly discretization error), and the **per-step forward error of s** (max of ‖s_k − s*_k‖∞ over "
        "the steps the backend solved, s*_k the certified solution of step k's own one-step problem where it is "
        "proven unique: the solver's error alone, in the units of the control; 0 = exact).\n\n";
  std::map<std::string, WorkPrecisionLines> by_scene;
  for (const auto& r : st.work_precision) {
    by_scene[r.scene][r.method == "explicit" ? std::string("explicit Euler") : "implicit, " + r.solver].push_back(&r);
  }
  for (const auto& [scene, lines] : by_scene) {
    WriteWorkPrecisionText(md, scene, lines);
    if (plots) WriteWorkPrecisionFigures(md, dir, scene, lines);
  }
}

}  // namespace

std::string WriteBenchReport(const std::string& dir, bool plots) {
  json env;
  const BenchResults results = ReadBenchResults(dir, &env);
  if (plots && !GnuplotAvailable()) {
    throw InvalidInputError("report: the plots need gnuplot (Debian package gnuplot-nox); install it or pass --no-plots");
  }
  std::ostringstream md;
  WriteHeader(md, dir, results, env);
  WriteSummary(md, results);
  for (const SuiteResults& suite : results.suites) {
    std::vector<std::string> cached;
    std::vector<ReplayRecord> cut;
    WriteSuite(md, WithoutCachedRecords(WithoutCutRecords(suite, &cut), &cached), dir, plots);
    WriteCachedNote(md, cached);
    WriteCutNote(md, cut);
  }
  if (results.has_stepper) {
    WriteWarmStart(md, results.stepper);
    WriteWorkPrecision(md, results.stepper, dir, plots);
  }
  WriteFailureList(md, results);
  WriteVerdictAppendix(md, results);
  const std::string text = md.str();
  std::ofstream out(fs::path(dir) / "report.md");
  out << text;
  if (!out) throw InvalidInputError("report: cannot write " + (fs::path(dir) / "report.md").string());
  return text;
}

}  // namespace smcbench
