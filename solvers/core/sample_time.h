// One timing sample for the measurement tools (auto_rule_measure, bpp_floor_measure): a call repeated until the
// repeats last at least min_seconds, so that the clock's resolution and call overhead stay small against it.
#pragma once

#include <chrono>

namespace smcbench {

// The time per call of f, in ns, over repeats lasting at least min_seconds (f is called at least once).
template <typename F>
double SampleNs(F& f, double min_seconds) {
  using Clock = std::chrono::steady_clock;
  int calls = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  do {
    f();
    ++calls;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < min_seconds);
  return elapsed / calls * 1e9;
}

}  // namespace smcbench
