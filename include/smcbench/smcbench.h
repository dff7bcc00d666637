// The umbrella header of the smcbench library: `#include <smcbench/smcbench.h>` and link smcbench::smcbench
// (find_package(smcbench CONFIG), docs/install.md). Everything is in namespace smcbench; it includes public headers
// only (cmake/SmcbenchPublicHeaders.cmake lists them, docs/architecture.md says what each is for).
#pragma once

// Problems (BoxMLCP, MCP), options, results, statuses, the Solver base class every backend derives from, sessions.
#include "solvers/core/options.h"
#include "solvers/core/problem.h"
#include "solvers/core/result.h"
#include "solvers/core/session.h"
#include "solvers/core/solver.h"
#include "solvers/core/status.h"
#include "solvers/core/verdict.h"
// Typed options of a backend of your own, settable from text (BackendWithOptions).
#include "solvers/core/backend_options.h"
// Backends by name (CreateSolver, SolverNames) and the run-time extension point (RegisterSolver).
#include "solvers/registry/registry.h"

// Affine variational inequalities over polytopes (AffineVI), solved by any box backend (SolveAvi, docs/avi.md).
#include "solvers/avi/avi_solver.h"
// The conformance checks every backend passes (CheckConformance).
#include "solvers/conformance/conformance.h"
// The certified reference solutions of the benchmark.
#include "solvers/reference/certify.h"
#include "solvers/reference/enclosure.h"
// Problem sources: Siconos files, seeded generators with known solutions, the problem library (.smcps).
#include "solvers/generators/random_problems.h"
#include "problems/io/siconos_format.h"
#include "problems/library/problem_set.h"
#include "problems/library/problem_set_io.h"
// The paper's scenes and the time-steppers.
#include "problems/scenes/registry.h"
#include "problems/scenes/scene.h"
#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/nonlinear_stepper.h"
// A benchmark run: MakeBenchPlan (suites, backends, settings → the jobs) and RunShard.
#include "bench/run/bench_plan.h"
#include "bench/run/run_shard.h"
// Version and git revision of this build.
#include "smcbench/version.h"
