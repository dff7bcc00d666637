// `smcbench simulate SCENE ...` and `smcbench scenes`: run a scene of SCENES.md (or a scene file) on any backend,
// write its trajectory CSV, JSON summary of sliding-surface accuracy metrics and a gnuplot figure.
#pragma once

#include <iosfwd>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "problems/scenes/scene.h"

namespace CLI {
class App;
}

namespace smcbench {

// The error of a run in the units users read (issue 12): the run against a reference run of the same scene, h,
// method, θ, γ, parameters and x0 stepped with certified solves, the backend "reference" (solvers/reference/
// certify.h: each one-step box-MLCP solved and verified in extended precision, dense m ≤ 64). A nonlinear scene's
// reference run takes Algorithm 2 (newton-mlcp) with the run's Newton tolerance, whatever the run's algorithm (the
// reference backend solves box-MLCPs, not MCPs), and the run's Newton tolerance. It costs a second run, far slower
// per step than the fast backends (measured: ≈ 3.5 µs a step on S1, m = 1; ≈ 16 µs on S6 zoh-mimo, m = 2, so a
// 1e5-step run adds ≈ 1.6 s), so it is made only up to kMaxReferenceSteps steps (about 16 s at m = 2).
inline constexpr std::int64_t kMaxReferenceSteps = 1'000'000;

struct ReferenceComparison {
  // s_error_max, y_error_max and the steps compared (metrics.h); nullopt when the reference run was skipped or
  // failed at its first step.
  std::optional<ReferenceErrors> errors;
  std::string skipped;             // why there are no errors (the summary's reference_skipped); empty otherwise
  bool ran = false;                // the reference run was made
  std::int64_t steps = 0;          // steps it took
  bool completed = false;          // it took every step without a failure
  std::string first_failure;       // its first failed step, as text, if any
  double wall_seconds = 0.0;       // its wall time, set-up included
};

// Runs the reference run for `run` (a recorded trajectory of scene with settings) and compares. Never throws for a
// valid run: an explicit method (no one-step problem: nothing to certify), more than kMaxReferenceSteps steps,
// m > 64, an unrecorded run or a reference run that fails at its first step give errors = nullopt and the reason.
ReferenceComparison CompareWithReferenceRun(const Scene& scene, const SimulationSettings& settings,
                                            const Trajectory& run);

// The JSON summary of a run (`--summary`). Stable keys; scripts rely on steps, x_final, reaching_step and:
//   s_error_max, y_error_max  max over steps k ≥ 1 of ‖s_k − s_ref,k‖∞ and ‖y_k − y_ref,k‖∞ against the reference
//                             run above (CompareWithReferenceRun); null when there is none, and then
//   reference_skipped         says why (a string; null when the errors are there);
//   reference                 {solver: "reference", steps, steps_compared, completed, first_failure, wall_seconds}
//                             of the reference run, or null when none was made.
// reference may be null (the keys are then null with reference_skipped "not computed"). The trajectory must be
// recorded unless metrics are not wanted (then only the always-kept fields are written).
//   reach_tol: a surface is "reached" from the first step after which |y_i| ≤ reach_tol at every later step.
nlohmann::json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                                 const Trajectory& trajectory, double reach_tol, double wall_seconds,
                                 const ReferenceComparison* reference = nullptr);

// Writes a PNG with gnuplot: states and s (and y) against time and, for n ≥ 2, the phase portrait (x1, x2).
// data_csv is a trajectory CSV (WriteTrajectoryCsv). Throws InvalidInputError if gnuplot is not on PATH
// ("--plot needs gnuplot (Debian package gnuplot-nox)") or fails.
void PlotTrajectory(const Trajectory& trajectory, const std::string& data_csv, const std::string& title,
                    const std::string& png_path);
// True if an executable named gnuplot is on PATH.
bool GnuplotAvailable();
// Runs a gnuplot script that writes png_path; InvalidInputError starting with what ("--plot: gnuplot failed to
// write 'x.png' (exit status 1): <its last error line>") if gnuplot is missing, fails or writes nothing.
void RunGnuplot(const std::string& script, const std::string& png_path, const std::string& what);
// The lines that select a PNG terminal (pngcairo when available) of this size writing png_path.
std::string GnuplotPngPreamble(int width, int height, const std::string& png_path);
// A gnuplot single-quoted string ('' for a quote); InvalidInputError if text holds a newline.
std::string GnuplotQuote(const std::string& text);

// The `simulate` subcommand: registers its options on construction; Run executes it if it was parsed.
class SimulateCommand {
 public:
  explicit SimulateCommand(CLI::App* app);
  ~SimulateCommand();
  bool parsed() const;
  // Exit status: 0 (even when a one-step problem fails: that is a result, reported in the summary and on err);
  // throws InvalidInputError for bad input (the caller prints it and exits 1).
  int Run(std::ostream& out, std::ostream& err) const;

  struct Flags;

 private:
  CLI::App* command_;
  std::unique_ptr<Flags> flags_;
};

// The `scenes` subcommand: lists the registered scenes with one-line descriptions.
class ScenesCommand {
 public:
  explicit ScenesCommand(CLI::App* app);
  bool parsed() const;
  int Run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_;
};

}  // namespace smcbench
