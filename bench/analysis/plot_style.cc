// The figures' backend styles: plot_style.h.
#include "bench/analysis/plot_style.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <vector>

#include "solvers/registry/registry.h"

namespace smcbench {

PlotStyle StyleOf(std::size_t index, bool external) {
  // Okabe & Ito (2008), "Color Universal Design": distinct under every common colour-vision deficiency. Its yellow
  // (#F0E442) is left out: it vanishes on a white background.
  static constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                             "#E69F00", "#56B4E9", "#000000"};
  // Filled circle, square, up and down triangles, diamond; open circle, open square.
  static constexpr int kPoints[] = {7, 5, 9, 11, 13, 6, 4};
  constexpr std::size_t kN = 7;
  const std::size_t colour = index % kN, round = index / kN;
  PlotStyle style;
  style.colour = kColours[colour];
  // Within one colour the point type steps with each round of the palette, so colour + point stays unique; the
  // external family starts 3 point types on, so our i-th and its i-th differ in more than the dash.
  style.point = kPoints[(colour + round + (external ? 3 : 0)) % kN];
  style.dash = external ? 2 + static_cast<int>(round % 4) : 1;
  style.width = external ? 2.0 : 2.5;
  return style;
}

std::string BackendStyle(const std::string& label) {
  std::vector<std::string> known;
  for (auto name : SolverNames()) known.emplace_back(name);
  known.emplace_back("newton-sparse-path");
  std::string backend = label;
  std::string token;
  for (char c : label + " ") {
    if (c == ' ' || c == '/' || c == '(' || c == ')' || c == ',') {
      if (!token.empty() && std::find(known.begin(), known.end(), token) != known.end()) {
        backend = token;
        break;
      }
      token.clear();
    } else {
      token.push_back(c);
    }
  }
  const bool external = IsExternalBackendName(backend);
  std::size_t index = 0;
  const auto it = std::find(known.begin(), known.end(), backend);
  if (it == known.end()) {
    index = std::hash<std::string>{}(backend) % 49;
  } else {
    for (auto k = known.begin(); k != it; ++k) index += IsExternalBackendName(*k) == external;
  }
  const PlotStyle style = StyleOf(index, external);
  char text[96];
  std::snprintf(text, sizeof text, "lw %g lc rgb '%s' dt %d pt %d", style.width, style.colour.c_str(), style.dash,
                style.point);
  return text;
}

}  // namespace smcbench
