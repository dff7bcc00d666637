// The time-stepper dimensions of the benchmark report: warm against cold starts along each scene's trajectory
// (the same steps replayed in order, each solve started from the previous step's s or from Π(0)), and
// work-precision diagrams (run time against trajectory error, over a sweep of h, per method and backend).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace smcbench {

struct StepperStudyOptions {
  std::vector<std::string> solvers;  // empty: every registered backend
  std::vector<std::string> warm_scenes{"sign", "galias-yu-2007", "multi-surface", "filippov", "zoh-siso",
                                       "zoh-mimo", "lyapunov", "observer"};
  std::vector<std::string> precision_scenes{"sign",     "galias-yu-2007", "multi-surface", "filippov",
                                            "zoh-siso", "zoh-mimo",       "lyapunov",      "observer"};
  int refinements = 6;              // work-precision: h = h_scene / 2^i, i = 0..refinements-1
  double min_seconds = 0.02;        // each timing repeats the run until it lasts this long
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
  double error = 0.0;                 // max over the grid of ‖x_k − x_ref(t_k)‖∞
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
