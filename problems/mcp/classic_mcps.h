// The classic small nonlinear complementarity problems of the literature (MCPLIB-style) and the hard cases
// (degenerate, several solutions, none, F undefined outside the box), each with its source, its starting points
// and what is known of its solutions. Formulas: classic_mcps.cc; ids: "mcp/classic/<name>", "mcp/hard/<name>".
#pragma once

#include <string>
#include <vector>

#include "problems/mcp/builtin_entry.h"

namespace smcbench {

// Ids in suite order.
std::vector<std::string> ClassicMcpIds();
std::vector<std::string> HardMcpIds();
// BuiltinMcpMaker for every id above.
bool MakeClassicMcp(const std::string& id, BuiltinMcpEntry* out);

}  // namespace smcbench
