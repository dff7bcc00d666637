// perf_probe: the measuring half of the perf gate (tools/perf-check and tools/perf-update drive it).
//   perf_probe list                         the tracked figures
//   perf_probe measure --out F [--filter R]  natively: wall-clock per unit (median of samples);
//                                            under `valgrind --tool=callgrind --collect-atstart=no`: one callgrind
//                                            dump per figure (its id as the trigger), counting only Run()
//   perf_probe collect --units F --callgrind DIR [--wallclock F] --out F
//                                            instructions per unit from the dumps, merged with the wall-clock run
//   perf_probe compare --baseline F --current F [--threshold 0.05] [--history CSV] [--markdown F]
//                                            the table; exit 1 if the gate fails
#include <valgrind/callgrind.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/perf/callgrind_dump.h"
#include "bench/perf/perf_figures.h"
#include "bench/perf/perf_record.h"
#include "bench/replay/results_io.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kWallclockSamples = 7;
constexpr double kMinSampleSeconds = 2e-3;  // each wall-clock sample runs the workload at least this long

bool Refused(SolveStatus s) { return s == SolveStatus::kSizeLimit || s == SolveStatus::kNotApplicable; }

double Seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// Median and spread of ns per unit over kWallclockSamples samples of `repeats` runs each.
void MeasureWallclock(PerfWorkload& w, PerfFigure* f) {
  int repeats = 1;
  for (;;) {  // calibrate: a sample lasts at least kMinSampleSeconds
    const auto start = Clock::now();
    for (int r = 0; r < repeats; ++r) w.Run();
    if (Seconds(start, Clock::now()) >= kMinSampleSeconds || repeats >= (1 << 20)) break;
    repeats *= 2;
  }
  std::vector<double> ns;
  for (int s = 0; s < kWallclockSamples; ++s) {
    const auto start = Clock::now();
    for (int r = 0; r < repeats; ++r) w.Run();
    ns.push_back(1e9 * Seconds(start, Clock::now()) / (static_cast<double>(repeats) * static_cast<double>(w.units())));
  }
  std::sort(ns.begin(), ns.end());
  f->ns = ns[ns.size() / 2];
  f->ns_min = ns.front();
  f->ns_max = ns.back();
}

int Measure(const std::string& out, const std::string& filter) {
  const bool callgrind = RUNNING_ON_VALGRIND != 0;
  const std::regex pattern(filter.empty() ? std::string(".*") : filter);
  PerfRun run;
  run.environment = BenchEnvironment();
  run.environment["measure"] = callgrind ? "callgrind" : "wallclock";
  for (const PerfCase& c : PerfCases()) {
    if (!std::regex_search(c.id, pattern)) continue;
    std::unique_ptr<PerfWorkload> w = c.make();
    w->Run();  // warm-up: sizes every workspace, so the measured runs are the steady state
    if (Refused(w->status())) continue;
    PerfFigure f;
    f.id = c.id;
    f.unit = c.unit;
    f.units = w->units();
    f.status = std::string(ToString(w->status()));
    if (callgrind) {
      CALLGRIND_ZERO_STATS;
      CALLGRIND_TOGGLE_COLLECT;
      w->Run();
      CALLGRIND_TOGGLE_COLLECT;
      CALLGRIND_DUMP_STATS_AT(c.id.c_str());
    } else {
      MeasureWallclock(*w, &f);
    }
    std::cerr << "perf_probe: " << c.id << " (" << f.status << ")\n";
    run.figures.push_back(std::move(f));
  }
  if (run.figures.empty()) throw InvalidInputError("perf_probe: no figure matches --filter '" + filter + "'");
  WritePerfRun(run, out);
  return 0;
}

int Collect(const std::string& units_path, const std::string& dir, const std::string& wallclock,
            const std::string& out) {
  PerfRun run = ReadPerfRun(units_path);
  if (run.environment.value("measure", std::string()) != "callgrind") {
    throw InvalidInputError(units_path + " was not written under callgrind (run it through tools/perf-check)");
  }
  std::map<std::string, double> totals;  // trigger → instructions
  if (!fs::is_directory(dir)) throw InvalidInputError("cannot read callgrind folder '" + dir + "'");
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().rfind("callgrind.out", 0) != 0) continue;
    std::ifstream in(entry.path());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const CallgrindDump dump = ParseCallgrindDump(text, entry.path().string());
    if (!dump.trigger.empty()) totals[dump.trigger] += dump.instructions;
  }
  for (PerfFigure& f : run.figures) {
    const auto it = totals.find(f.id);
    if (it == totals.end()) throw InvalidInputError("no callgrind dump for figure '" + f.id + "' in " + dir);
    f.instructions = it->second / static_cast<double>(f.units);
  }
  run.environment["measure"] = "callgrind+wallclock";
  if (!wallclock.empty()) run = MergePerfRuns(run, ReadPerfRun(wallclock));
  WritePerfRun(run, out);
  return 0;
}

int Compare(const std::string& baseline, const std::string& current, double threshold, const std::string& history,
            const std::string& markdown) {
  const PerfRun now = ReadPerfRun(current);
  const PerfComparison c = ComparePerfRuns(ReadPerfRun(baseline), now, threshold);
  const std::string table = FormatComparison(c);
  std::cout << table;
  if (!markdown.empty()) {
    std::ofstream md(markdown);
    md << table;
    if (!md) throw InvalidInputError("cannot write '" + markdown + "'");
  }
  if (!history.empty()) AppendPerfHistory(history, now, c);
  return c.failed() ? 1 : 0;
}

}  // namespace
}  // namespace smcbench

int main(int argc, char** argv) {
  CLI::App app{"perf_probe: instruction counts (callgrind) and wall-clock of the perf gate's figures"};
  app.require_subcommand(1);
  std::string out, filter, units, callgrind_dir, wallclock, baseline, current, history, markdown;
  double threshold = 0.05;
  CLI::App* list = app.add_subcommand("list", "print the tracked figures' ids");
  CLI::App* measure = app.add_subcommand("measure", "measure every figure (natively: wall-clock; under callgrind: "
                                                    "one dump per figure)");
  measure->add_option("--out", out, "the JSON record to write")->required();
  measure->add_option("--filter", filter, "only figures whose id matches this regular expression");
  CLI::App* collect = app.add_subcommand("collect", "instructions per unit from the callgrind dumps");
  collect->add_option("--units", units, "the record `measure` wrote under callgrind")->required();
  collect->add_option("--callgrind", callgrind_dir, "the folder of the callgrind.out.* dumps")->required();
  collect->add_option("--wallclock", wallclock, "the record of a native `measure` run to merge");
  collect->add_option("--out", out, "the merged record to write")->required();
  CLI::App* compare = app.add_subcommand("compare", "compare a record to the baseline; exit 1 if the gate fails");
  compare->add_option("--baseline", baseline, "e.g. results/baseline/perf.json")->required();
  compare->add_option("--current", current, "the record `collect` wrote")->required();
  compare->add_option("--threshold", threshold, "relative regression that fails the gate")->capture_default_str();
  compare->add_option("--history", history, "append one CSV line per figure to this file");
  compare->add_option("--markdown", markdown, "also write the table to this file");
  CLI11_PARSE(app, argc, argv);
  try {
    if (list->parsed()) {
      for (const auto& c : smcbench::PerfCases()) std::cout << c.id << "\n";
      return 0;
    }
    if (measure->parsed()) return smcbench::Measure(out, filter);
    if (collect->parsed()) return smcbench::Collect(units, callgrind_dir, wallclock, out);
    return smcbench::Compare(baseline, current, threshold, history, markdown);
  } catch (const std::exception& e) {
    std::cerr << "perf_probe: " << e.what() << "\n";
    return 2;
  }
}
