// `smcbench paper`: re-runs every scene of docs/scenes.md with the report's settings, implicit and explicit, tests each
// claim of Acary & Brogliato (2009) against what the code does, and writes results/paper/ (a markdown table
// claim → measured → verdict, per-scene sections, PNG figures, and every number in paper.json).
#pragma once

#include <iosfwd>
#include <memory>
#include <string>

#include <vector>

namespace CLI {
class App;
}

namespace smcbench {

struct PaperOptions {
  std::string out_dir = "results/paper";
  bool plots = true;             // PNG figures with gnuplot (needs gnuplot on PATH)
  std::string solver = "auto";   // backend of the implicit linear steps and of Algorithm 2 (S11 runs all of them)
  std::string command;           // the command line recorded in the report
};

// One row of the claims table.
struct PaperClaim {
  std::string scene;     // "S1 sign"
  std::string claim;     // what docs/scenes.md says the report claims
  std::string measured;  // what the code did, with numbers
  std::string verdict;   // "holds", "partly", "does not hold", or "measured" (no claim: S11)
};

struct PaperReport {
  std::vector<PaperClaim> claims;
  std::string markdown;  // README.md of the output folder
  std::string json;      // paper.json: every number behind the table
};

// Runs every study, writes options.out_dir/{README.md, paper.json, *.png} and returns the report. Progress lines go
// to log. Throws InvalidInputError for an unusable option (unknown solver, plots without gnuplot, unwritable dir).
PaperReport RunPaperStudies(const PaperOptions& options, std::ostream& log);

// The `paper` subcommand.
class PaperCommand {
 public:
  explicit PaperCommand(CLI::App* app);
  ~PaperCommand();
  bool parsed() const;
  int Run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_;
  std::unique_ptr<PaperOptions> options_;
  bool no_plots_ = false;
};

}  // namespace smcbench
