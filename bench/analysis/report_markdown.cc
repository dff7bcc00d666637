// `smcbench report`: report_markdown.h. The report is made in named phases (WriteBenchReport, at the end).
#include "bench/analysis/report_markdown.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "bench/analysis/markdown_sections.h"
#include "bench/analysis/record_facts.h"
#include "bench/analysis/report_figures.h"
#include "bench/figures/gnuplot_figure.h"
#include "bench/replay/warm_track.h"

namespace smcbench {

const char* const kVerdictInTwoSentences =
    "An answer z counts as solved when its status is solved and, recomputed by us from z, (1) the natural residual "
    "‖z − Π[l,u](z − w)‖∞ is ≤ tol·(1 + ‖q‖∞) and (2) the natural residual of the row-equilibrated problem (each "
    "row of M and q divided by d_i = max_j |M_ij|) is ≤ tol·(1 + ‖z‖∞). Where a certified reference z* proves the "
    "solution unique, also ‖z − z*‖∞ ≤ 10·max(1, μ)·tol·(1 + ‖z*‖∞), with μ = ‖(D⁻¹M)_FF⁻¹‖∞ the conditioning of "
    "z*'s free rows; a claim that no solution exists, on a problem known to have one, is wrongly refused.";

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

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace markdown;

void WriteCutNote(std::ostream& md, const std::vector<ReplayRecord>& cut) {
  if (cut.empty()) return;
  md << "<details><summary>Cut by a time budget: " << cut.size() << " job(s), neither solved nor failed and in no "
     << "table above (`bench --full` runs them to the end)</summary>\n\n| backend | problem or sequence | how far "
     << "|\n|---|---|---|\n";
  for (const ReplayRecord& r : cut) md << "| " << r.solver << " | " << InstanceOf(r) << " | " << r.message << " |\n";
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
  if (suite.replay.records.empty() && suite.replay.sweep.empty() && suite.warm.empty()) {
    md << "## Suite `" << suite.suite << "`: " << suite.description << "\n\nNo records: no chosen backend ran on it "
       << "(an MCP suite runs only on the backends that solve MCPs, an AVI suite on those that solve box-MLCPs).\n\n";
    return;
  }
  if (IsMcpSuite(suite)) return WriteMcpSection(md, suite, dir, plots);
  if (IsAviSuite(suite)) return WriteAviSection(md, suite, dir, plots);
  if (suite.replay.records.empty() && suite.replay.sweep.empty()) {  // its warm sequences alone were chosen
    md << "## Suite `" << suite.suite << "`: " << suite.description << "\n\n";
    return WriteWarmTrack(md, suite, dir, plots);
  }
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
