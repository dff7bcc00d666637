// The report's gnuplot figures: curves of time against an error on log axes, and the Dolan–Moré performance profile
// of a suite; each writes DIR/STEM.{png,svg,dat,gp} through the one figure writer (bench/figures).
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "bench/replay/results_io.h"

namespace smcbench::markdown {

// One curve per label of (x, time) points on log axes, joined in x order when sort_by_x (else in the given order,
// e.g. of decreasing h): the figure dir/STEM.{png,svg,dat,gp}.
void PlotCurves(const std::map<std::string, std::vector<std::pair<double, double>>>& curves, const std::string& dir,
                const std::string& stem, const std::string& xlabel, const std::string& ylabel,
                const std::string& title, bool sort_by_x = true, const char* with = "linespoints");

// Dolan–Moré performance profile of the suite (PerformanceRatios): dir/profile-SUITE.{png,svg,dat,gp} and its
// markdown, with the explanation when explain (else only the backends not drawn).
void WritePerformanceProfile(std::ostream& md, const SuiteResults& suite, const std::string& dir,
                             bool explain = true);

}  // namespace smcbench::markdown
