// Sliding-surface accuracy metrics of a run (its JSON summary) and error norms against an exact solution
// (the report's `eq:trivial-conv1`, with its "∞-norm" read as the max, not the sum it prints): from a recorded
// trajectory, or accumulated while the run goes in memory independent of its length (the *Accumulator
// sinks give the same numbers bit for bit).
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "problems/stepper/trajectory.h"

namespace smcbench {

// One sliding surface y_i = C_i x + D_i. "After reaching" means the recorded steps k ≥ reaching_step.
struct SurfaceMetrics {
  // First k such that |y_i,j| ≤ tol for every recorded j ≥ k; −1 if |y_i| > tol at the last step (never reached).
  std::int64_t reaching_step = -1;
  double max_abs_y_after = 0.0;        // max_{j ≥ reaching_step} |y_i,j| (0 if never reached)
  // Sign changes of s_i: an s_i,j with |s_i,j| > sign_dead_zone whose sign differs from the last such s_i before
  // it (so 1, 0, −1 counts once, and the ±1e-12 a solver leaves on an interior s = 0 counts as 0); rows j ≥ 1 only
  // (row 0 holds no step's s).
  std::int64_t sign_changes_after = 0; // among rows j > reaching_step
  double total_variation_after = 0.0;  // Σ_{j > reaching_step} |s_i,j − s_i,j−1|
  std::int64_t sign_changes_total = 0; // over rows 1..N
  double total_variation_total = 0.0;  // Σ_{j=2..N} |s_i,j − s_i,j−1|
};

// |s| at or below this is "zero" for sign changes: well above what a backend leaves at tolerance 1e-10 on the
// one-step problems of the paper's scenes, far below the ±1 of a chattering scheme.
inline constexpr double kSignDeadZone = 1e-6;

struct TrajectoryMetrics {
  double tolerance = 0.0;
  double sign_dead_zone = kSignDeadZone;
  std::vector<SurfaceMetrics> surfaces;  // one per row of C
  // All surfaces at once: max over i of reaching_step, −1 if any surface is never reached.
  std::int64_t reaching_step = -1;
  double max_residual = 0.0;             // max relative natural residual of the one-step problems
  std::int64_t total_iterations = 0;
  int max_iterations = 0;
  std::int64_t failed_steps = 0;
};

// Throws InvalidInputError if the trajectory was not recorded, or tol or sign_dead_zone is < 0 or NaN.
TrajectoryMetrics ComputeMetrics(const Trajectory& trajectory, double tol, double sign_dead_zone = kSignDeadZone);

// ComputeMetrics while the run goes (a TrajectorySink on StepperOptions::sink): O(m) memory whatever the number of
// steps, and the same numbers bit for bit (the same comparisons, and the sums of |Δs| added in the same order).
// The reaching step is defined backwards from the end ("|y_i| ≤ tol at every later step"); forwards it is one after
// the last row that violated it, known at every row, and the "after reaching" statistics restart from 0 at every
// violation, so when the run ends they cover exactly the rows after the last one.
class MetricsAccumulator final : public TrajectorySink {
 public:
  // InvalidInputError as ComputeMetrics for tol or sign_dead_zone < 0 or NaN, or m < 0.
  MetricsAccumulator(int m, double tol, double sign_dead_zone = kSignDeadZone);
  void OnRows(const TrajectoryBlock& block) override;
  // The metrics of the rows seen so far; the per-run counters (max_residual, iterations, failed_steps) from run.
  TrajectoryMetrics Result(const Trajectory& run) const;

 private:
  struct Surface {
    std::int64_t last_violation = -1;  // last row with |y| > tol or NaN (−1: none yet)
    double max_abs_y_after = 0.0;      // over the rows after last_violation
    std::int64_t changes_after = 0;
    double variation_after = 0.0;
    int last_sign_after = 0;
    std::int64_t changes_total = 0;
    double variation_total = 0.0;
    int last_sign_total = 0;
    double previous_s = 0.0;           // s of the previous row
  };
  double tol_;
  double dead_zone_;
  std::vector<Surface> surfaces_;
  std::int64_t last_row_ = -1;
};

// What a control engineer judges an SMC implementation by: the chattering of the input and the band of σ
// once the surfaces are reached. "Reached" is the classical reaching time, forwards and independent of any later
// behaviour (a chattering scheme, whose |σ| stays O(h) above any small tolerance, also reaches): from_step is the
// first row k by which every σ_i = y_i has been on its surface, i.e. |y_i,j| ≤ tol at some row j ≤ k or y_i changed
// sign between two rows j − 1, j ≤ k. Over the rows j ≥ from_step:
//   sigma_band              max_j ‖y_j‖∞ (the steady-state band of σ)
//   u_total_variation       Σ ‖u_{j+1} − u_j‖₁ over consecutive rows with both inputs known (u_N is NaN: no step
//                           applied it), u_max_jump = max ‖u_{j+1} − u_j‖∞ over the same pairs;
//   switching_sign_changes  sign changes of s_i summed over i (s multiplies the switching part of u: u_s = −α s
//                           for Siconos' scheme, −α (CG)⁻¹ s for the paper's), counted as in SurfaceMetrics with the
//                           dead zone, over rows j > from_step;
//   rows                    the rows j ≥ from_step.
// u_max_abs = max_k ‖u_k‖∞ is over the whole run (the input magnitude). The u keys are meaningful only when the run
// has an input (has_input).
struct ChatteringMetrics {
  bool has_input = false;
  std::int64_t from_step = -1;  // −1: some surface never reached
  double sigma_band = 0.0;
  double u_total_variation = 0.0;
  double u_max_jump = 0.0;
  double u_max_abs = 0.0;
  std::int64_t switching_sign_changes = 0;
  std::int64_t rows = 0;
};

// ChatteringMetrics while the run goes (a TrajectorySink), O(m) memory.
class ChatteringAccumulator final : public TrajectorySink {
 public:
  // InvalidInputError for tol or sign_dead_zone < 0 or NaN, or m < 1.
  ChatteringAccumulator(int m, double tol, double sign_dead_zone = kSignDeadZone);
  void OnRows(const TrajectoryBlock& block) override;
  const ChatteringMetrics& Result() const { return result_; }

 private:
  double tol_, dead_zone_;
  int m_;
  std::vector<char> on_surface_;   // per σ_i: has been on its surface
  std::vector<double> previous_y_;
  std::vector<int> last_sign_;     // per s_i, since from_step
  std::vector<double> previous_u_; // the last known u (NaN: none)
  bool have_previous_row_ = false;
  ChatteringMetrics result_;
};
// The same from a recorded trajectory (its rows through ChatteringAccumulator). InvalidInputError if not recorded.
ChatteringMetrics ComputeChattering(const Trajectory& trajectory, double tol, double sign_dead_zone = kSignDeadZone);

// Discrete error norms of e_k = ‖f_k − f(t_k)‖∞ (∞-norm over components):
//   l1 = h Σ_k e_k,  l2 = (h Σ_k e_k²)^½,  max = max_k e_k.
struct ErrorNorms {
  double l1 = 0.0;
  double l2 = 0.0;
  double max = 0.0;
};

// The exact solution, either part optional (null: not compared). Each callback writes into a pre-sized vector.
struct ExactSolution {
  std::function<void(double t, Eigen::Ref<Vector> x)> x;
  std::function<void(double t, Eigen::Ref<Vector> s)> s;
};

struct SolutionErrors {
  std::optional<ErrorNorms> x;  // over rows k = 0..N
  std::optional<ErrorNorms> s;  // over rows k = 1..N: s_k (the value on (t_{k−1}, t_k]) against s(t_k)
};

// Throws InvalidInputError if the trajectory was not recorded.
SolutionErrors ComputeErrors(const Trajectory& trajectory, const ExactSolution& exact);

// ComputeErrors while the run goes (a TrajectorySink): the same sums in the same order, O(n + m) memory.
class ErrorsAccumulator final : public TrajectorySink {
 public:
  // h: the run's step (the norms' weight).
  ErrorsAccumulator(int n, int m, double h, ExactSolution exact);
  void OnRows(const TrajectoryBlock& block) override;
  SolutionErrors Result() const;

 private:
  struct Sums {
    double sum = 0.0, sum_sq = 0.0, max = 0.0;
    void Add(double e) {
      sum += e;
      sum_sq += e * e;
      max = std::max(max, e);
    }
  };
  ExactSolution exact_;
  double h_;
  Vector x_ref_, s_ref_;
  Sums x_, s_;
};

// The error of a run in the units its users read: s is the control, y = Cx + D the sliding variable.
// Against a reference run of the same scene, h, method and x0 (`smcbench simulate` steps it with certified solves):
//   s_error_max = max_k ‖s_k − s_ref,k‖∞,  y_error_max = max_k ‖y_k − y_ref,k‖∞,
// over the steps k = 1..steps_compared both runs took without a failure of the reference (k = 0 is the shared
// initial state). A NaN difference counts as +∞.
struct ReferenceErrors {
  double s_error_max = 0.0;
  double y_error_max = 0.0;
  std::int64_t steps_compared = 0;  // min(run.steps_taken, reference's last good step)
};

// Throws InvalidInputError if either trajectory was not recorded or their n, m or h differ.
ReferenceErrors CompareWithReference(const Trajectory& run, const Trajectory& reference);

// CompareWithReference one step at a time, for runs that are streamed rather than recorded: Add(s, y, s_ref,
// y_ref) for each step k = 1..steps_compared, in any order (a maximum). m entries each.
class ReferenceErrorsAccumulator {
 public:
  void Add(const double* s, const double* y, const double* s_ref, const double* y_ref, int m);
  const ReferenceErrors& errors() const { return errors_; }

 private:
  ReferenceErrors errors_;
};

}  // namespace smcbench
