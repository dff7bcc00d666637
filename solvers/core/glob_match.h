// Glob patterns over names ('*' any run of characters, '/' included; '?' one character; no escapes): how bench's
// --allow-wrong names backends and --problem names problem ids. Header-only: a few lines every layer may use.
#pragma once

#include <cstddef>
#include <string_view>

namespace smcbench {

// True when text matches the glob pattern as a whole.
inline bool GlobMatch(std::string_view pattern, std::string_view text) {
  // Iterative wildcard matching with one backtrack point (the last '*'): linear in practice, no recursion.
  std::size_t p = 0, t = 0, star = std::string_view::npos, resume = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p, ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      resume = t;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      t = ++resume;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

}  // namespace smcbench
