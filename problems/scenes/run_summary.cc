#include "problems/scenes/run_summary.h"

#include <algorithm>
#include <vector>

#include <nlohmann/json.hpp>

#include "problems/scenes/scene.h"

namespace smcbench {
namespace {

using json = nlohmann::json;

json VectorJson(const Vector& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

}  // namespace

json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                       const Trajectory& tr, double reach_tol, double wall_seconds,
                       const ReferenceComparison* reference) {
  RunMetrics metrics;
  metrics.metrics = ComputeMetrics(tr, reach_tol);
  if (tr.m > 0) metrics.chattering = ComputeChattering(tr, reach_tol);
  if (const std::optional<double> band = scene.convergence_band()) {
    metrics.super_twisting = ComputeSuperTwistingPrecision(tr, *band);
  }
  try {
    if (const auto exact = scene.Exact(settings)) metrics.exact_errors = ComputeErrors(tr, *exact);
  } catch (const InvalidInputError& e) {
    metrics.exact_unavailable = e.what();
  }
  return SimulationSummary(scene, settings, solver, tr, metrics, reach_tol, wall_seconds, reference);
}

json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                       const Trajectory& tr, const RunMetrics& run_metrics, double reach_tol, double wall_seconds,
                       const ReferenceComparison* reference) {
  json j;
  j["scene"] = scene.info().name;
  j["source"] = scene.info().source;
  j["method"] = std::string(ToString(settings.method));
  j["discretization"] = tr.description;
  j["solver"] = solver.empty() ? json(nullptr) : json(std::string(solver));
  j["h"] = settings.h;
  j["T"] = settings.T;
  if (!IsZoh(settings.method)) j["theta"] = settings.theta;
  j["gamma"] = settings.gamma;
  // Only when asked for (a default run's summary is unchanged): the CSV's rows between samples; metrics are on samples.
  if (settings.plant_substeps > 1) j["plant_substeps"] = settings.plant_substeps;
  if (scene.step_kind() == SceneStepKind::kNonlinear) {
    j["algorithm"] = std::string(ToString(settings.algorithm));
    j["newton_tolerance"] = settings.newton_tolerance;
    j["newton_max_iterations"] = settings.newton_max_iterations;
  }
  // The implicit super-twisting step's route (closed-form or mcp); the explicit scheme solves nothing.
  if (scene.step_kind() == SceneStepKind::kSuperTwisting && settings.method == Method::kImplicit) {
    j["algorithm"] = std::string(ToString(settings.algorithm));
  }
  j["x0"] = VectorJson(settings.x0);
  j["parameters"] = json::object();
  for (const auto& [name, value] : settings.parameters) j["parameters"][name] = value;
  j["n"] = tr.n;
  j["m"] = tr.m;

  j["steps"] = tr.steps_taken;
  j["steps_requested"] = tr.num_steps;
  j["completed"] = tr.steps_taken == tr.num_steps && !tr.stopped_early;
  j["x_final"] = VectorJson(tr.x_final);
  j["s_final"] = VectorJson(tr.s_final);
  j["y_final"] = VectorJson(tr.y_final);

  // The one-step problems: only implicit methods solve any.
  j["max_residual"] = tr.max_residual;
  j["total_iterations"] = tr.total_iterations;
  j["max_iterations"] = tr.max_iterations;
  j["failed_steps"] = tr.failed_steps;
  // The step verdict (StepperOptions::refine_steps, docs/verdict.md): the backend's own largest forward error in
  // x_{k+1} against the exact step, and how many answers were off by more than the allowance (the run went on from
  // the exact step, so s_error_max below measures the trajectory, these the backend).
  j["step_x_error_max"] = tr.max_step_x_error;
  j["refined_steps"] = tr.refined_steps;
  if (tr.first_failed_step >= 0) {
    j["first_failure"] = {{"step", tr.first_failed_step},
                          {"status", std::string(ToString(tr.first_failure_status))},
                          {"residual", tr.first_failure_residual},
                          {"message", tr.first_failure_message}};
  } else {
    j["first_failure"] = nullptr;
  }
  j["wall_seconds"] = wall_seconds;
  j["steps_per_second"] = wall_seconds > 0.0 ? static_cast<double>(tr.steps_taken) / wall_seconds : 0.0;

  // Sliding-surface accuracy (computed while the run went, or from its recorded history).
  const TrajectoryMetrics& metrics = run_metrics.metrics;
  j["reaching_tolerance"] = reach_tol;
  j["sign_dead_zone"] = metrics.sign_dead_zone;
  j["reaching_step"] = metrics.reaching_step;
  j["reaching_time"] = metrics.reaching_step >= 0 ? json(tr.time(metrics.reaching_step)) : json(nullptr);
  double max_y = 0.0, tv_after = 0.0, tv_total = 0.0;
  std::int64_t changes_after = 0, changes_total = 0;
  json surfaces = json::array();
  for (const SurfaceMetrics& s : metrics.surfaces) {
    max_y = std::max(max_y, s.max_abs_y_after);
    changes_after += s.sign_changes_after;
    tv_after += s.total_variation_after;
    changes_total += s.sign_changes_total;
    tv_total += s.total_variation_total;
    surfaces.push_back({{"reaching_step", s.reaching_step},
                        {"max_abs_y_after_reaching", s.max_abs_y_after},
                        {"sign_changes_after_reaching", s.sign_changes_after},
                        {"total_variation_after_reaching", s.total_variation_after},
                        {"sign_changes_total", s.sign_changes_total},
                        {"total_variation_total", s.total_variation_total}});
  }
  // Summed over the surfaces (max for |y|); "after reaching" is per surface, from its own reaching step. A surface
  // never reached contributes nothing after reaching.
  j["max_abs_y_after_reaching"] = max_y;
  j["sign_changes_after_reaching"] = changes_after;
  j["total_variation_after_reaching"] = tv_after;
  j["sign_changes_total"] = changes_total;
  j["total_variation_total"] = tv_total;
  j["surfaces"] = surfaces;
  j["chattering"] = ChatteringJson(run_metrics.chattering, tr.t0, tr.h);
  if (run_metrics.super_twisting) j["super_twisting"] = SuperTwistingJson(*run_metrics.super_twisting, tr.t0, tr.h);

  // The error in s and y against the certified reference run (keys always present; null when there is none).
  if (reference != nullptr && reference->errors) {
    j["s_error_max"] = reference->errors->s_error_max;
    j["y_error_max"] = reference->errors->y_error_max;
    j["reference_skipped"] = nullptr;
  } else {
    j["s_error_max"] = nullptr;
    j["y_error_max"] = nullptr;
    j["reference_skipped"] = reference == nullptr ? std::string("not computed") : reference->skipped;
  }
  if (reference != nullptr && reference->ran) {
    j["reference"] = {{"solver", "reference"},
                      {"steps", reference->steps},
                      {"steps_compared", reference->errors ? reference->errors->steps_compared : 0},
                      {"completed", reference->completed},
                      {"first_failure",
                       reference->first_failure.empty() ? json(nullptr) : json(reference->first_failure)},
                      {"wall_seconds", reference->wall_seconds}};
  } else {
    j["reference"] = nullptr;
  }

  // Errors against the exact solution, for scenes that have one.
  if (!run_metrics.exact_unavailable.empty()) {
    j["errors"] = nullptr;
    j["exact_solution_unavailable"] = run_metrics.exact_unavailable;
  } else if (run_metrics.exact_errors) {
    const SolutionErrors& e = *run_metrics.exact_errors;
    json errors = json::object();
    if (e.x) errors["x"] = {{"l1", e.x->l1}, {"l2", e.x->l2}, {"max", e.x->max}};
    if (e.s) errors["s"] = {{"l1", e.s->l1}, {"l2", e.s->l2}, {"max", e.s->max}};
    j["errors"] = errors;
  }
  return j;
}

json SuperTwistingJson(const SuperTwistingPrecision& p, double t0, double h) {
  const auto time = [&](std::int64_t k) { return k >= 0 ? json(t0 + static_cast<double>(k) * h) : json(nullptr); };
  return {{"band", p.band},
          {"convergence_step", p.convergence_step >= 0 ? json(p.convergence_step) : json(nullptr)},
          {"convergence_time", time(p.convergence_step)},
          {"tail_from_step", p.tail_from},
          {"tail_from_time", time(p.tail_from)},
          {"max_abs_sigma_tail", p.max_abs_sigma_tail},
          {"max_abs_sigma_dot_tail", p.max_abs_sigma_dot_tail}};
}

json ChatteringJson(const std::optional<ChatteringMetrics>& chattering, double t0, double h) {
  if (!chattering) return nullptr;
  const ChatteringMetrics& c = *chattering;
  const auto input = [&](double v) { return c.has_input ? json(v) : json(nullptr); };
  return {{"has_input", c.has_input},
          {"from_step", c.from_step >= 0 ? json(c.from_step) : json(nullptr)},
          {"from_time", c.from_step >= 0 ? json(t0 + static_cast<double>(c.from_step) * h) : json(nullptr)},
          {"sigma_band", c.sigma_band},
          {"u_total_variation", input(c.u_total_variation)},
          {"u_max_jump", input(c.u_max_jump)},
          {"u_max_abs", input(c.u_max_abs)},
          {"switching_sign_changes", c.switching_sign_changes},
          {"rows", c.rows}};
}

}  // namespace smcbench
