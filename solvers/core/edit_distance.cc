#include "solvers/core/edit_distance.h"

#include <algorithm>
#include <utility>

namespace smcbench {

std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);  // one row of the dynamic-programming table
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::vector<std::string> NearestNames(std::string_view word, const std::vector<std::string>& known,
                                      std::size_t max_count) {
  std::vector<std::pair<std::size_t, const std::string*>> ranked;
  ranked.reserve(known.size());
  for (const std::string& name : known) ranked.emplace_back(EditDistance(word, name), &name);
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> nearest;
  for (std::size_t k = 0; k < ranked.size() && k < max_count; ++k) nearest.push_back(*ranked[k].second);
  return nearest;
}

}  // namespace smcbench
