// Levenshtein distance between short words, for "did you mean" suggestions of names (flags, backend names, ids).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace smcbench {

// The number of single-character insertions, deletions and substitutions that turn a into b.
std::size_t EditDistance(std::string_view a, std::string_view b);

// Up to max_count of known, nearest to word first (ties in known's order).
std::vector<std::string> NearestNames(std::string_view word, const std::vector<std::string>& known,
                                      std::size_t max_count);

}  // namespace smcbench
