// The problem filter of a run (`bench --problem GLOB`), shared by every problem kind's suite builder, so that a
// glob matching nothing is refused whichever kind of suite it was meant for.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace smcbench {

// An id (a box problem's, an MCP's, an AVI's or a warm sequence's, "<suite>/warm/...") is kept when it matches one
// of the globs (GlobMatch: '*' any characters, '/' included, '?' one); without globs every id is. It remembers which
// globs matched, so that a glob that matches nothing (a typo) is refused rather than run as an empty benchmark.
struct ProblemFilter {
  std::vector<std::string> globs;
  std::vector<char> matched;  // per glob: it matched an id Keeps was asked about

  explicit ProblemFilter(std::vector<std::string> globs_in);
  bool Keeps(std::string_view id);
  std::vector<std::string> Unmatched() const;  // the globs that matched no id, in the order given
};

// Keeps the items of a list whose id the filter keeps, in order: the one place a run's problems are selected.
template <typename Item, typename IdOf>
void KeepSelected(std::vector<Item>* items, IdOf id_of, ProblemFilter* filter) {
  std::vector<Item> kept;
  for (Item& item : *items) {
    if (filter->Keeps(id_of(item))) kept.push_back(std::move(item));
  }
  *items = std::move(kept);
}

}  // namespace smcbench
