#include "problems/stepper/trajectory.h"

#include <charconv>
#include <fstream>
#include <limits>
#include <ostream>

#include "solvers/core/number_text.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

// Appends value in shortest round-trip form (no locale, no allocation).
void Append(double value, std::string* line) { AppendNumberText(line, value); }

void Append(long long value, std::string* line) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  line->append(buffer, result.ptr);
}

std::string CsvHeader(int n, int m, bool has_input) {
  std::string line = "t";
  for (int i = 1; i <= n; ++i) line += ",x" + std::to_string(i);
  for (int i = 1; i <= m; ++i) line += ",s" + std::to_string(i);
  for (int i = 1; i <= m; ++i) line += ",y" + std::to_string(i);
  line += ",iterations,residual";
  // After the original columns, so that readers by position keep working.
  for (int i = 1; has_input && i <= m; ++i) line += ",u" + std::to_string(i);
  line += "\n";
  return line;
}

// One CSV row from column c of the history matrices (a recorded trajectory or a streamed block).
void AppendCsvRow(double t, const DenseMatrix& x, const DenseMatrix& s, const DenseMatrix& y, const DenseMatrix& u,
                  Eigen::Index c, int iterations, double residual, std::string* line) {
  Append(t, line);
  for (Eigen::Index i = 0; i < x.rows(); ++i) line->push_back(','), Append(x(i, c), line);
  for (Eigen::Index i = 0; i < s.rows(); ++i) line->push_back(','), Append(s(i, c), line);
  for (Eigen::Index i = 0; i < y.rows(); ++i) line->push_back(','), Append(y(i, c), line);
  line->push_back(',');
  Append(static_cast<long long>(iterations), line);
  line->push_back(',');
  Append(residual, line);
  for (Eigen::Index i = 0; i < u.rows(); ++i) line->push_back(','), Append(u(i, c), line);
  line->push_back('\n');
}

// Text buffered before each write to the stream.
constexpr std::size_t kCsvBufferBytes = std::size_t{1} << 16;

}  // namespace

void Trajectory::Reset(int n_states, int m_surfaces, double step, double start_time, const std::string& what,
                       std::int64_t steps, bool record, bool input) {
  n = n_states;
  m = m_surfaces;
  h = step;
  t0 = start_time;
  description = what;
  num_steps = steps;
  steps_taken = 0;
  recorded = record;
  const Eigen::Index columns = record ? static_cast<Eigen::Index>(steps + 1) : 0;
  t.resize(static_cast<std::size_t>(columns));
  x.resize(n, columns);
  s.resize(m, columns);
  y.resize(m, columns);
  iterations.resize(static_cast<std::size_t>(columns));
  residual.resize(static_cast<std::size_t>(columns));
  status.resize(static_cast<std::size_t>(columns));
  has_input = input;
  u.resize(input ? m : 0, columns);
  u.setConstant(std::numeric_limits<double>::quiet_NaN());
  max_residual = 0.0;
  total_iterations = 0;
  max_iterations = 0;
  max_step_x_error = 0.0;
  refined_steps = 0;
  failed_steps = 0;
  first_failed_step = -1;
  first_failure_status = SolveStatus::kNotRun;
  first_failure_residual = 0.0;
  first_failure_message.clear();
  stopped_early = false;
}

void Trajectory::Truncate(std::int64_t taken) {
  steps_taken = taken;
  if (!recorded || taken >= num_steps) return;
  const Eigen::Index columns = static_cast<Eigen::Index>(taken + 1);
  t.resize(static_cast<std::size_t>(columns));
  x.conservativeResize(Eigen::NoChange, columns);
  s.conservativeResize(Eigen::NoChange, columns);
  y.conservativeResize(Eigen::NoChange, columns);
  iterations.resize(static_cast<std::size_t>(columns));
  residual.resize(static_cast<std::size_t>(columns));
  status.resize(static_cast<std::size_t>(columns));
  if (has_input) u.conservativeResize(Eigen::NoChange, columns);
}

void WriteTrajectoryCsv(const Trajectory& trajectory, std::ostream& out) {
  const Trajectory& tr = trajectory;
  if (!tr.recorded) {
    throw InvalidInputError("WriteTrajectoryCsv: the trajectory was not recorded (StepperOptions::record = false)");
  }
  const bool has_input = tr.has_input && tr.u.cols() == static_cast<Eigen::Index>(tr.steps_taken + 1);
  const DenseMatrix no_input;
  out << CsvHeader(tr.n, tr.m, has_input);
  std::string line;
  const std::int64_t rows = tr.steps_taken + 1;
  for (std::int64_t k = 0; k < rows; ++k) {
    line.clear();
    AppendCsvRow(tr.t[k], tr.x, tr.s, tr.y, has_input ? tr.u : no_input, static_cast<Eigen::Index>(k),
                 tr.iterations[k], tr.residual[k], &line);
    out << line;
  }
  if (!out) throw InvalidInputError("WriteTrajectoryCsv: writing to the stream failed");
}

void WriteTrajectoryCsvFile(const Trajectory& trajectory, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InvalidInputError("WriteTrajectoryCsvFile: cannot open '" + path + "' for writing");
  WriteTrajectoryCsv(trajectory, out);
  out.flush();
  if (!out) throw InvalidInputError("WriteTrajectoryCsvFile: writing '" + path + "' failed");
}

void FeedRecorded(const Trajectory& trajectory, TrajectorySink* sink, std::int64_t block_rows) {
  const Trajectory& tr = trajectory;
  if (!tr.recorded) {
    throw InvalidInputError("FeedRecorded: the trajectory was not recorded (StepperOptions::record = false)");
  }
  if (block_rows < 1) throw InvalidInputError("FeedRecorded: block_rows must be >= 1");
  TrajectoryBlock block;
  block.n = tr.n;
  block.m = tr.m;
  const std::int64_t rows = tr.steps_taken + 1;
  for (std::int64_t first = 0; first < rows; first += block_rows) {
    const std::int64_t count = std::min(block_rows, rows - first);
    const auto f = static_cast<Eigen::Index>(first), c = static_cast<Eigen::Index>(count);
    block.first_row = first;
    block.rows = count;
    block.t.assign(tr.t.begin() + first, tr.t.begin() + first + count);
    block.x = tr.x.middleCols(f, c);
    block.s = tr.s.middleCols(f, c);
    block.y = tr.y.middleCols(f, c);
    block.iterations.assign(tr.iterations.begin() + first, tr.iterations.begin() + first + count);
    block.residual.assign(tr.residual.begin() + first, tr.residual.begin() + first + count);
    block.status.assign(tr.status.begin() + first, tr.status.begin() + first + count);
    if (tr.has_input) {
      block.u = tr.u.middleCols(f, c);
    } else {
      block.u.resize(0, c);
    }
    sink->OnRows(block);
  }
}

// ------------------------------------------------------------------------------------------------------------
// Streamed CSV

TrajectoryCsvWriter::TrajectoryCsvWriter(const std::string& path)
    : file_(std::make_unique<std::ofstream>(path)), out_(file_.get()), name_(path) {
  if (!*file_) throw InvalidInputError("TrajectoryCsvWriter: cannot open '" + path + "' for writing");
  buffer_.reserve(kCsvBufferBytes + 1024);
}

TrajectoryCsvWriter::TrajectoryCsvWriter(std::ostream* out, std::string name) : out_(out), name_(std::move(name)) {
  buffer_.reserve(kCsvBufferBytes + 1024);
}

TrajectoryCsvWriter::~TrajectoryCsvWriter() = default;

void TrajectoryCsvWriter::Drain() {
  out_->write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
  if (!*out_) throw InvalidInputError("TrajectoryCsvWriter: writing '" + name_ + "' failed");
}

void TrajectoryCsvWriter::OnRows(const TrajectoryBlock& block) {
  if (!header_written_) {
    buffer_ += CsvHeader(block.n, block.m, block.has_input());
    header_written_ = true;
  }
  for (std::int64_t j = 0; j < block.rows; ++j) {
    AppendCsvRow(block.t[j], block.x, block.s, block.y, block.u, static_cast<Eigen::Index>(j), block.iterations[j],
                 block.residual[j], &buffer_);
    if (buffer_.size() >= kCsvBufferBytes) Drain();
  }
  rows_ += block.rows;
}

void TrajectoryCsvWriter::Close() {
  Drain();
  out_->flush();
  if (!*out_) throw InvalidInputError("TrajectoryCsvWriter: writing '" + name_ + "' failed");
}

}  // namespace smcbench
