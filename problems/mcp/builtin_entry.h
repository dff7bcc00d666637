// What a built-in MCP module hands the suite for one id: the library entry (without references) and the solutions
// the literature or a proof gives, which join the backends' answers as candidates for the certifier.
#pragma once

#include <string>
#include <vector>

#include "problems/mcp/mcp_library.h"

namespace smcbench {

struct BuiltinMcpEntry {
  McpLibraryProblem problem;
  std::vector<Vector> known_solutions;  // published or proved solutions, any precision (the certifier refines them)
};

// Builds the entry for id into *out and returns true, or returns false if this module does not know id.
// InvalidInputError for an id of the module's form with bad parameters (named in the message).
using BuiltinMcpMaker = bool (*)(const std::string& id, BuiltinMcpEntry* out);

}  // namespace smcbench
