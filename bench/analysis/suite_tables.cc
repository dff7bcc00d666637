// The per-suite tables: suite_tables.h.
#include "bench/analysis/suite_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "bench/analysis/record_facts.h"
#include "bench/replay/warm_track.h"
#include "problems/avi_library/avi_library.h"

namespace smcbench {
namespace {

constexpr double kInfTime = std::numeric_limits<double>::infinity();

}  // namespace

// By the suite's recorded kind; results written before it was recorded: by the name (AVI) or the records (MCP).
bool IsAviSuite(const SuiteResults& suite) {
  return suite.kind.empty() ? suite.suite == kAviSuiteName : suite.kind == "avi";  // AviProblemKind's name
}

bool IsMcpSuite(const SuiteResults& suite) {
  if (!suite.kind.empty()) return suite.kind == "mcp";  // McpProblemKind's name
  return std::any_of(suite.replay.records.begin(), suite.replay.records.end(),
                     [](const ReplayRecord& r) { return !r.start.empty(); });
}

std::vector<BackendSummary> SummarizeSuite(const SuiteResults& suite, double time_limit_seconds) {
  return SummarizeRecords(suite.replay.records, time_limit_seconds);
}

FailureReason MostCommonFailureOf(const std::vector<const ReplayRecord*>& not_correct) {
  FailureReason reason;
  std::vector<SolveStatus> order;
  std::map<SolveStatus, int> by_status;
  for (const ReplayRecord* r : not_correct) {
    if (by_status[r->status]++ == 0) order.push_back(r->status);
  }
  for (SolveStatus s : order) {
    if (by_status[s] > reason.count) reason.status = s, reason.count = by_status[s];
  }
  std::vector<std::string> messages;
  std::map<std::string, int> by_message;
  std::vector<double> times;
  for (const ReplayRecord* r : not_correct) {
    if (r->status != reason.status) continue;
    if (by_message[r->message]++ == 0) messages.push_back(r->message);
    if (!std::isnan(r->time_median)) times.push_back(r->time_median);
  }
  for (const std::string& m : messages) {
    if (by_message[m] > reason.message_count) reason.message = m, reason.message_count = by_message[m];
  }
  std::sort(times.begin(), times.end());
  reason.median_time = MedianOfSorted(times);
  return reason;
}

std::vector<BackendSummary> SummarizeRecords(const std::vector<ReplayRecord>& records, double time_limit_seconds) {
  // Slowest correct time per problem.
  std::map<std::string, double> slowest;
  for (const auto& r : records) {
    if (IsCorrect(r)) slowest[InstanceOf(r)] = std::max(slowest[InstanceOf(r)], r.time_median);
  }
  std::vector<BackendSummary> out;
  for (const std::string& solver : SolversIn(records)) {
    BackendSummary b;
    b.solver = solver;
    double log_sum = 0.0;
    constexpr double kShift = 1e-6;
    std::vector<const ReplayRecord*> not_correct;
    for (const auto& r : records) {
      if (r.solver != solver) continue;
      ++b.problems;
      ++b.statuses[r.status];
      if (!IsCorrect(r)) not_correct.push_back(&r);
      switch (r.verdict) {
        case Verdict::kSolved:
          ++b.solved;
          b.worst_residual = MaxDefined(b.worst_residual, r.residual_rel);
          b.worst_residual_scaled = MaxDefined(b.worst_residual_scaled, r.residual_scaled);
          if (!std::isnan(r.forward_error)) {
            ++b.forward_error_defined;
            b.worst_forward_error = MaxDefined(b.worst_forward_error, r.forward_error);
          }
          break;
        case Verdict::kCorrectlyRefused:
          ++b.correctly_refused;
          break;
        case Verdict::kFailed:
          ++b.failed;
          break;
        case Verdict::kWronglyClaimed:
          ++b.wrongly_claimed;
          break;
        case Verdict::kInaccurate:
          ++b.inaccurate;
          break;
        case Verdict::kWronglyRefused:
          ++b.wrongly_refused;
          break;
      }
      const auto it = slowest.find(InstanceOf(r));
      const double t = IsCorrect(r) ? r.time_median
                                  : (it != slowest.end() ? kFailurePenaltyFactor * it->second : time_limit_seconds);
      log_sum += std::log(t + kShift);
    }
    if (!not_correct.empty()) b.failure = MostCommonFailureOf(not_correct);
    b.success_rate = b.problems ? static_cast<double>(b.solved + b.correctly_refused) / b.problems : 0.0;
    b.shifted_geomean = b.problems ? std::exp(log_sum / b.problems) - kShift : 0.0;
    out.push_back(b);
  }
  return out;
}

bool SolvedNothing(const BackendSummary& backend, const std::vector<BackendSummary>& suite) {
  return backend.solved == 0 &&
         std::any_of(suite.begin(), suite.end(), [](const BackendSummary& b) { return b.solved > 0; });
}

std::vector<BandWinner> FastestCorrectPerBand(const SuiteResults& suite, double time_limit_seconds) {
  std::vector<BandWinner> out;
  for (const SizeBand band : kSizeBands) {
    std::vector<ReplayRecord> records;
    for (const auto& r : suite.replay.records) {
      if (SizeBandOf(r.size) == band) records.push_back(r);
    }
    if (records.empty()) continue;
    BandWinner w;
    w.band = band;
    std::map<std::string, double> fastest;  // instance → smallest correct time
    for (const auto& r : records) {
      if (!IsCorrect(r)) continue;
      auto [it, inserted] = fastest.emplace(InstanceOf(r), r.time_median);
      if (!inserted) it->second = std::min(it->second, r.time_median);
    }
    std::set<std::string> instances;
    for (const auto& r : records) instances.insert(InstanceOf(r));
    w.problems = static_cast<int>(instances.size());
    std::vector<BackendSummary> candidates;
    for (const BackendSummary& b : SummarizeRecords(records, time_limit_seconds)) {
      if (b.wrong() == 0 && b.correct() > 0) candidates.push_back(b);
    }
    // Most correct answers first, then the smaller SGM.
    std::stable_sort(candidates.begin(), candidates.end(), [](const BackendSummary& a, const BackendSummary& b) {
      return a.correct() != b.correct() ? a.correct() > b.correct() : a.shifted_geomean < b.shifted_geomean;
    });
    if (!candidates.empty()) {
      w.solver = candidates[0].solver;
      w.correct = candidates[0].correct();
      w.shifted_geomean = candidates[0].shifted_geomean;
      for (const auto& r : records) {
        w.fastest_on += r.solver == w.solver && IsCorrect(r) && r.time_median <= fastest.at(InstanceOf(r));
      }
    }
    if (candidates.size() > 1) {
      w.runner_up = candidates[1].solver;
      w.runner_up_correct = candidates[1].correct();
      w.runner_up_geomean = candidates[1].shifted_geomean;
    }
    out.push_back(w);
  }
  return out;
}

bool ClaimedSolved(const ReplayRecord& record) {
  return record.backend_code ? *record.backend_code == 0 : record.status == SolveStatus::kSolved;
}

std::vector<ClaimAudit> AuditClaims(const SuiteResults& suite) {
  std::vector<ClaimAudit> out;
  for (const std::string& solver : SolversIn(suite.replay.records)) {
    ClaimAudit a;
    a.solver = solver;
    for (const auto& r : suite.replay.records) {
      if (r.solver != solver) continue;
      ++a.records;
      a.with_return_code += r.backend_code.has_value();
      const bool claimed = ClaimedSolved(r), solved = r.verdict == Verdict::kSolved;
      a.right += claimed == solved;
      a.false_success += claimed && !solved;
      a.false_failure += !claimed && solved;
    }
    out.push_back(a);
  }
  return out;
}

std::vector<std::pair<std::string, std::vector<double>>> PerformanceRatios(const SuiteResults& suite) {
  const auto& records = suite.replay.records;
  std::map<std::string, double> best;
  for (const auto& r : records) {
    if (r.verdict != Verdict::kSolved) continue;
    auto [it, inserted] = best.emplace(InstanceOf(r), r.time_median);
    if (!inserted) it->second = std::min(it->second, r.time_median);
  }
  std::vector<std::pair<std::string, std::vector<double>>> out;
  for (const std::string& solver : SolversIn(records)) {
    std::vector<double> ratios;
    for (const auto& r : records) {
      if (r.solver != solver || !best.count(InstanceOf(r))) continue;  // problems nobody solves are left out
      ratios.push_back(r.verdict == Verdict::kSolved ? r.time_median / best.at(InstanceOf(r)) : kInfTime);
    }
    std::sort(ratios.begin(), ratios.end());
    out.emplace_back(solver, std::move(ratios));
  }
  return out;
}

double GrowthExponent(const SuiteResults& suite, const std::string& solver) {
  std::map<int, std::vector<double>> by_size;
  for (const auto& r : suite.replay.records) {
    if (r.solver == solver && r.verdict == Verdict::kSolved) by_size[r.size].push_back(r.time_median);
  }
  std::vector<double> x, y;
  for (auto& [m, times] : by_size) {
    std::sort(times.begin(), times.end());
    x.push_back(m);
    y.push_back(times[times.size() / 2]);
  }
  return LogLogSlope(x, y);
}

SuiteResults SizeBandSlice(const SuiteResults& suite, SizeBand band) {
  SuiteResults slice;
  slice.suite = suite.suite + " " + std::string(ShortName(band));
  slice.description = suite.description;
  std::set<std::string> problems;
  for (const ReplayRecord& r : suite.replay.records) {
    if (SizeBandOf(r.size) != band) continue;
    slice.replay.records.push_back(r);
    problems.insert(InstanceOf(r));
  }
  for (const ReplayRecord& r : suite.replay.floor) {
    if (SizeBandOf(r.size) == band) slice.replay.floor.push_back(r);
  }
  slice.problems = static_cast<int>(problems.size());
  return slice;
}

SuiteResults WarmTrackAsSuite(const SuiteResults& suite) {
  SuiteResults warm;
  warm.suite = suite.suite + " warm";
  warm.description = "warm track of suite " + suite.suite;
  std::set<std::string> sequences;
  for (const WarmRecord& w : suite.warm) {
    warm.replay.records.push_back(w.record);
    sequences.insert(w.record.problem);
  }
  warm.problems = static_cast<int>(sequences.size());
  return warm;
}

// The suite without its records whose timed solves could not all start cold (mode "cached": bench/replay/replay.h,
// TimeSolves), which no cold table or profile may compare; *cached receives "backend on problem" for each.
SuiteResults WithoutCachedRecords(const SuiteResults& suite, std::vector<std::string>* cached) {
  SuiteResults cold = suite;
  auto& records = cold.replay.records;
  for (const auto& r : records) {
    if (r.mode == "cached") cached->push_back(r.solver + " on " + InstanceOf(r));
  }
  const auto is_cached = [](const ReplayRecord& r) { return r.mode == "cached"; };
  records.erase(std::remove_if(records.begin(), records.end(), is_cached), records.end());
  return cold;
}

// The suite without its records cut by a time budget (mode "cut": bench/replay/warm_track.h), which have no verdict
// and so belong in no table; *cut receives them.
SuiteResults WithoutCutRecords(const SuiteResults& suite, std::vector<ReplayRecord>* cut) {
  SuiteResults kept = suite;
  const auto is_cut = [](const ReplayRecord& r) { return r.mode == kCutMode; };
  for (const auto& r : suite.replay.records) if (is_cut(r)) cut->push_back(r);
  for (const auto& w : suite.warm) if (is_cut(w.record)) cut->push_back(w.record);
  auto& records = kept.replay.records;
  records.erase(std::remove_if(records.begin(), records.end(), is_cut), records.end());
  kept.warm.erase(std::remove_if(kept.warm.begin(), kept.warm.end(), [&](const WarmRecord& w) {
    return is_cut(w.record); }), kept.warm.end());
  return kept;
}

}  // namespace smcbench
