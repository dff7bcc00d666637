// The report's figures: report_figures.h.
#include "bench/analysis/report_figures.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bench/analysis/markdown_cells.h"
#include "bench/analysis/plot_style.h"
#include "bench/analysis/suite_tables.h"
#include "bench/figures/gnuplot_figure.h"

namespace smcbench::markdown {
namespace {

// A figure a user can restyle: dir/STEM.dat (the data), dir/STEM.gp (the gnuplot script, reading STEM.dat and
// writing STEM.png and STEM.svg; `cd DIR && gnuplot STEM.gp` remakes both) kept beside STEM.png and STEM.svg.
// body: the settings and the plot command, naming the data file as 'STEM.dat'.
void WriteFigure(const std::string& dir, const std::string& stem, const std::string& data, const std::string& body,
                 int width, int height) {
  WriteGnuplotFigure(dir, stem, data, body, width, height, "report");  // the one figure writer (bench/figures)
}

// Tick labels in %g ("1e-06", "0.001", "100"): never gnuplot's default fixed notation ("0.0000010").
constexpr const char* kTickFormat = "set format x '%g'\nset format y '%g'\n";

}  // namespace

void PlotCurves(const std::map<std::string, std::vector<std::pair<double, double>>>& curves, const std::string& dir,
                const std::string& stem, const std::string& xlabel, const std::string& ylabel,
                const std::string& title, bool sort_by_x, const char* with) {
  std::ostringstream data, g;
  g << "set logscale xy\nset grid\nset key outside right top\n" << kTickFormat << "set xlabel " << GnuplotQuote(xlabel)
    << "\nset ylabel " << GnuplotQuote(ylabel) << "\nset title " << GnuplotQuote(title) << "\nplot ";
  int index = 0;
  for (const auto& [label, points] : curves) {
    auto sorted = points;
    if (sort_by_x) std::sort(sorted.begin(), sorted.end());
    data << "# " << label << "\n";
    for (auto [x, y] : sorted) data << x << ' ' << y << '\n';
    data << "\n\n";
    g << (index ? ", " : "") << GnuplotQuote(stem + ".dat") << " index " << index << " using 1:2 with " << with << " "
      << BackendStyle(label) << " title " << GnuplotQuote(label);
    ++index;
  }
  g << "\n";
  WriteFigure(dir, stem, data.str(), g.str(), 1100, 600);
}

// Dolan–Moré performance profile of the suite: dir/profile-SUITE.{png,svg,dat,gp} and its markdown.
void WritePerformanceProfile(std::ostream& md, const SuiteResults& suite, const std::string& dir,
                             bool explain) {
  const auto ratios = PerformanceRatios(suite);
  if (ratios.empty()) return;
  std::ostringstream data;
  double tau_max = 2.0;
  for (const auto& [solver, r] : ratios) {
    for (double v : r) {
      if (std::isfinite(v)) tau_max = std::max(tau_max, v);
    }
  }
  tau_max = std::min(tau_max * 1.5, 1e6);
  std::ostringstream g;
  const std::string stem = "profile-" + Safe(suite.suite);
  // The key outside the plot: with 20 backends it would cover the curves.
  g << "set logscale x 2\nset grid\nset key outside right top\n" << kTickFormat
    << "set xlabel 'tau (time / best time)'\nset ylabel 'fraction of problems'\nset yrange [0:1.02]\nset xrange [1:"
    << tau_max << "]\nset title " << GnuplotQuote("Performance profile, suite " + suite.suite) << "\nplot ";
  // A backend that solved no problem would be a flat line on the x-axis, hiding the others' start: named below.
  std::vector<std::string> never;
  int index = 0;
  for (const auto& [solver, r] : ratios) {
    if (r.empty() || !std::isfinite(r.front())) {
      never.push_back(solver);
      continue;
    }
    // Step function: (τ_i, i/N), extended to τ_max.
    const double n = static_cast<double>(r.size());
    data << "# " << solver << "\n1 0\n";
    int k = 0;
    for (double v : r) {
      if (!std::isfinite(v)) break;
      ++k;
      data << v << ' ' << k / n << '\n';
    }
    data << tau_max << ' ' << k / n << "\n\n\n";
    // Steps draw no point types, and colour + dash alone repeat past seven backends: about eight markers on each
    // curve, and a key entry showing line and marker together.
    const std::string style = BackendStyle(solver), file = GnuplotQuote(stem + ".dat");
    g << (index ? ", " : "") << file << " index " << index << " using 1:2 with steps " << style << " notitle, "
      << file << " index " << index << " using 1:2 every " << std::max(1, k / 8) << " with points " << style
      << " notitle, keyentry with linespoints " << style << " title " << GnuplotQuote(solver);
    ++index;
  }
  g << "\n";
  if (index > 0) {
    WriteFigure(dir, stem, data.str(), g.str(), 1100, 600);
    md << FigureMarkdown("performance profile, " + suite.suite, stem);
  }
  if (!explain && never.empty()) return;
  if (!explain) {
    md << "Not drawn (solved none of these problems):";
    for (std::size_t i = 0; i < never.size(); ++i) md << (i ? ", " : " ") << never[i];
    md << ".\n\n";
    return;
  }
  md << "Performance profile: ρ(τ) = the fraction of problems a backend solved within τ × the fastest solved time "
        "on that problem; a failure or a wrong answer never counts (it sits at τ = ∞), and problems no backend "
        "solved are left out.";
  if (!never.empty()) {
    md << " Not drawn, since they solved none of those problems:";
    for (std::size_t i = 0; i < never.size(); ++i) md << (i ? ", " : " ") << never[i];
    md << ".";
  }
  md << "\n\n";
}

}  // namespace smcbench::markdown
