// Timed solves and their rendering (solve_report.h).
#include "tools/smcbench/solve_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string_view>

#include "solvers/auto/auto_solver.h"
#include "solvers/core/duration_text.h"
#include "solvers/isolation/child_process.h"

namespace smcbench {

namespace {
// A session of `auto` calls its choice directly (SolveSession::backend): an answer the choice gave itself (not
// auto's fallback path, which labels its own) is labelled as auto's Solve labels it, with no fallback.
void LabelDelegatedAnswer(const Solver& solver, const SolveSession& session, SolveResult* result) {
  if (&session.backend() == &solver || result->solver != session.backend().info().name) return;
  if (const std::optional<AutoCandidate> chosen = AutoCandidateFromString(result->solver)) {
    LabelAutoAnswer(*chosen, 0, result);
  }
}

// The repeats of a backend that keeps nothing between solves, in batches of b solves between two clock reads (a
// clock read costs about as much as a small solve): b is chosen from a calibration run so that a batch lasts ≈ 20 µs.
// Each sample is a batch's time divided by b.
template <typename Solve, typename InWorker>
void TimeBatches(const Solve& solve, const InWorker& in_worker, SolveRecord* record, std::vector<double>* samples) {
  using Clock = std::chrono::steady_clock;
  int calibration = 0;
  const Clock::time_point c0 = Clock::now();
  while (calibration < record->repeats && Clock::now() - c0 < std::chrono::microseconds(20)) {
    solve();
    ++calibration;
  }
  const double per_solve = std::chrono::duration<double>(Clock::now() - c0).count() / std::max(1, calibration);
  const int batch = std::clamp(static_cast<int>(std::ceil(2e-5 / std::max(per_solve, 1e-10))), 1, record->repeats);
  record->solves_per_sample = batch;
  samples->reserve(static_cast<std::size_t>(record->repeats / batch + 1));
  for (int done = 0; done < record->repeats; done += batch) {
    const Clock::time_point t0 = Clock::now();
    for (int i = 0; i < batch; ++i) solve();
    samples->push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / batch);
    record->timed_in_worker = record->timed_in_worker || in_worker();
  }
}
}  // namespace

SolveRecord TimedSolve(Solver& solver, const BoxMLCP& problem, const SolverOptions& options, int repeat,
                       bool warm) {
  using Clock = std::chrono::steady_clock;
  SolveRecord record;
  record.warm = warm;
  record.problem = problem.name();
  record.solver = std::string(solver.info().name);
  record.repeats = std::max(1, repeat);
  // One session for every repeat: cold = the backend's own algorithm each call, from the options' start point; warm =
  // each call from the previous answer, its active set tried first (as a time-stepper's steps).
  SessionOptions session_options;
  session_options.reuse_active_set = warm;
  SolveSession session = solver.Prepare(problem, options, session_options);
  const Eigen::Ref<const Vector> q = problem.q();
  Vector start = options.warm_start;
  const auto solve = [&] {
    session.Solve(q, &record.result, warm ? &start : nullptr);
    if (warm && record.result.solved() && start.size() == record.result.z.size()) {
      for (Eigen::Index i = 0; i < start.size(); ++i) start[i] = record.result.z[i];
    }
  };
  const auto in_worker = [&] { return AnswerProcessOf(record.result) == AnswerProcess::kWorker; };
  // The first solve, timed by the base class's own clock: the workspace, a siconos-* backend's probe (its later
  // solves then run in process), and the whole record when it hit the time limit or is the only one.
  solve();
  LabelDelegatedAnswer(solver, session, &record.result);
  if (record.repeats == 1 || record.result.status == SolveStatus::kTimeLimit) {
    record.repeats = 1;
    record.solves_per_sample = 1;
    record.time_ns_median = record.time_ns_min = record.time_ns_max = record.result.solve_seconds * 1e9;
    record.timed_in_worker = in_worker();
    return record;
  }
  // The timed repeats (median, min and max over their samples), each on the session's own clock-free path.
  SolverOptions untimed = options;
  untimed.measure_time = false;
  session.set_options(untimed);
  std::vector<double> samples;
  const WarmStateReset after_first = warm ? WarmStateReset::kNothingRemembered : session.ForgetWarmState();
  if (after_first != WarmStateReset::kNothingRemembered) {
    // Cold means cold: each repeat alone, the backend's memory of the previous one dropped before it, untimed.
    record.forgot_between_repeats = true;
    record.cached = after_first == WarmStateReset::kCannotForget;
    samples.reserve(static_cast<std::size_t>(record.repeats));
    for (int done = 0; done < record.repeats; ++done) {
      if (done > 0) record.cached = session.ForgetWarmState() == WarmStateReset::kCannotForget || record.cached;
      const Clock::time_point t0 = Clock::now();
      solve();
      samples.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count());
      record.timed_in_worker = record.timed_in_worker || in_worker();
    }
  } else {
    TimeBatches(solve, in_worker, &record, &samples);
  }
  LabelDelegatedAnswer(solver, session, &record.result);
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  record.time_ns_median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  record.time_ns_min = samples.front();
  record.time_ns_max = samples.back();
  return record;
}

std::string FormatDuration(double ns) { return DurationText(ns * 1e-9); }

std::string FormatRecordLine(const SolveRecord& record) {
  char buffer[256];
  if (!record.error.empty()) {
    std::snprintf(buffer, sizeof buffer, "%-8s error: %s", record.solver.c_str(), record.error.c_str());
    return buffer;
  }
  const SolveResult& r = record.result;
  std::snprintf(buffer, sizeof buffer, "%-8s %-18s iters %-7d res %.2e abs / %.2e rel / %.2e eq   %s",
                record.solver.c_str(), std::string(ToString(r.status)).c_str(), r.iterations, r.residual_abs,
                r.residual_rel, r.residual_scaled, FormatDuration(record.time_ns_median).c_str());
  std::string line = buffer;
  if (record.has_judgement) {
    const Judgement& j = record.judgement;
    if (std::isnan(j.forward_error)) {
      std::snprintf(buffer, sizeof buffer, "   fwd err n/a   %s", std::string(ToString(j.verdict)).c_str());
    } else {
      std::snprintf(buffer, sizeof buffer, "   fwd err %.2e (rel %.2e, allowed %.2e)   %s", j.forward_error,
                    j.forward_error_rel, j.forward_allowance, std::string(ToString(j.verdict)).c_str());
    }
    line += buffer;
  }
  if (const std::optional<AutoCandidate> chosen = ChosenCandidateOf(r)) {
    line += "   chose " + std::string(ToString(*chosen));
  }
  if (record.warm) line += "   [warm: session, from the previous answer]";
  if (record.timed_in_worker) line += "   [timed through the isolation worker: IPC included]";
  if (record.cached) line += "   [cached: the backend cannot forget between repeats, so they may not start cold]";
  if (!r.solved() && !r.message.empty()) line += "   (" + r.message + ")";
  return line;
}

namespace {
// JSON has no infinity or NaN: write them as null.
nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json RecordToJson(const SolveRecord& record) {
  const SolveResult& r = record.result;
  nlohmann::json j;
  j["problem"] = record.problem;
  j["solver"] = record.solver;
  if (!record.error.empty()) {
    j["status"] = "error";
    j["message"] = record.error;
    return j;
  }
  j["status"] = std::string(ToString(r.status));
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["residual_abs"] = Number(r.residual_abs);
  j["residual_rel"] = Number(r.residual_rel);
  j["residual_scaled"] = Number(r.residual_scaled);
  if (record.has_judgement) {
    j["forward_error"] = Number(record.judgement.forward_error);
    j["forward_error_rel"] = Number(record.judgement.forward_error_rel);
    j["forward_allowance"] = Number(record.judgement.forward_allowance);
    j["verdict"] = std::string(ToString(record.judgement.verdict));
  }
  j["time_ns_median"] = record.time_ns_median;
  j["time_ns_min"] = record.time_ns_min;
  j["time_ns_max"] = record.time_ns_max;
  j["repeats"] = record.repeats;
  j["solves_per_sample"] = record.solves_per_sample;
  j["timed_in_worker"] = record.timed_in_worker;
  j["forgot_between_repeats"] = record.forgot_between_repeats;
  j["cached"] = record.cached;
  nlohmann::json z = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.z.size(); ++i) z.push_back(Number(r.z[i]));
  j["z"] = std::move(z);
  nlohmann::json details = nlohmann::json::object();
  for (int i = 0; i < r.num_details; ++i) {
    // A code by its name ("reused_active_set"), a measurement as a number.
    const std::string_view code = SolveResult::CodeText(r.details[i]);
    details[r.details[i].name] = code.empty() ? Number(r.details[i].value) : nlohmann::json(std::string(code));
  }
  j["details"] = std::move(details);
  if (const std::optional<AutoCandidate> chosen = ChosenCandidateOf(r)) j["chosen"] = std::string(ToString(*chosen));
  j["warm"] = record.warm;
  return j;
}

nlohmann::json ReferenceToJson(const ReferenceSolution& reference) {
  nlohmann::json j;
  j["certificate"] = std::string(ToString(reference.certificate));
  j["condition"] = Number(reference.condition);
  j["proved_radius"] = Number(reference.proved_radius);  // null: not proved by an interval enclosure
  j["proved_unique"] = reference.proved_unique;
  nlohmann::json z = nlohmann::json::array();
  for (Eigen::Index i = 0; i < reference.z.size(); ++i) z.push_back(Number(reference.z[i]));
  j["z"] = std::move(z);
  return j;
}

}  // namespace smcbench
