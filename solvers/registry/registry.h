// The explicit list of backends: create one by name, list them with their capabilities. No static registration.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "solvers/core/solver.h"

namespace smcbench {

// Registered names in a fixed order: ours ("lemke", "psor", "newton", "enum", "ipopt", then "auto", which picks one
// of them per problem), then the external adapters that were built in ("siconos-*").
std::vector<std::string_view> SolverNames();
// A fresh backend with default options; throws InvalidInputError listing the known names if name is unknown.
std::unique_ptr<Solver> CreateSolver(std::string_view name);

}  // namespace smcbench
