// The JSON summary of a scene's run (`smcbench simulate --summary`, Python's Simulation.summary, the paper's
// chattering table): here, beside the scenes, so that every caller writes the same keys from the same numbers.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "problems/scenes/reference_run.h"
#include "problems/scenes/scene.h"
#include "problems/stepper/super_twisting.h"

namespace smcbench {

// The JSON summary of a run. Stable keys; scripts rely on steps, x_final, reaching_step and:
//   s_error_max, y_error_max  max over steps k ≥ 1 of ‖s_k − s_ref,k‖∞ and ‖y_k − y_ref,k‖∞ against the reference
//                             run (reference_run.h: CompareWithReferenceRun); null when there is none, and then
//   reference_skipped         says why (a string; null when the errors are there);
//   reference                 {solver: "reference", steps, steps_compared, completed, first_failure, wall_seconds}
//                             of the reference run, or null when none was made.
// reference may be null (the keys are then null with reference_skipped "not computed"). This overload computes the
// metrics from the history (ComputeMetrics, ComputeErrors: InvalidInputError if the trajectory was not recorded);
// `simulate` itself uses the one below with metrics accumulated while the run went (the same numbers).
//   reach_tol: a surface is "reached" from the first step after which |y_i| ≤ reach_tol at every later step.
//   chattering                the input and its chattering once the surfaces are reached (docs/smc.md;
//                             metrics.h ChatteringMetrics, the reaching time forwards: σ_i within reach_tol or
//                             crossed 0): {has_input, from_step, from_time, sigma_band, u_total_variation,
//                             u_max_jump, u_max_abs, switching_sign_changes, rows}; the u keys are null when the run
//                             has no control input (class-(2) scenes without control_input, Euler runs of ZOH plants),
//                             from_time null and the after-reaching keys 0 when a surface is never reached.
//   super_twisting            super-twisting scenes only (super_twisting_scene.h): {band, convergence_step,
//                             convergence_time, tail_from_step, tail_from_time, max_abs_sigma_tail,
//                             max_abs_sigma_dot_tail} (super_twisting.h: SuperTwistingPrecision; the tail is the
//                             second half of the run, σ' the difference quotient (σ_{k+1} − σ_k)/h).
nlohmann::json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                                 const Trajectory& trajectory, double reach_tol, double wall_seconds,
                                 const ReferenceComparison* reference = nullptr);

// What the summary says about a run's rows beyond its counters: computed while it ran (MetricsAccumulator,
// ErrorsAccumulator: `simulate`) or from a recorded trajectory (ComputeMetrics, ComputeErrors: the overload above).
struct RunMetrics {
  TrajectoryMetrics metrics;
  std::optional<SolutionErrors> exact_errors;  // against the scene's exact solution, when it has one
  std::string exact_unavailable;               // why Exact() refused these settings (errors: null); else empty
  std::optional<ChatteringMetrics> chattering; // null: the summary's chattering is null
  std::optional<SuperTwistingPrecision> super_twisting;  // super-twisting scenes
};
// The summary's "super_twisting" object; h and t0 give the times.
nlohmann::json SuperTwistingJson(const SuperTwistingPrecision& precision, double t0, double h);
// The summary's "chattering" object (null for nullopt); h and t0 give from_time.
nlohmann::json ChatteringJson(const std::optional<ChatteringMetrics>& chattering, double t0, double h);
// The summary from metrics computed elsewhere; run gives the counters, finals and sizes (it need not be recorded).
nlohmann::json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                                 const Trajectory& run, const RunMetrics& metrics, double reach_tol,
                                 double wall_seconds, const ReferenceComparison* reference);

}  // namespace smcbench
