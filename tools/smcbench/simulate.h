// `smcbench simulate SCENE ...` and `smcbench scenes`: run a scene of docs/scenes.md (or a scene file) on any backend,
// write its trajectory CSV, JSON summary of sliding-surface accuracy metrics and a gnuplot figure. Every output is
// produced while the run goes (issue 13): memory does not grow with the number of steps.
#pragma once

#include <cstdint>
#include <cstdio>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

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

// Why no reference run is made for a run of num_steps steps with m surfaces and these settings (the summary's
// reference_skipped); empty when one will be made.
std::string ReferenceRunSkipReason(const SimulationSettings& settings, int m, std::int64_t num_steps);

// A streamed run's s and y rows, kept for the comparison with its reference run after the run: a TrajectorySink
// on the run that writes 2m doubles a row to an anonymous temporary file (the run's memory stays constant; at most
// kMaxReferenceSteps rows, 16·m MB). CompareWithReferenceRun(scene, settings, run, &rows) then streams the
// reference run against the file. InvalidInputError if no temporary file can be made.
class RunRowsForReference final : public TrajectorySink {
 public:
  explicit RunRowsForReference(int m);
  ~RunRowsForReference() override;
  RunRowsForReference(const RunRowsForReference&) = delete;
  RunRowsForReference& operator=(const RunRowsForReference&) = delete;
  void OnRows(const TrajectoryBlock& block) override;

  // Reading back, from row 0: the next row's s and y (m entries each); false after the last row written.
  void Rewind();
  bool Next(const double** s, const double** y);
  int m() const { return m_; }

 private:
  int m_;
  std::FILE* file_ = nullptr;
  std::vector<double> buffer_;      // rows being written or read
  std::size_t buffered_rows_ = 0;   // rows in buffer_ (reading)
  std::size_t next_row_ = 0;        // next row of buffer_ to hand out (reading)
  std::int64_t rows_written_ = 0, rows_read_ = 0;
};

// The same comparison for a streamed run (unrecorded; its counters and steps_taken) whose rows went to *rows (null:
// skipped, "the run's rows were not kept").
ReferenceComparison CompareWithReferenceRun(const Scene& scene, const SimulationSettings& settings,
                                            const Trajectory& run, RunRowsForReference* rows);

// The JSON summary of a run (`--summary`). Stable keys; scripts rely on steps, x_final, reaching_step and:
//   s_error_max, y_error_max  max over steps k ≥ 1 of ‖s_k − s_ref,k‖∞ and ‖y_k − y_ref,k‖∞ against the reference
//                             run above (CompareWithReferenceRun); null when there is none, and then
//   reference_skipped         says why (a string; null when the errors are there);
//   reference                 {solver: "reference", steps, steps_compared, completed, first_failure, wall_seconds}
//                             of the reference run, or null when none was made.
// reference may be null (the keys are then null with reference_skipped "not computed"). This overload computes the
// metrics from the history (ComputeMetrics, ComputeErrors: InvalidInputError if the trajectory was not recorded);
// `simulate` itself uses the one below with metrics accumulated while the run went (the same numbers).
//   reach_tol: a surface is "reached" from the first step after which |y_i| ≤ reach_tol at every later step.
//   chattering                issue 15 (docs/smc.md): the input and its chattering once the surfaces are reached
//                             (metrics.h ChatteringMetrics, the reaching time forwards: σ_i within reach_tol or
//                             crossed 0): {has_input, from_step, from_time, sigma_band, u_total_variation,
//                             u_max_jump, u_max_abs, switching_sign_changes, rows}; the u keys are null when the run
//                             has no control input (class-(2) scenes without control_input, Euler runs of ZOH plants),
//                             from_time null and the after-reaching keys 0 when a surface is never reached.
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
};
// The summary's "chattering" object (null for nullopt); h and t0 give from_time.
nlohmann::json ChatteringJson(const std::optional<ChatteringMetrics>& chattering, double t0, double h);
// The summary from metrics computed elsewhere; run gives the counters, finals and sizes (it need not be recorded).
nlohmann::json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                                 const Trajectory& run, const RunMetrics& metrics, double reach_tol,
                                 double wall_seconds, const ReferenceComparison* reference);

// What `--plot` draws, kept in memory independent of the run's length: rows_expected rows (N + 1) are cut into at
// most kPlotBuckets consecutive buckets, and per bucket each series (x_i, s_i, y_i) keeps its minimum and maximum
// with their times, so a spike or chattering of a single step stays visible (a band between the extremes) where
// taking every k-th row would hide it. The phase portrait keeps, per bucket, the states (x1, x2) at the extremes
// of x1 and of x2 (true points of the trajectory), plus x0. A run of at most kPlotBuckets rows keeps every row.
inline constexpr std::int64_t kPlotBuckets = 2048;
class TrajectoryPlotData final : public TrajectorySink {
 public:
  TrajectoryPlotData(int n, int m, std::int64_t rows_expected);
  void OnRows(const TrajectoryBlock& block) override;
  // gnuplot data: one block (two blank lines apart) per series x1..xn, s1..sm, y1..ym of "t value" lines in time
  // order, then, for n ≥ 2, the phase block "x1 x2" starting at x0.
  void WriteData(std::ostream& out) const;
  // Points written per series at most (2 per bucket).
  std::int64_t max_points_per_series() const { return 2 * kPlotBuckets; }
  int n() const { return n_; }
  int m() const { return m_; }

 private:
  struct Extreme {
    double value;
    std::int64_t row;
    double t;
  };
  struct Bucket {
    bool used = false;
    Extreme min, max;
  };
  struct PhasePoint {
    std::int64_t row = -1;
    double t = 0.0, x1 = 0.0, x2 = 0.0;
  };
  int n_, m_;
  std::int64_t rows_per_bucket_;
  std::int64_t buckets_;
  std::vector<Bucket> series_;       // (n + 2m) × buckets_, series-major
  std::vector<PhasePoint> phase_;    // 4 × buckets_: at min x1, max x1, min x2, max x2
  std::vector<Extreme> ends_;        // per series: its first and last row (row −1: none yet)
};

// Writes a PNG with gnuplot from the decimated data: states, s and y against time and, for n ≥ 2, the phase
// portrait (x1, x2). Throws InvalidInputError if gnuplot is not on PATH ("--plot needs gnuplot (Debian package
// gnuplot-nox)") or fails.
void PlotTrajectory(const TrajectoryPlotData& data, const std::string& title, const std::string& png_path);
// The same for a recorded trajectory (its rows go through TrajectoryPlotData). data_csv is not read (the data are
// decimated from the trajectory); it is kept for callers written before issue 13.
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
// A figure a user can restyle: dir/STEM.dat (data), dir/STEM.gp (the gnuplot script: reads STEM.dat, writes STEM.png
// and STEM.svg; `cd DIR && gnuplot STEM.gp` remakes both), then runs it. body: the settings and the plot command,
// naming the data file 'STEM.dat'. made_by names the command in the script's first line and in errors
// ("smc-sweep: gnuplot wrote no 'x.svg'"). The one figure writer of the commands (`report` has the same layout).
void WriteGnuplotFigure(const std::string& dir, const std::string& stem, const std::string& data,
                        const std::string& body, int width, int height, const std::string& made_by);

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
