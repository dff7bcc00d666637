// Scalable nonlinear MCP families with sparse Jacobians (finite differences on the unit interval or square, the
// 3- or 5-point Laplacian with zero boundary values, rows multiplied by h²):
//   "mcp/obstacle1d/n<N>", "mcp/obstacle2d/m<M>" (n = M²): −Δu + u³ = g above an obstacle ψ (u ≥ ψ), g = −10 (1-D)
//     or −20 (2-D), ψ = −0.05 − ½|x − ½|²: a contact region in the middle. Strongly monotone (Laplacian SPD, u³
//     nondecreasing): one solution.
//   "mcp/bratu1d/n<N>", "mcp/bratu2d/m<M>": Bratu's −Δu = λ eᵘ (λ = 3 in 1-D, 5 in 2-D, below the fold) as an MCP
//     on the box 0 ≤ u ≤ 0.3 (an upper obstacle, in contact in the middle). F is not monotone on Rⁿ, but on the box
//     λ e^u ≤ λ e^0.3 < the smallest eigenvalue of the discrete −Δ (≈ π² in 1-D, 2π² in 2-D): strongly monotone
//     there, so the solution is unique.
#pragma once

#include <string>
#include <vector>

#include "problems/mcp/builtin_entry.h"

namespace smcbench {

// Ids in suite order: quick, the sizes CI runs (n ≤ 64, so they get extended-precision references); full adds the
// large sizes (up to 10⁴ unknowns).
std::vector<std::string> McpFamilyIds(bool quick);
// BuiltinMcpMaker: any size N ≥ 1 (1-D) or M ≥ 1 (2-D) up to 10⁶ unknowns parses.
bool MakeFamilyMcp(const std::string& id, BuiltinMcpEntry* out);

}  // namespace smcbench
