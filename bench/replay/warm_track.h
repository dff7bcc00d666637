// The warm track of `smcbench bench` (a time-stepper's situation): a sequence of one-step box-MLCPs sharing M, l and
// u, replayed in order, each step started from the previous step's answer through each backend's own warm
// mechanism: ours through one SolveSession whose reused active set answers when it still fits; an external backend
// (siconos-*, bullet-*, dart-*) through the same adapter instance kept alive across the steps (Siconos' direct
// solvers keep their cache, never reset here) with the previous answer as its start. Each step is judged by the
// verdict of the cold records (Judge against the step's certified reference); the sequence is correct only when
// every step is solved.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/replay/replay.h"
#include "problems/library/problem_set.h"

namespace smcbench {

// Where a sequence's steps come from.
enum class WarmSource : int {
  kScene = 0,       // one run of a paper scene, every step's one-step problem in order (capture.h)
  kTrajectory = 1,  // a families problem with q moving smoothly along a trajectory, M fixed
  kCapture = 2,     // consecutive problems of a user's problem-set file that share M, l and u
};
const char* ToString(WarmSource source);

// One sequence: its steps share M, l and u (CheckWarmSequence) and differ in q.
struct WarmSequence {
  std::string suite;  // the suite its records belong to
  std::string id;     // "<suite>/warm/<what>"
  WarmSource source = WarmSource::kTrajectory;
  std::vector<LibraryProblem> steps;  // in order; each with its expected outcome and certified reference
};

// InvalidInputError naming the sequence and the step unless it has a step and every step has the first one's
// M, l and u (bit for bit) and the same storage (dense or sparse).
void CheckWarmSequence(const WarmSequence& sequence);

// What a sequence run counted (over the judged pass).
struct WarmCounts {
  int steps = 0;
  int steps_solved = 0;        // steps whose verdict is solved
  // Steps whose answer's active set (ClassifyRow of every row) differs from the previous step's answer's.
  int active_set_changes = 0;
  std::int64_t iterations = 0;  // the backend's pivots or iterations, summed over the steps
  // Our session's warm path (detail "path"): steps after the first answered by the reused active set, and those
  // where it did not answer and the backend ran (fallbacks). Both 0 for a backend without that path (reuse false).
  bool reuse = false;
  int reused_steps = 0;
  int fallbacks = 0;
};

// One sequence × backend: record.mode "warm", problem = the sequence's id, size its m, iterations the total (capped
// to int), verdict and status those of the first step not solved (solved when all are), residuals and forward
// error their worst over the steps, time_* seconds per step (medians over repeats of the whole sequence).
struct WarmRecord {
  ReplayRecord record;
  WarmSource source = WarmSource::kTrajectory;
  WarmCounts counts;
};

// The mode of a record whose job was cut by a time budget (a warm sequence past its --sequence-budget, a cold job
// past its --job-budget or a backend past its --backend-budget): no verdict of the backend, neither a success nor a
// failure; its message says how far it got ("cut after N of M steps: ..."). The report lists such records apart.
inline constexpr const char* kCutMode = "cut";

// Runs sequence on solver: an untimed pass, then timed passes of the whole sequence (each with a fresh session,
// its set-up timed with it: a stepper prepares once per run) until options.repetitions or
// options.max_seconds_per_pair; the last pass's answers are judged at tolerance (and copied to *answers, one per
// step run, when given). A step that runs into the time limit ends a pass (the rest are not run: failed) and the
// untimed pass is then the only sample. A backend that fails is a record.
// budget_seconds > 0 bounds the job: every solve runs under min(time limit, budget); the untimed pass stops after
// a step when the next, at the pace of the last, would end past the budget, and if steps remain (or the budget
// stopped a solve) the record is cut (mode kCutMode, status not_run, the judged counts those of the steps answered,
// the message "cut after N of M steps: the next would pass the sequence budget of B s (T s spent)" or "cut in step
// N of M: its solve reached the sequence budget ..."); an untimed pass that fits but took more than half the budget
// is the only sample (as after a time limit), and a timed pass follows another only while it would end inside the
// budget.
WarmRecord ReplayWarmSequence(const WarmSequence& sequence, Solver* solver, const std::string& solver_name,
                              const ReplayOptions& options, double tolerance, std::vector<Vector>* answers = nullptr,
                              double budget_seconds = 0.0);

}  // namespace smcbench
