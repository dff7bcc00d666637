// The sampled-data plant of a ZOH controller (Siconos' ControlZOHSimulation setting): the controller acts at the
// samples t_k = t0 + k h and the plant runs on continuously under the held input u_k. For a linear plant the state
// between samples is exact: x(t_k + τ) = e^{Fτ} x_k + Ψ(τ) G u_k + the disturbance's forced response over
// [t_k, t_k + τ) (Ψ(τ) = ∫₀^τ e^{Fσ}dσ; the response is exact for the constant-plus-sinusoids d(t), no substepping).
// SampledPlantSink inserts the states at τ_j = j h / s (j = 1..s−1) between a run's rows on their way to a sink (the
// trajectory CSV, the plot), so they show the continuous plant and not only its samples; the run itself, its
// recorded history and every metric stay on the controller's samples.
#pragma once

#include <cstdint>
#include <vector>

#include "problems/stepper/discretization.h"
#include "problems/stepper/linear_system.h"
#include "problems/stepper/trajectory.h"

namespace smcbench {

// The maps from (x_k, u_k, t_k) to the state at one point t_k + τ between two samples.
struct PlantSubstep {
  double tau = 0.0;                 // j h / s
  DenseMatrix exp_F;                // e^{Fτ}, n×n
  DenseMatrix psi_G;                // Ψ(τ) G, n×m
  DisturbanceResponse disturbance;  // the forced response over [t_k, t_k + τ); empty without a disturbance
};

// The s − 1 points between two samples of step h (empty for s = 1), each from one exponential of the block matrix
// τ [[F, G], [0, 0]] (and one per sinusoid of the disturbance), computed once per run. InvalidInputError naming
// the field for substeps < 1, h ≤ 0 or non-finite, an invalid system or a non-finite exponential.
std::vector<PlantSubstep> DiscretizeBetweenSamples(const ZohSmcSystem& system, double h, int substeps);

// Passes a run's rows on to `downstream` with the s − 1 states between each row k and row k + 1 inserted after
// row k: t_k + τ_j, x(t_k + τ_j), s = s_{k+1} (the multiplier of the input held over the interval),
// y = C x + D + e(t_k + τ_j), 0 iterations, residual 0, status kNotRun, u = u_k (the input actually applied).
// The run's last row (u = NaN: no step applied it) gets no points after it. A row is held back until the next
// arrives (its points need s_{k+1}): call Finish() once after the run. The run's rows must carry the input
// (TrajectoryBlock::has_input: every ZOH run does); InvalidInputError otherwise. Sized once at construction: OnRows
// and Finish do not allocate (e(t) is evaluated into a member buffer).
// With s = 1 every row passes unchanged (the same numbers, in the same blocks' order).
class SampledPlantSink final : public TrajectorySink {
 public:
  // downstream: not owned, must outlive the sink.
  SampledPlantSink(const ZohSmcSystem& system, double h, int substeps, TrajectorySink* downstream);
  void OnRows(const TrajectoryBlock& block) override;
  // Hands out the held row and flushes the rows to downstream (the end of a run); the sink can then take another.
  void Finish();
  int substeps() const { return static_cast<int>(substeps_.size()) + 1; }
  // Rows handed to downstream for a run of num_steps steps: s·N + 1.
  std::int64_t RowsFor(std::int64_t num_steps) const { return num_steps * substeps() + 1; }

 private:
  void EmitHeld(const double* next_s);

  std::vector<PlantSubstep> substeps_;
  DenseMatrix C_;
  Vector D_;                 // m (zero when the system has none)
  Forcing relation_offset_;  // e(t) of y, null when none
  TrajectoryStream stream_;
  std::int64_t next_row_ = 0;
  // The held row.
  bool held_ = false;
  double held_t_ = 0.0;
  Vector held_x_, held_s_, held_y_, held_u_;
  int held_iterations_ = 0;
  double held_residual_ = 0.0;
  SolveStatus held_status_ = SolveStatus::kNotRun;
  // A point between samples.
  Vector point_x_, point_y_, point_e_;
};

}  // namespace smcbench
