#include "bench/compare/compare_output.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bench/compare/compare_render.h"
#include "bench/figures/gnuplot_figure.h"
#include "solvers/core/number_text.h"
#include "solvers/core/problem.h"

namespace smcbench {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFigureStem = "compare-ratios";

// One row per group (its label double-quoted: gnuplot reads only double quotes in data), top to bottom in table
// order: the ratio ÷ drift as a point, its interval as a horizontal bar, coloured by flag; vertical lines at 1 and at
// the two flag limits.
void WriteRatioFigure(const RunComparison& c, const CompareOptions& options, const std::string& dir) {
  std::ostringstream data, body;
  data << "# row ratio low high label flag(1 none, 2 slower, 3 faster)\n";
  const int rows = static_cast<int>(c.groups.size());
  const double drift = c.drift.divisor();
  for (int i = 0; i < rows; ++i) {
    const RatioGroup& g = c.groups[static_cast<std::size_t>(i)];
    data << rows - i << ' ' << NumberText(g.time.ratio / drift) << ' ' << NumberText(g.time.low / drift) << ' '
         << NumberText(g.time.high / drift) << " \"" << g.solver << ' ' << g.suite << ' ' << ShortName(g.band) << '"'
         << ' ' << static_cast<int>(g.time.flag) + 1 << '\n';
  }
  const double upper = c.flag_limit, lower = 1.0 / upper;
  double x_min = lower, x_max = upper;
  for (const RatioGroup& g : c.groups) {
    x_min = std::min(x_min, g.time.low / drift);
    x_max = std::max(x_max, g.time.high / drift);
  }
  const std::string file = GnuplotQuote(std::string(kFigureStem) + ".dat");
  const std::string bars = " with xerrorbars pt 7 ps 1 lw 2 lc rgb ";
  body << "set logscale x\nset grid xtics\nunset key\nset xrange [" << NumberText(x_min / 1.15) << ":"
       << NumberText(x_max * 1.15)
       << "]\nset xtics (0.1, 0.2, 0.5, 1, 1.5, 2, 3, 5, 10, 20, 50, 100, 1000)\nset xlabel 'time ratio B/A ÷ drift "
       << NumberText(drift) << ", " << static_cast<int>(std::lround(options.confidence * 100.0))
       << " % bootstrap interval (orange: flagged slower, blue: flagged faster)'\nset yrange [0.5:" << rows + 0.5
       << "]\nset ytics scale 0 font ',9'\nset title 'smcbench compare: B/A per backend, suite and size band'\n"
       << "set arrow from 1, graph 0 to 1, graph 1 nohead lc rgb 'black'\n"
       << "set arrow from " << NumberText(upper) << ", graph 0 to " << NumberText(upper)
       << ", graph 1 nohead dt 2 lc rgb '#D55E00'\n"
       << "set arrow from " << NumberText(lower) << ", graph 0 to " << NumberText(lower)
       << ", graph 1 nohead dt 2 lc rgb '#0072B2'\n"
       << "plot " << file << " using 2:1:3:4:ytic(5)" << bars << "'#555555', " << file
       << " using ($6 == 2 ? $2 : 1/0):1:3:4" << bars << "'#D55E00', " << file
       << " using ($6 == 3 ? $2 : 1/0):1:3:4" << bars << "'#0072B2'\n";
  WriteGnuplotFigure(dir, kFigureStem, data.str(), body.str(), 900, std::max(300, 120 + 22 * rows), "compare");
}

}  // namespace

ComparisonFiles WriteComparisonFolder(const RunComparison& comparison, const CompareOptions& options,
                                      const std::string& label_a, const std::string& label_b, const std::string& dir,
                                      bool plots) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InvalidInputError("compare: cannot create the folder '" + dir + "': " + ec.message());
  ComparisonFiles files;
  if (plots && !comparison.groups.empty()) {
    try {
      WriteRatioFigure(comparison, options, dir);
      files.figure_stem = kFigureStem;
    } catch (const InvalidInputError& e) {
      files.figure_error = e.what();
    }
  }
  files.markdown = (fs::path(dir) / "compare.md").string();
  files.json = (fs::path(dir) / "compare.json").string();
  std::ofstream md_file(files.markdown), json_file(files.json);
  md_file << CompareMarkdown(comparison, options, label_a, label_b, files.figure_stem);
  json_file << CompareJson(comparison, options, label_a, label_b).dump(1) << "\n";
  md_file.close();
  json_file.close();
  if (!md_file || !json_file) {
    throw InvalidInputError("compare: cannot write '" + (md_file ? files.json : files.markdown) + "'");
  }
  return files;
}

}  // namespace smcbench
