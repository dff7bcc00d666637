#include "tools/smcbench/simulate.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <system_error>

#include "problems/library/capture.h"
#include "problems/scenes/linear_scene.h"
#include "problems/scenes/nonlinear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/sampled_plant.h"
#include "solvers/core/duration_text.h"
#include "solvers/core/number_text.h"
#include "solvers/reference/certify.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The backend used when neither --solver nor the scene names one: "auto" (solvers/auto/auto_solver.h) picks per
// one-step problem the fastest backend that is exact or reliable for its class (enum on the paper's m ≤ 2
// problems), with lemke and newton behind it when a choice fails without a proof.
constexpr const char* kDefaultSolver = "auto";

std::string VectorText(const Vector& v) {
  std::string text = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) text += (i ? ", " : "") + NumberText(v[i]);
  return text + "]";
}

json VectorJson(const Vector& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// A double from the whole of text (no locale, no trailing characters); nullopt otherwise.
std::optional<double> ParseDouble(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size()) return std::nullopt;
  return value;
}

Vector ParseVector(const std::string& text, const char* option) {
  std::vector<double> values;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    const auto v = ParseDouble(item);
    if (!v) throw InvalidInputError(std::string(option) + ": '" + item + "' is not a number (expected v1,v2,...)");
    values.push_back(*v);
  }
  if (values.empty() || (!text.empty() && text.back() == ',')) {
    throw InvalidInputError(std::string(option) + ": expected comma-separated numbers v1,v2,..., got '" + text + "'");
  }
  return Eigen::Map<const Vector>(values.data(), static_cast<Eigen::Index>(values.size()));
}

std::string FormatSeconds(double seconds) { return DurationText(seconds); }

std::string FormatRate(double per_second) {
  char buffer[48];
  if (per_second >= 1e6) {
    std::snprintf(buffer, sizeof buffer, "%.1f M", per_second / 1e6);
  } else if (per_second >= 1e3) {
    std::snprintf(buffer, sizeof buffer, "%.1f k", per_second / 1e3);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.0f ", per_second);
  }
  return buffer;
}

// POSIX shell single-quoted word.
std::string ShellQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A fresh path in the temporary folder (the caller removes it).
fs::path TempPath(const std::string& stem, const std::string& extension) {
  static std::atomic<int> counter{0};
  return fs::temp_directory_path() /
         ("smcbench-" + stem + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + extension);
}

// Removes a file when it goes out of scope.
struct TempFile {
  fs::path path;
  ~TempFile() {
    std::error_code ec;
    if (!path.empty()) fs::remove(path, ec);
  }
};

bool IsZoh(Method m) { return m == Method::kZoh || m == Method::kZohExplicit; }
bool IsImplicit(Method m) { return m == Method::kImplicit || m == Method::kZoh; }

}  // namespace

// ------------------------------------------------------------------------------------------------------------
// Summary

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

json SimulationSummary(const Scene& scene, const SimulationSettings& settings, std::string_view solver,
                       const Trajectory& tr, double reach_tol, double wall_seconds,
                       const ReferenceComparison* reference) {
  RunMetrics metrics;
  metrics.metrics = ComputeMetrics(tr, reach_tol);
  if (tr.m > 0) metrics.chattering = ComputeChattering(tr, reach_tol);
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
  if (dynamic_cast<const NonlinearSceneAdapter*>(&scene)) {
    j["algorithm"] = std::string(ToString(settings.algorithm));
    j["newton_tolerance"] = settings.newton_tolerance;
    j["newton_max_iterations"] = settings.newton_max_iterations;
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

// ------------------------------------------------------------------------------------------------------------
// Plot

bool GnuplotAvailable() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream ss(path);
  for (std::string dir; std::getline(ss, dir, ':');) {
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return true;
  }
  return false;
}

TrajectoryPlotData::TrajectoryPlotData(int n, int m, std::int64_t rows_expected) : n_(n), m_(m) {
  if (n < 1 || m < 0) throw InvalidInputError("TrajectoryPlotData: n must be >= 1 and m >= 0");
  const std::int64_t rows = std::max<std::int64_t>(rows_expected, 1);
  rows_per_bucket_ = (rows + kPlotBuckets - 1) / kPlotBuckets;
  buckets_ = (rows + rows_per_bucket_ - 1) / rows_per_bucket_;
  series_.resize(static_cast<std::size_t>((n + 2 * m) * buckets_));
  if (n >= 2) phase_.resize(static_cast<std::size_t>(4 * buckets_));
  ends_.resize(static_cast<std::size_t>(2 * (n + 2 * m)), Extreme{0.0, -1, 0.0});
}

void TrajectoryPlotData::OnRows(const TrajectoryBlock& block) {
  if (block.n != n_ || block.m != m_) throw InvalidInputError("TrajectoryPlotData: a block of another size");
  const int series = n_ + 2 * m_;
  for (std::int64_t c = 0; c < block.rows; ++c) {
    const std::int64_t row = block.row(c);
    const double t = block.t[static_cast<std::size_t>(c)];
    const auto col = static_cast<Eigen::Index>(c);
    // Rows past rows_expected (none for a stepper run) join the last bucket.
    const std::int64_t b = std::min(row / rows_per_bucket_, buckets_ - 1);
    for (int i = 0; i < series; ++i) {
      const bool is_s = i >= n_ && i < n_ + m_;
      if (is_s && row == 0) continue;  // row 0 holds no step's s
      const double v = i < n_ ? block.x(i, col) : is_s ? block.s(i - n_, col) : block.y(i - n_ - m_, col);
      Extreme& first = ends_[static_cast<std::size_t>(2 * i)];
      if (first.row < 0) first = Extreme{v, row, t};
      ends_[static_cast<std::size_t>(2 * i + 1)] = Extreme{v, row, t};
      Bucket& bucket = series_[static_cast<std::size_t>(i * buckets_ + b)];
      const bool new_min = !bucket.used || v < bucket.min.value;
      const bool new_max = !bucket.used || v > bucket.max.value;
      if (new_min) bucket.min = Extreme{v, row, t};
      if (new_max) bucket.max = Extreme{v, row, t};
      bucket.used = true;
      if (n_ >= 2 && i < 2) {
        // The phase portrait: the true state at each new extreme of x1 (slots 0, 1) and of x2 (slots 2, 3).
        const PhasePoint point{row, t, block.x(0, col), block.x(1, col)};
        if (new_min) phase_[static_cast<std::size_t>(4 * b + 2 * i)] = point;
        if (new_max) phase_[static_cast<std::size_t>(4 * b + 2 * i + 1)] = point;
      }
    }
  }
}

void TrajectoryPlotData::WriteData(std::ostream& out) const {
  std::string line;
  const auto point = [&](double a, double b) {
    line.clear();
    AppendNumberText(&line, a);
    line.push_back(' ');
    AppendNumberText(&line, b);
    line.push_back('\n');
    out << line;
  };
  const int series = n_ + 2 * m_;
  for (int i = 0; i < series; ++i) {
    if (i > 0) out << "\n\n";
    const Extreme& first = ends_[static_cast<std::size_t>(2 * i)];
    const Extreme& last = ends_[static_cast<std::size_t>(2 * i + 1)];
    if (first.row < 0) continue;  // no row (s of a run without steps)
    std::int64_t written = first.row;
    point(first.t, first.value);
    for (std::int64_t b = 0; b < buckets_; ++b) {
      const Bucket& bucket = series_[static_cast<std::size_t>(i * buckets_ + b)];
      if (!bucket.used) continue;
      const Extreme& a = bucket.min.row <= bucket.max.row ? bucket.min : bucket.max;
      const Extreme& z = bucket.min.row <= bucket.max.row ? bucket.max : bucket.min;
      for (const Extreme* e : {&a, &z}) {
        if (e->row > written) point(e->t, e->value), written = e->row;
      }
    }
    if (last.row > written) point(last.t, last.value);
  }
  if (n_ >= 2) {
    out << "\n\n";
    const Extreme& x1 = ends_[0];
    const Extreme& x2 = ends_[2];
    if (x1.row < 0) return;
    point(x1.value, x2.value);  // x0 first: the plot marks it
    std::int64_t written = x1.row;
    for (std::int64_t b = 0; b < buckets_; ++b) {
      PhasePoint points[4];
      for (int k = 0; k < 4; ++k) points[k] = phase_[static_cast<std::size_t>(4 * b + k)];
      std::sort(points, points + 4, [](const PhasePoint& p, const PhasePoint& q) { return p.row < q.row; });
      for (const PhasePoint& p : points) {
        if (p.row > written) point(p.x1, p.x2), written = p.row;
      }
    }
    const Extreme& last1 = ends_[1];
    const Extreme& last2 = ends_[3];
    if (last1.row > written) point(last1.value, last2.value);
  }
}

void PlotTrajectory(const TrajectoryPlotData& plot_data, const std::string& title, const std::string& png_path) {
  if (!GnuplotAvailable()) {
    throw InvalidInputError("--plot needs gnuplot (Debian package gnuplot-nox), which is not on PATH");
  }
  // X.png: X.svg, X.dat and X.gp beside it (WriteGnuplotFigure, as the report's figures); another name: the PNG
  // alone, its data in a temporary file.
  const fs::path png(png_path);
  const bool beside = png.extension() == ".png";
  const std::string stem = png.stem().string();
  std::ostringstream data_text;
  plot_data.WriteData(data_text);
  std::optional<TempFile> temp;
  if (!beside) {
    temp.emplace();
    temp->path = TempPath("trajectory", ".dat");
    std::ofstream out(temp->path);
    out << data_text.str();
    out.flush();
    if (!out) throw InvalidInputError("--plot: cannot write the plot data " + temp->path.string());
  }
  const int n = plot_data.n(), m = plot_data.m();
  const std::string data = GnuplotQuote(beside ? stem + ".dat" : temp->path.string());
  const int height = n >= 2 ? 900 : 1000;
  std::ostringstream g;
  // Series i of the data is its gnuplot "index i" (blocks two blank lines apart): x1..xn, s1..sm, y1..ym, phase.
  g << "set grid\nset key top right\n"
    << "set multiplot layout " << (n >= 2 ? "2,2" : "3,1") << " title " << GnuplotQuote(title) << "\n"
    << "set xlabel 't'\n"
    << "set title 'state x'\n"
    << "plot for [i=0:" << n - 1 << "] " << data << " index i using 1:2 with lines lw 1.5 title sprintf('x%d', i+1)\n"
    // s_k (row k) acts on (t_{k-1}, t_k]: a step drawn vertically first (fsteps).
    << "set title 'multiplier s (s_k acts on (t_k-1, t_k])'\nset yrange [-1.1:1.1]\n"
    << "plot for [i=" << n << ":" << n + m - 1 << "] " << data
    << " index i using 1:2 with fsteps lw 1.5 title sprintf('s%d', i-" << n - 1 << ")\n"
    << "set autoscale y\n"
    << "set title 'sliding variable y = Cx + D'\n"
    << "plot for [i=" << n + m << ":" << n + 2 * m - 1 << "] " << data
    << " index i using 1:2 with lines lw 1.5 title sprintf('y%d', i-" << n + m - 1 << ")\n";
  if (n >= 2) {
    const int phase = n + 2 * m;
    g << "set title 'phase portrait'\nset xlabel 'x1'\nset ylabel 'x2'\n"
      << "plot " << data << " index " << phase << " using 1:2 with linespoints pt 7 ps 0.4 lw 1 title 'x_k', "
      << data << " index " << phase << " every ::0::0 using 1:2 with points pt 6 ps 2.5 lw 2 title 'x0'\n";
  }
  g << "unset multiplot\n";
  if (beside) {
    const std::string dir = png.has_parent_path() ? png.parent_path().string() : std::string(".");
    WriteGnuplotFigure(dir, stem, data_text.str(), g.str(), 1200, height, "simulate --plot");
    return;
  }
  RunGnuplot(GnuplotPngPreamble(1200, height, png_path) + g.str(), png_path, "--plot");
}

void PlotTrajectory(const Trajectory& tr, const std::string& data_csv, const std::string& title,
                    const std::string& png_path) {
  (void)data_csv;  // see the header: the data are decimated from the trajectory itself
  TrajectoryPlotData data(tr.n, tr.m, tr.steps_taken + 1);
  FeedRecorded(tr, &data);
  PlotTrajectory(data, title, png_path);
}

std::string GnuplotPngPreamble(int width, int height, const std::string& png_path) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  return "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo" + size +
         " noenhanced font ',10' } else { set terminal png" + size + " noenhanced }\nset output " +
         GnuplotQuote(png_path) + "\n";
}

std::string GnuplotQuote(const std::string& text) {
  if (text.find('\n') != std::string::npos) throw InvalidInputError("gnuplot: path contains a newline: " + text);
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

void WriteGnuplotFigure(const std::string& dir, const std::string& stem, const std::string& data,
                        const std::string& body, int width, int height, const std::string& made_by) {
  const fs::path folder(dir);
  const auto write = [&](const fs::path& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
    if (!out) throw InvalidInputError(made_by + ": cannot write '" + path.string() + "'");
  };
  write(folder / (stem + ".dat"), data);
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  std::ostringstream script;
  script << "# Made by `smcbench " << made_by << "`; remake " << stem << ".png and " << stem << ".svg with `gnuplot "
         << stem << ".gp` in this folder.\n# Data: " << stem << ".dat (one block per curve, in the order of the plot "
         << "command).\n"
         << GnuplotPngPreamble(width, height, stem + ".png") << body << "unset output\nset terminal svg size " << size
         << " dynamic noenhanced font 'sans,11'\nset output " << GnuplotQuote(stem + ".svg") << "\n"
         << body << "unset output\n";  // the body again, not replot: replot cannot redo a multiplot
  write(folder / (stem + ".gp"), script.str());
  RunGnuplot("cd " + GnuplotQuote(fs::absolute(folder).string()) + "\n" + script.str(),
             (folder / (stem + ".png")).string(), made_by);
  std::error_code ec;
  if (!fs::is_regular_file(folder / (stem + ".svg"), ec)) {
    throw InvalidInputError(made_by + ": gnuplot wrote no '" + (folder / (stem + ".svg")).string() + "'");
  }
}

void RunGnuplot(const std::string& script_text, const std::string& png_path, const std::string& what) {
  if (!GnuplotAvailable()) {
    throw InvalidInputError(what + " needs gnuplot (Debian package gnuplot-nox), which is not on PATH");
  }
  TempFile script{TempPath("plot", ".gp")};
  TempFile log{TempPath("plot", ".log")};
  {
    std::ofstream out(script.path);
    out << script_text;
    if (!out) throw InvalidInputError(what + ": cannot write the gnuplot script " + script.path.string());
  }
  const std::string command = "gnuplot " + ShellQuote(script.path.string()) + " 2> " + ShellQuote(log.path.string());
  const int rc = std::system(command.c_str());
  std::error_code ec;
  if (rc != 0 || !fs::is_regular_file(png_path, ec) || fs::file_size(png_path, ec) == 0) {
    std::ifstream in(log.path);
    std::string line, last;
    while (std::getline(in, line)) {
      if (!line.empty()) last = line;
    }
    throw InvalidInputError(what + ": gnuplot failed to write '" + png_path + "' (exit status " + std::to_string(rc) +
                            (last.empty() ? ")" : "): " + last));
  }
}

// ------------------------------------------------------------------------------------------------------------
// simulate

struct SimulateCommand::Flags {
  std::string scene, method, x0, solver, out, summary, plot, on_failure = "stop", algorithm, record;
  double h = 0.0, T = 0.0, theta = 0.0, gamma = 0.0, tol = 1e-10, reach_tol = 0.0, newton_tol = 0.0;
  int max_iter = 0, newton_max_iter = 0, plant_substeps = 1;
  bool no_warm_start = false, flush_subnormals = false, ieee_subnormals = false, no_polish = false;
  std::vector<std::string> params, sets;
  CLI::Option *method_opt = nullptr, *h_opt = nullptr, *T_opt = nullptr, *theta_opt = nullptr,
              *gamma_opt = nullptr, *x0_opt = nullptr, *reach_opt = nullptr, *solver_opt = nullptr,
              *algorithm_opt = nullptr, *newton_tol_opt = nullptr, *newton_max_iter_opt = nullptr,
              *plant_substeps_opt = nullptr;
};

SimulateCommand::SimulateCommand(CLI::App* app) : flags_(std::make_unique<Flags>()) {
  Flags& f = *flags_;
  command_ = app->add_subcommand("simulate", "run a scene of docs/scenes.md (see `smcbench scenes`) or a scene file");
  command_->add_option("SCENE", f.scene, "registered scene name or path to a scene JSON file")->required();
  f.method_opt = command_->add_option("--method", f.method,
                                      "implicit | explicit | zoh | zoh-explicit (default: the scene's); explicit "
                                      "without --theta/--gamma is the classical explicit Euler scheme (theta = "
                                      "gamma = 0)");
  f.h_opt = command_->add_option("--h", f.h, "time step (default: the scene's)");
  f.T_opt = command_->add_option("--T", f.T, "horizon; N = round(T/h) steps (default: the scene's)");
  f.x0_opt = command_->add_option("--x0", f.x0, "initial state v1,v2,... (default: the scene's)");
  f.theta_opt = command_->add_option("--theta", f.theta, "theta of the theta-method on f, in [0, 1]");
  f.gamma_opt = command_->add_option("--gamma", f.gamma, "gamma of the theta/gamma scheme, in [0, 1] (nonlinear g)");
  command_->add_option("--param", f.params, "scene parameter NAME=VALUE, e.g. --param tau=0.5 (repeatable)");
  f.solver_opt = command_->add_option("--solver", f.solver,
                                      std::string("backend for the one-step problems (default: the scene's, else ") +
                                          kDefaultSolver + ")");
  f.algorithm_opt = command_->add_option(
      "--algorithm", f.algorithm,
      "nonlinear scenes: newton-mlcp (Algorithm 2: outer Newton, each iteration a box-MLCP on any backend; "
      "default) | mcp (Algorithm 1: the step's MCP, backend newton)");
  f.newton_tol_opt = command_->add_option("--newton-tol", f.newton_tol,
                                          "nonlinear scenes: Newton stopping tolerance on the step's relative "
                                          "residual (default 1e-10)");
  f.newton_max_iter_opt = command_->add_option("--newton-max-iter", f.newton_max_iter,
                                               "nonlinear scenes: Newton iterations per step (default 50)");
  command_->add_option("--tol", f.tol, "tolerance on each step's relative natural residual (default 1e-10)");
  command_->add_option("--max-iter", f.max_iter, "backend iteration budget (0: its default)");
  command_->add_option("--set", f.sets, "typed backend option BACKEND.OPTION=VALUE (see `smcbench list`)");
  command_->add_option("--on-failure", f.on_failure, "stop | continue when a step's problem is not solved");
  command_->add_flag("--no-warm-start", f.no_warm_start, "cold-start every step instead of starting from s_k");
  command_->add_flag("--no-polish", f.no_polish,
                     "no exact polish of the backend's answers (SolverOptions::polish = false): the raw algorithm");
  command_->add_flag("--flush-subnormals", f.flush_subnormals,
                     "x86 flush-to-zero for the whole run, backend included, instead of the default (a state "
                     "component that underflows below 2.2e-308 after an implicit step is set to 0)");
  command_->add_flag("--ieee-subnormals", f.ieee_subnormals,
                     "plain IEEE arithmetic: keep subnormal states (a long run decaying to the origin then steps "
                     "2-18x slower; the default sets a state component below 2.2e-308 to 0)");
  f.reach_opt = command_->add_option("--reach-tol", f.reach_tol,
                                     "|y| bound defining 'on the surface' for the reaching step (default 10*tol)");
  command_->add_option("--out", f.out, "write the trajectory CSV t,x1..xn,s1..sm,y1..ym,iterations,residual (then u1..um, the "
                       "input applied over [t_k, t_k+1), for ZOH scenes and S1)");
  command_->add_option("--summary", f.summary,
                       "write the JSON summary (steps, x_final, reaching_step, s_error_max and y_error_max against a "
                       "certified reference run, ...)");
  command_->add_option("--plot", f.plot, "write a PNG (gnuplot): x, s, y against t and the phase portrait");
  f.plant_substeps_opt = command_->add_option(
      "--plant-substeps", f.plant_substeps,
      "methods zoh/zoh-explicit: S >= 1; --out and --plot also get the exact plant state at S-1 points between "
      "samples under the held input (default: the scene's plant_substeps, else 1; metrics stay on the samples)");
  command_->add_option("--record", f.record,
                       "write every one-step box-MLCP of the run (M, q, l, u, the z used, scene, method, h, theta, "
                       "step) to FILE, a problem set (problems/library/README.md; see `smcbench library FILE`)");
}

SimulateCommand::~SimulateCommand() = default;

bool SimulateCommand::parsed() const { return command_->parsed(); }

namespace {

using Flags = SimulateCommand::Flags;

// What one `simulate` run is: the scene, its defaults with the command line's overrides, and how errors read.
struct SimulatePlan {
  std::unique_ptr<Scene> scene;
  SimulationSettings settings;
  double reach_tol = 0.0;
  bool nonlinear = false;
  std::string prefix;  // "simulate NAME: " before every error

  [[noreturn]] void Fail(const std::string& what) const { throw InvalidInputError(prefix + what); }
};

// Phase 1: the scene, by name or file.
SimulatePlan LoadPlan(const Flags& f) {
  SimulatePlan plan;
  plan.scene = LoadScene(f.scene);
  plan.prefix = "simulate " + plan.scene->info().name + ": ";
  plan.settings = plan.scene->defaults();
  plan.nonlinear = dynamic_cast<const NonlinearSceneAdapter*>(plan.scene.get()) != nullptr;
  return plan;
}

// --param NAME=VALUE, each naming a parameter the scene declares.
void ApplyParameterOverrides(const Flags& f, SimulatePlan* plan) {
  const SceneParameters& declared = plan->scene->defaults().parameters;
  for (const std::string& p : f.params) {
    const auto eq = p.find('=');
    const auto value = eq == std::string::npos ? std::nullopt : ParseDouble(std::string_view(p).substr(eq + 1));
    if (!value) plan->Fail("--param expects NAME=VALUE with a number, got '" + p + "'");
    const std::string name = p.substr(0, eq);
    if (!declared.count(name)) {
      std::string known;
      for (const auto& [k, v] : declared) known += (known.empty() ? "" : ", ") + k;
      plan->Fail("--param: the scene has no parameter '" + name + "' (parameters: " + (known.empty() ? "none" : known) +
                 ")");
    }
    plan->settings.parameters[name] = *value;
  }
}

// The stepper's options: tolerance, budget, warm start, polish, subnormals, failure policy.
void ApplyStepperOverrides(const Flags& f, SimulatePlan* plan) {
  StepperOptions& stepper = plan->settings.stepper;
  stepper.solver.tolerance = f.tol;
  stepper.solver.max_iterations = f.max_iter;
  stepper.warm_start = !f.no_warm_start;
  stepper.solver.polish = !f.no_polish;
  if (f.flush_subnormals && f.ieee_subnormals) plan->Fail("--flush-subnormals and --ieee-subnormals exclude each other");
  stepper.subnormals = f.flush_subnormals   ? SubnormalPolicy::kFlushToZero
                       : f.ieee_subnormals ? SubnormalPolicy::kIeee
                                           : SubnormalPolicy::kZeroState;
  if (f.on_failure == "stop") {
    stepper.on_failure = FailurePolicy::kStop;
  } else if (f.on_failure == "continue") {
    stepper.on_failure = FailurePolicy::kContinue;
  } else {
    plan->Fail("--on-failure: expected stop or continue, got '" + f.on_failure + "'");
  }
  // Outputs are computed while the run goes (sinks): nothing is recorded.
  stepper.record = false;
}

// --plant-substeps overrides the scene file's plant_substeps; both apply to the ZOH methods only (an Euler method
// integrates the closed loop itself: there is no held input between samples).
void ApplyPlantSubsteps(const Flags& f, SimulatePlan* plan, std::ostream& err) {
  SimulationSettings& s = plan->settings;
  if (f.plant_substeps_opt->count()) {
    if (f.plant_substeps < 1) plan->Fail("--plant-substeps must be an integer >= 1, got " + std::to_string(f.plant_substeps));
    if (!IsZoh(s.method) && f.plant_substeps > 1) {
      plan->Fail("--plant-substeps " + std::to_string(f.plant_substeps) + " needs method zoh or zoh-explicit (the " +
                 "plant between a ZOH controller's samples); method '" + std::string(ToString(s.method)) +
                 "' integrates the closed loop");
    }
    s.plant_substeps = f.plant_substeps;
  } else if (!IsZoh(s.method) && s.plant_substeps > 1) {
    err << "note: the scene's plant_substeps applies to methods zoh and zoh-explicit only; method "
        << ToString(s.method) << " reports its samples\n";
    s.plant_substeps = 1;
  }
}

// Phase 2: every command-line override on the scene's defaults, then the settings validated.
void ApplyOverrides(const Flags& f, SimulatePlan* plan, std::ostream& err) {
  SimulationSettings& s = plan->settings;
  if (f.method_opt->count()) {
    const auto method = MethodFromString(f.method);
    if (!method) plan->Fail("--method: unknown method '" + f.method + "' (known: implicit, explicit, zoh, zoh-explicit)");
    s.method = *method;
    // "explicit" means the classical explicit Euler scheme unless a θ is asked for.
    if (s.method == Method::kExplicit && !f.theta_opt->count()) s.theta = 0.0;
    if (s.method == Method::kExplicit && !f.gamma_opt->count()) s.gamma = 0.0;
  }
  if (f.h_opt->count()) s.h = f.h;
  if (f.T_opt->count()) s.T = f.T;
  if (f.theta_opt->count()) s.theta = f.theta;
  if (f.gamma_opt->count()) s.gamma = f.gamma;
  if (f.x0_opt->count()) s.x0 = ParseVector(f.x0, "--x0");
  ApplyParameterOverrides(f, plan);
  if (f.algorithm_opt->count()) {
    const auto algorithm = NonlinearAlgorithmFromString(f.algorithm);
    if (!algorithm) plan->Fail("--algorithm: unknown algorithm '" + f.algorithm + "' (known: newton-mlcp, mcp)");
    s.algorithm = *algorithm;
  }
  if (f.newton_tol_opt->count()) s.newton_tolerance = f.newton_tol;
  if (f.newton_max_iter_opt->count()) s.newton_max_iterations = f.newton_max_iter;
  if (!plan->nonlinear && (f.algorithm_opt->count() || f.newton_tol_opt->count() || f.newton_max_iter_opt->count())) {
    err << "note: --algorithm, --newton-tol and --newton-max-iter apply to nonlinear scenes only; a linear scene "
           "solves one box-MLCP per step\n";
  }
  ApplyStepperOverrides(f, plan);
  ApplyPlantSubsteps(f, plan, err);
  plan->reach_tol = f.reach_opt->count() ? f.reach_tol : 10.0 * f.tol;
  if (!(plan->reach_tol >= 0.0) || !std::isfinite(plan->reach_tol)) plan->Fail("--reach-tol must be finite and >= 0");
  try {
    s.Validate(plan->scene->info().n);
  } catch (const InvalidInputError& e) {
    plan->Fail(e.what());
  }
  if (!plan->scene->Supports(s.method)) {
    plan->Fail("method '" + std::string(ToString(s.method)) +
               "' needs a ZOH plant (system type zoh); this scene runs implicit or explicit");
  }
  if (f.gamma_opt->count() && !plan->nonlinear) {
    err << "note: --gamma has no effect on a linear scene (g(x) = B is constant)\n";
  }
}

struct Backend {
  std::unique_ptr<Solver> solver;  // null for explicit methods (no one-step problem)
  std::string name;
};

// Phase 3: the backend, for implicit methods only, with its --set options.
Backend PickBackend(const Flags& f, const SimulatePlan& plan, std::ostream& err) {
  const SimulationSettings& s = plan.settings;
  Backend backend;
  if (!IsImplicit(s.method)) {
    if (f.solver_opt->count()) {
      err << "note: --solver is ignored: method " << ToString(s.method) << " solves no one-step problem\n";
    }
    return backend;
  }
  const bool mcp = plan.nonlinear && s.algorithm == NonlinearAlgorithm::kMcp;
  backend.name = f.solver_opt->count() ? f.solver : (!s.solver.empty() ? s.solver : mcp ? "newton" : kDefaultSolver);
  backend.solver = CreateSolver(backend.name);  // unknown name: error listing the known ones
  if (mcp && !backend.solver->info().mcp) {
    plan.Fail("--algorithm mcp needs a backend that solves nonlinear MCPs (newton); '" + backend.name +
              "' solves box-MLCPs only: use --algorithm newton-mlcp with it");
  }
  try {
    ApplyBackendSettings(f.sets, {backend.solver.get()});  // the one --set parser: solvers/registry/backend_settings.h
  } catch (const InvalidInputError& e) {
    plan.Fail(e.what());
  }
  return backend;
}

// Everything the run writes or measures besides its counters, each fed while the run goes (bounded memory whatever
// the number of steps). Built in place (the sinks point at the members): never moved.
struct SimulateOutputs {
  // --record: each one-step problem, streamed to the file.
  std::unique_ptr<ProblemSetWriter> record_writer;
  std::unique_ptr<ProblemRecorder> recorder;
  // The run's rows (the controller's samples) go to `sinks`; the CSV and the plot get them through `plant` (the
  // states between samples inserted) when plant_substeps > 1, else directly.
  TrajectorySinks sinks;
  TrajectorySinks trajectory;
  std::unique_ptr<SampledPlantSink> plant;
  std::unique_ptr<TrajectoryCsvWriter> csv;
  std::optional<TrajectoryPlotData> plot_data;
  std::optional<MetricsAccumulator> metrics;
  std::optional<ChatteringAccumulator> chattering;
  std::optional<ErrorsAccumulator> exact_errors;
  std::string exact_unavailable;
  std::unique_ptr<RunRowsForReference> run_rows;
  std::string no_run_rows;

  bool any() const { return csv || plot_data || metrics; }
};

// --record: the run hands each one-step problem to a recorder that streams it to the file.
void SetUpRecorder(const Flags& f, SimulatePlan* plan, const std::string& solver_name, SimulateOutputs* outputs) {
  if (f.record.empty()) return;
  SimulationSettings& s = plan->settings;
  if (!IsImplicit(s.method)) {
    plan->Fail("--record: method '" + std::string(ToString(s.method)) + "' solves no one-step problem: nothing to record");
  }
  if (plan->nonlinear && s.algorithm == NonlinearAlgorithm::kMcp) {
    plan->Fail("--record captures box-MLCPs, but --algorithm mcp solves each step as a nonlinear MCP; use --algorithm "
               "newton-mlcp (its inner problems are box-MLCPs)");
  }
  // The recorder's ids are distinct by construction: the writer need not remember them (constant memory).
  ProblemSetWriterOptions writer_options;
  writer_options.id_check = IdCheck::kGuaranteedByCaller;
  outputs->record_writer = std::make_unique<ProblemSetWriter>(
      f.record, "capture",
      "one-step problems of smcbench simulate " + plan->scene->info().name + " (" + std::string(ToString(s.method)) +
          ", h = " + NumberText(s.h) + ", backend " + solver_name + ")",
      writer_options);
  outputs->recorder = std::make_unique<ProblemRecorder>(MakeCaptureContext("capture", *plan->scene, s, solver_name),
                                                        outputs->record_writer.get());
  s.stepper.observer = outputs->recorder.get();
}

// The ZOH plant of a linear scene with the run's parameters (plant_substeps > 1 needs it).
ZohSmcSystem PlantOf(const SimulatePlan& plan) {
  const auto* linear = dynamic_cast<const LinearScene*>(plan.scene.get());
  if (linear == nullptr) plan.Fail("plant_substeps needs a linear scene of system type zoh");
  const LinearModel model = linear->Model(plan.settings.parameters);
  const auto* plant = std::get_if<ZohSmcSystem>(&model);
  if (plant == nullptr) plan.Fail("plant_substeps needs a system of type zoh (a ZOH-sampled plant)");
  return *plant;
}

// --out and --plot: the trajectory as users read it, the plant between samples included when asked for.
void SetUpTrajectoryOutputs(const Flags& f, const SimulatePlan& plan, std::int64_t num_steps, SimulateOutputs* o) {
  const SceneInfo& info = plan.scene->info();
  if (!f.out.empty()) {
    try {
      o->csv = std::make_unique<TrajectoryCsvWriter>(f.out);
    } catch (const InvalidInputError& e) {
      plan.Fail(std::string("--out: ") + e.what());
    }
    o->trajectory.Add(o->csv.get());
  }
  const int substeps = plan.settings.plant_substeps;
  if (!f.plot.empty()) {
    o->plot_data.emplace(info.n, info.m, num_steps * substeps + 1);
    o->trajectory.Add(&*o->plot_data);
  }
  if (o->trajectory.empty()) return;
  if (substeps > 1) {
    o->plant = std::make_unique<SampledPlantSink>(PlantOf(plan), plan.settings.h, substeps, &o->trajectory);
    o->sinks.Add(o->plant.get());
  } else {
    o->sinks.Add(&o->trajectory);
  }
}

// Phase 4: every output as a sink on the run's rows.
void SetUpOutputs(const Flags& f, SimulatePlan* plan, std::int64_t num_steps, SimulateOutputs* o) {
  const SceneInfo& info = plan->scene->info();
  const SimulationSettings& s = plan->settings;
  SetUpTrajectoryOutputs(f, *plan, num_steps, o);
  if (!f.out.empty() || !f.summary.empty() || !f.plot.empty()) {
    o->metrics.emplace(info.m, plan->reach_tol);
    o->sinks.Add(&*o->metrics);
    o->chattering.emplace(info.m, plan->reach_tol);
    o->sinks.Add(&*o->chattering);
  }
  if (!f.summary.empty()) {
    try {
      if (auto exact = plan->scene->Exact(s)) {
        o->exact_errors.emplace(info.n, info.m, s.h, std::move(*exact));
        o->sinks.Add(&*o->exact_errors);
      }
    } catch (const InvalidInputError& e) {
      o->exact_unavailable = e.what();
    }
    // With --summary: the run's error in s and y against a certified reference run (a second run, made only up
    // to kMaxReferenceSteps steps), compared against the run's rows kept in a temporary file.
    if (ReferenceRunSkipReason(s, info.m, num_steps).empty()) {
      try {
        o->run_rows = std::make_unique<RunRowsForReference>(info.m);
        o->sinks.Add(o->run_rows.get());
      } catch (const InvalidInputError& e) {
        o->no_run_rows = e.what();  // no temporary file: the summary says so instead of the errors
      }
    }
  }
  plan->settings.stepper.sink = o->sinks.empty() ? nullptr : &o->sinks;
}

// Phase 5: the run, timed (set-up included); no half-written CSV is left under --out when it throws.
double RunTimed(const Flags& f, const SimulatePlan& plan, const Backend& backend, SimulateOutputs* o, Trajectory* tr) {
  const auto start = std::chrono::steady_clock::now();
  try {
    plan.scene->Run(plan.settings, backend.solver.get(), tr);
  } catch (const InvalidInputError& e) {
    if (o->csv) {
      o->csv.reset();
      std::error_code ec;
      fs::remove(f.out, ec);
    }
    plan.Fail(e.what());
  }
  if (o->plant) o->plant->Finish();  // the run's last row, held back by the plant sink
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o->record_writer) o->record_writer->Close();
  if (o->csv) o->csv->Close();
  return wall;
}

// Phase 6: the summary and the figure.
std::optional<ReferenceComparison> WriteSummaryAndPlot(const Flags& f, const SimulatePlan& plan,
                                                       const std::string& solver_name, const Trajectory& tr,
                                                       double wall, SimulateOutputs* o) {
  std::optional<ReferenceComparison> reference;
  if (!f.summary.empty()) {
    reference = CompareWithReferenceRun(*plan.scene, plan.settings, tr, o->run_rows.get());
    if (!o->no_run_rows.empty()) reference->skipped = o->no_run_rows;
    RunMetrics run_metrics;
    run_metrics.metrics = o->metrics->Result(tr);
    if (o->exact_errors) run_metrics.exact_errors = o->exact_errors->Result();
    run_metrics.exact_unavailable = o->exact_unavailable;
    run_metrics.chattering = o->chattering->Result();
    const json summary =
        SimulationSummary(*plan.scene, plan.settings, solver_name, tr, run_metrics, plan.reach_tol, wall, &*reference);
    std::ofstream js(f.summary);
    js << summary.dump(2) << "\n";
    if (!js) plan.Fail("cannot write the summary '" + f.summary + "'");
  }
  if (o->plot_data) {
    std::string title = plan.scene->info().name + ": " + tr.description + ", h = " + NumberText(plan.settings.h);
    if (!solver_name.empty()) title += ", " + solver_name;
    PlotTrajectory(*o->plot_data, title, f.plot);
  }
  return reference;
}

// The surfaces and the input after reaching, from the metrics gathered during the run.
void ReportMetrics(const SimulateOutputs& o, double reach_tol, const Trajectory& tr, std::ostream& out) {
  const TrajectoryMetrics result = o.metrics->Result(tr);
  if (result.reaching_step >= 0) {
    double max_y = 0.0;
    std::int64_t changes = 0;
    for (const auto& sm : result.surfaces) {
      max_y = std::max(max_y, sm.max_abs_y_after);
      changes += sm.sign_changes_after;
    }
    out << "  surfaces reached at step " << result.reaching_step << " (t = " << NumberText(tr.time(result.reaching_step))
        << "): max |y| after " << NumberText(max_y) << ", sign changes of s after " << changes << "\n";
  } else {
    out << "  not every surface is reached (|y| <= " << NumberText(reach_tol) << " to the end)\n";
  }
  const ChatteringMetrics& c = o.chattering->Result();
  if (c.from_step >= 0) {
    out << "  from the reaching time t = " << NumberText(tr.time(c.from_step)) << ": sigma band "
        << NumberText(c.sigma_band);
    if (c.has_input) {
      out << ", input total variation " << NumberText(c.u_total_variation) << ", max jump "
          << NumberText(c.u_max_jump) << ", max |u| " << NumberText(c.u_max_abs);
    }
    out << ", sign changes of the switching part " << c.switching_sign_changes << "\n";
  }
}

// Phase 7: a short report on out (the files hold the details) and the first failure on err.
void Report(const Flags& f, const SimulatePlan& plan, const std::string& solver_name, const Trajectory& tr,
            double wall, const SimulateOutputs& o, const std::optional<ReferenceComparison>& reference,
            std::ostream& out, std::ostream& err) {
  const SimulationSettings& s = plan.settings;
  out << plan.scene->info().name << ": " << ToString(s.method) << " (" << tr.description
      << "), h = " << NumberText(s.h) << ", T = " << NumberText(s.T) << ", " << tr.steps_taken << " of "
      << tr.num_steps << " steps" << (solver_name.empty() ? "" : ", backend " + solver_name) << "\n";
  out << "  x_final = " << VectorText(tr.x_final) << ", s_final = " << VectorText(tr.s_final) << "\n";
  if (o.metrics) ReportMetrics(o, plan.reach_tol, tr, out);
  if (IsImplicit(s.method)) {
    out << "  max one-step residual " << NumberText(tr.max_residual) << ", " << tr.total_iterations
        << " backend iterations, " << tr.failed_steps << " failed steps\n";
  }
  if (o.plant) {
    out << "  plant between samples: " << o.plant->substeps() - 1 << " point(s) per interval in the trajectory ("
        << o.plant->RowsFor(tr.steps_taken) << " rows)\n";
  }
  // One cold run, set-up (discretization, factorization) included: `stepper_benchmark` measures the loop itself.
  out << "  wall " << FormatSeconds(wall) << " for set-up + " << tr.steps_taken << " steps ("
      << FormatRate(wall > 0 ? tr.steps_taken / wall : 0.0) << "steps/s" << (o.any() ? ", recording" : "") << ")\n";
  if (o.record_writer) {
    const std::uint64_t matrices = o.record_writer->matrices_written();
    out << "  recorded " << o.record_writer->problems_written() << " one-step problem(s), " << matrices
        << " distinct matri" << (matrices == 1 ? "x" : "ces") << ", to " << f.record << "\n";
  }
  if (reference) {
    if (reference->errors) {
      out << "  against the certified reference run (" << FormatSeconds(reference->wall_seconds)
          << "): max |s - s_ref| " << NumberText(reference->errors->s_error_max) << ", max |y - y_ref| "
          << NumberText(reference->errors->y_error_max) << " over " << reference->errors->steps_compared
          << " steps\n";
    } else {
      out << "  no reference run: " << reference->skipped << "\n";
    }
  }
  if (tr.first_failed_step >= 0) {
    err << "warning: step " << tr.first_failed_step << ": " << ToString(tr.first_failure_status) << " (residual "
        << NumberText(tr.first_failure_residual) << ")" << (tr.first_failure_message.empty() ? "" : ": ")
        << tr.first_failure_message << (tr.stopped_early ? "; the run stopped there" : "") << "\n";
  }
}

}  // namespace

// Named phases, top to bottom: load the scene, apply the overrides, pick the backend, set up the outputs, run,
// write the outputs, report.
int SimulateCommand::Run(std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  // Fail before simulating, not after.
  if (!f.plot.empty() && !GnuplotAvailable()) {
    throw InvalidInputError("--plot needs gnuplot (Debian package gnuplot-nox), which is not on PATH");
  }
  SimulatePlan plan = LoadPlan(f);
  ApplyOverrides(f, &plan, err);
  const Backend backend = PickBackend(f, plan, err);
  SimulateOutputs outputs;
  SetUpRecorder(f, &plan, backend.name, &outputs);
  const std::int64_t num_steps = NumSteps(plan.settings.T, plan.settings.h);
  SetUpOutputs(f, &plan, num_steps, &outputs);
  Trajectory tr;
  const double wall = RunTimed(f, plan, backend, &outputs, &tr);
  const std::optional<ReferenceComparison> reference =
      WriteSummaryAndPlot(f, plan, backend.name, tr, wall, &outputs);
  Report(f, plan, backend.name, tr, wall, outputs, reference, out, err);
  return 0;
}

// ------------------------------------------------------------------------------------------------------------
// scenes

ScenesCommand::ScenesCommand(CLI::App* app) {
  command_ = app->add_subcommand("scenes", "list the registered scenes (docs/scenes.md) with one-line descriptions");
}

bool ScenesCommand::parsed() const { return command_->parsed(); }

int ScenesCommand::Run(std::ostream& out, std::ostream& err) const {
  int status = 0;
  std::size_t width = 0;
  for (auto name : SceneNames()) width = std::max(width, name.size());
  for (auto name : SceneNames()) {
    out << name << std::string(width + 2 - name.size(), ' ');
    try {
      const auto scene = LoadScene(name);
      const SceneInfo& info = scene->info();
      const SimulationSettings& d = scene->defaults();
      out << info.description << "  [n=" << info.n << " m=" << info.m << "; " << ToString(d.method)
          << " h=" << NumberText(d.h) << " T=" << NumberText(d.T) << "]\n";
    } catch (const InvalidInputError& e) {
      out << "(cannot load)\n";
      err << "smcbench: scene " << name << ": " << e.what() << "\n";
      status = 1;
    }
  }
  return status;
}

}  // namespace smcbench
