// `smcbench simulate SCENE ...` and `smcbench scenes`: run a scene of SCENES.md (or a scene file) on any backend,
// write its trajectory CSV, JSON summary of sliding-surface accuracy metrics and a gnuplot figure.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "problems/scenes/scene.h"

namespace CLI {
class App;
}

namespace smcbench {

// The JSON summary of a run (`--summary`). Scripts rely on the keys steps, x_final and reaching_step. The
// trajectory must be recorded unless metrics are not wanted (then only the always-kept fields are written).
//   reach_tol: a surface is "reached" from the first step after which |y_i| ≤ reach_tol at every later step.
nlohmann::json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                                 const Trajectory& trajectory, double reach_tol, double wall_seconds);

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
