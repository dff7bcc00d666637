// The report's cells: markdown_cells.h.
#include "bench/analysis/markdown_cells.h"

#include <cmath>
#include <cctype>
#include <cstdio>

#include "bench/analysis/record_facts.h"
#include "solvers/core/duration_text.h"

namespace smcbench::markdown {

std::string G(double v, int digits) {
  if (std::isnan(v)) return "–";
  if (std::isinf(v)) return "∞";
  char b[40];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

std::string Seconds(double s) { return DurationText(s); }

std::string FigureMarkdown(const std::string& alt, const std::string& stem) {
  return "![" + alt + "](" + stem + ".png)\n\n(" + "[SVG](" + stem + ".svg), [data](" + stem + ".dat), [gnuplot script](" +
         stem + ".gp))\n\n";
}

std::string Safe(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return out;
}

std::string Count(int n) { return n ? "**" + std::to_string(n) + "**" : std::string("0"); }

// A table cell from free text: one line, no column separator, at most max_chars bytes.
std::string Cell(const std::string& text, std::size_t max_chars) {
  std::string out;
  for (char c : text) out += c == '|' ? '/' : c == '\n' ? ' ' : c;
  if (out.size() > max_chars) out = out.substr(0, max_chars) + "…";
  return out;
}

// A value that is not defined (NaN: nothing solved, no reference) as an empty cell, never as a 0.
std::string Blank(double v) { return std::isnan(v) ? std::string() : G(v); }

// "12/16 (75%)"; empty when nothing was run.
std::string Fraction(int part, int whole) {
  if (whole == 0) return "";
  return std::to_string(part) + "/" + std::to_string(whole) + " (" + G(100.0 * part / whole, 3) + "%)";
}

// "1.8× [0.5 – 3] (12)": median [min – max] (n) of sorted ratios; empty when there are none.
std::string RatioSpread(const std::vector<double>& r) {
  if (r.empty()) return "";
  return G(r[r.size() / 2]) + "× [" + G(r.front()) + " – " + G(r.back()) + "] (" + std::to_string(r.size()) + ")";
}


// A backend's time over the floor as a cell: the median of sorted ratios and their count, "–" when none.
std::string FloorRatioCell(const std::vector<double>& sorted) {
  if (sorted.empty()) return "–";
  return G(MedianOfSorted(sorted)) + "× (" + std::to_string(sorted.size()) + ")";
}


// "size_limit on 50 of 50: "refused m > 12" (50×), median 24 µs": the reason a backend solved nothing.
std::string FailureText(const FailureReason& f, int problems) {
  std::string text = "`" + std::string(ToString(f.status)) + "` on " + std::to_string(f.count) + " of " +
                     std::to_string(problems);
  if (!f.message.empty()) {
    text += ": \"" + Cell(f.message) + "\"";
    if (f.message_count != f.count) text += " (" + std::to_string(f.message_count) + "×)";
  }
  if (!std::isnan(f.median_time)) text += ", median " + Seconds(f.median_time);
  return text;
}

}  // namespace smcbench::markdown
