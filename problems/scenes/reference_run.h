// The error of a scene's run in the units users read: the run against a reference run of the same settings stepped
// with certified solves. Here, beside the scenes, because `simulate`, Python's smcbench.simulate and the paper all
// report it.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "problems/scenes/scene.h"

namespace smcbench {

// The reference run takes the run's scene, h, method, θ, γ, parameters and x0, with the backend "reference"
// (solvers/reference/certify.h: each one-step box-MLCP solved and verified in extended precision, dense m ≤ 64). A
// nonlinear scene's reference run takes Algorithm 2 (newton-mlcp) with the run's Newton tolerance, whatever the
// run's algorithm (the reference backend solves box-MLCPs, not MCPs). It is a second run, several times slower per
// step than the fast backends (extended precision), so it is made only up to kMaxReferenceSteps steps.
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

}  // namespace smcbench
