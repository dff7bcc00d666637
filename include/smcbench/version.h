// The version of this smcbench build, for `smcbench --version` and for results that must say what made them.
#pragma once

#include <string_view>

namespace smcbench {

// The project VERSION of CMakeLists.txt, e.g. "0.1.0".
std::string_view Version();
// `git describe --always --dirty` of the checkout at build time (a commit hash, "-dirty" when the work tree had
// changes), or "unknown" when it was not built from a git checkout.
std::string_view GitRevision();

}  // namespace smcbench
