// `smcbench bench` (replay suites of one-step problems on every backend, write results/…/results.{json,csv}) and
// `smcbench report DIR` (results → report.md with plots), plus the suites by name.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "problems/library/problem_set.h"
// The suite catalogue (BuildSuite, TinySuite, SiconosSuite, ...) lives below the command line; included here for the
// commands that name suites.
#include "problems/suites/catalogue.h"
#include "solvers/core/glob_match.h"  // GlobMatch: --allow-wrong's patterns

namespace CLI {
class App;
}

namespace smcbench {

// The progress line's time left: elapsed seconds scaled by the estimated seconds still to run over those run so far
// (each job's BenchJob::cost, so a slow job ahead counts for what it costs), as "ETA 1m05s" ("ETA 42s", "ETA
// 1h02m"); "ETA ?" before any estimated work is done. Exposed for its test.
std::string FormatEta(double elapsed_seconds, double estimated_done, double estimated_total);

// `bench`'s exit status when some result is wrong (Verdict IsWrong) on a backend not excused by --allow-wrong.
inline constexpr int kExitWrongAnswers = 3;

class BenchCommand {
 public:
  explicit BenchCommand(CLI::App* app);
  ~BenchCommand();
  bool bench_parsed() const;
  bool report_parsed() const;
  int RunBench(const std::string& command_line, std::ostream& out, std::ostream& err) const;
  int RunReport(std::ostream& out, std::ostream& err) const;

  struct Flags;

 private:
  CLI::App* bench_ = nullptr;
  CLI::App* report_ = nullptr;
  std::unique_ptr<Flags> flags_;
};

}  // namespace smcbench
