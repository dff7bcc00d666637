// How `bench` times one solve configuration, shared by the box replay (TimeSolves) and the MCP replay
// (TimeMcpSolves): an untimed warm-up solve, then samples of repeated solves, each lasting at least
// min_sample_seconds, until repetitions or max_seconds_per_pair (a warm-up longer than that is the one sample). A template so the box's smallest solves are not
// timed through an indirect call, whose cost would be a visible part of theirs. Private to bench/replay.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bench/replay/replay.h"
#include "solvers/isolation/child_process.h"

namespace smcbench::replay_internal {

inline double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The forget() of a configuration whose solves keep nothing between them (an MCP solve, a backend's plain Solve).
struct NothingToForget {
  WarmStateReset operator()() const { return WarmStateReset::kNothingRemembered; }
};

// solve() runs one solve into *result (the same object every call). Writes median/min/max/mad/samples/
// solves_per_sample and timed_in_worker of *record.
// forget() (SolveSession::ForgetWarmState) runs untimed after the warm-up. When it found nothing remembered, the
// timed solves run back to back, count per sample. Otherwise every timed solve starts cold: forget() before each
// one, outside the clock, each solve timed alone and count of them summed into one sample; and when something could
// not be forgotten (kCannotForget), a "cold" record becomes "cached" (the report keeps it out of its cold tables).
template <typename SolveOnce, typename Forget = NothingToForget>
void SampleSolveTimes(SolveOnce&& solve, const SolveResult* result, const ReplayOptions& replay,
                      ReplayRecord* record, Forget&& forget = Forget{}) {
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
  const WarmStateReset after_warm_up = forget();
  const bool forgetting = after_warm_up != WarmStateReset::kNothingRemembered;
  bool cached = after_warm_up == WarmStateReset::kCannotForget;
  bool forgotten = true;  // the state the next timed solve starts from is the forgotten one
  // A solve that ran into the time limit is not repeated: its time is the limit, not a measurement. Nor is one
  // that outlasted the sampling window (max_seconds_per_pair: half the job budget in a budgeted run), answered in
  // this process: a second solve would double the job for a median of two, and the warm-up of a solve that long is
  // a measurement (a worker's answer is not: that one is timed again, in process).
  const bool outlasted_window = first > replay.max_seconds_per_pair && !answered_in_worker();
  const bool warm_up_only = result->status == SolveStatus::kTimeLimit || outlasted_window;
  if (warm_up_only) {
    samples.push_back(first);
    count = 1;
    record->timed_in_worker = answered_in_worker();
  }
  const int wanted = warm_up_only ? 1 : std::max(1, replay.repetitions);
  while (static_cast<int>(samples.size()) < wanted) {
    double seconds = 0.0;
    if (!forgetting) {
      const auto s0 = Clock::now();
      for (std::int64_t i = 0; i < count; ++i) solve();
      seconds = std::chrono::duration<double>(Clock::now() - s0).count();
    } else {
      for (std::int64_t i = 0; i < count; ++i) {
        if (!forgotten) cached = forget() == WarmStateReset::kCannotForget || cached;
        forgotten = false;
        const auto s0 = Clock::now();
        solve();
        seconds += std::chrono::duration<double>(Clock::now() - s0).count();
      }
    }
    samples.push_back(seconds / static_cast<double>(count));
    record->timed_in_worker = record->timed_in_worker || answered_in_worker();
    if (std::chrono::duration<double>(Clock::now() - pair_start).count() > replay.max_seconds_per_pair) break;
  }
  if (cached && record->mode == "cold") record->mode = "cached";
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
