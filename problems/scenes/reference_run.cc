#include "problems/scenes/reference_run.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <system_error>

#include "problems/scenes/scene.h"
#include "solvers/reference/certify.h"

namespace smcbench {

namespace {

constexpr int kMaxReferenceSize = 64;  // ReferenceSolver: dense problems up to 64 rows

// The reference run's settings (CompareWithReferenceRun): the run's, stepped with certified solves.
SimulationSettings ReferenceSettings(const SimulationSettings& settings) {
  SimulationSettings reference_settings = settings;
  reference_settings.stepper.observer = nullptr;  // never into the run's --record file
  reference_settings.stepper.sink = nullptr;      // nor into its outputs
  reference_settings.stepper.on_failure = FailurePolicy::kStop;
  // The certified z* is the answer whatever the tolerance; 1e-10 (the default) only decides "solved", and the
  // polish, which would trade z* for the double-precision solve of the same active set, is off.
  reference_settings.stepper.solver = SolverOptions{};
  reference_settings.stepper.solver.polish = false;
  reference_settings.algorithm = NonlinearAlgorithm::kNewtonMlcp;
  return reference_settings;
}

// What the reference run gives besides the errors: its steps, completion, first failure and wall time.
void DescribeReferenceRun(const Trajectory& ref, double wall_seconds, ReferenceComparison* out) {
  out->wall_seconds = wall_seconds;
  out->ran = true;
  out->steps = ref.steps_taken;
  out->completed = ref.ok();
  if (ref.first_failed_step >= 0) {
    out->first_failure = "step " + std::to_string(ref.first_failed_step) + ": " +
                         std::string(ToString(ref.first_failure_status)) +
                         (ref.first_failure_message.empty() ? "" : ": " + ref.first_failure_message);
  }
}

// The errors, or why there are none: a reference run that fails at its first step compares nothing.
void SetReferenceErrors(const ReferenceErrors& errors, const Trajectory& run, ReferenceComparison* out) {
  if (errors.steps_compared == 0 && run.steps_taken > 0) {
    out->skipped = "the reference run failed at step 1 (" + out->first_failure + ")";
  } else {
    out->errors = errors;
  }
}

// The reference backend certifies box-MLCPs: a scene whose steps are none has no reference run.
std::string SceneSkipReason(const Scene& scene) {
  if (scene.step_kind() == SceneStepKind::kSuperTwisting) {
    return "a super-twisting step is a scalar generalized equation (closed form or MCP), not a box-MLCP the "
           "reference backend certifies";
  }
  return "";
}

}  // namespace

std::string ReferenceRunSkipReason(const SimulationSettings& settings, int m, std::int64_t num_steps) {
  if (!IsImplicit(settings.method)) {
    return "method " + std::string(ToString(settings.method)) +
           " solves no one-step problem: there is nothing to certify";
  }
  if (num_steps > kMaxReferenceSteps) {
    return std::to_string(num_steps) + " steps > " + std::to_string(kMaxReferenceSteps) +
           ": the reference run (certified solves) is made only up to that many steps";
  }
  if (m > kMaxReferenceSize) {
    return "m = " + std::to_string(m) + " > " + std::to_string(kMaxReferenceSize) +
           ": the reference backend certifies dense problems up to that size";
  }
  return "";
}

ReferenceComparison CompareWithReferenceRun(const Scene& scene, const SimulationSettings& settings,
                                            const Trajectory& run) {
  ReferenceComparison out;
  if (IsImplicit(settings.method) && !run.recorded) {
    out.skipped = "the run was not recorded";
  } else {
    out.skipped = ReferenceRunSkipReason(settings, run.m, run.num_steps);
  }
  if (out.skipped.empty()) out.skipped = SceneSkipReason(scene);
  if (!out.skipped.empty()) return out;

  SimulationSettings reference_settings = ReferenceSettings(settings);
  reference_settings.stepper.record = true;
  ReferenceSolver reference;
  Trajectory ref;
  const auto start = std::chrono::steady_clock::now();
  scene.Run(reference_settings, &reference, &ref);
  DescribeReferenceRun(ref, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), &out);
  SetReferenceErrors(CompareWithReference(run, ref), run, &out);
  return out;
}

// ------------------------------------------------------------------------------------------------------------
// The streamed comparison: the run's s and y in a temporary file, the reference run compared row by row.

namespace {

// Rows read back per chunk.
constexpr std::size_t kSpillChunkRows = 4096;

std::string ErrnoText() { return std::generic_category().message(errno); }

// The reference run's sink: reference row k against the run's row k, for k = 1 up to the last row of the run and
// before the reference's first failed step (the rows CompareWithReference compares).
class ReferenceRowComparer final : public TrajectorySink {
 public:
  explicit ReferenceRowComparer(RunRowsForReference* run_rows) : run_rows_(run_rows) {}
  void OnRows(const TrajectoryBlock& block) override {
    const int m = block.m;
    for (std::int64_t c = 0; c < block.rows && !done_; ++c) {
      const double *s = nullptr, *y = nullptr;
      if (!run_rows_->Next(&s, &y)) {
        done_ = true;  // past the run's last row
        break;
      }
      if (block.row(c) == 0) continue;  // the shared initial state
      if (block.status[static_cast<std::size_t>(c)] != SolveStatus::kSolved) {
        done_ = true;  // the reference is trusted up to its first failed step only
        break;
      }
      const auto col = static_cast<Eigen::Index>(c);
      errors_.Add(s, y, block.s.data() + col * m, block.y.data() + col * m, m);
    }
  }
  const ReferenceErrors& errors() const { return errors_.errors(); }

 private:
  RunRowsForReference* run_rows_;
  ReferenceErrorsAccumulator errors_;
  bool done_ = false;
};

}  // namespace

RunRowsForReference::RunRowsForReference(int m) : m_(m) {
  file_ = std::tmpfile();
  if (!file_) {
    throw InvalidInputError("--summary: cannot create a temporary file for the run's s and y (the comparison with "
                            "the reference run): " + ErrnoText());
  }
}

RunRowsForReference::~RunRowsForReference() {
  if (file_) std::fclose(file_);
}

void RunRowsForReference::OnRows(const TrajectoryBlock& block) {
  const auto m = static_cast<std::size_t>(m_);
  const auto rows = static_cast<std::size_t>(block.rows);
  buffer_.resize(rows * 2 * m);
  for (std::size_t c = 0; c < rows; ++c) {
    const auto col = static_cast<Eigen::Index>(c);
    for (std::size_t i = 0; i < m; ++i) {
      buffer_[c * 2 * m + i] = block.s(static_cast<Eigen::Index>(i), col);
      buffer_[c * 2 * m + m + i] = block.y(static_cast<Eigen::Index>(i), col);
    }
  }
  if (!buffer_.empty() && std::fwrite(buffer_.data(), sizeof(double), buffer_.size(), file_) != buffer_.size()) {
    throw InvalidInputError("--summary: writing the run's s and y to a temporary file failed: " + ErrnoText());
  }
  rows_written_ += block.rows;
}

void RunRowsForReference::Rewind() {
  std::fflush(file_);
  std::rewind(file_);
  buffered_rows_ = next_row_ = 0;
  rows_read_ = 0;
}

bool RunRowsForReference::Next(const double** s, const double** y) {
  const auto m = static_cast<std::size_t>(m_);
  if (next_row_ == buffered_rows_) {
    if (rows_read_ == rows_written_) return false;
    const auto rows = static_cast<std::size_t>(
        std::min<std::int64_t>(static_cast<std::int64_t>(kSpillChunkRows), rows_written_ - rows_read_));
    buffer_.resize(rows * 2 * m);
    if (!buffer_.empty() && std::fread(buffer_.data(), sizeof(double), buffer_.size(), file_) != buffer_.size()) {
      throw InvalidInputError("--summary: reading the run's s and y back from a temporary file failed");
    }
    buffered_rows_ = rows;
    next_row_ = 0;
    rows_read_ += static_cast<std::int64_t>(rows);
  }
  *s = buffer_.data() + next_row_ * 2 * m;
  *y = *s + m;
  ++next_row_;
  return true;
}

ReferenceComparison CompareWithReferenceRun(const Scene& scene, const SimulationSettings& settings,
                                            const Trajectory& run, RunRowsForReference* rows) {
  ReferenceComparison out;
  out.skipped = ReferenceRunSkipReason(settings, run.m, run.num_steps);
  if (out.skipped.empty()) out.skipped = SceneSkipReason(scene);
  if (out.skipped.empty() && rows == nullptr) out.skipped = "the run's rows were not kept";
  if (!out.skipped.empty()) return out;

  rows->Rewind();
  ReferenceRowComparer comparer(rows);
  SimulationSettings reference_settings = ReferenceSettings(settings);
  reference_settings.stepper.record = false;
  reference_settings.stepper.sink = &comparer;
  ReferenceSolver reference;
  Trajectory ref;
  const auto start = std::chrono::steady_clock::now();
  scene.Run(reference_settings, &reference, &ref);
  DescribeReferenceRun(ref, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), &out);
  SetReferenceErrors(comparer.errors(), run, &out);
  return out;
}

}  // namespace smcbench
