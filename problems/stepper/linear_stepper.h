// The time loop for the linear sliding-mode systems (class (2), ZOH-SMC): each implicit step is the box-MLCP
// `eq:TDS3` (z = s_{k+1}, M = C S, q = −(C R x_k + C p_k + D), l = −1, u = 1) solved by whichever backend the
// caller passes. Two paths:
//   LinearStepper: M, C R, C p + D (and the BoxMLCP itself) are built once; a step is a few small mat-vecs, an
//     in-place q update (BoxMLCP::set_q) and the solve, warm-started from s_k (a solve session, SolveSession,
//     whose checks that cannot change during the run are made once before the loop). Fixed-size Eigen kernels serve
//     n ≤ 4, m ≤ 2 (every linear scene of docs/scenes.md); larger systems use a dynamic kernel with preallocated
//     buffers. Neither allocates per step. A run either records its history (O(N) memory) or hands its rows to a
//     TrajectorySink as it goes (StepperOptions::sink: one bounded block), or keeps only the final state.
//   A polytope law (OneStepData::law): each implicit step is the AVI 0 ∈ M s + q + N_P(s) with the same M and q,
//     solved through AviSession (the exact reduction to a box-MLCP, built once per run; no per-step allocation
//     after the first step with an allocation-free backend). Warm-started as the box path: the session first tries
//     the reduction's last active set, and the backend starts from the previous step's (λ, μ) (warm_start on).
//   SimulateRebuildingEachStep: what a general simulator does: every step re-discretizes (LU of I − hθE or the
//     matrix exponential), rebuilds M = C S and a fresh BoxMLCP, then solves. Same trajectory up to rounding;
//     benchmarks compare the two to show what precomputation buys.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "problems/stepper/discretization.h"
#include "problems/stepper/trajectory.h"
#include "solvers/avi/affine_vi.h"
#include "solvers/core/solver.h"

namespace smcbench {

// What to do when a one-step problem is not solved (status != kSolved).
//   kStop: record that step (its x_k computed from the backend's returned z), then stop; the trajectory ends at
//     first_failed_step and stopped_early is set.
//   kContinue: record the status and go on; failed_steps counts them.
// A non-finite state (NaN → kNumericalFailure, ±∞ → kDiverged) always stops the run: nothing sensible follows.
enum class FailurePolicy { kStop, kContinue };

// Receives every one-step box-MLCP a stepper hands to its backend, right after the solve (capture of a run's
// problems into the problem library: problems/library/capture.h). Called only for implicit steps that reach the
// backend: LinearStepper and SimulateRebuildingEachStep once per step, NonlinearStepper (Algorithm 2) once per
// Newton iteration; Algorithm 1 (an MCP, not a box-MLCP) and explicit-sign steps call nothing. The references
// are valid during the call only. An exception thrown by OnStep propagates out of Run.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  // step: k ≥ 1, the step whose solve gives x_k. newton_iteration: 0 for a linear stepper, α ≥ 1 for the inner
  // MLCP of Algorithm 2's Newton iteration α. result: the backend's answer (result.z is the z the run used).
  virtual void OnStep(std::int64_t step, int newton_iteration, const BoxMLCP& problem,
                      const SolveResult& result) = 0;
};

// What a run does about subnormal numbers (|v| < 2.2e-308, float_mode.h): a state decaying to the origin enters
// that range and, in IEEE arithmetic, stays there for good (the smallest subnormal divided by 1.3 rounds back to
// itself), and on common hardware every operation on a subnormal is many times slower than on a normal number
// (docs/benchmarks.md, "Long runs and subnormal numbers", has the measured effect on a long run).
//   kZeroState (default): after each implicit step, a state component whose magnitude is below the smallest normal
//     double (std::numeric_limits<double>::min(), 2.2e-308) is set to exactly 0. The state then reaches the origin
//     exactly instead of parking on subnormals, and 0 is a fixed point. It changes a component by less than
//     2.2e-308 (absolute), the size of the subnormal range itself, and touches nothing else: the backend's and the
//     steppers' arithmetic stays plain IEEE on every architecture. Implicit steps only (like zero_rounding_residue):
//     s_{k+1} = Π(·) is continuous in x_k, whereas the explicit sgn(y_k) jumps at 0, so an explicit step keeps its
//     subnormal state (an explicit scheme chatters around the surface instead of decaying to the origin).
//   kFlushToZero: x86 flush-to-zero and denormals-are-zero for the whole run, on the calling thread, backend
//     included (ScopedFlushSubnormals); every subnormal result and operand is 0. A no-op on other architectures.
//   kIeee: plain IEEE arithmetic, subnormal states kept (`smcbench simulate --ieee-subnormals`).
enum class SubnormalPolicy { kZeroState, kFlushToZero, kIeee };

struct StepperOptions {
  // Passed to the backend at every step. The stepper overrides two fields: warm_start (s_k when warm_start below
  // is on, else empty; with a polytope law the previous step's (λ, μ) mapped into the reduction, AviSession) and
  // measure_time (false: the clock costs as much as a small solve).
  SolverOptions solver;
  // The run's solve session (solvers/core/session.h): by default each step first tries the previous step's active
  // set; reuse_active_set = false sends every step to the backend's own algorithm (to time or study it).
  SessionOptions session;
  bool warm_start = true;
  FailurePolicy on_failure = FailurePolicy::kStop;
  // false: keep only x_final/s_final/y_final and the counters (benchmarks; no O(N) memory).
  bool record = true;
  double t0 = 0.0;
  // Not owned; null (the default) costs one predictable branch per step and nothing else.
  StepObserver* observer = nullptr;
  // Not owned. Receives every row of the run (0 .. steps_taken) while it goes, through one buffer of bounded size
  // (trajectory.h: TrajectoryStream), whether or not record is on: outputs of long runs in constant memory. Null
  // (the default) costs one predictable branch per step.
  TrajectorySink* sink = nullptr;
  // See SubnormalPolicy: by default a state component that underflows below 2.2e-308 after an implicit step is 0.
  SubnormalPolicy subnormals = SubnormalPolicy::kZeroState;
  // Implicit steps: a component of x_{k+1} = a − b (a = R x_k + p_k, b = S s_{k+1}) with |x_{k+1,i}| ≤ K·u·(|a_i| +
  // |b_i|) (u = ε/2, K = n + m + 1, plus n with forcing) is set to exactly 0: it lies within the rounding-error
  // bound γ_K(|R||x_k| + |p_k| + |S||s_{k+1}|) of its own computation (Higham, Accuracy and Stability, §3.1), so
  // its digits are rounding, not state. Why: on the sliding surface of S1 the exact step is x_{k+1} = x_k − h·(x_k/h)
  // = 0, but with s = fl(x_k/h) rounded, fl(x_k − h·s) ≠ 0 for about 1 % of h, and the residue r only shrinks by
  // ~2⁻⁵³ per step (r − h·fl(r/h) again), ~20 steps to underflow: Lemma (yahoo) would fail by rounding alone.
  // Implicit steps only: s_{k+1} = Π(·) is continuous in x_k, so a zeroed residue moves the next s by residue/h;
  // the explicit sgn(y_k) jumps at 0 and is left to plain arithmetic. false: the plain update.
  bool zero_rounding_residue = true;
  // The step verdict in units of the next state (step_verdict.h, docs/verdict.md "The step verdict"): every implicit
  // step the backend calls solved is solved again exactly on its active set (long double); the run continues from
  // that exact step, Trajectory::refined_steps counts the answers off by more than tol·(‖S‖∞ + ‖x_{k+1}‖∞) in x, and
  // a step with no exact solution on its active set is kInaccurate. false: the backend's answer as given, judged by
  // its residual alone (to study a backend's own accuracy).
  bool refine_steps = true;

  // True if usable; otherwise *why names the field.
  bool IsValid(std::string* why) const;
};

class LinearStepper {
 public:
  // Validates data and builds everything constant: M = C S, C R, C p + D, C P, the BoxMLCP. InvalidInputError
  // naming the field on bad data.
  explicit LinearStepper(OneStepData data);
  ~LinearStepper();
  LinearStepper(LinearStepper&&) noexcept;
  LinearStepper& operator=(LinearStepper&&) noexcept;

  const OneStepData& data() const { return data_; }
  // The one-step problem: M = C S (constant) and the q of the last step run. With a polytope law, the box-MLCP of
  // the same M (its q is not updated); the one-step problem is then avi().
  const BoxMLCP& problem() const { return *problem_; }
  // The one-step AVI of a polytope law (M = C S, q = 0, P = {s : H s ≥ K}), null for the box.
  const AffineVI* avi() const { return avi_.get(); }
  // True when a fixed-size kernel serves this (n, m).
  bool uses_fixed_size_kernel() const;

  // Runs num_steps steps from x0 (at t = options.t0) into *out (storage reused across runs). solver may be null
  // only for an explicit-sign scheme. Throws InvalidInputError for bad arguments (x0 size/NaN, num_steps < 0,
  // null solver, invalid options); a step the backend does not solve is a status in *out, never an exception.
  void Run(const Vector& x0, std::int64_t num_steps, Solver* solver, const StepperOptions& options, Trajectory* out);
  Trajectory Run(const Vector& x0, std::int64_t num_steps, Solver* solver, const StepperOptions& options = {});

  class Kernel;  // implementation detail (fixed-size or dynamic)

 private:
  OneStepData data_;
  std::unique_ptr<BoxMLCP> problem_;
  std::unique_ptr<AffineVI> avi_;
  std::unique_ptr<Kernel> kernel_;
};

// The generic, rebuild-every-step path (see the file comment). Discretize(model, method, h, theta) is validated
// once; then each step recomputes the discretization without re-validating, builds M = C S, q and a new
// BoxMLCP, and solves. Arguments and failure handling as LinearStepper::Run.
void SimulateRebuildingEachStep(const LinearModel& model, Method method, double h, double theta, const Vector& x0,
                                std::int64_t num_steps, Solver* solver, const StepperOptions& options,
                                Trajectory* out);

}  // namespace smcbench
