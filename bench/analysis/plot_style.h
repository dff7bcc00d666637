// How a backend looks in every figure of the report: colour, dash and point type, fixed by its place in the registry.
#pragma once

#include <cstddef>
#include <string>

namespace smcbench {

// The look of a backend's curve: colour (Okabe–Ito, without its yellow, which vanishes on white), gnuplot dash
// type and point type. Ours solid (dash 1), the external siconos-* ones dashed (dash ≥ 2).
struct PlotStyle {
  std::string colour;  // "#RRGGBB"
  int dash = 1;
  int point = 7;
  double width = 2.5;
};
// The index-th style of a family (ours, or external): no two indices below 49 of one family share colour and
// point, and no two below 28 of the external family share colour and dash; the families differ in dash.
PlotStyle StyleOf(std::size_t index, bool external);
// A backend's style in every figure: its family and its position in the registry's order (SolverNames, then
// newton-sparse-path), so a backend looks the same in every figure; a label naming a backend ("implicit, lemke")
// gets that backend's, one naming none a style from a hash of it. As gnuplot options ("lw 2.5 lc rgb '#0072B2' dt 1
// pt 7").
std::string BackendStyle(const std::string& label);

}  // namespace smcbench
