// The report's cells and phrases: numbers in %g, times, counts in bold, free text made one table cell, fractions,
// ratio spreads, a figure's markdown. Shared by every markdown section (namespace markdown: not a public API).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "bench/analysis/suite_tables.h"

namespace smcbench::markdown {

// v in %g with digits significant digits; "–" for NaN, "∞" for infinity.
std::string G(double v, int digits = 3);
// A time in seconds as DurationText ("24 µs").
std::string Seconds(double s);
// A file name's stem from free text: every character not a letter or digit becomes '-'.
std::string Safe(const std::string& text);
// A count of wrong answers: bold unless 0.
std::string Count(int n);
// A table cell from free text: one line, no column separator, at most max_chars bytes.
std::string Cell(const std::string& text, std::size_t max_chars = 90);
// A value that is not defined (NaN: nothing solved, no reference) as an empty cell, never as a 0.
std::string Blank(double v);
// "12/16 (75%)"; empty when nothing was run.
std::string Fraction(int part, int whole);
// "1.8× [0.5 – 3] (12)": median [min – max] (n) of sorted ratios; empty when there are none.
std::string RatioSpread(const std::vector<double>& sorted);
// A backend's time over the floor as a cell: the median of sorted ratios and their count, "–" when none.
std::string FloorRatioCell(const std::vector<double>& sorted);
// "`size_limit` on 50 of 50: "refused m > 12" (50×), median 24 µs": the reason a backend solved nothing.
std::string FailureText(const FailureReason& f, int problems);
// The markdown of a figure: the PNG, with its SVG, data and script linked below it.
std::string FigureMarkdown(const std::string& alt, const std::string& stem);

}  // namespace smcbench::markdown
