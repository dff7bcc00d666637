// The built-in MCP suite (`bench --suite mcp`): the classic problems of the literature, the hard cases, the
// scalable families and the one-step MCPs captured from S9/S10, each with every starting point and certified
// references. A nonlinear F cannot be stored as data: a built-in MCP is stored by its id, which rebuilds it
// (MakeBuiltinMcp); problems/mcp/README.md lists the ids.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "problems/mcp/mcp_library.h"

namespace smcbench {

// The suite's ids in order (stable across runs and machines). quick: the small sizes CI runs (every problem then
// has n ≤ 64 and extended-precision references); otherwise also the family sizes up to 10⁴ unknowns.
std::vector<std::string> McpSuiteIds(bool quick);

// The suite with its references attached (AttachMcpReferences on every problem). Runs every registered MCP backend
// from every start of every problem: the full suite takes far longer than the quick one (the 10⁴-unknown
// references).
McpProblemSet BuildMcpSuite(bool quick);

// The suite of these ids only (built-in ids, normally a subset of McpSuiteIds(quick), in the given order),
// references attached to them alone: a run filtered by `bench --problem` pays only for the problems it runs.
// InvalidInputError for an unknown id (MakeBuiltinMcp's), or no id at all.
McpProblemSet BuildMcpSuite(bool quick, const std::vector<std::string>& ids);

// The MCP of a built-in id (any id of McpSuiteIds, and any size of a family or step of a scene of the same form).
// InvalidInputError for an unknown id, listing the closest known ids.
std::shared_ptr<const MCP> MakeBuiltinMcp(const std::string& id);

// The library entry of a built-in id (problem, starts, tags, expected outcome), without references.
McpLibraryProblem MakeBuiltinMcpProblem(const std::string& id);

// Certified references for a problem whose MCP implements ExtendedPrecisionMCP, dense up to n = 64 and sparse up
// to McpCertifyOptions::max_banded_size (others are left without references): the candidates are the answers of
// every registered backend that solves MCPs (SolverInfo::mcp) from every start, the built-in's published or proved
// solutions and, for n ≤ 64, the starts themselves (larger problems take only answers with a scale-free residual
// ≤ 1e-6); CertifyMCPSolutions (solvers/reference/mcp_certify.h) keeps the verified ones. references_complete stays
// true only when the entry declared it and the certified set matches what the literature or proof says (every
// known solution found; one solution certified unique when none is listed; none for an expected-infeasible
// problem).
void AttachMcpReferences(McpLibraryProblem* problem);

}  // namespace smcbench
