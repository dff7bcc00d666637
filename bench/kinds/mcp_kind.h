// The nonlinear MCP problem kind: the `mcp` suite, each problem × start × MCP backend replayed by ReplayMcpOne
// (job ids "problem@start"; manifest kind "mcp", as before the kinds).
#pragma once

#include <memory>

#include "bench/kinds/problem_kind.h"
#include "problems/mcp/mcp_library.h"

namespace smcbench {

std::shared_ptr<const ProblemKind> McpProblemKind();

PlanSuite MakeMcpSuite(McpProblemSet set);

// The problem set of an MCP suite; InvalidInputError for a suite of another kind.
const McpProblemSet& McpSet(const KindSuite& suite);

}  // namespace smcbench
