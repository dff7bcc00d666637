#include "tools/smcbench/compare_command.h"

#include <CLI/CLI.hpp>
#include <ostream>

#include "bench/compare/compare_output.h"
#include "bench/compare/compare_render.h"
#include "solvers/core/problem.h"
#include "tools/smcbench/output_paths.h"

namespace smcbench {

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
    ComparisonFiles files;
    try {
      files = WriteComparisonFolder(comparison, options, f.a, f.b, f.out, !f.no_plots);
    } catch (const InvalidInputError& e) {
      err << "smcbench: " << e.what() << "\n";
      return kExitCompareRefused;
    }
    // the verdict of the comparison stands without its figure
    if (!files.figure_error.empty()) err << "smcbench: compare: no figure: " << files.figure_error << "\n";
    out << "compare: wrote " << files.markdown << ", compare.json"
        << (files.figure_stem.empty() ? "" : " and " + files.figure_stem + ".png") << "\n";
  }
  return comparison.regressed() ? kExitCompareRegressed : 0;
}

}  // namespace smcbench
