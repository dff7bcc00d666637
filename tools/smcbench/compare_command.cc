#include "tools/smcbench/compare_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bench/compare/compare_runs.h"
#include "bench/compare/run_identity.h"
#include "bench/replay/results_io.h"
#include "solvers/core/number_text.h"
#include "solvers/core/problem.h"
#include "bench/figures/gnuplot_figure.h"
#include "tools/smcbench/output_paths.h"

namespace smcbench {

namespace fs = std::filesystem;

struct CompareCommand::Flags {
  std::string a, b, out;
  CompareOptions options;
  bool no_plots = false;
  bool keep_drift = false;
};

CompareCommand::CompareCommand(CLI::App* app) : flags_(std::make_unique<Flags>()) {
  Flags& f = *flags_;
  command_ = app->add_subcommand(
      "compare", "compare two `bench` results folders of the same suites (other builds, commits, machines or "
                 "options): what differs between the runs (settings, build, machine), verdict changes, then the time "
                 "ratio B/A per suite, backend and size band with a bootstrap interval and median iterations, flagged "
                 "only beyond the noise floor after a uniform machine drift is divided out; exit status 0 no "
                 "regression, 1 a verdict regression or a flagged slowdown, 2 could not compare");
  command_->add_option("A", f.a, "the reference run's folder (holds results.json)")->required();
  command_->add_option("B", f.b, "the run to judge against A")->required();
  command_->add_option("--threshold", f.options.threshold,
                       "the minimum relative change: flag a group slower when its whole interval (÷ drift) lies "
                       "above max(1 + THRESHOLD, noise floor) (faster: below its inverse)")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  command_->add_option("--resamples", f.options.resamples, "bootstrap resamples per group")
      ->check(CLI::Range(100, 1000000))
      ->capture_default_str();
  command_->add_option("--confidence", f.options.confidence, "of the interval")
      ->check(CLI::Range(0.5, 0.999))
      ->capture_default_str();
  command_->add_option("--out", f.out,
                       "also write DIR/compare.md, DIR/compare.json and the figure compare-ratios.{png,svg,dat,gp}");
  command_->add_flag("--no-plots", f.no_plots, "with --out: no figure (no gnuplot needed)");
  command_->add_flag("--keep-drift", f.keep_drift,
                     "report a uniform drift of every group but do not divide it out: flag on the raw ratios (a "
                     "dedicated machine, where every backend slower by one factor is a real slowdown)");
}

CompareCommand::~CompareCommand() = default;
bool CompareCommand::parsed() const { return command_->parsed(); }

namespace {

constexpr const char* kFigureStem = "compare-ratios";

// One row per group (its label double-quoted: gnuplot reads only double quotes in data), top to bottom in table
// order: the ratio ÷ drift as a point, its interval as a horizontal bar, coloured by flag; vertical lines at 1 and at
// the two flag limits.
void WriteRatioFigure(const RunComparison& c, const CompareOptions& options, const std::string& dir) {
  std::ostringstream data, body;
  data << "# row ratio low high label flag(1 none, 2 slower, 3 faster)\n";
  const int rows = static_cast<int>(c.groups.size());
  for (int i = 0; i < rows; ++i) {
    const RatioGroup& g = c.groups[static_cast<std::size_t>(i)];
    const double drift = c.drift.divisor();
    data << rows - i << ' ' << NumberText(g.time.ratio / drift) << ' ' << NumberText(g.time.low / drift) << ' '
         << NumberText(g.time.high / drift) << " \"" << g.solver << ' ' << g.suite << ' ' << ShortName(g.band) << '"'
         << ' ' << static_cast<int>(g.time.flag) + 1 << '\n';
  }
  const double upper = c.flag_limit, lower = 1.0 / upper;
  double x_min = lower, x_max = upper;
  for (const RatioGroup& g : c.groups) {
    x_min = std::min(x_min, g.time.low / c.drift.divisor());
    x_max = std::max(x_max, g.time.high / c.drift.divisor());
  }
  const std::string file = GnuplotQuote(std::string(kFigureStem) + ".dat");
  const std::string bars = " with xerrorbars pt 7 ps 1 lw 2 lc rgb ";
  body << "set logscale x\nset grid xtics\nunset key\nset xrange [" << NumberText(x_min / 1.15) << ":"
       << NumberText(x_max * 1.15)
       << "]\nset xtics (0.1, 0.2, 0.5, 1, 1.5, 2, 3, 5, 10, 20, 50, 100, 1000)\nset xlabel 'time ratio B/A ÷ drift "
       << NumberText(c.drift.divisor()) << ", " << static_cast<int>(std::lround(options.confidence * 100.0))
       << " % bootstrap interval (orange: flagged slower, blue: flagged faster)'\nset yrange [0.5:" << rows + 0.5
       << "]\nset ytics scale 0 font ',9'\nset title 'smcbench compare: B/A per backend, suite and size band'\n"
       << "set arrow from 1, graph 0 to 1, graph 1 nohead lc rgb 'black'\n"
       << "set arrow from " << NumberText(upper) << ", graph 0 to " << NumberText(upper)
       << ", graph 1 nohead dt 2 lc rgb '#D55E00'\n"
       << "set arrow from " << NumberText(lower) << ", graph 0 to " << NumberText(lower)
       << ", graph 1 nohead dt 2 lc rgb '#0072B2'\n"
       << "plot " << file << " using 2:1:3:4:ytic(5)" << bars << "'#555555', " << file
       << " using ($6 == 2 ? $2 : 1/0):1:3:4" << bars << "'#D55E00', " << file
       << " using ($6 == 3 ? $2 : 1/0):1:3:4" << bars << "'#0072B2'\n";
  WriteGnuplotFigure(dir, kFigureStem, data.str(), body.str(), 900, std::max(300, 120 + 22 * rows), "compare");
}

}  // namespace

int CompareCommand::Run(std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  if (!f.out.empty()) CheckOutputFolder("--out", f.out);
  RunComparison comparison;
  CompareOptions options = f.options;
  options.divide_drift = !f.keep_drift;
  try {
    comparison = CompareRunFolders(f.a, f.b, options);
  } catch (const InvalidInputError& e) {
    err << "smcbench: " << e.what() << "\n";
    return kExitCompareRefused;
  }
  out << CompareSummaryText(comparison, options);
  if (!f.out.empty()) {
    std::error_code ec;
    fs::create_directories(f.out, ec);
    std::string stem;
    if (!f.no_plots && !comparison.groups.empty()) {
      try {
        WriteRatioFigure(comparison, options, f.out);
        stem = kFigureStem;
      } catch (const InvalidInputError& e) {  // the verdict of the comparison stands without its figure
        err << "smcbench: compare: no figure: " << e.what() << "\n";
      }
    }
    const fs::path md = fs::path(f.out) / "compare.md", json = fs::path(f.out) / "compare.json";
    std::ofstream md_file(md), json_file(json);
    md_file << CompareMarkdown(comparison, options, f.a, f.b, stem);
    json_file << CompareJson(comparison, options, f.a, f.b).dump(1) << "\n";
    if (!md_file || !json_file) {
      err << "smcbench: compare: cannot write '" << (md_file ? json : md).string() << "'\n";
      return kExitCompareRefused;
    }
    out << "compare: wrote " << md.string() << ", compare.json" << (stem.empty() ? "" : " and " + stem + ".png")
        << "\n";
  }
  return comparison.regressed() ? kExitCompareRegressed : 0;
}

}  // namespace smcbench
