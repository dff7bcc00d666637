// `smcbench simulate SCENE ...` and `smcbench scenes`: run a scene of docs/scenes.md (or a scene file) on any backend,
// write its trajectory CSV, JSON summary of sliding-surface accuracy metrics and a gnuplot figure. Every output is
// produced while the run goes: memory does not grow with the number of steps. The rules of the overrides, the
// summary and the reference run live in problems/scenes (shared with Python), the figure in bench/figures.
#pragma once

#include <iosfwd>
#include <memory>

namespace CLI {
class App;
}

namespace smcbench {

// simulate's exit status when the run stopped on a failed step (--on-failure stop): its outputs are written for
// the steps taken, and the status tells a script the run did not reach T (1 is bad input, 2 a usage error).
inline constexpr int kStoppedEarlyExitStatus = 3;

// The `simulate` subcommand: registers its options on construction; Run executes it if it was parsed.
class SimulateCommand {
 public:
  explicit SimulateCommand(CLI::App* app);
  ~SimulateCommand();
  bool parsed() const;
  // Exit status: 0 (even when a one-step problem fails: that is a result, reported in the summary and on err);
  // throws InvalidInputError for bad input (the caller prints it and exits 1).
  int Run(std::ostream& out, std::ostream& err) const;

  struct Flags;

 private:
  CLI::App* command_;
  std::unique_ptr<Flags> flags_;
};

// The `scenes` subcommand: lists the registered scenes with one-line descriptions.
class ScenesCommand {
 public:
  explicit ScenesCommand(CLI::App* app);
  bool parsed() const;
  int Run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_;
};

}  // namespace smcbench
