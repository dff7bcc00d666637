// The smcbench command line: `list`, `solve`, `collection`, `convert`. Runs in-process so tests can drive it.
#pragma once

#include <iosfwd>

namespace smcbench {

// Parses argv and runs the subcommand, writing results to out and one-line errors to err.
// Returns the process exit status: 0 on success, 1 on invalid input or unreadable files, 2 on usage errors.
int RunCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace smcbench
