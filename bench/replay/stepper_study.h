// The time-stepper dimensions of the benchmark report: warm against cold starts along each scene's trajectory
// (the same steps replayed in order, each solve started from the previous step's s or from Π(0)), and
// work-precision diagrams over a sweep of h, per method and backend: run time against the trajectory error of x
// (against a finer reference run) and against the per-step forward error of s (each step's answer against the
// certified solution of that step's own one-step problem).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {

// ‖z − z*‖∞ for the certified solution z* of problem when it is proven unique, else NaN. The caller supplies it
// (bench: Certify, solvers/reference/certify.h), so the replay library does not link the extended-precision
// certifier.
using StepForwardError = std::function<double(const BoxMLCP& problem, const Vector& z)>;

struct StepperStudyOptions {
  std::vector<std::string> solvers;  // empty: every registered backend
  std::vector<std::string> warm_scenes{"sign", "galias-yu-2007", "multi-surface", "filippov", "zoh-siso",
                                       "zoh-mimo", "lyapunov", "observer"};
  std::vector<std::string> precision_scenes{"sign",     "galias-yu-2007", "multi-surface", "filippov",
                                            "zoh-siso", "zoh-mimo",       "lyapunov",      "observer"};
  int refinements = 6;              // work-precision: h = h_scene / 2^i, i = 0..refinements-1
  double min_seconds = 0.02;        // each timing repeats the run until it lasts this long
  bool polish = true;               // SolverOptions::polish of the studied runs (the reference run keeps it on)
  // Work-precision: when set, every solved step of the (untimed) recorded run of an implicit method is certified
  // and WorkPrecisionRecord::s_forward_error is the largest ‖s_k − s*_k‖∞. Null: not measured (NaN).
  StepForwardError step_forward_error;
  std::function<void(const std::string& what)> progress;
};

struct WarmStartRecord {
  std::string scene, solver, mode;  // mode: "warm" or "cold"
  std::int64_t steps = 0;
  double seconds_per_step = 0.0;
  double iterations_per_step = 0.0;
  bool ok = false;                  // every step solved
};

struct WorkPrecisionRecord {
  std::string scene, method, solver;  // method "implicit" or "explicit" (solver empty for explicit)
  double h = 0.0;
  std::int64_t steps = 0;
  double seconds = 0.0;               // one run, set-up included (median of repeats)
  // Trajectory error: max over the grid of ‖x_k − x_ref(t_k)‖∞, x_ref a reference run of the same scene with
  // implicit Euler (lemke) at the smallest h / StepperStudy::reference_h_factor (discretization error mostly).
  double error = 0.0;
  // Per-step forward error of the solves: max over the steps k the backend solved of ‖s_k − s*_k‖∞, s*_k the
  // certified unique solution of step k's own one-step problem (solver error only, no discretization error); NaN
  // when not measured, explicit, or no step's solution was proven unique. s_certified_steps: the steps it is
  // taken over.
  double s_forward_error = kNaN;
  std::int64_t s_certified_steps = 0;
  bool ok = false;
};

struct StepperStudy {
  std::vector<WarmStartRecord> warm_start;
  std::vector<WorkPrecisionRecord> work_precision;
  double reference_h_factor = 0.0;  // reference step = smallest h / this
};

// Throws InvalidInputError for an unknown backend or scene.
StepperStudy RunStepperStudy(const StepperStudyOptions& options);

}  // namespace smcbench
