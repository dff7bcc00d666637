// The trajectory figure of `simulate --plot` and `paper`: states, multipliers and sliding variables against time and
// the phase portrait, drawn from data kept in memory independent of the run's length.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "problems/stepper/trajectory.h"

namespace smcbench {

// What the figure draws: rows_expected rows (N + 1) are cut into at most kPlotBuckets consecutive buckets, and per
// bucket each series (x_i, s_i, y_i) keeps its minimum and maximum with their times, so a spike or chattering of a
// single step stays visible (a band between the extremes) where taking every k-th row would hide it. The phase
// portrait keeps, per bucket, the states (x1, x2) at the extremes of x1 and of x2 (true points of the trajectory),
// plus x0. A run of at most kPlotBuckets rows keeps every row.
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

// The gnuplot commands of the figure (after the terminal lines), reading the data from data_file (already quoted
// for gnuplot): a multiplot of states, s and y against t and, for n ≥ 2, the phase portrait (x1, x2) with x0
// marked. Legends sit outside the plot areas (they never cover x0 or the data) and y ticks use %g.
std::string TrajectoryFigureScript(int n, int m, const std::string& title, const std::string& data_file);

// Writes the figure as a PNG with gnuplot. png_path ending in .png: X.svg, X.dat and X.gp are written beside it
// (WriteGnuplotFigure: the user can restyle it); another name: the PNG alone, its data in a temporary file.
// InvalidInputError if gnuplot is not on PATH ("--plot needs gnuplot (Debian package gnuplot-nox)") or fails.
void PlotTrajectory(const TrajectoryPlotData& data, const std::string& title, const std::string& png_path);
// The same for a recorded trajectory (its rows go through TrajectoryPlotData); InvalidInputError if it was not
// recorded.
void PlotTrajectory(const Trajectory& trajectory, const std::string& title, const std::string& png_path);

}  // namespace smcbench
