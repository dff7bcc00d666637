#include "bench/replay/stepper_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "problems/scenes/linear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/linear_stepper.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using Clock = std::chrono::steady_clock;

// Median wall time of fn over repeats lasting at least min_seconds in total (at least 3 runs).
template <typename Fn>
double TimeRuns(Fn&& fn, double min_seconds) {
  std::vector<double> t;
  const auto start = Clock::now();
  while (t.size() < 3 || (std::chrono::duration<double>(Clock::now() - start).count() < min_seconds && t.size() < 1000)) {
    const auto s = Clock::now();
    fn();
    t.push_back(std::chrono::duration<double>(Clock::now() - s).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

constexpr double kReferenceFactor = 8.0;

// The largest per-step forward error of s over a run: each one-step problem the backend claimed to solve judged by
// the caller's certifier (a step it did not solve is a failure, already counted by Trajectory::ok, not an error).
class StepErrorObserver final : public StepObserver {
 public:
  explicit StepErrorObserver(const StepForwardError& forward_error) : forward_error_(forward_error) {}
  void OnStep(std::int64_t, int, const BoxMLCP& problem, const SolveResult& result) override {
    if (result.status != SolveStatus::kSolved || result.z.size() != problem.size()) return;
    const double e = forward_error_(problem, result.z);
    if (std::isnan(e)) return;
    max_error_ = std::isnan(max_error_) ? e : std::max(max_error_, e);
    ++steps_;
  }
  double max_error() const { return max_error_; }
  std::int64_t steps() const { return steps_; }

 private:
  const StepForwardError& forward_error_;
  double max_error_ = kNaN;
  std::int64_t steps_ = 0;
};

}  // namespace

StepperStudy RunStepperStudy(const StepperStudyOptions& options) {
  std::vector<std::string> names = options.solvers;
  if (names.empty()) {
    for (auto n : SolverNames()) names.emplace_back(n);
  }
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const auto& n : names) solvers.push_back(CreateSolver(n));
  StepperStudy out;
  out.reference_h_factor = kReferenceFactor;

  // Warm against cold: the scene's own run, each step's solve started from s_k or from Π(0).
  for (const auto& scene_name : options.warm_scenes) {
    const auto scene = LoadScene(scene_name);
    for (std::size_t b = 0; b < solvers.size(); ++b) {
      for (const bool warm : {true, false}) {
        SimulationSettings s = scene->defaults();
        s.stepper.record = false;
        s.stepper.warm_start = warm;
        s.stepper.on_failure = FailurePolicy::kContinue;
        s.stepper.solver.polish = options.polish;
        Trajectory tr;
        const double seconds = TimeRuns([&] { scene->Run(s, solvers[b].get(), &tr); }, options.min_seconds);
        WarmStartRecord r;
        r.scene = scene_name;
        r.solver = names[b];
        r.mode = warm ? "warm" : "cold";
        r.steps = tr.steps_taken;
        r.seconds_per_step = tr.steps_taken ? seconds / static_cast<double>(tr.steps_taken) : 0.0;
        r.iterations_per_step = tr.steps_taken ? static_cast<double>(tr.total_iterations) / tr.steps_taken : 0.0;
        r.ok = tr.ok();
        out.warm_start.push_back(r);
      }
      if (options.progress) options.progress("warm/cold " + scene_name + " " + names[b]);
    }
  }

  // Work-precision: h = h_scene / 2^i; reference implicit Euler with lemke at h_min / kReferenceFactor.
  for (const auto& scene_name : options.precision_scenes) {
    const auto scene = LoadScene(scene_name);
    const SimulationSettings base = scene->defaults();
    const double h_min = base.h / std::pow(2.0, options.refinements - 1);
    SimulationSettings ref_settings = base;
    ref_settings.h = h_min / kReferenceFactor;
    ref_settings.stepper.record = true;
    const auto reference_solver = CreateSolver("lemke");
    const Trajectory ref = scene->Run(ref_settings, reference_solver.get());
    const auto error_of = [&](const Trajectory& tr) {
      const std::int64_t stride = std::llround(tr.h / ref.h);
      double e = 0.0;
      for (std::int64_t k = 0; k <= tr.steps_taken && k * stride <= ref.steps_taken; ++k) {
        e = std::max(e, (tr.x.col(k) - ref.x.col(k * stride)).cwiseAbs().maxCoeff());
      }
      return e;
    };
    for (int i = 0; i < options.refinements; ++i) {
      const double h = base.h / std::pow(2.0, i);
      for (std::size_t b = 0; b <= solvers.size(); ++b) {
        const bool is_explicit = b == solvers.size();
        SimulationSettings s = base;
        s.h = h;
        s.stepper.solver.polish = options.polish;
        Solver* solver = nullptr;
        if (is_explicit) {
          s.method = s.method == Method::kZoh ? Method::kZohExplicit : Method::kExplicit;
          if (s.method == Method::kExplicit) s.theta = 0.0;
        } else {
          solver = solvers[b].get();
        }
        s.stepper.record = true;
        std::optional<StepErrorObserver> step_errors;
        if (options.step_forward_error && !is_explicit) {
          s.stepper.observer = &step_errors.emplace(options.step_forward_error);
        }
        const Trajectory tr = scene->Run(s, solver);
        s.stepper.record = false;
        s.stepper.observer = nullptr;  // the timed runs are not observed
        Trajectory quiet;
        WorkPrecisionRecord r;
        r.scene = scene_name;
        r.method = is_explicit ? "explicit" : "implicit";
        r.solver = is_explicit ? "" : names[b];
        r.h = h;
        r.steps = tr.steps_taken;
        r.ok = tr.ok();
        r.error = error_of(tr);
        if (step_errors) {
          r.s_forward_error = step_errors->max_error();
          r.s_certified_steps = step_errors->steps();
        }
        r.seconds = TimeRuns([&] { scene->Run(s, solver, &quiet); }, options.min_seconds);
        out.work_precision.push_back(r);
      }
      if (options.progress) options.progress("work-precision " + scene_name + " h=" + std::to_string(h));
    }
  }
  return out;
}

}  // namespace smcbench
