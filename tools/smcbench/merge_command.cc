#include "tools/smcbench/merge_command.h"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

#include "bench/replay/jobs.h"
#include "bench/replay/results_io.h"
#include "solvers/core/problem.h"
#include "bench/analysis/report_markdown.h"
#include "tools/smcbench/output_paths.h"

namespace smcbench {

namespace fs = std::filesystem;

struct MergeCommand::Flags {
  std::string out;
  std::vector<std::string> dirs;
  bool partial = false, overwrite = false, report = false, no_plots = false;
};

MergeCommand::MergeCommand(CLI::App* app) : flags_(std::make_unique<Flags>()) {
  Flags& f = *flags_;
  command_ = app->add_subcommand("merge", "combine the folders of a sharded `bench --shard K/N` run into "
                                          "OUT/results.{json,csv} (what `smcbench report OUT` reads); refuses "
                                          "folders of different builds, options or suites (exit status 2) and lists "
                                          "missing and duplicated jobs");
  command_->add_option("OUT", f.out, "folder to write results.json and results.csv to")->required();
  command_->add_option("DIR", f.dirs, "the shards' --out folders (each holds manifest.json and records.jsonl)")
      ->required();
  command_->add_flag("--partial", f.partial, "write the results even when jobs are missing (they are listed)");
  command_->add_flag("--overwrite", f.overwrite, "let OUT name a folder that already holds results.json");
  command_->add_flag("--report", f.report, "also write OUT/report.md (as `smcbench report OUT`)");
  command_->add_flag("--no-plots", f.no_plots, "with --report: no PNG plots");
}

MergeCommand::~MergeCommand() = default;
bool MergeCommand::parsed() const { return command_->parsed(); }

namespace {

// "N <what>: first, second, … (and K more)" on one line.
std::string ListLine(const std::string& what, const std::vector<std::string>& ids) {
  std::string line = std::to_string(ids.size()) + " " + what + ":";
  const std::size_t shown = std::min<std::size_t>(ids.size(), 10);
  for (std::size_t i = 0; i < shown; ++i) line += (i ? ", " : " ") + ids[i];
  if (ids.size() > shown) line += " (and " + std::to_string(ids.size() - shown) + " more)";
  return line;
}

}  // namespace

int MergeCommand::Run(std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  CheckOutputFolder("OUT", f.out);  // before reading the shards
  std::error_code ec;
  if (!f.overwrite && fs::exists(fs::path(f.out) / "results.json", ec)) {
    err << "smcbench: merge: '" << f.out << "' already holds results.json (choose another OUT, or --overwrite)\n";
    return kExitMergeRefused;
  }
  MergeReport merged;
  try {
    merged = MergeRunFolders(f.dirs);
  } catch (const InvalidInputError& e) {
    err << "smcbench: " << e.what() << "\n";
    return kExitMergeRefused;
  }
  if (!merged.duplicated.empty()) {
    err << "smcbench: merge: " << ListLine("jobs finished more than once (the first kept)", merged.duplicated)
        << "\n";
  }
  if (!merged.missing.empty()) {
    err << "smcbench: merge: " << ListLine("jobs missing", merged.missing) << "\n";
    if (!f.partial) {
      err << "smcbench: merge: run the missing shards (or `bench … --resume DIR` on the killed ones), or add "
             "--partial to write what there is\n";
      return kExitMergeRefused;
    }
  }
  WriteBenchResults(merged.results, f.out, merged.environment);
  std::size_t records = 0;
  for (const SuiteResults& s : merged.results.suites) records += s.replay.records.size() + s.replay.sweep.size();
  out << "merge: " << f.dirs.size() << " folders, " << records << " records from " << merged.hosts.size()
      << " host(s) → " << (fs::path(f.out) / "results.json").string() << " and results.csv";
  if (f.report) {
    WriteBenchReport(f.out, !f.no_plots);
    out << ", report.md";
  }
  out << "\n";
  return 0;
}

}  // namespace smcbench
