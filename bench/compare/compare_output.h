// What a comparison writes to a folder (compare.md, compare.json, the ratio figure): one home for `smcbench compare
// --out` and Python's smcbench.compare(out=...), so both write the same files.
#pragma once

#include <string>

#include "bench/compare/compare_runs.h"

namespace smcbench {

// The files WriteComparisonFolder wrote.
struct ComparisonFiles {
  std::string markdown;      // DIR/compare.md
  std::string json;          // DIR/compare.json
  std::string figure_stem;   // "compare-ratios" when DIR/compare-ratios.{png,svg,dat,gp} were written, else empty
  std::string figure_error;  // why the figure was asked for but not drawn (gnuplot missing or failing), else empty
};

// Writes dir/compare.md and dir/compare.json (creating dir) and, with plots and at least one group, the ratio
// figure compare-ratios.{png,svg,dat,gp} (one row per group: the ratio ÷ drift and its interval, coloured by flag),
// linked from compare.md. A figure gnuplot cannot draw is reported in figure_error and the rest is still written:
// the verdict of a comparison stands without its figure. InvalidInputError when a file cannot be written.
ComparisonFiles WriteComparisonFolder(const RunComparison& comparison, const CompareOptions& options,
                                      const std::string& label_a, const std::string& label_b, const std::string& dir,
                                      bool plots);

}  // namespace smcbench
