// The trajectory figure: its data keep every extreme of a long run in bounded memory, its script keeps legends off
// the data and ticks readable, and gnuplot draws it from a recorded run.
#include "bench/figures/trajectory_plot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bench/figures/gnuplot_figure.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

// --plot keeps per bucket the minimum and maximum of each series: a one-step spike and a chattering series stay
// visible in a 10⁵-row run, with at most 2 points per bucket; a short run keeps every row.
TEST(TrajectoryPlotData, KeepsExtremesPerBucketInBoundedMemory) {
  constexpr std::int64_t kRows = 100000;
  TrajectoryPlotData data(2, 1, kRows);
  TrajectoryBlock block;
  block.n = 2, block.m = 1;
  block.t.resize(1000), block.x.resize(2, 1000), block.s.resize(1, 1000), block.y.resize(1, 1000);
  block.iterations.resize(1000), block.residual.resize(1000), block.status.resize(1000);
  for (std::int64_t first = 0; first < kRows; first += 1000) {
    block.first_row = first;
    block.rows = 1000;
    for (Eigen::Index j = 0; j < 1000; ++j) {
      const std::int64_t k = first + j;
      block.t[static_cast<std::size_t>(j)] = 0.001 * static_cast<double>(k);
      block.x(0, j) = k == 54321 ? 7.0 : 1.0;  // a single-step spike
      block.x(1, j) = -static_cast<double>(k);
      block.s(0, j) = k % 2 ? 1.0 : -1.0;      // chattering every step
      block.y(0, j) = 0.0;
    }
    data.OnRows(block);
  }
  std::ostringstream out;
  data.WriteData(out);
  // Blocks two blank lines apart: x1, x2, s1, y1, phase.
  std::vector<std::vector<std::pair<double, double>>> series(1);
  std::istringstream in(out.str());
  int blank = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) {
      if (++blank == 2) series.emplace_back(), blank = 0;
      continue;
    }
    blank = 0;
    std::istringstream fields(line);
    double a = 0, b = 0;
    fields >> a >> b;
    series.back().emplace_back(a, b);
  }
  ASSERT_EQ(series.size(), 5u);
  for (const auto& points : series) EXPECT_LE(static_cast<std::int64_t>(points.size()), 2 * kPlotBuckets + 2);
  const auto has = [](const std::vector<std::pair<double, double>>& points, double t, double v) {
    for (const auto& [pt, pv] : points) {
      if (pt == t && pv == v) return true;
    }
    return false;
  };
  EXPECT_TRUE(has(series[0], 0.001 * 54321.0, 7.0)) << "the spike of x1";
  // s: both +1 and −1 in every bucket (the chattering band), in time order.
  int plus = 0, minus = 0;
  for (const auto& [t, v] : series[2]) plus += v == 1.0, minus += v == -1.0;
  EXPECT_GE(plus, 2000);  // 2041 buckets of 49 rows
  EXPECT_GE(minus, 2000);
  for (std::size_t i = 1; i < series[2].size(); ++i) EXPECT_LT(series[2][i - 1].first, series[2][i].first);
  // The phase portrait starts at x0 and holds the spike as a true state (x1, x2) = (7, −54321).
  EXPECT_EQ(series[4].front(), std::make_pair(1.0, 0.0));
  EXPECT_TRUE(has(series[4], 7.0, -54321.0));

  // A short run: every row, s from row 1.
  TrajectoryPlotData small(2, 1, 10);
  block.first_row = 0, block.rows = 10;
  small.OnRows(block);
  std::ostringstream short_out;
  small.WriteData(short_out);
  const std::string text = short_out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 10 + 2 + 10 + 2 + 9 + 2 + 10 + 2 + 10);
}

TEST(TrajectoryFigureScript, KeysOutsideTheAxesAndGeneralTickFormat) {
  const std::string script = TrajectoryFigureScript(2, 1, "a 'title'", "'d.dat'");
  EXPECT_THAT(script, HasSubstr("set key outside right top\n"));
  EXPECT_THAT(script, Not(HasSubstr("set key top right")));  // a key inside the phase portrait covered x0
  EXPECT_THAT(script, HasSubstr("set format y '%g'\n"));
  EXPECT_THAT(script, HasSubstr("title 'a ''title'''"));
  // Series x1, x2 (index 0, 1), s1 (2), y1 (3), then the phase portrait (4) with x0 as its first point.
  EXPECT_THAT(script, HasSubstr("plot for [i=0:1] 'd.dat' index i"));
  EXPECT_THAT(script, HasSubstr("plot for [i=2:2] 'd.dat' index i using 1:2 with fsteps"));
  EXPECT_THAT(script, HasSubstr("plot for [i=3:3] 'd.dat' index i"));
  EXPECT_THAT(script, HasSubstr("'d.dat' index 4 every ::0::0 using 1:2 with points"));
  // One state: no phase portrait, three panels.
  const std::string one = TrajectoryFigureScript(1, 1, "t", "'d.dat'");
  EXPECT_THAT(one, HasSubstr("layout 3,1"));
  EXPECT_THAT(one, Not(HasSubstr("phase portrait")));
}

// A recorded run (x = (cos t, sin t), one surface) drawn as X.png: the data, script and SVG beside it; another name
// writes the PNG alone and leaves no temporary file.
TEST(PlotTrajectory, DrawsARecordedRun) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  const fs::path dir = fs::temp_directory_path() / ("smcbench-trajectory-plot-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Trajectory tr;
  tr.Reset(2, 1, 0.01, 0.0, "test", 100, /*record=*/true, /*input=*/false);
  for (std::int64_t k = 0; k <= 100; ++k) {
    const double t = 0.01 * static_cast<double>(k);
    Vector x(2), s(1), y(1);
    x << std::cos(t), std::sin(t);
    s << (k == 0 ? 0.0 : 1.0);
    y << 1e-6 * x[1];
    tr.SetRow(k, t, x, s, y, 0, 0.0, SolveStatus::kSolved);
  }
  tr.Truncate(100);
  PlotTrajectory(tr, "circle", (dir / "circle.png").string());
  for (const char* name : {"circle.png", "circle.svg", "circle.dat", "circle.gp"}) {
    EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
  }
  std::ifstream dat(dir / "circle.dat");
  std::string first;
  std::getline(dat, first);
  EXPECT_EQ(first, "0 1");  // x1 starts at cos 0 = 1
  PlotTrajectory(tr, "circle", (dir / "alone.image").string());
  EXPECT_GT(fs::file_size(dir / "alone.image"), 1000u);
  const std::string temporary = "smcbench-trajectory-" + std::to_string(::getpid()) + "-";
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path())) {
    EXPECT_THAT(entry.path().filename().string(), Not(HasSubstr(temporary)));
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST(PlotTrajectory, AnUnrecordedRunIsAnError) {
  Trajectory tr;
  tr.n = 1, tr.m = 1;
  EXPECT_THROW(PlotTrajectory(tr, "t", "/nonexistent/x.png"), InvalidInputError);
}

}  // namespace
}  // namespace smcbench
