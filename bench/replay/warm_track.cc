#include "bench/replay/warm_track.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bench/replay/sample_times.h"
#include "solvers/core/active_set.h"
#include "solvers/core/session.h"

namespace smcbench {
namespace {

using Clock = std::chrono::steady_clock;

bool SameMatrix(const BoxMLCP& a, const BoxMLCP& b) {
  if (a.is_sparse() != b.is_sparse() || a.size() != b.size()) return false;
  if (a.is_sparse()) {
    const SparseMatrix& x = a.sparse_matrix();
    const SparseMatrix& y = b.sparse_matrix();
    return x.nonZeros() == y.nonZeros() && DenseMatrix(x) == DenseMatrix(y);
  }
  return a.dense_matrix() == b.dense_matrix();
}

// The active set of an answer, in the natural map's classification (ClassifyRow): what a warm start can reuse.
void ClassifyAnswer(const BoxMLCP& problem, const SolveResult& result, std::vector<signed char>* state) {
  const int n = problem.size();
  state->assign(static_cast<std::size_t>(n), 0);
  if (result.z.size() != n || result.w.size() != n) return;
  for (int i = 0; i < n; ++i) {
    (*state)[static_cast<std::size_t>(i)] = static_cast<signed char>(
        ClassifyRow(result.z[i], result.w[i], problem.l()[i], problem.u()[i]));
  }
}

std::string JoinTags(const std::vector<std::string>& tags) {
  std::string out;
  for (const auto& t : tags) out += (out.empty() ? "" : ",") + t;
  return out;
}

}  // namespace

const char* ToString(WarmSource source) {
  switch (source) {
    case WarmSource::kScene: return "scene";
    case WarmSource::kTrajectory: return "trajectory";
    case WarmSource::kCapture: return "capture";
  }
  return "?";
}

void CheckWarmSequence(const WarmSequence& sequence) {
  if (sequence.steps.empty()) throw InvalidInputError("warm sequence '" + sequence.id + "': steps is empty");
  const BoxMLCP& first = sequence.steps.front().problem;
  for (std::size_t k = 1; k < sequence.steps.size(); ++k) {
    const BoxMLCP& p = sequence.steps[k].problem;
    if (!SameMatrix(first, p) || p.l() != first.l() || p.u() != first.u()) {
      throw InvalidInputError("warm sequence '" + sequence.id + "': step " + std::to_string(k) + " ('" +
                              sequence.steps[k].id + "') has another M, l or u than step 0 (only q may move)");
    }
  }
}

WarmRecord ReplayWarmSequence(const WarmSequence& sequence, Solver* solver, const std::string& solver_name,
                              const ReplayOptions& options, double tolerance, std::vector<Vector>* answers,
                              double budget_seconds) {
  CheckWarmSequence(sequence);
  const LibraryProblem& head = sequence.steps.front();
  const std::size_t steps = sequence.steps.size();
  WarmRecord out;
  out.source = sequence.source;
  ReplayRecord& r = out.record;
  r.suite = sequence.suite;
  r.problem = sequence.id;
  r.solver = solver_name;
  r.size = head.size();
  r.sparse = head.sparse();
  r.tags = JoinTags(head.tags);
  r.expected = head.expected;
  r.mode = "warm";
  r.tolerance = tolerance;
  r.certificate = std::string(ToString(head.reference.certificate));
  r.reference_radius = head.reference.proved_radius;
  r.reference_proved_unique = head.reference.proved_unique;

  const bool budgeted = budget_seconds > 0.0;
  SolverOptions o = ReplaySolverOptions(options, tolerance);  // timed around the whole sequence
  // With a budget below the time limit, no step's solve may outlast the budget either (as a cold job's under
  // --job-budget): a solve the budget stopped cuts the sequence.
  const bool budget_limits_solves = budgeted && budget_seconds < o.time_limit_seconds;
  if (budget_limits_solves) o.time_limit_seconds = budget_seconds;
  SessionOptions session_options;
  session_options.reuse_active_set = true;  // the session itself leaves it off for external backends
  // One result per step, so step k starts from step k−1's answer without a copy; storage reused pass after pass.
  std::vector<SolveResult> results(steps);
  // A step that ran into the time limit ends the pass: the steps after it are not run (a time-stepper stops there
  // too), so a backend that cannot solve the sequence costs one time limit, not one per step.
  std::size_t steps_run = 0;
  // budget: seconds the pass may take (the untimed pass only; 0: none). It stops after a step when the next one,
  // at the pace of the last, would end past the budget: the job keeps to its budget rather than overrunning it by
  // a step.
  const auto pass = [&](double budget) {
    const auto pass_start = Clock::now();
    auto step_start = pass_start;
    SolveSession session = solver->Prepare(head.problem, o, session_options);
    steps_run = 0;
    for (std::size_t k = 0; k < steps; ++k) {
      session.Solve(sequence.steps[k].problem.q(), &results[k], k == 0 ? nullptr : &results[k - 1].z);
      ++steps_run;
      if (results[k].status == SolveStatus::kTimeLimit) break;
      if (budget > 0.0) {
        const auto now = Clock::now();
        const double spent = std::chrono::duration<double>(now - pass_start).count();
        const double last_step = std::chrono::duration<double>(now - step_start).count();
        step_start = now;
        if (spent + last_step > budget) break;
      }
    }
  };
  // Untimed: sizes every result's storage, and is a siconos-* backend's probe of the problem.
  const auto first_start = Clock::now();
  pass(budget_seconds);
  const double first = std::chrono::duration<double>(Clock::now() - first_start).count();
  const bool hit_time_limit = results[steps_run - 1].status == SolveStatus::kTimeLimit;
  // The budget ended the pass: before a step it had no time left for, or inside a solve it stopped.
  const bool cut = (steps_run < steps && !hit_time_limit) || (hit_time_limit && budget_limits_solves);
  const bool timed_out = hit_time_limit && !cut;
  std::vector<double> samples;
  // After a time limit the limit is the sample, not a measurement; a pass that took more than half the budget is
  // its own only sample (another would overrun the budget).
  if (timed_out || (budgeted && !cut && first > 0.5 * budget_seconds)) {
    samples.push_back(first / static_cast<double>(steps_run));
  }
  const int wanted = cut ? 0 : !samples.empty() ? 1 : std::max(1, options.repetitions);
  // The timed passes: at most options.max_seconds_per_pair of them, and with a budget only while the next pass, at
  // the pace of the last, ends inside it (the first always runs: the untimed pass took at most half the budget).
  const auto start = Clock::now();
  while (static_cast<int>(samples.size()) < wanted) {
    const auto s0 = Clock::now();
    pass(0.0);
    const auto now = Clock::now();
    const double last = std::chrono::duration<double>(now - s0).count();
    samples.push_back(last / static_cast<double>(steps));
    if (std::chrono::duration<double>(now - start).count() > options.max_seconds_per_pair) break;
    if (budgeted && std::chrono::duration<double>(now - first_start).count() + last > budget_seconds) break;
  }
  if (cut) samples.push_back(first / static_cast<double>(steps_run));  // not a sample: what the steps run took
  r.samples = cut ? 0 : static_cast<int>(samples.size());
  r.solves_per_sample = static_cast<std::int64_t>(steps);
  r.time_median = replay_internal::Median(samples);
  r.time_min = *std::min_element(samples.begin(), samples.end());
  r.time_max = *std::max_element(samples.begin(), samples.end());
  std::vector<double> deviations;
  for (double s : samples) deviations.push_back(std::abs(s - r.time_median));
  r.time_mad = replay_internal::Median(deviations);

  // Judge the last pass step by step.
  WarmCounts& c = out.counts;
  c.steps = static_cast<int>(steps);
  c.reuse = !solver->info().external && !head.sparse();
  r.status = SolveStatus::kSolved;
  r.verdict = Verdict::kSolved;
  r.residual_abs = r.residual_rel = r.residual_scaled = 0.0;
  std::vector<signed char> state, previous;
  bool first_failure = true;
  // The step whose solve the budget stopped has no answer to judge, as the steps never run.
  const std::size_t answered = cut && hit_time_limit ? steps_run - 1 : steps_run;
  for (std::size_t k = 0; k < steps; ++k) {
    const LibraryProblem& step = sequence.steps[k];
    if (k >= answered) {  // after a time limit or the budget: not run, no answer
      if (cut) break;
      if (first_failure) {
        first_failure = false;
        r.verdict = Verdict::kFailed;
        r.status = SolveStatus::kTimeLimit;
        r.message = "step " + std::to_string(k) + " (" + step.id + ") not run: an earlier step ran into the time limit";
      }
      continue;
    }
    const SolveResult& result = results[k];
    const Judgement j = Judge(step, result.status, result.z, tolerance);
    const bool has_z = result.z.size() == step.size();
    r.residual_abs = std::max(r.residual_abs, has_z ? j.residual.abs : result.residual_abs);
    r.residual_rel = std::max(r.residual_rel, has_z ? j.residual.rel : result.residual_rel);
    r.residual_scaled = std::max(r.residual_scaled, has_z ? j.residual.scaled : result.residual_scaled);
    if (!std::isnan(j.forward_error) && !(j.forward_error <= r.forward_error)) {
      r.forward_error = j.forward_error;
      r.forward_error_rel = j.forward_error_rel;
      r.forward_allowance = j.forward_allowance;
    }
    c.iterations += result.iterations;
    if (j.verdict == Verdict::kSolved) {
      ++c.steps_solved;
    } else if (first_failure) {
      first_failure = false;
      r.verdict = j.verdict;
      r.status = result.status;
      r.message = "step " + std::to_string(k) + " (" + step.id + "): " + std::string(ToString(j.verdict)) +
                  (result.message.empty() ? "" : ": " + result.message);
      r.backend_code = result.backend_code;
    }
    ClassifyAnswer(step.problem, result, &state);
    if (k > 0 && state != previous) ++c.active_set_changes;
    std::swap(state, previous);
    if (c.reuse && k > 0) {
      const bool reused = SessionPathOf(result) == SessionPath::kReusedActiveSet;
      (reused ? c.reused_steps : c.fallbacks) += 1;
    }
  }
  if (cut) {
    // No verdict: the steps run were judged (their counts and worst residuals are kept), the rest never ran.
    char message[200];
    if (hit_time_limit) {
      std::snprintf(message, sizeof message, "cut in step %zu of %zu: its solve reached the sequence budget of %g s "
                    "(the time limit is %g s)", steps_run, steps, budget_seconds, options.time_limit_seconds);
    } else {
      std::snprintf(message, sizeof message, "cut after %zu of %zu steps: the next would pass the sequence budget "
                    "of %g s (%.3g s spent)", steps_run, steps, budget_seconds, first);
    }
    r.mode = kCutMode;
    r.status = SolveStatus::kNotRun;
    r.verdict = Verdict::kFailed;  // kept out of every count by its mode
    r.message = message + (r.message.empty() ? std::string() : "; first failed step " + r.message);
    r.backend_code.reset();
  } else if (first_failure) {
    r.backend_code = results.back().backend_code;
  }
  if (answers) {
    answers->clear();
    for (std::size_t k = 0; k < answered; ++k) answers->push_back(results[k].z);
  }
  r.iterations = static_cast<int>(std::min<std::int64_t>(c.iterations, std::numeric_limits<int>::max()));
  return out;
}

}  // namespace smcbench
