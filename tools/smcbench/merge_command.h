// `smcbench merge OUT DIR…`: the folders of a sharded `bench` run (--shard K/N, one per Slurm array task) put back
// together into OUT/results.{json,csv}, which `smcbench report OUT` reads like a single run's. Refuses, with one
// line and exit status 2, folders of different builds, options or suites, and lists missing and duplicated jobs.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace smcbench {

// merge's exit status when the folders cannot be merged (other build, options, suites; missing jobs without
// --partial).
inline constexpr int kExitMergeRefused = 2;

class MergeCommand {
 public:
  explicit MergeCommand(CLI::App* app);
  ~MergeCommand();
  bool parsed() const;
  int Run(std::ostream& out, std::ostream& err) const;

  struct Flags;

 private:
  CLI::App* command_ = nullptr;
  std::unique_ptr<Flags> flags_;
};

}  // namespace smcbench
