// What a time-stepper run produces: the discrete trajectory (t_k, x_k, s_k, y_k) and, per step, what the
// backend reported; the streaming hook that hands the rows out while the run goes (TrajectorySink: outputs of
// long runs in constant memory); and the CSV writer (`t,x1..xn,s1..sm,y1..ym,iterations,residual`, then u1..um
// when the run has a control input), for a recorded trajectory or streamed.
#pragma once

#include <algorithm>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "solvers/core/status.h"
#include "solvers/core/types.h"

namespace smcbench {

// Row/column k (k = 0..steps_taken) holds t_k, x_k, the s_k that produced x_k (s_0 = 0: no step produced x_0)
// and y_k = C x_k + D. The per-step arrays describe the one-step problem that produced x_k; entry 0 is empty
// (0 iterations, residual 0, kNotRun), and so is every step of an explicit-sign scheme (no problem is solved).
struct Trajectory {
  int n = 0;
  int m = 0;
  double h = 0.0;
  double t0 = 0.0;
  std::string description;           // the discretization, e.g. "theta=1, implicit sign"
  std::int64_t num_steps = 0;        // N requested
  std::int64_t steps_taken = 0;      // steps done; < num_steps only if the run stopped on a failure

  // Full history, filled only when the run records (StepperOptions::record); else empty.
  bool recorded = false;
  std::vector<double> t;             // steps_taken + 1
  DenseMatrix x;                     // n × (steps_taken + 1)
  DenseMatrix s;                     // m × (steps_taken + 1)
  DenseMatrix y;                     // m × (steps_taken + 1)
  std::vector<int> iterations;       // backend iterations of the step producing x_k
  std::vector<double> residual;      // its relative natural residual (what options.tolerance judges)
  std::vector<SolveStatus> status;   // its status
  // The control input u_k applied over [t_k, t_{k+1}) (OneStepData::input_x/input_s), m × (steps_taken + 1) when
  // has_input and recorded; the last row's (no step applied it) is NaN.
  bool has_input = false;
  DenseMatrix u;

  // Always filled, recorded or not.
  Vector x_final, s_final, y_final;  // x_N, s_N, y_N (of the last step taken)
  double max_residual = 0.0;         // max relative natural residual over all solved one-step problems
  std::int64_t total_iterations = 0;
  int max_iterations = 0;
  // The step verdict (step_verdict.h), linear steppers with StepperOptions::refine_steps: the largest forward error
  // in x_{k+1} of a backend's answer against the exact step on its active set, and how many answers were off by more
  // than tol·(‖S‖∞ + ‖x_{k+1}‖∞) (the run continued from the exact step instead).
  double max_step_x_error = 0.0;
  std::int64_t refined_steps = 0;
  std::int64_t failed_steps = 0;     // steps whose one-step problem was not kSolved (or whose state overflowed)
  std::int64_t first_failed_step = -1;  // k of the first failed step (the step producing x_k), -1 if none
  SolveStatus first_failure_status = SolveStatus::kNotRun;
  double first_failure_residual = 0.0;
  std::string first_failure_message;
  bool stopped_early = false;        // true when the run stopped at first_failed_step

  bool ok() const { return failed_steps == 0 && steps_taken == num_steps; }
  // Prepares for a run of num_steps steps (every stepper's first act): sizes, h, t0, description, the counters and
  // the failure fields reset; with record, the history sized for num_steps + 1 rows (u too when has_input, all NaN:
  // the last row's stays NaN), else emptied. Reuses the storage: allocates only when a size grows.
  void Reset(int n_states, int m_surfaces, double step, double start_time, const std::string& what,
             std::int64_t steps, bool record, bool input);
  // After the run: steps_taken = taken, and the history trimmed to taken + 1 rows when the run stopped early.
  // The caller stores x_final, s_final, y_final and the counters.
  void Truncate(std::int64_t taken);
  // Writes recorded row k (storage already sized by the stepper). Templated so fixed-size kernels write their
  // fixed-size vectors without a conversion.
  template <typename X, typename S, typename Y>
  void SetRow(std::int64_t k, double t_k, const X& x_k, const S& s_k, const Y& y_k, int iterations_k,
              double residual_k, SolveStatus status_k) {
    const auto c = static_cast<Eigen::Index>(k);
    t[c] = t_k;
    x.col(c) = x_k;
    s.col(c) = s_k;
    y.col(c) = y_k;
    iterations[c] = iterations_k;
    residual[c] = residual_k;
    status[c] = status_k;
  }
  double time(std::int64_t k) const { return t0 + static_cast<double>(k) * h; }
};

// Rows first_row .. first_row + rows − 1 of a run, as a stepper hands them to a TrajectorySink: column j (j < rows)
// holds row first_row + j with the fields of Trajectory's history (t_k, x_k, s_k, y_k, and the iterations,
// residual and status of the step producing x_k; row 0: 0, 0, kNotRun). The storage may hold more columns than
// rows; only the first `rows` are meaningful.
struct TrajectoryBlock {
  int n = 0;
  int m = 0;
  std::int64_t first_row = 0;
  std::int64_t rows = 0;
  std::vector<double> t;
  DenseMatrix x, s, y;
  std::vector<int> iterations;
  std::vector<double> residual;
  std::vector<SolveStatus> status;  // the step's final status (a non-finite state: kNumericalFailure/kDiverged)
  // m × capacity when the run has a control input (row j: u applied from t_j on; NaN until the next step sets it,
  // and for the run's last row); 0 rows otherwise.
  DenseMatrix u;

  bool has_input() const { return u.rows() > 0; }
  std::int64_t row(std::int64_t j) const { return first_row + j; }
};

// Receives a run's rows while it goes (StepperOptions::sink): every row 0 .. steps_taken exactly once, in order,
// in blocks of bounded size, the last block before Run returns. Whatever a sink keeps is its own business; the
// stepper keeps one block. An exception thrown by OnRows propagates out of Run (the run stops there).
class TrajectorySink {
 public:
  virtual ~TrajectorySink() = default;
  virtual void OnRows(const TrajectoryBlock& block) = 0;
};

// Sends every block to each of several sinks, in order (not owned).
class TrajectorySinks final : public TrajectorySink {
 public:
  void Add(TrajectorySink* sink) {
    if (sink) sinks_.push_back(sink);
  }
  bool empty() const { return sinks_.empty(); }
  void OnRows(const TrajectoryBlock& block) override {
    for (TrajectorySink* sink : sinks_) sink->OnRows(block);
  }

 private:
  std::vector<TrajectorySink*> sinks_;
};

// Rows per streamed block: as many as fit in kTrajectoryBlockBytes, between 1 and kTrajectoryBlockMaxRows (a
// block is the only per-run buffer of a streamed run; 4096 rows amortize the sink's virtual call to nothing).
inline constexpr std::size_t kTrajectoryBlockBytes = std::size_t{1} << 18;
inline constexpr std::int64_t kTrajectoryBlockMaxRows = 4096;

// The steppers' side of a TrajectorySink: Add() writes row k into the block, which goes to the sink when it is full
// (at the next Add, so that the last row can still have its status corrected) and at Finish(). Sized once per
// run by Start(); Add() never allocates.
class TrajectoryStream {
 public:
  // sink may be null: then the stream is inactive and Add() must not be called. has_input: the rows carry u
  // (SetLastInput).
  void Start(int n, int m, TrajectorySink* sink, bool has_input = false) {
    sink_ = sink;
    if (!sink_) return;
    const std::size_t row_bytes = sizeof(double) * static_cast<std::size_t>(1 + n + (has_input ? 3 : 2) * m) + sizeof(int) +
                                  sizeof(double) + sizeof(SolveStatus);
    capacity_ = std::clamp<std::int64_t>(static_cast<std::int64_t>(kTrajectoryBlockBytes / row_bytes), 1,
                                         kTrajectoryBlockMaxRows);
    const auto c = static_cast<Eigen::Index>(capacity_);
    block_.n = n;
    block_.m = m;
    block_.first_row = 0;
    block_.rows = 0;
    block_.t.resize(capacity_);
    block_.x.resize(n, c);
    block_.s.resize(m, c);
    block_.y.resize(m, c);
    block_.iterations.resize(capacity_);
    block_.residual.resize(capacity_);
    block_.status.resize(capacity_);
    block_.u.resize(has_input ? m : 0, c);
  }
  bool active() const { return sink_ != nullptr; }

  // Plain loops over the first n / m entries (unrolled when they are compile-time constants): Eigen's fixed ↔
  // dynamic assignments are out-of-line calls.
  template <typename X, typename S, typename Y>
  void Add(std::int64_t k, double t_k, const X& x_k, const S& s_k, const Y& y_k, int iterations_k,
           double residual_k, SolveStatus status_k, int n, int m) {
    if (block_.rows == capacity_) Flush();
    const std::int64_t c = block_.rows;
    if (c == 0) block_.first_row = k;
    const auto col = static_cast<Eigen::Index>(c);
    block_.t[c] = t_k;
    double* x = block_.x.data() + col * n;
    for (int i = 0; i < n; ++i) x[i] = x_k[i];
    double* s = block_.s.data() + col * m;
    double* y = block_.y.data() + col * m;
    for (int i = 0; i < m; ++i) s[i] = s_k[i], y[i] = y_k[i];
    block_.iterations[c] = iterations_k;
    block_.residual[c] = residual_k;
    block_.status[c] = status_k;
    if (block_.u.rows() > 0) {
      double* u = block_.u.data() + col * m;
      for (int i = 0; i < m; ++i) u[i] = std::numeric_limits<double>::quiet_NaN();
    }
    block_.rows = c + 1;
  }
  // The input applied from the row added last on (known one step later; the block is handed out only at the next
  // Add, so the row is still here).
  template <typename U>
  void SetLastInput(const U& u_k, int m) {
    if (block_.rows == 0 || block_.u.rows() == 0) return;
    double* u = block_.u.data() + static_cast<Eigen::Index>(block_.rows - 1) * m;
    for (int i = 0; i < m; ++i) u[i] = u_k[i];
  }
  // The status of the row added last (a failed step's final status).
  void SetLastStatus(SolveStatus status) {
    if (block_.rows > 0) block_.status[block_.rows - 1] = status;
  }
  // Hands the buffered rows to the sink (the end of a run; Add() does it when the block is full).
  void Flush() {
    if (!sink_ || block_.rows == 0) return;
    sink_->OnRows(block_);
    block_.rows = 0;
  }

 private:
  TrajectorySink* sink_ = nullptr;
  std::int64_t capacity_ = 0;
  TrajectoryBlock block_;
};

// Hands a recorded trajectory's rows to a sink in blocks of at most block_rows rows (a recorded run seen by the
// streaming consumers: plots and tests). InvalidInputError if the trajectory was not recorded or block_rows < 1.
void FeedRecorded(const Trajectory& trajectory, TrajectorySink* sink,
                  std::int64_t block_rows = kTrajectoryBlockMaxRows);

// Header `t,x1..xn,s1..sm,y1..ym,iterations,residual` (then `,u1..um` when the run has a control input; the last
// row's u is `nan`: no step applied it), then one row per recorded step, numbers in shortest
// round-trip form. Throws InvalidInputError if the trajectory was not recorded or the stream fails.
void WriteTrajectoryCsv(const Trajectory& trajectory, std::ostream& out);
void WriteTrajectoryCsvFile(const Trajectory& trajectory, const std::string& path);

// The same CSV written while the run goes (a TrajectorySink): the header at the first block, then each block's
// rows through a bounded text buffer. Byte for byte what WriteTrajectoryCsv writes for the recorded run.
// InvalidInputError if the file cannot be opened (constructor) or a write fails (OnRows, Close).
class TrajectoryCsvWriter final : public TrajectorySink {
 public:
  explicit TrajectoryCsvWriter(const std::string& path);
  // Writes into out (not owned; it must outlive the writer); name names it in errors.
  TrajectoryCsvWriter(std::ostream* out, std::string name);
  ~TrajectoryCsvWriter() override;
  void OnRows(const TrajectoryBlock& block) override;
  // Flushes what is buffered and checks the stream.
  void Close();
  std::int64_t rows_written() const { return rows_; }

 private:
  void Drain();
  std::unique_ptr<std::ofstream> file_;
  std::ostream* out_;
  std::string name_;
  std::string buffer_;
  bool header_written_ = false;
  std::int64_t rows_ = 0;
};

}  // namespace smcbench
