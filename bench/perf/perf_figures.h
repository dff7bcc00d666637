// The perf gate's fixed, small replay set: for every built-in backend a few paper one-step problems, a few
// generated families and one time-stepper run each of S2 (galias-yu-2007) and S8 (observer). Small enough to run
// under callgrind in CI in about a minute; deterministic (same binary, same work).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solvers/core/status.h"

namespace smcbench {

// One figure's work, set up outside the measurement: Run() does `units()` solves or steps, identically each time.
class PerfWorkload {
 public:
  virtual ~PerfWorkload() = default;
  virtual void Run() = 0;
  virtual std::int64_t units() const = 0;
  // Of the last Run(): kSolved when every solve/step was solved, else the first other status.
  virtual SolveStatus status() const = 0;
};

struct PerfCase {
  std::string id;    // "solve/<problem id>/<backend>" or "step/<scene>/<backend>"
  std::string unit;  // "solve" or "step"
  std::function<std::unique_ptr<PerfWorkload>()> make;
};

// The tracked set, built lazily (the problems are generated or captured when a case is made, not here).
// Every built-in backend (the registry minus external ones) on every problem, except where it refuses the
// problem by capability (size limit, not applicable): those pairs are left out of the set, not tracked.
std::vector<PerfCase> PerfCases();

// Instruction counts per unit are deterministic only if a run does the same work: these are the fixed sizes.
inline constexpr int kPerfSolvesPerRun = 64;         // per solve figure (kPerfSlowSolvesPerRun for ipopt)
inline constexpr int kPerfSlowSolvesPerRun = 4;
inline constexpr std::int64_t kPerfStepsPerRun = 1000;  // per stepper figure (kPerfSlowStepsPerRun for ipopt)
inline constexpr std::int64_t kPerfSlowStepsPerRun = 40;

}  // namespace smcbench
