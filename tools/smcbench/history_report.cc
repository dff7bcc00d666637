#include "tools/smcbench/history_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "bench/figures/gnuplot_figure.h"
#include "bench/perf/perf_record.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

constexpr int kRunsShown = 6;  // columns of the table: the last runs

std::string Backend(const std::string& id) { return id.substr(id.rfind('/') + 1); }

}  // namespace

std::string WritePerfHistoryReport(const std::string& history_csv, const std::string& dir, bool plots) {
  const std::vector<PerfHistoryRow> rows = ReadPerfHistory(history_csv);
  if (rows.empty()) throw InvalidInputError("perf history '" + history_csv + "' has no runs yet");
  // A run is one (date, git SHA) pair, in the order the runs were appended.
  std::vector<std::string> runs, run_labels;
  std::map<std::string, int> run_index;
  std::vector<std::string> figures;
  std::map<std::string, std::map<int, double>> values;  // figure → run → instructions per unit
  for (const PerfHistoryRow& r : rows) {
    const std::string key = r.date + " " + r.git_sha;
    auto [it, fresh] = run_index.emplace(key, static_cast<int>(runs.size()));
    if (fresh) {
      runs.push_back(key);
      run_labels.push_back(r.git_sha.substr(0, 8));
    }
    if (!values.count(r.id)) figures.push_back(r.id);
    values[r.id][it->second] = r.instructions;
  }
  const int n = static_cast<int>(runs.size());

  std::ostringstream md;
  md << "# Perf history\n\n"
     << "Made by `smcbench report --history " << history_csv << "` from the " << n
     << " runs that `tools/perf-check --history` appended (first: " << runs.front() << "; last: " << runs.back()
     << "). Instructions per solve or per step under callgrind: deterministic for a given build, so a change "
        "between runs is a change of the code, the compiler or a library, not noise.\n\n";
  if (plots) md << "![instructions relative to the first run, per backend](history.png)\n\n";
  const int first_shown = std::max(0, n - kRunsShown);
  md << "| figure | first | last | last / first |";
  for (int k = first_shown; k < n; ++k) md << " " << run_labels[k] << " |";
  md << "\n|---|---:|---:|---:|";
  for (int k = first_shown; k < n; ++k) md << "---:|";
  md << "\n";
  for (const std::string& id : figures) {
    const std::map<int, double>& v = values[id];
    const double first = v.begin()->second, last = v.rbegin()->second;
    char ratio[32] = "-";
    if (first > 0.0 && last >= 0.0) std::snprintf(ratio, sizeof ratio, "%.3f", last / first);
    md << "| " << id << " | " << FormatInstructions(first) << " | " << FormatInstructions(last) << " | " << ratio
       << " |";
    for (int k = first_shown; k < n; ++k) {
      const auto it = v.find(k);
      md << " " << (it == v.end() ? std::string("-") : FormatInstructions(it->second)) << " |";
    }
    md << "\n";
  }

  fs::create_directories(dir);
  if (plots) {
    // Per backend and run: geometric mean over its figures of instructions / the figure's first value.
    std::map<std::string, std::vector<std::pair<double, int>>> mean;  // backend → per run (Σ log ratio, count)
    for (const std::string& id : figures) {
      auto& series = mean[Backend(id)];
      series.resize(n, {0.0, 0});
      const std::map<int, double>& v = values[id];
      const double first = v.begin()->second;
      if (!(first > 0.0)) continue;
      for (const auto& [k, value] : v) {
        if (value > 0.0) {
          series[k].first += std::log(value / first);
          ++series[k].second;
        }
      }
    }
    const std::string png = (fs::path(dir) / "history.png").string();
    std::ostringstream g;
    g << GnuplotPngPreamble(900, 500, png) << "set grid\nset key outside right\nset xlabel 'run'\n"
      << "set xtics 1\nset ylabel 'instructions / first run (geometric mean)'\nset xrange [0.5:" << n + 0.5 << "]\n"
      << "set title " << GnuplotQuote("Perf gate history: " + history_csv) << "\n";
    int block = 0;
    std::ostringstream plot;
    for (const auto& [backend, series] : mean) {
      g << "$b" << block << " << EOD\n";
      for (int k = 0; k < n; ++k) {
        if (series[k].second > 0) g << k + 1 << ' ' << std::exp(series[k].first / series[k].second) << '\n';
      }
      g << "EOD\n";
      plot << (block ? ", " : "plot ") << "$b" << block << " using 1:2 with linespoints lw 2 title "
           << GnuplotQuote(backend);
      ++block;
    }
    g << plot.str() << ", 1.05 with lines dt 2 lc 'red' title '+5 %'\n";
    RunGnuplot(g.str(), png, "report --history");
  }
  const std::string path = (fs::path(dir) / "history.md").string();
  std::ofstream out(path);
  out << md.str();
  if (!out) throw InvalidInputError("report: cannot write '" + path + "'");
  return md.str();
}

}  // namespace smcbench
