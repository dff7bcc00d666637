#include "bench/figures/trajectory_plot.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <optional>
#include <ostream>
#include <sstream>
#include <system_error>

#include "bench/figures/gnuplot_figure.h"
#include "solvers/core/number_text.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

// The data of a PNG written alone, removed when the figure is done.
struct TempDataFile {
  fs::path path;
  TempDataFile() {
    static std::atomic<int> counter{0};
    path = fs::temp_directory_path() /
           ("smcbench-trajectory-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".dat");
  }
  ~TempDataFile() {
    std::error_code ec;
    fs::remove(path, ec);
  }
  TempDataFile(const TempDataFile&) = delete;
  TempDataFile& operator=(const TempDataFile&) = delete;
};

}  // namespace

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

std::string TrajectoryFigureScript(int n, int m, const std::string& title, const std::string& data) {
  std::ostringstream g;
  // Series i of the data is its gnuplot "index i" (blocks two blank lines apart): x1..xn, s1..sm, y1..ym, phase.
  // Keys outside the axes: inside, the phase portrait's key sat on x0 (the portrait starts in a corner). %g ticks:
  // gnuplot's default prints a value of 1e-6 as "0.0000010".
  g << "set grid\nset key outside right top\nset format x '%g'\nset format y '%g'\n"
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
  return g.str();
}

void PlotTrajectory(const TrajectoryPlotData& plot_data, const std::string& title, const std::string& png_path) {
  if (!GnuplotAvailable()) {
    throw InvalidInputError("--plot needs gnuplot (Debian package gnuplot-nox), which is not on PATH");
  }
  const fs::path png(png_path);
  const bool beside = png.extension() == ".png";
  const std::string stem = png.stem().string();
  std::ostringstream data_text;
  plot_data.WriteData(data_text);
  std::optional<TempDataFile> temp;
  if (!beside) {
    temp.emplace();
    std::ofstream out(temp->path);
    out << data_text.str();
    out.flush();
    if (!out) throw InvalidInputError("--plot: cannot write the plot data " + temp->path.string());
  }
  const int n = plot_data.n(), m = plot_data.m();
  const std::string data = GnuplotQuote(beside ? stem + ".dat" : temp->path.string());
  const int height = n >= 2 ? 900 : 1000;
  const std::string script = TrajectoryFigureScript(n, m, title, data);
  if (beside) {
    const std::string dir = png.has_parent_path() ? png.parent_path().string() : std::string(".");
    WriteGnuplotFigure(dir, stem, data_text.str(), script, 1200, height, "simulate --plot");
    return;
  }
  RunGnuplot(GnuplotPngPreamble(1200, height, png_path) + script, png_path, "--plot");
}

void PlotTrajectory(const Trajectory& tr, const std::string& title, const std::string& png_path) {
  TrajectoryPlotData data(tr.n, tr.m, tr.steps_taken + 1);
  FeedRecorded(tr, &data);
  PlotTrajectory(data, title, png_path);
}

}  // namespace smcbench
