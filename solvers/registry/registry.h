// The explicit list of backends: create one by name, list them with their capabilities. Our backends and the
// built-in external adapters are a fixed list (no static registration); a program that brings its own backend
// adds it at run time with RegisterSolver (docs/custom-backend.md).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/core/solver.h"

namespace smcbench {

// Makes a fresh backend with default options.
using SolverFactory = std::function<std::unique_ptr<Solver>()>;

// Registered names in a fixed order: ours ("lemke", "psor", "newton", "enum", "ipopt", then "auto", which picks one
// of them per problem), then the external adapters that were built in ("siconos-*", "bullet-*", "dart-*"), then the backends added with
// RegisterSolver, in the order they were added.
std::vector<std::string_view> SolverNames();
// A fresh backend with default options; throws InvalidInputError listing the known names if name is unknown.
std::unique_ptr<Solver> CreateSolver(std::string_view name);

// The benchmark's generic sparse path (`bench` records it as "newton-sparse-path"): newton with its UMFPACK sparse
// LU forced at every size, i.e. what a general-purpose sparse complementarity solver does with these problems. Not
// auto's rule (auto lets newton factorize small sparse problems densely) and not a registered name: a baseline the
// fastest backend is measured against, defined here once.
std::unique_ptr<Solver> CreateGenericSparsePathSolver();

// The run-time extension point: adds a backend under name for the rest of the process, so that CreateSolver,
// SolverNames and every command built on them (`smcbench bench`, `solve`, `list`, reports) see it. Call it at
// the start of main, before any command runs. The factory is called once here to check that the backend it makes
// reports info().name == name. Throws InvalidInputError when name is empty or already taken (ours, an external
// adapter, or an earlier registration), when factory is empty or returns null, or when the names differ.
// Thread-safe; the table is process-wide because the commands create backends by name deep inside (a replayed
// suite, the reference certifier, the time-stepper studies), and an entry is never removed.
void RegisterSolver(std::string name, SolverFactory factory);
// True if name was added with RegisterSolver (not one of ours, not a built-in external adapter).
bool IsRegisteredAtRunTime(std::string_view name);
// True for a name of the external adapter families (siconos-*, bullet-*, dart-*), built into this binary or not:
// reports use it to keep other libraries' results apart from ours, also when they read another build's results.
bool IsExternalBackendName(std::string_view name);

}  // namespace smcbench
