// `smcbench compare A B`: two results folders of `smcbench bench` (two builds, commits, machines or option sets) —
// what differs between them (settings, build, machine), verdict changes, then the time ratio B/A per suite × backend
// × size band with a bootstrap interval, median iterations, the noise floor and the machine drift
// (bench/compare/compare_runs.h); a short table on stdout and, with --out, compare.md and a figure of the ratios.
// Exit status for CI: 0 no regression, 1 a verdict regression or a group flagged slower (beyond the noise floor,
// after the drift), 2 could not compare. A drift alone, or different machines, is reported, not a regression.
#pragma once

#include <iosfwd>
#include <memory>

namespace CLI {
class App;
}

namespace smcbench {

inline constexpr int kExitCompareRegressed = 1;
inline constexpr int kExitCompareRefused = 2;

class CompareCommand {
 public:
  explicit CompareCommand(CLI::App* app);
  ~CompareCommand();
  bool parsed() const;
  int Run(std::ostream& out, std::ostream& err) const;

  struct Flags;

 private:
  CLI::App* command_ = nullptr;
  std::unique_ptr<Flags> flags_;
};

}  // namespace smcbench
