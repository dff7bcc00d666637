// Timed, repeated solves of one problem by one backend, and their rendering as text and JSON rows.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solvers/core/solver.h"
#include "solvers/core/verdict.h"

namespace smcbench {

struct SolveRecord {
  std::string problem;
  std::string solver;
  SolveResult result;             // from the last repetition
  double time_ns_median = 0.0;    // median wall time per solve (cold, or warm with `solve --warm`)
  double time_ns_min = 0.0;
  double time_ns_max = 0.0;
  int repeats = 0;
  int solves_per_sample = 1;  // the repeats are timed in batches of this many solves (TimedSolve)
  bool warm = false;  // timed through a session, each repeat from the previous answer
  // Some timed solve was answered by a siconos-* backend's isolation worker (AnswerProcessOf: kWorker), so the times
  // include its inter-process round trip: `--repeat 1` (the one solve is the probe), isolate=always, or a
  // problem whose probe crashed or timed out. False for our backends.
  bool timed_in_worker = false;
  // Cold repeats (not warm) of a backend that remembers something between solves (Solver::ForgetWarmState: a Siconos
  // direct solver's active-set cache, auto's fallback choice) are each timed alone, after an untimed forget, so no
  // repeat is answered from that memory (solves_per_sample 1). cached: the backend said it cannot forget, so its
  // repeats may not have started cold.
  bool forgot_between_repeats = false;
  bool cached = false;
  std::string error;              // set when the backend could not even be configured
  // With `solve --reference`: the judgement against the certified reference (forward errors NaN when the
  // reference does not prove z* unique). has_judgement false: not judged, the keys are not written.
  bool has_judgement = false;
  Judgement judgement;
};

// Solves problem `repeat` times through one session (Solver::Prepare, docs/session.md) with one reused result, and
// records the median, min and max time per solve. The first solve is untimed by the batches: it sizes the workspace
// and, for a siconos-* backend, is the probe in its isolation worker, so that the timed solves run in process
// (solvers/siconos/siconos_solver.h); a first solve that hit the time limit, or repeat 1, is the record by itself
// (its own clock). The repeats are timed in batches of solves_per_sample solves between two clock reads (a clock
// read costs as much as a small solve), each sample a batch's time over its size.
// warm false (cold): every repeat runs the backend's own algorithm from the options' start point; a backend that
// remembers something between solves forgets it before each repeat, untimed, and each repeat is then timed alone
// (forgot_between_repeats). warm: each repeat
// starts from the previous answer with the session's reused active set on, as a time-stepper's steps do (never for
// an external backend, SolverInfo::external: Siconos' own warm behaviour is timed).
SolveRecord TimedSolve(Solver& solver, const BoxMLCP& problem, const SolverOptions& options, int repeat,
                       bool warm = false);

// "lemke    solved   iters 3   res 0.00e+00 abs / 0.00e+00 rel / 0.00e+00 eq   1.2 us" (fixed columns), then
// "   fwd err 1.11e-16 (rel 1.11e-16, allowed 2.00e-09)   solved" (or "fwd err n/a") when judged.
std::string FormatRecordLine(const SolveRecord& record);
// The stable JSON keys scripts depend on: solver, status, iterations, residual_abs, residual_rel,
// residual_scaled, time_ns_median, z (plus problem, message, time_ns_min/max, repeats, solves_per_sample, timed_in_worker,
// forgot_between_repeats, cached, details);
// when judged against a reference also forward_error, forward_error_rel (null when not defined), forward_allowance,
// verdict.
nlohmann::json RecordToJson(const SolveRecord& record);
// {certificate, condition, z} of a reference solution (z empty unless verified; condition null when infinite).
nlohmann::json ReferenceToJson(const ReferenceSolution& reference);
// Human time: "850 ns", "12.3 us", "4.56 ms", "1.23 s".
std::string FormatDuration(double ns);

}  // namespace smcbench
