// How `bench` times one solve configuration, shared by the box replay (TimeSolves) and the MCP replay
// (TimeMcpSolves): an untimed warm-up solve, then samples of repeated solves, each lasting at least
// min_sample_seconds, until repetitions or max_seconds_per_pair. A template so the box's 100 ns solves are not
// timed through an indirect call. Private to bench/replay.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bench/replay/replay.h"
#include "solvers/siconos/child_process.h"

namespace smcbench::replay_internal {

inline double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// solve() runs one solve into *result (the same object every call). Writes median/min/max/mad/samples/
// solves_per_sample and timed_in_worker of *record.
template <typename SolveOnce>
void SampleSolveTimes(SolveOnce&& solve, const SolveResult* result, const ReplayOptions& replay,
                      ReplayRecord* record) {
  using Clock = std::chrono::steady_clock;
  // Warm-up: sizes the workspace, tells how long one solve takes, and is a siconos-* backend's probe (its first
  // solve of a problem runs in its isolation worker; the timed ones then run in process, unless the probe crashed
  // or timed out, in which case every solve stays in the worker).
  const auto t0 = Clock::now();
  solve();
  const double first = std::chrono::duration<double>(Clock::now() - t0).count();
  const auto pair_start = Clock::now();
  std::int64_t count = 1;
  if (first > 0.0) {
    count = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(replay.min_sample_seconds / first)));
  }
  count = std::min<std::int64_t>(count, 1 << 20);
  std::vector<double> samples;
  // Which process answered the timed solves (none for our backends): one worker answer taints all.
  const auto answered_in_worker = [&] { return AnswerProcessOf(*result) == AnswerProcess::kWorker; };
  record->timed_in_worker = false;
  const int wanted = std::max(1, replay.repetitions);
  // A solve that ran into the time limit is not repeated: its time is the limit, not a measurement.
  if (result->status == SolveStatus::kTimeLimit) {
    samples.push_back(first);
    count = 1;
    record->timed_in_worker = answered_in_worker();
  }
  while (static_cast<int>(samples.size()) < wanted) {
    const auto s0 = Clock::now();
    for (std::int64_t i = 0; i < count; ++i) solve();
    samples.push_back(std::chrono::duration<double>(Clock::now() - s0).count() / static_cast<double>(count));
    record->timed_in_worker = record->timed_in_worker || answered_in_worker();
    if (std::chrono::duration<double>(Clock::now() - pair_start).count() > replay.max_seconds_per_pair) break;
  }
  record->samples = static_cast<int>(samples.size());
  record->solves_per_sample = count;
  record->time_median = Median(samples);
  record->time_min = *std::min_element(samples.begin(), samples.end());
  record->time_max = *std::max_element(samples.begin(), samples.end());
  std::vector<double> dev;
  for (double s : samples) dev.push_back(std::abs(s - record->time_median));
  record->time_mad = Median(dev);
}

}  // namespace smcbench::replay_internal
